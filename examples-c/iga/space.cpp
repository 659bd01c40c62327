// space.cpp: the analysis space of a spline map and its basis functions at reference points.

#include "space.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <thread>

namespace iga {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

std::string last_error() {
  char message[1024] = {0};
  igaparam_last_error_message(message, sizeof message);
  return message;
}

void check(igaparam_status status, const char *what) {
  if (status == IGAPARAM_STATUS_OK) return;
  throw std::runtime_error(std::string(what) + ": " + last_error());
}

SplinePtr clone(const igaparam_spline *spline) {
  igaparam_spline *copy = nullptr;
  check(igaparam_spline_clone(spline, &copy), "clone");
  return SplinePtr(copy);
}

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

namespace {

// The cubic Bernstein polynomials at t and their first and second derivatives.
void bernstein3(double t, double b[4], double db[4], double d2b[4]) {
  const double s = 1.0 - t;
  b[0] = s * s * s;
  b[1] = 3.0 * t * s * s;
  b[2] = 3.0 * t * t * s;
  b[3] = t * t * t;
  db[0] = -3.0 * s * s;
  db[1] = 3.0 * s * s - 6.0 * t * s;
  db[2] = 6.0 * t * s - 3.0 * t * t;
  db[3] = 3.0 * t * t;
  d2b[0] = 6.0 * s;
  d2b[1] = 6.0 * t - 12.0 * s;
  d2b[2] = 6.0 * s - 12.0 * t;
  d2b[3] = 6.0 * t;
}

}  // namespace

Reference::Reference(const std::vector<std::vector<double>> &x, const std::vector<std::vector<double>> &w,
                     bool with_second)
    : d(static_cast<int>(x.size())) {
  nq = 1;
  for (int k = 0; k < d; k++) nq *= static_cast<int>(x[k].size());
  points.resize(d, nq);
  weights.resize(nq);
  for (int q = 0; q < nq; q++) {
    int rest = q;
    double wq = 1.0;
    for (int k = 0; k < d; k++) {
      const int n = static_cast<int>(x[k].size()), i = rest % n;
      rest /= n;
      points(k, q) = x[k][i];
      wq *= w[k][i];
    }
    weights(q) = wq;
  }
  factors.resize(d);
  for (int k = 0; k < d; k++) {
    const int n = static_cast<int>(x[k].size());
    for (auto &f : factors[k]) f.resize(4, n);
    for (int i = 0; i < n; i++) {
      double b[3][4];
      bernstein3(x[k][i], b[0], b[1], b[2]);
      for (int order = 0; order < 3; order++)
        for (int a = 0; a < 4; a++) factors[k][order](a, i) = b[order][a];
    }
  }
  orders.push_back({0, 0, 0});
  for (int j = 0; j < d; j++) {
    std::array<int, 3> o{0, 0, 0};
    o[j] = 1;
    orders.push_back(o);
  }
  for (int j = 0; with_second && j < d; j++)
    for (int l = j; l < d; l++) {
      std::array<int, 3> o{0, 0, 0};
      o[j]++;
      o[l]++;
      orders.push_back(o);
    }
  blocks = static_cast<int>(orders.size());
}

void Reference::apply(const MatrixXd &c, int b, MatrixXd &work, Eigen::Ref<MatrixXd> out) const {
  // c holds, column a0 + 4 a1 (+ 16 a2), the Bernstein coefficients of each function (m rows).
  // Contracting axis k replaces index a_k (4 values) by q_k (n_k values); the layout stays
  // "function fastest, then the axes in order", so each step is a GEMM on a reshaped matrix.
  using Map = Eigen::Map<MatrixXd>;
  using ConstMap = Eigen::Map<const MatrixXd>;
  const Eigen::Index m = c.rows();
  Eigen::Index lead = m, rest = c.cols() / 4;  // rows of the reshaped matrix; trailing blocks
  const double *from = c.data();
  Eigen::Index current = m * c.cols(), size = 1;  // the largest intermediate result
  for (int k = 0; k + 1 < d; k++) size = std::max(size, current = current / 4 * factors[k][0].cols());
  if (work.size() < 2 * size) work.resize(2 * size, 1);  // two buffers, used in turn
  double *buffers[2] = {work.data(), work.data() + size};
  for (int k = 0; k < d; k++) {
    const MatrixXd &f = factors[k][orders[b][k]];
    const Eigen::Index n = f.cols();
    double *to = k + 1 == d ? out.data() : buffers[k % 2];
    for (Eigen::Index r = 0; r < rest; r++)
      Map(to + r * lead * n, lead, n).noalias() = ConstMap(from + r * lead * 4, lead, 4) * f;
    from = to;
    lead *= n;
    rest /= 4;
  }
}

int Reference::second_index(int j, int l) const {
  const int a = std::min(j, l), b = std::max(j, l);
  return 1 + d + a * d - a * (a - 1) / 2 + (b - a);
}

Reference Reference::gauss(int d, int n, bool with_second) {
  std::vector<double> x, w;
  gauss_legendre(n, x, w);
  return Reference(std::vector<std::vector<double>>(d, x), std::vector<std::vector<double>>(d, w), with_second);
}

Reference Reference::face(int d, int n, int axis, int side) {
  std::vector<double> x, w;
  gauss_legendre(n, x, w);
  std::vector<std::vector<double>> xs(d, x), ws(d, w);
  xs[axis] = {double(side)};
  ws[axis] = {1.0};
  return Reference(xs, ws, false);
}

Reference Reference::grid(int d, int n) {
  std::vector<double> x(n + 1), w(n + 1, 1.0);
  for (int i = 0; i <= n; i++) x[i] = double(i) / n;
  return Reference(std::vector<std::vector<double>>(d, x), std::vector<std::vector<double>>(d, w), false);
}

Space::Space(const igaparam_spline *s) {
  size_t dim = 0, ne = 0;
  check(igaparam_spline_dimension(s, &dim), "dimension");
  check(igaparam_spline_basis_count(s, &nb), "basis count");
  check(igaparam_spline_element_count(s, &ne), "element count");
  d = static_cast<int>(dim);
  std::vector<double> buffer(nb * d);
  check(igaparam_spline_copy_control_points(s, buffer.data(), buffer.size()), "control points");
  control = Eigen::Map<RowMajor>(buffer.data(), nb, d);
  check(igaparam_spline_copy_greville_points(s, buffer.data(), buffer.size()), "Greville points");
  faces.assign(nb, 0);
  for (size_t i = 0; i < nb; i++)
    for (int k = 0; k < d; k++) {
      const double g = buffer[i * d + k];
      if (g <= 1e-12) faces[i] |= face_bit(k, 0);
      if (g >= 1.0 - 1e-12) faces[i] |= face_bit(k, 1);
    }
  std::vector<double> bounds(ne * 2 * d);
  std::vector<uint8_t> levels(ne);
  check(igaparam_spline_copy_elements(s, levels.data(), bounds.data(), ne), "elements");
  const size_t nbern = size_t(1) << (2 * d);
  elements.resize(ne);
  for (size_t e = 0; e < ne; e++) {
    size_t m = 0;
    check(igaparam_spline_element_function_count(s, e, &m), "element function count");
    Element &el = elements[e];
    el.functions.resize(m);
    el.level = levels[e];
    std::vector<double> op(m * nbern);
    check(igaparam_spline_copy_element_extraction(s, e, el.functions.data(), m, op.data(), op.size()),
          "extraction");
    el.extraction = Eigen::Map<RowMajor>(op.data(), m, nbern);
    for (int k = 0; k < 2 * d; k++) el.box[k] = bounds[e * 2 * d + k];
    for (int k = 0; k < d; k++) h = std::max(h, el.box[d + k] - el.box[k]);
  }
  double centre[3], jac[9];
  for (int k = 0; k < d; k++) centre[k] = 0.5 * (elements[0].box[k] + elements[0].box[d + k]);
  check(igaparam_spline_evaluate(s, 1, centre, nullptr, jac), "evaluate");
  orientation = Eigen::Map<RowMajor>(jac, d, d).determinant() < 0.0 ? -1.0 : 1.0;
}

namespace {

// Physical Laplacians of the element's functions at point q: with G = J^{-1} and H_k the
// parametric Hessian of the map's coordinate k,
// ΔN = Σ_jl (G Gᵀ)_jl (∂²N/∂u_j∂u_l − Σ_k ∂N/∂x_k (H_k)_jl).
void laplacian_at(int q, const Reference &ref, const MatrixXd &local, const double *side, const MatrixXd &inverse,
                  ElementValues &out) {
  const int d = ref.d;
  const MatrixXd metric = inverse * inverse.transpose();
  auto lap = out.laplacians.col(q);
  lap.setZero();
  for (int j = 0; j < d; j++)
    for (int l = 0; l < d; l++) {
      const auto second = out.all.col(ref.second_index(j, l) * ref.nq + q);
      const double scale = metric(j, l) / (side[j] * side[l]);
      const VectorXd hessian_jl = local.transpose() * second;  // (H_k)_jl · side_j side_l, every k
      lap += scale * (second - out.gradient(q, d) * hessian_jl);
    }
}

}  // namespace

void element_values(const Space &sp, const Element &el, const Reference &ref, ElementValues &out,
                    bool with_laplacians) {
  const int d = sp.d, nq = ref.nq;
  const Eigen::Index m = static_cast<Eigen::Index>(el.functions.size());
  if (with_laplacians && !ref.has_second()) throw std::logic_error("the reference points have no second derivatives");
  out.all.resize(m, ref.blocks * nq);
  for (int b = 0; b < ref.blocks; b++) ref.apply(el.extraction, b, out.work, out.all.middleCols(b * nq, nq));
  out.values = out.all.leftCols(nq);
  MatrixXd local(m, d);
  for (Eigen::Index i = 0; i < m; i++) local.row(i) = sp.control.row(el.functions[i]);
  out.points.noalias() = local.transpose() * out.values;
  double volume = 1.0, side[3];
  for (int j = 0; j < d; j++) {
    side[j] = el.box[d + j] - el.box[j];
    volume *= side[j];
  }
  out.gradients.resize(m, nq * d);
  out.jacobians.resize(d, nq * d);
  out.dx.resize(nq);
  if (with_laplacians) out.laplacians.resize(m, nq);
  MatrixXd gu(m, d), inverse(d, d);
  for (int q = 0; q < nq; q++) {
    for (int j = 0; j < d; j++) gu.col(j) = out.all.col((1 + j) * nq + q) / side[j];
    out.jacobians.middleCols(q * d, d).noalias() = local.transpose() * gu;
    const auto J = out.jacobians.middleCols(q * d, d);
    const double det = sp.orientation * J.determinant();
    if (!(det > 0.0)) throw std::runtime_error("the map's Jacobian is not positive at a quadrature point");
    out.dx(q) = det * ref.weights(q) * volume;
    inverse = J.inverse();
    out.gradients.middleCols(q * d, d).noalias() = gu * inverse;  // ∇_x N = J^{-T} ∇_u N, as rows
    if (with_laplacians) laplacian_at(q, ref, local, side, inverse, out);
  }
}

void for_elements(size_t n, int threads, const std::function<void(size_t, size_t, int)> &block) {
  threads = std::max(1, std::min<int>(threads, static_cast<int>(std::max<size_t>(n, 1))));
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
    const size_t begin = n * t / threads, end = n * (t + 1) / threads;
    if (threads == 1)
      guarded(begin, end, t);
    else
      pool.emplace_back(guarded, begin, end, t);
  }
  for (auto &th : pool) th.join();
  for (auto &f : failures)
    if (f) std::rethrow_exception(f);
}

std::vector<double> control_box(const igaparam_spline *spline) {
  size_t nb = 0, d = 0;
  check(igaparam_spline_dimension(spline, &d), "dimension");
  check(igaparam_spline_basis_count(spline, &nb), "basis count");
  std::vector<double> xyz(nb * d), box(2 * d);
  check(igaparam_spline_copy_control_points(spline, xyz.data(), xyz.size()), "control points");
  for (size_t k = 0; k < d; k++) {
    box[k] = box[d + k] = xyz[k];
    for (size_t i = 0; i < nb; i++) {
      box[k] = std::min(box[k], xyz[i * d + k]);
      box[d + k] = std::max(box[d + k], xyz[i * d + k]);
    }
  }
  return box;
}

VectorXd local_coefficients(const Element &el, const VectorXd &c) {
  VectorXd ce(el.functions.size());
  for (size_t i = 0; i < el.functions.size(); i++) ce(i) = c(el.functions[i]);
  return ce;
}

}  // namespace iga
