//! Relocation of the free nodes of a [`Mesh`]: harmonic first placement, then the optimizer.

use std::time::Instant;

use super::{project, Mesh};
use crate::error::{Error, ErrorKind, Result};
use crate::optimize::{
    invalid_cells, laplace::MeshGraph, motion, small::Vector, NodeSolverOptions, QualitySummary,
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
            return Err(Error::cancelled());
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
            return Err(Error::cancelled());
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
            let mut on_sweep = |done: usize| progress(Stage::Optimization, done, 0);
            let stats = if options.placement == Placement::Current {
                motion::optimize_in_place(pool, &problem, &mut x, &sweep_options, &mut on_sweep)?
            } else {
                let (moved, stats) = motion::follow_motion(
                    pool,
                    &problem,
                    &graph,
                    &reference,
                    &goal,
                    &sweep_options,
                    &mut on_sweep,
                )?;
                x = moved;
                stats
            };
            report.sweeps = stats.sweeps;
            report.steps = stats.steps;
            report.converged = stats.converged;
        }
        let quality = QualitySummary::of(pool, &problem, &x);
        report.invalid_after = invalid_cells(pool, &problem, &x).len();
        report.min_quality = quality.min;
        report.mean_quality = quality.mean;
        for (p, q) in self.positions.iter_mut().zip(&x) {
            p[..D].copy_from_slice(q);
        }
        report.seconds = start.elapsed().as_secs_f64();
        Ok(report)
    }
}
