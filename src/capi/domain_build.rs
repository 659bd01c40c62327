//! Building a domain: `igaparam_domain_build`, its options and its report.

use std::ffi::{c_int, c_void};

use super::domain::{held, igaparam_domain, DomainData};
use super::ffi::{options_or, run, write_optional};
use super::progress::optimization_progress;
use super::{igaparam_progress_fn, igaparam_status};
use crate::domain::{DomainReport, PlanarDomain, PlanarOptions, SolidDomain, SolidOptions};
use crate::error::Result;

/// Options of `igaparam_domain_build`; get the defaults from `igaparam_domain_options_default`
/// (planar) or `igaparam_domain_options_default_solid`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_domain_options {
    /// Boundary tolerance, positive: a boundary cell edge (planar domain) is refined while the
    /// triangle formed by its end images and the image of its parametric midpoint, or a boundary
    /// cell face (solid) while the four tetrahedra of consecutive corner images and the image of
    /// its centre, measured in coordinates that map the bounding box onto the unit box, exceed
    /// `tolerance × √d^d` (for a square or cube box: `tolerance × diagonal^d`; default 1e-5 for a
    /// planar domain, 1e-3 for a solid).
    pub tolerance: f64,
    /// Level of the initial uniform refinement (default 2).
    pub min_level: u32,
    /// Deepest level of the adaptation, at least `min_level` and at most 16 (default 9).
    pub max_level: u32,
    /// Largest number of optimization sweeps of one stage (default 200): the first
    /// optimization, each step of the growth from the bounding box, each round of the seam
    /// relief and of the repair.
    pub max_sweeps: u32,
    /// Largest number of sweeps of all stages together, at least 1 (default 5,000,
    /// `IGAPARAM_DEFAULT_MAX_TOTAL_SWEEPS`): once spent, the running stage stops after its
    /// sweep and no later stage starts; the build succeeds with the T-mesh the sweeps reached,
    /// and the report's `sweep_budget_exhausted` is 1 (check `invalid_cells`). The bundled
    /// domains need at most about 4,100; inputs that fold at every level stop here after
    /// seconds instead of running for minutes.
    pub max_total_sweeps: u32,
    /// Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per core.
    pub threads: u32,
    /// Rounds of repair after the optimization (default 6): while cells stay invalid, they are
    /// refined (past `max_level`, up to level 16) and the mesh optimized again; 0 disables it.
    pub repair_rounds: u32,
    /// Seam relief cap, finite and at least 0: the largest distance, in coordinates that map
    /// the bounding box onto the unit box, by which a boundary vertex may leave the boundary to
    /// open a cell that stays folded with every boundary vertex on it (default 1e-2); 0 keeps
    /// every boundary vertex on the boundary.
    pub boundary_offset: f64,
    /// Largest number of cells of the T-mesh (default 1,000,000): a build whose uniform
    /// refinement to `min_level` alone exceeds it (4^min_level cells for a planar domain,
    /// 8^min_level for a solid) is refused before any work, one whose adaptation or repair
    /// exceeds it stops there; both with `IGAPARAM_STATUS_LIMIT_EXCEEDED`. Raise it for finer
    /// T-meshes (time and memory grow with the cells: minutes and about a gigabyte at the
    /// default in 2D, more for a solid).
    pub max_cells: usize,
    /// The Newton polish after the sweeps, finite and at least 0 (default 0: off): when
    /// positive and every cell is valid, the inner vertices go to a stationary point of the
    /// global objective (the sum of the cells' mean distortions) to this scaled max-norm of its
    /// gradient (1e-8 is typical). It raises the mean cell quality and may lower the smallest.
    pub stationarity_tolerance: f64,
    /// Progress callback, or NULL (default). Called with `IGAPARAM_STAGE_OPTIMIZATION`, `done`
    /// sweeps so far and `total` 0, also between the rounds of the adaptation of the tree (with
    /// `done` 0); returning non-zero cancels the build.
    pub progress: igaparam_progress_fn,
    /// Passed to `progress` as its first argument.
    pub progress_user: *mut c_void,
}

/// What `igaparam_domain_build` did. Quality is the inverse mean distortion of a cell against its
/// parametric (square) cell: 1 is a square, 0 an inverted cell.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct igaparam_domain_report {
    /// Cells of the T-mesh.
    pub cells: usize,
    /// Vertices of the T-mesh, hanging ones included.
    pub vertices: usize,
    /// Deepest level of a cell.
    pub max_level: u32,
    /// Largest boundary error, relative as `tolerance`.
    pub boundary_error: f64,
    /// Largest distance of a boundary vertex from its point on the boundary, in the coordinates
    /// of `boundary_offset` (at most the option; 0 when no seam relief was needed).
    pub boundary_offset: f64,
    /// Invalid cells (det J <= 0 somewhere) after the transfinite (Coons) placement.
    pub invalid_after_placement: usize,
    /// Invalid cells after the optimization; 0 for a usable parameterization.
    pub invalid_cells: usize,
    /// Smallest cell quality.
    pub min_quality: f64,
    /// Mean cell quality.
    pub mean_quality: f64,
    /// Optimization sweeps performed.
    pub sweeps: u32,
    /// 1 if the optimization stopped because it spent `max_total_sweeps` (the T-mesh is the
    /// state the sweeps reached: less optimized, possibly with invalid cells), else 0.
    pub sweep_budget_exhausted: c_int,
    /// Newton iterations of the polish (`stationarity_tolerance > 0`; 0 when it is off or a
    /// cell stays invalid).
    pub newton_iterations: u32,
    /// Scaled max-norm of the global objective's gradient after the polish: at most
    /// `stationarity_tolerance` when it converged (the state `igaparam_spline_tangent` and
    /// `igaparam_spline_adjoint` differentiate), infinite when a cell stays invalid, 0 when the
    /// polish is off.
    pub gradient_norm: f64,
    /// Wall-clock seconds of the call.
    pub seconds: f64,
}

/// The default options of a planar domain (tolerance 1e-5).
#[no_mangle]
pub extern "C" fn igaparam_domain_options_default() -> igaparam_domain_options {
    c_options(&PlanarOptions::default())
}

/// The default options of a solid: those of `igaparam_domain_options_default` with a
/// tolerance of 1e-3 (a tolerance bounds a volume in 3D; 1e-5 refines for many minutes).
/// `igaparam_domain_build` with NULL options uses these for a solid.
#[no_mangle]
pub extern "C" fn igaparam_domain_options_default_solid() -> igaparam_domain_options {
    c_options(&SolidOptions::solid())
}

fn c_options(d: &PlanarOptions) -> igaparam_domain_options {
    igaparam_domain_options {
        tolerance: d.tolerance,
        min_level: d.min_level as u32,
        max_level: d.max_level as u32,
        max_sweeps: d.max_sweeps,
        max_total_sweeps: d.max_total_sweeps,
        threads: d.threads as u32,
        repair_rounds: d.repair_rounds,
        boundary_offset: d.boundary_offset,
        max_cells: d.max_cells,
        stationarity_tolerance: d.stationarity_tolerance,
        progress: None,
        progress_user: std::ptr::null_mut(),
    }
}

/// The core's options of C options `o` (a conversion; the core checks the ranges when it builds).
fn planar_options(o: &igaparam_domain_options) -> Result<PlanarOptions> {
    // A level above 255 becomes 255, which the core refuses as above 16 with the others.
    let level = |l: u32| u8::try_from(l).unwrap_or(u8::MAX);
    let options = PlanarOptions {
        tolerance: o.tolerance,
        min_level: level(o.min_level),
        max_level: level(o.max_level),
        max_sweeps: o.max_sweeps,
        max_total_sweeps: o.max_total_sweeps,
        threads: o.threads as usize,
        repair_rounds: o.repair_rounds,
        boundary_offset: o.boundary_offset,
        max_cells: o.max_cells,
        stationarity_tolerance: o.stationarity_tolerance,
    };
    options.validate()?;
    Ok(options)
}

/// The C form of a build report.
pub(super) fn c_report(r: &DomainReport) -> igaparam_domain_report {
    igaparam_domain_report {
        cells: r.cells,
        vertices: r.vertices,
        max_level: r.max_level as u32,
        boundary_error: r.boundary_error,
        boundary_offset: r.boundary_offset,
        invalid_after_placement: r.invalid_after_placement,
        invalid_cells: r.invalid_cells,
        min_quality: r.min_quality,
        mean_quality: r.mean_quality,
        sweeps: r.sweeps,
        sweep_budget_exhausted: c_int::from(r.sweep_budget_exhausted),
        newton_iterations: r.newton_iterations,
        gradient_norm: r.gradient_norm,
        seconds: r.seconds,
    }
}

/// Adapts a T-mesh to the boundary (refining boundary cells until `options.tolerance` or
/// `options.max_level` is met), places its vertices (boundary ones on the curves, inner ones by
/// the Coons patch) and optimizes them; the result is kept in the handle, replacing that of an
/// earlier build. `options` may be NULL for the defaults (`igaparam_domain_options_default`, or
/// `igaparam_domain_options_default_solid` for a solid); `report` may be NULL. On any error or
/// cancellation the handle is unchanged (an earlier build stays) and `*report` is not written.
#[no_mangle]
pub extern "C" fn igaparam_domain_build(
    domain: *mut igaparam_domain,
    options: *const igaparam_domain_options,
    report: *mut igaparam_domain_report,
) -> igaparam_status {
    run("igaparam_domain_build", || {
        let mut held = held(domain)?;
        let (d, watch) = held.split();
        let defaults = match d {
            DomainData::Planar(..) => igaparam_domain_options_default(),
            DomainData::Solid(..) => igaparam_domain_options_default_solid(),
        };
        let raw = options_or(options, defaults);
        let opts = planar_options(&raw)?;
        let mut progress = optimization_progress(raw.progress, raw.progress_user, watch);
        let r = match d {
            DomainData::Planar(boundary, built) => {
                let (planar, r) = PlanarDomain::build(boundary.clone(), &opts, &mut progress)
                    .map_err(|e| watch.explain(e))?;
                *built = Some(planar);
                r
            }
            DomainData::Solid(boundary, built) => {
                let (solid, r) =
                    SolidDomain::build(boundary.as_ref().clone(), &opts, &mut progress)
                        .map_err(|e| watch.explain(e))?;
                *built = Some(Box::new(solid));
                r
            }
        };
        write_optional(report, c_report(&r));
        Ok(())
    })
}
