//! Planar domains bounded by four curves.

use super::build::Domain;
use super::cube_map::CubeMap;
use super::options::{DomainOptions, DomainReport};
use crate::boundary::{BoundaryLoop2, Side};

impl CubeMap<2> for BoundaryLoop2 {
    fn boundary_point(&self, [u, v]: [f64; 2]) -> [f64; 2] {
        if u == 0.0 || u == 1.0 {
            self.eval(if u == 0.0 { Side::U0 } else { Side::U1 }, v)
        } else {
            self.eval(if v == 0.0 { Side::V0 } else { Side::V1 }, u)
        }
    }
}

/// A planar domain with its optimized T-mesh.
pub type PlanarDomain = Domain<2, BoundaryLoop2>;
/// Options of [`PlanarDomain::build`].
pub type PlanarOptions = DomainOptions;
/// What [`PlanarDomain::build`] did.
pub type PlanarReport = DomainReport;
