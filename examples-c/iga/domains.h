// domains.h: the spline maps igaparam_poisson solves on: the built-in quarter annuli, or an
// input file (a boundary to build and fit, or a THB spline map to read).

#ifndef IGAPARAM_IGA_DOMAINS_H
#define IGAPARAM_IGA_DOMAINS_H

#include "space.h"

namespace iga {

/// How an input boundary becomes a spline map.
struct FitOptions {
  int threads = 1;
  double tolerance = 0.0;  // 0: the domain's default
  int max_level = -1;      // -1: the default
  int refits = 3;          // rebuilds with a ten times smaller tolerance while not certified
};

/// Builds the domain and fits its spline map. While the fitted map is not certified valid, the
/// domain is rebuilt with a tolerance ten times smaller (at most `refits` times); the solve
/// itself needs det J > 0 at the quadrature points only (checked during assembly).
SplinePtr fit(DomainPtr domain, const FitOptions &options);

/// The spline map of `input`: without one, the quarter annulus r ∈ [1, 2] from four polylines
/// (dim 2) or the thick quarter annulus as one cubic element (dim 3); a THB spline .xml
/// written by igaparam_spline_write_gismo is read; any other file (a B-rep, a coastline) or
/// folder (six faces) is built and fitted.
SplinePtr load(const std::string &input, int dim, const FitOptions &options);

/// The image of the parametric centre (½, ..., ½): a point inside the domain (d values).
std::array<double, 3> centre_point(const igaparam_spline *spline);

}  // namespace iga

#endif  // IGAPARAM_IGA_DOMAINS_H
