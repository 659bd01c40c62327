//! Spline maps of \[0,1\]^d over the T-mesh: cubic truncated hierarchical B-splines (THB) on the
//! tree levels, their Bézier extraction, Greville interpolation of the T-mesh's piecewise
//! quadratic map, queries (values, Jacobians, inverse), h-refinement, certified validity of the
//! Jacobian determinant, and output (`.vtu` samples, G+Smo XML).
//!
//! Everything past the basis construction works through the [`SplineSpace`] trait, which gives
//! per element the non-zero functions and the Bézier extraction operator `C^e` (`N^e = C^e B^e`
//! with `B^e` the tensor Bernstein polynomials of degree 3 on the element), so another basis over
//! the same elements can be added by implementing it.

mod adapt;
pub mod bernstein;
mod boundary_distance;
mod checked;
mod control;
mod fit;
mod fit_options;
mod gismo;
mod jacobian;
mod map;
mod piece;
mod quality_bound;
mod quasi;
mod refit;
mod sensitivity;
mod smooth;
mod space;
mod thb;
mod tmesh_map;
mod untangle;
mod validity;
mod vtu;

pub use adapt::{adapt, AdaptOptions, AdaptReport, AdaptRound};
pub use fit::{FitReport, FitStages};
pub use fit_options::{FitChoice, FitOptions, FitProgress, FitStage};
pub use gismo::{read_gismo_thb, write_gismo_thb};
pub use map::{InverseMap, SplineMap};
pub use quality_bound::{QualityBound, QualityBoundOptions, MAX_BOUND_DEPTH, MAX_SOLID_DEPTH};
pub use refit::{FitRecord, FitRule};
pub use smooth::SmoothReport;
pub use space::{BasisValues, SplineSpace};
pub use thb::ThbSpace;
pub use tmesh_map::QuadraticMap;
pub use untangle::{UntangleOptions, UntangleReport};
pub(crate) use validity::HISTOGRAM_BINS;
pub use validity::{ElementValidity, ValidityOptions, ValidityReport};
