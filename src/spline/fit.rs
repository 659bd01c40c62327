//! Fits of a spline map to a map given pointwise: interpolation at the interpolation points
//! (sparse LU of the collocation matrix), least squares at those points and 4^d points per
//! element (sparse Cholesky of the normal equations, assembled element by element), and the
//! rule that chooses between them.

use std::time::Instant;

use rayon::prelude::*;

use super::map::SplineMap;
use super::space::SplineSpace;
use crate::error::{check_finite, Error, Result};
use crate::sparse::{Entry, SparseSolver, SymmetricAssembly};

/// Smallest estimated reciprocal condition number (1-norm) of the collocation matrix for which
/// [`SplineMap::fit`] keeps the interpolation.
const WELL_CONDITIONED: f64 = 1e-8;

/// Largest distance, relative to the extent of the data, that [`SplineMap::fit`] lets an
/// interpolant stray from the data between the interpolation points before trying least squares.
const STRAY: f64 = 5e-2;

/// Elements whose normal-equation blocks are formed at once (in parallel) before they are added
/// up in element order.
const CHUNK: usize = 64;

/// What a fit did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FitReport {
    /// Basis functions (= control points).
    pub basis_count: usize,
    /// Elements of the space (the leaves of the hierarchical mesh).
    pub element_count: usize,
    /// Largest coordinate difference between the spline and the data at the fit points.
    pub residual: f64,
    /// Whether a least-squares fit replaced a singular or badly conditioned interpolation at
    /// the Greville points (1 in C, else 0).
    pub least_squares: bool,
    /// Whether the control points come from the local quasi-interpolant
    /// ([`SplineMap::fit_quasi_interpolation`]: in a checked fit, when its map was certified
    /// valid, or less invalid, than that of the interpolation; and every exact refinement,
    /// `igaparam_spline_refine` in C) (1 in C, else 0).
    pub quasi_interpolation: bool,
    /// Control points moved by the untangling ([`SplineMap::untangle`]) of a fitted map that
    /// was not certified valid (inner ones first; boundary ones, at most the untangling's
    /// `boundary_offset` of the bounding box, only when that was not enough); 0 when the fitted
    /// map was kept as it was.
    pub untangled: usize,
    /// Largest move of a boundary control point by that untangling, relative to the bounding
    /// box (each axis scaled to 1; see
    /// [`UntangleOptions::boundary_offset`](super::UntangleOptions::boundary_offset)); 0 when
    /// the boundary was kept.
    pub boundary_offset: f64,
    /// Estimated reciprocal condition number (1-norm) of the matrix solved: the collocation
    /// matrix, or the normal equations; 1 for the quasi-interpolant.
    pub reciprocal_condition: f64,
    /// Wall-clock seconds (with the certification and untangling of [`SplineMap::fit_checked`]).
    pub seconds: f64,
    // After `seconds`, as in the C struct, which appended it.
    /// Inner control points moved by the smoothing stage ([`SplineMap::smooth`]: on the map's
    /// own mean ratio, kept only when the map stays certified and its smallest sampled mean
    /// ratio rises); 0 when the map was kept as it was.
    pub smoothed: usize,
    /// Wall-clock seconds of the stages of [`SplineMap::fit_checked`].
    pub stages: FitStages,
    /// Largest distance from the map's boundary to the domain's boundary, in coordinates that
    /// map the domain's bounding box onto the unit box, sampled on every boundary facet of the
    /// elements ([`SplineMap::boundary_distance`]; an upper bound at the samples); 0 for a fit
    /// without a domain ([`SplineMap::fit_checked`] of a function).
    pub boundary_distance: f64,
}

/// Wall-clock seconds of the stages of a checked fit ([`SplineMap::fit_checked`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FitStages {
    /// Interpolation or least squares, and the quasi-interpolation when it was made.
    pub fit: f64,
    /// Certification of the fitted maps.
    pub certify: f64,
    /// Untangling (with its certifications).
    pub untangle: f64,
    /// Smoothing (with its certifications).
    pub smooth: f64,
}

/// The `4^d` points `((i + ½)/4)` per direction of element `e`.
pub(super) fn samples_of<const D: usize, S: SplineSpace<D>>(
    space: &S,
    e: usize,
) -> impl Iterator<Item = [f64; D]> {
    let (lo, hi) = space.element_bounds(e);
    (0..4usize.pow(D as u32)).map(move |s| {
        std::array::from_fn(|k| {
            let i = s / 4usize.pow(k as u32) % 4;
            lo[k] + (hi[k] - lo[k]) * (i as f64 + 0.5) / 4.0
        })
    })
}

/// `f(x)`, or an error saying where it is not defined or not finite.
fn value<const D: usize>(
    f: impl Fn([f64; D]) -> Option<[f64; D]>,
    x: [f64; D],
) -> Result<[f64; D]> {
    let y =
        f(x).ok_or_else(|| Error::invalid(format!("the map to fit is not defined at {x:?}")))?;
    check_finite("fitted value", &y)?;
    Ok(y)
}

/// The points of element `e` a least-squares fit uses: its interpolation points (`points_of`),
/// then its `4^d` samples.
pub(super) fn least_squares_points<'a, const D: usize, S: SplineSpace<D>>(
    space: &S,
    points_of: &'a [Vec<[f64; D]>],
    e: usize,
) -> impl Iterator<Item = [f64; D]> + 'a {
    let samples: Vec<[f64; D]> = samples_of(space, e).collect();
    points_of[e].iter().copied().chain(samples)
}

/// The least-squares points of every element beyond its samples (its interpolation points)
/// and its functions: what [`least_squares_points`] and [`normal_equations`] take.
pub(super) fn least_squares_layout<const D: usize, S: SplineSpace<D>>(
    space: &S,
) -> Result<LeastSquaresLayout<D>> {
    let m = space.element_count();
    let interpolation = space.interpolation_points();
    let mut points_of: Vec<Vec<[f64; D]>> = vec![Vec::new(); m];
    for (&x, e) in interpolation
        .iter()
        .zip(elements_of(space, &interpolation)?)
    {
        points_of[e].push(x);
    }
    let blocks: Vec<Vec<usize>> = (0..m).map(|e| space.extraction(e).0.to_vec()).collect();
    Ok((points_of, blocks))
}

/// Per element, its interpolation points and its functions (see [`least_squares_layout`]).
pub(super) type LeastSquaresLayout<const D: usize> = (Vec<Vec<[f64; D]>>, Vec<Vec<usize>>);

/// The entries of the collocation matrix: row `p` holds the functions of element
/// `elements[p]` with their `values[p]` at the `p`-th interpolation point.
pub(super) fn collocation_entries<const D: usize, S: SplineSpace<D>>(
    space: &S,
    elements: &[usize],
    values: &[&[f64]],
) -> Vec<Entry> {
    let mut entries: Vec<Entry> = Vec::new();
    for (p, (v, &e)) in values.iter().zip(elements).enumerate() {
        let (functions, _) = space.extraction(e);
        for (&i, &w) in functions.iter().zip(v.iter()) {
            if w != 0.0 {
                entries.push((p, i, w));
            }
        }
    }
    entries
}

/// The normal equations of the least-squares fit of `f` at the points of every element (see
/// [`least_squares_points`]; `blocks` holds each element's functions): the matrix, assembled
/// block by block in element order, and the right-hand sides.
pub(super) fn normal_equations<const D: usize, S: SplineSpace<D>>(
    space: &S,
    points_of: &[Vec<[f64; D]>],
    blocks: &[Vec<usize>],
    f: &(impl Fn([f64; D]) -> Option<[f64; D]> + Sync),
) -> Result<(SymmetricAssembly, Vec<[f64; D]>)> {
    let (n, m) = (space.basis_count(), space.element_count());
    let block_refs: Vec<&[usize]> = blocks.iter().map(|b| &b[..]).collect();
    let mut normal = SymmetricAssembly::new(n, &block_refs)?;
    let mut rhs = vec![[0.0; D]; n];
    for first in (0..m).step_by(CHUNK) {
        let local: Vec<(Vec<f64>, Vec<[f64; D]>)> = (first..(first + CHUNK).min(m))
            .into_par_iter()
            .map(|e| {
                let size = blocks[e].len();
                let mut gram = vec![0.0; size * size];
                let mut right = vec![[0.0; D]; size];
                for x in least_squares_points(space, points_of, e) {
                    let y = value(f, x)?;
                    let v = space.values_on(e, x);
                    for (a, &va) in v.iter().enumerate() {
                        for (g, &vb) in gram[a * size..=a * size + a].iter_mut().zip(&v) {
                            *g += va * vb;
                        }
                        for (r, yk) in right[a].iter_mut().zip(y) {
                            *r += va * yk;
                        }
                    }
                }
                Ok((gram, right))
            })
            .collect::<Result<_>>()?;
        for (e, (gram, right)) in (first..).zip(local) {
            normal.add_block(&blocks[e], &gram);
            for (&i, r) in blocks[e].iter().zip(right) {
                for k in 0..D {
                    rhs[i][k] += r[k];
                }
            }
        }
    }
    Ok((normal, rhs))
}

/// The element of each point, in point order; an error for a point outside \[0,1\]^d.
pub(super) fn elements_of<const D: usize, S: SplineSpace<D>>(
    space: &S,
    points: &[[f64; D]],
) -> Result<Vec<usize>> {
    points
        .iter()
        .map(|&x| {
            space
                .element_at(x)
                .ok_or_else(|| Error::invalid(format!("fit point {x:?} outside")))
        })
        .collect()
}

impl<const D: usize, S: SplineSpace<D>> SplineMap<D, S> {
    /// Fits `f`: interpolation at the space's interpolation points (see
    /// [`SplineMap::fit_collocation`]), or the least-squares fit of
    /// [`SplineMap::fit_least_squares`] when that square system is singular or badly conditioned
    /// (an estimated reciprocal condition number under 10⁻⁸, or a residual above 10⁻⁹ of the
    /// map's extent) — Greville-type points of hierarchical spaces are not unisolvent on every
    /// tree — or when the interpolant strays from `f` between the points (by more than 5% of
    /// the extent of `f` at the 4^d points `(i + ½)/4` of the elements) and the least-squares
    /// fit stays closer there. The report says which was used.
    pub fn fit(
        space: S,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
    ) -> Result<(Self, FitReport)> {
        match Self::fit_collocation(space.clone(), &f) {
            Ok(fit)
                if fit.1.reciprocal_condition >= WELL_CONDITIONED
                    && fit.1.residual <= 1e-9 * fit.0.extent().max(f64::MIN_POSITIVE) =>
            {
                let (error, size) = fit.0.sample_error(&f)?;
                if error <= STRAY * size {
                    return Ok(fit);
                }
                let least = Self::fit_least_squares(space, &f)?;
                let (least_error, _) = least.0.sample_error(&f)?;
                Ok(if least_error < error { least } else { fit })
            }
            Ok(_) => Self::fit_least_squares(space, &f),
            Err(e) if e.message.contains("singular") => Self::fit_least_squares(space, &f),
            Err(e) => Err(e),
        }
    }

    /// Largest coordinate difference between the map and `f` at the `4^d` points
    /// `((i + ½)/4)` of every element, and the largest coordinate extent of `f` there.
    fn sample_error(&self, f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync) -> Result<(f64, f64)> {
        type Extremes<const D: usize> = (f64, [f64; D], [f64; D]);
        let per_element: Vec<Extremes<D>> = (0..self.element_count())
            .into_par_iter()
            .map(|e| {
                let (functions, _) = self.space.extraction(e);
                let mut out = (0.0f64, [f64::INFINITY; D], [f64::NEG_INFINITY; D]);
                for x in samples_of(&self.space, e) {
                    let y = value(&f, x)?;
                    let v = self.space.values_on(e, x);
                    for (k, &yk) in y.iter().enumerate() {
                        let s: f64 = functions
                            .iter()
                            .zip(&v)
                            .map(|(&i, w)| w * self.control[i][k])
                            .sum();
                        out.0 = out.0.max((s - yk).abs());
                        out.1[k] = out.1[k].min(yk);
                        out.2[k] = out.2[k].max(yk);
                    }
                }
                Ok(out)
            })
            .collect::<Result<_>>()?;
        let mut lo = [f64::INFINITY; D];
        let mut hi = [f64::NEG_INFINITY; D];
        let mut error = 0.0f64;
        for (err, l, h) in per_element {
            error = error.max(err);
            for k in 0..D {
                lo[k] = lo[k].min(l[k]);
                hi[k] = hi[k].max(h[k]);
            }
        }
        let size = (0..D).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        Ok((error, size))
    }

    /// Interpolates `f` at the interpolation points of the space (see
    /// [`SplineSpace::interpolation_points`]) by solving the square collocation system with a
    /// sparse LU. Fails when `f` is not defined (returns `None`) or not finite at a point, or
    /// when the system is singular.
    pub fn fit_collocation(
        space: S,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
    ) -> Result<(Self, FitReport)> {
        let start = Instant::now();
        let points = space.interpolation_points();
        let elements = elements_of(&space, &points)?;
        let rows: Vec<([f64; D], Vec<f64>)> = points
            .par_iter()
            .zip(&elements)
            .map(|(&x, &e)| Ok((value(&f, x)?, space.values_on(e, x))))
            .collect::<Result<_>>()?;
        let values: Vec<&[f64]> = rows.iter().map(|r| &r.1[..]).collect();
        let entries = collocation_entries(&space, &elements, &values);
        let n = space.basis_count();
        let lu = SparseSolver::lu(n, &entries)?;
        let mut control: Vec<[f64; D]> = rows.iter().map(|r| r.0).collect();
        lu.solve(&mut control);
        check_finite("control", &control.concat())?;
        let residual = rows
            .iter()
            .zip(&elements)
            .map(|((y, v), &e)| {
                let (functions, _) = space.extraction(e);
                (0..D)
                    .map(|k| {
                        let s: f64 = functions
                            .iter()
                            .zip(v)
                            .map(|(&i, w)| w * control[i][k])
                            .sum();
                        (s - y[k]).abs()
                    })
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        let map = SplineMap { space, control };
        let report = map.fit_report(residual, false, lu.reciprocal_condition(), start);
        Ok((map, report))
    }

    /// Least-squares fit of `f` at the interpolation points and the `4^d` points
    /// `((i + ½)/4)` of every element: the normal equations are non-singular because the
    /// functions are linearly independent on each element and a tensor polynomial of degree 3
    /// vanishing on a 4^d grid is zero. Reproduces every map of the space exactly. The normal
    /// equations are assembled element by element (each element's points give a dense block
    /// on its functions) and solved by sparse Cholesky.
    pub fn fit_least_squares(
        space: S,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
    ) -> Result<(Self, FitReport)> {
        let start = Instant::now();
        let (points_of, blocks) = least_squares_layout(&space)?;
        let (normal, rhs) = normal_equations(&space, &points_of, &blocks, &f)?;
        let llt = normal.cholesky()?;
        let mut control = rhs;
        llt.solve(&mut control);
        check_finite("control", &control.concat())?;
        let map = SplineMap { space, control };
        let residual = map.least_squares_residual(&points_of, &blocks, &f)?;
        let report = map.fit_report(residual, true, llt.reciprocal_condition(), start);
        Ok((map, report))
    }

    /// The largest coordinate difference between the map and `f` at the least-squares points
    /// (`points_of` and the samples of each element, whose functions are `blocks`).
    fn least_squares_residual(
        &self,
        points_of: &[Vec<[f64; D]>],
        blocks: &[Vec<usize>],
        f: &(impl Fn([f64; D]) -> Option<[f64; D]> + Sync),
    ) -> Result<f64> {
        Ok((0..self.space.element_count())
            .into_par_iter()
            .map(|e| {
                let functions = &blocks[e];
                let mut largest = 0.0f64;
                for x in least_squares_points(&self.space, points_of, e) {
                    let y = value(f, x)?;
                    let v = self.space.values_on(e, x);
                    for (k, yk) in y.iter().enumerate() {
                        let s: f64 = functions
                            .iter()
                            .zip(&v)
                            .map(|(&i, w)| w * self.control[i][k])
                            .sum();
                        largest = largest.max((s - yk).abs());
                    }
                }
                Ok(largest)
            })
            .collect::<Result<Vec<f64>>>()?
            .into_iter()
            .fold(0.0, f64::max))
    }

    /// The report of a fit by a linear solve.
    fn fit_report(
        &self,
        residual: f64,
        least_squares: bool,
        reciprocal_condition: f64,
        start: Instant,
    ) -> FitReport {
        FitReport {
            basis_count: self.basis_count(),
            element_count: self.element_count(),
            residual,
            least_squares,
            reciprocal_condition,
            seconds: start.elapsed().as_secs_f64(),
            ..Default::default()
        }
    }
}
