//! Boundary input of the domain parameterization: B-spline curves and surfaces, G+Smo XML B-reps,
//! four-sided planar boundary loops (from B-splines or coastline polylines), closest-point
//! projection onto a boundary curve.

pub mod bspline;
mod crossing;
pub mod curve;
mod face;
pub mod gismo_xml;
pub mod loop2d;
mod solid;
pub mod trimesh;

pub use bspline::{BSplineCurve, BSplineSurface, KnotVector, Vec3};
pub use curve::{distance, Curve2, CurveKind, Point2, Polyline, Projection, SplineCurve2};
pub use gismo_xml::{
    parse_gismo_xml, read_gismo_curves, read_gismo_surfaces, read_gismo_xml, GismoGeometry,
};
pub use loop2d::{BoundaryLoop2, Coastline, LoopOptions, Side};
pub use solid::SolidBoundary;
pub use trimesh::{floater_parameterize, signed_areas, CubeFaces, TriMesh, CUBE_FACE_NAMES};

/// Checks per-axis scale factors: each must be finite and positive (an `InvalidArgument` error
/// naming the first bad one otherwise).
pub(crate) fn check_scale_factors(factors: Vec3) -> crate::error::Result<()> {
    match factors.iter().find(|f| !(f.is_finite() && **f > 0.0)) {
        Some(f) => Err(crate::error::Error::invalid(format!(
            "scale factors must be finite and positive, got {f} in {factors:?}"
        ))),
        None => Ok(()),
    }
}

/// Multiplies points stored one after another (`dim` coordinates each) by `factors`, axis by
/// axis, after [`check_scale_factors`]; nothing changes on an error.
pub(crate) fn scale_points(
    points: &mut [f64],
    dim: usize,
    factors: Vec3,
) -> crate::error::Result<()> {
    check_scale_factors(factors)?;
    for p in points.chunks_exact_mut(dim) {
        for (x, f) in p.iter_mut().zip(factors) {
            *x *= f;
        }
    }
    Ok(())
}
