//! The polynomial piece of a spline map on one element, in tensor Bernstein form: what the
//! quasi-interpolant reads coefficients from, and what the certification and the sampled
//! quality evaluate (one set of `4^d` Bézier points per element instead of the basis at every
//! point).

use super::bernstein::{bernstein_blossom, knot, Bernstein, GridTables};
use super::jacobian::jacobian_determinant;
use super::map::SplineMap;
use super::space::SplineSpace;
use crate::optimize::small_matrix::Matrix;

/// A polynomial of degree 3 per direction on a box: its tensor Bernstein coefficients there
/// (`4^d` points, direction 0 fastest).
#[derive(Clone, Debug)]
pub(super) struct Piece<const D: usize> {
    pub(super) lo: [f64; D],
    pub(super) hi: [f64; D],
    pub(super) bernstein: Vec<[f64; D]>,
}

impl<const D: usize> Piece<D> {
    /// The coefficient of B-spline `f` of `level` in this polynomial: its blossom at the
    /// function's inner knots, per direction.
    pub(super) fn coefficient(&self, level: u8, f: &[u32; D]) -> [f64; D] {
        let dual: [[f64; 4]; D] = std::array::from_fn(|k| {
            bernstein_blossom(std::array::from_fn(|r| {
                (knot(level, f[k] as i64 + 1 + r as i64) - self.lo[k]) / (self.hi[k] - self.lo[k])
            }))
        });
        let mut out = [0.0; D];
        for (b, p) in self.bernstein.iter().enumerate() {
            let w: f64 = (0..D).map(|k| dual[k][b >> (2 * k) & 3]).product();
            for k in 0..D {
                out[k] += w * p[k];
            }
        }
        out
    }

    /// Component `a` of the piece as a Bernstein polynomial on the box mapped to \[0,1\]^d.
    pub(super) fn component(&self, a: usize) -> Bernstein<D> {
        Bernstein {
            degree: [3; D],
            coef: self.bernstein.iter().map(|p| p[a]).collect(),
        }
    }

    /// `det J` on the box, the Jacobian with respect to the parametric coordinates, as a
    /// Bernstein polynomial of degree `3d − 1` per direction on the box mapped to \[0,1\]^d.
    pub(super) fn det_polynomial(&self) -> Bernstein<D> {
        let components: Vec<Bernstein<D>> = (0..D).map(|a| self.component(a)).collect();
        jacobian_determinant(&components, self.lo, self.hi)
    }

    /// The Jacobians (`J[a][b] = ∂S_a/∂x_b`, parametric coordinates) at the `n^d` points of the
    /// box's uniform grid, its corners included (`n ≥ 2`), direction 0 fastest.
    pub(super) fn grid_jacobians(&self, n: usize) -> Vec<Matrix<D>> {
        let grid = GridTables::new(n);
        let n = grid.points();
        // Per direction and grid line: the four Bernstein values and slopes on the box.
        let tables: [Vec<([f64; 4], [f64; 4])>; D] = std::array::from_fn(|k| {
            let h = self.hi[k] - self.lo[k];
            grid.values
                .iter()
                .zip(&grid.slopes)
                .map(|(v, d)| (*v, d.map(|s| s / h)))
                .collect()
        });
        (0..n.pow(D as u32))
            .map(|s| {
                let line: [usize; D] = std::array::from_fn(|k| s / n.pow(k as u32) % n);
                let mut j = [[0.0; D]; D];
                for (b, p) in self.bernstein.iter().enumerate() {
                    let digit: [usize; D] = std::array::from_fn(|k| b >> (2 * k) & 3);
                    for c in 0..D {
                        let w: f64 = (0..D)
                            .map(|k| {
                                let (v, d) = &tables[k][line[k]];
                                if k == c {
                                    d[digit[k]]
                                } else {
                                    v[digit[k]]
                                }
                            })
                            .product();
                        for (row, pa) in j.iter_mut().zip(p) {
                            row[c] += w * pa;
                        }
                    }
                }
                j
            })
            .collect()
    }
}

impl<const D: usize, S: SplineSpace<D>> SplineMap<D, S> {
    /// The polynomial piece of the map on element `e`.
    pub(super) fn piece(&self, e: usize) -> Piece<D> {
        self.piece_with(e, &self.control)
    }

    /// The polynomial piece on element `e` of the map of this space with control points
    /// `control`.
    pub(super) fn piece_with(&self, e: usize, control: &[[f64; D]]) -> Piece<D> {
        let (lo, hi) = self.space.element_bounds(e);
        let local = 4usize.pow(D as u32);
        let (functions, c) = self.space.extraction(e);
        let mut bernstein = vec![[0.0; D]; local];
        for (&j, row) in functions.iter().zip(c.chunks_exact(local)) {
            for (b, &v) in bernstein.iter_mut().zip(row) {
                for (bk, ck) in b.iter_mut().zip(&control[j]) {
                    *bk += v * ck;
                }
            }
        }
        Piece { lo, hi, bernstein }
    }
}
