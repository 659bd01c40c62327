// igaparam: header-only C++17 wrapper of the C API in igaparam.h.
//
// - igaparam::Error (a std::runtime_error) carries the status and message of a failed call.
// - igaparam::Mesh is a move-only owner of an igaparam_mesh*, with methods that check sizes,
//   throw on failure and return std::vector for the arrays the C API copies out.
// - igaparam::Domain owns an igaparam_domain* (a planar domain or a solid and its T-mesh).
// - igaparam::Spline likewise owns an igaparam_spline* (a cubic THB-spline map).
//
// Every C call goes through `detail::check`, so a method either succeeds or throws; as in the C
// API, a method that throws leaves the mesh unchanged.

#ifndef IGAPARAM_HPP
#define IGAPARAM_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "igaparam.h"

namespace igaparam {

/// A failed call: what() is the library's message, status() the igaparam_status it returned.
class Error : public std::runtime_error {
 public:
  Error(igaparam_status status, const std::string& message)
      : std::runtime_error(message), status_(status) {}

  igaparam_status status() const noexcept { return status_; }

 private:
  igaparam_status status_;
};

/// The library version string, e.g. "0.1.0".
inline std::string version() { return igaparam_version(); }

/// The default relocation options.
inline igaparam_relocate_options default_options() { return igaparam_relocate_options_default(); }

/// Nodes per cell of a supported cell type (VTK codes), or 0 for an unsupported one.
inline std::size_t nodes_per_cell(igaparam_cell_type type) noexcept {
  std::size_t count = 0;
  return igaparam_cell_type_node_count(type, &count) == IGAPARAM_STATUS_OK ? count : 0;
}

/// Progress of igaparam_mesh_relocate: return true to go on, false to cancel.
using Progress = std::function<bool(igaparam_stage stage, std::size_t done, std::size_t total)>;

namespace detail {

/// The calling thread's last error message.
inline std::string last_error_message() {
  const std::size_t size = igaparam_last_error_message(nullptr, 0);
  std::string message(size, '\0');
  igaparam_last_error_message(message.data(), message.size());
  message.resize(size > 0 ? size - 1 : 0);
  return message;
}

/// Throws Error unless `status` is IGAPARAM_STATUS_OK.
inline void check(igaparam_status status) {
  if (status != IGAPARAM_STATUS_OK) {
    throw Error(status, last_error_message());
  }
}

/// Throws Error(IGAPARAM_STATUS_INVALID_ARGUMENT) with `message` unless `ok`: for size checks the
/// wrapper must do itself, since the C API trusts the sizes it is given.
inline void require(bool ok, const std::string& message) {
  if (!ok) {
    throw Error(IGAPARAM_STATUS_INVALID_ARGUMENT, message);
  }
}

/// Carries a C++ progress function through the C callback; an exception it throws is kept and
/// rethrown once the C call has returned (exceptions must not cross the C boundary).
struct ProgressTrampoline {
  const Progress* progress;
  std::exception_ptr exception;

  static int call(void* user, igaparam_stage stage, std::size_t done, std::size_t total) {
    auto* self = static_cast<ProgressTrampoline*>(user);
    try {
      return (*self->progress)(stage, done, total) ? 0 : 1;
    } catch (...) {
      self->exception = std::current_exception();
      return 1;
    }
  }
};

}  // namespace detail

/// A quadrilateral or hexahedral mesh (owner of an igaparam_mesh*). Move-only.
class Mesh {
 public:
  /// Builds a mesh from `xyz` (3 coordinates per node, flat) and `connectivity` (nodes_per_cell(type)
  /// indices per cell, each cell's nodes in `order`: IGAPARAM_ORDER_VTK or IGAPARAM_ORDER_GMSH).
  /// The arrays are copied; all nodes start free.
  Mesh(igaparam_cell_type type, const std::vector<double>& xyz, const std::vector<std::int64_t>& connectivity,
       igaparam_node_order order = IGAPARAM_ORDER_VTK) {
    detail::require(xyz.size() % 3 == 0, "igaparam::Mesh: xyz must hold 3 coordinates per node");
    const std::size_t per_cell = nodes_per_cell(type);
    // For an unsupported type, pass no cells and let the library report the type.
    detail::require(per_cell == 0 || connectivity.size() % per_cell == 0,
                    "igaparam::Mesh: connectivity must hold " + std::to_string(per_cell) + " indices per cell");
    const std::size_t cells = per_cell == 0 ? 0 : connectivity.size() / per_cell;
    detail::check(
        igaparam_mesh_new_ordered(type, order, xyz.size() / 3, xyz.data(), cells, connectivity.data(), &mesh_));
  }

  /// Reads a mesh and its prescribed motion (point arrays fixed_components, moved) from a .vtu file
  /// in any storage (see igaparam_mesh_read_vtu).
  static Mesh read_vtu(const std::string& path) {
    igaparam_mesh* handle = nullptr;
    detail::check(igaparam_mesh_read_vtu(path.c_str(), &handle));
    return Mesh(handle);
  }

  /// Writes the mesh to a .vtu file in `format` (IGAPARAM_VTU_*; default zlib-compressed base64).
  void write_vtu(const std::string& path, igaparam_vtu_format format = IGAPARAM_VTU_DEFAULT) const {
    detail::check(igaparam_mesh_write_vtu_format(mesh_, path.c_str(), format));
  }

  /// Takes ownership of a handle from igaparam_mesh_new (may be NULL).
  explicit Mesh(igaparam_mesh* handle) noexcept : mesh_(handle) {}

  ~Mesh() { igaparam_mesh_free(mesh_); }

  Mesh(const Mesh&) = delete;
  Mesh& operator=(const Mesh&) = delete;
  Mesh(Mesh&& other) noexcept : mesh_(std::exchange(other.mesh_, nullptr)) {}
  Mesh& operator=(Mesh&& other) noexcept {
    if (this != &other) {
      igaparam_mesh_free(mesh_);
      mesh_ = std::exchange(other.mesh_, nullptr);
    }
    return *this;
  }

  /// The C handle (still owned by this object).
  igaparam_mesh* get() const noexcept { return mesh_; }
  /// Gives up ownership of the C handle.
  igaparam_mesh* release() noexcept { return std::exchange(mesh_, nullptr); }

  std::size_t node_count() const { return query<std::size_t>(igaparam_mesh_node_count); }
  std::size_t cell_count() const { return query<std::size_t>(igaparam_mesh_cell_count); }
  /// 2 for quadrilaterals, 3 for hexahedra.
  int dimension() const { return query<int>(igaparam_mesh_dimension); }
  /// The cell type (IGAPARAM_CELL_*).
  igaparam_cell_type cell_type() const { return query<igaparam_cell_type>(igaparam_mesh_cell_type); }
  /// The node order the connectivity was given in.
  igaparam_node_order order() const { return query<igaparam_node_order>(igaparam_mesh_order); }
  /// Cells with det J <= 0 at some Gauss–Lobatto point.
  std::size_t invalid_cell_count() const { return query<std::size_t>(igaparam_mesh_invalid_cell_count); }

  /// Sets every node's constraint mask (bit 0 keeps x, bit 1 y, bit 2 z); one entry per node.
  void set_fixed(const std::vector<std::uint8_t>& mask) {
    detail::check(igaparam_mesh_set_fixed(mesh_, mask.size(), mask.data()));
  }

  /// Moves node indices[i] to xyz[3i..3i+3].
  void move_nodes(const std::vector<std::int64_t>& indices, const std::vector<double>& xyz) {
    detail::require(xyz.size() == 3 * indices.size(), "igaparam::Mesh::move_nodes: xyz must hold 3 values per index");
    detail::check(igaparam_mesh_move_nodes(mesh_, indices.size(), indices.data(), xyz.data()));
  }

  /// Moves nodes 0..xyz.size()/3-1 to xyz.
  void move_nodes(const std::vector<double>& xyz) {
    detail::require(xyz.size() % 3 == 0, "igaparam::Mesh::move_nodes: xyz must hold 3 values per node");
    detail::check(igaparam_mesh_move_nodes(mesh_, xyz.size() / 3, nullptr, xyz.data()));
  }

  /// Makes the current positions the reference shape of the targets.
  void reset_reference() { detail::check(igaparam_mesh_reset_reference(mesh_)); }

  /// Relocates the free nodes; `options.progress` (a C callback) is used as given.
  igaparam_relocate_report relocate(const igaparam_relocate_options& options = default_options()) {
    igaparam_relocate_report report{};
    detail::check(igaparam_mesh_relocate(mesh_, &options, &report));
    return report;
  }

  /// Relocates the free nodes, calling `progress` (instead of options.progress) as work proceeds.
  /// If `progress` throws, the relocation is cancelled and the exception is rethrown.
  igaparam_relocate_report relocate(igaparam_relocate_options options, const Progress& progress) {
    detail::ProgressTrampoline trampoline{&progress, nullptr};
    options.progress = &detail::ProgressTrampoline::call;
    options.progress_user = &trampoline;
    igaparam_relocate_report report{};
    const igaparam_status status = igaparam_mesh_relocate(mesh_, &options, &report);
    if (trampoline.exception) {
      std::rethrow_exception(trampoline.exception);
    }
    detail::check(status);
    return report;
  }

  /// Current node positions, 3 per node (x0 y0 z0 x1 ...).
  std::vector<double> positions() const {
    std::vector<double> xyz(3 * node_count());
    detail::check(igaparam_mesh_copy_positions(mesh_, xyz.data(), xyz.size()));
    return xyz;
  }

  /// Reference positions (the shape of the targets), 3 per node.
  std::vector<double> reference() const {
    std::vector<double> xyz(3 * node_count());
    detail::check(igaparam_mesh_copy_reference(mesh_, xyz.data(), xyz.size()));
    return xyz;
  }

  /// Constraint mask of every node (bit 0 x, bit 1 y, bit 2 z fixed).
  std::vector<std::uint8_t> fixed() const {
    std::vector<std::uint8_t> mask(node_count());
    detail::check(igaparam_mesh_copy_fixed(mesh_, mask.data(), mask.size()));
    return mask;
  }

  /// The connectivity, each cell's nodes in `order` (the mesh's own order by default).
  std::vector<std::int64_t> connectivity() const { return connectivity(order()); }
  std::vector<std::int64_t> connectivity(igaparam_node_order order) const {
    std::vector<std::int64_t> cells(cell_count() * nodes_per_cell(cell_type()));
    detail::check(igaparam_mesh_copy_connectivity(mesh_, order, cells.data(), cells.size()));
    return cells;
  }

  /// Quality of every cell against `target` (IGAPARAM_TARGET_*): in (0, 1], 0 for an invalid cell.
  std::vector<double> cell_quality(igaparam_target target = IGAPARAM_TARGET_INITIAL) const {
    std::vector<double> quality(cell_count());
    detail::check(igaparam_mesh_copy_cell_quality(mesh_, target, quality.data(), quality.size()));
    return quality;
  }

 private:
  /// Calls a getter of the form f(const igaparam_mesh*, T*) and returns its output.
  template <typename T>
  T query(igaparam_status (*getter)(const igaparam_mesh*, T*)) const {
    T value{};
    detail::check(getter(mesh_, &value));
    return value;
  }

  igaparam_mesh* mesh_ = nullptr;
};

/// A planar domain or a solid and its T-mesh parameterization (owner of an igaparam_domain*).
/// Move-only.
class Domain {
 public:
  /// A planar domain from a G+Smo XML B-rep (.xml, four curves) or a coastline (.txt).
  static Domain planar_from_file(const std::string& path) {
    igaparam_domain* d = nullptr;
    detail::check(igaparam_domain_new_from_file(path.c_str(), &d));
    return Domain(d);
  }

  /// A solid from a G+Smo XML B-rep of six surfaces (.xml) or a folder of six OBJ faces.
  static Domain solid_from_file(const std::string& path) {
    igaparam_domain* d = nullptr;
    detail::check(igaparam_domain_new_solid_from_file(path.c_str(), &d));
    return Domain(d);
  }

  /// A solid from a file or folder as solid_from_file(path), every input coordinate multiplied
  /// by its axis' factor first (`scale` = {fx, fy, fz}, each finite and positive): for data whose
  /// axes are in different units; the T-mesh and spline map are in the scaled coordinates (see
  /// igaparam_domain_new_solid_from_file_scaled).
  static Domain solid_from_file(const std::string& path, const std::array<double, 3>& scale) {
    igaparam_domain* d = nullptr;
    detail::check(igaparam_domain_new_solid_from_file_scaled(path.c_str(), scale.data(), &d));
    return Domain(d);
  }

  /// A solid from six triangulated faces (xmin, xmax, ymin, ymax, zmin, zmax): `xyz[f]` holds 3
  /// coordinates per vertex, `triangles[f]` 3 vertex indices per triangle. The arrays are copied.
  static Domain solid_from_triangulations(const std::vector<std::vector<double>>& xyz,
                                          const std::vector<std::vector<std::uint32_t>>& triangles) {
    detail::require(xyz.size() == 6 && triangles.size() == 6,
                    "igaparam::Domain: six faces are needed");
    std::size_t nv[6], nt[6];
    const double* points[6];
    const std::uint32_t* tris[6];
    for (int f = 0; f < 6; f++) {
      detail::require(xyz[f].size() % 3 == 0 && triangles[f].size() % 3 == 0,
                      "igaparam::Domain: 3 coordinates per vertex and 3 indices per triangle");
      nv[f] = xyz[f].size() / 3;
      nt[f] = triangles[f].size() / 3;
      points[f] = xyz[f].data();
      tris[f] = triangles[f].data();
    }
    igaparam_domain* d = nullptr;
    detail::check(igaparam_domain_new_solid_from_triangulations(nv, points, nt, tris, &d));
    return Domain(d);
  }

  /// Takes ownership of a handle from igaparam_domain_new_* (may be NULL).
  explicit Domain(igaparam_domain* handle) noexcept : domain_(handle) {}
  ~Domain() { igaparam_domain_free(domain_); }
  Domain(const Domain&) = delete;
  Domain& operator=(const Domain&) = delete;
  Domain(Domain&& other) noexcept : domain_(std::exchange(other.domain_, nullptr)) {}
  Domain& operator=(Domain&& other) noexcept {
    if (this != &other) {
      igaparam_domain_free(domain_);
      domain_ = std::exchange(other.domain_, nullptr);
    }
    return *this;
  }

  /// The C handle (still owned by this object).
  igaparam_domain* get() const noexcept { return domain_; }

  /// 2 for a planar domain, 3 for a solid.
  std::size_t dimension() const {
    std::size_t d = 0;
    detail::check(igaparam_domain_dimension(domain_, &d));
    return d;
  }

  /// Adapts, places and optimizes the T-mesh with the defaults of its dimension
  /// (igaparam_domain_options_default, or igaparam_domain_options_default_solid for a solid).
  igaparam_domain_report build() {
    igaparam_domain_report report{};
    detail::check(igaparam_domain_build(domain_, nullptr, &report));
    return report;
  }

  /// Adapts, places and optimizes the T-mesh with the given options (start from
  /// default_options()).
  igaparam_domain_report build(const igaparam_domain_options& options) {
    igaparam_domain_report report{};
    detail::check(igaparam_domain_build(domain_, &options, &report));
    return report;
  }

  /// The default options of this domain's dimension.
  igaparam_domain_options default_options() const {
    return dimension() == 3 ? igaparam_domain_options_default_solid() : igaparam_domain_options_default();
  }

  /// Parametric coordinates of the vertices, dimension() per vertex.
  std::vector<double> parametric() const { return vertices(true); }

  /// Physical coordinates of the vertices, dimension() per vertex.
  std::vector<double> physical() const { return vertices(false); }

  /// Quality of every cell.
  std::vector<double> cell_quality() const {
    std::vector<double> q(cell_count());
    detail::check(igaparam_domain_copy_cell_quality(domain_, q.data(), q.size()));
    return q;
  }

  /// Level of every cell.
  std::vector<std::uint8_t> cell_levels() const {
    std::vector<std::uint8_t> levels(cell_count());
    detail::check(igaparam_domain_copy_cells(domain_, levels.data(), nullptr, levels.size()));
    return levels;
  }

  /// Corner vertices of every cell, 2^dimension() per cell (VTK quad / hexahedron order).
  std::vector<std::size_t> cell_corners() const {
    std::vector<std::size_t> corners(cell_count() << dimension());
    detail::check(igaparam_domain_copy_cell_corners(domain_, corners.data(), corners.size()));
    return corners;
  }

  /// Writes the T-mesh as a .vtu file.
  void write_vtu(const std::string& path) const {
    detail::check(igaparam_domain_write_vtu(domain_, path.c_str()));
  }

  /// Number of vertices of the built T-mesh, hanging ones included.
  std::size_t vertex_count() const {
    std::size_t n = 0;
    detail::check(igaparam_domain_vertex_count(domain_, &n));
    return n;
  }

  /// Number of cells of the built T-mesh.
  std::size_t cell_count() const {
    std::size_t n = 0;
    detail::check(igaparam_domain_cell_count(domain_, &n));
    return n;
  }

 private:
  std::vector<double> vertices(bool parametric) const {
    std::vector<double> out(vertex_count() * dimension());
    detail::check(igaparam_domain_copy_vertices(domain_, parametric ? out.data() : nullptr,
                                                parametric ? nullptr : out.data(), out.size()));
    return out;
  }

  igaparam_domain* domain_ = nullptr;
};

/// The Bézier extraction of one element: N_functions[i] = Σ_k op[i·4^d + k] B_k on the element.
struct Extraction {
  std::vector<std::size_t> functions;  ///< global indices of the functions non-zero on it
  std::vector<double> op;              ///< functions.size() × 4^d, row-major
};

/// The basis functions non-zero at a point.
struct BasisValues {
  std::vector<std::size_t> functions;  ///< global indices
  std::vector<double> values;          ///< one per function
  std::vector<double> gradients;       ///< d per function, with respect to the parameters
};

/// A cubic THB-spline map S: [0,1]^d → Ω (owner of an igaparam_spline*). Move-only; clone() copies.
/// Points are flat arrays, d doubles each.
class Spline {
 public:
  /// Fits the spline map of a built domain; `report` may be NULL.
  static Spline fit(const igaparam_domain* domain, igaparam_fit_report* report = nullptr) {
    igaparam_spline* handle = nullptr;
    detail::check(igaparam_spline_fit_domain(domain, &handle, report));
    return Spline(handle);
  }

  /// Fits the spline map of a built domain; `report` may be NULL.
  static Spline fit(const Domain& domain, igaparam_fit_report* report = nullptr) {
    return fit(domain.get(), report);
  }

  /// The adaptive loop: fits the map of a built domain, refines its T-mesh where the map is of
  /// poor quality, optimizes and refits (igaparam_domain_fit_adaptive); the domain keeps the
  /// refined T-mesh. `report` may be NULL.
  static Spline fit_adaptive(Domain& domain,
                             const igaparam_adapt_options& options = igaparam_adapt_options_default(),
                             igaparam_adapt_report* report = nullptr) {
    igaparam_spline* handle = nullptr;
    detail::check(igaparam_domain_fit_adaptive(domain.get(), &options, &handle, report));
    return Spline(handle);
  }

  /// Reads a map written by write_gismo.
  static Spline read_gismo(const std::string& path) {
    igaparam_spline* handle = nullptr;
    detail::check(igaparam_spline_read_gismo(path.c_str(), &handle));
    return Spline(handle);
  }

  /// Takes ownership of a handle (may be NULL).
  explicit Spline(igaparam_spline* handle) noexcept : spline_(handle) {}
  ~Spline() { igaparam_spline_free(spline_); }
  Spline(const Spline&) = delete;
  Spline& operator=(const Spline&) = delete;
  Spline(Spline&& other) noexcept : spline_(std::exchange(other.spline_, nullptr)) {}
  Spline& operator=(Spline&& other) noexcept {
    if (this != &other) {
      igaparam_spline_free(spline_);
      spline_ = std::exchange(other.spline_, nullptr);
    }
    return *this;
  }

  /// An independent copy.
  Spline clone() const {
    igaparam_spline* handle = nullptr;
    detail::check(igaparam_spline_clone(spline_, &handle));
    return Spline(handle);
  }

  /// The C handle (still owned by this object).
  igaparam_spline* get() const noexcept { return spline_; }

  std::size_t dimension() const { return query(igaparam_spline_dimension); }
  std::size_t basis_count() const { return query(igaparam_spline_basis_count); }
  std::size_t element_count() const { return query(igaparam_spline_element_count); }

  /// Control points, basis_count() × d.
  std::vector<double> control_points() const {
    return copied(basis_count() * dimension(), igaparam_spline_copy_control_points);
  }

  /// Greville points of the basis functions, basis_count() × d.
  std::vector<double> greville_points() const {
    return copied(basis_count() * dimension(), igaparam_spline_copy_greville_points);
  }

  /// Level of every element.
  std::vector<std::uint8_t> element_levels() const {
    std::vector<std::uint8_t> levels(element_count());
    detail::check(igaparam_spline_copy_elements(spline_, levels.data(), nullptr, levels.size()));
    return levels;
  }

  /// Box of every element, element_count() × 2d (lower corner, then upper corner).
  std::vector<double> element_bounds() const {
    const std::size_t n = element_count();
    std::vector<double> bounds(2 * dimension() * n);
    detail::check(igaparam_spline_copy_elements(spline_, nullptr, bounds.data(), n));
    return bounds;
  }

  /// The Bézier extraction of element `e`.
  Extraction extraction(std::size_t e) const {
    std::size_t m = 0;
    detail::check(igaparam_spline_element_function_count(spline_, e, &m));
    Extraction x{std::vector<std::size_t>(m), std::vector<double>(m * bernstein_count())};
    detail::check(igaparam_spline_copy_element_extraction(spline_, e, x.functions.data(), m, x.op.data(),
                                                          x.op.size()));
    return x;
  }

  /// S at the parametric points `params` (n × d in [0,1]^d); `jacobians`, if given, receives
  /// n × d × d row-major entries ∂S_i/∂u_j.
  std::vector<double> evaluate(const std::vector<double>& params, std::vector<double>* jacobians = nullptr) const {
    const std::size_t d = dimension(), n = count(params, d);
    std::vector<double> points(n * d);
    if (jacobians) jacobians->assign(n * d * d, 0.0);
    detail::check(igaparam_spline_evaluate(spline_, n, params.data(), points.data(),
                                           jacobians ? jacobians->data() : nullptr));
    return points;
  }

  /// Mean ratio of the Jacobian at the parametric points `params` (n × d).
  std::vector<double> mean_ratio(const std::vector<double>& params) const {
    const std::size_t n = count(params, dimension());
    std::vector<double> q(n);
    detail::check(igaparam_spline_mean_ratio(spline_, n, params.data(), q.data()));
    return q;
  }

  /// Parametric points of the physical points `points` (n × d): NaN where `found` is 0.
  std::vector<double> invert(const std::vector<double>& points, std::vector<int>* found = nullptr,
                             std::uint32_t samples = 4) const {
    const std::size_t d = dimension(), n = count(points, d);
    std::vector<double> params(n * d);
    if (found) found->assign(n, 0);
    detail::check(igaparam_spline_invert(spline_, n, points.data(), samples, params.data(),
                                         found ? found->data() : nullptr));
    return params;
  }

  /// The basis functions non-zero at the parametric point `param` (d values).
  BasisValues basis_at(const std::vector<double>& param) const {
    const std::size_t d = dimension();
    detail::require(param.size() == d, "igaparam::Spline::basis_at: param must hold d values");
    std::size_t m = 0;
    detail::check(igaparam_spline_basis_count_at(spline_, param.data(), &m));
    BasisValues b{std::vector<std::size_t>(m), std::vector<double>(m), std::vector<double>(m * d)};
    detail::check(igaparam_spline_basis_at(spline_, param.data(), &m, b.functions.data(), b.values.data(),
                                           b.gradients.data(), m));
    return b;
  }

  /// Refines the marked elements (all when empty), the map staying the same.
  igaparam_fit_report refine(const std::vector<std::size_t>& elements = {}) {
    igaparam_fit_report report{};
    detail::check(igaparam_spline_refine(spline_, elements.size(), elements.empty() ? nullptr : elements.data(),
                                         &report));
    return report;
  }

  /// Certified validity and quality; `element_quality`, if given, receives each element's
  /// smallest sampled mean ratio.
  igaparam_validity_report check_validity(const igaparam_validity_options& options = igaparam_validity_options_default(),
                                          std::vector<double>* element_quality = nullptr) const {
    igaparam_validity_report report{};
    const std::size_t n = element_quality ? element_count() : 0;
    if (element_quality) element_quality->assign(n, 0.0);
    detail::check(igaparam_spline_check_validity(spline_, &options, &report, nullptr,
                                                 element_quality ? element_quality->data() : nullptr, n));
    return report;
  }

  /// Writes the map sampled on `samples`^d sub-cells per element as .vtu.
  void write_vtu(const std::string& path, std::uint32_t samples = 4) const {
    detail::check(igaparam_spline_write_vtu(spline_, path.c_str(), samples));
  }

  /// Writes the map as G+Smo XML.
  void write_gismo(const std::string& path) const { detail::check(igaparam_spline_write_gismo(spline_, path.c_str())); }

 private:
  std::size_t query(igaparam_status (*getter)(const igaparam_spline*, std::size_t*)) const {
    std::size_t value = 0;
    detail::check(getter(spline_, &value));
    return value;
  }

  std::vector<double> copied(std::size_t n, igaparam_status (*copy)(const igaparam_spline*, double*, std::size_t)) const {
    std::vector<double> values(n);
    detail::check(copy(spline_, values.data(), values.size()));
    return values;
  }

  std::size_t bernstein_count() const { return dimension() == 2 ? 16 : 64; }

  static std::size_t count(const std::vector<double>& points, std::size_t d) {
    detail::require(points.size() % d == 0, "igaparam::Spline: point arrays must hold d values per point");
    return points.size() / d;
  }

  igaparam_spline* spline_ = nullptr;
};

}  // namespace igaparam

#endif  // IGAPARAM_HPP
