// estimate.cpp: errors, residual indicators and rates.

#include "estimate.h"

#include <algorithm>
#include <cmath>

namespace iga {

double ElementNorms::total(const std::vector<double> &squares) {
  double s = 0.0;
  for (double v : squares) s += v;
  return std::sqrt(s);
}

namespace {

// The squared errors and indicator of one element.
void norms_of_element(const Space &sp, const Problem &p, const VectorXd &ce, const ElementValues &ev, bool estimator,
                      double out[3]) {
  const VectorXd uh = ev.values.transpose() * ce;
  VectorXd lap;
  if (estimator) lap = ev.laplacians.transpose() * ce;
  double sl2 = 0.0, sh1 = 0.0, residual = 0.0, volume = 0.0, g[3];
  for (int q = 0; q < ev.dx.size(); q++) {
    const double *x = ev.points.col(q).data();
    const double diff = uh(q) - p.u(x);
    p.grad(x, g);
    const VectorXd guh = ev.gradient(q, sp.d).transpose() * ce;
    double dg = 0.0;
    for (int k = 0; k < sp.d; k++) dg += (guh(k) - g[k]) * (guh(k) - g[k]);
    sl2 += ev.dx(q) * diff * diff;
    sh1 += ev.dx(q) * dg;
    volume += ev.dx(q);
    if (estimator) {
      const double r = p.f(x) + lap(q) + (p.kappa2 ? p.kappa2(x) * uh(q) : 0.0);
      residual += ev.dx(q) * r * r;
    }
  }
  out[0] = sl2;
  out[1] = sh1;
  out[2] = estimator ? std::pow(volume, 2.0 / sp.d) * residual : 0.0;
}

}  // namespace

ElementNorms element_norms(const Space &sp, const Problem &p, const VectorXd &c, const Reference &ref, int threads,
                           bool with_estimator) {
  const size_t ne = sp.elements.size();
  ElementNorms out;
  out.l2.assign(ne, 0.0);
  out.h1.assign(ne, 0.0);
  if (with_estimator) out.eta.assign(ne, 0.0);
  for_elements(ne, threads, [&](size_t begin, size_t end, int) {
    ElementValues ev;
    for (size_t e = begin; e < end; e++) {
      const Element &el = sp.elements[e];
      element_values(sp, el, ref, ev, with_estimator);
      double n[3];
      norms_of_element(sp, p, local_coefficients(el, c), ev, with_estimator, n);
      out.l2[e] = n[0];
      out.h1[e] = n[1];
      if (with_estimator) out.eta[e] = n[2];
    }
  });
  return out;
}

std::vector<size_t> mark(const Space &sp, const std::vector<double> &eta_squared, double gamma) {
  double largest = 0.0;
  for (size_t e = 0; e < eta_squared.size(); e++)
    if (sp.elements[e].level < kDeepestLevel) largest = std::max(largest, eta_squared[e]);
  std::vector<size_t> marked;
  for (size_t e = 0; e < eta_squared.size(); e++)
    if (sp.elements[e].level < kDeepestLevel && eta_squared[e] > gamma * gamma * largest) marked.push_back(e);
  return marked;
}

std::vector<size_t> extend(const Space &sp, const std::vector<size_t> &marked, int layers) {
  const int d = sp.d;
  std::vector<char> chosen(sp.elements.size(), 0);
  for (size_t m : marked) chosen[m] = 1;
  if (layers > 0)
    for (size_t m : marked) {
      const Element &me = sp.elements[m];
      double lo[3], hi[3];
      for (int k = 0; k < d; k++) {
        const double side = me.box[d + k] - me.box[k], margin = layers * side - 1e-3 * side;
        lo[k] = me.box[k] - margin;
        hi[k] = me.box[d + k] + margin;
      }
      for (size_t e = 0; e < sp.elements.size(); e++) {
        const Element &el = sp.elements[e];
        bool meets = el.level <= me.level && el.level < kDeepestLevel;
        for (int k = 0; k < d && meets; k++) meets = el.box[k] < hi[k] && el.box[d + k] > lo[k];
        if (meets) chosen[e] = 1;
      }
    }
  std::vector<size_t> out;
  for (size_t e = 0; e < chosen.size(); e++)
    if (chosen[e]) out.push_back(e);
  return out;
}

double fitted_rate(const std::vector<double> &dofs, const std::vector<double> &error, double span) {
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  int n = 0;
  for (size_t i = 0; i < dofs.size(); i++) {
    if (dofs[i] < dofs.back() / span) continue;
    const double x = std::log(dofs[i]), y = std::log(error[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    n++;
  }
  const double denominator = n * sxx - sx * sx;
  if (n < 2 || !(denominator > 0.0)) return NAN;
  return -(n * sxy - sx * sy) / denominator;
}

double last_rate(const std::vector<double> &h, const std::vector<double> &error) {
  const size_t n = error.size();
  if (n < 2) return 0.0;
  return std::log(error[n - 2] / error[n - 1]) / std::log(h[n - 2] / h[n - 1]);
}

double dofs_to_reach(const std::vector<double> &dofs, const std::vector<double> &error, double target) {
  for (size_t i = 0; i < error.size(); i++) {
    if (error[i] > target) continue;
    if (i == 0) return dofs[0];
    const double t = std::log(error[i - 1] / target) / std::log(error[i - 1] / error[i]);
    return std::exp(std::log(dofs[i - 1]) + t * std::log(dofs[i] / dofs[i - 1]));
  }
  return NAN;
}

}  // namespace iga
