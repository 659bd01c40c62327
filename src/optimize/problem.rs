//! The optimizer's view of a mesh: cells as quadratic maps over shared patterns, targets, the
//! free components of each node, and the node-to-cell incidence.

use super::lattice;
use super::metric::{mean_ratio, Term};
use super::pattern::CellPattern;
use super::small_matrix::{det, inverse, mul, mul_transpose_vec, scaled_identity, Matrix, Vector};
use crate::error::{Error, Result};

/// One cell: its pattern and where its real node ids start in [`Problem`]'s node list.
#[derive(Clone, Copy, Debug)]
struct CellRef {
    pattern: u32,
    first: usize,
}

/// The ideal shape a cell is measured against.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TargetKind {
    /// The cell's own shape in the reference positions (keeps size grading and anisotropy).
    Reference,
    /// The master square/cube, scaled to the reference cell's size.
    Master,
}

/// A set of cells to optimize; positions live outside so they can be swapped cheaply.
#[derive(Clone, Debug)]
pub struct Problem<const D: usize> {
    patterns: Vec<CellPattern<D>>,
    cells: Vec<CellRef>,
    cell_nodes: Vec<u32>,
    /// `W⁻¹` per cell and lattice point (`cell·3^d + q`).
    target_inverse: Vec<Matrix<D>>,
    /// Per cell: its target size, `|det W|^{1/d}` at the first point.
    target_length: Vec<f64>,
    /// Per node: bit `k` set when component `k` may move.
    free: Vec<u8>,
    incidence_start: Vec<usize>,
    incidence: Vec<(u32, u8)>,
    /// Weight of each incidence (cell in a node's objective), parallel to `incidence`.
    incidence_weight: Vec<f64>,
}

/// A cell as given to [`Problem::new`]: pattern index and real node ids.
pub struct CellSpec<'a> {
    /// Index into the pattern list.
    pub pattern: usize,
    /// Global ids of the real nodes, in the pattern's real-node order.
    pub nodes: &'a [u32],
}

impl<const D: usize> Problem<D> {
    /// Number of Gauss–Lobatto points per cell.
    pub const POINTS: usize = lattice::count(D);

    /// Builds a problem; targets are computed from `reference` (node positions) by `target`.
    /// `free[n]` has bit `k` set when component `k` of node `n` may move.
    pub fn new(
        patterns: Vec<CellPattern<D>>,
        cells: &[CellSpec<'_>],
        reference: &[Vector<D>],
        target: TargetKind,
        free: Vec<u8>,
    ) -> Result<Self> {
        let node_count = reference.len();
        if free.len() != node_count {
            return Err(Error::invalid("one free-component mask per node is needed"));
        }
        let mut cell_refs = Vec::with_capacity(cells.len());
        let mut cell_nodes = Vec::new();
        for (c, spec) in cells.iter().enumerate() {
            let pattern = patterns
                .get(spec.pattern)
                .ok_or_else(|| Error::mesh(format!("cell {c} refers to a missing pattern")))?;
            if spec.nodes.len() != pattern.real_count {
                return Err(Error::mesh(format!(
                    "cell {c} has the wrong number of nodes"
                )));
            }
            for (i, &n) in spec.nodes.iter().enumerate() {
                if n as usize >= node_count {
                    return Err(Error::mesh(format!(
                        "cell {c} refers to node {n}, but there are {node_count} nodes"
                    )));
                }
                if spec.nodes[..i].contains(&n) {
                    return Err(Error::mesh(format!("cell {c} uses node {n} twice")));
                }
            }
            cell_refs.push(CellRef {
                pattern: spec.pattern as u32,
                first: cell_nodes.len(),
            });
            cell_nodes.extend_from_slice(spec.nodes);
        }
        let mut counts = vec![0usize; node_count + 1];
        for &n in &cell_nodes {
            counts[n as usize + 1] += 1;
        }
        for i in 0..node_count {
            counts[i + 1] += counts[i];
        }
        let mut fill = counts.clone();
        let mut incidence = vec![(0u32, 0u8); cell_nodes.len()];
        for (c, cell) in cell_refs.iter().enumerate() {
            let count = patterns[cell.pattern as usize].real_count;
            for (r, &n) in cell_nodes[cell.first..cell.first + count]
                .iter()
                .enumerate()
            {
                incidence[fill[n as usize]] = (c as u32, r as u8);
                fill[n as usize] += 1;
            }
        }
        let mut problem = Problem {
            patterns,
            cells: cell_refs,
            cell_nodes,
            target_inverse: Vec::new(),
            target_length: Vec::new(),
            free,
            incidence_weight: vec![1.0; incidence.len()],
            incidence_start: counts,
            incidence,
        };
        problem.target_inverse = (0..problem.cells.len())
            .flat_map(|c| problem.cell_targets(c, reference, target))
            .collect();
        problem.target_length = problem
            .target_inverse
            .chunks(Self::POINTS)
            .map(|w| det(&w[0]).abs().powf(-1.0 / D as f64))
            .collect();
        Ok(problem)
    }

    /// `W⁻¹` at every point of cell `c` for the given target kind. A reference cell that is
    /// itself inverted somewhere falls back to the scaled master cell.
    fn cell_targets(&self, c: usize, reference: &[Vector<D>], kind: TargetKind) -> Vec<Matrix<D>> {
        let jac: Vec<Matrix<D>> = (0..Self::POINTS)
            .map(|q| self.jacobian(c, q, reference))
            .collect();
        let dets: Vec<f64> = jac.iter().map(det).collect();
        if kind == TargetKind::Reference && dets.iter().all(|&d| d > 0.0) {
            if let Some(inv) = jac.iter().map(inverse).collect::<Option<Vec<_>>>() {
                return inv;
            }
        }
        let mean = dets.iter().map(|d| d.abs()).sum::<f64>() / dets.len() as f64;
        let size = if mean > 0.0 && mean.is_finite() {
            mean.powf(1.0 / D as f64)
        } else {
            1.0
        };
        vec![scaled_identity::<D>(1.0 / size); Self::POINTS]
    }

    /// Weights the cells of a hierarchical mesh as the method does: in the objective of a node,
    /// a cell one level coarser than the finest cell around the node counts twice.
    pub fn weight_coarser_cells(&mut self, cell_levels: &[u8]) -> Result<()> {
        if cell_levels.len() != self.cells.len() {
            return Err(Error::invalid("one level per cell is needed"));
        }
        for node in 0..self.node_count() {
            let range = self.incidence_start[node]..self.incidence_start[node + 1];
            let finest = self.incidence[range.clone()]
                .iter()
                .map(|&(c, _)| cell_levels[c as usize])
                .max()
                .unwrap_or(0);
            for i in range {
                let level = cell_levels[self.incidence[i].0 as usize];
                self.incidence_weight[i] = if level < finest { 2.0 } else { 1.0 };
            }
        }
        Ok(())
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.free.len()
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.cells.len()
    }

    /// Bit mask of the components of `node` that may move.
    pub fn free_mask(&self, node: usize) -> u8 {
        self.free[node]
    }

    /// Real node ids of cell `c`.
    pub fn cell_nodes(&self, c: usize) -> &[u32] {
        let cell = self.cells[c];
        let count = self.patterns[cell.pattern as usize].real_count;
        &self.cell_nodes[cell.first..cell.first + count]
    }

    /// The cells around `node`, each with the node's local index in it.
    pub fn incident_cells(&self, node: usize) -> &[(u32, u8)] {
        &self.incidence[self.incidence_start[node]..self.incidence_start[node + 1]]
    }

    /// Pattern of cell `c`.
    pub fn pattern(&self, c: usize) -> &CellPattern<D> {
        &self.patterns[self.cells[c].pattern as usize]
    }

    /// Jacobian `∂x/∂ξ` of cell `c` at point `q`.
    pub fn jacobian(&self, c: usize, q: usize, positions: &[Vector<D>]) -> Matrix<D> {
        let nodes = self.cell_nodes(c);
        self.pattern(c)
            .jacobian_at(q, |r| positions[nodes[r] as usize])
    }

    /// Jacobian of cell `c` at `q` composed with the inverse of its target: `S = J W⁻¹`.
    pub fn normalized_jacobian(&self, c: usize, q: usize, positions: &[Vector<D>]) -> Matrix<D> {
        mul(
            &self.jacobian(c, q, positions),
            &self.target_inverse[c * Self::POINTS + q],
        )
    }

    /// The normalised Jacobian stencil of cell `c` at point `q`: for each real node `r` whose
    /// position enters, `g` with `S = J W⁻¹ = Σ_r x_r gᵀ`.
    pub fn normalized_stencil(
        &self,
        c: usize,
        q: usize,
    ) -> impl Iterator<Item = (usize, Vector<D>)> + '_ {
        let w_inv = &self.target_inverse[c * Self::POINTS + q];
        self.pattern(c).jacobian[q]
            .iter()
            .map(move |&(r, g)| (r as usize, mul_transpose_vec(w_inv, &g)))
    }

    /// Whether `det J > 0` at every Gauss–Lobatto point of cell `c`.
    pub fn cell_is_valid(&self, c: usize, positions: &[Vector<D>]) -> bool {
        (0..Self::POINTS).all(|q| det(&self.jacobian(c, q, positions)) > 0.0)
    }

    /// Whether cell `c` is folded (`det J ≤ 0`) at a Gauss–Lobatto point whose Jacobian depends
    /// on fixed nodes only (every node of its stencil has no free component): no placement of
    /// the free nodes makes that cell valid.
    pub fn has_fixed_fold(&self, c: usize, positions: &[Vector<D>]) -> bool {
        let nodes = self.cell_nodes(c);
        let pattern = self.pattern(c);
        (0..Self::POINTS).any(|q| {
            pattern.jacobian[q]
                .iter()
                .all(|&(r, _)| self.free[nodes[r as usize] as usize] == 0)
                && det(&self.jacobian(c, q, positions)) <= 0.0
        })
    }

    /// Quality of cell `c`: the inverse of its mean distortion over the Gauss–Lobatto points
    /// (1 = the target shape up to rotation and scale; 0 = inverted somewhere).
    pub fn cell_quality(&self, c: usize, positions: &[Vector<D>]) -> f64 {
        let mut eta = 0.0;
        for q in 0..Self::POINTS {
            let m = mean_ratio(&self.normalized_jacobian(c, q, positions));
            if m <= 0.0 {
                return 0.0;
            }
            eta += 1.0 / m;
        }
        Self::POINTS as f64 / eta
    }

    /// Local length of `node`: the mean target size of its cells (0 for a node in no cell).
    pub fn node_length(&self, node: usize) -> f64 {
        let incident = self.incident_cells(node);
        if incident.is_empty() {
            return 0.0;
        }
        let sum: f64 = incident
            .iter()
            .map(|&(c, _)| self.target_length[c as usize])
            .sum();
        sum / incident.len() as f64
    }

    /// The objective terms of `node` (all other nodes fixed at `positions`), the sum of its
    /// cell weights, and a local length (mean target size of the incident cells).
    pub fn node_terms(
        &self,
        node: usize,
        positions: &[Vector<D>],
        terms: &mut Vec<Term<D>>,
    ) -> (f64, f64) {
        terms.clear();
        let mut weight_sum = 0.0;
        let range = self.incidence_start[node]..self.incidence_start[node + 1];
        let incident = &self.incidence[range.clone()];
        for (&(c, r), &weight) in incident.iter().zip(&self.incidence_weight[range]) {
            let c = c as usize;
            let cell = self.cells[c];
            let pattern = &self.patterns[cell.pattern as usize];
            let nodes = self.cell_nodes(c);
            weight_sum += weight;
            let w = weight / Self::POINTS as f64;
            for &(q, g) in &pattern.influence[r as usize] {
                let q = q as usize;
                let mut j_other = [[0.0; D]; D];
                for &(r2, g2) in &pattern.jacobian[q] {
                    if r2 == r {
                        continue;
                    }
                    let x = positions[nodes[r2 as usize] as usize];
                    for a in 0..D {
                        for b in 0..D {
                            j_other[a][b] += x[a] * g2[b];
                        }
                    }
                }
                let w_inv = &self.target_inverse[c * Self::POINTS + q];
                terms.push(Term {
                    a: mul(&j_other, w_inv),
                    g: mul_transpose_vec(w_inv, &g),
                    w,
                });
            }
        }
        (weight_sum, self.node_length(node))
    }
}
