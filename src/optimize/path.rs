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
use super::solver::{HessianSolver, Preconditioner, SolverSetup};
use super::stationary::{minimise, solver_at, Lagged, StationaryOptions};
use super::sweep::invalid_cells;
use crate::error::Result;

/// Smallest fraction of the motion tried in one step.
const MIN_STEP: f64 = 1.0 / 64.0;

/// Scaled-gradient tolerance of the corrector at intermediate steps.
const STEP_TOLERANCE: f64 = 1e-4;

/// Relative residual of the predictor's solve: the corrector takes it from there.
const PREDICTION_TOLERANCE: f64 = 1e-3;

/// Newton iterations allowed to the corrector of one step. A prediction where the Hessian is
/// indefinite costs tens of iterations of modified Newton steps before the quadratic rate: the
/// 96,740-node refined airfoil's whole motion converges in 31 (with a limit of 30 it was
/// rejected there, and again on half the motion: 127 iterations and 108 s, against 40 and 35 s).
const CORRECTOR_ITERATIONS: u32 = 60;

/// Where path following got to.
pub struct PathOutcome<const D: usize> {
    /// The last accepted state (stationary at the prescribed values of `reached`).
    pub x: Vec<Vector<D>>,
    /// The solver of the Hessian at `x` (`None` only where the path stopped short of its goal).
    pub solver: Option<Arc<HessianSolver<D>>>,
    /// The preconditioner of the last corrector, to make the solver at `x` again with.
    lagged: Option<Arc<Preconditioner<D>>>,
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
        solver: Some(start.solver),
        lagged: None,
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
        let target = target_at(&prescribed, (&origin, goal.positions), &outcome.x, t);
        let Some(solver) = outcome.take_solver(pool, problem, setup)? else {
            break;
        };
        let predicted = predict(pool, &solver, &outcome.x, &target)?;
        let invalid = predicted
            .as_ref()
            .map_or(usize::MAX, |x| invalid_cells(pool, problem, x).len());
        crate::diagnostics::note(|| match invalid {
            usize::MAX => format!("path: step to {t}, no prediction (its solve failed)"),
            _ => format!("path: step to {t}, predicted, {invalid} invalid"),
        });
        if outcome.steps == 0 && schedule.first() {
            outcome.first_invalid = invalid;
        }
        let Some(mut x) = predicted.filter(|_| invalid == 0) else {
            outcome.solver = Some(solver);
            schedule.reject(t);
            continue;
        };
        let (lagged, kept) = hand_over(solver);
        outcome.lagged = Some(lagged.preconditioner.clone());
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
            Some(lagged),
            &mut |i| progress(done + i),
        )?;
        outcome.newton_iterations += stats.iterations;
        match solver.filter(|_| stats.converged) {
            Some(solver) => {
                outcome.x = x;
                outcome.solver = Some(Arc::new(solver));
                outcome.gradient_norm = stats.gradient_norm;
                outcome.reached = t;
                outcome.steps += 1;
                outcome.converged = last;
                schedule.accept(t);
            }
            None => {
                outcome.solver = kept;
                schedule.reject(t);
            }
        }
    }
    Ok(outcome)
}

impl<const D: usize> PathOutcome<D> {
    /// The solver at the last accepted state: the one kept, or one made again (with the last
    /// preconditioner) where a failed step had retired it; `None` where none can be made.
    fn take_solver(
        &mut self,
        pool: &ThreadPool,
        problem: &Problem<D>,
        setup: &Arc<SolverSetup>,
    ) -> Result<Option<Arc<HessianSolver<D>>>> {
        match (self.solver.take(), self.lagged.clone()) {
            (Some(solver), _) => Ok(Some(solver)),
            (None, Some(p)) => Ok(solver_at(pool, problem, setup, &self.x, p)?.map(Arc::new)),
            (None, None) => Ok(None),
        }
    }
}

/// The prescribed coordinates at fraction `t` of their motion from `origin` to `goal` (`ends`),
/// the free ones those of `x`.
fn target_at<const D: usize>(
    prescribed: &[u8],
    (origin, goal): (&[Vector<D>], &[Vector<D>]),
    x: &[Vector<D>],
    t: f64,
) -> Vec<Vector<D>> {
    (0..goal.len())
        .map(|v| {
            std::array::from_fn(|k| match prescribed[v] & (1 << k) != 0 {
                true => prescribed_at(&origin[v], &goal[v], k, t),
                false => x[v][k],
            })
        })
        .collect()
}

/// The predictor's solver handed to the corrector. One no one else holds is done with: its
/// Hessian's storage receives the corrector's first evaluation (one Hessian at a time: a
/// million-node solid's are gigabytes), and it is evaluated again should the step fail. One
/// held elsewhere too (a state kept on the mesh) lends its preconditioner and is returned.
fn hand_over<const D: usize>(
    solver: Arc<HessianSolver<D>>,
) -> (Lagged<D>, Option<Arc<HessianSolver<D>>>) {
    match Arc::try_unwrap(solver) {
        Ok(solver) => (Lagged::retired(solver), None),
        Err(shared) => (Lagged::shared(shared.preconditioner()), Some(shared)),
    }
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
