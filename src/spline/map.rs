//! A spline map `S = Σ P_i N_i` of \[0,1\]^d: evaluation, Jacobians, mean ratio, inverse (the
//! fits are in `fit.rs`, h-refinement in `quasi.rs`).

use rayon::prelude::*;

use super::space::{BasisValues, SplineSpace};
use super::thb::ThbSpace;
use crate::error::{check_finite, Error, Result};
use crate::optimize::metric::mean_ratio;
use crate::optimize::single::largest;
use crate::optimize::small_matrix::{bounding_box, det, inverse, Matrix};

/// A spline space with one control point per basis function.
#[derive(Clone, Debug)]
pub struct SplineMap<const D: usize, S = ThbSpace<D>> {
    pub(super) space: S,
    pub(super) control: Vec<[f64; D]>,
}

impl<const D: usize, S: SplineSpace<D>> SplineMap<D, S> {
    /// The map with the given control points, one per basis function.
    pub fn new(space: S, control: Vec<[f64; D]>) -> Result<Self> {
        if control.len() != space.basis_count() {
            return Err(Error::invalid(format!(
                "{} control points for {} basis functions",
                control.len(),
                space.basis_count()
            )));
        }
        check_finite("control", &control.concat())?;
        Ok(SplineMap { space, control })
    }

    /// Largest absolute coordinate of the control points (a scale for tolerances).
    pub fn extent(&self) -> f64 {
        largest(self.control.iter().flatten().copied())
    }

    /// The space.
    pub fn space(&self) -> &S {
        &self.space
    }

    /// The control points, one per basis function.
    pub fn control_points(&self) -> &[[f64; D]] {
        &self.control
    }

    /// Number of basis functions.
    pub fn basis_count(&self) -> usize {
        self.space.basis_count()
    }

    /// Number of elements.
    pub fn element_count(&self) -> usize {
        self.space.element_count()
    }

    /// Parametric bounds of element `e`.
    pub fn element_bounds(&self, e: usize) -> ([f64; D], [f64; D]) {
        self.space.element_bounds(e)
    }

    /// Level of element `e`.
    pub fn element_level(&self, e: usize) -> u8 {
        self.space.element_level(e)
    }

    /// Functions non-zero on element `e` and its extraction operator (see
    /// [`SplineSpace::extraction`]).
    pub fn extraction(&self, e: usize) -> (&[usize], &[f64]) {
        self.space.extraction(e)
    }

    /// The non-zero basis functions at `x` with values and gradients.
    pub fn basis_at(&self, x: [f64; D]) -> Option<BasisValues<D>> {
        self.space.basis_at(x)
    }

    /// `S(x)` and its Jacobian (`J[a][b] = ∂S_a/∂x_b`), `None` outside \[0,1\]^d.
    pub fn eval_with_jacobian(&self, x: [f64; D]) -> Option<([f64; D], Matrix<D>)> {
        let b = self.space.basis_at(x)?;
        let mut y = [0.0; D];
        let mut j = [[0.0; D]; D];
        for ((&i, &v), g) in b.functions.iter().zip(&b.values).zip(&b.gradients) {
            let p = self.control[i];
            for a in 0..D {
                y[a] += v * p[a];
                for c in 0..D {
                    j[a][c] += g[c] * p[a];
                }
            }
        }
        Some((y, j))
    }

    /// `S(x)`, `None` outside \[0,1\]^d.
    pub fn eval(&self, x: [f64; D]) -> Option<[f64; D]> {
        self.eval_with_jacobian(x).map(|r| r.0)
    }

    /// `S` and its Jacobian at many points (in parallel; the order of the input is kept).
    pub fn eval_many(&self, x: &[[f64; D]]) -> Vec<Option<([f64; D], Matrix<D>)>> {
        x.par_iter().map(|&p| self.eval_with_jacobian(p)).collect()
    }

    /// Mean ratio `q_S = d·det(J)^{2/d}/‖J‖²_F` at `x` (0 where `det J ≤ 0`).
    pub fn mean_ratio(&self, x: [f64; D]) -> Option<f64> {
        self.eval_with_jacobian(x).map(|(_, j)| mean_ratio(&j))
    }

    /// Prepares the inverse map with `samples^d` start points per element.
    pub fn inverse_map(&self, samples: usize) -> InverseMap<'_, D, S> {
        let n = samples.max(2);
        let per = n.pow(D as u32);
        let starts = (0..self.element_count())
            .into_par_iter()
            .flat_map_iter(|e| {
                let (lo, hi) = self.space.element_bounds(e);
                (0..per).filter_map(move |s| {
                    let x: [f64; D] = std::array::from_fn(|k| {
                        let i = s / n.pow(k as u32) % n;
                        lo[k] + (hi[k] - lo[k]) * (i as f64 + 0.5) / n as f64
                    });
                    self.eval(x).map(|y| (x, y))
                })
            })
            .collect::<Vec<_>>();
        let (lo, hi) = bounding_box(starts.iter().map(|&(_, y)| y));
        let size = (0..D).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        InverseMap {
            map: self,
            starts,
            size,
        }
    }
}

/// The inverse of a spline map (physical → parametric) by Newton's method from the nearest
/// sample.
#[derive(Clone, Debug)]
pub struct InverseMap<'a, const D: usize, S> {
    map: &'a SplineMap<D, S>,
    starts: Vec<([f64; D], [f64; D])>,
    size: f64,
}

impl<const D: usize, S: SplineSpace<D>> InverseMap<'_, D, S> {
    /// The parametric point whose image is `y`, `None` when `y` is outside the image (or Newton
    /// does not converge from the nearest samples).
    pub fn locate(&self, y: [f64; D]) -> Option<[f64; D]> {
        if y.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let dist = |a: &[f64; D]| (0..D).map(|k| (a[k] - y[k]).powi(2)).sum::<f64>();
        let mut near: Vec<(f64, usize)> = self
            .starts
            .iter()
            .enumerate()
            .map(|(i, (_, s))| (dist(s), i))
            .collect();
        let tries = near.len().min(4);
        if tries == 0 {
            return None;
        }
        near.select_nth_unstable_by(tries - 1, |a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        near[..tries].sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let tolerance = 1e-12 * self.size.max(f64::MIN_POSITIVE);
        near[..tries]
            .iter()
            .find_map(|&(_, i)| self.newton(self.starts[i].0, y, tolerance))
    }

    fn newton(&self, mut x: [f64; D], y: [f64; D], tolerance: f64) -> Option<[f64; D]> {
        let residual = |x: [f64; D]| -> Option<([f64; D], Matrix<D>, f64)> {
            let (s, j) = self.map.eval_with_jacobian(x)?;
            let r: [f64; D] = std::array::from_fn(|k| s[k] - y[k]);
            let norm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
            Some((r, j, norm))
        };
        let (mut r, mut j, mut norm) = residual(x)?;
        for _ in 0..60 {
            if norm <= tolerance {
                return Some(x);
            }
            if det(&j) <= 0.0 {
                return None;
            }
            let inv = inverse(&j)?;
            let step: [f64; D] =
                std::array::from_fn(|a| (0..D).map(|b| inv[a][b] * r[b]).sum::<f64>());
            let mut t = 1.0;
            let mut improved = false;
            for _ in 0..20 {
                let trial: [f64; D] = std::array::from_fn(|k| (x[k] - t * step[k]).clamp(0.0, 1.0));
                if let Some((rt, jt, nt)) = residual(trial) {
                    if nt < norm {
                        (x, r, j, norm) = (trial, rt, jt, nt);
                        improved = true;
                        break;
                    }
                }
                t *= 0.5;
            }
            if !improved {
                break;
            }
        }
        (norm <= tolerance).then_some(x)
    }
}
