// problems.cpp: exact solutions, in the unit coordinates of the domain's bounding box.

#include "problems.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace iga {

namespace {

constexpr double kPi = 3.14159265358979323846;

// u = 1 + x - 2y (+ 3z).
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

// u = sin(πx) sin(πy) exp(x/2).
Problem poisson_2d() {
  Problem p;
  p.name = "poisson";
  p.u = [](const double *x) { return std::sin(kPi * x[0]) * std::sin(kPi * x[1]) * std::exp(0.5 * x[0]); };
  p.grad = [](const double *x, double *g) {
    const double e = std::exp(0.5 * x[0]), sx = std::sin(kPi * x[0]), cx = std::cos(kPi * x[0]);
    const double sy = std::sin(kPi * x[1]), cy = std::cos(kPi * x[1]);
    g[0] = (kPi * cx + 0.5 * sx) * sy * e;
    g[1] = kPi * sx * cy * e;
  };
  p.f = [](const double *x) {
    const double e = std::exp(0.5 * x[0]), sx = std::sin(kPi * x[0]), cx = std::cos(kPi * x[0]);
    return -((0.25 - 2.0 * kPi * kPi) * sx + kPi * cx) * std::sin(kPi * x[1]) * e;
  };
  return p;
}

double distance(const double *x, const std::array<double, 3> &c, int d, double *unit) {
  double r2 = 0.0;
  for (int k = 0; k < d; k++) r2 += (x[k] - c[k]) * (x[k] - c[k]);
  const double r = std::sqrt(r2);
  for (int k = 0; k < d; k++) unit[k] = (x[k] - c[k]) / r;
  return r;
}

// A radial solution u(r), r = |x - c|, of -Δu - κ(r)² u = f: f = -(u'' + (d-1) u'/r) - κ² u.
struct Radial {
  std::array<double, 3> centre;
  int d;
  std::function<double(double)> u, du, d2u, kappa2;
};

Problem radial_problem(const std::string &name, const Radial &rad) {
  Problem p;
  p.name = name;
  p.u = [rad](const double *x) {
    double n[3];
    return rad.u(distance(x, rad.centre, rad.d, n));
  };
  p.grad = [rad](const double *x, double *g) {
    double n[3];
    const double du = rad.du(distance(x, rad.centre, rad.d, n));
    for (int k = 0; k < rad.d; k++) g[k] = du * n[k];
  };
  p.f = [rad](const double *x) {
    double n[3];
    const double r = distance(x, rad.centre, rad.d, n);
    return -(rad.d2u(r) + (rad.d - 1) * rad.du(r) / r) - (rad.kappa2 ? rad.kappa2(r) * rad.u(r) : 0.0);
  };
  if (rad.kappa2)
    p.kappa2 = [rad](const double *x) {
      double n[3];
      return rad.kappa2(distance(x, rad.centre, rad.d, n));
    };
  return p;
}

// u = arctan(α(r - r0)).
Problem arctan_layer(const std::string &name, int d, std::array<double, 3> centre, double alpha, double r0) {
  Radial rad{centre, d, nullptr, nullptr, nullptr, nullptr};
  rad.u = [=](double r) { return std::atan(alpha * (r - r0)); };
  rad.du = [=](double r) {
    const double t = alpha * (r - r0);
    return alpha / (1.0 + t * t);
  };
  rad.d2u = [=](double r) {
    const double t = alpha * (r - r0);
    return -2.0 * alpha * alpha * t / ((1.0 + t * t) * (1.0 + t * t));
  };
  return radial_problem(name, rad);
}

// -Δu - κ² u = f with u = sin(1/s), s = α + r, κ = 1/s², α = 1/(4π): u' = -cos(1/s)/s²,
// u'' = (2 cos(1/s)/s³ - sin(1/s)/s⁴), so f = cos(1/s) ((d-1)/(r s²) - 2/s³).
Problem helmholtz(int d, std::array<double, 3> centre) {
  const double alpha = 1.0 / (4.0 * kPi);
  Radial rad{centre, d, nullptr, nullptr, nullptr, nullptr};
  rad.u = [=](double r) { return std::sin(1.0 / (alpha + r)); };
  rad.du = [=](double r) {
    const double s = alpha + r;
    return -std::cos(1.0 / s) / (s * s);
  };
  rad.d2u = [=](double r) {
    const double s = alpha + r;
    return 2.0 * std::cos(1.0 / s) / (s * s * s) - std::sin(1.0 / s) / (s * s * s * s);
  };
  rad.kappa2 = [=](double r) {
    const double s = alpha + r;
    return 1.0 / (s * s * s * s);
  };
  return radial_problem("helmholtz", rad);
}

// The problem p written in ξ = (x - origin) / scale, in x: u(x) = p.u(ξ), ∇u = ∇_ξ p.u / scale,
// f = p.f / scale², κ² = p.κ² / scale².
Problem placed(const Problem &p, int d, const std::array<double, 3> &origin, double scale) {
  auto unit = [=](const double *x, double *xi) {
    for (int k = 0; k < d; k++) xi[k] = (x[k] - origin[k]) / scale;
  };
  Problem out;
  out.name = p.name;
  out.u = [=](const double *x) {
    double xi[3];
    unit(x, xi);
    return p.u(xi);
  };
  out.grad = [=](const double *x, double *g) {
    double xi[3];
    unit(x, xi);
    p.grad(xi, g);
    for (int k = 0; k < d; k++) g[k] /= scale;
  };
  out.f = [=](const double *x) {
    double xi[3];
    unit(x, xi);
    return p.f(xi) / (scale * scale);
  };
  if (p.kappa2)
    out.kappa2 = [=](const double *x) {
      double xi[3];
      unit(x, xi);
      return p.kappa2(xi) / (scale * scale);
    };
  return out;
}

// The 3D Poisson layer of an input domain, in ξ: centre a quarter of the box beyond its lower
// corner, the layer through the box's centre, α = 10 L / diagonal.
Problem poisson_3d_in_box(const Placement &pl, double scale) {
  std::array<double, 3> centre{}, middle{};
  double diagonal = 0.0, r0 = 0.0;
  for (int k = 0; k < 3; k++) {
    const double extent = (pl.box[3 + k] - pl.box[k]) / scale;
    centre[k] = -0.25 * extent;
    middle[k] = 0.5 * extent;
    diagonal += extent * extent;
    r0 += (middle[k] - centre[k]) * (middle[k] - centre[k]);
  }
  return arctan_layer("poisson", 3, pl.centre.value_or(centre), pl.alpha.value_or(10.0 / std::sqrt(diagonal)),
                      pl.r0.value_or(std::sqrt(r0)));
}

}  // namespace

Problem make_problem(const std::string &name, const Placement &pl) {
  const int d = pl.d;
  std::array<double, 3> origin{0.0, 0.0, 0.0};
  double scale = 1.0;
  const bool input = !pl.box.empty();
  if (input) {
    scale = 0.0;
    for (int k = 0; k < d; k++) {
      origin[k] = pl.box[k];
      scale = std::max(scale, pl.box[d + k] - pl.box[k]);
    }
    if (!(scale > 0.0)) throw std::invalid_argument("the domain's bounding box is empty");
  }
  Problem p;
  if (name == "poisson") {
    if (d == 2)
      p = poisson_2d();
    else if (input)
      p = poisson_3d_in_box(pl, scale);
    else
      p = arctan_layer("poisson", d, pl.centre.value_or(std::array<double, 3>{-0.5, -0.5, -0.5}),
                       pl.alpha.value_or(5.0), pl.r0.value_or(2.0));
  } else if (name == "helmholtz") {
    std::array<double, 3> centre{0.6, 0.6, -0.4};
    if (input && pl.inside)
      for (int k = 0; k < d; k++) centre[k] = ((*pl.inside)[k] - origin[k]) / scale;
    p = helmholtz(d, pl.centre.value_or(centre));
  } else if (name == "wavefront") {
    p = arctan_layer("wavefront", d, pl.centre.value_or(std::array<double, 3>{0.0, 0.0, 0.0}),
                     pl.alpha.value_or(200.0), pl.r0.value_or(0.6));
  } else if (name == "linear") {
    p = linear(d);
  } else {
    throw std::invalid_argument("unknown problem '" + name + "' (poisson, helmholtz, wavefront or linear)");
  }
  return input ? placed(p, d, origin, scale) : p;
}

double source_residual(const Problem &p, int d, const std::vector<double> &points) {
  const double h = 1e-4;
  double worst = 0.0;
  for (size_t i = 0; i + d <= points.size(); i += d) {
    double x[3], y[3];
    std::copy(points.begin() + i, points.begin() + i + d, x);
    const double u0 = p.u(x);
    double lap = 0.0;
    for (int k = 0; k < d; k++) {
      std::copy(x, x + d, y);
      y[k] = x[k] + h;
      const double up = p.u(y);
      y[k] = x[k] - h;
      lap += (up - 2.0 * u0 + p.u(y)) / (h * h);
    }
    const double fd = -lap - (p.kappa2 ? p.kappa2(x) * u0 : 0.0);
    const double f = p.f(x);
    worst = std::max(worst, std::abs(fd - f) / std::max(1.0, std::abs(f)));
  }
  return worst;
}

}  // namespace iga
