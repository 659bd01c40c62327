//! Sensitivities of a relocated mesh: at a stationary point of the global objective,
//! `∇_f F(x_f, x_p) = 0` makes the free coordinates a function of the prescribed ones, with
//! `dx_f/dx_p = −H_ff⁻¹ H_fp` (implicit function theorem). The adjoint product gives the total
//! derivative of a scalar of the positions with respect to the prescribed coordinates, the
//! tangent product the first-order motion of every node for a motion of the prescribed ones.
//!
//! Coordinates: a component is free when its bit in the node's constraint mask is clear and the
//! node belongs to a cell (sliding nodes have free and prescribed components); every other
//! component is prescribed, and so is z for every node of a 2D mesh (relocation carries it
//! unchanged).

use rayon::ThreadPool;

use super::{Mesh, Solver};
use crate::error::{check_finite, Error, Result};
use crate::optimize::implicit::EXACT;
use crate::optimize::small_matrix::Vector;
use crate::optimize::solver::HessianSolver;

impl Mesh {
    /// The adjoint product at the last relocation's stationary point: given `dj_dx`, the partial
    /// derivatives `∂J/∂x` of a scalar `J` of the node positions (`#nodes × 3`, flat), returns
    /// the total derivative `dJ/dx_p = ∂J/∂x_p − H_pf H_ff⁻¹ ∂J/∂x_f` with respect to every
    /// prescribed coordinate (`#nodes × 3`, 0 at free coordinates).
    ///
    /// Needs a relocation with `stationarity_tolerance > 0` that met it, and no change of the
    /// mesh since (moving nodes, constraints or the reference); else an error says which.
    pub fn adjoint(&self, threads: usize, dj_dx: &[f64]) -> Result<Vec<f64>> {
        self.check_sensitivity_input("dj_dx", dj_dx)?;
        let pool = pool(threads)?;
        match self.dimension() {
            2 => self.adjoint_d::<2>(&pool, dj_dx),
            _ => self.adjoint_d::<3>(&pool, dj_dx),
        }
    }

    /// The tangent product at the last relocation's stationary point: given a motion
    /// `dx_prescribed` of the prescribed coordinates (`#nodes × 3`, flat; entries at free
    /// coordinates are ignored), returns the first-order motion of every node (`#nodes × 3`):
    /// the given one at prescribed coordinates, `−H_ff⁻¹ H_fp dx_p` at free ones. Same
    /// conditions as [`Mesh::adjoint`], whose transpose it is.
    pub fn tangent(&self, threads: usize, dx_prescribed: &[f64]) -> Result<Vec<f64>> {
        self.check_sensitivity_input("dx_prescribed", dx_prescribed)?;
        let pool = pool(threads)?;
        match self.dimension() {
            2 => self.tangent_d::<2>(&pool, dx_prescribed),
            _ => self.tangent_d::<3>(&pool, dx_prescribed),
        }
    }

    fn check_sensitivity_input(&self, name: &str, values: &[f64]) -> Result<()> {
        if values.len() != 3 * self.node_count() {
            return Err(Error::invalid(format!(
                "{name} has {} values, expected 3 per node ({})",
                values.len(),
                3 * self.node_count()
            )));
        }
        check_finite(name, values)?;
        self.stationary_solver_state().map(|_| ())
    }

    fn stationary_solver_state(&self) -> Result<&Solver> {
        let unavailable = |why: &str| {
            Error::invalid(format!(
                "no sensitivities: {why}; relocate with stationarity_tolerance > 0 (e.g. 1e-10) first"
            ))
        };
        self.sensitivity.as_ref().map_err(|why| unavailable(why))?;
        self.last
            .as_ref()
            .and_then(|last| last.solver.as_ref())
            .ok_or_else(|| unavailable("the last relocation kept no Hessian"))
    }

    /// The solver at the last relocation's stationary point.
    fn solver<const D: usize>(&self) -> Result<&HessianSolver<D>> {
        self.stationary_solver_state()?
            .downcast_ref::<HessianSolver<D>>()
            .ok_or_else(|| Error::invalid("the stored Hessian does not match the mesh's dimension"))
    }

    fn adjoint_d<const D: usize>(&self, pool: &ThreadPool, dj_dx: &[f64]) -> Result<Vec<f64>> {
        let total = self.solver::<D>()?.adjoint(pool, &split::<D>(dj_dx))?;
        Ok(merge(dj_dx, &total))
    }

    fn tangent_d<const D: usize>(&self, pool: &ThreadPool, dx: &[f64]) -> Result<Vec<f64>> {
        let motion = self.solver::<D>()?.tangent(pool, &split::<D>(dx), EXACT)?;
        Ok(merge(dx, &motion))
    }
}

/// The first `D` components of each point of a flat `#nodes × 3` array.
fn split<const D: usize>(flat: &[f64]) -> Vec<Vector<D>> {
    flat.chunks(3)
        .map(|p| std::array::from_fn(|k| p[k]))
        .collect()
}

/// `flat` (`#nodes × 3`) with its first `D` components of each point replaced by `points`: the
/// third component of a 2D mesh passes through (z is prescribed: relocation keeps it).
fn merge<const D: usize>(flat: &[f64], points: &[Vector<D>]) -> Vec<f64> {
    let mut out = flat.to_vec();
    for (o, p) in out.chunks_mut(3).zip(points) {
        o[..D].copy_from_slice(p);
    }
    out
}

fn pool(threads: usize) -> Result<ThreadPool> {
    crate::threads::pool(threads)
}
