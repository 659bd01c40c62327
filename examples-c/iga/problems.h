// problems.h: exact solutions of −Δu − κ(x)² u = f for the convergence studies of
// igaparam_poisson, placed and scaled by the domain's bounding box.

#ifndef IGAPARAM_IGA_PROBLEMS_H
#define IGAPARAM_IGA_PROBLEMS_H

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace iga {

/// An exact solution: value, gradient (d values), right-hand side f and κ² (empty for
/// Poisson).
struct Problem {
  std::string name;
  std::function<double(const double *)> u;
  std::function<void(const double *, double *)> grad;
  std::function<double(const double *)> f;
  std::function<double(const double *)> kappa2;
};

/// How a problem is placed on a domain of dimension d. For an input domain `box` is its
/// bounding box (lower corner then upper corner, d values each) and every problem is written in
/// the box's unit coordinates ξ = (x − lower corner) / L, L the box's largest side (so that
/// the same problem sits the same way on the domain whatever its units); for the built-in
/// domains (`box` empty) ξ = x. `centre` and `alpha`, `r0` override a problem's defaults (in
/// ξ); `inside` (in x) is a point of the domain, the default centre of the Helmholtz problem on
/// an input domain.
struct Placement {
  int d = 2;
  std::vector<double> box;
  std::optional<std::array<double, 3>> centre, inside;
  std::optional<double> alpha, r0;
};

/// The problems, by name:
/// - `poisson`: 2D u = sin(πξ) sin(πη) exp(ξ/2); 3D u = arctan(α(r − r0)), for an input domain
///   its centre a quarter of the box beyond its lower corner along each axis, the layer through
///   the box's centre, α = 10 L / diagonal (the built-in thick annulus: centre (−½, −½, −½),
///   α = 5, r0 = 2);
/// - `helmholtz`: −Δu − k² u = f with u = sin(1/(α + r)), α = 1/(4π), k = 1/(α + r)², centre
///   (0.6, 0.6, −0.4) on the built-in domains (outside them), on an input domain `inside`
///   (a gradient singularity inside the domain);
/// - `wavefront`: u = arctan(α(r − r0)), α = 200, r0 = 0.6, centre ξ = 0 (the box's lower corner);
/// - `linear`: u = 1 + ξ − 2η (+ 3ζ), reproduced exactly by every isoparametric space.
/// Throws std::invalid_argument for another name.
Problem make_problem(const std::string &name, const Placement &placement);

/// Largest relative difference between f and −Δu − κ² u by central differences (step 1e-4)
/// at the given points (d coordinates each).
double source_residual(const Problem &p, int d, const std::vector<double> &points);

}  // namespace iga

#endif  // IGAPARAM_IGA_PROBLEMS_H
