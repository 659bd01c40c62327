// estimate.h: errors of a discrete solution against an exact one, the residual-based error
// indicator of adaptive refinement, and convergence rates.

#ifndef IGAPARAM_IGA_ESTIMATE_H
#define IGAPARAM_IGA_ESTIMATE_H

#include "problems.h"
#include "space.h"

namespace iga {

/// Per element: the squared L2 and H1-seminorm errors of u_h and, when asked, the squared
/// residual indicator η_e² = h_e² ‖f + Δu_h + κ² u_h‖²_{L2(Ω_e)}, h_e = |Ω_e|^{1/d}. The THB
/// basis is C² across every element face, so the residual has no jump terms.
struct ElementNorms {
  std::vector<double> l2, h1, eta;

  /// √Σ over the elements, summed in element order.
  static double total(const std::vector<double> &squares);
};

/// The norms of the solution with coefficients `c` by the quadrature `ref` (which must hold
/// second derivatives when `with_estimator`).
ElementNorms element_norms(const Space &sp, const Problem &p, const VectorXd &c, const Reference &ref, int threads,
                           bool with_estimator);

/// The deepest level of the library's hierarchical meshes: igaparam_spline_refine leaves
/// elements of this level as they are.
constexpr int kDeepestLevel = 20;

/// The elements whose indicator exceeds γ times the largest one (η_e > γ max η), among the
/// elements that can still be refined (below kDeepestLevel).
std::vector<size_t> mark(const Space &sp, const std::vector<double> &eta_squared, double gamma);

/// The marked elements and their neighbourhood: every element of at most the marked one's
/// level that meets its box grown by `layers` of its own side in each direction (clipped to
/// [0,1]^d). Refining a single element of a THB space adds no function (a cubic function of the
/// next level needs 4^d refined elements of its level in its support, 2^d of the marked one's
/// level); one layer makes the refined region hold new functions around every marked element.
std::vector<size_t> extend(const Space &sp, const std::vector<size_t> &marked, int layers);

/// The convergence rate in dofs: minus the least-squares slope of log error against log dofs
/// over the last points, those with at least dofs.back() / span dofs (NaN with fewer than two).
double fitted_rate(const std::vector<double> &dofs, const std::vector<double> &error, double span);

/// The rate log(e_{n-2}/e_{n-1}) / log(h_{n-2}/h_{n-1}) of the last two entries (0 with fewer).
double last_rate(const std::vector<double> &h, const std::vector<double> &error);

/// The number of dofs at which the series (dofs, error), in log-log interpolation, first
/// reaches `target` (NaN if it does not).
double dofs_to_reach(const std::vector<double> &dofs, const std::vector<double> &error, double target);

}  // namespace iga

#endif  // IGAPARAM_IGA_ESTIMATE_H
