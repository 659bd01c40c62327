// series.h: the refinement series of igaparam_poisson: uniform refinement of the analysis
// space, and adaptive refinement driven by the residual indicator.

#ifndef IGAPARAM_IGA_SERIES_H
#define IGAPARAM_IGA_SERIES_H

#include "estimate.h"
#include "problems.h"
#include "space.h"

namespace iga {

/// The quadratures of a series: assembly, and errors (with second derivatives when the
/// indicator is wanted).
struct Rules {
  Reference assembly, error;
};

/// One solve of a series.
struct Step {
  double elements = 0, dofs = 0, h = 0, l2 = 0, h1 = 0, eta = 0, marked = 0, seconds = 0;
};

/// A series of solves, in order.
struct Series {
  std::vector<Step> steps;

  /// One figure of every step, e.g. column(&Step::h1).
  std::vector<double> column(double Step::*field) const;
};

/// The discrete solution on the current space of `spline`, with its errors (and indicators).
struct Solution {
  Space space;
  VectorXd c;
  ElementNorms norms;
  double seconds[4] = {0, 0, 0, 0};  // extraction, assembly, solve, errors
};

/// Solves the problem on the spline's space: Dirichlet values from the L2 projection of the
/// exact solution on the functions with a Greville point on the boundary, the interior ones
/// from the Galerkin system; then the errors and, with `estimator`, the indicators.
Solution solve_problem(const igaparam_spline *spline, const Problem &p, const Rules &rules, int threads,
                       bool estimator);

/// Options of a series.
struct SeriesOptions {
  int levels = 3;            // uniform: refinements after the first solve
  bool estimator = false;    // uniform: compute the indicator too
  double gamma = 0.5;        // adaptive: marking threshold η_e > γ max η
  int layers = 1;            // adaptive: neighbourhood of the marked elements refined with them
  double max_dofs = 2e4;     // adaptive: stop once a step has this many dofs
  int max_steps = 60;        // adaptive: at most this many solves
  int threads = 1;
  bool quiet = false;        // no table
};

/// The uniform series: solve, refine every element, `levels` times (the spline is refined in
/// place). Prints a table unless quiet.
Series uniform_series(igaparam_spline *spline, const Problem &p, const Rules &rules, const SeriesOptions &options,
                      Solution *last = nullptr);

/// The adaptive series: solve, mark η_e > γ max η, refine the marked elements with `layers`
/// layers of elements around them (see extend) and those the 2:1 balance needs, until max_dofs or max_steps (the spline is refined in place; the map
/// stays the same). Prints a table unless quiet.
Series adaptive_series(igaparam_spline *spline, const Problem &p, const Rules &rules, const SeriesOptions &options,
                       Solution *last = nullptr);

/// "[1, 2.5, 3]": a JSON list of numbers (NaN and infinities as null).
std::string json_list(const std::vector<double> &v);

/// A JSON number (NaN and infinities as null).
std::string json_number(double v);

}  // namespace iga

#endif  // IGAPARAM_IGA_SERIES_H
