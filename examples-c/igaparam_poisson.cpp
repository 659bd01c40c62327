// igaparam_poisson: isogeometric Galerkin solver of the Poisson and Helmholtz equations on the
// cubic THB-spline maps of the library, with a uniform refinement series and its convergence
// rates.
//
//   igaparam_poisson [INPUT] [--problem poisson|helmholtz|linear] [--levels N] [--threads N]
//                    [--dim 2|3] [--quad N] [--tolerance T] [--max-level L] [--refits N]
//                    [--vtu PATH] [--check-rates L2MIN H1MIN] [--check-max-error E] [--check-source]
//                    [--check-certified]
//
// INPUT is a G+Smo XML B-rep (four curves or six surfaces), a coastline .txt or a folder of six
// triangulated faces (the domain is built and its spline map fitted; --tolerance sets the
// domain's boundary tolerance and --max-level its deepest level; while the map is not certified valid, the domain is rebuilt
// with a tolerance ten times smaller, at most --refits times, default 3), or a THB spline .xml
// written by igaparam_spline_write_gismo (read, 2D or 3D).
// Without INPUT: a quarter annulus (radii 1 and 2) built from four polylines (--dim 2, the
// default) or a thick quarter annulus given as one cubic element (--dim 3), written as G+Smo
// THB XML to a temporary file and read back.
//
// The analysis space is the map's own spline space, refined uniformly --levels times (the map
// does not change). On each level: stiffness (and mass) matrices and load by Gauss quadrature
// per element through the Bézier extraction, Dirichlet values from the L2 projection of the
// exact solution (kept on the functions with a Greville point on the boundary), solution of the
// interior system, and L2 / H1-seminorm errors by a finer quadrature. Prints a table and, as
// its last line, a JSON object with the series and the rates between the last two levels.
// --check-rates exits with status 3 when a rate is below its bound, --check-max-error when an
// L2 or H1 error exceeds E (--problem linear, u = 1 + x - 2y (+ 3z), is reproduced exactly by
// the isoparametric space: a test of the assembly and of the boundary treatment); --check-source compares
// the right-hand sides with finite differences of the exact solutions and exits;
// --check-certified exits with status 3 unless det J > 0 is proven on every element of the map.
// For an input domain the 3D Poisson solution's layer is placed by the domain's bounding box
// (see make_problem).

#include <igaparam.h>

#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// C API helpers

std::string last_error() {
  char message[1024] = {0};
  igaparam_last_error_message(message, sizeof message);
  return message;
}

void check(igaparam_status status, const char *what) {
  if (status == IGAPARAM_STATUS_OK) return;
  throw std::runtime_error(std::string(what) + ": " + last_error());
}

struct SplineDeleter {
  void operator()(igaparam_spline *s) const { igaparam_spline_free(s); }
};
struct DomainDeleter {
  void operator()(igaparam_domain *d) const { igaparam_domain_free(d); }
};
using SplinePtr = std::unique_ptr<igaparam_spline, SplineDeleter>;
using DomainPtr = std::unique_ptr<igaparam_domain, DomainDeleter>;

// ---------------------------------------------------------------------------------------------
// Exact solutions: value, gradient and right-hand side f of -Δu - κ(x)² u = f.

struct Problem {
  std::string name;
  std::function<double(const double *)> u;
  std::function<void(const double *, double *)> grad;  // d values
  std::function<double(const double *)> f;
  std::function<double(const double *)> kappa2;  // nullptr for Poisson
};

// u = 1 + x - 2y (+ 3z): in every isoparametric space (Σ N_i = 1, Σ P_i N_i = x), so the
// discrete solution is exact up to round-off.
Problem linear(int d) {
  Problem p;
  p.name = "linear";
  const double a[3] = {1.0, -2.0, 3.0};
  p.u = [=](const double *x) {
    double v = 1.0;
    for (int k = 0; k < d; k++) v += a[k] * x[k];
    return v;
  };
  p.grad = [=](const double *, double *g) {
    for (int k = 0; k < d; k++) g[k] = a[k];
  };
  p.f = [](const double *) { return 0.0; };
  return p;
}

// u = sin(πx) sin(πy) exp(x/2) in 2D.
Problem poisson_2d() {
  Problem p;
  p.name = "poisson";
  p.u = [](const double *x) {
    return std::sin(kPi * x[0]) * std::sin(kPi * x[1]) * std::exp(0.5 * x[0]);
  };
  p.grad = [](const double *x, double *g) {
    double e = std::exp(0.5 * x[0]), sx = std::sin(kPi * x[0]), cx = std::cos(kPi * x[0]);
    double sy = std::sin(kPi * x[1]), cy = std::cos(kPi * x[1]);
    g[0] = (kPi * cx + 0.5 * sx) * sy * e;
    g[1] = kPi * sx * cy * e;
  };
  p.f = [](const double *x) {
    double e = std::exp(0.5 * x[0]), sx = std::sin(kPi * x[0]), cx = std::cos(kPi * x[0]);
    double sy = std::sin(kPi * x[1]);
    return -((0.25 - 2.0 * kPi * kPi) * sx + kPi * cx) * sy * e;
  };
  return p;
}

double distance(const double *x, const double *c, int d, double *unit) {
  double r2 = 0.0;
  for (int k = 0; k < d; k++) r2 += (x[k] - c[k]) * (x[k] - c[k]);
  double r = std::sqrt(r2);
  for (int k = 0; k < d; k++) unit[k] = (x[k] - c[k]) / r;
  return r;
}

// A radial solution u(r), r = |x - c|: -Δu = -(u'' + (d-1) u'/r).
struct Radial {
  std::array<double, 3> centre;
  int d;
  std::function<double(double)> u, du, d2u;
};

Problem radial_problem(const std::string &name, const Radial &rad) {
  Problem p;
  p.name = name;
  p.u = [rad](const double *x) {
    double n[3];
    return rad.u(distance(x, rad.centre.data(), rad.d, n));
  };
  p.grad = [rad](const double *x, double *g) {
    double n[3];
    double r = distance(x, rad.centre.data(), rad.d, n);
    double du = rad.du(r);
    for (int k = 0; k < rad.d; k++) g[k] = du * n[k];
  };
  p.f = [rad](const double *x) {
    double n[3];
    double r = distance(x, rad.centre.data(), rad.d, n);
    return -(rad.d2u(r) + (rad.d - 1) * rad.du(r) / r);
  };
  return p;
}

// u = arctan(α(r - r0)).
Problem arctan_layer(int d, std::array<double, 3> centre, double alpha, double r0) {
  Radial rad{centre, d, nullptr, nullptr, nullptr};
  rad.u = [=](double r) { return std::atan(alpha * (r - r0)); };
  rad.du = [=](double r) {
    double t = alpha * (r - r0);
    return alpha / (1.0 + t * t);
  };
  rad.d2u = [=](double r) {
    double t = alpha * (r - r0);
    return -2.0 * alpha * alpha * t / ((1.0 + t * t) * (1.0 + t * t));
  };
  return radial_problem("poisson", rad);
}

// -Δu - κ² u = f with u = sin(1/(α + r)), κ = 1/(α + r)², α = 1/(4π): with s = α + r,
// Δu = -sin(1/s)/s⁴ + cos(1/s) (2/s³ - (d-1)/(r s²)), so f = cos(1/s) ((d-1)/(r s²) - 2/s³).
Problem helmholtz(int d, std::array<double, 3> centre) {
  const double alpha = 1.0 / (4.0 * kPi);
  Problem p;
  p.name = "helmholtz";
  p.u = [=](const double *x) {
    double n[3];
    return std::sin(1.0 / (alpha + distance(x, centre.data(), d, n)));
  };
  p.grad = [=](const double *x, double *g) {
    double n[3];
    double s = alpha + distance(x, centre.data(), d, n);
    double du = -std::cos(1.0 / s) / (s * s);
    for (int k = 0; k < d; k++) g[k] = du * n[k];
  };
  p.f = [=](const double *x) {
    double n[3];
    double r = distance(x, centre.data(), d, n);
    double s = alpha + r;
    return std::cos(1.0 / s) * ((d - 1) / (r * s * s) - 2.0 / (s * s * s));
  };
  p.kappa2 = [=](const double *x) {
    double n[3];
    double s = alpha + distance(x, centre.data(), d, n);
    return 1.0 / (s * s * s * s);
  };
  return p;
}

// Largest relative difference between f and -Δu - κ² u by central differences (step h) at
// the given points.
double source_residual(const Problem &p, int d, const std::vector<double> &points) {
  const double h = 1e-4;
  double worst = 0.0;
  for (size_t i = 0; i + d <= points.size(); i += d) {
    double x[3], y[3];
    std::copy(points.begin() + i, points.begin() + i + d, x);
    double u0 = p.u(x), lap = 0.0;
    for (int k = 0; k < d; k++) {
      std::copy(x, x + d, y);
      y[k] = x[k] + h;
      double up = p.u(y);
      y[k] = x[k] - h;
      double um = p.u(y);
      lap += (up - 2.0 * u0 + um) / (h * h);
    }
    double fd = -lap - (p.kappa2 ? p.kappa2(x) * u0 : 0.0);
    double f = p.f(x);
    worst = std::max(worst, std::abs(fd - f) / std::max(1.0, std::abs(f)));
  }
  return worst;
}

// ---------------------------------------------------------------------------------------------
// Quadrature and Bernstein polynomials

// Gauss–Legendre rule with n points on [0, 1].
void gauss_legendre(int n, std::vector<double> &x, std::vector<double> &w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; i++) {
    double t = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; it++) {
      double p0 = 1.0, p1 = t;
      for (int k = 2; k <= n; k++) {
        double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (t * p1 - p0) / (t * t - 1.0);
      double dt = p1 / dp;
      t -= dt;
      if (std::abs(dt) < 1e-16) break;
    }
    x[i] = 0.5 * (1.0 - t);
    w[i] = 1.0 / ((1.0 - t * t) * dp * dp);
  }
}

void bernstein3(double t, double b[4], double db[4]) {
  double s = 1.0 - t;
  b[0] = s * s * s;
  b[1] = 3.0 * t * s * s;
  b[2] = 3.0 * t * t * s;
  b[3] = t * t * t;
  db[0] = -3.0 * s * s;
  db[1] = 3.0 * s * s - 6.0 * t * s;
  db[2] = 6.0 * t * s - 3.0 * t * t;
  db[3] = 3.0 * t * t;
}

// Tensor Gauss rule with n^d points on [0,1]^d and the tensor Bernstein polynomials there:
// values (4^d × n^d) and derivatives along each direction.
struct Reference {
  int d = 0, nq = 0;
  MatrixXd points;  // d × nq, in [0,1]^d
  VectorXd weights;
  MatrixXd values;
  std::vector<MatrixXd> derivatives;

  Reference(int dim, int n) : d(dim) {
    std::vector<double> x, w;
    gauss_legendre(n, x, w);
    nq = 1;
    for (int k = 0; k < d; k++) nq *= n;
    int nb = 1 << (2 * d);
    points.resize(d, nq);
    weights.resize(nq);
    values.resize(nb, nq);
    derivatives.assign(d, MatrixXd(nb, nq));
    for (int q = 0; q < nq; q++) {
      int idx[3], rest = q;
      double wq = 1.0, b[3][4], db[3][4];
      for (int k = 0; k < d; k++) {
        idx[k] = rest % n;
        rest /= n;
        points(k, q) = x[idx[k]];
        wq *= w[idx[k]];
        bernstein3(x[idx[k]], b[k], db[k]);
      }
      weights(q) = wq;
      for (int kb = 0; kb < nb; kb++) {
        int a[3] = {kb & 3, (kb >> 2) & 3, (kb >> 4) & 3};
        double v = 1.0;
        for (int k = 0; k < d; k++) v *= b[k][a[k]];
        values(kb, q) = v;
        for (int j = 0; j < d; j++) {
          double g = 1.0;
          for (int k = 0; k < d; k++) g *= (k == j ? db[k][a[k]] : b[k][a[k]]);
          derivatives[j](kb, q) = g;
        }
      }
    }
  }
};

// ---------------------------------------------------------------------------------------------
// The discrete space of one level

struct Element {
  std::vector<size_t> functions;
  MatrixXd extraction;  // m × 4^d
  std::array<double, 6> box;
};

struct Space {
  int d = 0;
  size_t nb = 0;
  MatrixXd control;  // nb × d
  std::vector<Element> elements;
  std::vector<char> boundary;  // per function
  double h = 0.0;              // largest parametric element side
  double orientation = 1.0;    // sign of det J (a map may reverse the orientation)

  explicit Space(const igaparam_spline *s) {
    size_t dim = 0, ne = 0;
    check(igaparam_spline_dimension(s, &dim), "dimension");
    check(igaparam_spline_basis_count(s, &nb), "basis count");
    check(igaparam_spline_element_count(s, &ne), "element count");
    d = static_cast<int>(dim);
    std::vector<double> buffer(nb * d);
    check(igaparam_spline_copy_control_points(s, buffer.data(), buffer.size()), "control points");
    control.resize(nb, d);
    for (size_t i = 0; i < nb; i++)
      for (int k = 0; k < d; k++) control(i, k) = buffer[i * d + k];
    check(igaparam_spline_copy_greville_points(s, buffer.data(), buffer.size()), "Greville points");
    boundary.assign(nb, 0);
    for (size_t i = 0; i < nb; i++)
      for (int k = 0; k < d; k++) {
        double g = buffer[i * d + k];
        if (g <= 1e-12 || g >= 1.0 - 1e-12) boundary[i] = 1;
      }
    std::vector<double> bounds(ne * 2 * d);
    check(igaparam_spline_copy_elements(s, nullptr, bounds.data(), ne), "elements");
    const size_t nbern = size_t(1) << (2 * d);
    elements.resize(ne);
    for (size_t e = 0; e < ne; e++) {
      size_t m = 0;
      check(igaparam_spline_element_function_count(s, e, &m), "element function count");
      Element &el = elements[e];
      el.functions.resize(m);
      std::vector<double> op(m * nbern);
      check(igaparam_spline_copy_element_extraction(s, e, el.functions.data(), m, op.data(), op.size()),
            "extraction");
      el.extraction = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          op.data(), m, nbern);
      for (int k = 0; k < 2 * d; k++) el.box[k] = bounds[e * 2 * d + k];
      for (int k = 0; k < d; k++) h = std::max(h, el.box[d + k] - el.box[k]);
    }
    double centre[3], jac[9];
    for (int k = 0; k < d; k++) centre[k] = 0.5 * (elements[0].box[k] + elements[0].box[d + k]);
    check(igaparam_spline_evaluate(s, 1, centre, nullptr, jac), "evaluate");
    orientation = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jac, d, d)
                              .determinant() < 0.0
                      ? -1.0
                      : 1.0;
  }
};

// Basis functions of an element at the reference points: values (m × nq), physical points
// (d × nq), physical gradients (per point, m × d) and |det J| × weight.
struct ElementValues {
  MatrixXd values, points;
  std::vector<MatrixXd> gradients;
  VectorXd dx;
};

void element_values(const Space &sp, const Element &el, const Reference &ref, ElementValues &out) {
  const int d = sp.d;
  const size_t m = el.functions.size();
  out.values.noalias() = el.extraction * ref.values;
  MatrixXd local(m, d);
  for (size_t i = 0; i < m; i++) local.row(i) = sp.control.row(el.functions[i]);
  out.points.noalias() = local.transpose() * out.values;
  std::vector<MatrixXd> du(d);
  std::vector<MatrixXd> jac_col(d);  // column j of J at every point: d × nq
  for (int j = 0; j < d; j++) {
    du[j].noalias() = el.extraction * ref.derivatives[j];
    du[j] /= (el.box[d + j] - el.box[j]);
    jac_col[j].noalias() = local.transpose() * du[j];
  }
  out.gradients.resize(ref.nq);
  out.dx.resize(ref.nq);
  double volume = 1.0;
  for (int j = 0; j < d; j++) volume *= el.box[d + j] - el.box[j];
  MatrixXd gu(m, d), J(d, d);
  for (int q = 0; q < ref.nq; q++) {
    for (int j = 0; j < d; j++) {
      J.col(j) = jac_col[j].col(q);
      gu.col(j) = du[j].col(q);
    }
    double det = sp.orientation * J.determinant();
    if (!(det > 0.0)) throw std::runtime_error("the map's Jacobian is not positive at a quadrature point");
    out.dx(q) = det * ref.weights(q) * volume;
    // ∇_x N = J^{-T} ∇_u N: rows of gu times J^{-1}.
    out.gradients[q].noalias() = gu * J.inverse();
  }
}

// Runs block(begin, end, thread) on contiguous blocks of the elements, one per thread; an
// exception thrown in a block is rethrown here.
void for_elements(size_t ne, int threads, const std::function<void(size_t, size_t, int)> &block) {
  threads = std::max(1, std::min<int>(threads, static_cast<int>(std::max<size_t>(ne, 1))));
  std::vector<std::thread> pool;
  std::vector<std::exception_ptr> failures(threads);
  auto guarded = [&](size_t begin, size_t end, int t) {
    try {
      block(begin, end, t);
    } catch (...) {
      failures[t] = std::current_exception();
    }
  };
  for (int t = 0; t < threads; t++) {
    size_t begin = ne * t / threads, end = ne * (t + 1) / threads;
    if (threads == 1)
      guarded(begin, end, t);
    else
      pool.emplace_back(guarded, begin, end, t);
  }
  for (auto &th : pool) th.join();
  for (auto &f : failures)
    if (f) std::rethrow_exception(f);
}

struct System {
  SparseMatrix a, mass;
  VectorXd load, projection_rhs;
};

// Assembles A = K - κ² M (K for Poisson), M, the load ∫ f N and ∫ u N. The triplets of each
// thread's block of elements are concatenated in element order, so the sums do not depend on
// the thread count.
System assemble(const Space &sp, const Problem &p, const Reference &ref, int threads) {
  const size_t ne = sp.elements.size();
  int nt = std::max(1, threads);
  std::vector<std::vector<Triplet>> ta(nt), tm(nt);
  std::vector<VectorXd> load_e(ne), proj_e(ne);
  for_elements(ne, nt, [&](size_t begin, size_t end, int t) {
    ElementValues ev;
    for (size_t e = begin; e < end; e++) {
      const Element &el = sp.elements[e];
      element_values(sp, el, ref, ev);
      const size_t m = el.functions.size();
      MatrixXd weighted_grad(m, ref.nq * sp.d), grad(m, ref.nq * sp.d);
      VectorXd fw(ref.nq), uw(ref.nq), kw(ref.nq);
      for (int q = 0; q < ref.nq; q++) {
        const double *x = ev.points.col(q).data();
        grad.middleCols(q * sp.d, sp.d) = ev.gradients[q];
        weighted_grad.middleCols(q * sp.d, sp.d) = ev.dx(q) * ev.gradients[q];
        fw(q) = ev.dx(q) * p.f(x);
        uw(q) = ev.dx(q) * p.u(x);
        kw(q) = ev.dx(q) * (p.kappa2 ? p.kappa2(x) : 0.0);
      }
      MatrixXd ke = weighted_grad * grad.transpose();
      MatrixXd me = (ev.values * ev.dx.asDiagonal()) * ev.values.transpose();
      if (p.kappa2) ke.noalias() -= (ev.values * kw.asDiagonal()) * ev.values.transpose();
      load_e[e] = ev.values * fw;
      proj_e[e] = ev.values * uw;
      for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < m; j++) {
          ta[t].emplace_back(el.functions[i], el.functions[j], ke(i, j));
          tm[t].emplace_back(el.functions[i], el.functions[j], me(i, j));
        }
    }
  });
  System sys;
  std::vector<Triplet> all_a, all_m;
  for (int t = 0; t < nt; t++) {
    all_a.insert(all_a.end(), ta[t].begin(), ta[t].end());
    all_m.insert(all_m.end(), tm[t].begin(), tm[t].end());
  }
  sys.a.resize(sp.nb, sp.nb);
  sys.mass.resize(sp.nb, sp.nb);
  sys.a.setFromTriplets(all_a.begin(), all_a.end());
  sys.mass.setFromTriplets(all_m.begin(), all_m.end());
  sys.load = VectorXd::Zero(sp.nb);
  sys.projection_rhs = VectorXd::Zero(sp.nb);
  for (size_t e = 0; e < ne; e++)
    for (size_t i = 0; i < sp.elements[e].functions.size(); i++) {
      sys.load(sp.elements[e].functions[i]) += load_e[e](i);
      sys.projection_rhs(sp.elements[e].functions[i]) += proj_e[e](i);
    }
  return sys;
}

// Solves a symmetric system: sparse LDLᵀ up to `direct_limit` unknowns (LU when indefinite),
// else conjugate gradients with a diagonal preconditioner to a relative residual of 1e-13.
VectorXd solve(const SparseMatrix &a, const VectorXd &b, bool definite) {
  const Eigen::Index direct_limit = 20000;
  if (!definite) {
    Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
    lu.compute(a);
    if (lu.info() != Eigen::Success) throw std::runtime_error("sparse LU failed");
    return lu.solve(b);
  }
  if (a.rows() <= direct_limit) {
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

// The coefficients of the discrete solution: boundary values from the L2 projection of u,
// interior ones from the Galerkin system.
VectorXd solve_level(const Space &sp, const System &sys, bool definite) {
  VectorXd projection = solve(sys.mass, sys.projection_rhs, true);
  std::vector<Eigen::Index> interior_index(sp.nb, -1);
  Eigen::Index ni = 0;
  for (size_t i = 0; i < sp.nb; i++)
    if (!sp.boundary[i]) interior_index[i] = ni++;
  VectorXd c = VectorXd::Zero(sp.nb);
  for (size_t i = 0; i < sp.nb; i++)
    if (sp.boundary[i]) c(i) = projection(i);
  VectorXd rhs = VectorXd::Zero(ni);
  std::vector<Triplet> t;
  VectorXd lifted = sys.a * c;  // A applied to the boundary part
  for (int k = 0; k < sys.a.outerSize(); k++)
    for (SparseMatrix::InnerIterator it(sys.a, k); it; ++it) {
      Eigen::Index r = interior_index[it.row()], col = interior_index[it.col()];
      if (r >= 0 && col >= 0) t.emplace_back(r, col, it.value());
    }
  for (size_t i = 0; i < sp.nb; i++)
    if (interior_index[i] >= 0) rhs(interior_index[i]) = sys.load(i) - lifted(i);
  if (ni > 0) {
    SparseMatrix ai(ni, ni);
    ai.setFromTriplets(t.begin(), t.end());
    VectorXd xi = solve(ai, rhs, definite);
    for (size_t i = 0; i < sp.nb; i++)
      if (interior_index[i] >= 0) c(i) = xi(interior_index[i]);
  }
  return c;
}

// L2 and H1-seminorm errors of the discrete solution (summed per element, then in element
// order).
std::pair<double, double> errors(const Space &sp, const Problem &p, const VectorXd &c,
                                 const Reference &ref, int threads) {
  const size_t ne = sp.elements.size();
  std::vector<double> l2(ne), h1(ne);
  for_elements(ne, threads, [&](size_t begin, size_t end, int) {
    ElementValues ev;
    for (size_t e = begin; e < end; e++) {
      const Element &el = sp.elements[e];
      element_values(sp, el, ref, ev);
      VectorXd ce(el.functions.size());
      for (size_t i = 0; i < el.functions.size(); i++) ce(i) = c(el.functions[i]);
      VectorXd uh = ev.values.transpose() * ce;
      double sl2 = 0.0, sh1 = 0.0, g[3];
      for (int q = 0; q < ref.nq; q++) {
        const double *x = ev.points.col(q).data();
        double diff = uh(q) - p.u(x);
        p.grad(x, g);
        Eigen::VectorXd guh = ev.gradients[q].transpose() * ce;
        double dg = 0.0;
        for (int k = 0; k < sp.d; k++) dg += (guh(k) - g[k]) * (guh(k) - g[k]);
        sl2 += ev.dx(q) * diff * diff;
        sh1 += ev.dx(q) * dg;
      }
      l2[e] = sl2;
      h1[e] = sh1;
    }
  });
  double sl2 = 0.0, sh1 = 0.0;
  for (size_t e = 0; e < ne; e++) {
    sl2 += l2[e];
    sh1 += h1[e];
  }
  return {std::sqrt(sl2), std::sqrt(sh1)};
}

// ASCII .vtu of the solution and the exact solution sampled on 4^d sub-cells per element.
void write_vtu(const Space &sp, const Problem &p, const VectorXd &c, const std::string &path) {
  const int n = 4, d = sp.d;
  int per_el = 1, cells_el = 1;
  for (int k = 0; k < d; k++) {
    per_el *= n + 1;
    cells_el *= n;
  }
  std::vector<double> pts, uh, ue;
  std::vector<int> conn;
  MatrixXd samples(d, per_el), values(1 << (2 * d), per_el);
  for (int s = 0; s < per_el; s++) {
    int rest = s, a[3] = {0, 0, 0};
    for (int k = 0; k < d; k++) {
      a[k] = rest % (n + 1);
      rest /= n + 1;
      samples(k, s) = double(a[k]) / n;
    }
    double b[3][4], db[4];
    for (int k = 0; k < d; k++) bernstein3(samples(k, s), b[k], db);
    for (int kb = 0; kb < (1 << (2 * d)); kb++) {
      int ia[3] = {kb & 3, (kb >> 2) & 3, (kb >> 4) & 3};
      double v = 1.0;
      for (int k = 0; k < d; k++) v *= b[k][ia[k]];
      values(kb, s) = v;
    }
  }
  for (const Element &el : sp.elements) {
    const int base = static_cast<int>(pts.size() / 3);
    MatrixXd nv = el.extraction * values;
    for (int s = 0; s < per_el; s++) {
      double x[3] = {0, 0, 0}, v = 0.0;
      for (size_t i = 0; i < el.functions.size(); i++) {
        for (int k = 0; k < d; k++) x[k] += nv(i, s) * sp.control(el.functions[i], k);
        v += nv(i, s) * c(el.functions[i]);
      }
      pts.insert(pts.end(), x, x + 3);
      uh.push_back(v);
      ue.push_back(p.u(x));
    }
    for (int cidx = 0; cidx < cells_el; cidx++) {
      int rest = cidx, a[3] = {0, 0, 0};
      for (int k = 0; k < d; k++) {
        a[k] = rest % n;
        rest /= n;
      }
      auto id = [&](int i, int j, int k) { return base + (a[0] + i) + (n + 1) * ((a[1] + j) + (n + 1) * (a[2] + k)); };
      int corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
      for (int v = 0; v < (d == 2 ? 4 : 8); v++) conn.push_back(id(corners[v][0], corners[v][1], corners[v][2]));
    }
  }
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  const size_t np = uh.size(), nc = conn.size() / (d == 2 ? 4 : 8);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid><Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc << "\">\n"
      << "<PointData Scalars=\"u_h\">\n<DataArray type=\"Float64\" Name=\"u_h\" format=\"ascii\">\n";
  out.precision(12);
  for (double v : uh) out << v << "\n";
  out << "</DataArray>\n<DataArray type=\"Float64\" Name=\"error\" format=\"ascii\">\n";
  for (size_t i = 0; i < np; i++) out << uh[i] - ue[i] << "\n";
  out << "</DataArray>\n</PointData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (size_t i = 0; i < np; i++) out << pts[3 * i] << " " << pts[3 * i + 1] << " " << pts[3 * i + 2] << "\n";
  out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (size_t i = 0; i < conn.size(); i++) out << conn[i] << ((i + 1) % 8 == 0 ? "\n" : " ");
  out << "\n</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  for (size_t i = 1; i <= nc; i++) out << i * (d == 2 ? 4 : 8) << "\n";
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (size_t i = 0; i < nc; i++) out << (d == 2 ? 9 : 12) << "\n";
  out << "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
}

// ---------------------------------------------------------------------------------------------
// Geometries

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
        double r = 1.0 + i0 / 3.0;
        s << "   " << r * arc[i1][0] << " " << r * arc[i1][1] << " " << i2 / 3.0 << "\n";
      }
  s << "  </coefs>\n </Geometry>\n</xml>\n";
  return s.str();
}

std::string temporary_path(const std::string &name) {
  const char *dir = std::getenv("TMPDIR");
  std::string base = dir && *dir ? dir : "/tmp";
  return base + "/" + name + "_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + ".xml";
}

SplinePtr read_spline_text(const std::string &text) {
  std::string path = temporary_path("igaparam_poisson_map");
  {
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write " + path);
    out << text;
  }
  igaparam_spline *s = nullptr;
  igaparam_status status = igaparam_spline_read_gismo(path.c_str(), &s);
  std::remove(path.c_str());
  check(status, "reading the built-in map");
  return SplinePtr(s);
}

// Builds the domain and fits its spline map. The cubic fit of a valid piecewise quadratic map
// may fold where the boundary is coarsely resolved: while the fitted map is not certified
// valid, the domain is rebuilt with a tolerance ten times smaller (at most `refits` times). The
// solve itself needs det J > 0 at the quadrature points only (checked during assembly).
SplinePtr fit(DomainPtr domain, int threads, double tolerance, int max_level, int refits) {
  igaparam_domain_options options = igaparam_domain_options_default();
  options.threads = static_cast<uint32_t>(threads);
  if (tolerance > 0.0) options.tolerance = tolerance;
  if (max_level >= 0) options.max_level = static_cast<uint8_t>(max_level);
  for (int attempt = 0;; attempt++) {
    igaparam_domain_report report;
    check(igaparam_domain_build(domain.get(), &options, &report), "domain build");
    if (report.invalid_cells != 0) throw std::runtime_error("the domain has invalid cells");
    igaparam_spline *raw = nullptr;
    check(igaparam_spline_fit_domain(domain.get(), &raw, nullptr), "spline fit");
    SplinePtr s(raw);
    igaparam_validity_report validity;
    check(igaparam_spline_check_validity(s.get(), nullptr, &validity, nullptr, nullptr, 0), "validity");
    if (validity.certified_positive || attempt >= refits) {
      if (!validity.certified_positive)
        std::fprintf(stderr, "igaparam_poisson: the map is not certified valid on %zu elements (min sampled q %.3g)\n",
                     validity.uncertified, validity.min_quality);
      return s;
    }
    options.tolerance /= 10.0;
    std::fprintf(stderr, "igaparam_poisson: the fitted map is not certified valid; rebuilding with tolerance %g\n",
                 options.tolerance);
  }
}

// The quarter annulus r ∈ [1, 2], θ ∈ [0, π/2] from four polylines (arcs of 257 points).
SplinePtr quarter_annulus(int threads) {
  const int n = 257;
  std::vector<double> inner, outer, bottom = {1, 0, 2, 0}, left = {0, 2, 0, 1};
  for (int i = 0; i < n; i++) {
    double t = 0.5 * kPi * i / (n - 1);
    outer.push_back(2 * std::cos(t));
    outer.push_back(2 * std::sin(t));
    double ti = 0.5 * kPi * (n - 1 - i) / (n - 1);
    inner.push_back(std::cos(ti));
    inner.push_back(std::sin(ti));
  }
  size_t counts[4] = {2, size_t(n), 2, size_t(n)};
  const double *points[4] = {bottom.data(), outer.data(), left.data(), inner.data()};
  igaparam_domain *domain = nullptr;
  check(igaparam_domain_new_from_polylines(counts, points, &domain), "quarter annulus");
  return fit(DomainPtr(domain), threads, 0.0, -1, 3);
}

bool is_thb_xml(const std::string &path) {
  std::ifstream in(path);
  std::string head(4096, '\0');
  in.read(&head[0], head.size());
  head.resize(static_cast<size_t>(in.gcount()));
  return head.find("THBSpline") != std::string::npos;
}

SplinePtr load(const std::string &input, int dim, int threads, double tolerance, int max_level, int refits) {
  if (input.empty()) return dim == 3 ? read_spline_text(thick_quarter_annulus_xml()) : quarter_annulus(threads);
  if (is_thb_xml(input)) {
    igaparam_spline *s = nullptr;
    check(igaparam_spline_read_gismo(input.c_str(), &s), input.c_str());
    return SplinePtr(s);
  }
  // A B-rep or coastline with four curves; else a solid (six surfaces, or a folder of six faces).
  igaparam_domain *domain = nullptr;
  if (igaparam_domain_new_from_file(input.c_str(), &domain) != IGAPARAM_STATUS_OK) {
    std::string planar = last_error();
    if (igaparam_domain_new_solid_from_file(input.c_str(), &domain) != IGAPARAM_STATUS_OK)
      throw std::runtime_error(input + ": " + planar + " (as a solid: " + last_error() + ")");
  }
  return fit(DomainPtr(domain), threads, tolerance, max_level, refits);
}

// The exact solution of a problem on a map of dimension d. `box` (lower corner, then upper
// corner; empty for the built-in domains) is the bounding box of an input domain: there the 3D
// Poisson layer is placed by it, its centre outside the box at a quarter of the box beyond the
// lower corner, the layer through the box's centre, α = 10 / diagonal.
Problem make_problem(const std::string &name, int d, const std::vector<double> &box = {}) {
  if (name == "poisson") {
    if (d == 2) return poisson_2d();
    if (box.empty()) return arctan_layer(d, {-0.5, -0.5, -0.5}, 5.0, 2.0);
    std::array<double, 3> centre{}, middle{};
    double diagonal = 0.0, r0 = 0.0;
    for (int k = 0; k < 3; k++) {
      double extent = box[3 + k] - box[k];
      centre[k] = box[k] - 0.25 * extent;
      middle[k] = 0.5 * (box[k] + box[3 + k]);
      diagonal += extent * extent;
      r0 += (middle[k] - centre[k]) * (middle[k] - centre[k]);
    }
    return arctan_layer(d, centre, 10.0 / std::sqrt(diagonal), std::sqrt(r0));
  }
  if (name == "helmholtz") return helmholtz(d, {0.6, 0.6, -0.4});
  if (name == "linear") return linear(d);
  throw std::invalid_argument("unknown problem '" + name + "' (poisson, helmholtz or linear)");
}

void usage() {
  std::fprintf(stderr,
               "usage: igaparam_poisson [INPUT] [--problem poisson|helmholtz|linear] [--levels N] [--threads N]\n"
               "                        [--dim 2|3] [--quad N] [--tolerance T] [--max-level L] [--refits N]\n"
               "                        [--vtu PATH]\n"
               "                        [--check-rates L2MIN H1MIN] [--check-max-error E] [--check-source]\n"
               "                        [--check-certified]\n");
}

std::string json_list(const std::vector<double> &v) {
  std::ostringstream s;
  s.precision(6);
  s << "[";
  for (size_t i = 0; i < v.size(); i++) s << (i ? ", " : "") << v[i];
  s << "]";
  return s.str();
}

int run(int argc, char **argv) {
  std::string input, problem_name = "poisson", vtu;
  int levels = 3, threads = 0, dim = 2, quad = 0, refits = 3, max_level = -1;
  bool check_rates = false, check_source = false, check_certified = false;
  double l2_min = 0.0, h1_min = 0.0, tolerance = 0.0, max_error = -1.0;
  for (int i = 1; i < argc; i++) {
    std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--problem")
      problem_name = next();
    else if (a == "--levels")
      levels = std::stoi(next());
    else if (a == "--threads")
      threads = std::stoi(next());
    else if (a == "--dim")
      dim = std::stoi(next());
    else if (a == "--quad")
      quad = std::stoi(next());
    else if (a == "--refits")
      refits = std::stoi(next());
    else if (a == "--tolerance")
      tolerance = std::stod(next());
    else if (a == "--max-level")
      max_level = std::stoi(next());
    else if (a == "--vtu")
      vtu = next();
    else if (a == "--check-rates") {
      check_rates = true;
      l2_min = std::stod(next());
      h1_min = std::stod(next());
    } else if (a == "--check-max-error")
      max_error = std::stod(next());
    else if (a == "--check-source")
      check_source = true;
    else if (a == "--check-certified")
      check_certified = true;
    else if (a == "-h" || a == "--help") {
      usage();
      return 0;
    } else if (!a.empty() && a[0] == '-')
      throw std::invalid_argument("unknown option " + a);
    else if (input.empty())
      input = a;
    else
      throw std::invalid_argument("more than one input");
  }
  if (levels < 0 || levels > 12 || (dim != 2 && dim != 3) || quad < 0 || quad > 12 || threads < 0 ||
      max_level > 16 || (max_level < 0 && max_level != -1))
    throw std::invalid_argument("bad --levels, --dim, --quad, --threads or --max-level");
  if (threads == 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  if (check_source) {
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
    bool ok = true;
    for (std::string name : {"poisson", "helmholtz"}) {
      double r = source_residual(make_problem(name, dim), dim, pts);
      std::printf("%s %dD: largest relative difference between f and the finite differences: %.3g\n",
                  name.c_str(), dim, r);
      ok = ok && r < 1e-5;
    }
    return ok ? 0 : 3;
  }

  SplinePtr spline = load(input, dim, threads, tolerance, max_level, refits);
  size_t d = 0;
  check(igaparam_spline_dimension(spline.get(), &d), "dimension");
  if (check_certified) {
    igaparam_validity_report validity;
    check(igaparam_spline_check_validity(spline.get(), nullptr, &validity, nullptr, nullptr, 0), "validity");
    if (!validity.certified_positive) {
      std::fprintf(stderr, "igaparam_poisson: the map is not certified valid (%zu elements)\n", validity.uncertified);
      return 3;
    }
    std::printf("map certified valid: det J > 0 proven on all elements, min sampled q_S %.4f\n",
                validity.min_quality);
  }
  // The bounding box of the control points (it holds the domain) places the solution of an
  // input domain.
  std::vector<double> box;
  if (!input.empty()) {
    size_t nb = 0;
    check(igaparam_spline_basis_count(spline.get(), &nb), "basis count");
    std::vector<double> xyz(nb * d);
    check(igaparam_spline_copy_control_points(spline.get(), xyz.data(), xyz.size()), "control points");
    box.assign(6, 0.0);
    for (size_t k = 0; k < d; k++) {
      box[k] = box[3 + k] = xyz[k];
      for (size_t i = 0; i < nb; i++) {
        box[k] = std::min(box[k], xyz[i * d + k]);
        box[3 + k] = std::max(box[3 + k], xyz[i * d + k]);
      }
    }
  }
  const Problem problem = make_problem(problem_name, static_cast<int>(d), box);
  const int assembly_points = quad > 0 ? quad : (d == 2 ? 5 : 4);
  const Reference assembly(static_cast<int>(d), assembly_points), error_rule(static_cast<int>(d), 6);

  std::vector<double> elements, dofs, hs, l2s, h1s;
  std::printf("%5s %9s %9s %10s %12s %7s %12s %7s %8s\n", "level", "elements", "dofs", "h", "L2", "rate",
              "H1", "rate", "seconds");
  for (int level = 0; level <= levels; level++) {
    auto start = std::chrono::steady_clock::now();
    auto lap = [&start]() { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    if (level > 0) check(igaparam_spline_refine(spline.get(), 0, nullptr, nullptr), "uniform refinement");
    double t_refine = lap();
    Space space(spline.get());
    double t_space = lap();
    System sys = assemble(space, problem, assembly, threads);
    double t_assemble = lap();
    VectorXd c = solve_level(space, sys, !problem.kappa2);
    double t_solve = lap();
    auto [l2, h1] = errors(space, problem, c, error_rule, threads);
    std::fprintf(stderr, "level %d: refine %.2f s, extraction %.2f s, assembly %.2f s, solve %.2f s, errors %.2f s\n",
                 level, t_refine, t_space - t_refine, t_assemble - t_space, t_solve - t_assemble, lap() - t_solve);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    elements.push_back(double(space.elements.size()));
    dofs.push_back(double(space.nb));
    hs.push_back(space.h);
    l2s.push_back(l2);
    h1s.push_back(h1);
    char r2[16] = "", r1[16] = "";
    if (level > 0) {
      double lh = std::log(hs[level - 1] / hs[level]);
      std::snprintf(r2, sizeof r2, "%.2f", std::log(l2s[level - 1] / l2) / lh);
      std::snprintf(r1, sizeof r1, "%.2f", std::log(h1s[level - 1] / h1) / lh);
    }
    std::printf("%5d %9zu %9zu %10.4g %12.4e %7s %12.4e %7s %8.2f\n", level, space.elements.size(), space.nb,
                space.h, l2, r2, h1, r1, seconds);
    std::fflush(stdout);
    if (level == levels && !vtu.empty()) write_vtu(space, problem, c, vtu);
  }
  double rate_l2 = 0.0, rate_h1 = 0.0;
  const size_t n = l2s.size();
  if (n >= 2) {
    double lh = std::log(hs[n - 2] / hs[n - 1]);
    rate_l2 = std::log(l2s[n - 2] / l2s[n - 1]) / lh;
    rate_h1 = std::log(h1s[n - 2] / h1s[n - 1]) / lh;
  }
  std::printf("{\"problem\": \"%s\", \"dim\": %zu, \"threads\": %d, \"elements\": %s, \"dofs\": %s, \"h\": %s, "
              "\"l2\": %s, \"h1\": %s, \"rate_l2\": %.4f, \"rate_h1\": %.4f}\n",
              problem.name.c_str(), d, threads, json_list(elements).c_str(), json_list(dofs).c_str(),
              json_list(hs).c_str(), json_list(l2s).c_str(), json_list(h1s).c_str(), rate_l2, rate_h1);
  if (check_rates && (n < 2 || !(rate_l2 >= l2_min) || !(rate_h1 >= h1_min))) {
    std::fprintf(stderr, "igaparam_poisson: rates %.3f (L2) and %.3f (H1) below %.3f and %.3f\n", rate_l2,
                 rate_h1, l2_min, h1_min);
    return 3;
  }
  if (max_error >= 0.0 && !(*std::max_element(l2s.begin(), l2s.end()) <= max_error &&
                            *std::max_element(h1s.begin(), h1s.end()) <= max_error)) {
    std::fprintf(stderr, "igaparam_poisson: errors above %g\n", max_error);
    return 3;
  }
  return 0;
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
