//! Path following of the optimum: the prescribed coordinates go from their values at a stationary
//! state to their goal in steps; each step is predicted by the tangent of the optimum
//! (`−H_ff⁻¹ H_fp Δx_p`, the mesh's linearised response with the mean-ratio metric as its
//! stiffness) and corrected by Newton's method on the global objective. A step whose prediction
//! folds a cell, or whose correction does not converge, is halved; after a success the step
//! grows back.
//!
//! Measured on the bundled airfoil (profile rotated by 60°): the tangent at the reference shape
//! places the whole motion with no folded cell, where the harmonic extension folds 49, so the
//! motion usually takes one step.

use std::sync::Arc;

use rayon::ThreadPool;

use super::problem::Problem;
use super::small_matrix::Vector;
use super::solver::{HessianSolver, SolverSetup};
use super::stationary::{minimise, StationaryOptions};
use super::sweep::invalid_cells;
use crate::error::Result;

/// Smallest fraction of the motion tried in one step.
const MIN_STEP: f64 = 1.0 / 64.0;

/// Scaled-gradient tolerance of the corrector at intermediate steps.
const STEP_TOLERANCE: f64 = 1e-4;

/// Relative residual of the predictor's solve: the corrector takes it from there.
const PREDICTION_TOLERANCE: f64 = 1e-3;

/// Newton iterations allowed to the corrector of one step.
const CORRECTOR_ITERATIONS: u32 = 30;

/// Where path following got to.
pub struct PathOutcome<const D: usize> {
    /// The last accepted state (stationary at the prescribed values of `reached`).
    pub x: Vec<Vector<D>>,
    /// The solver of the Hessian at `x`.
    pub solver: Arc<HessianSolver<D>>,
    /// Invalid cells of the first prediction.
    pub first_invalid: usize,
    /// Fraction of the motion reached (1: the goal).
    pub reached: f64,
    /// Accepted steps.
    pub steps: u32,
    /// Newton iterations over all steps, the rejected ones included.
    pub newton_iterations: u32,
    /// Whether the final corrector met `tolerance` (at the goal).
    pub converged: bool,
    /// Scaled gradient norm at `x`.
    pub gradient_norm: f64,
}

/// The state path following starts from: positions stationary at their own prescribed values,
/// with the solver of the Hessian there.
pub struct PathStart<const D: usize> {
    /// Positions.
    pub x: Vec<Vector<D>>,
    /// The solver of the Hessian at `x`.
    pub solver: Arc<HessianSolver<D>>,
}

/// Where path following ends, and how.
#[derive(Clone, Copy)]
pub struct Goal<'a, const D: usize> {
    /// The positions whose prescribed coordinates are the goal (the free ones are ignored).
    pub positions: &'a [Vector<D>],
    /// The scaled-gradient tolerance met there.
    pub tolerance: f64,
    /// Whether the solver returned must be that of the Hessian at the final state
    /// ([`StationaryOptions::exact_solver`]): the sensitivities are asked for.
    pub exact_solver: bool,
}

/// Follows the optimum from `start` to the prescribed values of `goal`, meeting its tolerance
/// there. `progress(newton_iterations)` may cancel.
pub fn follow<const D: usize>(
    pool: &ThreadPool,
    problem: &Problem<D>,
    setup: &Arc<SolverSetup>,
    start: PathStart<D>,
    goal: Goal<'_, D>,
    progress: &mut dyn FnMut(usize) -> bool,
) -> Result<PathOutcome<D>> {
    let prescribed = start.solver.prescribed();
    let origin = start.x.clone();
    let mut outcome = PathOutcome {
        x: start.x,
        solver: start.solver,
        first_invalid: 0,
        reached: 0.0,
        steps: 0,
        newton_iterations: 0,
        converged: false,
        gradient_norm: f64::INFINITY,
    };
    let mut schedule = Schedule::default();
    while let Some(t) = schedule.next() {
        let last = t >= 1.0;
        // The prescribed coordinates at t, and their motion over this step.
        let target: Vec<Vector<D>> = (0..goal.positions.len())
            .map(|v| {
                std::array::from_fn(|k| match prescribed[v] & (1 << k) != 0 {
                    true => prescribed_at(&origin[v], &goal.positions[v], k, t),
                    false => outcome.x[v][k],
                })
            })
            .collect();
        let predicted = predict(pool, &outcome.solver, &outcome.x, &target)?;
        let invalid = predicted
            .as_ref()
            .map_or(usize::MAX, |x| invalid_cells(pool, problem, x).len());
        if outcome.steps == 0 && schedule.first() {
            outcome.first_invalid = invalid;
        }
        let corrected = match predicted {
            Some(mut x) if invalid == 0 => {
                let options = StationaryOptions {
                    tolerance: if last { goal.tolerance } else { STEP_TOLERANCE },
                    max_iterations: CORRECTOR_ITERATIONS,
                    exact_solver: last && goal.exact_solver,
                };
                let done = outcome.newton_iterations as usize;
                let (stats, solver) = minimise(
                    pool,
                    problem,
                    setup,
                    &mut x,
                    &options,
                    Some(outcome.solver.preconditioner().clone()),
                    &mut |i| progress(done + i),
                )?;
                outcome.newton_iterations += stats.iterations;
                match solver {
                    Some(solver) if stats.converged => Some((x, solver, stats.gradient_norm)),
                    _ => None,
                }
            }
            _ => None,
        };
        match corrected {
            Some((x, solver, gradient_norm)) => {
                outcome.x = x;
                outcome.solver = Arc::new(solver);
                outcome.gradient_norm = gradient_norm;
                outcome.reached = t;
                outcome.steps += 1;
                outcome.converged = last;
                schedule.accept(t);
            }
            None => schedule.reject(t),
        }
    }
    Ok(outcome)
}

/// The fractions of the motion path following tries: the whole rest first, half the step tried
/// after a failure, twice the last step after a success, until the goal or a step below
/// [`MIN_STEP`].
#[derive(Clone, Copy, Debug)]
struct Schedule {
    reached: f64,
    dt: f64,
}

impl Default for Schedule {
    fn default() -> Self {
        Schedule {
            reached: 0.0,
            dt: 1.0,
        }
    }
}

impl Schedule {
    /// The next fraction to reach, `None` when done or the step became too small.
    fn next(&self) -> Option<f64> {
        (self.reached < 1.0 && self.dt >= MIN_STEP).then(|| (self.reached + self.dt).min(1.0))
    }

    /// Whether nothing was tried yet.
    fn first(&self) -> bool {
        self.reached == 0.0 && self.dt == 1.0
    }

    /// `t` was reached.
    fn accept(&mut self, t: f64) {
        self.dt = (2.0 * (t - self.reached)).min(1.0);
        self.reached = t;
    }

    /// `t` could not be reached: half the step tried next (not half of a `dt` that reached
    /// past the goal, which would try the same step again).
    fn reject(&mut self, t: f64) {
        self.dt = 0.5 * (t - self.reached);
    }
}

/// Component `k` of a prescribed node at fraction `t` of its motion from `origin` to `goal`.
fn prescribed_at<const D: usize>(origin: &Vector<D>, goal: &Vector<D>, k: usize, t: f64) -> f64 {
    match t >= 1.0 {
        true => goal[k],
        false => origin[k] + t * (goal[k] - origin[k]),
    }
}

/// `x` with its prescribed coordinates at `target` (exactly) and its free ones moved by the
/// tangent response to that motion; `None` if the solve did not converge.
fn predict<const D: usize>(
    pool: &ThreadPool,
    solver: &HessianSolver<D>,
    x: &[Vector<D>],
    target: &[Vector<D>],
) -> Result<Option<Vec<Vector<D>>>> {
    let motion: Vec<Vector<D>> = x
        .iter()
        .zip(target)
        .map(|(x, t)| std::array::from_fn(|k| t[k] - x[k]))
        .collect();
    let Ok(dx) = solver.tangent(pool, &motion, PREDICTION_TOLERANCE) else {
        return Ok(None);
    };
    let free = solver.free();
    Ok(Some(
        (0..x.len())
            .map(|v| {
                std::array::from_fn(|k| match free[v] & (1 << k) != 0 {
                    true => x[v][k] + dx[v][k],
                    false => target[v][k],
                })
            })
            .collect(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whatever steps fail, no step is tried twice, and the goal is reached where steps of
    /// some size at least `MIN_STEP` succeed. Here the longest step that succeeds shrinks
    /// towards the goal, as where the end of the motion is the hard part.
    #[test]
    fn the_schedule_never_repeats_a_failed_step() {
        for longest in [0.9, 0.6, 0.5, 0.4, 0.3, 0.2, 0.13, 0.1, 0.08] {
            let mut schedule = Schedule::default();
            let mut tried = Vec::new();
            while let Some(t) = schedule.next() {
                let step = (schedule.reached, t);
                assert!(!tried.contains(&step), "{step:?} twice (longest {longest})");
                tried.push(step);
                match t - schedule.reached <= longest * (1.2 - schedule.reached) {
                    true => schedule.accept(t),
                    false => schedule.reject(t),
                }
                assert!(tried.len() < 200);
            }
            assert_eq!(schedule.reached, 1.0, "longest {longest}");
        }
    }
}
