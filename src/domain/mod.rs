//! From a boundary to an optimized T-mesh parameterization of the interior (stages 2–3 of the
//! method): adapt a balanced quadtree to the boundary, place the vertices (boundary ones on the
//! curves, inner ones by the Coons patch), then untangle and smooth with the optimizer.

mod planar;

pub use planar::{PlanarDomain, PlanarOptions, PlanarReport};
