//! The optimum of the global objective as a function of the prescribed coordinates: at a
//! stationary point, `∇_f F(x_f, x_p) = 0` gives `dx_f/dx_p = −H_ff⁻¹ H_fp` (implicit function
//! theorem). The tangent product moves the optimum with the prescribed coordinates (the
//! predictor of path following, the sensitivities' forward mode); the adjoint product is its
//! transpose (reverse mode).

use rayon::ThreadPool;

use super::cg::Stop;
use super::small_matrix::Vector;
use super::solver::{mask, HessianSolver};
use crate::error::{Error, Result};

/// Relative residual to which the solves of the sensitivities are carried.
pub(crate) const EXACT: f64 = 1e-13;

/// Largest relative residual an exact solve may end with before the product is refused.
const ACCEPTED_RESIDUAL: f64 = 1e-9;

impl<const D: usize> HessianSolver<D> {
    /// Bits of the prescribed coordinates of every node (the complement of the free ones).
    pub fn prescribed(&self) -> Vec<u8> {
        self.free().iter().map(|m| !m & ((1 << D) - 1)).collect()
    }

    /// The first-order motion of every node for a motion `dx` of the prescribed coordinates
    /// (its free entries are ignored): `dx` at prescribed coordinates, `−H_ff⁻¹ H_fp dx_p` at
    /// free ones, solved to the relative residual `tolerance` (`EXACT` for sensitivities).
    pub fn tangent(
        &self,
        pool: &ThreadPool,
        dx: &[Vector<D>],
        tolerance: f64,
    ) -> Result<Vec<Vector<D>>> {
        let prescribed = self.prescribed();
        let mut coupling = vec![[0.0; D]; dx.len()];
        self.hessian().product(
            pool,
            self.layout(),
            self.free(),
            &prescribed,
            dx,
            &mut coupling,
        );
        let minus: Vec<Vector<D>> = coupling.iter().map(|c| c.map(|v| -v)).collect();
        let free_motion = self.checked_solve(pool, &minus, tolerance)?;
        let mut out = mask(&prescribed, dx);
        for (o, f) in out.iter_mut().zip(&free_motion) {
            for k in 0..D {
                o[k] += f[k];
            }
        }
        Ok(out)
    }

    /// The total derivative of a scalar `J` with respect to the prescribed coordinates, given its
    /// partial derivatives `w = ∂J/∂x` at every node: `w_p − H_pf H_ff⁻¹ w_f` at prescribed
    /// coordinates, 0 at free ones.
    pub fn adjoint(&self, pool: &ThreadPool, w: &[Vector<D>]) -> Result<Vec<Vector<D>>> {
        let prescribed = self.prescribed();
        let lambda = self.checked_solve(pool, w, EXACT)?;
        let mut coupling = vec![[0.0; D]; w.len()];
        self.hessian().product(
            pool,
            self.layout(),
            &prescribed,
            self.free(),
            &lambda,
            &mut coupling,
        );
        let mut out = mask(&prescribed, w);
        for (o, c) in out.iter_mut().zip(&coupling) {
            for k in 0..D {
                o[k] -= c[k];
            }
        }
        Ok(out)
    }

    /// `H_ff⁻¹ b` to the relative residual `tolerance`, refused when the solve does not get
    /// near it or meets negative curvature.
    fn checked_solve(
        &self,
        pool: &ThreadPool,
        b: &[Vector<D>],
        tolerance: f64,
    ) -> Result<Vec<Vector<D>>> {
        let (y, stats) = self.solve(pool, b, Stop::relative(tolerance));
        if stats.negative_curvature {
            return Err(Error::invalid(
                "the Hessian at the last relocation's end is not positive definite (not a strict \
                 minimum): the sensitivities are not defined",
            ));
        }
        if stats.residual.is_nan() || stats.residual > ACCEPTED_RESIDUAL.max(10.0 * tolerance) {
            return Err(Error::invalid(format!(
                "the Hessian solve reached a relative residual of {:.1e} only",
                stats.residual
            )));
        }
        Ok(y)
    }
}
