//! A boundary's points as combinations of its own control points: for B-spline and NURBS
//! curves and surfaces (weights fixed) the point at fixed parameters is `Σ_i R_i P_i`, linear
//! in the control points `P_i` with the rational basis values `R_i` as coefficients. This is
//! the last link of the sensitivities of a spline map to its boundary's control points.
//!
//! The control points are numbered through the curves or surfaces in the order the boundary
//! was made from (first all of the first one's, in its own order, then the next one's): a
//! corner shared by two curves, or an edge row shared by two surfaces, appears once per curve
//! or surface, and a point of the boundary on it depends on one of the copies only (a host
//! moves both together). Polylines (by chord length) and triangulated faces (by Floater's
//! map) are not linear in their vertices, and have no such weights.

use super::bspline::{BSplineCurve, BSplineSurface};
use super::curve::{Curve2, CurveKind};
use super::face::Face;
use super::loop2d::{BoundaryLoop2, Side};
use super::solid::SolidBoundary;
use crate::error::{Error, Result};

/// Normalises the homogeneous basis values `(i, N_i w_i)` of a rational map to `R_i`.
fn rational(mut values: Vec<(usize, f64)>, rational: bool) -> Vec<(usize, f64)> {
    if rational {
        let sum: f64 = values.iter().map(|v| v.1).sum();
        for v in &mut values {
            v.1 /= sum;
        }
    }
    values
}

impl BSplineCurve {
    /// The control points of the curve's point at `t` (clamped to the domain) and their
    /// (rational) basis values: the point is their weighted sum.
    pub fn basis_weights(&self, t: f64) -> Vec<(usize, f64)> {
        let p = self.degree();
        let (span, ders) = self.knot_vector().basis_derivs(t, 0);
        let w = self.weights();
        let values = (0..=p)
            .map(|j| {
                let i = span - p + j;
                (i, ders[0][j] * w.map_or(1.0, |w| w[i]))
            })
            .collect();
        rational(values, w.is_some())
    }
}

impl BSplineSurface {
    /// The control points (index `i + j n_u`) of the surface's point at `(u, v)` (clamped to
    /// the domain) and their (rational) basis values.
    pub fn basis_weights(&self, u: f64, v: f64) -> Vec<(usize, f64)> {
        let (ku, kv) = (self.knot_vector_u(), self.knot_vector_v());
        let (pu, pv) = (ku.degree(), kv.degree());
        let (su, du) = ku.basis_derivs(u, 0);
        let (sv, dv) = kv.basis_derivs(v, 0);
        let nu = ku.num_basis();
        let w = self.weights();
        let mut values = Vec::with_capacity((pu + 1) * (pv + 1));
        for (jb, &bv) in dv[0].iter().enumerate().take(pv + 1) {
            for (ib, &bu) in du[0].iter().enumerate().take(pu + 1) {
                let k = (su - pu + ib) + (sv - pv + jb) * nu;
                values.push((k, bu * bv * w.map_or(1.0, |w| w[k])));
            }
        }
        rational(values, w.is_some())
    }
}

impl Curve2 {
    /// Control points of the curve, `None` for a polyline.
    pub fn control_count(&self) -> Option<usize> {
        match self.kind() {
            CurveKind::Spline(c) => Some(c.bspline().num_control_points()),
            CurveKind::Polyline(_) => None,
        }
    }

    /// The control points of the point at `t ∈ [0,1]` and their basis values (see
    /// [`Curve2::eval`]), `None` for a polyline.
    pub fn basis_weights(&self, t: f64) -> Option<Vec<(usize, f64)>> {
        let CurveKind::Spline(c) = self.kind() else {
            return None;
        };
        let t = t.clamp(0.0, 1.0);
        let s = if self.is_reversed() { 1.0 - t } else { t };
        let (a, b) = c.bspline().domain();
        Some(c.bspline().basis_weights(a + s * (b - a)))
    }
}

/// The error of a boundary without control points.
fn no_controls(what: &str) -> Error {
    Error::invalid(format!(
        "the boundary has {what}, whose points are not linear in their vertices: derivatives \
         with respect to the boundary's control points need B-spline or NURBS curves or \
         surfaces (use those with respect to the T-mesh's boundary vertices)"
    ))
}

/// The first global index of each of `counts` (in list order).
fn offsets(counts: &[usize]) -> Vec<usize> {
    counts
        .iter()
        .scan(0, |next, &n| {
            let first = *next;
            *next += n;
            Some(first)
        })
        .collect()
}

impl BoundaryLoop2 {
    /// Control points of the four curves together, in the order the curves were given.
    pub fn control_count(&self) -> Result<usize> {
        Ok(self.control_offsets()?.1)
    }

    /// Per side, the global index of its curve's first control point, and their total.
    fn control_offsets(&self) -> Result<([usize; 4], usize)> {
        let mut counts = [0; 4];
        for side in Side::all() {
            let n = self
                .side(side)
                .control_count()
                .ok_or_else(|| no_controls("polylines"))?;
            counts[self.origin(side)] = n;
        }
        let first = offsets(&counts);
        Ok((
            Side::all().map(|side| first[self.origin(side)]),
            counts.iter().sum(),
        ))
    }

    /// The control points (global indices, see the module documentation) of the point of
    /// `side` at `t` ([`BoundaryLoop2::eval`]) and their basis values.
    pub fn control_weights(&self, side: Side, t: f64) -> Result<Vec<(usize, f64)>> {
        let (first, _) = self.control_offsets()?;
        let values = self
            .side(side)
            .basis_weights(t)
            .ok_or_else(|| no_controls("polylines"))?;
        let offset = first[side.index()];
        Ok(values.into_iter().map(|(i, w)| (offset + i, w)).collect())
    }
}

impl SolidBoundary {
    /// Per face, its surface and the global index of its first control point, and their total.
    fn control_offsets(&self) -> Result<([(&BSplineSurface, usize); 6], usize)> {
        let mut counts = [0; 6];
        for f in 0..6 {
            let Face::Spline(face) = self.face(f) else {
                return Err(no_controls("triangulated faces"));
            };
            let (nu, nv) = face.surface.num_control_points();
            counts[face.origin] = nu * nv;
        }
        let first = offsets(&counts);
        let faces = std::array::from_fn(|f| match self.face(f) {
            Face::Spline(face) => (&face.surface, first[face.origin]),
            Face::Mesh(_) => unreachable!("checked above"),
        });
        Ok((faces, counts.iter().sum()))
    }

    /// Control points of the six surfaces together, in the order the surfaces were given.
    pub fn control_count(&self) -> Result<usize> {
        Ok(self.control_offsets()?.1)
    }

    /// The control points (global indices) of the boundary point of the cube point `p`
    /// ([`SolidBoundary::eval`]) and their basis values.
    pub fn control_weights(&self, p: [f64; 3]) -> Result<Vec<(usize, f64)>> {
        let (faces, _) = self.control_offsets()?;
        let (f, a, b) = self.face_coordinates(p);
        let Face::Spline(face) = self.face(f) else {
            return Err(no_controls("triangulated faces"));
        };
        let (u, v) = face.parameters(a, b);
        let offset = faces[f].1;
        Ok(face
            .surface
            .basis_weights(u, v)
            .into_iter()
            .map(|(i, w)| (offset + i, w))
            .collect())
    }
}
