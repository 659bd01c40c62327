// igaparam_wind: wind-field adjustment over a terrain by the mass-consistent model, solved by
// isogeometric analysis on the spline map of a block of air above the terrain.
//
//   igaparam_wind INPUT|--hill HEIGHT,RADIUS,SIDE [--scale SX,SY,SZ] [--lid Z] [--flat-terrain]
//                 [--tol T] [--max-level L]
//                 [--threads N] [--wind U,V,W] [--profile constant|log] [--roughness Z0]
//                 [--reference-height H] [--levels N] [--vtu PATH] [--png PATH] [--stretch S]
//                 [--size W H] [--check-rates DIVMIN NORMALMIN] [--check-exact TOL]
//                 [--check-normal-reduction F] [--check-certified]
//
// INPUT is a folder of six triangulated faces (xmin, xmax, ymin, ymax: vertical walls; zmin: the
// terrain; zmax: a flat lid; .obj/.off/.stl/.ply, read by OpenMesh) or a G+Smo XML B-rep of six
// surfaces. --scale multiplies the coordinates per axis (e.g. 89273.3,111200,1 for the bundled
// Jacksboro block, degrees/1000 to km). For faces, --lid Z moves the lid to height Z and
// stretches the walls above the terrain (see terrain_block.h), --flat-terrain replaces the terrain
// by the plane at its lowest height. Instead of INPUT, --hill makes a synthetic block: a Gaussian
// hill of the given height and e-folding radius at the centre of a square plain of the given
// side (a rim flat to round-off for radius ≤ side/8), lid at --lid (default 10). The block's domain is built (solid defaults, --tol,
// --max-level) and its spline map fitted; the face of the map lowest in z is the terrain.
//
// The initial wind u0 (--wind, default 10,0,0) is constant or a logarithmic profile in the
// height above the terrain's lowest point (--profile log: u0 = wind · ln((h + z0)/z0) /
// ln((H + z0)/z0), z0 = --roughness, default 0.1, H = --reference-height, default 1, in the map's
// length unit). λ solves −Δλ = ∇·u0, −n·∇λ = n·u0 on the terrain, λ = 0 on the lid and the
// walls, on the map's space refined uniformly --levels times (default 2); the adjusted wind is
// u = u0 + ∇λ. On each level the program prints ‖∇·u‖_L2(Ω), ‖n·u‖_L2(terrain) and
// max |u − u0| / max |u0|, and as its last line one JSON object with the series and the rates
// (`rate_divergence`, `rate_normal`: in h between the last two levels). --vtu writes λ, u and u0
// sampled on the last level, --png the streamlines from seeds near the ground and higher up on
// the upwind wall (VTK, offscreen: run under xvfb-run without a display; --stretch: vertical
// exaggeration, default 1; --size: pixels, default 1200 800). Checks (exit status 3 when one
// fails): --check-rates (both rates at least their bounds), --check-exact (max |u − u0| / max |u0|
// at most TOL on every level), --check-normal-reduction (‖n·u‖ on the last level at most F times
// ‖n·u0‖), --check-certified (the spline map certified valid). Exit
// codes: 0 success, 1 error, 2 usage, 77 no display for --png.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include "cli_numbers.h"
#include "face_files.h"
#include "iga/domains.h"
#include "iga/estimate.h"
#include "iga/series.h"
#include "iga/wind.h"
#include "render_streamlines.h"
#include "terrain_block.h"

namespace {

using namespace iga;
using cli::integer;
using cli::number;
using cli::positive;
using cli::UsageError;
namespace fs = std::filesystem;

struct Options {
  std::string input, vtu, png;
  std::optional<std::array<double, 3>> scale, hill;
  std::optional<double> lid, tolerance, check_exact, check_reduction;
  std::optional<std::array<double, 2>> check_rates;
  bool flat = false, check_certified = false;
  int max_level = -1, threads = 0, levels = 2, width = 1200, height = 800;
  double stretch = 1.0;
  InitialWind wind;
};

void usage() {
  std::fprintf(stderr,
               "usage: igaparam_wind INPUT|--hill HEIGHT,RADIUS,SIDE [--scale SX,SY,SZ] [--lid Z] [--flat-terrain]\n"
               "                     [--tol T] [--max-level L]\n"
               "                     [--threads N] [--wind U,V,W] [--profile constant|log] [--roughness Z0]\n"
               "                     [--reference-height H] [--levels N] [--vtu PATH] [--png PATH] [--stretch S]\n"
               "                     [--size W H] [--check-rates DIVMIN NORMALMIN] [--check-exact TOL]\n"
               "                     [--check-normal-reduction F] [--check-certified]\n");
}

std::array<double, 3> triple(const std::string &option, const std::string &text) {
  const std::vector<double> v = cli::numbers(option, text, 3, 3);
  return {v[0], v[1], v[2]};
}

void option(Options &o, const std::string &a, const std::function<std::string()> &next) {
  if (a == "--scale") {
    try {
      o.scale = face_files::parse_scale(next());
    } catch (const std::logic_error &) {
      throw UsageError("--scale expects three positive numbers SX,SY,SZ");
    }
  } else if (a == "--lid") o.lid = number(a, next());
  else if (a == "--hill") o.hill = triple(a, next());
  else if (a == "--tol") o.tolerance = positive(a, next());
  else if (a == "--max-level") o.max_level = integer(a, next(), 0, 16);
  else if (a == "--threads") o.threads = integer(a, next(), 0, 1024);
  else if (a == "--wind") o.wind.velocity = triple(a, next());
  else if (a == "--profile") {
    const std::string p = next();
    if (p != "constant" && p != "log") throw UsageError("--profile is constant or log");
    o.wind.logarithmic = p == "log";
  } else if (a == "--roughness") o.wind.roughness = positive(a, next());
  else if (a == "--reference-height") o.wind.reference_height = positive(a, next());
  else if (a == "--levels") o.levels = integer(a, next(), 0, 6);
  else if (a == "--vtu") o.vtu = next();
  else if (a == "--png") o.png = next();
  else if (a == "--stretch") o.stretch = positive(a, next());
  else if (a == "--check-exact") o.check_exact = positive(a, next());
  else if (a == "--check-normal-reduction") o.check_reduction = positive(a, next());
  else if (a == "--size") {
    o.width = integer(a, next(), 64, 8192);
    o.height = integer(a, next(), 64, 8192);
  }
  else if (a == "--check-rates") {
    const double div = number(a, next());
    o.check_rates = std::array<double, 2>{div, number(a, next())};
  } else throw UsageError("unknown option " + a);
}

Options parse(int argc, char **argv) {
  Options o;
  for (int i = 1; i < argc; i++) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(a + " needs a value");
      return argv[++i];
    };
    if (a == "--flat-terrain") o.flat = true;
    else if (a == "--check-certified") o.check_certified = true;
    else if (!a.empty() && a[0] == '-') option(o, a, next);
    else if (o.input.empty()) o.input = a;
    else throw UsageError("more than one input");
  }
  if (o.input.empty() == !o.hill) throw UsageError("give either INPUT or --hill");
  if (o.hill && (o.scale || o.flat)) throw UsageError("--scale and --flat-terrain apply to INPUT only");
  if (o.threads == 0) o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return o;
}

// The block's domain: faces (reshaped as asked) or a B-rep.
DomainPtr open_block(const Options &o) {
  igaparam_domain *domain = nullptr;
  const fs::path path(o.input);
  if (o.hill) {
    const auto [height, radius, side] = *o.hill;
    const double lid = o.lid.value_or(10.0);
    std::printf("Gaussian hill: height %g, radius %g, on the square of side %g; lid at %g\n", height, radius, side,
                lid);
    check(face_files::new_solid(terrain_block::gaussian_hill(side, height, radius, lid, 32), &domain), "hill");
  } else if (fs::is_directory(path)) {
    std::vector<face_files::Face> faces = face_files::read_faces(path, o.scale ? &*o.scale : nullptr);
    const double old_lid = terrain_block::lid_height(faces);
    if (o.lid || o.flat) terrain_block::reshape(faces, o.lid.value_or(old_lid), o.flat);
    std::printf("%s: lid at %.6g%s%s\n", o.input.c_str(), o.lid.value_or(old_lid),
                o.lid ? " (moved, walls stretched)" : "", o.flat ? ", terrain flattened" : "");
    check(face_files::new_solid(faces, &domain), o.input.c_str());
  } else {
    if (!fs::exists(path)) throw std::runtime_error(o.input + ": no such file or folder");
    if (o.lid || o.flat) throw UsageError("--lid and --flat-terrain need a folder of triangulated faces");
    check(igaparam_domain_new_solid_from_file_scaled(o.input.c_str(), o.scale ? o.scale->data() : nullptr, &domain),
          o.input.c_str());
  }
  return DomainPtr(domain);
}

SplinePtr build_and_fit(const Options &o, DomainPtr domain, bool &certified) {
  size_t dim = 0;
  check(igaparam_domain_dimension(domain.get(), &dim), "dimension");
  if (dim != 3) throw std::runtime_error(o.input + ": not a solid (six surfaces or six faces)");
  FitOptions options;
  options.threads = o.threads;
  options.tolerance = o.tolerance.value_or(0.0);
  options.max_level = o.max_level;
  options.refits = 0;
  SplinePtr spline = fit(std::move(domain), options);
  igaparam_validity_report v;
  check(igaparam_spline_check_validity(spline.get(), nullptr, &v, nullptr, nullptr, 0), "validity");
  certified = v.certified_positive != 0;
  std::printf("spline map: q_S min %.4f mean %.4f, det J %s\n", v.min_quality, v.mean_quality,
              certified ? "certified positive" : "NOT certified positive");
  return spline;
}

// The images of parametric points (3 values each).
std::vector<double> map_points(const igaparam_spline *s, const std::vector<double> &params) {
  std::vector<double> xyz(params.size());
  check(igaparam_spline_evaluate(s, params.size() / 3, params.data(), xyz.data(), nullptr), "evaluate");
  return xyz;
}

// The parametric point with coordinate `a` = va, `b` = vb and the third one = vc.
std::array<double, 3> param(int a, double va, int b, double vb, double vc) {
  std::array<double, 3> p{vc, vc, vc};
  p[a] = va;
  p[b] = vb;
  return p;
}

// The images of an n × n grid of the parametric face (axis, side), row-major.
std::vector<double> face_grid(const igaparam_spline *s, TerrainFace face, int n) {
  std::vector<double> params;
  const int u = (face.axis + 1) % 3, v = (face.axis + 2) % 3;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      std::array<double, 3> p = param(u, double(i) / (n - 1), v, double(j) / (n - 1), 0.0);
      p[face.axis] = double(face.side);
      params.insert(params.end(), p.begin(), p.end());
    }
  return map_points(s, params);
}

// Seeds of the streamlines: on the upwind wall (the side face whose centre lies furthest against
// the wind), 1% inside it, 12 across, at 2% and at 25% of the parametric height.
std::vector<double> seeds(const igaparam_spline *s, TerrainFace terrain, const InitialWind &wind) {
  int best_axis = -1, best_side = 0;
  double best = HUGE_VAL;
  for (int axis = 0; axis < 3; axis++)
    for (int side = 0; side < 2 && axis != terrain.axis; side++) {
      std::array<double, 3> centre{0.5, 0.5, 0.5};
      centre[axis] = double(side);
      const std::vector<double> c = map_points(s, {centre.begin(), centre.end()});
      const double along = c[0] * wind.velocity[0] + c[1] * wind.velocity[1] + c[2] * wind.velocity[2];
      if (along < best) best = along, best_axis = axis, best_side = side;
    }
  const int across = 3 - terrain.axis - best_axis;
  std::vector<double> params;
  for (double height : {0.02, 0.25})
    for (int i = 0; i < 12; i++) {
      std::array<double, 3> p = param(terrain.axis, terrain.side == 0 ? height : 1.0 - height, across,
                                      0.04 + 0.92 * i / 11.0, 0.0);
      p[best_axis] = best_side == 0 ? 0.01 : 0.99;
      params.insert(params.end(), p.begin(), p.end());
    }
  return map_points(s, params);
}

void write_outputs(const Options &o, const WindSolution &s, const igaparam_spline *spline, TerrainFace terrain) {
  if (o.vtu.empty() && o.png.empty()) return;
  auto grid = render_streamlines::to_vtk(sample(s.space, 2, wind_fields(s, o.wind)));
  if (!o.vtu.empty()) {
    render_streamlines::write_vtu(grid, o.vtu);
    std::printf("wrote %s\n", o.vtu.c_str());
  }
  if (o.png.empty()) return;
  const int n = 96;
  render_streamlines::Picture picture;
  picture.stretch = o.stretch;
  picture.width = o.width;
  picture.height = o.height;
  picture.title = "adjusted wind over the terrain: streamlines from near the ground and higher up";
  char sub[256];
  double top[3];
  std::array<double, 3> lid_centre{0.5, 0.5, 0.5};
  lid_centre[terrain.axis] = 1.0 - terrain.side;
  check(igaparam_spline_evaluate(spline, 1, lid_centre.data(), top, nullptr), "evaluate");
  std::snprintf(sub, sizeof sub, "%s initial wind (%g, %g, %g), %zu elements, lid at z = %.3g (above the view), "
                "vertical scale x%g", o.wind.logarithmic ? "logarithmic" : "constant", o.wind.velocity[0],
                o.wind.velocity[1], o.wind.velocity[2], s.space.elements.size(), top[2], o.stretch);
  picture.subtitle = sub;
  render_streamlines::render_png(grid, seeds(spline, terrain, o.wind), face_grid(spline, terrain, n), n, picture,
                                 o.png);
  std::printf("wrote %s\n", o.png.c_str());
}

int run(int argc, char **argv) {
  const Options o = parse(argc, argv);
  bool certified = false;
  SplinePtr spline = build_and_fit(o, open_block(o), certified);
  const TerrainFace terrain = find_terrain(spline.get());
  InitialWind wind = o.wind;
  wind.ground = lowest_point(spline.get(), terrain, 64);
  std::printf("terrain: parametric face u%d = %d, lowest point z = %.6g\n", terrain.axis, terrain.side, wind.ground);
  std::printf("%5s %9s %9s %10s %12s %7s %12s %7s %12s %8s\n", "level", "elements", "dofs", "h", "|div u|", "rate",
              "|n.u|", "rate", "max change", "seconds");
  std::vector<double> elements, dofs, hs, divs, normals, changes;
  WindSolution last;
  double normal_initial = 0.0;
  for (int level = 0; level <= o.levels; level++) {
    const auto start = std::chrono::steady_clock::now();
    if (level > 0) check(igaparam_spline_refine(spline.get(), 0, nullptr, nullptr), "uniform refinement");
    last = solve_wind(spline.get(), wind, terrain, o.threads);
    elements.push_back(double(last.space.elements.size()));
    dofs.push_back(double(last.space.nb));
    hs.push_back(last.space.h);
    divs.push_back(last.checks.divergence);
    normals.push_back(last.checks.normal);
    changes.push_back(last.checks.max_change);
    normal_initial = last.checks.normal_initial;
    char r1[16] = "", r2[16] = "";
    if (level > 0) {
      std::snprintf(r1, sizeof r1, "%.2f", last_rate(hs, divs));
      std::snprintf(r2, sizeof r2, "%.2f", last_rate(hs, normals));
    }
    std::printf("%5d %9.0f %9.0f %10.4g %12.4e %7s %12.4e %7s %12.4e %8.2f\n", level, elements.back(), dofs.back(),
                hs.back(), divs.back(), r1, normals.back(), r2, changes.back(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    std::fflush(stdout);
  }
  const double rate_div = last_rate(hs, divs), rate_normal = last_rate(hs, normals);
  std::printf("initial wind: |n.u0| over the terrain %.4e\n", normal_initial);
  write_outputs(o, last, spline.get(), terrain);
  std::printf("{\"certified\": %s, \"terrain_axis\": %d, \"terrain_side\": %d, \"profile\": \"%s\", \"threads\": %d, "
              "\"elements\": %s, \"dofs\": %s, \"h\": %s, \"divergence\": %s, \"normal\": %s, \"max_change\": %s, "
              "\"normal_initial\": %s, \"rate_divergence\": %s, \"rate_normal\": %s}\n",
              certified ? "true" : "false", terrain.axis, terrain.side, wind.logarithmic ? "log" : "constant", o.threads,
              json_list(elements).c_str(), json_list(dofs).c_str(), json_list(hs).c_str(), json_list(divs).c_str(),
              json_list(normals).c_str(), json_list(changes).c_str(), json_number(normal_initial).c_str(),
              json_number(rate_div).c_str(), json_number(rate_normal).c_str());
  int status = 0;
  if (o.check_rates && !(o.levels >= 1 && rate_div >= (*o.check_rates)[0] && rate_normal >= (*o.check_rates)[1])) {
    std::fprintf(stderr, "igaparam_wind: rates %.3f (divergence) and %.3f (normal) below %.3f and %.3f\n", rate_div,
                 rate_normal, (*o.check_rates)[0], (*o.check_rates)[1]);
    status = 3;
  }
  if (o.check_certified && !certified) {
    std::fprintf(stderr, "igaparam_wind: the spline map is not certified valid\n");
    status = 3;
  }
  if (o.check_reduction && !(normals.back() <= *o.check_reduction * normal_initial)) {
    std::fprintf(stderr, "igaparam_wind: |n.u| over the terrain %.3e is above %g times that of u0 (%.3e)\n",
                 normals.back(), *o.check_reduction, normal_initial);
    status = 3;
  }
  if (o.check_exact && !(*std::max_element(changes.begin(), changes.end()) <= *o.check_exact)) {
    std::fprintf(stderr, "igaparam_wind: the adjusted wind differs from u0 by more than %g\n", *o.check_exact);
    status = 3;
  }
  return status;
}

}  // namespace

int main(int argc, char **argv) {
  try {
    return run(argc, argv);
  } catch (const UsageError &e) {
    std::fprintf(stderr, "igaparam_wind: %s\n", e.what());
    usage();
    return 2;
  } catch (const render_picture::NoDisplayError &e) {
    std::fprintf(stderr, "igaparam_wind: %s\n", e.what());
    return 77;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "igaparam_wind: %s\n", e.what());
    return 1;
  }
}
