//! The optimized T-mesh as a function of its boundary vertices: at the stationary point the
//! Newton polish leaves (a build or update with `stationarity_tolerance > 0`), the inner
//! vertices `X_f` satisfy `∇_f F(X_f, X_b) = 0`, so `dX_f/dX_b = −H_ff⁻¹ H_fb` (implicit
//! function theorem, the operator of [`crate::optimize::implicit`]). The tangent product moves
//! every vertex for a motion of the boundary vertices, the adjoint product is its transpose.
//!
//! The products are taken in physical coordinates: the frame of the optimization is the
//! build's and stays fixed through updates, so it is a constant diagonal scaling. They need a
//! T-mesh whose boundary vertices all sit at their points on the boundary: a vertex the seam
//! relief moved off it follows a non-linear rule whose derivative is not provided.

use std::sync::Arc;

use rayon::ThreadPool;

use super::build::Domain;
use super::cube_map::CubeMap;
use crate::error::{check_finite, Error, Result};
use crate::optimize::blocks::BlockLayout;
use crate::optimize::global::GlobalObjective;
use crate::optimize::implicit::EXACT;
use crate::optimize::solver::{HessianSolver, SolverSetup};
use crate::optimize::stationary::scaled_gradient_norm;

/// Largest distance, in frame coordinates, between a boundary vertex and its point on the
/// boundary for the vertex to count as on it (round-off of the placement).
const ON_BOUNDARY: f64 = 1e-12;

impl<const D: usize, B: CubeMap<D>> Domain<D, B> {
    /// The first-order motion of every vertex for a motion `boundary_motion` of the boundary
    /// vertices (one point per vertex, physical; entries at inner vertices are ignored): the
    /// given motion at boundary vertices, `−H_ff⁻¹ H_fb` of it at inner ones. Needs the
    /// stationary point of a build or update with `stationarity_tolerance > 0` and no seam
    /// relief offset (see the module documentation); else an error says which.
    pub fn boundary_tangent(
        &self,
        threads: usize,
        boundary_motion: &[[f64; D]],
    ) -> Result<Vec<[f64; D]>> {
        self.check_vertex_values("boundary_motion", boundary_motion)?;
        let pool = crate::threads::pool(threads)?;
        let solver = self.stationary_solver(&pool)?;
        let framed: Vec<[f64; D]> = boundary_motion
            .iter()
            .enumerate()
            .map(|(v, m)| match self.mesh.on_boundary(v) {
                true => std::array::from_fn(|k| m[k] / self.frame.extent[k]),
                false => [0.0; D],
            })
            .collect();
        let motion = solver.tangent(&pool, &framed, EXACT)?;
        Ok(motion
            .iter()
            .map(|m| std::array::from_fn(|k| m[k] * self.frame.extent[k]))
            .collect())
    }

    /// The total derivative of a scalar `J` of the vertex positions with respect to the
    /// boundary vertices, given its partial derivatives `dj_dx` (one per vertex, physical):
    /// `∂J/∂X_b − H_bf H_ff⁻¹ ∂J/∂X_f` at boundary vertices, 0 at inner ones. The transpose of
    /// [`Domain::boundary_tangent`], with its conditions.
    pub fn boundary_adjoint(&self, threads: usize, dj_dx: &[[f64; D]]) -> Result<Vec<[f64; D]>> {
        self.check_vertex_values("dj_dx", dj_dx)?;
        let pool = crate::threads::pool(threads)?;
        let solver = self.stationary_solver(&pool)?;
        let framed: Vec<[f64; D]> = dj_dx
            .iter()
            .map(|w| std::array::from_fn(|k| w[k] * self.frame.extent[k]))
            .collect();
        let total = solver.adjoint(&pool, &framed)?;
        Ok(total
            .iter()
            .map(|g| std::array::from_fn(|k| g[k] / self.frame.extent[k]))
            .collect())
    }

    /// Checks one value per vertex, all finite.
    fn check_vertex_values(&self, name: &str, values: &[[f64; D]]) -> Result<()> {
        if values.len() != self.mesh.vertex_count() {
            return Err(Error::invalid(format!(
                "{name} has {} points, expected one per vertex of the T-mesh ({})",
                values.len(),
                self.mesh.vertex_count()
            )));
        }
        check_finite(name, values.as_flattened())
    }

    /// The solver of `H_ff` at the current T-mesh, after checking that it is the stationary
    /// point the sensitivities differentiate.
    fn stationary_solver(&self, pool: &ThreadPool) -> Result<HessianSolver<D>> {
        let tolerance = self.options.stationarity_tolerance;
        if tolerance <= 0.0 {
            return Err(unavailable(
                "the domain was built without the Newton polish",
            ));
        }
        self.check_on_boundary()?;
        let problem = self.mesh.problem()?;
        let layout = Arc::new(BlockLayout::new(pool, &problem));
        let setup = Arc::new(SolverSetup::new(&problem, layout)?);
        self.check_prescribed(&setup.free)?;
        let objective = GlobalObjective::new(&problem, setup.layout(), None, 0.0);
        let mut eval = objective.evaluate(pool, &self.framed, true)?;
        if !eval.value.is_finite() {
            return Err(unavailable("a cell of the T-mesh is invalid"));
        }
        let norm = scaled_gradient_norm(&objective, &setup.free, &eval.gradient);
        if norm > tolerance {
            return Err(unavailable(&format!(
                "the T-mesh is not at the stationary point (gradient norm {norm:.2e} above the \
                 stationarity_tolerance {tolerance:.2e}: the polish did not converge)"
            )));
        }
        let hessian = eval.hessian.take().expect("Hessian evaluated");
        HessianSolver::fresh(pool, &problem, &setup, hessian, (&self.framed, 0))?
            .ok_or_else(|| unavailable("the Hessian at the T-mesh has no factorisation"))
    }

    /// Checks that every boundary vertex sits at its point on the boundary.
    fn check_on_boundary(&self) -> Result<()> {
        for (v, anchor) in self.boundary_anchors().into_iter().enumerate() {
            let Some(a) = anchor else { continue };
            let x = self.framed[v];
            let distance = (0..D).map(|k| (x[k] - a[k]).powi(2)).sum::<f64>().sqrt();
            if distance > ON_BOUNDARY {
                return Err(unavailable(&format!(
                    "the seam relief moved boundary vertex {v} off the boundary (by {distance:.2e} \
                     of the box); build with boundary_offset = 0 or refine where it folds"
                )));
            }
        }
        Ok(())
    }

    /// Checks that the prescribed coordinates of the optimization are exactly those of the
    /// boundary vertices.
    fn check_prescribed(&self, free: &[u8]) -> Result<()> {
        let all = (1u8 << D) - 1;
        for (v, &mask) in free.iter().enumerate() {
            let expected = if self.mesh.on_boundary(v) { 0 } else { all };
            if mask != expected {
                return Err(unavailable(&format!(
                    "vertex {v} is {} but has free coordinates {mask:#b}",
                    if self.mesh.on_boundary(v) {
                        "on the boundary"
                    } else {
                        "inner"
                    }
                )));
            }
        }
        Ok(())
    }
}

/// The error of a sensitivity that cannot be computed, and why.
fn unavailable(why: &str) -> Error {
    Error::invalid(format!(
        "no sensitivities of the T-mesh: {why}; they need a build (or update) with \
         stationarity_tolerance > 0 (e.g. 1e-10) that converged"
    ))
}
