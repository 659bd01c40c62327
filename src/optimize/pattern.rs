//! A cell pattern: which lattice points of a quadratic cell are real nodes, and the resulting
//! Jacobian stencils at the Gauss–Lobatto points.

use super::lattice;
use super::small_matrix::{Matrix, Vector};

/// One term of a Jacobian stencil: local real node and the vector `G` with
/// `J(ξ_q) = Σ x_r ⊗ G_{q,r}`.
pub type StencilTerm<const D: usize> = (u8, Vector<D>);

/// The Jacobian stencils of one kind of cell (one set of real lattice points).
#[derive(Clone, Debug)]
pub struct CellPattern<const D: usize> {
    /// Number of real nodes of the cell.
    pub real_count: usize,
    /// Lattice point of each real node.
    pub real: Vec<usize>,
    /// For each real node `r`: the points `q` whose Jacobian depends on it, with `G_{q,r}`.
    pub influence: Vec<Vec<StencilTerm<D>>>,
    /// For each point `q`: the real nodes its Jacobian depends on, with `G_{q,r}`.
    pub jacobian: Vec<Vec<StencilTerm<D>>>,
}

impl<const D: usize> CellPattern<D> {
    /// Builds the pattern of a cell whose real node `r` sits at lattice point `real[r]`; the
    /// missing points are virtual nodes (see [`lattice::completion`]). `None` if a corner is
    /// missing or a lattice point is given twice.
    pub fn new(real: &[usize]) -> Option<Self> {
        let n = lattice::count(D);
        let mut seen = vec![false; n];
        for &l in real {
            if l >= n || std::mem::replace(&mut seen[l], true) {
                return None;
            }
        }
        let rows = lattice::completion::<D>(real)?;
        let mut jacobian = vec![Vec::new(); n];
        let mut influence = vec![Vec::new(); real.len()];
        for (q, stencil) in jacobian.iter_mut().enumerate() {
            let mut dense = vec![[0.0; D]; real.len()];
            for (l, row) in rows.iter().enumerate() {
                let g = lattice::shape_gradient::<D>(l, q);
                if g.iter().all(|&v| v == 0.0) {
                    continue;
                }
                for &(r, coef) in row {
                    for k in 0..D {
                        dense[r][k] += coef * g[k];
                    }
                }
            }
            for (r, g) in dense.into_iter().enumerate() {
                if g.iter().any(|v| v.abs() > 1e-14) {
                    stencil.push((r as u8, g));
                    influence[r].push((q as u8, g));
                }
            }
        }
        Some(CellPattern {
            real_count: real.len(),
            real: real.to_vec(),
            influence,
            jacobian,
        })
    }

    /// Jacobian `∂x/∂ξ` at point `q`, the real node positions given by `position(r)`.
    pub fn jacobian_at(&self, q: usize, position: impl Fn(usize) -> Vector<D>) -> Matrix<D> {
        let mut j = [[0.0; D]; D];
        for &(r, g) in &self.jacobian[q] {
            let x = position(r as usize);
            for a in 0..D {
                for b in 0..D {
                    j[a][b] += x[a] * g[b];
                }
            }
        }
        j
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_quadratic_cell_touches_2d_plus_1_points_per_node() {
        let p = CellPattern::<3>::new(&(0..27).collect::<Vec<_>>()).unwrap();
        // The body centre influences the 7 points on the grid lines through it.
        assert_eq!(p.influence[13].len(), 6);
        assert!(p.influence.iter().all(|l| l.len() <= 7));
        let p2 = CellPattern::<2>::new(&(0..9).collect::<Vec<_>>()).unwrap();
        assert!(p2.influence.iter().all(|l| l.len() <= 5));
    }

    #[test]
    fn linear_cell_reproduces_affine_jacobian() {
        let corners = [0, 2, 6, 8];
        let p = CellPattern::<2>::new(&corners).unwrap();
        let a = [[2.0, 0.5], [-0.3, 1.5]];
        let pos = |r: usize| {
            let c = lattice::coords::<2>(corners[r]);
            let xi = [c[0] as f64 - 1.0, c[1] as f64 - 1.0];
            [
                a[0][0] * xi[0] + a[0][1] * xi[1] + 3.0,
                a[1][0] * xi[0] + a[1][1] * xi[1] - 1.0,
            ]
        };
        for q in 0..9 {
            let j = p.jacobian_at(q, pos);
            for i in 0..2 {
                for k in 0..2 {
                    assert!((j[i][k] - a[i][k]).abs() < 1e-14);
                }
            }
        }
    }
}
