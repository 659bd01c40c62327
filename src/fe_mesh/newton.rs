//! The Newton stages of relocation: path following of the optimum from a stationary state (the
//! reference shape, or the last relocation for `Placement::Incremental`), and the stage that
//! polishes the result of the sweeps.

use std::sync::Arc;

use rayon::ThreadPool;

use super::relocate::{Placement, RelocateOptions, RelocateReport, Stage};
use super::{lift, project, Mesh, Solver, State};
use crate::error::Result;
use crate::optimize::blocks::BlockLayout;
use crate::optimize::global::GlobalObjective;
use crate::optimize::path::{self, PathStart};
use crate::optimize::small_matrix::Vector;
use crate::optimize::solver::{HessianSolver, Preconditioner, SolverSetup};
use crate::optimize::stationary::{self, StationaryOptions};
use crate::optimize::{invalid_cells, Problem};

/// Largest number of iterations of the Newton stage after the sweeps.
const MAX_NEWTON_ITERATIONS: u32 = 100;

/// Tolerance of the correction of a start state that is not yet stationary.
const START_TOLERANCE: f64 = 1e-6;

/// A relocated state with its solver, and whether its sensitivities are valid (else why not).
pub(super) type Relocated<const D: usize> = (
    Vec<Vector<D>>,
    Option<Solver>,
    std::result::Result<(), String>,
);

impl Mesh {
    /// The layout of the Hessian, built once per mesh.
    fn layout_for<const D: usize>(
        &mut self,
        pool: &ThreadPool,
        problem: &Problem<D>,
    ) -> Arc<BlockLayout> {
        self.layout
            .get_or_insert_with(|| {
                let layout = BlockLayout::new(pool, problem);
                let blocks = layout.block_count();
                crate::diagnostics::note(|| format!("Hessian layout: {blocks} node blocks"));
                Arc::new(layout)
            })
            .clone()
    }

    /// The solvers' setup for the current constraints, built once per set of constraints.
    pub(super) fn setup_for<const D: usize>(
        &mut self,
        pool: &ThreadPool,
        problem: &Problem<D>,
    ) -> Result<Arc<SolverSetup>> {
        if self.setup.is_none() {
            let layout = self.layout_for(pool, problem);
            self.setup = Some(Arc::new(SolverSetup::new(problem, layout)?));
        }
        Ok(self.setup.clone().expect("setup"))
    }

    /// Follows the optimum from a stationary state to the prescribed coordinates of `goal`.
    /// `None` when that is not possible (an invalid start, a step that cannot be made): the
    /// caller then falls back to the sweeps.
    pub(super) fn follow_path<const D: usize>(
        &mut self,
        pool: &ThreadPool,
        problem: &Problem<D>,
        goal: &[Vector<D>],
        options: &RelocateOptions,
        report: &mut RelocateReport,
        progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
    ) -> Result<Option<Relocated<D>>> {
        let setup = self.setup_for(pool, problem)?;
        if !progress(Stage::Placement, 0, 1) {
            return Err(crate::error::Error::cancelled());
        }
        let Some(start) = self.path_start(pool, problem, &setup, options, report)? else {
            return Ok(None);
        };
        let done = report.newton_iterations as usize;
        let outcome = path::follow(
            pool,
            problem,
            &setup,
            start,
            path::Goal {
                positions: goal,
                tolerance: options.newton_tolerance(),
                exact_solver: options.stationarity_tolerance > 0.0,
            },
            &mut |i| progress(Stage::Stationarity, done + i, 0),
        )?;
        report.newton_iterations += outcome.newton_iterations;
        report.invalid_after_placement = outcome.first_invalid;
        if !(outcome.reached >= 1.0 && outcome.converged) {
            return Ok(None);
        }
        report.steps = outcome.steps;
        report.gradient_norm = outcome.gradient_norm;
        report.converged = true;
        let sensitivity = match options.stationarity_tolerance > 0.0 {
            true => Ok(()),
            false => Err(NOT_ASKED.to_string()),
        };
        let solver = outcome.solver.map(|s| s as Solver);
        Ok(Some((outcome.x, solver, sensitivity)))
    }

    /// Where path following starts: the last relocated state (`Incremental`) or the optimum at
    /// the reference shape's prescribed coordinates, corrected to stationarity where it is not;
    /// `None` if that state is invalid.
    fn path_start<const D: usize>(
        &mut self,
        pool: &ThreadPool,
        problem: &Problem<D>,
        setup: &Arc<SolverSetup>,
        options: &RelocateOptions,
        report: &mut RelocateReport,
    ) -> Result<Option<PathStart<D>>> {
        let from_last = options.placement == Placement::Incremental && self.last.is_some();
        let stored = match from_last {
            true => self.last.clone(),
            false => self
                .reference_state
                .as_ref()
                .filter(|(target, _)| *target == options.target)
                .map(|(_, state)| state.clone()),
        };
        let state = stored.unwrap_or(State {
            positions: self.reference.clone(),
            solver: None,
            stationary: false,
            threads: options.threads,
        });
        let mut x = project::<D>(&state.positions, self.unit());
        let stored_solver = match state.solver.clone().filter(|_| state.stationary) {
            Some(s) => restore(pool, problem, setup, &x, s)?,
            None => None,
        };
        let solver = match stored_solver {
            Some(solver) => solver,
            None => {
                if !invalid_cells(pool, problem, &x).is_empty() {
                    return Ok(None);
                }
                let start_options = StationaryOptions {
                    tolerance: START_TOLERANCE.min(options.newton_tolerance()),
                    max_iterations: MAX_NEWTON_ITERATIONS,
                    // The start's solver predicts the first step: it need not be exact.
                    exact_solver: false,
                };
                let (stats, solver) = stationary::minimise(
                    pool,
                    problem,
                    setup,
                    &mut x,
                    &start_options,
                    None,
                    &mut |_| true,
                )?;
                report.newton_iterations += stats.iterations;
                let Some(solver) = solver.filter(|_| stats.converged) else {
                    return Ok(None);
                };
                let solver = Arc::new(solver);
                if !from_last {
                    let positions = lift(&self.reference, &x, self.unit(), &self.fixed);
                    // A factor's Hessian is kept with it; a multigrid's is not (a solid's
                    // Hessian is the relocation's largest array: the wing's 0.27 GB) and is
                    // evaluated again at the next cold start.
                    let kept = match setup.is_direct() {
                        true => solver.clone() as Solver,
                        false => solver.preconditioner().clone() as Solver,
                    };
                    let state = State {
                        positions,
                        solver: Some(kept),
                        stationary: true,
                        threads: options.threads,
                    };
                    self.reference_state = Some((options.target, state));
                }
                solver
            }
        };
        Ok(Some(PathStart { x, solver }))
    }

    /// After the sweeps: the Newton stage when asked for (else the gradient norm only), on a
    /// valid state `x`. Returns the solver at the end and whether sensitivities are valid.
    pub(super) fn stationary_stage<const D: usize>(
        &mut self,
        pool: &ThreadPool,
        problem: &Problem<D>,
        x: &mut [Vector<D>],
        options: &RelocateOptions,
        report: &mut RelocateReport,
        progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
    ) -> Result<(Option<Solver>, std::result::Result<(), String>)> {
        if !options.optimize {
            return Ok((None, Err("the last relocation did not optimize".into())));
        }
        let invalid = invalid_cells(pool, problem, x).len();
        if invalid > 0 {
            let why = format!("the last relocation left {invalid} invalid cells");
            return Ok((None, Err(why)));
        }
        let layout = self.layout_for(pool, problem);
        if options.stationarity_tolerance <= 0.0 {
            let objective = GlobalObjective::new(problem, &layout, None, 0.0);
            let free = SolverSetup::free_mask(problem);
            let eval = objective.evaluate(pool, x, false)?;
            report.gradient_norm =
                stationary::scaled_gradient_norm(&objective, &free, &eval.gradient);
            return Ok((None, Err(NOT_ASKED.into())));
        }
        let setup = self.setup_for(pool, problem)?;
        let stationary_options = StationaryOptions {
            tolerance: options.stationarity_tolerance,
            max_iterations: MAX_NEWTON_ITERATIONS,
            exact_solver: true,
        };
        let done = report.newton_iterations as usize;
        let (stats, solver) = stationary::minimise(
            pool,
            problem,
            &setup,
            x,
            &stationary_options,
            None,
            &mut |i| progress(Stage::Stationarity, done + i, 0),
        )?;
        report.gradient_norm = stats.gradient_norm;
        report.newton_iterations += stats.iterations;
        report.converged &= stats.converged;
        let sensitivity = match &solver {
            Some(_) if stats.converged => Ok(()),
            _ => Err(format!(
                "the last relocation stopped at a scaled gradient norm of {:.1e}, above its \
                 stationarity tolerance {:.1e}",
                stats.gradient_norm, options.stationarity_tolerance
            )),
        };
        Ok((solver.map(|s| Arc::new(s) as Solver), sensitivity))
    }
}

/// The solver a stored state kept at `x`: the solver itself, or one made again from the
/// Hessian evaluated there with the preconditioner it kept.
fn restore<const D: usize>(
    pool: &ThreadPool,
    problem: &Problem<D>,
    setup: &Arc<SolverSetup>,
    x: &[Vector<D>],
    stored: Solver,
) -> Result<Option<Arc<HessianSolver<D>>>> {
    match stored.downcast::<HessianSolver<D>>() {
        Ok(solver) => Ok(Some(solver)),
        Err(stored) => match stored.downcast::<Preconditioner<D>>() {
            Ok(p) => Ok(stationary::solver_at(pool, problem, setup, x, p)?.map(Arc::new)),
            Err(_) => Ok(None),
        },
    }
}

/// Why a relocation without a stationarity tolerance has no sensitivities.
const NOT_ASKED: &str =
    "the last relocation did not ask for a stationary point (stationarity_tolerance = 0)";
