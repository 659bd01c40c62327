//! The options of a domain build and what it reports, with their rules (ranges, budgets of cells
//! and sweeps) and the optimizer's settings they give.

use crate::error::{Error, ErrorKind, Result};
use crate::optimize::{NodeSolverOptions, SweepOptions};

/// Options of [`Domain::build`](super::Domain::build).
#[derive(Clone, Copy, Debug)]
pub struct DomainOptions {
    // The coordinates of the tolerances and of `boundary_offset` are those of the `Frame`.
    /// Boundary tolerance, positive: a boundary cell edge (planar domain) is refined while the
    /// triangle formed by its end images and the image of its parametric midpoint, or a boundary
    /// cell face (solid) while the four tetrahedra of consecutive corner images and the image of
    /// its centre, measured in coordinates that map the bounding box onto the unit box, exceed
    /// `tolerance × √d^d` (for a square or cube box: `tolerance × diagonal^d`; default 1e-5 for a
    /// planar domain, 1e-3 for a solid).
    pub tolerance: f64,
    /// Level of the initial uniform refinement (default 2).
    pub min_level: u8,
    /// Deepest level of the adaptation, at least `min_level` and at most 16 (default 9).
    pub max_level: u8,
    /// Largest number of optimization sweeps of one stage (default 200): the first
    /// optimization, each step of the growth from the bounding box, each round of the seam
    /// relief and of the repair.
    pub max_sweeps: u32,
    /// Largest number of sweeps of all stages together, at least 1 (default 5,000,
    /// [`DEFAULT_MAX_TOTAL_SWEEPS`]): once spent, the running stage stops after its sweep and no
    /// later stage starts; the build succeeds with the T-mesh the sweeps reached, and the
    /// report's [`sweep_budget_exhausted`](DomainReport::sweep_budget_exhausted) is set (check
    /// `invalid_cells`). The bundled domains need at most about 4,100; inputs that fold at every
    /// level stop here after seconds instead of running for minutes.
    pub max_total_sweeps: u32,
    /// Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per core.
    pub threads: usize,
    /// Rounds of repair after the optimization (default 6): while cells stay invalid, they are
    /// refined (past `max_level`, up to level 16) and the mesh optimized again; 0 disables it.
    pub repair_rounds: u32,
    // The seam relief: `MARGIN` in `domain/relief.rs`.
    /// Seam relief cap, finite and at least 0: the largest distance, in coordinates that map
    /// the bounding box onto the unit box, by which a boundary vertex may leave the boundary to
    /// open a cell that stays folded with every boundary vertex on it (default 1e-2: the jagged
    /// terrain edge of the Jacksboro block needs offsets near it, the jittered duck faces 1e-3
    /// with a few more levels of refinement); 0 keeps every boundary vertex on the boundary.
    pub boundary_offset: f64,
    /// Largest number of cells of the T-mesh (default 1,000,000, [`DEFAULT_MAX_CELLS`]): a build
    /// whose uniform refinement to `min_level` alone exceeds it (4^min_level cells for a planar
    /// domain, 8^min_level for a solid) is refused before any work, one whose adaptation or
    /// repair exceeds it stops there; both fail with `IGAPARAM_STATUS_LIMIT_EXCEEDED`
    /// ([`ErrorKind::LimitExceeded`]). Raise it for finer T-meshes (time and memory grow with
    /// the cells: minutes and about a gigabyte at the default in 2D, more for a solid).
    pub max_cells: usize,
    /// The Newton polish after the sweeps, finite and at least 0 (default 0: off): when
    /// positive and every cell is valid, the inner vertices go to a stationary point of the
    /// global objective (the sum of the cells' mean distortions, `F = Σ_cells η̄*_c` with
    /// δ = 0) to this scaled max-norm of its gradient (1e-8 is typical: a few to a few tens of
    /// Newton iterations). The stationary point depends on the basin the sweeps end in, not on
    /// their round-off within it; it raises the mean cell quality and may lower the smallest
    /// (the bundled planar domains: mean +3–11%, min −6% to −51%), so it is off by default.
    pub stationarity_tolerance: f64,
}

/// The default cell budget of a domain build (`max_cells` of its options): a million cells, a
/// planar T-mesh of level 10 everywhere (minutes of optimization and about a gigabyte; a
/// solid's cells cost more).
pub const DEFAULT_MAX_CELLS: usize = 1_000_000;

/// The default total sweep budget of a domain build (`max_total_sweeps` of its options): 25
/// times the default `max_sweeps`. The bundled domains need at most 4,071 (the duck's B-rep at
/// tolerance 1e-4, level 4, with its growth from the bounding box and its repair); inputs that
/// fold at every level stop here, after seconds, instead of running for minutes.
pub const DEFAULT_MAX_TOTAL_SWEEPS: u32 = 5_000;

impl DomainOptions {
    /// Checks the ranges of every field: what [`Domain::build`](super::Domain::build),
    /// [`Domain::refine_cells`](super::Domain::refine_cells) and
    /// [`Domain::update`](super::Domain::update) check before any work.
    pub fn validate(&self) -> Result<()> {
        for (name, value) in [
            ("tolerance", self.tolerance),
            ("boundary_offset", self.boundary_offset),
            ("stationarity_tolerance", self.stationarity_tolerance),
        ] {
            if !value.is_finite() {
                return Err(Error::new(
                    ErrorKind::NotFinite,
                    format!("{name} is {value}, it must be finite"),
                ));
            }
        }
        crate::threads::check(self.threads)?;
        if self.tolerance <= 0.0 {
            return Err(Error::invalid(format!(
                "tolerance = {} must be positive",
                self.tolerance
            )));
        }
        if self.min_level > self.max_level || self.max_level > MAX_REPAIR_LEVEL {
            return Err(Error::invalid(format!(
            "levels must satisfy min_level <= max_level <= 16, got min_level = {}, max_level = {}",
            self.min_level, self.max_level
        )));
        }
        if self.max_total_sweeps == 0 {
            return Err(Error::invalid(
                "max_total_sweeps = 0: the sweep budget of a build must be at least 1",
            ));
        }
        if self.stationarity_tolerance < 0.0 {
            return Err(Error::invalid(format!(
                "stationarity_tolerance = {} must be at least 0",
                self.stationarity_tolerance
            )));
        }
        if self.boundary_offset < 0.0 {
            return Err(Error::invalid(format!(
                "boundary_offset = {} must be at least 0",
                self.boundary_offset
            )));
        }
        Ok(())
    }

    /// The defaults of a solid: [`DomainOptions::default`] with a boundary tolerance of 1e-3
    /// instead of 1e-5. A tolerance bounds a volume in 3D (an area in 2D), and at 1e-3 the
    /// shared solids (the duck's B-rep and faces, the Jacksboro block with its axes in km) give
    /// valid T-meshes of 64–92 cells and certified spline maps in seconds, where 1e-5 refines
    /// for many minutes.
    pub fn solid() -> Self {
        DomainOptions {
            tolerance: 1e-3,
            ..Default::default()
        }
    }
}

/// The defaults of a planar domain (see [`DomainOptions::solid`] for a solid's).
impl Default for DomainOptions {
    fn default() -> Self {
        DomainOptions {
            tolerance: 1e-5,
            min_level: 2,
            max_level: 9,
            max_sweeps: 200,
            max_total_sweeps: DEFAULT_MAX_TOTAL_SWEEPS,
            threads: 0,
            repair_rounds: 6,
            boundary_offset: 1e-2,
            max_cells: DEFAULT_MAX_CELLS,
            stationarity_tolerance: 0.0,
        }
    }
}

/// What [`Domain::build`](super::Domain::build) did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DomainReport {
    /// Cells of the T-mesh.
    pub cells: usize,
    /// Vertices of the T-mesh, hanging ones included.
    pub vertices: usize,
    /// Deepest level of a cell.
    pub max_level: u8,
    /// Largest boundary error, relative as [`tolerance`](DomainOptions::tolerance).
    pub boundary_error: f64,
    /// Largest distance of a boundary vertex from its point on the boundary, in coordinates
    /// that map the bounding box onto the unit box (at most the option
    /// [`boundary_offset`](DomainOptions::boundary_offset); 0 when no seam relief was needed).
    pub boundary_offset: f64,
    /// Invalid cells (`det J ≤ 0` somewhere) after the transfinite (Coons) placement.
    pub invalid_after_placement: usize,
    /// Invalid cells after the optimization; 0 for a usable parameterization.
    pub invalid_cells: usize,
    /// Smallest cell quality (1/mean distortion against the parametric cell).
    pub min_quality: f64,
    /// Mean cell quality.
    pub mean_quality: f64,
    /// Optimization sweeps (with those of the fallback growth from the bounding box and of the
    /// repair).
    pub sweeps: u32,
    /// Whether the optimization stopped because it spent
    /// [`max_total_sweeps`](DomainOptions::max_total_sweeps) (1 in C, else 0): the T-mesh is the
    /// state the sweeps reached, less optimized (and possibly with more invalid cells) than a
    /// larger budget would give.
    pub sweep_budget_exhausted: bool,
    /// Repair rounds that refined invalid cells.
    pub repair_rounds: u32,
    /// Newton iterations of the polish (`stationarity_tolerance > 0`; 0 when it is off or a
    /// cell stays invalid).
    pub newton_iterations: u32,
    /// Scaled max-norm of the global objective's gradient after the polish: at most
    /// [`stationarity_tolerance`](DomainOptions::stationarity_tolerance) when it converged (the
    /// state the sensitivities of a fitted spline, `igaparam_spline_tangent` and
    /// `igaparam_spline_adjoint`, differentiate), infinite when a cell stays invalid, 0 when the
    /// polish is off.
    pub gradient_norm: f64,
    /// Wall-clock seconds of the call.
    pub seconds: f64,
    /// Wall-clock seconds of each stage.
    pub stages: StageSeconds,
    /// Whether the boundary's parameterization is left-handed, so that the T-mesh's first two
    /// parametric coordinates are swapped relative to it.
    pub swapped: bool,
}

/// Wall-clock seconds of the stages of [`Domain::build`](super::Domain::build).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageSeconds {
    /// Adapting the tree to the boundary and building the T-mesh.
    pub adaptation: f64,
    /// Placing the vertices (boundary and transfinite interpolation).
    pub placement: f64,
    /// Optimizing, with the fallback growth from the bounding box.
    pub optimization: f64,
    /// Refining the cells left invalid and optimizing again.
    pub repair: f64,
    /// The Newton polish.
    pub polish: f64,
}

/// Deepest level the repair refines to.
pub(super) const MAX_REPAIR_LEVEL: u8 = 16;

/// Refuses a build whose uniform refinement to `min_level` alone exceeds `max_cells`.
pub(super) fn check_uniform_cells<const D: usize>(options: &DomainOptions) -> Result<()> {
    let cells = 1u128 << (D * options.min_level as usize);
    if cells > options.max_cells as u128 {
        return Err(Error::new(
            ErrorKind::LimitExceeded,
            format!(
                "min_level = {} refines [0,1]^{D} into {cells} cells, above max_cells = {}: \
                 lower min_level or raise max_cells",
                options.min_level, options.max_cells
            ),
        ));
    }
    Ok(())
}

/// Refuses a T-mesh of `cells` cells beyond `max_cells`; `stage` names what made them.
pub(super) fn cells_within(options: &DomainOptions, cells: usize, stage: &str) -> Result<()> {
    if cells > options.max_cells {
        return Err(Error::new(
            ErrorKind::LimitExceeded,
            format!(
                "{stage} reached {cells} cells, above max_cells = {}: raise the tolerance or \
                 max_cells, or lower max_level",
                options.max_cells
            ),
        ));
    }
    Ok(())
}

/// The worker threads of the options.
pub(super) fn thread_pool(options: &DomainOptions) -> Result<rayon::ThreadPool> {
    crate::threads::pool(options.threads)
}

/// The sweep options of a domain's optimization.
pub(super) fn sweep_options(options: &DomainOptions) -> SweepOptions {
    SweepOptions {
        max_sweeps: options.max_sweeps,
        move_tolerance: 1e-3,
        node: NodeSolverOptions {
            gradient_tolerance: 1e-3,
            max_iterations: 150,
            relaxation: 1.8,
            power: 1.0,
        },
    }
}
