//! The one global objective of a mesh, `F(x) = Σ_c w_c · (1/3^d) Σ_q η*(S_cq(x))`, with its
//! gradient and its sparse Hessian over all node coordinates.
//!
//! The per-node sweeps minimise each node's share of `F` with a δ of its own; `F` with one fixed
//! δ (0 on a valid mesh, where `η* = ‖S‖²/(d σ^{2/d})` is smooth and infinite at folds) is the
//! function whose stationary point the Newton stage (`stationary.rs`) reaches and whose Hessian
//! gives the sensitivities of the optimum.
//!
//! The Hessian is stored by node blocks (d×d), full (both triangles), over the pairs of nodes whose
//! positions enter one Jacobian: two real nodes of a cell couple when some Gauss–Lobatto point
//! depends on both.

use rayon::prelude::*;
use rayon::ThreadPool;

use super::blocks::{BlockLayout, BlockMatrix, Touch, NONE};
use super::distortion::{derivatives, value as distortion};
use super::problem::Problem;
use super::small_matrix::{Matrix, Vector};
use crate::error::Result;
use crate::threads;

/// The objective's value, gradient (per node) and, if asked, Hessian at one state.
#[derive(Clone, Debug)]
pub struct Evaluation<const D: usize> {
    /// `F(x)`; `+∞` where a Jacobian folds (δ = 0).
    pub value: f64,
    /// `∂F/∂x_v` for every node (fixed components included).
    pub gradient: Vec<Vector<D>>,
    /// `∂²F/∂x²`, when asked for.
    pub hessian: Option<BlockMatrix<D>>,
}

/// The global objective of a [`Problem`] over a [`BlockLayout`] of its Hessian.
pub struct GlobalObjective<'p, const D: usize> {
    problem: &'p Problem<D>,
    layout: &'p BlockLayout,
    cell_weight: Vec<f64>,
    /// Regularisation of `η*`: 0 for a valid mesh.
    delta: f64,
}

/// One cell's share: value, gradient per real node, Hessian blocks per pair of real nodes.
struct Local<const D: usize> {
    value: f64,
    gradient: Vec<Vector<D>>,
    hessian: Vec<Matrix<D>>,
}

impl<'p, const D: usize> GlobalObjective<'p, D> {
    /// The objective of `problem` (its Hessian laid out by `layout`) with weight
    /// `cell_weight[c]` per cell (all 1 when `None`) and regularisation `delta`.
    pub fn new(
        problem: &'p Problem<D>,
        layout: &'p BlockLayout,
        cell_weight: Option<Vec<f64>>,
        delta: f64,
    ) -> Self {
        let cell_weight = cell_weight.unwrap_or_else(|| vec![1.0; problem.cell_count()]);
        GlobalObjective {
            problem,
            layout,
            cell_weight,
            delta,
        }
    }

    /// The problem.
    pub fn problem(&self) -> &Problem<D> {
        self.problem
    }

    /// The Hessian's layout.
    pub fn layout(&self) -> &BlockLayout {
        self.layout
    }

    /// Sum of the weights of the cells around `node`: `∂F/∂x_v` divided by it is the gradient of
    /// the node's own objective, the one the sweeps minimise.
    pub fn node_weight(&self, node: usize) -> f64 {
        self.problem
            .incident_cells(node)
            .iter()
            .map(|&(c, _)| self.cell_weight[c as usize])
            .sum()
    }

    /// Value, gradient and (if `hessian`) Hessian at `x`. The result does not depend on the
    /// thread count: cells are evaluated in parallel and added in cell order.
    /// Refused where a Hessian's storage cannot be allocated ([`BlockMatrix::zero`]).
    pub fn evaluate(
        &self,
        pool: &ThreadPool,
        x: &[Vector<D>],
        hessian: bool,
    ) -> Result<Evaluation<D>> {
        self.evaluate_into(pool, x, hessian, &mut None)
    }

    /// [`GlobalObjective::evaluate`], the Hessian (where one is evaluated) written into the
    /// storage taken from `spare` (a Hessian of the same layout that is no longer needed) when
    /// there is one: a solid mesh's Hessian is hundreds of megabytes, and fresh storage is
    /// faulted in page by page (on the wing, 0.27 GB: most of the page faults of a relocation
    /// were the first writes of new Hessians). Without a Hessian, `spare` is left as it is.
    pub fn evaluate_into(
        &self,
        pool: &ThreadPool,
        x: &[Vector<D>],
        hessian: bool,
        spare: &mut Option<BlockMatrix<D>>,
    ) -> Result<Evaluation<D>> {
        let n = self.problem.node_count();
        let storage = || -> Result<BlockMatrix<D>> {
            let reused = spare
                .take()
                .filter(|m| m.blocks.len() == self.layout.block_count());
            let mut m = match reused {
                Some(m) => m,
                None => BlockMatrix::zero(self.layout)?,
            };
            // Zeroed by plain stores, in order and in parallel: a reused Hessian's values, a
            // fresh one's pages (the assembly's first accesses, scattered and read before
            // written, faulted each page in twice, through the zero page and a flush of every
            // thread's TLB: the wing's Hessian took 0.95 s to evaluate into, 0.27 s so).
            let work = m.blocks.len() * D * D;
            threads::for_each_mut(pool, work, &mut m.blocks, |_, b| *b = [[0.0; D]; D]);
            Ok(m)
        };
        let mut out = Evaluation {
            value: 0.0,
            gradient: vec![[0.0; D]; n],
            hessian: hessian.then(storage).transpose()?,
        };
        let cells: Vec<usize> = (0..self.problem.cell_count()).collect();
        for (k, chunk) in cells.chunks(self.layout.chunk()).enumerate() {
            let locals: Vec<Local<D>> = pool.install(|| {
                chunk
                    .par_iter()
                    .map(|&c| self.cell(c, x, hessian))
                    .collect()
            });
            for (&c, local) in chunk.iter().zip(&locals) {
                out.value += local.value;
                let nodes = self.problem.cell_nodes(c);
                for (&v, g) in nodes.iter().zip(&local.gradient) {
                    for (o, gk) in out.gradient[v as usize].iter_mut().zip(g) {
                        *o += gk;
                    }
                }
            }
            if let Some(h) = out.hessian.as_mut() {
                self.assemble(pool, (chunk, self.layout.chunk_touches(k)), &locals, h);
            }
        }
        Ok(out)
    }

    /// Adds the Hessian blocks of the `chunk`'s cells (`locals`, in the chunk's order; `touches`,
    /// the chunk's rows by node then cell) to `h`, rows in parallel. Each block receives the
    /// cells' contributions in cell order, as one pass over the cells would add them: the sums
    /// are the same to the last bit, for any thread count. (Adding them in one pass took more
    /// time than computing them on the wing: 0.28 s against 0.19 s per evaluation.)
    fn assemble(
        &self,
        pool: &ThreadPool,
        (chunk, touches): (&[usize], &[Touch]),
        locals: &[Local<D>],
        h: &mut BlockMatrix<D>,
    ) {
        // The rows touched, each with its slice of the blocks (rows are contiguous, ascending).
        let mut rows = Vec::new();
        let (mut rest, mut offset) = (&mut h.blocks[..], 0usize);
        for group in touches.chunk_by(|a, b| a.0 == b.0) {
            let range = self.layout.row(group[0].0 as usize).0;
            let tail = std::mem::take(&mut rest)
                .split_at_mut(range.start - offset)
                .1;
            let (row, tail) = tail.split_at_mut(range.len());
            (rest, offset) = (tail, range.end);
            rows.push((group, range.start, row));
        }
        pool.install(|| {
            rows.into_par_iter().for_each(|(group, first, row)| {
                for &(_, i, r) in group {
                    let (c, local) = (chunk[i as usize], &locals[i as usize]);
                    let count = self.problem.cell_nodes(c).len();
                    let at = r as usize * count..(r as usize + 1) * count;
                    let map = &self.layout.cell_blocks(c)[at.clone()];
                    for (&b, block) in map.iter().zip(&local.hessian[at]) {
                        if b != NONE {
                            add_to(&mut row[b as usize - first], block);
                        }
                    }
                }
            })
        });
    }

    /// Value of `F` at `x` only (`+∞` when some Jacobian folds at δ = 0).
    pub fn value(&self, pool: &ThreadPool, x: &[Vector<D>]) -> f64 {
        let values: Vec<f64> = pool.install(|| {
            (0..self.problem.cell_count())
                .into_par_iter()
                .map(|c| self.cell_value(c, x))
                .collect()
        });
        values.iter().sum()
    }

    fn cell_value(&self, c: usize, x: &[Vector<D>]) -> f64 {
        let p = self.problem;
        let w = self.cell_weight[c] / Problem::<D>::POINTS as f64;
        let mut value = 0.0;
        for q in 0..Problem::<D>::POINTS {
            value += w * distortion(&p.normalized_jacobian(c, q, x), self.delta);
        }
        value
    }

    /// The share of cell `c`.
    fn cell(&self, c: usize, x: &[Vector<D>], hessian: bool) -> Local<D> {
        let p = self.problem;
        let nodes = p.cell_nodes(c);
        let count = nodes.len();
        let mut local = Local {
            value: 0.0,
            gradient: vec![[0.0; D]; count],
            hessian: if hessian {
                vec![[[0.0; D]; D]; count * count]
            } else {
                Vec::new()
            },
        };
        let w = self.cell_weight[c] / Problem::<D>::POINTS as f64;
        let mut stencil: Vec<(usize, Vector<D>)> = Vec::new();
        for q in 0..Problem::<D>::POINTS {
            stencil.clear();
            stencil.extend(p.normalized_stencil(c, q));
            let s = p.normalized_jacobian(c, q, x);
            let d = derivatives(&s, self.delta);
            local.value += w * d.value;
            for &(r, g) in &stencil {
                for a in 0..D {
                    let dot: f64 = (0..D).map(|i| d.gradient[a][i] * g[i]).sum();
                    local.gradient[r][a] += w * dot;
                }
            }
            if !hessian {
                continue;
            }
            for (k, &(r, gr)) in stencil.iter().enumerate() {
                // t[a][b][j] = Σ_i ∂²η/∂S_ai∂S_bj g_r[i]
                let mut t = [[[0.0; D]; D]; D];
                for (a, ta) in t.iter_mut().enumerate() {
                    for (b, tab) in ta.iter_mut().enumerate() {
                        for (j, v) in tab.iter_mut().enumerate() {
                            *v = (0..D).map(|i| d.hessian[a][i][b][j] * gr[i]).sum();
                        }
                    }
                }
                // Block (s, r) is the transpose of block (r, s): each pair once.
                for &(s_node, gs) in &stencil[k..] {
                    let v: Matrix<D> = std::array::from_fn(|a| {
                        std::array::from_fn(|b| w * (0..D).map(|j| t[a][b][j] * gs[j]).sum::<f64>())
                    });
                    add_to(&mut local.hessian[r * count + s_node], &v);
                    if s_node != r {
                        let transposed = std::array::from_fn(|b| std::array::from_fn(|a| v[a][b]));
                        add_to(&mut local.hessian[s_node * count + r], &transposed);
                    }
                }
            }
        }
        local
    }
}

fn add_to<const D: usize>(target: &mut Matrix<D>, block: &Matrix<D>) {
    for (row, add) in target.iter_mut().zip(block) {
        for (v, a) in row.iter_mut().zip(add) {
            *v += a;
        }
    }
}
