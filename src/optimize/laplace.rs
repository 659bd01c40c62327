//! First placement by a discrete Laplace equation: the displacement of the free components is the
//! harmonic extension of the prescribed ones over the mesh graph (conjugate gradients).
//!
//! Two real nodes of a cell are neighbours when they lie on one lattice line of the cell with no
//! real node between them (along the edges of a linear cell, between consecutive nodes of a
//! quadratic one).

use super::lattice;
use super::problem::Problem;
use super::small::Vector;

/// The mesh graph: sorted, deduplicated neighbour lists.
fn neighbours<const D: usize>(problem: &Problem<D>) -> Vec<Vec<u32>> {
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); problem.node_count()];
    for c in 0..problem.cell_count() {
        let pattern = problem.pattern(c);
        let nodes = problem.cell_nodes(c);
        let coords: Vec<[usize; D]> = pattern.real.iter().map(|&l| lattice::coords::<D>(l)).collect();
        for a in 0..coords.len() {
            for b in a + 1..coords.len() {
                let differ: Vec<usize> = (0..D).filter(|&k| coords[a][k] != coords[b][k]).collect();
                if differ.len() != 1 {
                    continue;
                }
                let k = differ[0];
                let (lo, hi) = (coords[a][k].min(coords[b][k]), coords[a][k].max(coords[b][k]));
                let blocked = coords.iter().any(|c| {
                    c[k] > lo && c[k] < hi && (0..D).all(|l| l == k || c[l] == coords[a][l])
                });
                if !blocked {
                    adj[nodes[a] as usize].push(nodes[b]);
                    adj[nodes[b] as usize].push(nodes[a]);
                }
            }
        }
    }
    for list in &mut adj {
        list.sort_unstable();
        list.dedup();
    }
    adj
}

/// Moves the free components of every node to the harmonic extension of the displacement
/// `positions − reference` of the fixed ones. Returns the number of CG iterations used.
pub fn harmonic_placement<const D: usize>(
    problem: &Problem<D>,
    reference: &[Vector<D>],
    positions: &mut [Vector<D>],
) -> usize {
    let adj = neighbours(problem);
    let n = problem.node_count();
    let mut iterations = 0;
    for k in 0..D {
        let free: Vec<bool> = (0..n)
            .map(|v| problem.free_mask(v) & (1 << k) != 0 && !adj[v].is_empty())
            .collect();
        let displacement: Vec<f64> = (0..n).map(|v| positions[v][k] - reference[v][k]).collect();
        let apply = |u: &[f64], out: &mut [f64]| {
            for v in 0..n {
                out[v] = if free[v] {
                    adj[v].len() as f64 * u[v]
                        - adj[v].iter().filter(|&&w| free[w as usize]).map(|&w| u[w as usize]).sum::<f64>()
                } else {
                    0.0
                };
            }
        };
        let rhs: Vec<f64> = (0..n)
            .map(|v| {
                if free[v] {
                    adj[v].iter().filter(|&&w| !free[w as usize]).map(|&w| displacement[w as usize]).sum()
                } else {
                    0.0
                }
            })
            .collect();
        let mut u: Vec<f64> = (0..n).map(|v| if free[v] { displacement[v] } else { 0.0 }).collect();
        iterations += conjugate_gradients(&apply, &rhs, &mut u, 1e-12, 20 * n + 100);
        for v in 0..n {
            if free[v] {
                positions[v][k] = reference[v][k] + u[v];
            }
        }
    }
    iterations
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Solves `A u = b` for a symmetric positive semi-definite `A` given by `apply`; stops at
/// `‖r‖ ≤ tolerance·‖b‖` (or an absolute `tolerance` when `b = 0`). Returns the iterations.
fn conjugate_gradients(
    apply: &dyn Fn(&[f64], &mut [f64]),
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
    let mut p = r.clone();
    let mut ap = vec![0.0; n];
    let mut rr = dot(&r, &r);
    for it in 0..max_iterations {
        if rr.sqrt() <= stop {
            return it;
        }
        apply(&p, &mut ap);
        let pap = dot(&p, &ap);
        if pap <= 0.0 {
            return it;
        }
        let alpha = rr / pap;
        for i in 0..n {
            u[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
        }
        let rr_new = dot(&r, &r);
        let beta = rr_new / rr;
        rr = rr_new;
        for i in 0..n {
            p[i] = r[i] + beta * p[i];
        }
    }
    max_iterations
}
