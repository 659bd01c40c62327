//! Boundary input of the domain parameterization: B-spline curves and surfaces, G+Smo XML B-reps,
//! four-sided planar boundary loops (from B-splines or coastline polylines), closest-point
//! projection onto a boundary curve.

pub mod bspline;
mod controls;
pub(crate) mod crossing;
pub mod curve;
mod face;
pub mod gismo_xml;
pub mod loop2d;
mod scale;
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
