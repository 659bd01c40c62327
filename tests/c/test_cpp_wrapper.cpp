// Tests of the C++ wrapper bindings/cpp/igaparam.hpp: errors become igaparam::Error with the
// status and the library's message, Mesh owns and moves its handle, vectors have the right sizes,
// and a progress function can cancel or throw through the C callback; a domain of curves morphed
// in steps (update and refit).

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "igaparam.hpp"
#include "structured_grid.h"

namespace {

int passed = 0, failed = 0;

void check_at(bool ok, const char* file, int line, const char* what) {
  if (ok) {
    passed++;
  } else {
    failed++;
    std::fprintf(stderr, "FAIL %s:%d: %s\n", file, line, what);
  }
}

#define CHECK(cond) check_at((cond), __FILE__, __LINE__, #cond)

/// Runs `f`, which must throw igaparam::Error with `status` and a non-empty message.
template <typename F>
void expect_error_at(igaparam_status status, F&& f, const char* file, int line, const char* what) {
  try {
    f();
    check_at(false, file, line, what);
  } catch (const igaparam::Error& e) {
    check_at(e.status() == status && std::strlen(e.what()) > 0, file, line, what);
  }
}

#define EXPECT_ERROR(status, statement) expect_error_at((status), [&] { statement; }, __FILE__, __LINE__, #statement)

/// A Q4 grid mesh with its boundary fixed and its middle node pushed past a neighbour (a folded cell).
igaparam::Mesh tangled_mesh(structured_grid& g) {
  structured_grid_init(&g, IGAPARAM_CELL_QUAD4, 4, 4, 1);
  igaparam::Mesh mesh(g.type, std::vector<double>(g.xyz, g.xyz + 3 * g.num_nodes),
                      std::vector<std::int64_t>(g.connectivity, g.connectivity + 4 * g.num_cells));
  uint8_t* mask = structured_grid_boundary_mask(&g);
  mesh.set_fixed(std::vector<std::uint8_t>(mask, mask + g.num_nodes));
  std::free(mask);
  const auto middle = static_cast<std::int64_t>(structured_grid_node(&g, 2, 2, 0));  // at (0.5, 0.5)
  mesh.move_nodes({middle}, {0.3, 0.3, 0.0});
  return mesh;
}

igaparam_relocate_options from_current() {
  igaparam_relocate_options o = igaparam::default_options();
  o.placement = IGAPARAM_PLACEMENT_CURRENT;
  return o;
}

/// The spline map of a quarter annulus (radii 1 and 2) built from four polylines: Spline's sizes,
/// the agreement of its basis with its evaluation, refinement keeping the map, errors.
void test_spline() {
  const double pi = 3.14159265358979323846;
  const int n = 33;
  std::vector<std::vector<double>> sides(4);
  for (int i = 0; i < n; i++) {
    const double t = double(i) / (n - 1), a = 0.5 * pi * t;
    sides[0].insert(sides[0].end(), {0.0, 2.0 - t});                        // x = 0, from (0,2) to (0,1)
    sides[1].insert(sides[1].end(), {1.0 + t, 0.0});                        // y = 0
    sides[2].insert(sides[2].end(), {2.0 * std::cos(a), 2.0 * std::sin(a)});  // outer arc
    sides[3].insert(sides[3].end(), {std::sin(a), std::cos(a)});             // inner arc, from (0,1)
  }
  // The reader matches the curves by their end points and orients them.
  const double* points[4] = {sides[0].data(), sides[1].data(), sides[2].data(), sides[3].data()};
  const std::size_t counts[4] = {std::size_t(n), std::size_t(n), std::size_t(n), std::size_t(n)};
  igaparam_domain* domain = nullptr;
  igaparam::detail::check(igaparam_domain_new_from_polylines(counts, points, &domain));
  igaparam::detail::check(igaparam_domain_build(domain, nullptr, nullptr));
  igaparam_fit_report fit{};
  igaparam::Spline spline = igaparam::Spline::fit(domain, &fit);
  igaparam_domain_free(domain);
  CHECK(spline.dimension() == 2 && spline.basis_count() == fit.basis_count);
  CHECK(spline.control_points().size() == 2 * spline.basis_count());
  CHECK(spline.greville_points().size() == 2 * spline.basis_count());
  CHECK(spline.element_bounds().size() == 4 * spline.element_count());
  CHECK(spline.element_levels().size() == spline.element_count());
  const igaparam::Extraction x = spline.extraction(0);
  CHECK(!x.functions.empty() && x.op.size() == 16 * x.functions.size());

  // Σ N_i P_i = S at a point; the image lies in the annulus.
  const std::vector<double> uv = {0.3, 0.6};
  std::vector<double> jac;
  const std::vector<double> xy = spline.evaluate(uv, &jac);
  const igaparam::BasisValues b = spline.basis_at(uv);
  const std::vector<double> control = spline.control_points();
  double sx = 0, sy = 0, sum = 0;
  for (std::size_t i = 0; i < b.functions.size(); i++) {
    sx += b.values[i] * control[2 * b.functions[i]];
    sy += b.values[i] * control[2 * b.functions[i] + 1];
    sum += b.values[i];
  }
  CHECK(std::fabs(sx - xy[0]) < 1e-12 && std::fabs(sy - xy[1]) < 1e-12 && std::fabs(sum - 1) < 1e-13);
  const double r = std::hypot(xy[0], xy[1]);
  CHECK(r > 1.0 && r < 2.0 && jac.size() == 4);
  const std::vector<double> back = spline.invert(xy);
  CHECK(std::fabs(back[0] - uv[0]) < 1e-9 && std::fabs(back[1] - uv[1]) < 1e-9);
  CHECK(spline.mean_ratio(uv)[0] > 0.0);

  // Refining a copy keeps the map; the original is untouched.
  igaparam::Spline finer = spline.clone();
  const igaparam_fit_report refined = finer.refine();
  CHECK(refined.basis_count > spline.basis_count() && finer.basis_count() == refined.basis_count);
  const std::vector<double> again = finer.evaluate(uv);
  CHECK(std::fabs(again[0] - xy[0]) < 1e-9 && std::fabs(again[1] - xy[1]) < 1e-9);
  const igaparam_validity_report v = finer.check_validity();
  CHECK(v.certified_positive == 1 && v.min_quality > 0.2);
  const igaparam_quality_bound_report qb = finer.quality_bound();
  CHECK(qb.lower_bound > 0.0 && qb.lower_bound <= qb.sampled_min && qb.sampled_min == v.min_quality);
  igaparam_quality_bound_options bad = igaparam_quality_bound_options_default();
  bad.samples = 1;
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, finer.quality_bound(bad));

  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, spline.evaluate({0.5, 1.5}));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, spline.evaluate({0.5}));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, spline.extraction(spline.element_count()));
  EXPECT_ERROR(IGAPARAM_STATUS_IO, igaparam::Spline::read_gismo("/nonexistent/spline.xml"));
}

/// A solid read with per-axis factors: bad factors throw before any I/O; the duck B-rep doubled
/// builds into the same T-mesh with every physical coordinate doubled.
void test_scaled_solid() {
  const std::string duck = std::string(IGAPARAM_TEST_DATA) + "/duck3d_BRep.xml";
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, igaparam::Domain::solid_from_file(duck, {1.0, 0.0, 1.0}));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT,
               igaparam::Domain::solid_from_file("/nonexistent/duck.xml", {1.0, 1.0, NAN}));
  EXPECT_ERROR(IGAPARAM_STATUS_IO, igaparam::Domain::solid_from_file("/nonexistent/duck.xml", {2.0, 2.0, 2.0}));
  igaparam::Domain plain = igaparam::Domain::solid_from_file(duck);
  igaparam::Domain doubled = igaparam::Domain::solid_from_file(duck, {2.0, 2.0, 2.0});
  CHECK(doubled.dimension() == 3);
  igaparam_domain_options o = igaparam_domain_options_default();
  o.tolerance = 3e-3;
  o.min_level = 1;
  o.max_level = 3;
  const igaparam_domain_report a = plain.build(o), b = doubled.build(o);
  CHECK(a.invalid_cells == 0 && a.cells == b.cells);
  std::vector<double> x = plain.physical(), y = doubled.physical();
  for (double& v : x) v *= 2;
  CHECK(x.size() == 3 * a.vertices && x == y);
  CHECK(plain.parametric() == doubled.parametric());
}

/// One 27-node hexahedron on the lattice {0, 1/2, 1}^3 (node i + 3j + 9k at (i, j, k)/2): its
/// connectivity in `order`, read from the library's table of reference coordinates.
std::vector<std::int64_t> cube_cell(igaparam_node_order order) {
  std::vector<double> xi(27 * 3);
  igaparam::detail::check(igaparam_cell_type_copy_node_coordinates(IGAPARAM_CELL_HEX27, order, xi.data(), xi.size()));
  std::vector<std::int64_t> cell(27);
  for (std::size_t n = 0; n < 27; n++) {
    cell[n] = static_cast<std::int64_t>((xi[3 * n] + 1) + 3 * (xi[3 * n + 1] + 1) + 9 * (xi[3 * n + 2] + 1));
  }
  return cell;
}

/// Node orders and .vtu files through the wrapper.
void orders_and_files() {
  std::vector<double> xyz;
  for (int k = 0; k < 3; k++)
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3; i++) xyz.insert(xyz.end(), {i / 2.0, j / 2.0, k / 2.0});
  const std::vector<std::int64_t> vtk = cube_cell(IGAPARAM_ORDER_VTK), gmsh = cube_cell(IGAPARAM_ORDER_GMSH);
  CHECK(vtk != gmsh && vtk[9] == 5 && gmsh[9] == 3);  // node 9: edge 1-2 (VTK), edge 0-3 (Gmsh)
  igaparam::Mesh from_gmsh(IGAPARAM_CELL_HEX27, xyz, gmsh, IGAPARAM_ORDER_GMSH);
  CHECK(from_gmsh.order() == IGAPARAM_ORDER_GMSH && from_gmsh.cell_type() == IGAPARAM_CELL_HEX27);
  CHECK(from_gmsh.connectivity() == gmsh && from_gmsh.connectivity(IGAPARAM_ORDER_VTK) == vtk);
  CHECK(from_gmsh.invalid_cell_count() == 0);
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_MESH, igaparam::Mesh(IGAPARAM_CELL_HEX27, xyz, gmsh));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, igaparam::Mesh(IGAPARAM_CELL_HEX27, xyz, gmsh, 7));

  igaparam::Mesh airfoil = igaparam::Mesh::read_vtu(IGAPARAM_TEST_DATA "/../airfoil_0012_q9.vtu");
  CHECK(airfoil.cell_type() == IGAPARAM_CELL_QUAD9 && airfoil.cell_count() == 490);
  const std::string path = std::string(IGAPARAM_TEST_OUT) + "/cpp_wrapper_airfoil.vtu";
  airfoil.write_vtu(path, IGAPARAM_VTU_APPENDED | IGAPARAM_VTU_ZLIB);
  igaparam::Mesh back = igaparam::Mesh::read_vtu(path);
  CHECK(back.positions() == airfoil.positions() && back.fixed() == airfoil.fixed());
  CHECK(back.connectivity() == airfoil.connectivity());
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, airfoil.write_vtu(path, IGAPARAM_VTU_ASCII | IGAPARAM_VTU_ZLIB));
  EXPECT_ERROR(IGAPARAM_STATUS_IO, igaparam::Mesh::read_vtu(path + ".missing"));
}

/// The boundary of a quarter annulus of outer radius `outer` as four curves: the inner and outer
/// arcs exact NURBS quarter circles, the two straight sides lines.
std::vector<igaparam::Curve> quarter_annulus(double outer) {
  const double w = std::sqrt(0.5);
  const std::vector<double> line = {0, 0, 1, 1}, arc = {0, 0, 0, 1, 1, 1};
  return {
      {1, line, {0.0, outer, 0.0, 1.0}, {}},                      // x = 0, from (0, R) to (0, 1)
      {1, line, {1.0, 0.0, outer, 0.0}, {}},                      // y = 0
      {2, arc, {outer, 0.0, outer, outer, 0.0, outer}, {1, w, 1}},  // outer arc
      {2, arc, {0.0, 1.0, 1.0, 1.0, 1.0, 0.0}, {1, w, 1}},        // inner arc, from (0, 1)
  };
}

/// The loop of shape optimization through the wrapper: the outer radius of a quarter annulus
/// grows in steps, each an update of the domain and a refit of its spline in the same space.
void test_morph_loop() {
  igaparam::Domain domain = igaparam::Domain::planar_from_curves(quarter_annulus(2.0));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, domain.update());  // not built yet
  const igaparam_domain_report built = domain.build();
  igaparam::Spline spline = igaparam::Spline::fit(domain);
  const std::size_t basis = spline.basis_count();
  const std::vector<double> elements = spline.element_bounds();
  const igaparam_fit_rule rule = spline.fit_rule();
  for (int step = 1; step <= 4; step++) {
    domain.set_boundary(quarter_annulus(2.0 + 0.05 * step));
    const igaparam_domain_update_report u = domain.update();
    CHECK(u.domain.invalid_cells == 0 && u.domain.cells == built.cells && u.boundary_motion > 0);
    const igaparam_refit_report r = spline.refit(domain);
    CHECK(r.rule == rule && r.certified_positive == 1 && r.fit.basis_count == basis);
    CHECK(spline.basis_count() == basis && spline.element_bounds() == elements);
  }
  // The outer corners are at the new radius.
  const std::vector<double> corners = spline.evaluate({0, 0, 1, 0, 1, 1, 0, 1});
  double outer = 0;
  for (int c = 0; c < 4; c++) outer = std::fmax(outer, std::hypot(corners[2 * c], corners[2 * c + 1]));
  CHECK(std::fabs(outer - 2.2) < 1e-9);
  // Sensitivities need a polished build (stationarity_tolerance > 0) and arrays of the sizes.
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT,
               spline.tangent(domain, std::vector<double>(2 * domain.vertex_count())));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, spline.adjoint(domain, std::vector<double>(3)));
  CHECK(domain.control_count() > 0);
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT,
               spline.tangent_controls(domain, std::vector<double>(2 * domain.control_count())));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, spline.adjoint_controls(domain, std::vector<double>(3)));
  // Wrong arrays and boundaries of the other kind throw, the domain unchanged.
  std::vector<igaparam::Curve> odd = quarter_annulus(2.0);
  odd[0].control_points.pop_back();
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, domain.set_boundary(odd));
  odd = quarter_annulus(2.0);
  odd[2].knots = {0, 0, 0, 0.7, 0.2, 1, 1};
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, domain.set_boundary(odd));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, domain.set_boundary(std::vector<igaparam::Surface>(6)));
  CHECK(domain.update().boundary_motion == 0);
}

/// The fit with options through the wrapper: a C++ progress function sees the fit's stages, its
/// exception cancels the fit and is rethrown, and the result is that of the plain fit.
void test_fit_with_progress() {
  igaparam::Domain domain = igaparam::Domain::planar_from_curves(quarter_annulus(2.0));
  domain.build();
  const igaparam::Spline plain = igaparam::Spline::fit(domain);
  int fits = 0, smoothing = 0;
  const igaparam::Spline with = igaparam::Spline::fit(
      domain, igaparam_fit_options_default(), [&](igaparam_stage stage, std::size_t, std::size_t) {
        fits += stage == IGAPARAM_STAGE_FIT;
        smoothing += stage == IGAPARAM_STAGE_SMOOTHING;
        return true;
      });
  CHECK(fits > 0 && smoothing > 0 && with.control_points() == plain.control_points());
  bool thrown = false;
  try {
    igaparam::Spline::fit(domain, igaparam_fit_options_default(),
                          [](igaparam_stage, std::size_t, std::size_t) -> bool { throw 7; });
  } catch (int e) {
    thrown = e == 7;
  }
  CHECK(thrown);
  igaparam_fit_options options = igaparam_fit_options_default();
  options.validity.samples = 0;
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, igaparam::Spline::fit(domain, options));
}

}  // namespace

int main() {
  orders_and_files();
  CHECK(igaparam::version() == igaparam_version());
  CHECK(igaparam::nodes_per_cell(IGAPARAM_CELL_HEX27) == 27 && igaparam::nodes_per_cell(7) == 0);

  // Errors carry the status and the library's message.
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_MESH, igaparam::Mesh(IGAPARAM_CELL_QUAD4, {0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 1, 2, 3}));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, igaparam::Mesh(IGAPARAM_CELL_QUAD4, {0, 0, 0, 1}, {0, 1, 2, 3}));
  try {
    igaparam::Mesh(IGAPARAM_CELL_QUAD4, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 2});
    CHECK(false);
  } catch (const std::runtime_error& e) {  // igaparam::Error is a std::runtime_error
    CHECK(std::strlen(e.what()) > 0);
  }

  structured_grid g;
  igaparam::Mesh mesh = tangled_mesh(g);
  CHECK(mesh.node_count() == g.num_nodes && mesh.cell_count() == g.num_cells && mesh.dimension() == 2);
  CHECK(mesh.positions().size() == 3 * g.num_nodes && mesh.cell_quality().size() == g.num_cells);
  CHECK(mesh.invalid_cell_count() > 0);
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, mesh.move_nodes({0}, {1.0, 2.0}));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, mesh.set_fixed({0, 0}));
  EXPECT_ERROR(IGAPARAM_STATUS_INVALID_ARGUMENT, mesh.cell_quality(5));

  // Moving transfers the handle.
  igaparam_mesh* handle = mesh.get();
  igaparam::Mesh moved(std::move(mesh));
  CHECK(moved.get() == handle && mesh.get() == nullptr);
  mesh = std::move(moved);
  CHECK(mesh.get() == handle && moved.get() == nullptr);

  // A progress function that declines cancels; one that throws has its exception rethrown; the
  // mesh is unchanged either way.
  const std::vector<double> before = mesh.positions();
  EXPECT_ERROR(IGAPARAM_STATUS_CANCELLED, mesh.relocate(from_current(), [](igaparam_stage, std::size_t, std::size_t) {
    return false;
  }));
  bool rethrown = false;
  try {
    mesh.relocate(from_current(), [](igaparam_stage, std::size_t, std::size_t) -> bool {
      throw std::logic_error("stop");
    });
  } catch (const std::logic_error& e) {
    rethrown = std::string(e.what()) == "stop";
  }
  CHECK(rethrown);
  CHECK(mesh.positions() == before);

  // Untangling through the wrapper.
  std::size_t calls = 0;
  const igaparam_relocate_report r = mesh.relocate(from_current(), [&](igaparam_stage, std::size_t, std::size_t) {
    calls++;
    return true;
  });
  CHECK(calls > 0 && r.invalid_after == 0 && mesh.invalid_cell_count() == 0);
  CHECK(mesh.relocate().invalid_after == 0);

  test_spline();
  test_scaled_solid();
  test_morph_loop();
  test_fit_with_progress();

  structured_grid_free(&g);
  std::printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 ? 0 : 1;
}
