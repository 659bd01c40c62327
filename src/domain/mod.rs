//! From a boundary to an optimized T-mesh parameterization of the interior (stages 2–3 of the
//! method): adapt a balanced quadtree/octree to the boundary, place the vertices (boundary ones on
//! the boundary, inner ones by transfinite interpolation), then untangle and smooth with the
//! optimizer; move the boundary of a built domain keeping its tree.

mod boundary_image;
mod budget;
mod build;
mod controls;
mod cube_map;
mod frame;
mod options;
mod planar;
mod polish;
mod refine;
mod relief;
mod repair;
mod sensitivity;
mod solid;
mod update;

pub use build::Domain;
pub use controls::BoundaryControls;
pub use cube_map::{transfinite, CubeMap};
pub use frame::Frame;
pub use options::{
    DomainOptions, DomainReport, StageSeconds, DEFAULT_MAX_CELLS, DEFAULT_MAX_TOTAL_SWEEPS,
};
pub use planar::{PlanarDomain, PlanarOptions, PlanarReport};
pub use solid::{SolidDomain, SolidOptions, SolidReport};
pub use update::{UpdateOptions, UpdateReport};
