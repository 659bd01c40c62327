//! Moving the boundary of a built domain, the tree kept: the boundary vertices go to the points
//! of their parameters on the new boundary, the inner ones follow by the harmonic extension of
//! that motion (large motions in steps, as in relocation) and are optimized again with the
//! kernel. What a shape-optimization loop calls at every step instead of a new build: the
//! T-mesh, and so the spline space of a fit, stay the same.
//!
//! The frame (the bounding box whose axes scale the targets of the cells, see [`Frame`]) stays
//! that of the build, as the targets of a relocated mesh stay those of its creation: through a
//! loop the vertices minimise one fixed function of their positions, whose optimum depends
//! smoothly on the boundary vertices (the hook of sensitivities by the implicit function
//! theorem). The boundary tolerance, though, is checked as a build would check it, in the new
//! boundary's own frame.

use std::time::Instant;

use rayon::ThreadPool;

use super::budget::Sweeps;
use super::build::Domain;
use super::cube_map::{cell_boundary_error, facet_scale, CubeMap};
use super::frame::{signed_measure, Frame, Framed};
use super::options::{sweep_options, thread_pool, DomainOptions, DomainReport};
use crate::error::{Error, ErrorKind, Result};
use crate::optimize::invalid_cells;
use crate::optimize::laplace::MeshGraph;
use crate::optimize::motion::follow_motion;
use crate::optimize::QualitySummary;

/// Options of [`Domain::update`]; the boundary tolerance, the levels, the repair rounds and the
/// boundary offset are those the domain was built with ([`Domain::options`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UpdateOptions {
    /// Largest number of optimization sweeps per step of the motion (default 200).
    pub max_sweeps: u32,
    /// Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per core.
    pub threads: usize,
    /// Whether to refine where the boundary moved out of tolerance. Off (false, 0 in C; the
    /// default): keep the tree, and only report whether its tolerance still holds. On (true,
    /// 1): refine the boundary cells whose error exceeds the build's tolerance (below its
    /// `max_level`) until none does, and repair cells left folded as the build does; the
    /// T-mesh, and with it the spline space of a fit, then changes (a spline fitted before can
    /// no longer be refitted to it).
    pub refine: bool,
}

impl Default for UpdateOptions {
    fn default() -> Self {
        UpdateOptions {
            max_sweeps: DomainOptions::default().max_sweeps,
            threads: 0,
            refine: false,
        }
    }
}

/// What [`Domain::update`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UpdateReport {
    /// The T-mesh as a build reports it (`igaparam_domain_build`, [`Domain::build`] in Rust):
    /// `invalid_after_placement` counts
    /// the cells the harmonic placement (old positions plus the harmonic extension of the
    /// boundary motion) left invalid, `boundary_error` is measured in the new boundary's own
    /// bounding box (as a build would), `sweeps` and `seconds` are those of the update.
    pub domain: DomainReport,
    /// Whether the tree still meets the build's tolerance (1 in C, else 0): no boundary cell
    /// below the build's `max_level` has an error above it (a build's adaptation would refine
    /// none).
    pub tolerance_met: bool,
    /// Boundary cells below the build's `max_level` whose error exceeds its tolerance (after
    /// the refinement when the option [`refine`](UpdateOptions::refine) is set).
    pub cells_over_tolerance: usize,
    /// Cells added by refinement (0 unless the option [`refine`](UpdateOptions::refine) is set).
    pub refined_cells: usize,
    /// Largest move of a boundary vertex, in coordinates that map the build's bounding box onto
    /// the unit box.
    pub boundary_motion: f64,
    /// Steps the motion was applied in (a motion of more than about four cell sizes is split).
    pub steps: u32,
}

impl<const D: usize, B: CubeMap<D>> Domain<D, B> {
    /// Checks that `boundary` can replace the domain's boundary in [`Domain::update`]: it has an
    /// extent and the same orientation (its parameterization right- or left-handed as the
    /// current one), so that the vertices keep their parameters and the cells do not turn
    /// inside out. Same topology is the boundary type's own: four curves or six faces assigned
    /// to the sides as by its constructor, so the curves or faces must be given in the order of
    /// the first ones.
    pub fn check_boundary(&self, boundary: &B) -> Result<()> {
        let swapped = signed_measure(boundary) < 0.0;
        if swapped != self.swapped {
            return Err(Error::invalid(
                "the new boundary is oriented the other way round: its parameterization is \
                 mirrored relative to the domain's (give the curves or faces in the order and \
                 direction of the first ones)",
            ));
        }
        own_frame(boundary, swapped).map(|_| ())
    }

    /// Replaces the boundary by `boundary` (see [`Domain::check_boundary`]) and moves the
    /// T-mesh onto it, keeping the tree: every boundary vertex goes to the point of its
    /// parameters on the new boundary (plus the offset the seam relief gave it, if any, so
    /// that a fold the relief opened stays open), the inner vertices to their current positions plus the
    /// harmonic extension of that motion (a motion of more than about four cell sizes in
    /// steps, each placed from the last and optimized), and all are optimized again with the
    /// kernel; cells left folded get the seam relief of the build, and a build with
    /// `stationarity_tolerance > 0` gets its Newton polish again (the state
    /// [`Domain::boundary_tangent`] differentiates). The tree changes only with
    /// [`UpdateOptions::refine`]. `progress(sweeps, 0)` is called after every sweep; returning
    /// false cancels. Fails as [`Domain::build`] does when cells stay invalid on boundary facets
    /// whose images cross. On any error the domain is unchanged.
    pub fn update(
        &mut self,
        boundary: B,
        options: &UpdateOptions,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Result<UpdateReport> {
        let start = Instant::now();
        self.check_boundary(&boundary)?;
        let domain_options = DomainOptions {
            max_sweeps: options.max_sweeps,
            threads: options.threads,
            ..self.options
        };
        domain_options.validate()?;
        let pool = thread_pool(&domain_options)?;
        let anchors = self.boundary_anchors();
        let mut next = Domain {
            boundary,
            swapped: self.swapped,
            frame: self.frame,
            options: self.options,
            mesh: self.mesh.clone(),
            framed: self.framed.clone(),
            positions: self.positions.clone(),
            quality: self.quality.clone(),
        };
        let mut per_sweep = |done: usize| progress(done, 0);
        let mut sweeps = Sweeps::new(domain_options.max_total_sweeps, &mut per_sweep);
        let mut report = next.follow_boundary(&anchors, &domain_options, &pool, &mut sweeps)?;
        let invalid = next.relieve(&domain_options, &pool, &mut sweeps)?;
        if options.refine {
            let cells = next.mesh.cell_count();
            next.refine_to_tolerance(&domain_options, &pool, &mut sweeps)?;
            if !invalid.is_empty() || next.mesh.cell_count() != cells {
                report.domain.repair_rounds =
                    next.relieve_and_repair(&domain_options, &pool, &mut sweeps)?;
            }
            report.refined_cells = next.mesh.cell_count().saturating_sub(cells);
        }
        let (spent, exhausted) = (sweeps.spent(), sweeps.exhausted());
        let polished = next.polish(&domain_options, &pool, &mut |_| progress(spent as usize, 0))?;
        let over = next.cells_over_tolerance()?;
        let summary = next.report(&pool)?;
        report.domain = DomainReport {
            boundary_error: over.1,
            invalid_after_placement: report.domain.invalid_after_placement,
            sweeps: spent,
            sweep_budget_exhausted: exhausted,
            repair_rounds: report.domain.repair_rounds,
            newton_iterations: polished.iterations,
            gradient_norm: polished.gradient_norm,
            seconds: start.elapsed().as_secs_f64(),
            ..summary
        };
        report.cells_over_tolerance = over.0.len();
        report.tolerance_met = over.0.is_empty();
        next.refuse_crossing_image(report.domain.invalid_cells)?;
        *self = next;
        Ok(report)
    }

    /// Moves the boundary vertices onto the (new) boundary and the inner ones after them, and
    /// optimizes: the first part of [`Domain::update`]. `old` holds the points of the boundary
    /// vertices on the old boundary: a vertex the seam relief moved off it keeps its offset.
    /// Fills the report's placement count, sweeps, steps and boundary motion.
    fn follow_boundary(
        &mut self,
        old: &[Option<[f64; D]>],
        options: &DomainOptions,
        pool: &ThreadPool,
        sweeps: &mut Sweeps<'_>,
    ) -> Result<UpdateReport> {
        let problem = self.mesh.problem()?;
        let mut goal = self.framed.clone();
        let mut motion = 0.0f64;
        for (v, anchor) in self.boundary_anchors().into_iter().enumerate() {
            if let (Some(a), Some(before)) = (anchor, old[v]) {
                let moved: [f64; D] = std::array::from_fn(|k| goal[v][k] + (a[k] - before[k]));
                let d = (0..D).map(|k| (moved[k] - goal[v][k]).powi(2)).sum::<f64>();
                motion = motion.max(d.sqrt());
                goal[v] = moved;
            }
        }
        let graph = MeshGraph::new(&problem);
        let mut placed = goal.clone();
        pool.install(|| graph.harmonic_placement(&problem, &self.framed, &mut placed));
        let invalid_after_placement = invalid_cells(pool, &problem, &placed).len();
        let followed = follow_motion(
            pool,
            &problem,
            &graph,
            &self.framed,
            &goal,
            &sweep_options(options),
            &mut sweeps.stage(),
        );
        let Some((x, stats)) = sweeps.absorb(followed)? else {
            return Err(Error::new(
                ErrorKind::LimitExceeded,
                format!(
                    "the sweep budget (max_total_sweeps = {} of the build) ran out while the \
                     vertices followed the boundary; the domain is unchanged",
                    options.max_total_sweeps
                ),
            ));
        };
        self.quality = QualitySummary::of(pool, &problem, &x).quality;
        self.set_framed(x);
        Ok(UpdateReport {
            domain: DomainReport {
                invalid_after_placement,
                ..Default::default()
            },
            boundary_motion: motion,
            steps: stats.steps,
            ..Default::default()
        })
    }

    /// Refines the boundary cells over tolerance (see [`Domain::cells_over_tolerance`]) until
    /// none is left or the sweep budget is spent.
    fn refine_to_tolerance(
        &mut self,
        options: &DomainOptions,
        pool: &ThreadPool,
        sweeps: &mut Sweeps<'_>,
    ) -> Result<()> {
        loop {
            let (cells, _) = self.cells_over_tolerance()?;
            if cells.is_empty() || sweeps.exhausted() {
                return Ok(());
            }
            let refined = self.refine_in_place(&cells, options, pool, &mut sweeps.stage());
            if sweeps.absorb(refined)?.is_none() {
                return Ok(());
            }
        }
    }

    /// The cells (indices into the T-mesh's cells) that the adaptation of a build would refine
    /// on the current boundary — boundary cells below the build's `max_level` whose boundary
    /// error, measured in the boundary's own frame, exceeds the build's tolerance — and the
    /// largest relative boundary error of all cells.
    pub fn cells_over_tolerance(&self) -> Result<(Vec<usize>, f64)> {
        let frame = own_frame(&self.boundary, self.swapped)?;
        let framed = Framed {
            inner: &self.boundary,
            swap: self.swapped,
            frame: Some(frame),
        };
        let tree = self.mesh.tree();
        let limit = self.options.tolerance * facet_scale::<D>();
        let mut over = Vec::new();
        let mut worst = 0.0f64;
        for (c, &leaf) in self.mesh.leaves().iter().enumerate() {
            let error = cell_boundary_error(tree, leaf, &framed);
            worst = worst.max(error);
            if error > limit && self.mesh.cell_level(c) < self.options.max_level {
                over.push(c);
            }
        }
        Ok((over, worst / facet_scale::<D>()))
    }
}

/// The frame a build of `boundary` would use.
fn own_frame<const D: usize, B: CubeMap<D>>(boundary: &B, swap: bool) -> Result<Frame<D>> {
    Frame::of(&Framed {
        inner: boundary,
        swap,
        frame: None,
    })
    .ok_or_else(|| {
        Error::invalid("the new boundary has no extent: its bounding box is flat or not finite")
    })
}
