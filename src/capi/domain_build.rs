//! Building a domain: `igaparam_domain_build`, its default options (the struct is generated from
//! the core's in `options_gen.rs`) and its report.

use std::ffi::c_int;

use super::domain::{held, igaparam_domain, DomainData};
use super::ffi::{options_or, run, write_optional};
use super::igaparam_status;
use super::options_gen::igaparam_domain_options;
use super::progress::optimization_progress;
use crate::domain::{DomainReport, PlanarDomain, PlanarOptions, SolidDomain, SolidOptions};

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
    igaparam_domain_options::from(&PlanarOptions::default())
}

/// The default options of a solid: those of `igaparam_domain_options_default` with a
/// tolerance of 1e-3 (a tolerance bounds a volume in 3D; 1e-5 refines for many minutes).
/// `igaparam_domain_build` with NULL options uses these for a solid.
#[no_mangle]
pub extern "C" fn igaparam_domain_options_default_solid() -> igaparam_domain_options {
    igaparam_domain_options::from(&SolidOptions::solid())
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
        let opts = raw.to_core()?;
        opts.validate()?;
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
