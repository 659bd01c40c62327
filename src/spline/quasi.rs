//! Quasi-interpolation in the THB space: each coefficient is read off polynomial pieces by the
//! dual functional of its B-spline (the blossom at its inner knots), averaged over the elements
//! of the function's level in its support. On such an element the function is not truncated
//! and every other function of the space is a combination of the other B-splines of that level,
//! so the operator reproduces every map of the space exactly (the coefficient preservation of
//! truncated hierarchical B-splines). Local, with no linear system: it refines a map exactly
//! and fits maps given piece by piece.

use std::time::Instant;

use rayon::prelude::*;

use super::bernstein::{bernstein3, extraction, Matrix4};
use super::fit::FitReport;
use super::map::SplineMap;
use super::piece::Piece;
use super::space::SplineSpace;
use super::thb::{support_span_indices, tensor_apply, ThbSpace};
use crate::error::{check_finite, Error, Result};

/// Interior points of the local interpolation, per direction, in [0, 1].
const LOCAL_POINTS: [f64; 4] = [0.125, 0.375, 0.625, 0.875];

/// The matrix taking the values of a cubic at [`LOCAL_POINTS`] to its Bernstein coefficients,
/// stored transposed for [`tensor_apply`] (`m[j][b]`: value at `t_j` → coefficient `b`): the
/// inverse of the collocation matrix `V[j][b] = B_b(t_j)`, by Gauss–Jordan elimination with
/// partial pivoting, transposed.
fn local_interpolation() -> Matrix4 {
    let mut a: Matrix4 = std::array::from_fn(|j| bernstein3(LOCAL_POINTS[j]).0);
    let mut inv: Matrix4 = std::array::from_fn(|i| std::array::from_fn(|j| (i == j) as u8 as f64));
    for col in 0..4 {
        let pivot = (col..4)
            .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
            .unwrap_or(col);
        a.swap(col, pivot);
        inv.swap(col, pivot);
        let p = a[col][col];
        for j in 0..4 {
            a[col][j] /= p;
            inv[col][j] /= p;
        }
        for row in 0..4 {
            if row != col {
                let factor = a[row][col];
                for j in 0..4 {
                    a[row][j] -= factor * a[col][j];
                    inv[row][j] -= factor * inv[col][j];
                }
            }
        }
    }
    std::array::from_fn(|j| std::array::from_fn(|b| inv[b][j]))
}

impl<const D: usize> ThbSpace<D> {
    /// The elements of function `i`'s level in its support, each with the integral of the
    /// (untruncated) B-spline over it relative to the cell size.
    fn coefficient_cells(&self, i: usize) -> Vec<(usize, f64)> {
        let (level, f) = self.functions()[i];
        let h = 1.0 / (1u64 << level) as f64;
        let spans = support_span_indices(level, &f);
        let mut out = Vec::with_capacity(spans.len());
        for span in spans {
            let centre = std::array::from_fn(|k| (span[k] as f64 + 0.5) * h);
            let Some(e) = self.element_at(centre) else {
                continue;
            };
            if self.element_level(e) != level {
                continue;
            }
            let weight: f64 = (0..D)
                .map(|k| {
                    extraction(level, span[k])[f[k] as usize - span[k]]
                        .iter()
                        .sum::<f64>()
                })
                .product();
            out.push((e, weight));
        }
        out
    }
}

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// The map whose coefficients are those of the pieces: per function, the weighted mean
    /// (weights: the B-spline's integral over each element) of the coefficients read on the
    /// elements of its level in its support, element `e` seeing `pieces[piece_of(e)]`.
    fn quasi_interpolate(
        space: ThbSpace<D>,
        pieces: &[Piece<D>],
        piece_of: impl Fn(&ThbSpace<D>, usize) -> Result<usize> + Sync,
    ) -> Result<Self> {
        let control: Vec<[f64; D]> = (0..space.basis_count())
            .into_par_iter()
            .map(|i| {
                let (level, f) = space.functions()[i];
                let mut sum = [0.0; D];
                let mut total = 0.0;
                for (e, w) in space.coefficient_cells(i) {
                    let c = pieces[piece_of(&space, e)?].coefficient(level, &f);
                    for k in 0..D {
                        sum[k] += w * c[k];
                    }
                    total += w;
                }
                if total <= 0.0 {
                    return Err(Error::invalid(format!(
                        "function {i} has no element of its level in its support"
                    )));
                }
                Ok(sum.map(|v| v / total))
            })
            .collect::<Result<_>>()?;
        check_finite("control", &control.concat())?;
        SplineMap::new(space, control)
    }

    /// Largest coordinate difference between this map and `other` at this map's Greville points.
    fn difference_at_greville(&self, other: impl Fn([f64; D]) -> Option<[f64; D]> + Sync) -> f64 {
        self.space
            .greville_points()
            .par_iter()
            .filter_map(|&x| Some((self.eval(x)?, other(x)?)))
            .map(|(a, b)| (0..D).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max))
            .reduce(|| 0.0, f64::max)
    }

    /// The report of a quasi-interpolation with the given residual.
    fn quasi_report(&self, residual: f64, start: Instant) -> FitReport {
        FitReport {
            basis_count: self.basis_count(),
            element_count: self.element_count(),
            residual,
            least_squares: false,
            quasi_interpolation: true,
            reciprocal_condition: 1.0,
            seconds: start.elapsed().as_secs_f64(),
            ..Default::default()
        }
    }

    /// The map on the space refined at the marked elements (all of them for uniform
    /// refinement), unchanged: the spaces are nested and the quasi-interpolant of the map's
    /// own pieces reproduces it. Local and exact; the report's residual is the largest
    /// difference between the two maps at the new space's Greville points (round-off).
    /// Each element may be marked once: an index out of range or repeated is refused, naming
    /// its positions in `marked`.
    pub fn refine(&self, marked: &[usize]) -> Result<(Self, FitReport)> {
        let start = Instant::now();
        check_marked(marked, self.element_count())?;
        let space = self.space.refine(marked)?;
        let pieces: Vec<Piece<D>> = (0..self.element_count())
            .into_par_iter()
            .map(|e| self.piece(e))
            .collect();
        let refined = Self::quasi_interpolate(space, &pieces, |space, e| {
            let (lo, hi) = space.element_bounds(e);
            let centre = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
            self.space
                .element_at(centre)
                .ok_or_else(|| Error::invalid(format!("refined element centre {centre:?} outside")))
        })?;
        let residual = refined.difference_at_greville(|x| self.eval(x));
        let report = refined.quasi_report(residual, start);
        Ok((refined, report))
    }

    /// The map refined uniformly once.
    pub fn refine_uniformly(&self) -> Result<(Self, FitReport)> {
        let all: Vec<usize> = (0..self.element_count()).collect();
        self.refine(&all)
    }

    /// Fits `f` by quasi-interpolation: on every element, the cubic interpolating `f` at the
    /// `4^d` points `(1 + 2i)/8` (exact where `f` is a polynomial of degree ≤ 3 per direction on
    /// the element, as the T-mesh's piecewise map is), then the coefficients as above. Needs no
    /// linear system and cannot be ill-conditioned; reproduces every map of the space. The
    /// report's residual is the largest difference from `f` at the Greville points.
    pub fn fit_quasi_interpolation(
        space: ThbSpace<D>,
        f: impl Fn([f64; D]) -> Option<[f64; D]> + Sync,
    ) -> Result<(Self, FitReport)> {
        let start = Instant::now();
        let inverse = local_interpolation();
        let local = 4usize.pow(D as u32);
        let pieces: Vec<Piece<D>> = (0..space.element_count())
            .into_par_iter()
            .map(|e| {
                let (lo, hi) = space.element_bounds(e);
                let values = (0..local)
                    .map(|s| {
                        let x = std::array::from_fn(|k| {
                            let t = LOCAL_POINTS[s >> (2 * k) & 3];
                            lo[k] + (hi[k] - lo[k]) * t
                        });
                        let y = f(x).ok_or_else(|| {
                            Error::invalid(format!("the map to fit is not defined at {x:?}"))
                        })?;
                        check_finite("fitted value", &y)?;
                        Ok(y)
                    })
                    .collect::<Result<Vec<_>>>()?;
                // Per coordinate, `inverse` applied in every direction.
                let coordinates: [Vec<f64>; D] = std::array::from_fn(|k| {
                    let v: Vec<f64> = values.iter().map(|y| y[k]).collect();
                    tensor_apply(&[inverse; D], &v)
                });
                let bernstein = (0..local)
                    .map(|b| std::array::from_fn(|k| coordinates[k][b]))
                    .collect();
                Ok(Piece { lo, hi, bernstein })
            })
            .collect::<Result<_>>()?;
        let map = Self::quasi_interpolate(space, &pieces, |_, e| Ok(e))?;
        let residual = map.difference_at_greville(&f);
        let report = map.quasi_report(residual, start);
        Ok((map, report))
    }
}

/// Refuses a marking with an element out of range or marked twice, naming the positions in
/// `marked` (the caller's indices).
fn check_marked(marked: &[usize], count: usize) -> Result<()> {
    let mut first = std::collections::HashMap::with_capacity(marked.len());
    for (i, &e) in marked.iter().enumerate() {
        if e >= count {
            return Err(Error::invalid(format!(
                "elements[{i}] = {e} is out of range (the map has {count} elements)"
            )));
        }
        if let Some(j) = first.insert(e, i) {
            return Err(Error::invalid(format!(
                "elements[{i}] = {e} repeats elements[{j}]: mark each element once"
            )));
        }
    }
    Ok(())
}
