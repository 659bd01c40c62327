//! The hierarchical quadtree (d = 2) / octree (d = 3) over \[0,1\]^d: cells, refinement, point
//! location and the strong 2:1 balance.
//!
//! Coordinates are integers on the finest half-grid: a cell of level `l` has side
//! `2^(MAX_LEVEL + 1 − l)` units, so every lattice point of every cell (its corners, edge
//! midpoints, face centres, centre) has integer coordinates, and `2^(MAX_LEVEL + 1)` is 1.

use crate::error::{Error, Result};

/// Deepest level a cell may have.
pub const MAX_LEVEL: u8 = 20;

/// Integer length of the unit interval.
pub const UNIT: u32 = 1 << (MAX_LEVEL as u32 + 1);

/// One cell of the tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cell<const D: usize> {
    /// Refinement level (0 = the whole domain).
    pub level: u8,
    /// Integer coordinates of the lower corner.
    pub lower: [u32; D],
    /// Index of the first of the `2^d` children, if refined.
    pub first_child: Option<u32>,
}

impl<const D: usize> Cell<D> {
    /// Integer side length.
    pub fn side(&self) -> u32 {
        UNIT >> self.level
    }

    /// Whether the cell contains the integer point (closed box).
    pub fn contains(&self, p: &[i64; D]) -> bool {
        (0..D).all(|k| {
            let lo = self.lower[k] as i64;
            p[k] >= lo && p[k] <= lo + self.side() as i64
        })
    }
}

/// A quadtree/octree over \[0,1\]^d.
#[derive(Clone, Debug)]
pub struct Tree<const D: usize> {
    cells: Vec<Cell<D>>,
}

impl<const D: usize> Default for Tree<D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const D: usize> Tree<D> {
    /// The tree with one cell, the whole domain.
    pub fn new() -> Self {
        Tree {
            cells: vec![Cell {
                level: 0,
                lower: [0; D],
                first_child: None,
            }],
        }
    }

    /// All cells, refined ones included; index 0 is the root.
    pub fn cells(&self) -> &[Cell<D>] {
        &self.cells
    }

    /// Indices of the leaves (the active cells), in depth-first order.
    pub fn leaves(&self) -> Vec<usize> {
        let mut out = Vec::new();
        let mut stack = vec![0usize];
        while let Some(c) = stack.pop() {
            match self.cells[c].first_child {
                None => out.push(c),
                Some(first) => stack.extend((0..1usize << D).rev().map(|k| first as usize + k)),
            }
        }
        out
    }

    /// Splits leaf `c` into `2^d` children. Fails for a refined cell or one at [`MAX_LEVEL`].
    pub fn refine(&mut self, c: usize) -> Result<()> {
        let cell = *self
            .cells
            .get(c)
            .ok_or_else(|| Error::invalid(format!("cell {c} does not exist")))?;
        if cell.first_child.is_some() {
            return Err(Error::invalid(format!("cell {c} is already refined")));
        }
        if cell.level >= MAX_LEVEL {
            return Err(Error::invalid(format!(
                "cell {c} is at the deepest level {MAX_LEVEL}"
            )));
        }
        let half = cell.side() / 2;
        let first = self.cells.len() as u32;
        for k in 0..1usize << D {
            let lower =
                std::array::from_fn(|d| cell.lower[d] + if k >> d & 1 == 1 { half } else { 0 });
            self.cells.push(Cell {
                level: cell.level + 1,
                lower,
                first_child: None,
            });
        }
        self.cells[c].first_child = Some(first);
        Ok(())
    }

    /// Refines every leaf `levels` times.
    pub fn refine_uniformly(&mut self, levels: u8) -> Result<()> {
        for _ in 0..levels {
            for c in self.leaves() {
                self.refine(c)?;
            }
        }
        Ok(())
    }

    /// Refines, round after round, every leaf for which `marked(tree, leaf)` holds, until no leaf
    /// is marked; with `balance`, the tree is 2:1 balanced after every round. `marked` must stop
    /// holding (e.g. at a level limit) for the loop to end.
    pub fn refine_while(
        &mut self,
        balance: bool,
        marked: impl FnMut(&Tree<D>, usize) -> bool,
    ) -> Result<()> {
        self.refine_while_bounded(balance, marked, &mut |_| Ok(()))
    }

    /// [`Tree::refine_while`], calling `before_round(leaves)` before every round with the number
    /// of leaves the round would make: an error it returns (a cell budget exceeded, a
    /// cancellation) stops the refinement before that round and is returned.
    pub fn refine_while_bounded(
        &mut self,
        balance: bool,
        mut marked: impl FnMut(&Tree<D>, usize) -> bool,
        before_round: &mut dyn FnMut(usize) -> Result<()>,
    ) -> Result<()> {
        loop {
            let round: Vec<usize> = self
                .leaves()
                .into_iter()
                .filter(|&c| marked(self, c))
                .collect();
            if round.is_empty() {
                return Ok(());
            }
            // Every refined cell holds 2^d children: the others are the leaves.
            let leaves = self.cells.len() - ((self.cells.len() - 1) >> D);
            before_round(leaves + round.len() * ((1 << D) - 1))?;
            self.cells
                .try_reserve(round.len() << D)
                .map_err(|e| Error::invalid(format!("cannot refine the tree: {e}")))?;
            for c in round {
                self.refine(c)?;
            }
            if balance {
                self.balance()?;
            }
        }
    }

    /// The leaf containing the integer point `p`, or `None` outside the domain. On shared
    /// boundaries the cell on the upper side is chosen.
    pub fn leaf_at(&self, p: &[i64; D]) -> Option<usize> {
        if !self.cells[0].contains(p) {
            return None;
        }
        let mut c = 0usize;
        while let Some(first) = self.cells[c].first_child {
            let cell = self.cells[c];
            let half = (cell.side() / 2) as i64;
            let k = (0..D)
                .filter(|&d| p[d] >= cell.lower[d] as i64 + half)
                .fold(0, |acc, d| acc | 1 << d);
            c = first as usize + k;
        }
        Some(c)
    }

    /// The leaf containing the parametric point `x ∈ \[0,1\]^d`, or `None` outside (or not finite).
    /// On shared boundaries the cell on the upper side is chosen.
    pub fn leaf_at_point(&self, x: &[f64; D]) -> Option<usize> {
        if x.iter().any(|v| !v.is_finite() || *v < 0.0 || *v > 1.0) {
            return None;
        }
        let p: [i64; D] = std::array::from_fn(|k| (x[k] * UNIT as f64).floor() as i64);
        self.leaf_at(&p)
    }

    /// Refines leaves until every two leaves that touch (across a face, an edge or a corner)
    /// differ by at most one level (strong 2:1 balance). Returns the number of refinements.
    pub fn balance(&mut self) -> Result<usize> {
        let mut refinements = 0;
        let mut queue: Vec<usize> = self.leaves();
        while let Some(c) = queue.pop() {
            let cell = self.cells[c];
            if cell.first_child.is_some() {
                continue;
            }
            let coarse = self.too_coarse_neighbours(c);
            if coarse.is_empty() {
                continue;
            }
            for n in coarse {
                self.refine(n)?;
                refinements += 1;
                let first = self.cells[n].first_child.unwrap_or_default() as usize;
                queue.extend(first..first + (1 << D));
            }
            // The new children may still be too coarse for this cell: look again.
            queue.push(c);
        }
        Ok(refinements)
    }

    /// The leaves touching leaf `c` that are more than one level coarser.
    pub fn too_coarse_neighbours(&self, c: usize) -> Vec<usize> {
        let cell = self.cells[c];
        let side = cell.side() as i64;
        let mut out = Vec::new();
        for dir in 0..3usize.pow(D as u32) {
            let offset: [i64; D] =
                std::array::from_fn(|k| (dir / 3usize.pow(k as u32) % 3) as i64 - 1);
            if offset.iter().all(|&o| o == 0) {
                continue;
            }
            // A point just outside the cell, beyond the middle of the face, edge or corner.
            let probe: [i64; D] = std::array::from_fn(|k| {
                let centre = cell.lower[k] as i64 + side / 2;
                centre + offset[k] * (side / 2 + 1)
            });
            if let Some(n) = self.leaf_at(&probe) {
                if self.cells[n].level + 1 < cell.level && !out.contains(&n) {
                    out.push(n);
                }
            }
        }
        out
    }

    /// Whether the leaves are strongly 2:1 balanced.
    pub fn is_balanced(&self) -> bool {
        self.leaves()
            .into_iter()
            .all(|c| self.too_coarse_neighbours(c).is_empty())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_refinement_counts_leaves() {
        let mut t = Tree::<3>::new();
        t.refine_uniformly(2).unwrap();
        assert_eq!(t.leaves().len(), 64);
        assert!(t.is_balanced());
    }

    #[test]
    fn refining_next_to_the_centre_is_balanced_by_refining_the_neighbours() {
        // Cells shrinking towards the centre from one quadrant end up next to the other
        // quadrants' level-1 cells.
        let mut t = Tree::<2>::new();
        let near_centre = (UNIT / 2 - 1) as i64;
        for _ in 0..5 {
            let leaf = t.leaf_at(&[near_centre, near_centre]).unwrap();
            t.refine(leaf).unwrap();
        }
        assert!(!t.is_balanced());
        assert!(t.balance().unwrap() > 0);
        assert!(t.is_balanced());
    }
}
