//! A spline map `S = Σ P_i N_i` of [0,1]^d: Greville interpolation, evaluation, Jacobians, mean
//! ratio, inverse, h-refinement.

use std::time::Instant;

use rayon::prelude::*;

use super::solve::SparseLu;
use super::space::{BasisValues, SplineSpace};
use super::thb::ThbSpace;
use super::untangle::UntangleOptions;
use super::validity::{ValidityOptions, ValidityReport};
use crate::error::{check_finite, Error, Result};
use crate::optimize::metric::mean_ratio;
use crate::optimize::small::{bounding_box, det, inverse, Matrix};

/// Per fit point: the data and the sparse row of basis values.
type FitRow<const D: usize> = ([f64; D], Vec<(usize, f64)>);

/// Smallest relative pivot for which [`SplineMap::fit`] keeps the interpolation.
const WELL_CONDITIONED: f64 = 1e-3;

/// Largest distance, relative to the extent of the data, that [`SplineMap::fit`] lets an
/// interpolant stray from the data between the interpolation points before trying least squares.
const STRAY: f64 = 5e-2;

/// The `4^d` points `((i + ½)/4)` per direction of every element.
fn element_samples<const D: usize, S: SplineSpace<D>>(space: &S) -> Vec<[f64; D]> {
    let per = 4usize.pow(D as u32);
    let mut points = Vec::with_capacity(per * space.element_count());
    for e in 0..space.element_count() {
        let (lo, hi) = space.element_bounds(e);
        for s in 0..per {
            points.push(std::array::from_fn(|k| {
                let i = s / 4usize.pow(k as u32) % 4;
                lo[k] + (hi[k] - lo[k]) * (i as f64 + 0.5) / 4.0
            }));
        }
    }
    points
}

/// A spline space with one control point per basis function.
#[derive(Clone, Debug)]
pub struct SplineMap<const D: usize, S = ThbSpace<D>> {
    pub(super) space: S,
    pub(super) control: Vec<[f64; D]>,
}

/// What an interpolation did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FitReport {
    /// Basis functions (= interpolation points).
    pub basis_count: usize,
    /// Elements of the space.
    pub element_count: usize,
    /// Largest coordinate difference between the spline and the data at the fit points.
    pub residual: f64,
    /// Whether the least-squares fit replaced a singular interpolation.
    pub least_squares: bool,
    /// Whether the coefficients come from the quasi-interpolant
    /// ([`SplineMap::fit_quasi_interpolation`], or an exact refinement).
    pub quasi_interpolation: bool,
    /// Control points moved by the untangling ([`SplineMap::untangle`]) of a map the fit left
    /// uncertified; 0 when the fitted map was kept as it was.
    pub untangled: usize,
    /// Largest move of a boundary control point by the untangling, relative to the bounding
    /// box (see [`UntangleOptions::boundary_offset`]); 0 when the boundary was kept.
    pub boundary_offset: f64,
    /// Smallest LU pivot relative to the largest matrix entry.
    pub smallest_pivot: f64,
    /// Bandwidth of the reordered collocation matrix.
    pub bandwidth: usize,
    /// Wall-clock seconds (with the certification and untangling of [`SplineMap::fit_checked`]).
    pub seconds: f64,
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

    /// Fits `f`: interpolation at the space's interpolation points (see
    /// [`SplineMap::fit_collocation`]), or the least-squares fit of
    /// [`SplineMap::fit_least_squares`] when that square system is singular or badly conditioned
    /// (a relative LU pivot under 10⁻³, or a residual above 10⁻⁹ of the map's extent) —
    /// Greville-type points of hierarchical spaces are not unisolvent on every tree — or when
    /// the interpolant strays from `f` between the points (by more than 5% of the extent of `f`
    /// at the 4^d points `(i + ½)/4` of the elements) and the least-squares fit stays closer
    /// there. The report says which was used.
    pub fn fit(
        space: S,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
    ) -> Result<(Self, FitReport)> {
        match Self::fit_collocation(space.clone(), &f) {
            Ok(fit)
                if fit.1.smallest_pivot >= WELL_CONDITIONED
                    && fit.1.residual <= 1e-9 * fit.0.extent().max(f64::MIN_POSITIVE) =>
            {
                let samples = element_samples(&space);
                let (error, size) = fit.0.sample_error(&samples, &f);
                if error <= STRAY * size {
                    return Ok(fit);
                }
                let least = Self::fit_least_squares(space, &f)?;
                let (least_error, _) = least.0.sample_error(&samples, &f);
                Ok(if least_error < error { least } else { fit })
            }
            Ok(_) => Self::fit_least_squares(space, &f),
            Err(e) if e.message.contains("singular") => Self::fit_least_squares(space, &f),
            Err(e) => Err(e),
        }
    }

    /// Largest coordinate difference between the map and `f` at `points`, and the largest
    /// coordinate extent of `f` there.
    fn sample_error(
        &self,
        points: &[[f64; D]],
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
    ) -> (f64, f64) {
        let pairs: Vec<([f64; D], [f64; D])> = points
            .par_iter()
            .filter_map(|&x| Some((self.eval(x)?, f(x)?)))
            .collect();
        let mut lo = [f64::INFINITY; D];
        let mut hi = [f64::NEG_INFINITY; D];
        let mut error = 0.0f64;
        for (s, y) in &pairs {
            for k in 0..D {
                lo[k] = lo[k].min(y[k]);
                hi[k] = hi[k].max(y[k]);
                error = error.max((s[k] - y[k]).abs());
            }
        }
        let size = (0..D).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        (error, size)
    }

    /// Interpolates `f` at the interpolation points of the space (see
    /// [`SplineSpace::interpolation_points`]) by solving the square collocation system with a
    /// sparse LU. Fails when `f` is not defined (returns `None`) or not finite at a point, or
    /// when the system is singular.
    pub fn fit_collocation(
        space: S,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
    ) -> Result<(Self, FitReport)> {
        let points = space.interpolation_points();
        Self::solve_fit(space, &points, f, false)
    }

    /// Least-squares fit of `f` at the interpolation points and the `4^d` points
    /// `((i + ½)/4)` of every element: the normal equations are non-singular because the
    /// functions are linearly independent on each element and a tensor polynomial of degree 3
    /// vanishing on a 4^d grid is zero. Reproduces every map of the space exactly.
    pub fn fit_least_squares(
        space: S,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
    ) -> Result<(Self, FitReport)> {
        let mut points = space.interpolation_points();
        points.extend(element_samples(&space));
        Self::solve_fit(space, &points, f, true)
    }

    fn solve_fit(
        space: S,
        points: &[[f64; D]],
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
        least_squares: bool,
    ) -> Result<(Self, FitReport)> {
        let start = Instant::now();
        let n = space.basis_count();
        let data: Vec<FitRow<D>> = points
            .par_iter()
            .map(|&x| {
                let y = f(x).ok_or_else(|| {
                    Error::invalid(format!("the map to fit is not defined at {x:?}"))
                })?;
                check_finite("fitted value", &y)?;
                let b = space
                    .basis_at(x)
                    .ok_or_else(|| Error::invalid(format!("fit point {x:?} outside")))?;
                let row = b
                    .functions
                    .iter()
                    .zip(&b.values)
                    .filter(|(_, &v)| v != 0.0)
                    .map(|(&i, &v)| (i, v))
                    .collect();
                Ok((y, row))
            })
            .collect::<Result<_>>()?;
        type System<const D: usize> = (Vec<Vec<(usize, f64)>>, Vec<[f64; D]>);
        let (rows, rhs): System<D> = if least_squares {
            let mut normal: Vec<std::collections::BTreeMap<usize, f64>> =
                vec![Default::default(); n];
            let mut rhs = vec![[0.0; D]; n];
            for (y, row) in &data {
                for &(i, vi) in row {
                    for &(j, vj) in row {
                        *normal[i].entry(j).or_insert(0.0) += vi * vj;
                    }
                    for k in 0..D {
                        rhs[i][k] += vi * y[k];
                    }
                }
            }
            (
                normal
                    .into_iter()
                    .map(|r| r.into_iter().collect())
                    .collect(),
                rhs,
            )
        } else {
            (
                data.iter().map(|d| d.1.clone()).collect(),
                data.iter().map(|d| d.0).collect(),
            )
        };
        let lu = SparseLu::factor(n, &rows)?;
        let mut control = vec![[0.0; D]; n];
        for k in 0..D {
            let mut b: Vec<f64> = rhs.iter().map(|r| r[k]).collect();
            lu.solve(&mut b);
            for (c, v) in control.iter_mut().zip(b) {
                c[k] = v;
            }
        }
        check_finite("control", &control.concat())?;
        let residual = data
            .iter()
            .map(|(y, row)| {
                (0..D)
                    .map(|k| {
                        let s: f64 = row.iter().map(|&(i, v)| v * control[i][k]).sum();
                        (s - y[k]).abs()
                    })
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        let report = FitReport {
            basis_count: n,
            element_count: space.element_count(),
            residual,
            bandwidth: lu.bandwidth(),
            least_squares,
            quasi_interpolation: false,
            smallest_pivot: lu.smallest_pivot(),
            untangled: 0,
            boundary_offset: 0.0,
            seconds: start.elapsed().as_secs_f64(),
        };
        Ok((SplineMap { space, control }, report))
    }

    /// Largest absolute coordinate of the control points (a scale for tolerances).
    pub fn extent(&self) -> f64 {
        self.control
            .iter()
            .flatten()
            .fold(0.0, |m: f64, v| m.max(v.abs()))
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

    /// `S(x)` and its Jacobian (`J[a][b] = ∂S_a/∂x_b`), `None` outside [0,1]^d.
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

    /// `S(x)`, `None` outside [0,1]^d.
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

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// Fits the THB space of the T-mesh's tree to its piecewise quadratic map (see
    /// [`SplineMap::fit_tmesh_checked`]).
    pub fn fit_tmesh(
        mesh: &crate::tmesh::TMesh<D>,
        positions: &[[f64; D]],
    ) -> Result<(Self, FitReport)> {
        let (map, report, _) = Self::fit_tmesh_checked(
            mesh,
            positions,
            &ValidityOptions::default(),
            &UntangleOptions::default(),
        )?;
        Ok((map, report))
    }

    /// Fits the THB space of the T-mesh's tree to its piecewise quadratic map with
    /// [`SplineMap::fit_checked`]. Returns the map, its fit report and its validity.
    pub fn fit_tmesh_checked(
        mesh: &crate::tmesh::TMesh<D>,
        positions: &[[f64; D]],
        options: &ValidityOptions,
        untangle: &UntangleOptions,
    ) -> Result<(Self, FitReport, ValidityReport)> {
        let source = super::quadratic::QuadraticMap::new(mesh, positions)?;
        let space = ThbSpace::new(mesh.tree().clone())?;
        Self::fit_checked(space, |x| source.eval(x), options, untangle)
    }

    /// Fits `f` by [`SplineMap::fit`] (Greville interpolation, or least squares) and, unless
    /// that map is certified valid, also by [`SplineMap::fit_quasi_interpolation`], and keeps
    /// the better: certified valid first, then fewer uncertified elements, then the higher
    /// smallest mean ratio, the interpolation on ties. Interpolation follows the data more
    /// closely; the local quasi-interpolant does not overshoot where the collocation is badly
    /// conditioned. When the map kept is not certified valid, it is untangled
    /// ([`SplineMap::untangle`] with `untangle`). Returns the map, its fit report and its
    /// validity (certified with `options`).
    pub fn fit_checked(
        space: ThbSpace<D>,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
        options: &ValidityOptions,
        untangle: &UntangleOptions,
    ) -> Result<(Self, FitReport, ValidityReport)> {
        let start = Instant::now();
        let (map, mut report) = SplineMap::fit(space.clone(), &f)?;
        let validity = map.validity(options);
        if validity.certified_positive {
            report.seconds = start.elapsed().as_secs_f64();
            return Ok((map, report, validity));
        }
        let (quasi, quasi_report) = SplineMap::fit_quasi_interpolation(space, &f)?;
        let quasi_validity = quasi.validity(options);
        let (mut map, mut report, validity) = if quasi_validity.is_better_than(&validity) {
            (quasi, quasi_report, quasi_validity)
        } else {
            (map, report, validity)
        };
        let (validity, untangled) = map.untangle(validity, options, untangle);
        report.untangled = untangled.moved;
        report.boundary_offset = untangled.boundary_offset;
        report.seconds = start.elapsed().as_secs_f64();
        Ok((map, report, validity))
    }
}
