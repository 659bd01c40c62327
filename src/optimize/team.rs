//! The ranks a relocation runs on together. A mesh in one process is a team of one
//! ([`Alone`]); a mesh partitioned over MPI ranks is a team whose nodes are each updated by
//! their owner, whose ghost copies are refreshed from the owners, and whose sums and extrema
//! are taken over all ranks (see `crate::partition`).
//!
//! Every result of a team is the same on all its ranks and does not depend on how the mesh is
//! split: sums are exact ([`ExactSum`]), the colouring is the serial greedy one in node order.

use super::colour::colour_nodes;
use super::exact::ExactSum;
use super::problem::Problem;
use crate::error::Result;

/// The ranks a relocation runs on; all calls are collective (every rank makes them in the same
/// order).
pub trait Team {
    /// Whether local node `v` is updated here (its owner's copy).
    fn owns(&self, v: usize) -> bool;
    /// Whether cell `c` is counted here in sums over cells (each cell on exactly one rank).
    fn counts(&self, c: usize) -> bool;
    /// Copies `width` values per node from each node's owner to its ghost copies.
    fn refresh(&mut self, values: &mut [f64], width: usize) -> Result<()>;
    /// The largest `x` over all ranks.
    fn max(&mut self, x: f64) -> Result<f64>;
    /// The smallest `x` over all ranks.
    fn min(&mut self, x: f64) -> Result<f64>;
    /// The exact sum over all ranks, rounded.
    fn sum(&mut self, s: &ExactSum) -> Result<f64>;
    /// The sum of `n` over all ranks.
    fn count(&mut self, n: usize) -> Result<usize>;
    /// Whether `b` holds on some rank.
    fn any(&mut self, b: bool) -> Result<bool>;
    /// The colour classes of `nodes` (owned here), each in node order: greedy in global node
    /// order over the whole mesh, so that no two nodes of a class share a cell. Every rank gets
    /// the same number of classes (some perhaps empty).
    fn colour_classes<const D: usize>(
        &mut self,
        problem: &Problem<D>,
        nodes: &[usize],
    ) -> Result<Vec<Vec<usize>>>;
}

/// The team of one process holding the whole mesh.
pub struct Alone;

impl Team for Alone {
    fn owns(&self, _: usize) -> bool {
        true
    }
    fn counts(&self, _: usize) -> bool {
        true
    }
    fn refresh(&mut self, _: &mut [f64], _: usize) -> Result<()> {
        Ok(())
    }
    fn max(&mut self, x: f64) -> Result<f64> {
        Ok(x)
    }
    fn min(&mut self, x: f64) -> Result<f64> {
        Ok(x)
    }
    fn sum(&mut self, s: &ExactSum) -> Result<f64> {
        Ok(s.value())
    }
    fn count(&mut self, n: usize) -> Result<usize> {
        Ok(n)
    }
    fn any(&mut self, b: bool) -> Result<bool> {
        Ok(b)
    }
    fn colour_classes<const D: usize>(
        &mut self,
        problem: &Problem<D>,
        nodes: &[usize],
    ) -> Result<Vec<Vec<usize>>> {
        Ok(colour_nodes(problem, nodes))
    }
}
