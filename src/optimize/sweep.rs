//! Gauss–Seidel sweeps over the free nodes, colour by colour, each colour in parallel.

use rayon::prelude::*;
use rayon::ThreadPool;

use super::exact::ExactSum;
use super::node::{minimise, NodeSolverOptions};
use super::problem::Problem;
use super::small_matrix::Vector;
use super::team::{Alone, Team};
use crate::error::{Error, Result};
use crate::threads;

/// When the sweeps stop.
#[derive(Clone, Copy, Debug)]
pub struct SweepOptions {
    /// Largest number of sweeps.
    pub max_sweeps: u32,
    /// Stop once the mesh is valid (but for cells that fixed nodes alone fold) and no node moved
    /// more than this fraction of its local length.
    pub move_tolerance: f64,
    /// The per-node solver's stopping rules.
    pub node: NodeSolverOptions,
}

/// What the sweeps did.
#[derive(Clone, Copy, Debug, Default)]
pub struct SweepStats {
    /// Sweeps performed.
    pub sweeps: u32,
    /// Largest relative move in the last sweep.
    pub last_max_move: f64,
    /// Whether the stopping rule (valid, small moves) was met before the sweep limit. The sweeps
    /// also stop, not converged, on small moves when the only invalid cells are folded where
    /// fixed nodes alone act ([`Problem::has_fixed_fold`]).
    pub converged: bool,
}

/// Indices of the cells that are not valid (`det J ≤ 0` at some Gauss–Lobatto point).
pub fn invalid_cells<const D: usize>(
    pool: &ThreadPool,
    problem: &Problem<D>,
    positions: &[Vector<D>],
) -> Vec<usize> {
    let mut valid = vec![false; problem.cell_count()];
    // A Jacobian per Gauss–Lobatto point, from up to 3^d nodes (as many as the points).
    let per_cell = Problem::<D>::POINTS * Problem::<D>::POINTS * D * D;
    threads::for_each_mut(pool, valid.len() * per_cell, &mut valid, |c, valid| {
        *valid = problem.cell_is_valid(c, positions)
    });
    (0..valid.len()).filter(|&c| !valid[c]).collect()
}

/// Optimizes the free components of the free nodes in place. `progress(done, total)` is called
/// after every sweep; returning `false` cancels (positions then hold the last complete sweep).
pub fn optimize<const D: usize>(
    pool: &ThreadPool,
    problem: &Problem<D>,
    positions: &mut [Vector<D>],
    options: &SweepOptions,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<SweepStats> {
    optimize_on(&mut Alone, pool, problem, positions, options, progress)
}

/// [`optimize`] on the ranks of `team`: each rank updates the nodes it owns, ghost copies are
/// refreshed after every colour class, and the stopping rules use global figures, so that the
/// result is the one of the whole mesh in one process. A cancellation on any rank cancels all.
pub fn optimize_on<const D: usize, T: Team>(
    team: &mut T,
    pool: &ThreadPool,
    problem: &Problem<D>,
    positions: &mut [Vector<D>],
    options: &SweepOptions,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<SweepStats> {
    let n = problem.node_count();
    let free_nodes: Vec<usize> = (0..n)
        .filter(|&v| team.owns(v))
        .filter(|&v| problem.free_mask(v) != 0 && !problem.incident_cells(v).is_empty())
        .collect();
    let colours = team.colour_classes(problem, &free_nodes)?;
    let mut active = vec![true; n];
    let mut stats = SweepStats::default();
    let mut history: Vec<(f64, f64)> = Vec::new();

    let total = options.max_sweeps as usize;
    for sweep in 1..=options.max_sweeps {
        let (mut marks, max_move) =
            sweep_once(team, pool, problem, positions, &colours, &active, options)?;
        let max_move = team.max(max_move)?;
        stats.sweeps = sweep;
        stats.last_max_move = max_move;
        if team.any(!progress(sweep as usize, total))? {
            return Err(Error::cancelled());
        }
        let quality = QualitySummary::on(team, pool, problem, positions)?;
        let stalled = history
            .len()
            .checked_sub(STALL_WINDOW)
            .is_some_and(|i| quality.stalled_since(history[i]));
        history.push((quality.min, quality.mean));
        // Cells folded where only fixed nodes act stay folded whatever the sweeps do: the
        // others decide when to stop and which nodes to revisit.
        let mendable = mendable(problem, &quality.invalid, positions);
        if count_on(team, &mendable)? == 0 && (max_move < options.move_tolerance || stalled) {
            stats.converged = quality.invalid_count == 0;
            break;
        }
        for &c in &mendable {
            for &v in problem.cell_nodes(c) {
                marks[v as usize] = 1.0;
            }
        }
        team.refresh(&mut marks, 1)?;
        let mut next_active = vec![false; n];
        for v in (0..n).filter(|&v| marks[v] != 0.0) {
            mark_neighbours(problem, v, &mut next_active);
        }
        if !team.any((0..n).any(|v| next_active[v] && team.owns(v)))? {
            break;
        }
        active = next_active;
    }
    Ok(stats)
}

/// One sweep: the `active` nodes of each colour class in parallel, the ghosts refreshed after
/// each class. Returns per node 1 when it moved more than the tolerance (the nodes sharing a
/// cell with such a node are optimized in the next sweep), else 0, and the largest relative
/// move on this rank.
fn sweep_once<const D: usize, T: Team>(
    team: &mut T,
    pool: &ThreadPool,
    problem: &Problem<D>,
    positions: &mut [Vector<D>],
    colours: &[Vec<usize>],
    active: &[bool],
    options: &SweepOptions,
) -> Result<(Vec<f64>, f64)> {
    let mut marks = vec![0.0; problem.node_count()];
    let mut max_move = 0.0f64;
    for class in colours {
        let todo: Vec<usize> = class.iter().copied().filter(|&v| active[v]).collect();
        let snapshot: &[Vector<D>] = positions;
        let solve = |terms: &mut Vec<_>, &v: &usize| {
            let (weight_sum, length) = problem.node_terms(v, snapshot, terms);
            let free = problem.free_mask(v);
            let x = minimise(
                &terms[..],
                snapshot[v],
                free,
                weight_sum,
                length,
                &options.node,
            );
            (v, x, length)
        };
        let results: Vec<(usize, Option<Vector<D>>, f64)> =
            pool.install(|| todo.par_iter().map_init(Vec::new, solve).collect());
        for (v, x, length) in results {
            let Some(x) = x else { continue };
            let step = (0..D)
                .map(|k| (x[k] - positions[v][k]).powi(2))
                .sum::<f64>()
                .sqrt();
            let relative = step / length;
            max_move = max_move.max(relative);
            positions[v] = x;
            if relative > options.move_tolerance {
                marks[v] = 1.0;
            }
        }
        team.refresh(positions.as_flattened_mut(), D)?;
    }
    Ok((marks, max_move))
}

/// Sweeps over which a stalled quality ends the optimization.
const STALL_WINDOW: usize = 10;

/// Quality of every cell of a mesh and its summary.
#[derive(Clone, Debug)]
pub struct QualitySummary {
    /// Quality of every (local) cell (see [`Problem::cell_quality`]).
    pub quality: Vec<f64>,
    /// Smallest cell quality (over all ranks).
    pub min: f64,
    /// Mean cell quality (over all ranks), from the exact sum of the qualities.
    pub mean: f64,
    /// Local cells of quality 0 (inverted somewhere).
    pub invalid: Vec<usize>,
    /// Cells of quality 0 over all ranks.
    pub invalid_count: usize,
}

impl QualitySummary {
    /// Evaluates every cell in parallel; the summary does not depend on the thread count.
    pub fn of<const D: usize>(
        pool: &ThreadPool,
        problem: &Problem<D>,
        positions: &[Vector<D>],
    ) -> Self {
        let (quality, invalid) = Self::cells(pool, problem, positions);
        QualitySummary {
            min: quality.iter().copied().fold(f64::INFINITY, f64::min),
            mean: ExactSum::of(quality.iter().copied()).value() / quality.len().max(1) as f64,
            invalid_count: invalid.len(),
            invalid,
            quality,
        }
    }

    /// [`QualitySummary::of`] over the ranks of `team` (each cell counted once).
    pub fn on<const D: usize, T: Team>(
        team: &mut T,
        pool: &ThreadPool,
        problem: &Problem<D>,
        positions: &[Vector<D>],
    ) -> Result<Self> {
        let (quality, invalid) = Self::cells(pool, problem, positions);
        let counted = || (0..quality.len()).filter(|&c| team.counts(c));
        let min = counted().map(|c| quality[c]).fold(f64::INFINITY, f64::min);
        let sum = ExactSum::of(counted().map(|c| quality[c]));
        let cells = counted().count();
        let cells = team.count(cells)?;
        Ok(QualitySummary {
            min: team.min(min)?,
            mean: team.sum(&sum)? / cells.max(1) as f64,
            invalid_count: count_on(team, &invalid)?,
            invalid,
            quality,
        })
    }

    /// The quality of every cell and the invalid ones.
    fn cells<const D: usize>(
        pool: &ThreadPool,
        problem: &Problem<D>,
        positions: &[Vector<D>],
    ) -> (Vec<f64>, Vec<usize>) {
        let quality: Vec<f64> = pool.install(|| {
            (0..problem.cell_count())
                .into_par_iter()
                .map(|c| problem.cell_quality(c, positions))
                .collect()
        });
        let invalid = (0..quality.len()).filter(|&c| quality[c] <= 0.0).collect();
        (quality, invalid)
    }

    /// Whether neither the smallest nor the mean quality improved noticeably since the
    /// `(min, mean)` of an earlier sweep.
    fn stalled_since(&self, (old_min, old_mean): (f64, f64)) -> bool {
        self.min - old_min < 1e-2 && self.mean - old_mean < 1e-4
    }
}

/// The number of invalid cells over the ranks of `team`.
pub fn invalid_count_on<const D: usize, T: Team>(
    team: &mut T,
    pool: &ThreadPool,
    problem: &Problem<D>,
    positions: &[Vector<D>],
) -> Result<usize> {
    count_on(team, &invalid_cells(pool, problem, positions))
}

/// The number of invalid cells over the ranks of `team` that the free nodes may mend: those
/// without a fold where only fixed nodes act ([`Problem::has_fixed_fold`]).
pub fn mendable_count_on<const D: usize, T: Team>(
    team: &mut T,
    pool: &ThreadPool,
    problem: &Problem<D>,
    positions: &[Vector<D>],
) -> Result<usize> {
    let invalid = invalid_cells(pool, problem, positions);
    count_on(team, &mendable(problem, &invalid, positions))
}

/// How many of the local `cells` there are over the ranks of `team` (each counted once).
fn count_on<T: Team>(team: &mut T, cells: &[usize]) -> Result<usize> {
    team.count(cells.iter().filter(|&&c| team.counts(c)).count())
}

/// The cells of `invalid` without a fold where only fixed nodes act.
fn mendable<const D: usize>(
    problem: &Problem<D>,
    invalid: &[usize],
    positions: &[Vector<D>],
) -> Vec<usize> {
    invalid
        .iter()
        .copied()
        .filter(|&c| !problem.has_fixed_fold(c, positions))
        .collect()
}

fn mark_neighbours<const D: usize>(problem: &Problem<D>, v: usize, active: &mut [bool]) {
    for &(c, _) in problem.incident_cells(v) {
        for &m in problem.cell_nodes(c as usize) {
            active[m as usize] = true;
        }
    }
}
