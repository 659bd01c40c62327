//! Sensitivities of a spline map's control points to its domain's boundary: with the fit rule
//! fixed the control points are `P = A X + c` (see [`refit`](super::refit)), `X` the T-mesh's
//! vertex positions and `c` a fixed untangling correction, and at the Newton polish's
//! stationary point the T-mesh follows its boundary vertices `X_b` by the implicit function
//! theorem ([`Domain::boundary_tangent`]). So
//!
//! - tangent: `dP = A (dX/dX_b) dX_b`, the rule applied to the T-mesh's tangent motion;
//! - adjoint: `dJ/dX_b = (dX/dX_b)ᵀ Aᵀ ∂J/∂P`, with `Aᵀ = Eᵀ Rᵀ`: `Rᵀ` the transposed rule on
//!   the values at the fit's points (a solve with the transposed collocation matrix, or with
//!   the normal matrix and the basis values at the least-squares points), `Eᵀ` the T-mesh
//!   map's coefficients at those points ([`QuadraticMap::vertex_weights`]) scattered to the
//!   vertices.
//!
//! The quasi-interpolant's transpose is not provided (its adjoint is refused; its tangent is
//! given), nor the derivative of an untangling: a map whose last fit or refit untangled is
//! refused until a refit leaves the correction as it is.

use super::fit::{
    collocation_entries, elements_of, least_squares_layout, least_squares_points, normal_equations,
};
use super::refit::relation_is_same;
use super::{FitRecord, FitRule, QuadraticMap, SplineMap, SplineSpace, ThbSpace};
use crate::domain::{BoundaryControls, CubeMap, Domain};
use crate::error::{check_finite, Error, Result};
use crate::sparse::SparseSolver;
use crate::tmesh::TMesh;

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// `A dX`: the control points the rule `rule` gives for the T-mesh `mesh` with vertex
    /// positions `dx` (the map is linear in them). The space must be the T-mesh's.
    pub fn rule_tangent(
        &self,
        mesh: &TMesh<D>,
        rule: FitRule,
        dx: &[[f64; D]],
    ) -> Result<Vec<[f64; D]>> {
        relation_is_same(self.space.tree(), mesh.tree())?;
        let source = QuadraticMap::new(mesh, dx)?;
        let (map, _) = Self::fit_by_rule(self.space.clone(), rule, |x| source.eval(x))?;
        Ok(map.control)
    }

    /// `Aᵀ w`: the partial derivatives with respect to the T-mesh's vertex positions of a
    /// scalar whose derivatives with respect to the control points are `w` (one point per
    /// basis function), through the rule `rule` (see the module documentation).
    pub fn rule_adjoint(
        &self,
        mesh: &TMesh<D>,
        rule: FitRule,
        w: &[[f64; D]],
    ) -> Result<Vec<[f64; D]>> {
        relation_is_same(self.space.tree(), mesh.tree())?;
        if w.len() != self.basis_count() {
            return Err(Error::invalid(format!(
                "{} points for {} control points",
                w.len(),
                self.basis_count()
            )));
        }
        let zero = vec![[0.0; D]; mesh.vertex_count()];
        // The map's coefficients do not depend on the positions it is made with.
        let weights = QuadraticMap::new(mesh, &zero)?;
        let mut out = zero.clone();
        let mut scatter = |x: [f64; D], y: [f64; D]| -> Result<()> {
            let terms = weights
                .vertex_weights(x)
                .ok_or_else(|| Error::invalid(format!("fit point {x:?} outside [0,1]^d")))?;
            for (v, c) in terms {
                for k in 0..D {
                    out[v][k] += c * y[k];
                }
            }
            Ok(())
        };
        match rule {
            FitRule::Interpolation => self.collocation_adjoint(w, &mut scatter)?,
            FitRule::LeastSquares => self.least_squares_adjoint(w, &mut scatter)?,
            FitRule::QuasiInterpolation => {
                return Err(Error::invalid(
                    "the adjoint of a quasi-interpolation fit is not provided (its tangent is)",
                ))
            }
        }
        Ok(out)
    }

    /// `G⁻ᵀ w` at the interpolation points, passed to `scatter(point, value)`.
    fn collocation_adjoint(
        &self,
        w: &[[f64; D]],
        scatter: &mut dyn FnMut([f64; D], [f64; D]) -> Result<()>,
    ) -> Result<()> {
        let space = &self.space;
        let points = space.interpolation_points();
        let elements = elements_of(space, &points)?;
        let values: Vec<Vec<f64>> = points
            .iter()
            .zip(&elements)
            .map(|(&x, &e)| space.values_on(e, x))
            .collect();
        let rows: Vec<&[f64]> = values.iter().map(|v| &v[..]).collect();
        let transposed: Vec<_> = collocation_entries(space, &elements, &rows)
            .into_iter()
            .map(|(p, i, v)| (i, p, v))
            .collect();
        let lu = SparseSolver::lu(space.basis_count(), &transposed)?;
        let mut y = w.to_vec();
        lu.solve(&mut y);
        check_finite("adjoint values", y.as_flattened())?;
        for (&x, &yp) in points.iter().zip(&y) {
            scatter(x, yp)?;
        }
        Ok(())
    }

    /// `B N⁻¹ w` at the least-squares points (`N = BᵀB` the normal matrix), passed to
    /// `scatter(point, value)`; a point of several elements' lists counts once per list, as
    /// in the fit.
    fn least_squares_adjoint(
        &self,
        w: &[[f64; D]],
        scatter: &mut dyn FnMut([f64; D], [f64; D]) -> Result<()>,
    ) -> Result<()> {
        let space = &self.space;
        let (points_of, blocks) = least_squares_layout(space)?;
        let zero = |_: [f64; D]| Some([0.0; D]);
        let (normal, _) = normal_equations(space, &points_of, &blocks, &zero)?;
        let llt = normal.cholesky()?;
        let mut z = w.to_vec();
        llt.solve(&mut z);
        check_finite("adjoint values", z.as_flattened())?;
        for (e, functions) in blocks.iter().enumerate() {
            for x in least_squares_points(space, &points_of, e) {
                let values = space.values_on(e, x);
                let mut y = [0.0; D];
                for (&i, &b) in functions.iter().zip(&values) {
                    for k in 0..D {
                        y[k] += b * z[i][k];
                    }
                }
                scatter(x, y)?;
            }
        }
        Ok(())
    }

    /// The tangent product of the control points: their first-order motion for a motion
    /// `boundary_motion` of the domain's boundary vertices (one point per T-mesh vertex,
    /// physical; entries at inner vertices are ignored), through the T-mesh's optimum and the
    /// fit rule of `record`. Needs the conditions of [`Domain::boundary_tangent`] and a map
    /// whose last fit or refit did not untangle ([`FitRecord::differentiable`]), in the
    /// T-mesh's own space.
    pub fn boundary_tangent<B: CubeMap<D>>(
        &self,
        domain: &Domain<D, B>,
        record: &FitRecord,
        threads: usize,
        boundary_motion: &[[f64; D]],
    ) -> Result<Vec<[f64; D]>> {
        check_differentiable(record)?;
        let motion = domain.boundary_tangent(threads, boundary_motion)?;
        self.rule_tangent(domain.mesh(), record.rule, &motion)
    }

    /// The adjoint product of the control points: the total derivative, with respect to the
    /// domain's boundary vertices (one point per T-mesh vertex, 0 at inner ones), of a scalar
    /// `J` of the control points given `dj_dp = ∂J/∂P` (one point per basis function). The
    /// transpose of [`SplineMap::boundary_tangent`], with its conditions; the rule must not be
    /// quasi-interpolation.
    pub fn boundary_adjoint<B: CubeMap<D>>(
        &self,
        domain: &Domain<D, B>,
        record: &FitRecord,
        threads: usize,
        dj_dp: &[[f64; D]],
    ) -> Result<Vec<[f64; D]>> {
        check_differentiable(record)?;
        check_finite("dj_dp", dj_dp.as_flattened())?;
        let dj_dx = self.rule_adjoint(domain.mesh(), record.rule, dj_dp)?;
        domain.boundary_adjoint(threads, &dj_dx)
    }
}

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// The tangent product with respect to the boundary's own control points: the first-order
    /// motion of the control points for a motion `dc` of the boundary's control points (one
    /// point per [`BoundaryControls::control_count`], in the order of the curves or surfaces
    /// the boundary was made from). The boundary vertices move by their basis values
    /// ([`Domain::boundary_control_weights`]); then as [`SplineMap::boundary_tangent`].
    pub fn control_tangent<B: BoundaryControls<D>>(
        &self,
        domain: &Domain<D, B>,
        record: &FitRecord,
        threads: usize,
        dc: &[[f64; D]],
    ) -> Result<Vec<[f64; D]>> {
        check_controls(domain, dc.len())?;
        check_finite("dc", dc.as_flattened())?;
        let mut motion = vec![[0.0; D]; domain.mesh().vertex_count()];
        for (v, j, w) in domain.boundary_control_weights()? {
            for k in 0..D {
                motion[v][k] += w * dc[j][k];
            }
        }
        self.boundary_tangent(domain, record, threads, &motion)
    }

    /// The adjoint product with respect to the boundary's own control points: the total
    /// derivative of a scalar `J` of the spline's control points, given `dj_dp = ∂J/∂P`, with
    /// respect to each of the boundary's control points; the transpose of
    /// [`SplineMap::control_tangent`].
    pub fn control_adjoint<B: BoundaryControls<D>>(
        &self,
        domain: &Domain<D, B>,
        record: &FitRecord,
        threads: usize,
        dj_dp: &[[f64; D]],
    ) -> Result<Vec<[f64; D]>> {
        let count = domain.boundary().control_count()?;
        let weights = domain.boundary_control_weights()?;
        let total = self.boundary_adjoint(domain, record, threads, dj_dp)?;
        let mut out = vec![[0.0; D]; count];
        for (v, j, w) in weights {
            for k in 0..D {
                out[j][k] += w * total[v][k];
            }
        }
        Ok(out)
    }
}

/// Checks `n` points against the boundary's control points.
fn check_controls<const D: usize, B: BoundaryControls<D>>(
    domain: &Domain<D, B>,
    n: usize,
) -> Result<()> {
    let count = domain.boundary().control_count()?;
    if n != count {
        return Err(Error::invalid(format!(
            "{n} points for the boundary's {count} control points"
        )));
    }
    Ok(())
}

/// Refuses a map whose control points are not the linear rule's (plus a fixed correction).
fn check_differentiable(record: &FitRecord) -> Result<()> {
    if record.differentiable {
        return Ok(());
    }
    Err(Error::invalid(
        "no sensitivities of the control points: the last fit or refit untangled the map, a \
         non-linear step whose derivative is not provided (one more refit, to the same \
         T-mesh or an updated one, carries its correction as a constant)",
    ))
}
