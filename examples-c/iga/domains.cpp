// domains.cpp: built-in and input spline maps.

#include "domains.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace iga {

namespace {

// The thick quarter annulus r ∈ [1, 2], θ ∈ [0, π/2], z ∈ [0, 1] as one cubic element: the
// quarter circle by its usual cubic Bézier approximation, linear in r and z.
std::string thick_quarter_annulus_xml() {
  const double k = 4.0 / 3.0 * (std::sqrt(2.0) - 1.0);
  const double arc[4][2] = {{1, 0}, {1, k}, {k, 1}, {0, 1}};
  std::ostringstream s;
  s.precision(17);
  s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xml>\n <Geometry type=\"THBSpline3\" id=\"0\">\n"
       "  <Basis type=\"THBSplineBasis3\">\n   <Basis type=\"TensorBSplineBasis3\">\n";
  for (int d = 0; d < 3; d++)
    s << "    <Basis type=\"BSplineBasis\" index=\"" << d
      << "\">\n     <KnotVector degree=\"3\">0 0 0 0 1 1 1 1</KnotVector>\n    </Basis>\n";
  s << "   </Basis>\n  </Basis>\n  <coefs geoDim=\"3\">\n";
  for (int i2 = 0; i2 < 4; i2++)
    for (int i1 = 0; i1 < 4; i1++)
      for (int i0 = 0; i0 < 4; i0++) {
        const double r = 1.0 + i0 / 3.0;
        s << "   " << r * arc[i1][0] << " " << r * arc[i1][1] << " " << i2 / 3.0 << "\n";
      }
  s << "  </coefs>\n </Geometry>\n</xml>\n";
  return s.str();
}

std::string temporary_path(const std::string &name) {
  const char *dir = std::getenv("TMPDIR");
  const std::string base = dir && *dir ? dir : "/tmp";
  return base + "/" + name + "_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) +
         ".xml";
}

SplinePtr read_spline_text(const std::string &text) {
  const std::string path = temporary_path("igaparam_poisson_map");
  {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write " + path);
    out << text;
  }
  igaparam_spline *s = nullptr;
  const igaparam_status status = igaparam_spline_read_gismo(path.c_str(), &s);
  std::remove(path.c_str());
  check(status, "reading the built-in map");
  return SplinePtr(s);
}

// The quarter annulus r ∈ [1, 2], θ ∈ [0, π/2] from four polylines (arcs of 257 points).
SplinePtr quarter_annulus(const FitOptions &options) {
  const int n = 257;
  std::vector<double> inner, outer, bottom = {1, 0, 2, 0}, left = {0, 2, 0, 1};
  for (int i = 0; i < n; i++) {
    const double t = 0.5 * kPi * i / (n - 1);
    outer.push_back(2 * std::cos(t));
    outer.push_back(2 * std::sin(t));
    const double ti = 0.5 * kPi * (n - 1 - i) / (n - 1);
    inner.push_back(std::cos(ti));
    inner.push_back(std::sin(ti));
  }
  size_t counts[4] = {2, size_t(n), 2, size_t(n)};
  const double *points[4] = {bottom.data(), outer.data(), left.data(), inner.data()};
  igaparam_domain *domain = nullptr;
  check(igaparam_domain_new_from_polylines(counts, points, &domain), "quarter annulus");
  FitOptions defaults;
  defaults.threads = options.threads;
  return fit(DomainPtr(domain), defaults);
}

bool is_thb_xml(const std::string &path) {
  std::ifstream in(path);
  std::string head(4096, '\0');
  in.read(&head[0], head.size());
  head.resize(static_cast<size_t>(in.gcount()));
  return head.find("THBSpline") != std::string::npos;
}

}  // namespace

SplinePtr fit(DomainPtr domain, const FitOptions &fit_options) {
  size_t dim = 0;
  check(igaparam_domain_dimension(domain.get(), &dim), "dimension");
  igaparam_domain_options options =
      dim == 3 ? igaparam_domain_options_default_solid() : igaparam_domain_options_default();
  options.threads = static_cast<uint32_t>(fit_options.threads);
  if (fit_options.tolerance > 0.0) options.tolerance = fit_options.tolerance;
  if (fit_options.max_level >= 0) options.max_level = static_cast<uint8_t>(fit_options.max_level);
  for (int attempt = 0;; attempt++) {
    igaparam_domain_report report;
    check(igaparam_domain_build(domain.get(), &options, &report), "domain build");
    std::printf("T-mesh: %zu cells, max level %u, %zu invalid, quality min %.3f mean %.3f (tolerance %g, %.2f s)\n",
                report.cells, report.max_level, report.invalid_cells, report.min_quality, report.mean_quality,
                options.tolerance, report.seconds);
    if (report.invalid_cells != 0) throw std::runtime_error("the domain has invalid cells");
    igaparam_spline *raw = nullptr;
    check(igaparam_spline_fit_domain(domain.get(), &raw, nullptr), "spline fit");
    SplinePtr s(raw);
    igaparam_validity_report validity;
    check(igaparam_spline_check_validity(s.get(), nullptr, &validity, nullptr, nullptr, 0), "validity");
    if (validity.certified_positive || attempt >= fit_options.refits) {
      if (!validity.certified_positive)
        std::fprintf(stderr, "the map is not certified valid on %zu elements (min sampled q %.3g)\n",
                     validity.uncertified, validity.min_quality);
      return s;
    }
    options.tolerance /= 10.0;
    std::fprintf(stderr, "the fitted map is not certified valid; rebuilding with tolerance %g\n", options.tolerance);
  }
}

SplinePtr load(const std::string &input, int dim, const FitOptions &options) {
  if (input.empty()) return dim == 3 ? read_spline_text(thick_quarter_annulus_xml()) : quarter_annulus(options);
  if (is_thb_xml(input)) {
    igaparam_spline *s = nullptr;
    check(igaparam_spline_read_gismo(input.c_str(), &s), input.c_str());
    return SplinePtr(s);
  }
  // A B-rep or coastline with four curves; else a solid (six surfaces, or a folder of six faces).
  igaparam_domain *domain = nullptr;
  if (igaparam_domain_new_from_file(input.c_str(), &domain) != IGAPARAM_STATUS_OK) {
    const std::string planar = last_error();
    if (igaparam_domain_new_solid_from_file(input.c_str(), &domain) != IGAPARAM_STATUS_OK)
      throw std::runtime_error(input + ": " + planar + " (as a solid: " + last_error() + ")");
  }
  return fit(DomainPtr(domain), options);
}

std::array<double, 3> centre_point(const igaparam_spline *spline) {
  size_t d = 0;
  check(igaparam_spline_dimension(spline, &d), "dimension");
  const double half[3] = {0.5, 0.5, 0.5};
  std::array<double, 3> x{};
  check(igaparam_spline_evaluate(spline, 1, half, x.data(), nullptr), "evaluate");
  return x;
}

}  // namespace iga
