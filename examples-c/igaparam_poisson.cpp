// igaparam_poisson: isogeometric Galerkin solver of the Poisson and Helmholtz equations on the
// cubic THB-spline maps of the library, with a uniform or an adaptive refinement series and
// its convergence rates.
//
//   igaparam_poisson [INPUT] [--problem poisson|helmholtz|wavefront|linear] [--levels N]
//                    [--threads N] [--dim 2|3] [--quad N] [--tolerance T] [--max-level L]
//                    [--refits N] [--centre X,Y[,Z]] [--alpha A] [--r0 R] [--vtu PATH]
//                    [--spline-vtu PATH] [--json PATH] [--estimator]
//                    [--adaptive] [--gamma G] [--layers K] [--max-dofs N] [--max-steps N] [--fit-span F]
//                    [--check-rates L2MIN H1MIN] [--check-estimator-rate MIN]
//                    [--check-adaptive H1MIN RATIOMAX] [--check-max-error E] [--check-source]
//                    [--check-certified]
//
// INPUT is a G+Smo XML B-rep (four curves or six surfaces), a coastline .txt or a folder of six
// triangulated faces (the domain is built and its spline map fitted; --tolerance sets the
// domain's boundary tolerance and --max-level its deepest level; while the map is not certified
// valid, the domain is rebuilt with a tolerance ten times smaller, at most --refits times,
// default 3), or a THB spline .xml written by igaparam_spline_write_gismo (read, 2D or 3D).
// Without INPUT: a quarter annulus (radii 1 and 2) built from four polylines (--dim 2, the
// default) or a thick quarter annulus given as one cubic element (--dim 3).
//
// On an input domain every problem is placed and scaled by the domain's bounding box (see
// iga/problems.h); --centre, --alpha and --r0 override the centre (in the box's unit
// coordinates), the steepness and the radius of the radial problems.
//
// The analysis space is the map's own spline space (the map does not change). Uniform series:
// refined uniformly --levels times; on each level the stiffness (and mass) matrices and the load
// by Gauss quadrature per element through the Bézier extraction, Dirichlet values from the L2
// projection of the exact solution, the interior system solved, L2 / H1-seminorm errors (and,
// with --estimator, the residual indicator) by a finer quadrature. Adaptive series
// (--adaptive): solve, mark the elements with η_e > γ max η (--gamma, default 0.5), refine
// them with --layers layers of elements around them (default 1: a THB space gains functions only
// where whole supports are refined), until a step has --max-dofs dofs (default 20000) or after
// --max-steps solves (60); then the uniform series of the same map (--levels) for comparison.
// Prints a table and, as its last line (also written to --json), one JSON object with the
// series and the rates: in h between the last two levels (uniform), fitted in dofs over the last
// steps, those with at least 1/--fit-span (default 4) of the last step's dofs (adaptive).
// --vtu writes u_h and its error sampled on the last space, --spline-vtu that space's elements
// (igaparam_spline_write_vtu, cell data `level`).
//
// Checks (exit status 3 when one fails): --check-rates (uniform L2 and H1 rates),
// --check-estimator-rate (uniform rate of the indicator), --check-adaptive (adaptive H1 rate in
// dofs at least H1MIN, and the adaptive series reaching the uniform series' last H1 error with at
// most RATIOMAX times its dofs), --check-max-error (every L2 and H1 error at most E; --problem
// linear is reproduced exactly by the isoparametric space), --check-certified (det J > 0 proven
// on every element of the map). --check-source compares the right-hand sides with finite
// differences of the exact solutions and exits.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "cli_numbers.h"
#include "iga/domains.h"
#include "iga/sample.h"
#include "iga/series.h"

namespace {

using namespace iga;
using cli::integer;
using cli::number;

struct Options {
  std::string input, problem = "poisson", vtu, spline_vtu, json;
  int levels = 3, threads = 0, dim = 2, quad = 0;
  FitOptions fit;
  Placement placement;
  bool adaptive = false, estimator = false, check_source = false, check_certified = false;
  SeriesOptions series;
  double fit_span = 4.0;
  std::optional<std::array<double, 2>> check_rates, check_adaptive;
  std::optional<double> check_estimator_rate, max_error;
};

void usage() {
  std::fprintf(stderr,
               "usage: igaparam_poisson [INPUT] [--problem poisson|helmholtz|wavefront|linear] [--levels N]\n"
               "                        [--threads N] [--dim 2|3] [--quad N] [--tolerance T] [--max-level L]\n"
               "                        [--refits N] [--centre X,Y[,Z]] [--alpha A] [--r0 R] [--vtu PATH]\n"
               "                        [--spline-vtu PATH] [--json PATH] [--estimator]\n"
               "                        [--adaptive] [--gamma G] [--layers K] [--max-dofs N] [--max-steps N] [--fit-span F]\n"
               "                        [--check-rates L2MIN H1MIN] [--check-estimator-rate MIN]\n"
               "                        [--check-adaptive H1MIN RATIOMAX] [--check-max-error E]\n"
               "                        [--check-source] [--check-certified]\n");
}

// X,Y[,Z]: a point of 2 or 3 coordinates.
std::array<double, 3> point(const std::string &option, const std::string &text) {
  const std::vector<double> v = cli::numbers(option, text, 2, 3);
  return {v[0], v[1], v.size() > 2 ? v[2] : 0.0};
}

// Options that take no value, or true when `a` is one of them.
bool flag(Options &o, const std::string &a) {
  bool *target = a == "--adaptive"           ? &o.adaptive
                 : a == "--estimator"        ? &o.estimator
                 : a == "--check-source"     ? &o.check_source
                 : a == "--check-certified"  ? &o.check_certified
                                             : nullptr;
  if (target) *target = true;
  return target != nullptr;
}

void option(Options &o, const std::string &a, const std::function<std::string()> &next) {
  if (a == "--problem") o.problem = next();
  else if (a == "--levels") o.levels = integer(a, next(), 0, 12);
  else if (a == "--threads") o.threads = integer(a, next(), 0, 1024);
  else if (a == "--dim") o.dim = integer(a, next(), 2, 3);
  else if (a == "--quad") o.quad = integer(a, next(), 0, 12);
  else if (a == "--refits") o.fit.refits = integer(a, next(), 0, 10);
  else if (a == "--tolerance") o.fit.tolerance = number(a, next());
  else if (a == "--max-level") o.fit.max_level = integer(a, next(), 0, 16);
  else if (a == "--centre") o.placement.centre = point(a, next());
  else if (a == "--alpha") o.placement.alpha = number(a, next());
  else if (a == "--r0") o.placement.r0 = number(a, next());
  else if (a == "--vtu") o.vtu = next();
  else if (a == "--spline-vtu") o.spline_vtu = next();
  else if (a == "--json") o.json = next();
  else if (a == "--gamma") o.series.gamma = number(a, next());
  else if (a == "--layers") o.series.layers = integer(a, next(), 0, 4);
  else if (a == "--max-dofs") o.series.max_dofs = number(a, next());
  else if (a == "--max-steps") o.series.max_steps = integer(a, next(), 1, 1000);
  else if (a == "--fit-span") o.fit_span = number(a, next());
  else if (a == "--check-rates") {
    const double l2 = number(a, next());
    o.check_rates = std::array<double, 2>{l2, number(a, next())};
  } else if (a == "--check-adaptive") {
    const double rate = number(a, next());
    o.check_adaptive = std::array<double, 2>{rate, number(a, next())};
  } else if (a == "--check-estimator-rate") o.check_estimator_rate = number(a, next());
  else if (a == "--check-max-error") o.max_error = number(a, next());
  else throw cli::UsageError("unknown option " + a);
}

Options parse(int argc, char **argv) {
  Options o;
  for (int i = 1; i < argc; i++) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw cli::UsageError(a + " needs a value");
      return argv[++i];
    };
    if (flag(o, a)) continue;
    if (!a.empty() && a[0] == '-') option(o, a, next);
    else if (o.input.empty()) o.input = a;
    else throw cli::UsageError("more than one input");
  }
  if (!(o.series.gamma > 0.0 && o.series.gamma < 1.0)) throw cli::UsageError("--gamma must lie in (0, 1)");
  if (!(o.fit_span > 1.0)) throw cli::UsageError("--fit-span must exceed 1");
  if (o.threads == 0) o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.fit.threads = o.series.threads = o.threads;
  o.series.levels = o.levels;
  o.series.estimator = o.estimator || o.check_estimator_rate.has_value();
  return o;
}

// Compares the right-hand sides with finite differences, on the built-in domains' region and
// on a box in km (the placed problems).
int check_sources(int dim) {
  // Points of the box [0.1, 2]^d at distance at least 1 from the origin: the region of the
  // built-in domains, away from the centres of the radial solutions.
  std::vector<double> pts;
  for (int i = 0; pts.size() < size_t(200 * dim); i++) {
    double x[3], r2 = 0.0;
    for (int k = 0; k < dim; k++) {
      x[k] = 0.1 + 1.9 * std::fmod(0.6180339887 * (i + 1) * (k + 1.7), 1.0);
      r2 += x[k] * x[k];
    }
    if (r2 >= 1.0) pts.insert(pts.end(), x, x + dim);
  }
  Placement builtin, km;
  builtin.d = km.d = dim;
  // The same points in a box of 20 × 16 (× 12) km: the problems placed by it, centres off the points.
  km.box = dim == 2 ? std::vector<double>{0, 0, 20, 16} : std::vector<double>{0, 0, 0, 20, 16, 12};
  km.inside = {0.3, 0.2, 0.1};
  std::vector<double> km_pts(pts);
  for (double &v : km_pts) v *= 10.0;
  bool ok = true;
  for (const char *name : {"poisson", "helmholtz", "wavefront"}) {
    for (const Placement *pl : {&builtin, &km}) {
      const double r = source_residual(make_problem(name, *pl), dim, pl == &km ? km_pts : pts);
      std::printf("%s %dD%s: largest relative difference between f and the finite differences: %.3g\n", name, dim,
                  pl == &km ? " (placed in a box in km)" : "", r);
      ok = ok && r < 1e-5;
    }
  }
  return ok ? 0 : 3;
}

bool certified(const igaparam_spline *spline) {
  igaparam_validity_report validity;
  check(igaparam_spline_check_validity(spline, nullptr, &validity, nullptr, nullptr, 0), "validity");
  if (!validity.certified_positive) {
    std::fprintf(stderr, "igaparam_poisson: the map is not certified valid (%zu elements)\n", validity.uncertified);
    return false;
  }
  std::printf("map certified valid: det J > 0 proven on all elements, min sampled q_S %.4f\n", validity.min_quality);
  return true;
}

void write_outputs(const Options &o, const Solution &s, const Problem &p, const igaparam_spline *spline) {
  if (!o.vtu.empty()) {
    std::vector<FieldSpec> fields = {
        {"u_h", 1, [&](const Element &el, const ElementValues &ev, int q, double *out) {
           out[0] = ev.values.col(q).dot(local_coefficients(el, s.c));
         }},
        {"error", 1, [&](const Element &el, const ElementValues &ev, int q, double *out) {
           out[0] = ev.values.col(q).dot(local_coefficients(el, s.c)) - p.u(ev.points.col(q).data());
         }}};
    write_vtu(sample(s.space, 4, fields), o.vtu);
  }
  if (!o.spline_vtu.empty())
    check(igaparam_spline_write_vtu(spline, o.spline_vtu.c_str(), 1), o.spline_vtu.c_str());
}

// The series' figures as JSON members ("dofs": [...], ...), keys prefixed by `prefix`.
std::string series_json(const Series &s, const std::string &prefix) {
  std::string out;
  const std::pair<const char *, double Step::*> columns[] = {
      {"elements", &Step::elements}, {"dofs", &Step::dofs}, {"h", &Step::h},
      {"l2", &Step::l2},             {"h1", &Step::h1},     {"eta", &Step::eta}};
  for (const auto &[name, field] : columns) out += ", \"" + prefix + name + "\": " + json_list(s.column(field));
  return out;
}

// Prints the JSON summary as the last line, and writes it to --json.
void emit_json(const Options &o, const std::string &json) {
  std::printf("%s\n", json.c_str());
  if (o.json.empty()) return;
  std::ofstream out(o.json);
  out << json << "\n";
  if (!out) throw std::runtime_error("cannot write " + o.json);
}

// The common head of the JSON summary: `{"problem": ..., "dim": ..., "threads": ..., "mode": ...`.
std::string json_head(const Options &o, const Problem &p, const char *mode) {
  return "{\"problem\": \"" + p.name + "\", \"dim\": " + std::to_string(o.placement.d) +
         ", \"threads\": " + std::to_string(o.threads) + ", \"mode\": \"" + mode + "\"";
}

int report_uniform(const Options &o, const Problem &p, const Series &s) {
  const auto h = s.column(&Step::h), l2 = s.column(&Step::l2), h1 = s.column(&Step::h1), eta = s.column(&Step::eta);
  const double rate_l2 = last_rate(h, l2), rate_h1 = last_rate(h, h1), rate_eta = last_rate(h, eta);
  emit_json(o, json_head(o, p, "uniform") + series_json(s, "") + ", \"rate_l2\": " + json_number(rate_l2) +
                  ", \"rate_h1\": " + json_number(rate_h1) + ", \"rate_eta\": " + json_number(rate_eta) + "}");
  int status = 0;
  if (o.check_rates && (s.steps.size() < 2 || !(rate_l2 >= (*o.check_rates)[0]) || !(rate_h1 >= (*o.check_rates)[1]))) {
    std::fprintf(stderr, "igaparam_poisson: rates %.3f (L2) and %.3f (H1) below %.3f and %.3f\n", rate_l2, rate_h1,
                 (*o.check_rates)[0], (*o.check_rates)[1]);
    status = 3;
  }
  if (o.check_estimator_rate && !(rate_eta >= *o.check_estimator_rate)) {
    std::fprintf(stderr, "igaparam_poisson: indicator rate %.3f below %.3f\n", rate_eta, *o.check_estimator_rate);
    status = 3;
  }
  if (o.max_error && !(*std::max_element(l2.begin(), l2.end()) <= *o.max_error &&
                       *std::max_element(h1.begin(), h1.end()) <= *o.max_error)) {
    std::fprintf(stderr, "igaparam_poisson: errors above %g\n", *o.max_error);
    status = 3;
  }
  return status;
}

int report_adaptive(const Options &o, const Problem &p, const Series &a, const Series &u) {
  const auto dofs = a.column(&Step::dofs), h1 = a.column(&Step::h1), udofs = u.column(&Step::dofs),
             uh1 = u.column(&Step::h1);
  const double rate_l2 = fitted_rate(dofs, a.column(&Step::l2), o.fit_span), rate_h1 = fitted_rate(dofs, h1, o.fit_span),
               rate_eta = fitted_rate(dofs, a.column(&Step::eta), o.fit_span);
  const double uniform_rate_h1 = -last_rate(udofs, uh1);  // log(e_p/e_l) / log(N_l/N_p)
  // The dofs the adaptive series needs for the uniform series' last H1 error, relative to the
  // uniform series' dofs.
  const double ratio = dofs_to_reach(dofs, h1, uh1.back()) / udofs.back();
  const double efficiency = a.steps.back().eta / a.steps.back().h1;
  std::printf("adaptive: H1 rate %.3f in dofs over the last steps (optimal %.3f); the uniform series' last H1 error "
              "%.3e (%.0f dofs) reached with %.3g times its dofs; eta / H1 error %.3f\n",
              rate_h1, 3.0 / o.placement.d, uh1.back(), udofs.back(), ratio, efficiency);
  emit_json(o, json_head(o, p, "adaptive") + ", \"gamma\": " + json_number(o.series.gamma) + series_json(a, "") +
                  series_json(u, "uniform_") + ", \"rate_l2\": " + json_number(rate_l2) +
                  ", \"rate_h1\": " + json_number(rate_h1) + ", \"rate_eta\": " + json_number(rate_eta) +
                  ", \"uniform_rate_h1\": " + json_number(uniform_rate_h1) + ", \"dofs_ratio\": " +
                  json_number(ratio) + ", \"efficiency\": " + json_number(efficiency) + "}");
  if (o.check_adaptive && !(rate_h1 >= (*o.check_adaptive)[0] && ratio <= (*o.check_adaptive)[1])) {
    std::fprintf(stderr, "igaparam_poisson: adaptive H1 rate %.3f (at least %.3f wanted), dofs ratio %.3g (at most %.3g)\n",
                 rate_h1, (*o.check_adaptive)[0], ratio, (*o.check_adaptive)[1]);
    return 3;
  }
  return 0;
}

int run(int argc, char **argv) {
  Options o = parse(argc, argv);
  if (o.check_source) return check_sources(o.dim);
  SplinePtr spline = load(o.input, o.dim, o.fit);
  size_t d = 0;
  check(igaparam_spline_dimension(spline.get(), &d), "dimension");
  if (o.check_certified && !certified(spline.get())) return 3;
  o.placement.d = static_cast<int>(d);
  if (!o.input.empty()) {
    o.placement.box = control_box(spline.get());
    o.placement.inside = centre_point(spline.get());
  }
  const Problem problem = make_problem(o.problem, o.placement);
  const int dim = static_cast<int>(d);
  const Rules rules{Reference::gauss(dim, o.quad > 0 ? o.quad : (dim == 2 ? 5 : 4)),
                    Reference::gauss(dim, dim == 2 ? 6 : 5, o.adaptive || o.series.estimator)};
  Solution last;
  if (!o.adaptive) {
    const Series s = uniform_series(spline.get(), problem, rules, o.series, &last);
    write_outputs(o, last, problem, spline.get());
    return report_uniform(o, problem, s);
  }
  SplinePtr uniform_spline = clone(spline.get());
  std::printf("adaptive refinement, gamma %g:\n", o.series.gamma);
  const Series a = adaptive_series(spline.get(), problem, rules, o.series, &last);
  write_outputs(o, last, problem, spline.get());
  std::printf("uniform refinement:\n");
  const Series u = uniform_series(uniform_spline.get(), problem, rules, o.series);
  return report_adaptive(o, problem, a, u);
}

}  // namespace

int main(int argc, char **argv) {
  try {
    return run(argc, argv);
  } catch (const std::invalid_argument &e) {
    std::fprintf(stderr, "igaparam_poisson: %s\n", e.what());
    usage();
    return 2;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "igaparam_poisson: %s\n", e.what());
    return 1;
  }
}
