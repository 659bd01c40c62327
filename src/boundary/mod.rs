//! Boundary input of the domain parameterization: B-spline curves and surfaces, G+Smo XML B-reps,
//! four-sided planar boundary loops (from B-splines or coastline polylines), closest-point
//! projection onto a boundary curve.

pub mod bspline;

pub use bspline::{BSplineCurve, BSplineSurface, KnotVector, Vec3};
