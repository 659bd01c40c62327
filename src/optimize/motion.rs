//! Optimization that follows a prescribed motion of the constrained components: large motions are
//! applied in steps, each placed harmonically from the previous optimized state and optimized; a
//! step that leaves invalid cells is halved (cells that fixed nodes alone fold do not count: no
//! step mends them).
//!
//! Measured on the rotated airfoil: in one step the per-node optimizer leaves 2 of 490 cells
//! folded (nodes pinned between several nearly-zero Jacobians, which no single-node move can
//! open); in four steps it leaves none.

use rayon::ThreadPool;

use super::laplace::MeshGraph;
use super::problem::Problem;
use super::small_matrix::Vector;
use super::sweep::{mendable_count_on, optimize_on, SweepOptions, SweepStats};
use super::team::{Alone, Team};
use crate::error::Result;

/// Smallest fraction of the motion applied in one step.
const MIN_STEP: f64 = 1.0 / 256.0;

/// Intermediate steps stop at a looser move tolerance: only the last one needs to be smooth.
const INTERMEDIATE_TOLERANCE_FACTOR: f64 = 10.0;

/// The sweeps of all steps together stay below this many times the sweep limit of one step
/// (the last step excepted).
const SWEEP_BUDGET_FACTOR: u32 = 10;

/// Largest prescribed move, in local cell sizes, applied in one step.
const CELLS_PER_STEP: f64 = 4.0;

/// What following a motion did.
#[derive(Clone, Copy, Debug, Default)]
pub struct MotionStats {
    /// Sweeps over all steps.
    pub sweeps: u32,
    /// Steps the motion was applied in.
    pub steps: u32,
    /// Whether the last step's sweeps met their stopping rule.
    pub converged: bool,
}

/// Optimizes `x` as it is, in one go. `progress(sweeps)` may cancel.
pub fn optimize_in_place<const D: usize>(
    pool: &ThreadPool,
    problem: &Problem<D>,
    x: &mut [Vector<D>],
    options: &SweepOptions,
    progress: &mut dyn FnMut(usize) -> bool,
) -> Result<MotionStats> {
    optimize_in_place_on(&mut Alone, pool, problem, x, options, progress)
}

/// [`optimize_in_place`] on the ranks of `team`.
pub fn optimize_in_place_on<const D: usize, T: Team>(
    team: &mut T,
    pool: &ThreadPool,
    problem: &Problem<D>,
    x: &mut [Vector<D>],
    options: &SweepOptions,
    progress: &mut dyn FnMut(usize) -> bool,
) -> Result<MotionStats> {
    let stats = optimize_on(team, pool, problem, x, options, &mut |done, _| {
        progress(done)
    })?;
    Ok(MotionStats {
        sweeps: stats.sweeps,
        steps: 1,
        converged: stats.converged,
    })
}

/// Carries the constrained components of `start` (a valid state) to their values in `goal`
/// (whose free components are ignored), placing and optimizing the free ones on the way.
/// `progress(sweeps)` is called after every sweep; returning false cancels.
pub fn follow_motion<const D: usize>(
    pool: &ThreadPool,
    problem: &Problem<D>,
    graph: &MeshGraph,
    start: &[Vector<D>],
    goal: &[Vector<D>],
    options: &SweepOptions,
    progress: &mut dyn FnMut(usize) -> bool,
) -> Result<(Vec<Vector<D>>, MotionStats)> {
    let ends = Ends { start, goal };
    follow_motion_on(&mut Alone, pool, problem, graph, ends, options, progress)
}

/// The two ends of a motion: a valid state and the goal of its constrained components.
#[derive(Clone, Copy)]
pub struct Ends<'a, const D: usize> {
    /// The valid state the motion starts from.
    pub start: &'a [Vector<D>],
    /// The goal (its free components are ignored).
    pub goal: &'a [Vector<D>],
}

/// [`follow_motion`] on the ranks of `team`.
pub fn follow_motion_on<const D: usize, T: Team>(
    team: &mut T,
    pool: &ThreadPool,
    problem: &Problem<D>,
    graph: &MeshGraph,
    Ends { start, goal }: Ends<'_, D>,
    options: &SweepOptions,
    progress: &mut dyn FnMut(usize) -> bool,
) -> Result<(Vec<Vector<D>>, MotionStats)> {
    let mut stats = MotionStats::default();
    let mut run = |team: &mut T,
                   x: &mut Vec<Vector<D>>,
                   sweeps_done: u32,
                   last: bool|
     -> Result<(SweepStats, bool)> {
        let mut step_options = *options;
        if !last {
            step_options.move_tolerance *= INTERMEDIATE_TOLERANCE_FACTOR;
        }
        let s = optimize_on(team, pool, problem, x, &step_options, &mut |done, _| {
            progress(sweeps_done as usize + done)
        })?;
        Ok((s, mendable_count_on(team, pool, problem, x)? == 0))
    };
    // Bounds the work when steps keep failing: the remaining motion then comes in one step.
    let budget = options.max_sweeps.saturating_mul(SWEEP_BUDGET_FACTOR);
    let mut done_t = 0.0;
    let mut state = start.to_vec();
    let first_dt = 1.0 / initial_steps(team, problem, start, goal)? as f64;
    let mut dt = first_dt;
    while done_t < 1.0 {
        let t = (done_t + dt).min(1.0);
        let mut trial = state.clone();
        set_fixed_at(problem, start, goal, t, &mut trial);
        graph.harmonic_placement_on(team, pool, problem, &state, &mut trial)?;
        let (sweep, valid) = run(team, &mut trial, stats.sweeps, t >= 1.0)?;
        stats.sweeps += sweep.sweeps;
        if !valid && dt > MIN_STEP && stats.sweeps < budget {
            dt *= 0.5;
            continue;
        }
        stats.converged = sweep.converged;
        stats.steps += 1;
        done_t = t;
        state = trial;
        // After a success the step grows back; a failure even at the smallest step will not be
        // repaired by more small steps, so the rest comes in one.
        dt = if valid && stats.sweeps < budget {
            (2.0 * dt).min(first_dt)
        } else {
            1.0 - done_t
        };
    }
    Ok((state, stats))
}

/// Number of steps so that no constrained node moves more than [`CELLS_PER_STEP`] times the size
/// of its cells in one step.
fn initial_steps<const D: usize, T: Team>(
    team: &mut T,
    problem: &Problem<D>,
    start: &[Vector<D>],
    goal: &[Vector<D>],
) -> Result<usize> {
    let mut ratio = 0.0f64;
    for v in 0..start.len() {
        if problem.free_mask(v) == (1 << D) - 1 || !team.owns(v) {
            continue;
        }
        let moved = (0..D)
            .map(|k| (goal[v][k] - start[v][k]).powi(2))
            .sum::<f64>()
            .sqrt();
        if moved == 0.0 {
            continue;
        }
        let length = problem.node_length(v);
        if length > 0.0 {
            ratio = ratio.max(moved / (2.0 * length));
        }
    }
    let ratio = team.max(ratio)?;
    Ok(((ratio / CELLS_PER_STEP).ceil() as usize).clamp(1, (1.0 / MIN_STEP) as usize))
}

/// Puts the constrained components at `start + t·(goal − start)`.
fn set_fixed_at<const D: usize>(
    problem: &Problem<D>,
    start: &[Vector<D>],
    goal: &[Vector<D>],
    t: f64,
    x: &mut [Vector<D>],
) {
    for (v, p) in x.iter_mut().enumerate() {
        for k in 0..D {
            if problem.free_mask(v) & (1 << k) == 0 {
                p[k] = if t >= 1.0 {
                    goal[v][k]
                } else {
                    start[v][k] + t * (goal[v][k] - start[v][k])
                };
            }
        }
    }
}
