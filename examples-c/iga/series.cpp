// series.cpp: uniform and adaptive refinement series.

#include "series.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "system.h"

namespace iga {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Step step_of(const Solution &s, double seconds) {
  Step st;
  st.elements = double(s.space.elements.size());
  st.dofs = double(s.space.nb);
  st.h = s.space.h;
  st.l2 = ElementNorms::total(s.norms.l2);
  st.h1 = ElementNorms::total(s.norms.h1);
  st.eta = s.norms.eta.empty() ? NAN : ElementNorms::total(s.norms.eta);
  st.seconds = seconds;
  return st;
}

void print_header(bool adaptive) {
  std::printf("%5s %9s %9s %10s %12s %7s %12s %7s %12s %8s %8s\n", adaptive ? "step" : "level", "elements", "dofs",
              "h", "L2", "rate", "H1", "rate", "eta", adaptive ? "marked" : "", "seconds");
}

// One row of the table; rates against the previous step, in h (uniform) or in dofs (adaptive).
void print_row(int index, const Series &series, bool adaptive) {
  const Step &s = series.steps.back();
  char r2[16] = "", r1[16] = "", marked[16] = "", eta[16] = "";
  if (series.steps.size() >= 2) {
    const Step &p = series.steps[series.steps.size() - 2];
    const double lx = adaptive ? std::log(s.dofs / p.dofs) : std::log(p.h / s.h);
    std::snprintf(r2, sizeof r2, "%.2f", std::log(p.l2 / s.l2) / lx);
    std::snprintf(r1, sizeof r1, "%.2f", std::log(p.h1 / s.h1) / lx);
  }
  if (adaptive) std::snprintf(marked, sizeof marked, "%.0f", s.marked);
  if (!std::isnan(s.eta)) std::snprintf(eta, sizeof eta, "%.4e", s.eta);
  std::printf("%5d %9.0f %9.0f %10.4g %12.4e %7s %12.4e %7s %12s %8s %8.2f\n", index, s.elements, s.dofs, s.h, s.l2, r2,
              s.h1, r1, eta, marked, s.seconds);
  std::fflush(stdout);
}

}  // namespace

std::vector<double> Series::column(double Step::*field) const {
  std::vector<double> v;
  for (const Step &s : steps) v.push_back(s.*field);
  return v;
}

Solution solve_problem(const igaparam_spline *spline, const Problem &p, const Rules &rules, int threads,
                       bool estimator) {
  Solution s;
  auto start = std::chrono::steady_clock::now();
  auto lap = [&](int stage) {
    s.seconds[stage] = seconds_since(start);
    start = std::chrono::steady_clock::now();
  };
  s.space = Space(spline);
  lap(0);
  Integrands terms;
  terms.source = p.f;
  terms.reaction = p.kappa2;
  terms.projected = p.u;
  const System sys = assemble(s.space, terms, rules.assembly, threads);
  lap(1);
  const VectorXd projection = solve(sys.mass, sys.projection_rhs, true);
  s.c = solve_dirichlet(s.space, sys, kAllFaces, projection, !p.kappa2);
  lap(2);
  s.norms = element_norms(s.space, p, s.c, rules.error, threads, estimator);
  lap(3);
  std::fprintf(stderr, "%zu elements: extraction %.2f s, assembly %.2f s, solve %.2f s, errors %.2f s\n",
               s.space.elements.size(), s.seconds[0], s.seconds[1], s.seconds[2], s.seconds[3]);
  return s;
}

Series uniform_series(igaparam_spline *spline, const Problem &p, const Rules &rules, const SeriesOptions &options,
                      Solution *last) {
  Series series;
  if (!options.quiet) print_header(false);
  for (int level = 0; level <= options.levels; level++) {
    const auto start = std::chrono::steady_clock::now();
    if (level > 0) check(igaparam_spline_refine(spline, 0, nullptr, nullptr), "uniform refinement");
    Solution s = solve_problem(spline, p, rules, options.threads, options.estimator);
    series.steps.push_back(step_of(s, seconds_since(start)));
    if (!options.quiet) print_row(level, series, false);
    if (last && level == options.levels) *last = std::move(s);
  }
  return series;
}

Series adaptive_series(igaparam_spline *spline, const Problem &p, const Rules &rules, const SeriesOptions &options,
                       Solution *last) {
  Series series;
  if (!options.quiet) print_header(true);
  for (int step = 0; step < options.max_steps; step++) {
    const auto start = std::chrono::steady_clock::now();
    Solution s = solve_problem(spline, p, rules, options.threads, true);
    series.steps.push_back(step_of(s, 0.0));
    const std::vector<size_t> marked = mark(s.space, s.norms.eta, options.gamma);
    if (marked.empty()) std::fprintf(stderr, "every element is at the deepest level: the refinement stops\n");
    const bool done =
        series.steps.back().dofs >= options.max_dofs || step + 1 == options.max_steps || marked.empty();
    const std::vector<size_t> refined = extend(s.space, marked, options.layers);
    if (!done) check(igaparam_spline_refine(spline, refined.size(), refined.data(), nullptr), "marked refinement");
    series.steps.back().marked = done ? 0.0 : double(marked.size());
    series.steps.back().seconds = seconds_since(start);
    if (!options.quiet) print_row(step, series, true);
    if (done) {
      if (last) *last = std::move(s);
      break;
    }
  }
  return series;
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string json_list(const std::vector<double> &v) {
  std::ostringstream s;
  s << "[";
  for (size_t i = 0; i < v.size(); i++) s << (i ? ", " : "") << json_number(v[i]);
  s << "]";
  return s.str();
}

}  // namespace iga
