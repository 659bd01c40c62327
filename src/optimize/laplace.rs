//! First placement by a discrete Laplace equation: the displacement of the free components is the
//! harmonic extension of the prescribed ones over the mesh graph (conjugate gradients).
//!
//! Two real nodes of a cell are neighbours when they lie on one lattice line of the cell with no
//! real node between them (along the edges of a linear cell, between consecutive nodes of a
//! quadratic one).

use rayon::prelude::*;

use super::lattice;
use super::problem::Problem;
use super::small::Vector;

/// The mesh graph in compressed rows: neighbours of node `v` are
/// `neighbours[start[v]..start[v + 1]]`.
pub struct MeshGraph {
    start: Vec<usize>,
    neighbours: Vec<u32>,
}

impl MeshGraph {
    /// Builds the graph of a problem's cells.
    pub fn new<const D: usize>(problem: &Problem<D>) -> Self {
        let mut adj: Vec<Vec<u32>> = vec![Vec::new(); problem.node_count()];
        for c in 0..problem.cell_count() {
            let pattern = problem.pattern(c);
            let nodes = problem.cell_nodes(c);
            let coords: Vec<[usize; D]> = pattern
                .real
                .iter()
                .map(|&l| lattice::coords::<D>(l))
                .collect();
            for a in 0..coords.len() {
                for b in a + 1..coords.len() {
                    if adjacent_on_lattice_line(&coords, a, b) {
                        adj[nodes[a] as usize].push(nodes[b]);
                        adj[nodes[b] as usize].push(nodes[a]);
                    }
                }
            }
        }
        let mut start = vec![0];
        let mut neighbours = Vec::new();
        for mut list in adj {
            list.sort_unstable();
            list.dedup();
            neighbours.extend_from_slice(&list);
            start.push(neighbours.len());
        }
        MeshGraph { start, neighbours }
    }

    fn of(&self, v: usize) -> &[u32] {
        &self.neighbours[self.start[v]..self.start[v + 1]]
    }

    /// Moves the free components of every node to the harmonic extension of the displacement
    /// `positions − reference` of the fixed ones. Returns the number of CG iterations used.
    pub fn harmonic_placement<const D: usize>(
        &self,
        problem: &Problem<D>,
        reference: &[Vector<D>],
        positions: &mut [Vector<D>],
    ) -> usize {
        let n = problem.node_count();
        let degree: Vec<f64> = (0..n).map(|v| self.of(v).len() as f64).collect();
        let mut iterations = 0;
        for k in 0..D {
            let free: Vec<bool> = (0..n)
                .map(|v| problem.free_mask(v) & (1 << k) != 0 && degree[v] > 0.0)
                .collect();
            let displacement: Vec<f64> =
                (0..n).map(|v| positions[v][k] - reference[v][k]).collect();
            // Every vector of the iteration vanishes at the fixed nodes, so the matrix–vector
            // product needs no test on the neighbours.
            let apply = |u: &[f64], out: &mut [f64]| {
                out.par_iter_mut().enumerate().for_each(|(v, o)| {
                    *o = if free[v] {
                        degree[v] * u[v] - self.of(v).iter().map(|&w| u[w as usize]).sum::<f64>()
                    } else {
                        0.0
                    };
                });
            };
            let rhs: Vec<f64> = (0..n)
                .map(|v| {
                    let fixed_sum = || {
                        self.of(v)
                            .iter()
                            .filter(|&&w| !free[w as usize])
                            .map(|&w| displacement[w as usize])
                            .sum()
                    };
                    if free[v] {
                        fixed_sum()
                    } else {
                        0.0
                    }
                })
                .collect();
            let mut u: Vec<f64> = (0..n)
                .map(|v| if free[v] { displacement[v] } else { 0.0 })
                .collect();
            let diagonal: Vec<f64> = degree.iter().map(|&d| d.max(1.0)).collect();
            iterations += conjugate_gradients(&apply, &diagonal, &rhs, &mut u, 1e-10, 4 * n + 100);
            for v in 0..n {
                if free[v] {
                    positions[v][k] = reference[v][k] + u[v];
                }
            }
        }
        iterations
    }
}

/// Whether lattice points `a` and `b` of a cell's real nodes lie on one lattice line with no
/// other real node between them.
fn adjacent_on_lattice_line<const D: usize>(coords: &[[usize; D]], a: usize, b: usize) -> bool {
    let differ: Vec<usize> = (0..D).filter(|&k| coords[a][k] != coords[b][k]).collect();
    let [k] = differ[..] else { return false };
    let (lo, hi) = (
        coords[a][k].min(coords[b][k]),
        coords[a][k].max(coords[b][k]),
    );
    !coords
        .iter()
        .any(|c| c[k] > lo && c[k] < hi && (0..D).all(|l| l == k || c[l] == coords[a][l]))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Solves `A u = b` for a symmetric positive semi-definite `A` given by `apply`, with the
/// Jacobi preconditioner `diagonal`; stops at `‖r‖ ≤ tolerance·max(‖b‖, 1)`. Returns the
/// iterations.
fn conjugate_gradients(
    apply: &dyn Fn(&[f64], &mut [f64]),
    diagonal: &[f64],
    b: &[f64],
    u: &mut [f64],
    tolerance: f64,
    max_iterations: usize,
) -> usize {
    let n = b.len();
    let mut r = vec![0.0; n];
    apply(u, &mut r);
    for (ri, bi) in r.iter_mut().zip(b) {
        *ri = bi - *ri;
    }
    let stop = tolerance * dot(b, b).sqrt().max(1.0);
    let precondition =
        |r: &[f64]| -> Vec<f64> { r.iter().zip(diagonal).map(|(x, d)| x / d).collect() };
    let mut z = precondition(&r);
    let mut p = z.clone();
    let mut ap = vec![0.0; n];
    let mut rz = dot(&r, &z);
    for it in 0..max_iterations {
        if dot(&r, &r).sqrt() <= stop {
            return it;
        }
        apply(&p, &mut ap);
        let pap = dot(&p, &ap);
        if pap <= 0.0 {
            return it;
        }
        let alpha = rz / pap;
        for i in 0..n {
            u[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
        }
        z = precondition(&r);
        let rz_new = dot(&r, &z);
        let beta = rz_new / rz;
        rz = rz_new;
        for i in 0..n {
            p[i] = z[i] + beta * p[i];
        }
    }
    max_iterations
}
