// system.cpp: Galerkin assembly and solution.

#include "system.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include <algorithm>
#include <stdexcept>

namespace iga {

namespace {

// The element matrices and vectors of one element.
struct ElementSystem {
  MatrixXd a, mass;
  VectorXd load, projection;
};

void element_system(const Space &sp, const Element &el, const Integrands &terms, const Reference &ref,
                    ElementValues &ev, ElementSystem &out) {
  element_values(sp, el, ref, ev);
  const int d = sp.d;
  const Eigen::Index m = static_cast<Eigen::Index>(el.functions.size());
  VectorXd fw = VectorXd::Zero(ref.nq), pw = VectorXd::Zero(ref.nq), kw = VectorXd::Zero(ref.nq);
  VectorXd gradient_weights(ref.nq * d);
  out.load = VectorXd::Zero(m);
  double g[3];
  for (int q = 0; q < ref.nq; q++) {
    const double *x = ev.points.col(q).data();
    gradient_weights.segment(q * d, d).setConstant(ev.dx(q));
    if (terms.source) fw(q) = ev.dx(q) * terms.source(x);
    if (terms.projected) pw(q) = ev.dx(q) * terms.projected(x);
    if (terms.reaction) kw(q) = ev.dx(q) * terms.reaction(x);
    if (terms.flux) {
      terms.flux(x, g);
      out.load += ev.dx(q) * (ev.gradient(q, d) * Eigen::Map<const VectorXd>(g, d));
    }
  }
  out.a.noalias() = (ev.gradients * gradient_weights.asDiagonal()) * ev.gradients.transpose();
  if (terms.reaction) out.a.noalias() -= (ev.values * kw.asDiagonal()) * ev.values.transpose();
  if (terms.source) out.load += ev.values * fw;
  if (terms.projected) {
    out.mass.noalias() = (ev.values * ev.dx.asDiagonal()) * ev.values.transpose();
    out.projection = ev.values * pw;
  }
}

void add_triplets(const Element &el, const MatrixXd &local, std::vector<Triplet> &out) {
  for (size_t j = 0; j < el.functions.size(); j++)
    for (size_t i = 0; i < el.functions.size(); i++) out.emplace_back(el.functions[i], el.functions[j], local(i, j));
}

// Elements per chunk of the assembly: each chunk's element matrices are summed into one sparse
// matrix from its triplets (in element order), and the chunks' matrices pairwise, in a fixed
// tree: the sums do not depend on the thread count, and the triplets of only one chunk per
// thread are held at a time.
constexpr size_t kChunk = 64;

// Sums the matrices pairwise ((0 + 1) + (2 + 3)) + ..., in parallel.
SparseMatrix tree_sum(std::vector<SparseMatrix> pieces, int threads) {
  if (pieces.empty()) return SparseMatrix();
  while (pieces.size() > 1) {
    std::vector<SparseMatrix> next((pieces.size() + 1) / 2);
    for_elements(next.size(), threads, [&](size_t begin, size_t end, int) {
      for (size_t i = begin; i < end; i++)
        next[i] = 2 * i + 1 < pieces.size() ? SparseMatrix(pieces[2 * i] + pieces[2 * i + 1]) : pieces[2 * i];
    });
    pieces = std::move(next);
  }
  return pieces[0];
}

}  // namespace

System assemble(const Space &sp, const Integrands &terms, const Reference &ref, int threads) {
  const size_t ne = sp.elements.size(), chunks = (ne + kChunk - 1) / kChunk;
  std::vector<SparseMatrix> pieces_a(chunks), pieces_m(terms.projected ? chunks : 0);
  std::vector<VectorXd> load_e(ne), proj_e(ne);
  for_elements(chunks, threads, [&](size_t begin, size_t end, int) {
    ElementValues ev;
    ElementSystem es;
    std::vector<Triplet> ta, tm;
    for (size_t c = begin; c < end; c++) {
      ta.clear();
      tm.clear();
      for (size_t e = c * kChunk; e < std::min(ne, (c + 1) * kChunk); e++) {
        const Element &el = sp.elements[e];
        element_system(sp, el, terms, ref, ev, es);
        load_e[e] = es.load;
        add_triplets(el, es.a, ta);
        if (terms.projected) {
          proj_e[e] = es.projection;
          add_triplets(el, es.mass, tm);
        }
      }
      pieces_a[c].resize(sp.nb, sp.nb);
      pieces_a[c].setFromTriplets(ta.begin(), ta.end());
      if (terms.projected) {
        pieces_m[c].resize(sp.nb, sp.nb);
        pieces_m[c].setFromTriplets(tm.begin(), tm.end());
      }
    }
  });
  System sys;
  sys.a = tree_sum(std::move(pieces_a), threads);
  if (terms.projected) sys.mass = tree_sum(std::move(pieces_m), threads);
  sys.load = VectorXd::Zero(sp.nb);
  sys.projection_rhs = VectorXd::Zero(sp.nb);
  for (size_t e = 0; e < ne; e++)
    for (size_t i = 0; i < sp.elements[e].functions.size(); i++) {
      sys.load(sp.elements[e].functions[i]) += load_e[e](i);
      if (terms.projected) sys.projection_rhs(sp.elements[e].functions[i]) += proj_e[e](i);
    }
  return sys;
}

VectorXd solve(const SparseMatrix &a, const VectorXd &b, bool definite) {
  if (!definite) {
    Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
    lu.compute(a);
    if (lu.info() != Eigen::Success) throw std::runtime_error("sparse LU failed");
    return lu.solve(b);
  }
  // The fill of a sparse Cholesky factor stays moderate for the 2D systems (49 entries a row
  // for cubic splines) but grows fast for the 3D ones (343 a row): those above a few thousand
  // unknowns go to conjugate gradients.
  const double per_row = double(a.nonZeros()) / double(std::max<Eigen::Index>(1, a.rows()));
  if (a.rows() <= 2000 || (a.rows() <= 20000 && per_row <= 100)) {
    Eigen::SimplicialLDLT<SparseMatrix> ldlt(a);
    if (ldlt.info() != Eigen::Success) throw std::runtime_error("sparse LDLT failed");
    return ldlt.solve(b);
  }
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(1e-13);
  cg.setMaxIterations(20 * static_cast<int>(a.rows()));
  cg.compute(a);
  VectorXd x = cg.solve(b);
  if (cg.info() != Eigen::Success) throw std::runtime_error("conjugate gradients did not converge");
  return x;
}

VectorXd solve_dirichlet(const Space &sp, const System &sys, uint8_t dirichlet_faces, const VectorXd &boundary_values,
                         bool definite) {
  std::vector<Eigen::Index> interior_index(sp.nb, -1);
  Eigen::Index ni = 0;
  VectorXd c = VectorXd::Zero(sp.nb);
  for (size_t i = 0; i < sp.nb; i++) {
    if (sp.faces[i] & dirichlet_faces)
      c(i) = boundary_values(i);
    else
      interior_index[i] = ni++;
  }
  const VectorXd lifted = sys.a * c;  // A applied to the Dirichlet part
  VectorXd rhs = VectorXd::Zero(ni);
  for (size_t i = 0; i < sp.nb; i++)
    if (interior_index[i] >= 0) rhs(interior_index[i]) = sys.load(i) - lifted(i);
  std::vector<Triplet> t;
  for (int k = 0; k < sys.a.outerSize(); k++)
    for (SparseMatrix::InnerIterator it(sys.a, k); it; ++it) {
      const Eigen::Index r = interior_index[it.row()], col = interior_index[it.col()];
      if (r >= 0 && col >= 0) t.emplace_back(r, col, it.value());
    }
  if (ni > 0) {
    SparseMatrix ai(ni, ni);
    ai.setFromTriplets(t.begin(), t.end());
    const VectorXd xi = solve(ai, rhs, definite);
    for (size_t i = 0; i < sp.nb; i++)
      if (interior_index[i] >= 0) c(i) = xi(interior_index[i]);
  }
  return c;
}

}  // namespace iga
