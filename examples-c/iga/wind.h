// wind.h: the mass-consistent wind model on a spline map of a block of air above a terrain.
// Given an initial wind u0, λ solves −Δλ = ∇·u0 in Ω, −n·∇λ = n·u0 on the terrain, λ = 0 on the
// lid and the walls; the adjusted wind u = u0 + ∇λ has ∇·u = 0 and n·u = 0 on the terrain. The
// weak form needs no boundary term: ∫ ∇λ·∇v = −∫ u0·∇v for every v vanishing on the lid and
// the walls.

#ifndef IGAPARAM_IGA_WIND_H
#define IGAPARAM_IGA_WIND_H

#include "sample.h"
#include "space.h"

namespace iga {

/// The initial wind: constant, or a logarithmic profile in the height h above the ground,
/// u0 = velocity · ln((h + z0)/z0) / ln((h_ref + z0)/z0) (h clamped at 0), which is
/// `velocity` at the reference height.
struct InitialWind {
  std::array<double, 3> velocity{10.0, 0.0, 0.0};
  bool logarithmic = false;
  double roughness = 0.1;         // z0, in the map's length unit
  double reference_height = 1.0;  // h_ref, in the map's length unit
  double ground = 0.0;            // the height z where h = 0

  /// u0 at x (3 values).
  void value(const double *x, double *u) const;
  /// ∇·u0 at x.
  double divergence(const double *x) const;
};

/// The face of [0,1]^3 (axis, side) the map sends onto the terrain.
struct TerrainFace {
  int axis = 2, side = 0;
};

/// The terrain face: the face whose centre's image is lowest; the lid, the face whose centre's
/// image is highest, must be the opposite one (else std::runtime_error).
TerrainFace find_terrain(const igaparam_spline *spline);

/// The lowest z of the map on an n × n grid of the terrain face.
double lowest_point(const igaparam_spline *spline, TerrainFace terrain, int n);

/// What the adjusted wind achieves: ‖∇·u‖_{L2(Ω)}, ‖n·u‖_{L2(terrain)}, the initial wind's
/// ‖n·u0‖_{L2(terrain)}, and max |u − u0| / max |u0| at the quadrature points.
struct WindChecks {
  double divergence = 0, normal = 0, normal_initial = 0, max_change = 0;
};

/// The discrete λ on the spline's current space and its checks.
struct WindSolution {
  Space space;
  VectorXd lambda;
  WindChecks checks;
};

/// Assembles and solves the λ problem (Gauss quadrature with 5 points per direction, which
/// integrates −∫ u0·∇v exactly for a constant u0: with dx = det J du, ∇v dx = adj(J)ᵀ ∇_u v du
/// is a polynomial of degree at most 9 per direction), then the checks.
WindSolution solve_wind(const igaparam_spline *spline, const InitialWind &wind, TerrainFace terrain, int threads);

/// The fields `lambda`, `u` (adjusted wind) and `u0` for sampling.
std::vector<FieldSpec> wind_fields(const WindSolution &solution, const InitialWind &wind);

}  // namespace iga

#endif  // IGAPARAM_IGA_WIND_H
