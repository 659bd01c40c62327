//! Planar domains bounded by four curves.

use super::build::Domain;
use super::controls::BoundaryControls;
use super::cube_map::CubeMap;
use super::options::{DomainOptions, DomainReport};
use crate::boundary::{BoundaryLoop2, Side};
use crate::error::Result;

/// The side a point of the unit square's boundary is evaluated on, and its parameter there.
fn side_of([u, v]: [f64; 2]) -> (Side, f64) {
    if u == 0.0 || u == 1.0 {
        (if u == 0.0 { Side::U0 } else { Side::U1 }, v)
    } else {
        (if v == 0.0 { Side::V0 } else { Side::V1 }, u)
    }
}

impl CubeMap<2> for BoundaryLoop2 {
    fn boundary_point(&self, p: [f64; 2]) -> [f64; 2] {
        let (side, t) = side_of(p);
        self.eval(side, t)
    }
}

impl BoundaryControls<2> for BoundaryLoop2 {
    fn control_count(&self) -> Result<usize> {
        BoundaryLoop2::control_count(self)
    }

    fn control_weights(&self, p: [f64; 2]) -> Result<Vec<(usize, f64)>> {
        let (side, t) = side_of(p);
        BoundaryLoop2::control_weights(self, side, t)
    }
}

/// A planar domain with its optimized T-mesh.
pub type PlanarDomain = Domain<2, BoundaryLoop2>;
/// Options of [`PlanarDomain::build`].
pub type PlanarOptions = DomainOptions;
/// What [`PlanarDomain::build`] did.
pub type PlanarReport = DomainReport;
