//! Relocation of the free nodes of a [`Mesh`]: harmonic first placement, then the optimizer.

use std::time::Instant;

use super::{project, Mesh};
use crate::error::{Error, ErrorKind, Result};
use crate::optimize::{
    invalid_cells, laplace::MeshGraph, optimize, small::Vector, NodeSolverOptions, Problem,
    SweepOptions, TargetKind,
};

/// Where the free nodes start before the optimizer runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Placement {
    /// Harmonic extension of the prescribed displacements (discrete Laplace equation).
    Laplacian,
    /// The current positions, as they are.
    Current,
}

/// Stages reported to a progress callback.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// First placement of the free nodes.
    Placement,
    /// Optimization sweeps.
    Optimization,
}

/// Options of [`Mesh::relocate`].
#[derive(Clone, Copy, Debug)]
pub struct RelocateOptions {
    /// The ideal shape of each cell.
    pub target: TargetKind,
    /// The first placement of the free nodes.
    pub placement: Placement,
    /// Run the optimizer after the placement (false: placement only).
    pub optimize: bool,
    /// Largest number of Gauss–Seidel sweeps.
    pub max_sweeps: u32,
    /// Stop when the mesh is valid and no node moved more than this fraction of its local size.
    pub move_tolerance: f64,
    /// Per-node Newton stops when the gradient times the local size is below this. Every node
    /// is revisited by the following sweeps, so an inexact solve (10⁻³, the default) reaches the
    /// same meshes in less time than the tight 6·10⁻⁶ of a one-pass optimizer.
    pub gradient_tolerance: f64,
    /// Largest number of Newton iterations per node and sweep.
    pub max_newton_iterations: u32,
    /// Over-relaxation of each node's move, in [1, 2): speeds up smoothing; a relaxed move is
    /// kept only if it lowers the node's objective and inverts nothing.
    pub relaxation: f64,
    /// Worker threads; 0 uses one per core. The result does not depend on it.
    pub threads: usize,
}

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
        }
    }
}

impl RelocateOptions {
    fn validate(&self) -> Result<()> {
        let values = [
            ("move_tolerance", self.move_tolerance),
            ("gradient_tolerance", self.gradient_tolerance),
            ("relaxation", self.relaxation),
        ];
        if let Some((name, v)) = values.iter().find(|(_, v)| !v.is_finite()) {
            return Err(Error::new(
                ErrorKind::NotFinite,
                format!("{name} = {v} must be finite"),
            ));
        }
        if let Some((name, v)) = values[..2].iter().find(|(_, v)| *v < 0.0) {
            return Err(Error::invalid(format!("{name} = {v} must be non-negative")));
        }
        if !(1.0..2.0).contains(&self.relaxation) {
            return Err(Error::invalid(format!(
                "relaxation = {} is not in [1, 2)",
                self.relaxation
            )));
        }
        if self.threads > 4096 {
            return Err(Error::invalid(format!(
                "threads = {} is more than 4096",
                self.threads
            )));
        }
        Ok(())
    }
}

/// What [`Mesh::relocate`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RelocateReport {
    /// Number of cells.
    pub cells: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Nodes with at least one free component.
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
    /// Steps the prescribed motion was applied in.
    pub steps: u32,
    /// Whether the sweeps met their stopping rule (valid mesh, small moves).
    pub converged: bool,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl Mesh {
    /// Relocates the free components of the nodes (see [`Mesh::set_fixed`]) so that every cell is
    /// valid and close to its target shape. `progress(stage, done, total)` is called as work
    /// proceeds; returning `false` cancels. On error or cancellation the mesh is unchanged.
    pub fn relocate(
        &mut self,
        options: &RelocateOptions,
        progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
    ) -> Result<RelocateReport> {
        options.validate()?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(options.threads)
            .build()
            .map_err(|e| {
                Error::invalid(format!("cannot start {} threads: {e}", options.threads))
            })?;
        match self.dimension() {
            2 => self.relocate_d::<2>(&pool, options, progress),
            _ => self.relocate_d::<3>(&pool, options, progress),
        }
    }

    fn relocate_d<const D: usize>(
        &mut self,
        pool: &rayon::ThreadPool,
        options: &RelocateOptions,
        progress: &mut dyn FnMut(Stage, usize, usize) -> bool,
    ) -> Result<RelocateReport> {
        let start = Instant::now();
        let problem = self.problem::<D>(options.target)?;
        let reference = project::<D>(&self.reference);
        let goal = project::<D>(&self.positions);
        let mut report = RelocateReport {
            cells: self.cell_count(),
            nodes: self.node_count(),
            free_nodes: (0..self.node_count())
                .filter(|&v| problem.free_mask(v) != 0)
                .count(),
            invalid_before: invalid_cells(pool, &problem, &goal).len(),
            ..Default::default()
        };
        if !progress(Stage::Placement, 0, 1) {
            return Err(cancelled());
        }
        let mut x = goal.clone();
        let graph = MeshGraph::new(&problem);
        let place = |from: &[Vector<D>], x: &mut [Vector<D>]| {
            pool.install(|| graph.harmonic_placement(&problem, from, x));
        };
        if options.placement == Placement::Laplacian {
            place(&reference, &mut x);
        }
        report.invalid_after_placement = invalid_cells(pool, &problem, &x).len();
        if !progress(Stage::Placement, 1, 1) {
            return Err(cancelled());
        }
        if options.optimize {
            let sweep_options = SweepOptions {
                max_sweeps: options.max_sweeps,
                move_tolerance: options.move_tolerance,
                node: NodeSolverOptions {
                    gradient_tolerance: options.gradient_tolerance,
                    max_iterations: options.max_newton_iterations,
                    relaxation: options.relaxation,
                },
            };
            let mut run = |x: &mut Vec<Vector<D>>, sweeps_done: u32, last: bool| {
                let mut step_options = sweep_options;
                if !last {
                    step_options.move_tolerance *= INTERMEDIATE_TOLERANCE_FACTOR;
                }
                let stats = optimize(pool, &problem, x, &step_options, &mut |done, _| {
                    progress(Stage::Optimization, sweeps_done as usize + done, 0)
                })?;
                Ok::<_, Error>((stats, invalid_cells(pool, &problem, x).is_empty()))
            };
            if options.placement == Placement::Current {
                let (stats, _) = run(&mut x, 0, true)?;
                report.sweeps = stats.sweeps;
                report.converged = stats.converged;
            } else {
                // Large motions are applied in steps, each placed harmonically from the previous
                // optimized state and optimized; a step that leaves invalid cells is halved.
                let mut done_t = 0.0;
                let mut state = reference.clone();
                let first_dt = 1.0 / initial_steps(&problem, &reference, &goal) as f64;
                let mut dt = first_dt;
                while done_t < 1.0 {
                    let t = (done_t + dt).min(1.0);
                    let mut trial = state.clone();
                    set_fixed_at(&problem, &reference, &goal, t, &mut trial);
                    place(&state, &mut trial);
                    let (stats, valid) = run(&mut trial, report.sweeps, t >= 1.0)?;
                    report.sweeps += stats.sweeps;
                    if !valid && dt > MIN_STEP {
                        dt *= 0.5;
                        continue;
                    }
                    report.converged = stats.converged;
                    report.steps += 1;
                    done_t = t;
                    state = trial;
                    // After a success the step grows back; a failure even at the smallest step
                    // will not be repaired by more small steps, so the rest comes in one.
                    dt = if valid {
                        (2.0 * dt).min(first_dt)
                    } else {
                        1.0 - done_t
                    };
                }
                x = state;
            }
        }
        let quality: Vec<f64> = (0..problem.cell_count())
            .map(|c| problem.cell_quality(c, &x))
            .collect();
        report.invalid_after = invalid_cells(pool, &problem, &x).len();
        report.min_quality = quality.iter().copied().fold(f64::INFINITY, f64::min);
        report.mean_quality = quality.iter().sum::<f64>() / quality.len() as f64;
        for (p, q) in self.positions.iter_mut().zip(&x) {
            p[..D].copy_from_slice(q);
        }
        report.seconds = start.elapsed().as_secs_f64();
        Ok(report)
    }
}

/// Smallest fraction of the motion applied in one step.
const MIN_STEP: f64 = 1.0 / 256.0;

/// Intermediate steps stop at a looser move tolerance: only the last one needs to be smooth.
const INTERMEDIATE_TOLERANCE_FACTOR: f64 = 10.0;

/// Largest prescribed move, in local cell sizes, applied in one step.
const CELLS_PER_STEP: f64 = 4.0;

fn cancelled() -> Error {
    Error::new(ErrorKind::Cancelled, "cancelled by the progress callback")
}

/// Number of steps so that no prescribed node moves more than [`CELLS_PER_STEP`] times the size
/// of its cells in one step.
fn initial_steps<const D: usize>(
    problem: &Problem<D>,
    reference: &[Vector<D>],
    goal: &[Vector<D>],
) -> usize {
    let mut terms = Vec::new();
    let mut ratio = 0.0f64;
    for v in 0..reference.len() {
        if problem.free_mask(v) == (1 << D) - 1 {
            continue;
        }
        let moved = (0..D)
            .map(|k| (goal[v][k] - reference[v][k]).powi(2))
            .sum::<f64>()
            .sqrt();
        if moved == 0.0 {
            continue;
        }
        let (_, length) = problem.node_terms(v, reference, &mut terms);
        if length > 0.0 {
            ratio = ratio.max(moved / (2.0 * length));
        }
    }
    ((ratio / CELLS_PER_STEP).ceil() as usize).clamp(1, (1.0 / MIN_STEP) as usize)
}

/// Puts the constrained components at `reference + t·(goal − reference)`.
fn set_fixed_at<const D: usize>(
    problem: &Problem<D>,
    reference: &[Vector<D>],
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
                    reference[v][k] + t * (goal[v][k] - reference[v][k])
                };
            }
        }
    }
}
