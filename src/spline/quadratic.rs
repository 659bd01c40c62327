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

    /// The map of `mesh` made continuous across the T-junctions: where a cell's virtual
    /// lattice point lies on the boundary of a coarser cell, it takes that cell's image of the
    /// point instead of the mean of its edge's or face's nodes. The cells then agree on their
    /// shared edges and faces (a fine cell's face inside a coarse cell's face is the same
    /// quadratic patch), while on a uniform mesh nothing changes. This is the map the spline
    /// fit approximates: a fit can follow a continuous map, not jumps at the T-junctions.
    pub fn conforming(mesh: &'a TMesh<D>, positions: &[[f64; D]]) -> Result<Self> {
        let mut map = Self::new(mesh, positions)?;
        let lattice_points = 3usize.pow(D as u32);
        let tree = mesh.tree();
        let replaced: Vec<Vec<(usize, [f64; D])>> = (0..mesh.cell_count())
            .map(|c| {
                let (real, _) = mesh.cell_vertices(c);
                let level = mesh.cell_level(c);
                let (lo, hi) = mesh.cell_bounds(c);
                let delta = 1e-3 * (hi[0] - lo[0]);
                (0..lattice_points)
                    .filter(|l| !real.contains(l))
                    .filter_map(|l| {
                        let lc = lattice::coords::<D>(l);
                        let p: [f64; D] =
                            std::array::from_fn(|k| lo[k] + (hi[k] - lo[k]) * lc[k] as f64 / 2.0);
                        let coarsest = (0..1usize << D)
                            .filter_map(|s| {
                                let q = std::array::from_fn(|k| {
                                    p[k] + if s >> k & 1 == 1 { delta } else { -delta }
                                });
                                tree.leaf_at_point(&q).map(|leaf| map.leaf_of_cell[leaf])
                            })
                            .filter(|&n| mesh.cell_level(n) < level)
                            .min_by_key(|&n| (mesh.cell_level(n), n))?;
                        Some((l, map.eval_cell(coarsest, p)))
                    })
                    .collect()
            })
            .collect();
        for (nodes, fix) in map.nodes.iter_mut().zip(replaced) {
            for (l, y) in fix {
                nodes[l] = y;
            }
        }
        Ok(map)
    }

    /// The image of the parametric point `x`, `None` outside [0,1]^d.
    pub fn eval(&self, x: [f64; D]) -> Option<[f64; D]> {
        let c = self.leaf_of_cell[self.mesh.tree().leaf_at_point(&x)?];
        Some(self.eval_cell(c, x))
    }

    /// The image of `x` by the quadratic map of cell `c` (extended outside the cell).
    fn eval_cell(&self, c: usize, x: [f64; D]) -> [f64; D] {
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
        y
    }
}
