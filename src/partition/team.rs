//! The ranks of a partition as a [`Team`] of the optimizer.

use super::exchange::Ranks;
use super::ghost::GhostPlan;
use crate::error::Result;
use crate::optimize::exact::ExactSum;
use crate::optimize::team::Team;
use crate::optimize::Problem;

/// A colour not yet given.
const NONE: f64 = -1.0;

/// The ranks of a partition with its ownership and ghost plan.
pub struct PartTeam<'r, 'e> {
    /// The ranks.
    pub ranks: &'r mut Ranks<'e>,
    /// The ghost refreshes.
    pub plan: &'r GhostPlan,
    /// Per local node: owned here.
    pub owned: &'r [bool],
    /// Per local cell: counted here (its first node is owned here).
    pub counted: Vec<bool>,
}

impl PartTeam<'_, '_> {
    /// Every rank's `x`.
    fn gather(&mut self, x: u64) -> Result<Vec<u64>> {
        Ok(self
            .ranks
            .all_gather_words(&[x])?
            .iter()
            .map(|w| w[0])
            .collect())
    }
}

impl Team for PartTeam<'_, '_> {
    fn owns(&self, v: usize) -> bool {
        self.owned[v]
    }
    fn counts(&self, c: usize) -> bool {
        self.counted[c]
    }
    fn refresh(&mut self, values: &mut [f64], width: usize) -> Result<()> {
        self.plan.refresh(self.ranks, values, width)
    }
    fn max(&mut self, x: f64) -> Result<f64> {
        let all = self.gather(x.to_bits())?;
        Ok(all
            .iter()
            .map(|&b| f64::from_bits(b))
            .fold(f64::NEG_INFINITY, f64::max))
    }
    fn min(&mut self, x: f64) -> Result<f64> {
        let all = self.gather(x.to_bits())?;
        Ok(all
            .iter()
            .map(|&b| f64::from_bits(b))
            .fold(f64::INFINITY, f64::min))
    }
    fn sum(&mut self, s: &ExactSum) -> Result<f64> {
        let mine: Vec<u64> = s.to_words().iter().map(|&w| w as u64).collect();
        let mut total = ExactSum::default();
        for words in self.ranks.all_gather_words(&mine)? {
            let w: Vec<i64> = words.iter().map(|&x| x as i64).collect();
            let part = ExactSum::from_words(&w)
                .ok_or_else(|| super::exchange::exchange_failed("a sum was garbled"))?;
            total.merge(&part);
        }
        Ok(total.value())
    }
    fn count(&mut self, n: usize) -> Result<usize> {
        Ok(self.gather(n as u64)?.iter().sum::<u64>() as usize)
    }
    fn any(&mut self, b: bool) -> Result<bool> {
        Ok(self.gather(b as u64)?.iter().any(|&x| x != 0))
    }

    /// The serial greedy colouring in global id order, computed in rounds: a node takes the
    /// smallest colour none of its coloured neighbours of smaller id has, once all of those are
    /// coloured; ghost colours are refreshed between rounds.
    fn colour_classes<const D: usize>(
        &mut self,
        problem: &Problem<D>,
        nodes: &[usize],
    ) -> Result<Vec<Vec<usize>>> {
        let n = problem.node_count();
        // Local order is global id order, and the free nodes with cells are those coloured.
        let coloured_kind: Vec<bool> = (0..n)
            .map(|v| problem.free_mask(v) != 0 && !problem.incident_cells(v).is_empty())
            .collect();
        let mut colour = vec![NONE; n];
        let mut todo: Vec<usize> = nodes.to_vec();
        let mut neighbours = Vec::new();
        // Dependencies go to smaller ids only, so every round colours at least the smallest
        // waiting node of the whole mesh.
        while self.any(!todo.is_empty())? {
            let mut waiting = Vec::new();
            for &v in &todo {
                neighbours.clear();
                for &(c, _) in problem.incident_cells(v) {
                    neighbours.extend(problem.cell_nodes(c as usize).iter().map(|&m| m as usize));
                }
                let lower = || neighbours.iter().filter(|&&m| m < v && coloured_kind[m]);
                if lower().any(|&m| colour[m] == NONE) {
                    waiting.push(v);
                    continue;
                }
                let used: Vec<usize> = lower().map(|&m| colour[m] as usize).collect();
                colour[v] = (0..).find(|k| !used.contains(k)).unwrap_or(0) as f64;
            }
            todo = waiting;
            self.refresh(&mut colour, 1)?;
        }
        let classes = nodes
            .iter()
            .map(|&v| colour[v] as usize + 1)
            .max()
            .unwrap_or(0);
        let classes = self.gather(classes as u64)?.into_iter().max().unwrap_or(0) as usize;
        let mut out = vec![Vec::new(); classes];
        for &v in nodes {
            out[colour[v] as usize].push(v);
        }
        Ok(out)
    }
}
