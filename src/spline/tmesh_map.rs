//! The T-mesh's piecewise quadratic map \[0,1\]^d → Ω: on each cell the quadratic Lagrange map of
//! its 3^d lattice points, the real ones at their vertex positions and the virtual ones completed
//! by [`lattice::completion`] — the map the optimizer shaped and the spline fit interpolates.

use std::collections::HashMap;

use rayon::prelude::*;

use super::bernstein::Bernstein;
use super::jacobian::{jacobian_determinant, lower_bound};
use crate::error::{Error, Result};
use crate::optimize::lattice;
use crate::tmesh::TMesh;

/// A T-mesh with vertex positions, evaluated as its piecewise quadratic map.
#[derive(Clone, Debug)]
pub struct QuadraticMap<'a, const D: usize> {
    mesh: &'a TMesh<D>,
    leaf_of_cell: Vec<usize>,
    /// Per cell, the positions of its 3^d lattice points.
    nodes: Vec<Vec<[f64; D]>>,
    /// The distinct completions of the cells' lattice points ([`lattice::completion`]: per
    /// lattice point, its (real point, weight) terms), and each cell's among them.
    completions: Vec<Vec<Vec<(usize, f64)>>>,
    completion_of_cell: Vec<usize>,
}

impl<'a, const D: usize> QuadraticMap<'a, D> {
    /// The map of `mesh` with vertex `v` at `positions[v]`.
    pub fn new(mesh: &'a TMesh<D>, positions: &[[f64; D]]) -> Result<Self> {
        if positions.len() != mesh.vertex_count() {
            return Err(Error::invalid(format!(
                "{} positions for {} vertices",
                positions.len(),
                mesh.vertex_count()
            )));
        }
        let mut index: HashMap<&[usize], usize> = HashMap::new();
        let mut completions = Vec::new();
        let mut completion_of_cell = Vec::with_capacity(mesh.cell_count());
        let mut nodes = Vec::with_capacity(mesh.cell_count());
        for c in 0..mesh.cell_count() {
            let (lat, ver) = mesh.cell_vertices(c);
            let i = match index.get(lat) {
                Some(&i) => i,
                None => {
                    let rows = lattice::completion::<D>(lat)
                        .ok_or_else(|| Error::mesh(format!("cell {c} misses a corner")))?;
                    completions.push(rows);
                    index.insert(lat, completions.len() - 1);
                    completions.len() - 1
                }
            };
            completion_of_cell.push(i);
            let rows = &completions[i];
            nodes.push(
                rows.iter()
                    .map(|row| {
                        let mut x = [0.0; D];
                        for &(r, w) in row {
                            for k in 0..D {
                                x[k] += w * positions[ver[r] as usize][k];
                            }
                        }
                        x
                    })
                    .collect(),
            );
        }
        let mut leaf_of_cell = vec![usize::MAX; mesh.tree().cells().len()];
        for (i, &c) in mesh.leaves().iter().enumerate() {
            leaf_of_cell[c] = i;
        }
        Ok(QuadraticMap {
            mesh,
            leaf_of_cell,
            nodes,
            completions,
            completion_of_cell,
        })
    }

    /// The image of the parametric point `x`, `None` outside \[0,1\]^d.
    pub fn eval(&self, x: [f64; D]) -> Option<[f64; D]> {
        let c = self.leaf_of_cell[self.mesh.tree().leaf_at_point(&x)?];
        let mut y = [0.0; D];
        for (p, w) in self.nodes[c].iter().zip(lagrange_weights(self.mesh, c, x)) {
            for k in 0..D {
                y[k] += w * p[k];
            }
        }
        Some(y)
    }

    /// The map's value at the parametric point `x` as a combination of the vertex positions:
    /// the pairs (vertex, weight), a vertex possibly repeated (through the completion of the
    /// virtual lattice points); `None` outside \[0,1\]^d. The map is linear in the positions,
    /// and these are its coefficients at `x`, the same for every coordinate.
    pub fn vertex_weights(&self, x: [f64; D]) -> Option<Vec<(usize, f64)>> {
        let c = self.leaf_of_cell[self.mesh.tree().leaf_at_point(&x)?];
        let (_, ver) = self.mesh.cell_vertices(c);
        let rows = &self.completions[self.completion_of_cell[c]];
        let mut out = Vec::new();
        for (row, w) in rows.iter().zip(lagrange_weights(self.mesh, c, x)) {
            out.extend(row.iter().map(|&(r, rw)| (ver[r] as usize, w * rw)));
        }
        Some(out)
    }

    /// `det J` of cell `c`'s quadratic map, with respect to the parametric coordinates, as a
    /// Bernstein polynomial (degree `2d − 1` per direction) on the cell mapped to \[0,1\]^d.
    pub fn cell_det_polynomial(&self, c: usize) -> Bernstein<D> {
        let (lo, hi) = self.mesh.cell_bounds(c);
        let patches: Vec<Bernstein<D>> = (0..D)
            .map(|a| {
                // The lattice and the Bernstein coefficients share their order (direction 0
                // fastest); the values at 0, ½, 1 become Bernstein coefficients direction by
                // direction: b₁ = 2·f(½) − (f(0) + f(1))/2.
                let mut p = Bernstein::zero([2; D]);
                for (l, x) in self.nodes[c].iter().enumerate() {
                    p.coef[l] = x[a];
                }
                for k in 0..D {
                    let stride = 3usize.pow(k as u32);
                    for l in 0..p.coef.len() {
                        if lattice::coords::<D>(l)[k] == 1 {
                            let (f0, f2) = (p.coef[l - stride], p.coef[l + stride]);
                            p.coef[l] = 2.0 * p.coef[l] - 0.5 * (f0 + f2);
                        }
                    }
                }
                p
            })
            .collect();
        jacobian_determinant(&patches, lo, hi)
    }

    /// The cells on which `det J > 0` is not proven by the Bernstein coefficients of
    /// [`QuadraticMap::cell_det_polynomial`], subdivided at most `depth` times (in parallel,
    /// in cell order).
    pub fn uncertified_cells(&self, depth: u32) -> Vec<usize> {
        (0..self.nodes.len())
            .into_par_iter()
            .filter(|&c| lower_bound(&self.cell_det_polynomial(c), depth) <= 0.0)
            .collect()
    }
}

/// The values at `x` of the `3^d` quadratic Lagrange functions of cell `c`'s lattice points, in
/// lattice order.
fn lagrange_weights<const D: usize>(mesh: &TMesh<D>, c: usize, x: [f64; D]) -> Vec<f64> {
    let (lo, hi) = mesh.cell_bounds(c);
    let shape: [[f64; 3]; D] = std::array::from_fn(|k| {
        let xi = 2.0 * (x[k] - lo[k]) / (hi[k] - lo[k]) - 1.0;
        [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)]
    });
    (0..lattice::count(D))
        .map(|l| {
            let lc = lattice::coords::<D>(l);
            (0..D).map(|k| shape[k][lc[k]]).product()
        })
        .collect()
}
