// space.h: the isogeometric analysis space of a spline map, read through the public C API of
// igaparam (Bézier extraction, control points, Greville points, element boxes), and the values
// of its basis functions at reference points of an element: physical points, Jacobians,
// gradients and, on demand, Laplacians. Shared by igaparam_poisson and igaparam_wind.

#ifndef IGAPARAM_IGA_SPACE_H
#define IGAPARAM_IGA_SPACE_H

#include <igaparam.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace iga {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;

constexpr double kPi = 3.14159265358979323846;

/// The calling thread's last error message of the library.
std::string last_error();

/// Throws a std::runtime_error "what: <message>" unless `status` is IGAPARAM_STATUS_OK.
void check(igaparam_status status, const char *what);

struct SplineDeleter {
  void operator()(igaparam_spline *s) const { igaparam_spline_free(s); }
};
struct DomainDeleter {
  void operator()(igaparam_domain *d) const { igaparam_domain_free(d); }
};
using SplinePtr = std::unique_ptr<igaparam_spline, SplineDeleter>;
using DomainPtr = std::unique_ptr<igaparam_domain, DomainDeleter>;

/// A new, independent copy of a spline (igaparam_spline_clone).
SplinePtr clone(const igaparam_spline *spline);

/// Reference points in [0,1]^d with weights: the tensor product of per-axis points, and the
/// cubic Bernstein polynomials there as per-axis factors (value, first and second derivative,
/// 4 × n_k each). The element values are computed in blocks of nq columns: the values, the
/// first derivatives along each direction and, when asked, the second derivatives ∂²/∂u_j∂u_l
/// for j ≤ l (in the order of second_index); block b takes the derivative of order
/// orders[b][k] along axis k.
struct Reference {
  int d = 0, nq = 0, blocks = 0;
  MatrixXd points;  // d × nq, point q = q0 + n0 (q1 + n1 q2)
  VectorXd weights;
  std::vector<std::array<MatrixXd, 3>> factors;  // per axis, per derivative order
  std::vector<std::array<int, 3>> orders;       // per block

  /// The tensor points of per-axis coordinates and weights (d lists each).
  Reference(const std::vector<std::vector<double>> &x, const std::vector<std::vector<double>> &w,
            bool with_second);

  bool has_second() const { return blocks > 1 + d; }
  /// The block of ∂²/∂u_j∂u_l (j, l in any order).
  int second_index(int j, int l) const;
  /// The values of block b of the functions C·B (C: m × 4^d, one row per function in Bernstein
  /// coefficients) at the points, into out (m × nq), by sum factorization: one axis at a time.
  void apply(const MatrixXd &c, int b, MatrixXd &work, Eigen::Ref<MatrixXd> out) const;

  /// The tensor Gauss–Legendre rule with n points per direction.
  static Reference gauss(int d, int n, bool with_second = false);
  /// The Gauss rule with n points per direction on the face `axis` = side (0 or 1) of [0,1]^d;
  /// the weights are those of the (d-1)-dimensional face.
  static Reference face(int d, int n, int axis, int side);
  /// The (n+1)^d points of the uniform grid (weights 1), for sampling.
  static Reference grid(int d, int n);
};

/// Gauss–Legendre points and weights of n points on [0, 1].
void gauss_legendre(int n, std::vector<double> &x, std::vector<double> &w);

/// One element: the functions non-zero on it, its extraction operator and its parametric box
/// (lower corner then upper corner, d values each).
struct Element {
  std::vector<size_t> functions;
  MatrixXd extraction;  // m × 4^d
  std::array<double, 6> box{};
  int level = 0;
};

/// Bit of a function's face mask: its Greville point lies on the face u_axis = side.
constexpr uint8_t face_bit(int axis, int side) { return uint8_t(1u << (2 * axis + side)); }
constexpr uint8_t kAllFaces = 0x3f;

/// The analysis space of a spline map (its own basis): control points, elements, and per
/// function the faces of [0,1]^d its Greville point lies on (the functions that do not vanish
/// there: the degrees of freedom of a Dirichlet condition on that face).
struct Space {
  int d = 0;
  size_t nb = 0;
  MatrixXd control;  // nb × d
  std::vector<Element> elements;
  std::vector<uint8_t> faces;  // per function, bits face_bit(axis, side)
  double h = 0.0;              // largest parametric element side
  double orientation = 1.0;    // sign of det J (a map may reverse the orientation)

  Space() = default;
  explicit Space(const igaparam_spline *s);
};

/// The basis functions of one element at reference points: values (m × nq), physical points
/// (d × nq), Jacobians dx/du (d × d per point, point q in columns q·d ... q·d + d − 1),
/// physical gradients (m × d per point, likewise), |det J| × weight × parametric volume (the
/// measure of each point) and, when asked, physical Laplacians (m × nq).
struct ElementValues {
  MatrixXd values, points, jacobians, gradients, laplacians;
  VectorXd dx;
  MatrixXd all, work;  // the blocks of Reference::apply side by side, and its workspace

  auto gradient(int q, int d) const { return gradients.middleCols(q * d, d); }
  auto jacobian(int q, int d) const { return jacobians.middleCols(q * d, d); }
};

/// Fills `out` for element `el` at the points of `ref` (which must hold second derivatives
/// when `with_laplacians`). Throws when det J is not positive at a point.
void element_values(const Space &sp, const Element &el, const Reference &ref, ElementValues &out,
                    bool with_laplacians = false);

/// Runs block(begin, end, thread) on contiguous blocks of [0, n), one per thread; an exception
/// thrown in a block is rethrown here.
void for_elements(size_t n, int threads, const std::function<void(size_t, size_t, int)> &block);

/// The bounding box of the map's control points (which holds the domain): lower corner then
/// upper corner, d values each.
std::vector<double> control_box(const igaparam_spline *spline);

/// The coefficient vector of one element's functions.
VectorXd local_coefficients(const Element &el, const VectorXd &c);

}  // namespace iga

#endif  // IGAPARAM_IGA_SPACE_H
