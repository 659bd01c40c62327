// system.h: Galerkin assembly of scalar second-order problems on an analysis space, and their
// solution with Dirichlet values on chosen faces of the parametric domain.

#ifndef IGAPARAM_IGA_SYSTEM_H
#define IGAPARAM_IGA_SYSTEM_H

#include "space.h"

namespace iga {

/// The terms of a(u, v) = ∫ ∇u·∇v − ∫ κ² u v and of the load ℓ(v) = ∫ f v + ∫ g·∇v, each
/// optional (empty: absent); `projected` asks for the mass matrix and ∫ p v, the L2 projection
/// of p (the Dirichlet values of a problem with an exact solution).
struct Integrands {
  std::function<double(const double *)> reaction;          // κ²(x)
  std::function<double(const double *)> source;            // f(x)
  std::function<void(const double *, double *)> flux;      // g(x), d values
  std::function<double(const double *)> projected;         // p(x)
};

/// The assembled matrices and vectors (mass and projection_rhs only with `projected`).
struct System {
  SparseMatrix a, mass;
  VectorXd load, projection_rhs;
};

/// Assembles the system by the quadrature `ref` per element. The triplets of each thread's block
/// of elements are concatenated in element order, so the sums do not depend on the thread count.
System assemble(const Space &sp, const Integrands &terms, const Reference &ref, int threads);

/// Solves a symmetric system: LU when indefinite; sparse LDLᵀ up to 2,000 unknowns, or 20,000
/// with at most 100 entries a row (2D), else conjugate gradients with a diagonal
/// preconditioner to a relative residual of 1e-13.
VectorXd solve(const SparseMatrix &a, const VectorXd &b, bool definite);

/// The coefficients of the discrete solution: the functions whose Greville point lies on one of
/// `dirichlet_faces` (bits face_bit) take their entry of `boundary_values` (nb values), the
/// others solve the Galerkin system.
VectorXd solve_dirichlet(const Space &sp, const System &sys, uint8_t dirichlet_faces, const VectorXd &boundary_values,
                         bool definite);

}  // namespace iga

#endif  // IGAPARAM_IGA_SYSTEM_H
