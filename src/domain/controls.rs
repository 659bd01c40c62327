//! The boundary vertices of a domain's T-mesh as linear combinations of its boundary's own
//! control points (B-spline and NURBS curves and surfaces): a boundary vertex sits at its
//! parameters' point on the boundary, fixed through [`Domain::update`], so its position is
//! `Σ_j R_j C_j` with the basis values `R_j` there. With the T-mesh's and the fit's
//! sensitivities this carries a host's change of its curves or surfaces to the spline's
//! control points.

use super::build::Domain;
use super::cube_map::CubeMap;
use crate::error::Result;

/// A boundary map whose points are linear in control points of its own.
pub trait BoundaryControls<const D: usize>: CubeMap<D> {
    /// Control points of the boundary, numbered through its curves or surfaces in the order
    /// it was made from; an error for a boundary without (polylines, triangulated faces).
    fn control_count(&self) -> Result<usize>;

    /// The control points of the image of `p` (a point of the boundary of \[0,1\]^d, as
    /// [`CubeMap::boundary_point`] takes it) and their basis values: the image is their
    /// weighted sum.
    fn control_weights(&self, p: [f64; D]) -> Result<Vec<(usize, f64)>>;
}

impl<const D: usize, B: BoundaryControls<D>> Domain<D, B> {
    /// Per boundary vertex of the T-mesh, the control points its position combines: triplets
    /// (vertex, control point, basis value), grouped by vertex in vertex order.
    pub fn boundary_control_weights(&self) -> Result<Vec<(usize, usize, f64)>> {
        let mut out = Vec::new();
        for (v, mut p) in self.mesh.parametric().into_iter().enumerate() {
            if !self.mesh.on_boundary(v) {
                continue;
            }
            if self.swapped {
                p.swap(0, 1);
            }
            let weights = self.boundary.control_weights(p)?;
            out.extend(weights.into_iter().map(|(j, w)| (v, j, w)));
        }
        Ok(out)
    }
}
