// igaparam: header-only C++17 wrapper of the C API in igaparam.h.
//
// - igaparam::Error (a std::runtime_error) carries the status and message of a failed call.
// - igaparam::Mesh is a move-only owner of an igaparam_mesh*, with methods that check sizes,
//   throw on failure and return std::vector for the arrays the C API copies out.
// - igaparam::Domain owns an igaparam_domain* (a planar domain or a solid and its T-mesh);
//   igaparam::Curve and igaparam::Surface hold the arrays of B-spline/NURBS boundaries.
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

/// Owner of one C handle of type `T`, released with `Free` (which accepts NULL) when the owner
/// is destroyed or assigned. Move-only; the base of Mesh, Domain and Spline.
template <typename T, void (*Free)(T*)>
class Handle {
 public:
  explicit Handle(T* handle = nullptr) noexcept : handle_(handle) {}
  ~Handle() { Free(handle_); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      Free(handle_);
      handle_ = std::exchange(other.handle_, nullptr);
    }
    return *this;
  }

  /// The C handle (still owned by this object).
  T* get() const noexcept { return handle_; }
  /// Gives up ownership of the C handle.
  T* release() noexcept { return std::exchange(handle_, nullptr); }

 protected:
  T* handle_ = nullptr;
};

}  // namespace detail

/// A quadrilateral or hexahedral mesh (owner of an igaparam_mesh*). Move-only.
class Mesh : public detail::Handle<igaparam_mesh, igaparam_mesh_free> {
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
        igaparam_mesh_new_ordered(type, order, xyz.size() / 3, xyz.data(), cells, connectivity.data(), &handle_));
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
    detail::check(igaparam_mesh_write_vtu_format(handle_, path.c_str(), format));
  }

  /// Takes ownership of a handle from igaparam_mesh_new (may be NULL).
  explicit Mesh(igaparam_mesh* handle) noexcept : Handle(handle) {}

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
    detail::check(igaparam_mesh_set_fixed(handle_, mask.size(), mask.data()));
  }

  /// Moves node indices[i] to xyz[3i..3i+3].
  void move_nodes(const std::vector<std::int64_t>& indices, const std::vector<double>& xyz) {
    detail::require(xyz.size() == 3 * indices.size(), "igaparam::Mesh::move_nodes: xyz must hold 3 values per index");
    detail::check(igaparam_mesh_move_nodes(handle_, indices.size(), indices.data(), xyz.data()));
  }

  /// Moves nodes 0..xyz.size()/3-1 to xyz.
  void move_nodes(const std::vector<double>& xyz) {
    detail::require(xyz.size() % 3 == 0, "igaparam::Mesh::move_nodes: xyz must hold 3 values per node");
    detail::check(igaparam_mesh_move_nodes(handle_, xyz.size() / 3, nullptr, xyz.data()));
  }

  /// Makes the current positions the reference shape of the targets.
  void reset_reference() { detail::check(igaparam_mesh_reset_reference(handle_)); }

  /// Relocates the free nodes; `options.progress` (a C callback) is used as given.
  igaparam_relocate_report relocate(const igaparam_relocate_options& options = default_options()) {
    igaparam_relocate_report report{};
    detail::check(igaparam_mesh_relocate(handle_, &options, &report));
    return report;
  }

  /// Relocates the free nodes, calling `progress` (instead of options.progress) as work proceeds.
  /// If `progress` throws, the relocation is cancelled and the exception is rethrown.
  igaparam_relocate_report relocate(igaparam_relocate_options options, const Progress& progress) {
    detail::ProgressTrampoline trampoline{&progress, nullptr};
    options.progress = &detail::ProgressTrampoline::call;
    options.progress_user = &trampoline;
    igaparam_relocate_report report{};
    const igaparam_status status = igaparam_mesh_relocate(handle_, &options, &report);
    if (trampoline.exception) {
      std::rethrow_exception(trampoline.exception);
    }
    detail::check(status);
    return report;
  }

  /// The total derivative of a scalar J with respect to the prescribed coordinates through the
  /// last relocation, given dJ/dx at every node (3 per node); see igaparam_mesh_adjoint.
  std::vector<double> adjoint(const std::vector<double>& dj_dx) const {
    std::vector<double> out(dj_dx.size());
    detail::check(igaparam_mesh_adjoint(handle_, dj_dx.size(), dj_dx.data(), out.data()));
    return out;
  }

  /// The first-order motion of every node for a motion of the prescribed coordinates (3 per
  /// node) through the last relocation; see igaparam_mesh_tangent.
  std::vector<double> tangent(const std::vector<double>& dx_prescribed) const {
    std::vector<double> out(dx_prescribed.size());
    detail::check(igaparam_mesh_tangent(handle_, dx_prescribed.size(), dx_prescribed.data(), out.data()));
    return out;
  }

  /// Current node positions, 3 per node (x0 y0 z0 x1 ...).
  std::vector<double> positions() const {
    std::vector<double> xyz(3 * node_count());
    detail::check(igaparam_mesh_copy_positions(handle_, xyz.data(), xyz.size()));
    return xyz;
  }

  /// Reference positions (the shape of the targets), 3 per node.
  std::vector<double> reference() const {
    std::vector<double> xyz(3 * node_count());
    detail::check(igaparam_mesh_copy_reference(handle_, xyz.data(), xyz.size()));
    return xyz;
  }

  /// Constraint mask of every node (bit 0 x, bit 1 y, bit 2 z fixed).
  std::vector<std::uint8_t> fixed() const {
    std::vector<std::uint8_t> mask(node_count());
    detail::check(igaparam_mesh_copy_fixed(handle_, mask.data(), mask.size()));
    return mask;
  }

  /// The connectivity, each cell's nodes in `order` (the mesh's own order by default).
  std::vector<std::int64_t> connectivity() const { return connectivity(order()); }
  std::vector<std::int64_t> connectivity(igaparam_node_order order) const {
    std::vector<std::int64_t> cells(cell_count() * nodes_per_cell(cell_type()));
    detail::check(igaparam_mesh_copy_connectivity(handle_, order, cells.data(), cells.size()));
    return cells;
  }

  /// Quality of every cell against `target` (IGAPARAM_TARGET_*): in (0, 1], 0 for an invalid cell.
  std::vector<double> cell_quality(igaparam_target target = IGAPARAM_TARGET_INITIAL) const {
    std::vector<double> quality(cell_count());
    detail::check(igaparam_mesh_copy_cell_quality(handle_, target, quality.data(), quality.size()));
    return quality;
  }

 private:
  /// Calls a getter of the form f(const igaparam_mesh*, T*) and returns its output.
  template <typename T>
  T query(igaparam_status (*getter)(const igaparam_mesh*, T*)) const {
    T value{};
    detail::check(getter(handle_, &value));
    return value;
  }

};

/// A B-spline or NURBS curve of the plane given by arrays (see igaparam_curve).
struct Curve {
  std::uint32_t degree = 3;
  std::vector<double> knots;           ///< control points + degree + 1 knots, non-decreasing
  std::vector<double> control_points;  ///< 2 per control point: x0 y0 x1 y1 ...
  std::vector<double> weights;         ///< one per control point (NURBS), or empty (B-spline)
};

/// A tensor-product B-spline or NURBS surface in 3D given by arrays (see igaparam_surface).
struct Surface {
  std::uint32_t degree_u = 2, degree_v = 2;
  std::vector<double> knots_u, knots_v;
  std::size_t count_u = 0, count_v = 0;  ///< control points in u and in v
  std::vector<double> control_points;    ///< 3 per control point, point (i, j) at i + j·count_u
  std::vector<double> weights;           ///< count_u·count_v (NURBS), or empty (B-spline)
};

namespace detail {

/// The C views of curves (pointing into them).
inline std::vector<igaparam_curve> c_curves(const std::vector<Curve>& curves) {
  std::vector<igaparam_curve> out;
  for (const Curve& c : curves) {
    require(c.control_points.size() % 2 == 0, "igaparam::Curve: 2 coordinates per control point");
    const std::size_t n = c.control_points.size() / 2;
    require(c.weights.empty() || c.weights.size() == n, "igaparam::Curve: one weight per control point");
    out.push_back({c.degree, c.knots.size(), c.knots.data(), n, c.control_points.data(),
                   c.weights.empty() ? nullptr : c.weights.data()});
  }
  return out;
}

/// The C views of surfaces (pointing into them).
inline std::vector<igaparam_surface> c_surfaces(const std::vector<Surface>& surfaces) {
  std::vector<igaparam_surface> out;
  for (const Surface& s : surfaces) {
    const std::size_t n = s.count_u * s.count_v;
    require(s.control_points.size() == 3 * n, "igaparam::Surface: 3 coordinates per control point");
    require(s.weights.empty() || s.weights.size() == n, "igaparam::Surface: one weight per control point");
    out.push_back({s.degree_u, s.degree_v, s.knots_u.size(), s.knots_u.data(), s.knots_v.size(),
                   s.knots_v.data(), s.count_u, s.count_v, s.control_points.data(),
                   s.weights.empty() ? nullptr : s.weights.data()});
  }
  return out;
}

/// The C arrays of six triangulated faces (pointing into them).
struct Triangulations {
  std::size_t nv[6], nt[6];
  const double* points[6];
  const std::uint32_t* tris[6];

  Triangulations(const std::vector<std::vector<double>>& xyz,
                 const std::vector<std::vector<std::uint32_t>>& triangles) {
    require(xyz.size() == 6 && triangles.size() == 6, "igaparam::Domain: six faces are needed");
    for (int f = 0; f < 6; f++) {
      require(xyz[f].size() % 3 == 0 && triangles[f].size() % 3 == 0,
              "igaparam::Domain: 3 coordinates per vertex and 3 indices per triangle");
      nv[f] = xyz[f].size() / 3;
      nt[f] = triangles[f].size() / 3;
      points[f] = xyz[f].data();
      tris[f] = triangles[f].data();
    }
  }
};

/// The C arrays of four polylines (pointing into them).
struct Polylines {
  std::size_t counts[4];
  const double* points[4];

  explicit Polylines(const std::vector<std::vector<double>>& polylines) {
    require(polylines.size() == 4, "igaparam::Domain: four polylines are needed");
    for (int i = 0; i < 4; i++) {
      require(polylines[i].size() % 2 == 0, "igaparam::Domain: 2 coordinates per polyline point");
      counts[i] = polylines[i].size() / 2;
      points[i] = polylines[i].data();
    }
  }
};

}  // namespace detail

/// A planar domain or a solid and its T-mesh parameterization (owner of an igaparam_domain*).
/// Move-only.
class Domain : public detail::Handle<igaparam_domain, igaparam_domain_free> {
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
    detail::Triangulations t(xyz, triangles);
    igaparam_domain* d = nullptr;
    detail::check(igaparam_domain_new_solid_from_triangulations(t.nv, t.points, t.nt, t.tris, &d));
    return Domain(d);
  }

  /// A planar domain bounded by four polylines, 2 coordinates per point (see
  /// igaparam_domain_new_from_polylines). The arrays are copied.
  static Domain planar_from_polylines(const std::vector<std::vector<double>>& polylines) {
    detail::Polylines p(polylines);
    igaparam_domain* d = nullptr;
    detail::check(igaparam_domain_new_from_polylines(p.counts, p.points, &d));
    return Domain(d);
  }

  /// A planar domain bounded by four B-spline or NURBS curves (igaparam_domain_new_from_curves:
  /// the same domain, bit for bit, as from a G+Smo file of the same curves).
  static Domain planar_from_curves(const std::vector<Curve>& curves) {
    const std::vector<igaparam_curve> c = detail::c_curves(curves);
    igaparam_domain* d = nullptr;
    detail::check(igaparam_domain_new_from_curves(c.size(), c.data(), &d));
    return Domain(d);
  }

  /// A solid bounded by six tensor-product B-spline or NURBS surfaces
  /// (igaparam_domain_new_solid_from_surfaces).
  static Domain solid_from_surfaces(const std::vector<Surface>& surfaces) {
    const std::vector<igaparam_surface> c = detail::c_surfaces(surfaces);
    igaparam_domain* d = nullptr;
    detail::check(igaparam_domain_new_solid_from_surfaces(c.size(), c.data(), &d));
    return Domain(d);
  }

  /// Takes ownership of a handle from igaparam_domain_new_* (may be NULL).
  explicit Domain(igaparam_domain* handle) noexcept : Handle(handle) {}

  /// 2 for a planar domain, 3 for a solid.
  std::size_t dimension() const {
    std::size_t d = 0;
    detail::check(igaparam_domain_dimension(handle_, &d));
    return d;
  }

  /// Adapts, places and optimizes the T-mesh with the defaults of its dimension
  /// (igaparam_domain_options_default, or igaparam_domain_options_default_solid for a solid).
  igaparam_domain_report build() {
    igaparam_domain_report report{};
    detail::check(igaparam_domain_build(handle_, nullptr, &report));
    return report;
  }

  /// Adapts, places and optimizes the T-mesh with the given options (start from
  /// default_options()).
  igaparam_domain_report build(const igaparam_domain_options& options) {
    igaparam_domain_report report{};
    detail::check(igaparam_domain_build(handle_, &options, &report));
    return report;
  }

  /// Replaces the boundary by four curves given in the order and direction of the first ones
  /// (igaparam_domain_set_boundary_curves); the T-mesh moves onto it with update().
  void set_boundary(const std::vector<Curve>& curves) {
    const std::vector<igaparam_curve> c = detail::c_curves(curves);
    detail::check(igaparam_domain_set_boundary_curves(handle_, c.size(), c.data()));
  }

  /// Replaces the boundary of a solid by six surfaces (igaparam_domain_set_boundary_surfaces).
  void set_boundary(const std::vector<Surface>& surfaces) {
    const std::vector<igaparam_surface> c = detail::c_surfaces(surfaces);
    detail::check(igaparam_domain_set_boundary_surfaces(handle_, c.size(), c.data()));
  }

  /// Replaces the boundary of a planar domain by four polylines.
  void set_boundary_polylines(const std::vector<std::vector<double>>& polylines) {
    detail::Polylines p(polylines);
    detail::check(igaparam_domain_set_boundary_polylines(handle_, p.counts, p.points));
  }

  /// Replaces the boundary of a solid by six triangulated faces.
  void set_boundary_triangulations(const std::vector<std::vector<double>>& xyz,
                                   const std::vector<std::vector<std::uint32_t>>& triangles) {
    detail::Triangulations t(xyz, triangles);
    detail::check(igaparam_domain_set_boundary_triangulations(handle_, t.nv, t.points, t.nt, t.tris));
  }

  /// Replaces the boundary by the one of a file (a planar domain's or a solid's, as the
  /// constructors read them).
  void set_boundary_from_file(const std::string& path) {
    detail::check(igaparam_domain_set_boundary_from_file(handle_, path.c_str()));
  }

  /// Replaces the boundary of a solid by the one of a file, scaled axis by axis first.
  void set_boundary_from_file(const std::string& path, const std::array<double, 3>& scale) {
    detail::check(igaparam_domain_set_boundary_from_file_scaled(handle_, path.c_str(), scale.data()));
  }

  /// Moves the built T-mesh onto the current boundary, keeping its tree
  /// (igaparam_domain_update); then Spline::refit gives the spline map in the same space.
  igaparam_domain_update_report update(
      const igaparam_domain_update_options& options = igaparam_domain_update_options_default()) {
    igaparam_domain_update_report report{};
    detail::check(igaparam_domain_update(handle_, &options, &report));
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
    detail::check(igaparam_domain_copy_cell_quality(handle_, q.data(), q.size()));
    return q;
  }

  /// Level of every cell.
  std::vector<std::uint8_t> cell_levels() const {
    std::vector<std::uint8_t> levels(cell_count());
    detail::check(igaparam_domain_copy_cells(handle_, levels.data(), nullptr, levels.size()));
    return levels;
  }

  /// Corner vertices of every cell, 2^dimension() per cell (VTK quad / hexahedron order).
  std::vector<std::size_t> cell_corners() const {
    std::vector<std::size_t> corners(cell_count() << dimension());
    detail::check(igaparam_domain_copy_cell_corners(handle_, corners.data(), corners.size()));
    return corners;
  }

  /// Writes the T-mesh as a .vtu file.
  void write_vtu(const std::string& path) const {
    detail::check(igaparam_domain_write_vtu(handle_, path.c_str()));
  }

  /// Number of vertices of the built T-mesh, hanging ones included.
  /// Control points of the boundary's curves or surfaces together (igaparam_domain_control_count;
  /// throws for polylines and triangulated faces).
  std::size_t control_count() const {
    std::size_t n = 0;
    detail::check(igaparam_domain_control_count(handle_, &n));
    return n;
  }

  std::size_t vertex_count() const {
    std::size_t n = 0;
    detail::check(igaparam_domain_vertex_count(handle_, &n));
    return n;
  }

  /// Number of cells of the built T-mesh.
  std::size_t cell_count() const {
    std::size_t n = 0;
    detail::check(igaparam_domain_cell_count(handle_, &n));
    return n;
  }

 private:
  std::vector<double> vertices(bool parametric) const {
    std::vector<double> out(vertex_count() * dimension());
    detail::check(igaparam_domain_copy_vertices(handle_, parametric ? out.data() : nullptr,
                                                parametric ? nullptr : out.data(), out.size()));
    return out;
  }

};

}  // namespace igaparam

// igaparam::Spline, the spline map of a domain.
#include "igaparam_spline.hpp"  // IWYU pragma: export

#endif  // IGAPARAM_HPP
