//! Solids bounded by six surfaces mapped onto the faces of the unit cube.

use super::build::Domain;
use super::controls::BoundaryControls;
use super::cube_map::CubeMap;
use super::options::{DomainOptions, DomainReport};
use crate::boundary::SolidBoundary;
use crate::error::Result;

impl CubeMap<3> for SolidBoundary {
    fn boundary_point(&self, p: [f64; 3]) -> [f64; 3] {
        self.eval(p)
    }
}

impl BoundaryControls<3> for SolidBoundary {
    fn control_count(&self) -> Result<usize> {
        SolidBoundary::control_count(self)
    }

    fn control_weights(&self, p: [f64; 3]) -> Result<Vec<(usize, f64)>> {
        SolidBoundary::control_weights(self, p)
    }
}

/// A solid with its optimized T-mesh.
pub type SolidDomain = Domain<3, SolidBoundary>;
/// Options of [`SolidDomain::build`].
pub type SolidOptions = DomainOptions;
/// What [`SolidDomain::build`] did.
pub type SolidReport = DomainReport;
