//! The T-mesh's piecewise quadratic map [0,1]^d → Ω: on each cell the quadratic Lagrange map of
//! its 3^d lattice points, the real ones at their vertex positions and the virtual ones completed
//! by [`lattice::completion`] — the map the optimizer shaped and the spline fit interpolates.

use std::collections::HashMap;

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
        let mut completions: HashMap<Vec<usize>, Vec<Vec<(usize, f64)>>> = HashMap::new();
        let mut nodes = Vec::with_capacity(mesh.cell_count());
        for c in 0..mesh.cell_count() {
            let (lat, ver) = mesh.cell_vertices(c);
            if !completions.contains_key(lat) {
                let rows = lattice::completion::<D>(lat)
                    .ok_or_else(|| Error::mesh(format!("cell {c} misses a corner")))?;
                completions.insert(lat.to_vec(), rows);
            }
            let rows = &completions[lat];
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
        })
    }

    /// The image of the parametric point `x`, `None` outside [0,1]^d.
    pub fn eval(&self, x: [f64; D]) -> Option<[f64; D]> {
        let c = self.leaf_of_cell[self.mesh.tree().leaf_at_point(&x)?];
        let (lo, hi) = self.mesh.cell_bounds(c);
        let shape: [[f64; 3]; D] = std::array::from_fn(|k| {
            let xi = 2.0 * (x[k] - lo[k]) / (hi[k] - lo[k]) - 1.0;
            [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)]
        });
        let mut y = [0.0; D];
        for (l, p) in self.nodes[c].iter().enumerate() {
            let lc = lattice::coords::<D>(l);
            let w: f64 = (0..D).map(|k| shape[k][lc[k]]).product();
            for k in 0..D {
                y[k] += w * p[k];
            }
        }
        Some(y)
    }
}
