//! First placement by a discrete Laplace equation: the displacement of the free components is the
//! harmonic extension of the prescribed ones over the mesh graph (conjugate gradients).
//!
//! Two real nodes of a cell are neighbours when they lie on one lattice line of the cell with no
//! real node between them (along the edges of a linear cell, between consecutive nodes of a
//! quadratic one).

use rayon::prelude::*;
use rayon::ThreadPool;

use super::exact::ExactSum;
use super::lattice;
use super::problem::Problem;
use super::small_matrix::Vector;
use super::team::{Alone, Team};
use crate::error::Result;

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
        // Runs in the caller's pool (`ThreadPool::install`); a team of one never fails.
        self.place_on(&mut Alone, None, problem, reference, positions)
            .unwrap_or(0)
    }

    /// [`MeshGraph::harmonic_placement`] on the ranks of `team`, the parallel work in `pool`;
    /// the iterates (and so the result) do not depend on the split, as the dot products are
    /// exact. Ghost positions are refreshed at the end.
    pub fn harmonic_placement_on<const D: usize, T: Team>(
        &self,
        team: &mut T,
        pool: &ThreadPool,
        problem: &Problem<D>,
        reference: &[Vector<D>],
        positions: &mut [Vector<D>],
    ) -> Result<usize> {
        let iterations = self.place_on(team, Some(pool), problem, reference, positions)?;
        team.refresh(positions.as_flattened_mut(), D)?;
        Ok(iterations)
    }

    fn place_on<const D: usize, T: Team>(
        &self,
        team: &mut T,
        pool: Option<&ThreadPool>,
        problem: &Problem<D>,
        reference: &[Vector<D>],
        positions: &mut [Vector<D>],
    ) -> Result<usize> {
        let n = problem.node_count();
        let global_n = team.count((0..n).filter(|&v| team.owns(v)).count())?;
        let degree: Vec<f64> = (0..n).map(|v| self.of(v).len() as f64).collect();
        let mut iterations = 0;
        for k in 0..D {
            let free: Vec<bool> = (0..n)
                .map(|v| problem.free_mask(v) & (1 << k) != 0 && degree[v] > 0.0)
                .collect();
            // The rows of this rank: the free nodes it owns (its ghosts' rows are elsewhere).
            let row: Vec<bool> = (0..n).map(|v| free[v] && team.owns(v)).collect();
            let displacement: Vec<f64> =
                (0..n).map(|v| positions[v][k] - reference[v][k]).collect();
            // Every vector of the iteration vanishes at the fixed nodes, so the matrix–vector
            // product needs no test on the neighbours.
            let product = |u: &[f64], out: &mut [f64]| {
                out.par_iter_mut().enumerate().for_each(|(v, o)| {
                    *o = if row[v] {
                        degree[v] * u[v] - self.of(v).iter().map(|&w| u[w as usize]).sum::<f64>()
                    } else {
                        0.0
                    };
                });
            };
            let apply = |u: &[f64], out: &mut [f64]| match pool {
                Some(pool) => pool.install(|| product(u, out)),
                None => product(u, out),
            };
            let rhs: Vec<f64> = (0..n)
                .map(|v| match row[v] {
                    true => self
                        .of(v)
                        .iter()
                        .filter(|&&w| !free[w as usize])
                        .map(|&w| displacement[w as usize])
                        .sum(),
                    false => 0.0,
                })
                .collect();
            let mut u: Vec<f64> = (0..n)
                .map(|v| if free[v] { displacement[v] } else { 0.0 })
                .collect();
            let diagonal: Vec<f64> = degree.iter().map(|&d| d.max(1.0)).collect();
            let system = System {
                apply: &apply,
                diagonal: &diagonal,
                rows: &row,
                pool,
            };
            iterations +=
                conjugate_gradients(team, &system, &rhs, &mut u, 1e-10, 4 * global_n + 100)?;
            for v in 0..n {
                if free[v] {
                    positions[v][k] = reference[v][k] + u[v];
                }
            }
        }
        Ok(iterations)
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

/// A symmetric positive semi-definite system over the nodes of a rank: the product (rows of
/// this rank only), the Jacobi preconditioner, and the rows of this rank.
struct System<'a> {
    apply: &'a dyn Fn(&[f64], &mut [f64]),
    diagonal: &'a [f64],
    rows: &'a [bool],
    /// Where the parallel work runs (`None`: the caller's pool).
    pool: Option<&'a ThreadPool>,
}

/// Entries per exact partial sum of [`dot`].
const DOT_CHUNK: usize = 4096;

/// The dot product over the rows of this rank, summed exactly over the team. The chunks' exact
/// sums are added in parallel (on the caller's pool): being exact, the result does not depend on
/// how they are grouped.
fn dot<T: Team>(team: &mut T, system: &System<'_>, a: &[f64], b: &[f64]) -> Result<f64> {
    let sum = || {
        (a.par_chunks(DOT_CHUNK).zip(b.par_chunks(DOT_CHUNK)))
            .zip(system.rows.par_chunks(DOT_CHUNK))
            .map(|((a, b), rows)| {
                let products = (0..a.len()).filter(|&i| rows[i]).map(|i| a[i] * b[i]);
                ExactSum::of(products)
            })
            .reduce(ExactSum::default, |mut total, part| {
                total.merge(&part);
                total
            })
    };
    let sum = match system.pool {
        Some(pool) => pool.install(sum),
        None => sum(),
    };
    team.sum(&sum)
}

/// Solves `A u = b` by conjugate gradients with the Jacobi preconditioner; stops at
/// `‖r‖ ≤ tolerance·max(‖b‖, 1)`. The search direction's ghost values are refreshed before
/// every product. Returns the iterations.
fn conjugate_gradients<T: Team>(
    team: &mut T,
    system: &System<'_>,
    b: &[f64],
    u: &mut [f64],
    tolerance: f64,
    max_iterations: usize,
) -> Result<usize> {
    let n = b.len();
    let mut r = vec![0.0; n];
    team.refresh(u, 1)?;
    (system.apply)(u, &mut r);
    for (ri, bi) in r.iter_mut().zip(b) {
        *ri = bi - *ri;
    }
    let stop = tolerance * dot(team, system, b, b)?.sqrt().max(1.0);
    let precondition =
        |r: &[f64]| -> Vec<f64> { r.iter().zip(system.diagonal).map(|(x, d)| x / d).collect() };
    let mut z = precondition(&r);
    let mut p = z.clone();
    let mut ap = vec![0.0; n];
    let mut rz = dot(team, system, &r, &z)?;
    for it in 0..max_iterations {
        if dot(team, system, &r, &r)?.sqrt() <= stop {
            return Ok(it);
        }
        team.refresh(&mut p, 1)?;
        (system.apply)(&p, &mut ap);
        let pap = dot(team, system, &p, &ap)?;
        if pap <= 0.0 {
            return Ok(it);
        }
        let alpha = rz / pap;
        for i in 0..n {
            u[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
        }
        z = precondition(&r);
        let rz_new = dot(team, system, &r, &z)?;
        let beta = rz_new / rz;
        rz = rz_new;
        for i in 0..n {
            p[i] = z[i] + beta * p[i];
        }
    }
    Ok(max_iterations)
}
