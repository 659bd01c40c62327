//! The interface of a spline space over the elements of a tree: what evaluation, interpolation,
//! certification and output need.

use super::bernstein::{bernstein3, SPAN_FUNCTIONS};
use crate::error::Result;

/// A spline space of degree 3 per direction on \[0,1\]^d, split into box elements on each of which
/// every function is a polynomial.
pub trait SplineSpace<const D: usize>: Clone + Send + Sync {
    /// Number of basis functions.
    fn basis_count(&self) -> usize;

    /// Number of elements.
    fn element_count(&self) -> usize;

    /// Parametric bounds `(lower, upper)` of element `e`.
    fn element_bounds(&self, e: usize) -> ([f64; D], [f64; D]);

    /// Refinement level of element `e` (its side is `2^-level`).
    fn element_level(&self, e: usize) -> u8;

    /// The element containing the parametric point `x`, `None` outside \[0,1\]^d. On shared
    /// element boundaries the element on the upper side is chosen.
    fn element_at(&self, x: [f64; D]) -> Option<usize>;

    /// The functions non-zero on element `e` (global indices, increasing) and the extraction
    /// operator `C^e`, row-major, one row of `4^d` Bernstein coefficients per function: Bernstein
    /// polynomial `b = Σ b_k 4^k` (direction 0 fastest) of degree 3 on the element.
    fn extraction(&self, e: usize) -> (&[usize], &[f64]);

    /// Greville points of the basis functions, in the order of the global indices.
    fn greville_points(&self) -> Vec<[f64; D]>;

    /// The points where [`SplineMap::fit`](super::SplineMap::fit) interpolates, one per
    /// function, in global order: the Greville points unless the space moves some to keep the
    /// collocation system non-singular.
    fn interpolation_points(&self) -> Vec<[f64; D]> {
        self.greville_points()
    }

    /// The space refined on the marked elements (and wherever its own rules require, e.g. to
    /// keep a tree balanced). The refined space contains this one.
    fn refine(&self, marked: &[usize]) -> Result<Self>;

    /// Values and first derivatives (with respect to the parametric coordinates) of the
    /// functions non-zero at `x`; `None` outside \[0,1\]^d.
    fn basis_at(&self, x: [f64; D]) -> Option<BasisValues<D>> {
        Some(self.basis_on(self.element_at(x)?, x))
    }

    /// The values at `x` of the functions non-zero on element `e` (in the order of
    /// [`SplineSpace::extraction`]): [`SplineSpace::basis_on`] without the gradients.
    fn values_on(&self, e: usize, x: [f64; D]) -> Vec<f64> {
        let (lo, hi) = self.element_bounds(e);
        let value: [[f64; SPAN_FUNCTIONS]; D] = std::array::from_fn(|k| {
            bernstein3(((x[k] - lo[k]) / (hi[k] - lo[k])).clamp(0.0, 1.0)).0
        });
        let count = SPAN_FUNCTIONS.pow(D as u32);
        let b: Vec<f64> = (0..count)
            .map(|flat| {
                (0..D)
                    .map(|k| value[k][flat / SPAN_FUNCTIONS.pow(k as u32) % SPAN_FUNCTIONS])
                    .product()
            })
            .collect();
        let (_, c) = self.extraction(e);
        c.chunks_exact(count)
            .map(|row| row.iter().zip(&b).map(|(cij, bj)| cij * bj).sum())
            .collect()
    }

    /// [`SplineSpace::basis_at`] with the element given: the polynomials of element `e` at `x`
    /// (a point of the element or of its boundary; outside it, `x` is clamped to the element).
    fn basis_on(&self, e: usize, x: [f64; D]) -> BasisValues<D> {
        let (lo, hi) = self.element_bounds(e);
        let mut value = [[0.0; SPAN_FUNCTIONS]; D];
        let mut slope = [[0.0; SPAN_FUNCTIONS]; D];
        for k in 0..D {
            let h = hi[k] - lo[k];
            let (v, d) = bernstein3(((x[k] - lo[k]) / h).clamp(0.0, 1.0));
            value[k] = v;
            slope[k] = d.map(|s| s / h);
        }
        let count = SPAN_FUNCTIONS.pow(D as u32);
        let mut b = vec![0.0; count];
        let mut db = vec![[0.0; D]; count];
        for flat in 0..count {
            let idx: [usize; D] = std::array::from_fn(|k| flat / SPAN_FUNCTIONS.pow(k as u32) % 4);
            b[flat] = (0..D).map(|k| value[k][idx[k]]).product();
            for (g, dbg) in db[flat].iter_mut().enumerate() {
                *dbg = (0..D)
                    .map(|k| {
                        if k == g {
                            slope[k][idx[k]]
                        } else {
                            value[k][idx[k]]
                        }
                    })
                    .product();
            }
        }
        let (functions, c) = self.extraction(e);
        let mut values = vec![0.0; functions.len()];
        let mut gradients = vec![[0.0; D]; functions.len()];
        for (i, row) in c.chunks_exact(count).enumerate() {
            for (flat, &cij) in row.iter().enumerate() {
                if cij == 0.0 {
                    continue;
                }
                values[i] += cij * b[flat];
                for g in 0..D {
                    gradients[i][g] += cij * db[flat][g];
                }
            }
        }
        BasisValues {
            element: e,
            functions: functions.to_vec(),
            values,
            gradients,
        }
    }
}

/// The functions non-zero at a point with their values and gradients.
#[derive(Clone, Debug, PartialEq)]
pub struct BasisValues<const D: usize> {
    /// The element holding the point.
    pub element: usize,
    /// Global indices of the functions non-zero on the element.
    pub functions: Vec<usize>,
    /// Their values at the point.
    pub values: Vec<f64>,
    /// Their gradients (with respect to the parametric coordinates) at the point.
    pub gradients: Vec<[f64; D]>,
}
