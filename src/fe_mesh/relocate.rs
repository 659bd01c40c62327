//! Relocation of the free nodes of a [`Mesh`]: harmonic first placement, then the optimizer.

use std::time::Instant;

use super::{project, Mesh};
use crate::error::{Error, ErrorKind, Result};
use crate::optimize::motion::{self, Ends};
use crate::optimize::team::{Alone, Team};
use crate::optimize::{
    invalid_cells, laplace::MeshGraph, small_matrix::Vector, NodeSolverOptions, Problem,
    QualitySummary, SweepOptions, TargetKind,
};

/// Where the free nodes start before the optimizer runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Placement {
    /// Harmonic extension of the prescribed displacements (discrete Laplace equation): every
    /// free coordinate starts from its reference position plus that extension, whatever
    /// position [`Mesh::move_nodes`](crate::Mesh::move_nodes) gave it.
    Laplacian,
    /// The current positions, as they are.
    Current,
    /// Warm start: the positions of the last successful relocation plus the harmonic extension
    /// of the prescribed motion since then (a first relocation starts as `Laplacian`). The
    /// targets stay the reference shapes. The placement of a loop that moves the boundary a
    /// little at every step.
    Incremental,
}

/// Stages reported to a progress callback.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// First placement of the free nodes.
    Placement,
    /// Optimization sweeps.
    Optimization,
    /// Newton iterations on the global objective (`RelocateOptions::stationarity_tolerance`).
    Stationarity,
}

/// How the free nodes are carried to the optimum.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// `Newton` where the Hessian's Cholesky factor is small (2D meshes, 3D ones up to about
    /// 20,000 nodes) or, beyond, where the Hessian has at most 10⁸ values (about 310,000 H27
    /// nodes; multigrid-preconditioned steps, about 17 bytes per value at the peak), else
    /// `Sweeps`. Where memory is short, `Sweeps` needs about a quarter (the wing: 0.16 GB
    /// against 0.59 GB).
    Auto,
    /// The per-node optimizer's coloured Gauss–Seidel sweeps, large motions in steps placed
    /// harmonically; with `stationarity_tolerance > 0`, followed by the Newton stage.
    Sweeps,
    /// Path following of the optimum of the global objective: each step predicted by the tangent
    /// of the optimum (the linearised response of the mesh) and corrected by Newton's method;
    /// the sweeps are the fallback where a step cannot be made (e.g. a tangled start). With
    /// [`Placement::Current`] (untangling in place): 3 sweeps (more while cells stay invalid),
    /// then Newton's method to the stationarity tolerance
    /// ([`DEFAULT_NEWTON_TOLERANCE`] when none is asked for). A Hessian, or a multigrid
    /// preconditioner beside it, whose storage cannot be reserved (past an address-space limit,
    /// strict overcommit's commit limit, or the machine's memory and swap) is refused
    /// ([`ErrorKind::LimitExceeded`]).
    Newton,
}

/// Options of [`Mesh::relocate`].
#[derive(Clone, Copy, Debug)]
pub struct RelocateOptions {
    /// The ideal shape of each cell.
    pub target: TargetKind,
    /// The first placement of the free nodes.
    pub placement: Placement,
    /// Whether the optimizer runs after the placement (default: true, non-zero in C); false
    /// (0) stops after the placement.
    pub optimize: bool,
    /// Largest number of Gauss–Seidel sweeps (default 100 per step).
    pub max_sweeps: u32,
    /// Stop when the mesh is valid and no node moved more than this fraction of its local cell
    /// size in a sweep (default 1e-3).
    pub move_tolerance: f64,
    /// A node's Newton iteration stops when the gradient of its objective times its local cell
    /// size is below this (default 1e-3: nodes are revisited by the following sweeps, so an
    /// inexact solve per sweep suffices, and reaches the same meshes in less time than the tight
    /// 6·10⁻⁶ of a one-pass optimizer).
    pub gradient_tolerance: f64,
    /// Largest number of Newton iterations per node and sweep (default 150).
    pub max_newton_iterations: u32,
    /// Over-relaxation of each node's move, in [1, 2) (default 1.8; 1 disables it): speeds up
    /// smoothing. A relaxed move is kept only if it lowers the node's objective and inverts
    /// nothing.
    pub relaxation: f64,
    /// Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per
    /// core. The result does not depend on it.
    pub threads: usize,
    /// When positive, the result is a stationary point of the one global objective F, the sum
    /// over cells of their mean distortion η̄*_c (regularisation δ = 0, so F is infinite at a
    /// fold): the report's
    /// [`gradient_norm`](RelocateReport::gradient_norm) is at most this (e.g. 1e-10), reached by
    /// Newton's method with the sparse Hessian on a valid mesh; the sensitivities
    /// (`igaparam_mesh_adjoint` and `igaparam_mesh_tangent`, [`Mesh::adjoint`] and
    /// [`Mesh::tangent`] in Rust) then differentiate the result. 0 (default): no such guarantee
    /// (the sweeps stop on their own rule, the Newton method at 1e-8,
    /// [`DEFAULT_NEWTON_TOLERANCE`]).
    pub stationarity_tolerance: f64,
    /// How the optimum is reached.
    pub method: Method,
}

/// What a relocation refused for lack of memory (the only limit it has: a Hessian's or a
/// multigrid's storage) can do instead.
const WITHOUT_HESSIAN: &str =
    "the sweeps alone (method SWEEPS, stationarity_tolerance 0) keep no Hessian";

/// Where the Newton method stops when no stationarity tolerance is asked for.
pub const DEFAULT_NEWTON_TOLERANCE: f64 = 1e-8;

impl Default for RelocateOptions {
    fn default() -> Self {
        RelocateOptions {
            target: TargetKind::Reference,
            placement: Placement::Laplacian,
            optimize: true,
            max_sweeps: 100,
            move_tolerance: 1e-3,
            gradient_tolerance: 1e-3,
            max_newton_iterations: 150,
            relaxation: 1.8,
            threads: 0,
            stationarity_tolerance: 0.0,
            method: Method::Auto,
        }
    }
}

impl RelocateOptions {
    /// Checks the values of the options.
    pub(crate) fn validate(&self) -> Result<()> {
        let values = [
            ("move_tolerance", self.move_tolerance),
            ("gradient_tolerance", self.gradient_tolerance),
            ("relaxation", self.relaxation),
            ("stationarity_tolerance", self.stationarity_tolerance),
        ];
        if let Some((name, v)) = values.iter().find(|(_, v)| !v.is_finite()) {
            return Err(Error::new(
                ErrorKind::NotFinite,
                format!("{name} = {v} must be finite"),
            ));
        }
        if let Some((name, v)) = values.iter().find(|(_, v)| *v < 0.0) {
            return Err(Error::invalid(format!("{name} = {v} must be non-negative")));
        }
        if !(1.0..2.0).contains(&self.relaxation) {
            return Err(Error::invalid(format!(
                "relaxation = {} is not in [1, 2)",
                self.relaxation
            )));
        }
        crate::threads::check(self.threads)
    }
}

impl RelocateOptions {
    /// The Newton method's tolerance: the one asked for, or the default.
    pub(crate) fn newton_tolerance(&self) -> f64 {
        match self.stationarity_tolerance > 0.0 {
            true => self.stationarity_tolerance,
            false => DEFAULT_NEWTON_TOLERANCE,
        }
    }

    /// The stopping rules of the sweeps.
    pub(crate) fn sweep_options(&self) -> SweepOptions {
        SweepOptions {
            max_sweeps: self.max_sweeps,
            move_tolerance: self.move_tolerance,
            node: NodeSolverOptions {
                gradient_tolerance: self.gradient_tolerance,
                max_iterations: self.max_newton_iterations,
                relaxation: self.relaxation,
                power: 1.0,
            },
        }
    }
}

/// What [`Mesh::relocate`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RelocateReport {
    /// Number of cells.
    pub cells: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Nodes with at least one free coordinate.
    pub free_nodes: usize,
    /// Cells with `det J ≤ 0` at a Gauss–Lobatto point when the call started.
    pub invalid_before: usize,
    /// Invalid cells after the first placement.
    pub invalid_after_placement: usize,
    /// Invalid cells at the end.
    pub invalid_after: usize,
    /// Smallest cell quality at the end (against the target; 0 for an invalid cell).
    pub min_quality: f64,
    /// Mean cell quality at the end.
    pub mean_quality: f64,
    /// Optimization sweeps performed (over all steps).
    pub sweeps: u32,
    /// Steps the prescribed motion was applied in (large motions are split so that no prescribed
    /// node moves more than about one cell size per step).
    pub steps: u32,
    /// Whether the sweeps met their stopping rule (valid mesh, small moves) and, when asked for,
    /// the Newton stage its `stationarity_tolerance` (1 in C, else 0).
    pub converged: bool,
    /// Scaled max-norm of the gradient of the global objective F at the end: over the free
    /// coordinates, |∂F/∂x| times the node's local cell size divided by its number of cells
    /// (the gradient of the node's own objective times its size; dimensionless). Infinite for
    /// an invalid mesh.
    pub gradient_norm: f64,
    /// Newton iterations of the stationarity stage.
    pub newton_iterations: u32,
    /// Wall-clock seconds of the call.
    pub seconds: f64,
}

impl Mesh {
    /// Relocates the free components of the nodes (see [`Mesh::set_fixed`]) so that every cell is
    /// valid and close to its target shape. `progress(stage, done, total)` is called as work
    /// proceeds; returning `false` cancels. On error or cancellation the mesh is unchanged.
    ///
    /// The optimizer runs on the mesh scaled by a power of two to a size of 1–2 (see
    /// `unit_of` in `fe_mesh`): the result does not depend on the units.
    pub fn relocate(
        &mut self,
        options: &RelocateOptions,
        progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
    ) -> Result<RelocateReport> {
        options.validate()?;
        let pool = crate::threads::pool(options.threads)?;
        crate::diagnostics::note(|| {
            format!(
                "relocation: {} nodes, {} cells, {:?}, {:?}",
                self.node_count(),
                self.cell_count(),
                options.method,
                options.placement
            )
        });
        let report = match self.dimension() {
            2 => self.relocate_d::<2>(&pool, options, progress),
            _ => self.relocate_d::<3>(&pool, options, progress),
        }
        .map_err(|e| e.hinted(ErrorKind::LimitExceeded, WITHOUT_HESSIAN));
        crate::diagnostics::note(|| match &report {
            Ok(r) => format!(
                "relocation: done in {:.3} s, {} sweeps, {} Newton iterations, {} invalid, \
                 min q {:.3}",
                r.seconds, r.sweeps, r.newton_iterations, r.invalid_after, r.min_quality
            ),
            Err(e) => format!("relocation: failed ({e})"),
        });
        report
    }

    fn relocate_d<const D: usize>(
        &mut self,
        pool: &rayon::ThreadPool,
        options: &RelocateOptions,
        progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
    ) -> Result<RelocateReport> {
        let start = Instant::now();
        let kept = self.kept_problem::<D>(options.target)?;
        let problem: &Problem<D> = &kept;
        let unit = self.unit();
        let goal = project::<D>(&self.positions, unit);
        let mut report = RelocateReport {
            cells: self.cell_count(),
            nodes: self.node_count(),
            free_nodes: (0..self.node_count())
                .filter(|&v| problem.free_mask(v) != 0)
                .count(),
            invalid_before: invalid_cells(pool, problem, &goal).len(),
            gradient_norm: f64::INFINITY,
            ..Default::default()
        };
        let newton = options.optimize
            && match options.method {
                Method::Sweeps => false,
                Method::Newton => true,
                Method::Auto => self.setup_for(pool, problem)?.newton_by_default(),
            };
        let followed = match newton && options.placement != Placement::Current {
            true => self.follow_path(pool, problem, &goal, options, &mut report, progress)?,
            false => None,
        };
        let (x, solver, sensitivity) = match followed {
            Some(relocated) => relocated,
            None if newton && options.placement == Placement::Current => {
                // Untangling in place: a few sweeps (more while cells stay invalid, each pass
                // starting where the last ended), then Newton's method converges.
                let mut x = goal.clone();
                let (mut allowed, mut sweeps, placed) = (0, 0, report.invalid_before);
                let mut valid = false;
                while allowed < options.max_sweeps && (allowed == 0 || !valid) {
                    let pass = untangling_pass(options, allowed);
                    x = self.place_and_sweep(pool, problem, &x, &pass, &mut report, progress)?;
                    (allowed, sweeps) = (allowed + pass.max_sweeps, sweeps + report.sweeps);
                    valid = invalid_cells(pool, problem, &x).is_empty();
                }
                (report.sweeps, report.invalid_after_placement) = (sweeps, placed);
                // Converged when the Newton stage below is, on a valid mesh.
                report.converged = valid;
                let newton = RelocateOptions {
                    stationarity_tolerance: options.newton_tolerance(),
                    ..*options
                };
                let (solver, sensitivity) =
                    self.stationary_stage(pool, problem, &mut x, &newton, &mut report, progress)?;
                (x, solver, sensitivity)
            }
            None => {
                let mut x =
                    self.place_and_sweep(pool, problem, &goal, options, &mut report, progress)?;
                let (solver, sensitivity) =
                    self.stationary_stage(pool, problem, &mut x, options, &mut report, progress)?;
                (x, solver, sensitivity)
            }
        };
        let quality = QualitySummary::of(pool, problem, &x);
        report.invalid_after = quality.invalid.len();
        report.min_quality = quality.min;
        report.mean_quality = quality.mean;
        self.positions = super::lift(&self.positions, &x, unit, &self.fixed);
        self.last = Some(super::State {
            positions: self.positions.clone(),
            stationary: report.gradient_norm
                <= options.stationarity_tolerance.max(DEFAULT_NEWTON_TOLERANCE),
            solver,
            threads: options.threads,
        });
        self.sensitivity = sensitivity;
        report.seconds = start.elapsed().as_secs_f64();
        Ok(report)
    }

    /// The first placement and the sweeps (following the motion in steps where it is large).
    fn place_and_sweep<const D: usize>(
        &self,
        pool: &rayon::ThreadPool,
        problem: &Problem<D>,
        goal: &[Vector<D>],
        options: &RelocateOptions,
        report: &mut RelocateReport,
        progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
    ) -> Result<Vec<Vector<D>>> {
        if !progress(Stage::Placement, 0, 1) {
            return Err(Error::cancelled());
        }
        // Where the motion starts: the reference shape, or the last relocated state.
        let from = match (options.placement, &self.last) {
            (Placement::Incremental, Some(last)) => project::<D>(&last.positions, self.unit()),
            _ => project::<D>(&self.reference, self.unit()),
        };
        let mut x = goal.to_vec();
        let graph = MeshGraph::new(problem);
        if options.placement != Placement::Current {
            pool.install(|| graph.harmonic_placement(problem, &from, &mut x));
        }
        report.invalid_after_placement = invalid_cells(pool, problem, &x).len();
        if !progress(Stage::Placement, 1, 1) {
            return Err(Error::cancelled());
        }
        if !options.optimize {
            return Ok(x);
        }
        let ends = Ends { start: &from, goal };
        sweep_motion(
            &mut Alone, pool, problem, &graph, ends, &mut x, options, report, progress,
        )?;
        Ok(x)
    }
}

/// Sweeps that untangle a start in place before Newton's method takes over: a tangled 200-cell
/// Q4 grid (`cargo bench --bench small`) then takes 3 sweeps and 8 Newton iterations, 11-12 ms
/// on one thread, where the sweeps alone take 29 sweeps, 16-17 ms.
const UNTANGLING_SWEEPS: u32 = 3;

/// The options of a pass of untangling sweeps in place after `done` sweeps: at most
/// [`UNTANGLING_SWEEPS`], within `max_sweeps`; the sweeps' own rule (valid and small moves) is
/// not awaited, Newton's method converging faster.
fn untangling_pass(options: &RelocateOptions, done: u32) -> RelocateOptions {
    RelocateOptions {
        max_sweeps: UNTANGLING_SWEEPS.min(options.max_sweeps - done),
        ..*options
    }
}

/// The sweeps after the first placement `x` (in place, or following the motion from
/// `ends.start` to `ends.goal`), on the ranks of `team`; fills the report's sweep figures.
#[allow(clippy::too_many_arguments)]
pub(crate) fn sweep_motion<const D: usize, T: Team>(
    team: &mut T,
    pool: &rayon::ThreadPool,
    problem: &Problem<D>,
    graph: &MeshGraph,
    ends: Ends<'_, D>,
    x: &mut Vec<Vector<D>>,
    options: &RelocateOptions,
    report: &mut RelocateReport,
    progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
) -> Result<()> {
    let sweep_options = options.sweep_options();
    let mut on_sweep = |done: usize| progress(Stage::Optimization, done, 0);
    let stats = if options.placement == Placement::Current {
        motion::optimize_in_place_on(team, pool, problem, x, &sweep_options, &mut on_sweep)?
    } else {
        let (moved, stats) = motion::follow_motion_on(
            team,
            pool,
            problem,
            graph,
            ends,
            &sweep_options,
            &mut on_sweep,
        )?;
        *x = moved;
        stats
    };
    report.sweeps = stats.sweeps;
    report.steps = stats.steps;
    report.converged = stats.converged;
    Ok(())
}
