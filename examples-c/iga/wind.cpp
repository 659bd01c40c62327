// wind.cpp: the mass-consistent wind model.

#include "wind.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "system.h"

namespace iga {

namespace {

// The profile factor g(h) of the logarithmic wind and its derivative.
double profile(const InitialWind &w, double z, double *derivative) {
  const double h = std::max(0.0, z - w.ground), z0 = w.roughness;
  const double norm = std::log((w.reference_height + z0) / z0);
  if (derivative) *derivative = z - w.ground > 0.0 ? 1.0 / ((h + z0) * norm) : 0.0;
  return std::log((h + z0) / z0) / norm;
}

// ‖∇·u‖² over the elements and max |∇λ| at the quadrature points, with max |u0| there.
void volume_checks(const WindSolution &s, const InitialWind &wind, int threads, double &div2, double &change,
                   double &speed) {
  const Reference ref = Reference::gauss(3, 5, true);
  const size_t ne = s.space.elements.size();
  std::vector<std::array<double, 3>> per(ne);
  for_elements(ne, threads, [&](size_t begin, size_t end, int) {
    ElementValues ev;
    for (size_t e = begin; e < end; e++) {
      const Element &el = s.space.elements[e];
      element_values(s.space, el, ref, ev, true);
      const VectorXd ce = local_coefficients(el, s.lambda), lap = ev.laplacians.transpose() * ce;
      double sum = 0.0, most = 0.0, fastest = 0.0, u0[3];
      for (int q = 0; q < ref.nq; q++) {
        const double *x = ev.points.col(q).data();
        const double div = wind.divergence(x) + lap(q);
        sum += ev.dx(q) * div * div;
        most = std::max(most, (ev.gradient(q, 3).transpose() * ce).norm());
        wind.value(x, u0);
        fastest = std::max(fastest, std::sqrt(u0[0] * u0[0] + u0[1] * u0[1] + u0[2] * u0[2]));
      }
      per[e] = {sum, most, fastest};
    }
  });
  div2 = change = speed = 0.0;
  for (const auto &p : per) {
    div2 += p[0];
    change = std::max(change, p[1]);
    speed = std::max(speed, p[2]);
  }
}

// ‖n·u‖² and ‖n·u0‖² over the terrain face.
void terrain_checks(const WindSolution &s, const InitialWind &wind, TerrainFace terrain, double &normal2,
                    double &initial2) {
  const Reference ref = Reference::face(3, 5, terrain.axis, terrain.side);
  const double sign = terrain.side == 1 ? 1.0 : -1.0;
  normal2 = initial2 = 0.0;
  ElementValues ev;
  for (const Element &el : s.space.elements) {
    const int a = terrain.axis;
    if (terrain.side == 0 ? el.box[a] > 0.0 : el.box[3 + a] < 1.0) continue;
    element_values(s.space, el, ref, ev);
    const VectorXd ce = local_coefficients(el, s.lambda);
    for (int q = 0; q < ref.nq; q++) {
      // n ds = det J J^{-T} N dA (Nanson): the row `a` of J^{-1} is the gradient of u_a.
      const Eigen::RowVector3d g = Eigen::Matrix3d(ev.jacobian(q, 3)).inverse().row(a);
      const double ds = ev.dx(q) / (el.box[3 + a] - el.box[a]) * g.norm();
      const Eigen::Vector3d n = sign * g.transpose() / g.norm();
      double u0[3];
      wind.value(ev.points.col(q).data(), u0);
      const Eigen::Vector3d initial(u0[0], u0[1], u0[2]);
      const Eigen::Vector3d u = initial + ev.gradient(q, 3).transpose() * ce;
      normal2 += ds * n.dot(u) * n.dot(u);
      initial2 += ds * n.dot(initial) * n.dot(initial);
    }
  }
}

}  // namespace

void InitialWind::value(const double *x, double *u) const {
  const double g = logarithmic ? profile(*this, x[2], nullptr) : 1.0;
  for (int k = 0; k < 3; k++) u[k] = g * velocity[k];
}

double InitialWind::divergence(const double *x) const {
  if (!logarithmic) return 0.0;
  double derivative = 0.0;
  profile(*this, x[2], &derivative);
  return velocity[2] * derivative;
}

TerrainFace find_terrain(const igaparam_spline *spline) {
  double centres[18], images[18];
  for (int f = 0; f < 6; f++)
    for (int k = 0; k < 3; k++) centres[3 * f + k] = k == f / 2 ? double(f % 2) : 0.5;
  check(igaparam_spline_evaluate(spline, 6, centres, images, nullptr), "evaluate");
  int low = 0, high = 0;
  for (int f = 1; f < 6; f++) {
    if (images[3 * f + 2] < images[3 * low + 2]) low = f;
    if (images[3 * f + 2] > images[3 * high + 2]) high = f;
  }
  if (high / 2 != low / 2 || high == low)
    throw std::runtime_error("cannot tell the terrain: the lowest and highest faces of the map are not opposite");
  return TerrainFace{low / 2, low % 2};
}

double lowest_point(const igaparam_spline *spline, TerrainFace terrain, int n) {
  std::vector<double> params, images(3 * size_t(n + 1) * size_t(n + 1));
  for (int j = 0; j <= n; j++)
    for (int i = 0; i <= n; i++) {
      double p[3];
      p[terrain.axis] = double(terrain.side);
      p[(terrain.axis + 1) % 3] = double(i) / n;
      p[(terrain.axis + 2) % 3] = double(j) / n;
      params.insert(params.end(), p, p + 3);
    }
  check(igaparam_spline_evaluate(spline, params.size() / 3, params.data(), images.data(), nullptr), "evaluate");
  double lowest = HUGE_VAL;
  for (size_t i = 2; i < images.size(); i += 3) lowest = std::min(lowest, images[i]);
  return lowest;
}

WindSolution solve_wind(const igaparam_spline *spline, const InitialWind &wind, TerrainFace terrain, int threads) {
  WindSolution s;
  s.space = Space(spline);
  if (s.space.d != 3) throw std::runtime_error("the wind model needs a solid (a 3D map)");
  Integrands terms;
  terms.flux = [&wind](const double *x, double *g) {
    wind.value(x, g);
    for (int k = 0; k < 3; k++) g[k] = -g[k];
  };
  const System sys = assemble(s.space, terms, Reference::gauss(3, 5), threads);
  const uint8_t dirichlet = kAllFaces & uint8_t(~face_bit(terrain.axis, terrain.side));
  s.lambda = solve_dirichlet(s.space, sys, dirichlet, VectorXd::Zero(s.space.nb), true);
  double div2 = 0, change = 0, speed = 0, normal2 = 0, initial2 = 0;
  volume_checks(s, wind, threads, div2, change, speed);
  terrain_checks(s, wind, terrain, normal2, initial2);
  s.checks = {std::sqrt(div2), std::sqrt(normal2), std::sqrt(initial2), speed > 0.0 ? change / speed : change};
  return s;
}

std::vector<FieldSpec> wind_fields(const WindSolution &s, const InitialWind &wind) {
  auto lambda = [&s](const Element &el, const ElementValues &ev, int q, double *out) {
    out[0] = ev.values.col(q).dot(local_coefficients(el, s.lambda));
  };
  auto adjusted = [&s, &wind](const Element &el, const ElementValues &ev, int q, double *out) {
    wind.value(ev.points.col(q).data(), out);
    const Eigen::Vector3d g = ev.gradient(q, 3).transpose() * local_coefficients(el, s.lambda);
    for (int k = 0; k < 3; k++) out[k] += g(k);
  };
  auto initial = [&wind](const Element &, const ElementValues &ev, int q, double *out) {
    wind.value(ev.points.col(q).data(), out);
  };
  return {{"lambda", 1, lambda}, {"u", 3, adjusted}, {"u0", 3, initial}};
}

}  // namespace iga
