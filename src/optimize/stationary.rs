//! The Newton stage: on a valid mesh, minimises the one global objective
//! `F(x) = Σ_c w_c η̄*_c(x)` with δ = 0 (where `η* = ‖S‖²/(d σ^{2/d})` is smooth and infinite at
//! folds) until the scaled gradient is below a tolerance.
//!
//! The scaled gradient of a free coordinate is `|∂F/∂x_vk| · L_v / W_v` (`L_v` the node's local
//! length, `W_v` the weights of its cells): the gradient of the node's own objective times its
//! length, the quantity the per-node solver stops on, so both tolerances mean the same thing.
//! Steps come from the sparse Hessian (`solver.rs`), are cut to no more than a local length per
//! node and backtracked until `F` decreases (a fold makes `F` infinite, so the mesh stays valid).

use std::sync::Arc;

use rayon::ThreadPool;

use super::blocks::BlockMatrix;
use super::cg::{scaled_max_norm, SolveStats, Stop};
use super::global::{Evaluation, GlobalObjective};
use super::problem::Problem;
use super::small_matrix::Vector;
use super::solver::{mask, HessianSolver, Preconditioner, SolverSetup};
use crate::error::{Error, Result};

/// Stopping rules of the Newton stage.
#[derive(Clone, Copy, Debug)]
pub struct StationaryOptions {
    /// Stop when the scaled gradient's max-norm is at most this.
    pub tolerance: f64,
    /// Largest number of Newton iterations.
    pub max_iterations: u32,
    /// Whether the solver returned must be that of the Hessian at the final state (the
    /// sensitivities' operator). Else, where a step is expected to end the minimisation, its
    /// state is evaluated without the Hessian first and, the tolerance met, the solver returned
    /// is that of the state before it: a predictor's operator, off by the last step (a
    /// relative change of about the tolerance), for a fraction of an evaluation's cost.
    pub exact_solver: bool,
}

/// What the Newton stage did.
#[derive(Clone, Copy, Debug, Default)]
pub struct StationaryStats {
    /// Newton iterations performed.
    pub iterations: u32,
    /// Scaled max-norm of `∇F` at the end (`+∞` on an invalid mesh).
    pub gradient_norm: f64,
    /// Whether `gradient_norm ≤ tolerance`.
    pub converged: bool,
}

/// Scaled max-norm of a gradient over the free coordinates.
pub fn scaled_gradient_norm<const D: usize>(
    objective: &GlobalObjective<'_, D>,
    free: &[u8],
    gradient: &[Vector<D>],
) -> f64 {
    scaled_max_norm(&node_scales(objective, free), Some(free), gradient)
}

/// Per node, the scale of its gradient in the scaled norm: its local length over its cells'
/// weights (0 for a node with no free component).
fn node_scales<const D: usize>(objective: &GlobalObjective<'_, D>, free: &[u8]) -> Vec<f64> {
    let length = |v: usize| objective.problem().node_length(v);
    (0..free.len())
        .map(|v| match free[v] {
            0 => 0.0,
            _ => length(v) / objective.node_weight(v),
        })
        .collect()
}

/// Whether Newton's quadratic term no longer stands in the way of ending at `tolerance` in one
/// step from a scaled gradient norm `gradient_norm` (then the step's solve decides).
fn quadratic_negligible(gradient_norm: f64, tolerance: f64) -> bool {
    gradient_norm * gradient_norm <= tolerance
}

/// The share of the tolerance a step expected to be the last leaves to its solve's residual
/// (in the scaled max-norm; the rest to the quadratic term).
const RESIDUAL_SHARE: f64 = 0.5;

/// Largest move of a node in one Newton step, in local lengths (the line search backtracks from
/// there where a cell would fold).
const NODE_STEP: f64 = 4.0;

/// What a minimisation takes from the solver of a nearby state.
pub struct Lagged<const D: usize> {
    /// Used while it pays.
    pub preconditioner: Arc<Preconditioner<D>>,
    /// A Hessian done with, whose storage the first evaluation writes into.
    pub storage: Option<BlockMatrix<D>>,
}

impl<const D: usize> Lagged<D> {
    /// A nearby state's preconditioner, shared.
    pub fn shared(preconditioner: &Arc<Preconditioner<D>>) -> Self {
        Lagged {
            preconditioner: preconditioner.clone(),
            storage: None,
        }
    }

    /// A nearby state's solver, done with: its preconditioner and its Hessian's storage.
    pub fn retired(solver: HessianSolver<D>) -> Self {
        let (hessian, preconditioner) = solver.into_parts();
        Lagged {
            preconditioner,
            storage: Some(hessian),
        }
    }

    /// The preconditioner and the storage, each as an option.
    fn into_parts(self) -> (Option<Arc<Preconditioner<D>>>, Option<BlockMatrix<D>>) {
        (Some(self.preconditioner), self.storage)
    }
}

/// The solver of the Hessian at `x` with `preconditioner` (made for that Hessian, or from a
/// nearby state); `None` where `x` is not a valid state.
pub fn solver_at<const D: usize>(
    pool: &ThreadPool,
    problem: &Problem<D>,
    setup: &Arc<SolverSetup>,
    x: &[Vector<D>],
    preconditioner: Arc<Preconditioner<D>>,
) -> Result<Option<HessianSolver<D>>> {
    let objective = GlobalObjective::new(problem, setup.layout(), None, 0.0);
    let eval = objective.evaluate(pool, x, true)?;
    let hessian = eval.hessian.filter(|_| eval.value.is_finite());
    Ok(hessian.map(|h| HessianSolver::new(setup.clone(), h, preconditioner)))
}

/// Minimises `F` over the free coordinates of `x` (a valid state). `lagged`, when given, comes
/// from a nearby state: its preconditioner is used while it pays. Returns the stats and the
/// solver of the Hessian at the final `x` (when one could be made; see
/// [`StationaryOptions::exact_solver`]): the sensitivities' operator where the tolerance was met,
/// the predictor of path following. `progress(iterations)` may cancel.
pub fn minimise<const D: usize>(
    pool: &ThreadPool,
    problem: &Problem<D>,
    setup: &Arc<SolverSetup>,
    x: &mut [Vector<D>],
    options: &StationaryOptions,
    lagged: Option<Lagged<D>>,
    progress: &mut dyn FnMut(usize) -> bool,
) -> Result<(StationaryStats, Option<HessianSolver<D>>)> {
    let objective = GlobalObjective::new(problem, setup.layout(), None, 0.0);
    let free = &setup.free[..];
    let newton = Newton::new((pool, problem), &objective, setup, options.tolerance);
    let mut stats = StationaryStats {
        gradient_norm: f64::INFINITY,
        ..Default::default()
    };
    // A nearby state's preconditioner; the last solver's Hessian for the next evaluation.
    let (mut preconditioner, mut spare) = lagged.map_or((None, None), Lagged::into_parts);
    let mut eval = objective.evaluate_into(pool, x, true, &mut spare)?;
    crate::diagnostics::note(|| format!("newton: F {} and its Hessian evaluated", eval.value));
    if !eval.value.is_finite() {
        return Ok((stats, None));
    }
    loop {
        stats.gradient_norm = newton.gradient_norm(&eval.gradient);
        let hessian = eval.hessian.take().expect("Hessian evaluated");
        let lagged = preconditioner.is_some();
        let Some(mut solver) = newton.solver_for(x, hessian, preconditioner.take())? else {
            return Ok((stats, None));
        };
        stats.converged = stats.gradient_norm <= options.tolerance;
        if stats.converged || stats.iterations >= options.max_iterations {
            return Ok((stats, Some(solver)));
        }
        if !progress(stats.iterations as usize) {
            return Err(Error::cancelled());
        }
        stats.iterations += 1;
        let Some((step, solved)) =
            newton.step(x, &mut solver, &eval.gradient, stats.gradient_norm, lagged)?
        else {
            return Ok((stats, Some(solver)));
        };
        trace(&stats, eval.value, &solved, lagged);
        let search = Search::after(options, stats.gradient_norm, &solved);
        // Where the step's state is evaluated with its Hessian, that evaluation writes into the
        // solver's storage (one Hessian at a time; the wing's: 0.27 GB); else the solver is kept.
        let kept = match search.hessian {
            true => retire(solver, &mut spare, &mut preconditioner),
            false => Some(solver),
        };
        let found = line_search(
            pool,
            &objective,
            free,
            x,
            (&eval, &mut spare),
            &step,
            search,
        )?;
        let Some((next, next_eval)) = found else {
            return Ok((stats, kept)); // No descent: short of the tolerance.
        };
        x.copy_from_slice(&next);
        eval = next_eval;
        if let Some(solver) = kept {
            let norm = newton.gradient_norm(&eval.gradient);
            if norm <= options.tolerance {
                (stats.gradient_norm, stats.converged) = (norm, true);
                return Ok((stats, Some(solver)));
            }
            retire(solver, &mut spare, &mut preconditioner);
            eval = objective.evaluate_into(pool, x, true, &mut spare)?;
        }
    }
}

/// The solver done with: its Hessian's storage becomes `spare`, for the next evaluation to write
/// into, and its preconditioner the next solves'. Returns no solver (a minimisation that then
/// stops short of its tolerance returns none: its state predicts nothing).
fn retire<const D: usize>(
    solver: HessianSolver<D>,
    spare: &mut Option<BlockMatrix<D>>,
    preconditioner: &mut Option<Arc<Preconditioner<D>>>,
) -> Option<HessianSolver<D>> {
    (*preconditioner, *spare) = Lagged::retired(solver).into_parts();
    None
}

/// A diagnostic line per Newton iteration ([`crate::diagnostics`]).
fn trace(stats: &StationaryStats, value: f64, solved: &SolveStats, lagged: bool) {
    crate::diagnostics::note(|| {
        format!(
            "newton {} g {:e} F {value} solve {solved:?} lagged {lagged}",
            stats.iterations, stats.gradient_norm
        )
    });
}

/// What the iterations of [`minimise`] share.
struct Newton<'a, const D: usize> {
    pool: &'a ThreadPool,
    problem: &'a Problem<D>,
    setup: &'a Arc<SolverSetup>,
    /// The scaled-gradient tolerance of the stage.
    tolerance: f64,
    /// Per node, the scale of its gradient in the scaled norm (0 for a node with no free
    /// component).
    scales: Vec<f64>,
}

impl<'a, const D: usize> Newton<'a, D> {
    /// The iterations' shared state for the minimisation of `objective`.
    fn new(
        (pool, problem): (&'a ThreadPool, &'a Problem<D>),
        objective: &GlobalObjective<'_, D>,
        setup: &'a Arc<SolverSetup>,
        tolerance: f64,
    ) -> Self {
        Newton {
            pool,
            problem,
            setup,
            tolerance,
            scales: node_scales(objective, &setup.free),
        }
    }

    /// The scaled max-norm of `gradient` over the free coordinates.
    fn gradient_norm(&self, gradient: &[Vector<D>]) -> f64 {
        scaled_max_norm(&self.scales, Some(&self.setup.free), gradient)
    }

    /// The solver of `hessian` (at `x`) with `preconditioner` from an earlier state, or with
    /// one made from it when none is given; `None` where none can be made.
    fn solver_for(
        &self,
        x: &[Vector<D>],
        hessian: BlockMatrix<D>,
        preconditioner: Option<Arc<Preconditioner<D>>>,
    ) -> Result<Option<HessianSolver<D>>> {
        match preconditioner {
            Some(p) => Ok(Some(HessianSolver::new(self.setup.clone(), hessian, p))),
            None => HessianSolver::fresh(self.pool, self.problem, self.setup, hessian, (x, 0)),
        }
    }

    /// The Newton step at `x` for the `gradient` (scaled max-norm `gradient_norm`), and the
    /// stats of its solve: inexact, the inner tolerance shrinking with the gradient. A `lagged`
    /// preconditioner that stopped paying is replaced in `solver` by a fresh one (`None`, the
    /// solver unchanged, where none can be made).
    fn step(
        &self,
        x: &[Vector<D>],
        solver: &mut HessianSolver<D>,
        gradient: &[Vector<D>],
        gradient_norm: f64,
        lagged: bool,
    ) -> Result<Option<(Vec<Vector<D>>, SolveStats)>> {
        let minus_g: Vec<Vector<D>> = gradient.iter().map(|g| g.map(|v| -v)).collect();
        // Inexact Newton: the inner tolerance shrinks with the gradient (superlinear rate); where
        // the quadratic term no longer stands in the way, tight enough to end in this step.
        // There the solve also stops once the gradient it leaves (its residual, to first order)
        // is within its share of the tolerance in the scaled norm: the relative residual, a
        // 2-norm, bounds that only loosely (the wing's last step: 16 CG iterations to the
        // relative residual, 13 to the scaled share, the same final gradient).
        let mut inner = gradient_norm.sqrt();
        let last = quadratic_negligible(gradient_norm, self.tolerance);
        if last {
            inner = inner.min(0.1 * self.tolerance / gradient_norm);
        }
        let stop = Stop {
            relative: inner.clamp(1e-14, 0.1),
            scales: if last { &self.scales } else { &[] },
            scaled: RESIDUAL_SHARE * self.tolerance,
        };
        // A preconditioner from an earlier state gets its own budget of iterations
        // ([`Preconditioner::lagged_iterations`]); CG gives up sooner where its rate shows
        // `stop` out of reach within them.
        let budget = solver.preconditioner().lagged_iterations();
        let (mut step, mut solved) = solver.solve_with(self.pool, &minus_g, stop, budget);
        let mut stale = lagged;
        if lagged && (!stop.met(&solved) || solved.negative_curvature) {
            // The earlier preconditioner stopped paying: make one from this Hessian. Where CG
            // met negative curvature, this Hessian is indefinite: its factor's shifts start from
            // the one the earlier state's needed (none tried below it).
            let first = match solved.negative_curvature {
                true => solver.preconditioner().next_shift(),
                false => 0,
            };
            if !solver.refresh(self.pool, self.problem, (x, first))? {
                return Ok(None);
            }
            (step, solved) = solver.solve(self.pool, &minus_g, stop);
            stale = false;
        }
        // A factor modified for an earlier, indefinite Hessian says nothing of this one: where
        // CG met no negative curvature of this Hessian its step (a descent direction) is kept.
        // Taking the stale factor's step instead made Newton a fixed-metric gradient descent
        // (a tangled 200-cell Q4 grid: 100 iterations, the gradient falling 4% each; the
        // true Newton steps converge in 7).
        let indefinite = match stale {
            true => solved.negative_curvature,
            false => solver.preconditioner().modified(),
        };
        if indefinite || solved.iterations == 0 {
            // An indefinite Hessian: the step of its modified factor (modified Newton), or the
            // preconditioned gradient, is a descent direction.
            step = solver.precondition(self.pool, &minus_g);
        }
        Ok(Some((step, solved)))
    }
}

/// What a line search starts from besides the state: the scaled gradient norm there, and
/// whether the full step's state is evaluated with its Hessian (else without, when the step is
/// expected to be the last).
#[derive(Clone, Copy)]
struct Search {
    gradient_norm: f64,
    hessian: bool,
}

impl Search {
    /// The search after a step from a state of scaled gradient norm `gradient_norm`, solved
    /// as `solved`: the full step's state is evaluated without its Hessian where the solver
    /// returned need not be exact and the step is expected to end the minimisation (the
    /// linear model's residual within the tolerance, its quadratic term negligible).
    fn after(options: &StationaryOptions, gradient_norm: f64, solved: &SolveStats) -> Self {
        let tolerance = options.tolerance;
        let last = quadratic_negligible(gradient_norm, tolerance)
            && (solved.residual * gradient_norm <= tolerance
                || solved.scaled <= RESIDUAL_SHARE * tolerance);
        Search {
            gradient_norm,
            hessian: options.exact_solver || !last,
        }
    }
}

/// Backtracks along `step` from `x` until `F` decreases enough (Armijo), or — where the decrease
/// is below `F`'s round-off — until the scaled gradient decreases. The step is first cut so that
/// no node moves more than a few local lengths.
/// Refused where a Hessian's storage cannot be allocated.
fn line_search<const D: usize>(
    pool: &ThreadPool,
    objective: &GlobalObjective<'_, D>,
    free: &[u8],
    x: &[Vector<D>],
    (eval, spare): (&Evaluation<D>, &mut Option<BlockMatrix<D>>),
    step: &[Vector<D>],
    search: Search,
) -> Result<Option<(Vec<Vector<D>>, Evaluation<D>)>> {
    let gradient_norm = search.gradient_norm;
    let step = mask(free, step);
    let slope: f64 = eval
        .gradient
        .iter()
        .zip(&step)
        .map(|(g, p)| (0..D).map(|k| g[k] * p[k]).sum::<f64>())
        .sum();
    if slope.is_nan() || slope >= 0.0 {
        return Ok(None);
    }
    let problem = objective.problem();
    let mut alpha = 1.0f64;
    for (v, p) in step.iter().enumerate() {
        let length = (0..D).map(|k| p[k] * p[k]).sum::<f64>().sqrt();
        let limit = NODE_STEP * problem.node_length(v);
        if length > limit && limit > 0.0 {
            alpha = alpha.min(limit / length);
        }
    }
    let round_off = 16.0 * f64::EPSILON * eval.value.abs();
    for tries in 0..40 {
        let trial: Vec<Vector<D>> = x
            .iter()
            .zip(&step)
            .map(|(x, p)| std::array::from_fn(|k| x[k] + alpha * p[k]))
            .collect();
        // The first trial, which a Newton step near the optimum passes, is evaluated with its
        // derivatives at once; the backtracking ones by value only, their derivatives when kept.
        let mut full = match tries {
            0 => Some(objective.evaluate_into(pool, &trial, search.hessian, spare)?),
            _ => None,
        };
        let value = match &full {
            Some(e) => e.value,
            None => objective.value(pool, &trial),
        };
        crate::diagnostics::note(|| {
            format!(
                "  alpha {alpha:e} value {value} (F {} slope {slope:e})",
                eval.value
            )
        });
        if value.is_finite() {
            let mut derivatives = || match full.take() {
                Some(e) => Ok(e),
                None => objective.evaluate_into(pool, &trial, true, spare),
            };
            if value <= eval.value + 1e-4 * alpha * slope {
                let next = derivatives()?;
                return Ok(Some((trial, next)));
            }
            if value - eval.value <= round_off {
                let next = derivatives()?;
                if scaled_gradient_norm(objective, free, &next.gradient) < gradient_norm {
                    return Ok(Some((trial, next)));
                }
            }
        }
        // A rejected full step's Hessian storage serves the next evaluation.
        if let Some(rejected) = full.and_then(|e| e.hessian) {
            *spare = Some(rejected);
        }
        alpha *= 0.5;
    }
    Ok(None)
}
