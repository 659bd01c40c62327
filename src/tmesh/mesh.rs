//! The T-mesh of a balanced tree: its vertices (with the hanging ones) and, for every leaf, the
//! lattice points of its quadratic map that are real vertices — the corners, and the hanging
//! vertices at edge midpoints or face centres. The other lattice points are virtual nodes.

use std::collections::HashMap;

use super::tree::{Tree, UNIT};
use crate::error::{Error, Result};
use crate::optimize::{lattice, CellPattern, CellSpec, Problem, TargetKind};

/// A strongly balanced T-mesh of \[0,1\]^d.
#[derive(Clone, Debug)]
pub struct TMesh<const D: usize> {
    tree: Tree<D>,
    leaves: Vec<usize>,
    vertices: Vec<[u32; D]>,
    /// Per leaf: lattice points that are real vertices, and the vertex ids.
    real_lattice: Vec<Vec<usize>>,
    real_vertices: Vec<Vec<u32>>,
}

impl<const D: usize> TMesh<D> {
    /// Builds the T-mesh of a tree, which must be strongly 2:1 balanced.
    pub fn new(tree: Tree<D>) -> Result<Self> {
        if !tree.is_balanced() {
            return Err(Error::invalid(
                "the tree is not 2:1 balanced; call Tree::balance first",
            ));
        }
        let leaves = tree.leaves();
        let mut ids: HashMap<[u32; D], u32> = HashMap::new();
        let mut vertices = Vec::new();
        let corners: Vec<usize> = (0..lattice::count(D))
            .filter(|&l| lattice::coords::<D>(l).iter().all(|&c| c != 1))
            .collect();
        for &c in &leaves {
            for &l in &corners {
                let p = Self::lattice_point(&tree, c, l);
                ids.entry(p).or_insert_with(|| {
                    vertices.push(p);
                    (vertices.len() - 1) as u32
                });
            }
        }
        let mut real_lattice = Vec::with_capacity(leaves.len());
        let mut real_vertices = Vec::with_capacity(leaves.len());
        for &c in &leaves {
            let (mut lat, mut ver) = (Vec::new(), Vec::new());
            for l in 0..lattice::count(D) {
                if let Some(&v) = ids.get(&Self::lattice_point(&tree, c, l)) {
                    lat.push(l);
                    ver.push(v);
                }
            }
            real_lattice.push(lat);
            real_vertices.push(ver);
        }
        Ok(TMesh {
            tree,
            leaves,
            vertices,
            real_lattice,
            real_vertices,
        })
    }

    fn lattice_point(tree: &Tree<D>, c: usize, l: usize) -> [u32; D] {
        let cell = tree.cells()[c];
        let half = cell.side() / 2;
        let lc = lattice::coords::<D>(l);
        std::array::from_fn(|k| cell.lower[k] + lc[k] as u32 * half)
    }

    /// The tree.
    pub fn tree(&self) -> &Tree<D> {
        &self.tree
    }

    /// Tree-cell index of each T-mesh cell (the tree's leaves in depth-first order).
    pub fn leaves(&self) -> &[usize] {
        &self.leaves
    }

    /// Number of cells (leaves).
    pub fn cell_count(&self) -> usize {
        self.leaves.len()
    }

    /// Number of vertices, hanging ones included.
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// Level of cell `i`.
    pub fn cell_level(&self, i: usize) -> u8 {
        self.tree.cells()[self.leaves[i]].level
    }

    /// Parametric bounds `(lower, upper)` of cell `i`.
    pub fn cell_bounds(&self, i: usize) -> ([f64; D], [f64; D]) {
        let cell = self.tree.cells()[self.leaves[i]];
        let lo = cell.lower.map(|v| v as f64 / UNIT as f64);
        let hi = std::array::from_fn(|k| (cell.lower[k] + cell.side()) as f64 / UNIT as f64);
        (lo, hi)
    }

    /// Parametric coordinates of every vertex.
    pub fn parametric(&self) -> Vec<[f64; D]> {
        self.vertices
            .iter()
            .map(|p| p.map(|v| v as f64 / UNIT as f64))
            .collect()
    }

    /// Whether vertex `v` lies on the boundary of \[0,1\]^d.
    pub fn on_boundary(&self, v: usize) -> bool {
        self.vertices[v].iter().any(|&c| c == 0 || c == UNIT)
    }

    /// Whether vertex `v` is hanging: the midpoint of an edge or the centre of a face of some cell.
    pub fn is_hanging(&self, v: usize) -> bool {
        self.real_lattice
            .iter()
            .zip(&self.real_vertices)
            .any(|(lat, ver)| {
                lat.iter()
                    .zip(ver)
                    .any(|(&l, &id)| id as usize == v && lattice::coords::<D>(l).contains(&1))
            })
    }

    /// Real vertices of cell `i` with their lattice points (`i + 3j (+ 9k)`).
    pub fn cell_vertices(&self, i: usize) -> (&[usize], &[u32]) {
        (&self.real_lattice[i], &self.real_vertices[i])
    }

    /// The optimizer's view of the T-mesh: each cell a quadratic map over its real vertices
    /// (virtual nodes elsewhere), targets the parametric cells, boundary vertices fixed, and in
    /// each vertex's objective the cells one level coarser weighted 2.
    pub fn problem(&self) -> Result<Problem<D>> {
        let mut pattern_ids: HashMap<&[usize], usize> = HashMap::new();
        let mut patterns = Vec::new();
        let mut specs = Vec::with_capacity(self.leaves.len());
        for (lat, ver) in self.real_lattice.iter().zip(&self.real_vertices) {
            let pattern = match pattern_ids.get(lat.as_slice()) {
                Some(&p) => p,
                None => {
                    let p = CellPattern::<D>::new(lat)
                        .ok_or_else(|| Error::mesh("a T-mesh cell misses a corner"))?;
                    patterns.push(p);
                    pattern_ids.insert(lat, patterns.len() - 1);
                    patterns.len() - 1
                }
            };
            specs.push(CellSpec {
                pattern,
                nodes: ver,
            });
        }
        let all = (1u8 << D) - 1;
        let free = (0..self.vertex_count())
            .map(|v| if self.on_boundary(v) { 0 } else { all })
            .collect();
        let reference = self.parametric();
        let mut problem = Problem::new(patterns, &specs, &reference, TargetKind::Reference, free)?;
        let levels: Vec<u8> = (0..self.cell_count()).map(|c| self.cell_level(c)).collect();
        problem.weight_coarser_cells(&levels)?;
        Ok(problem)
    }
}
