//! The fit with options: `igaparam_spline_fit_domain_with` (rule, certification, untangling,
//! smoothing, threads, progress and cancellation).

use std::ffi::c_void;

use super::{fit_report, igaparam_fit_report, igaparam_spline};
use super::{new_recorded_handle, AnyMap};
use crate::capi::domain::{current, igaparam_domain, Built};
use crate::capi::ffi::{non_null_mut, options_or, run, write_optional, Failure};
use crate::capi::options_gen::{c_fit_choice, fit_choice};
use crate::capi::progress::call_progress;
use crate::capi::{
    igaparam_fit_choice, igaparam_progress_fn, igaparam_stage, igaparam_status,
    igaparam_validity_options,
};
use crate::domain::{CubeMap, Domain};
use crate::error::Result;
use crate::spline::{
    FitChoice, FitOptions, FitProgress, FitRecord, FitReport, FitStage, SplineMap, UntangleOptions,
    ValidityReport,
};

/// Options of `igaparam_spline_fit_domain_with`; get the defaults (those of
/// `igaparam_spline_fit_domain`) from `igaparam_fit_options_default`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_fit_options {
    /// The fit rule (default `IGAPARAM_FIT_CHOICE_BEST`).
    pub choice: igaparam_fit_choice,
    /// The certification of the fitted, untangled and smoothed maps (default: the defaults of
    /// `igaparam_validity_options_default`); the spline keeps its result for
    /// `igaparam_spline_check_validity` with equal options.
    pub validity: igaparam_validity_options,
    /// Largest number of untangling rounds per stage for a map that is not certified (default
    /// 4); 0 turns the untangling off: such a map is returned as fitted, with its uncertified
    /// elements in the report of `igaparam_spline_check_validity`.
    pub untangle_rounds: u32,
    /// Sweeps over the free control points per untangling round (default 20).
    pub untangle_sweeps: u32,
    /// Largest move of a boundary control point by the untangling, relative to the bounding
    /// box; negative (default) uses the `boundary_offset` the domain was built with, 0 keeps
    /// the boundary.
    pub boundary_offset: f64,
    /// Largest number of smoothing sweeps over the inner control points of a certified map
    /// (default 8); 0 turns the smoothing off.
    pub smoothing_sweeps: u32,
    /// Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per
    /// core. The result does not depend on it.
    pub threads: u32,
    /// Progress callback, or NULL (default): called on the calling thread with
    /// `IGAPARAM_STAGE_FIT` (`done` of `total` fits and certifications),
    /// `IGAPARAM_STAGE_UNTANGLING` (rounds) and `IGAPARAM_STAGE_SMOOTHING` (sweeps); returning
    /// non-zero cancels (`IGAPARAM_STATUS_CANCELLED`, nothing written).
    pub progress: igaparam_progress_fn,
    /// Passed to `progress` as its first argument.
    pub progress_user: *mut c_void,
}

/// The default fit options: those of `igaparam_spline_fit_domain`.
#[no_mangle]
pub extern "C" fn igaparam_fit_options_default() -> igaparam_fit_options {
    let u = UntangleOptions::default();
    igaparam_fit_options {
        choice: c_fit_choice(FitChoice::default()),
        validity: super::igaparam_validity_options_default(),
        untangle_rounds: u.rounds,
        untangle_sweeps: u.sweeps,
        boundary_offset: -1.0,
        smoothing_sweeps: u.smoothing_sweeps,
        threads: 0,
        progress: None,
        progress_user: std::ptr::null_mut(),
    }
}

/// The core options of `raw` for a domain built with `boundary_offset`.
fn fit_options(raw: &igaparam_fit_options, boundary_offset: f64) -> Result<FitOptions> {
    let options = FitOptions {
        choice: fit_choice(raw.choice)?,
        validity: raw.validity.to_core()?,
        untangle: UntangleOptions {
            rounds: raw.untangle_rounds,
            sweeps: raw.untangle_sweeps,
            boundary_offset: match raw.boundary_offset < 0.0 {
                true => boundary_offset,
                false => raw.boundary_offset,
            },
            smoothing_sweeps: raw.smoothing_sweeps,
            ..UntangleOptions::default()
        },
        threads: raw.threads as usize,
    };
    options.validate()?;
    Ok(options)
}

/// The fit of a built domain with `raw`, and its record.
fn fit<const D: usize, B: CubeMap<D>>(
    domain: &Domain<D, B>,
    raw: &igaparam_fit_options,
    progress: &mut FitProgress,
) -> Result<(
    SplineMap<D>,
    FitReport,
    ValidityReport,
    FitOptions,
    FitRecord,
)> {
    let options = fit_options(raw, domain.options().boundary_offset)?;
    let (map, report, validity) =
        SplineMap::fit_tmesh_with(domain.mesh(), domain.positions(), &options, progress)?;
    let record = map.fit_record(domain.mesh(), domain.positions(), &report)?;
    Ok((map, report, validity, options, record))
}

/// Fits the built `domain` with `raw` and writes the handle to `*out` and, when `report` is not
/// NULL, the report; nothing is written on failure. The body of both fit entry points.
pub(super) fn fit_into(
    domain: *const igaparam_domain,
    raw: &igaparam_fit_options,
    out: *mut *mut igaparam_spline,
    report: *mut igaparam_fit_report,
) -> std::result::Result<(), Failure> {
    non_null_mut(out, "out")?;
    let mut held = current(domain)?;
    let (d, watch) = held.split();
    let mut progress = |stage: FitStage, done: usize, total: usize| {
        let stage = match stage {
            FitStage::Fit => igaparam_stage::IGAPARAM_STAGE_FIT,
            FitStage::Untangling => igaparam_stage::IGAPARAM_STAGE_UNTANGLING,
            FitStage::Smoothing => igaparam_stage::IGAPARAM_STAGE_SMOOTHING,
        };
        call_progress(raw.progress, raw.progress_user, stage, done, total) && !watch.requested()
    };
    let explain = |e| Failure::from(watch.explain(e));
    let (map, r, validity, opts, record) = match d.built()? {
        Built::Planar((_, d)) => {
            let (m, r, v, o, rec) = fit(d, raw, &mut progress).map_err(explain)?;
            (AnyMap::Two(m), r, v, o, rec)
        }
        Built::Solid((_, d)) => {
            let (m, r, v, o, rec) = fit(d, raw, &mut progress).map_err(explain)?;
            (AnyMap::Three(m), r, v, o, rec)
        }
    };
    write_optional(report, fit_report(&r));
    new_recorded_handle(map, Some((opts.validity, validity)), Some(record), out)
}

/// Fits the cubic THB spline space of a built domain's T-mesh to its optimized map as
/// `igaparam_spline_fit_domain` does, with `options` (NULL for the defaults, which make the
/// two calls equal): the fit rule, the certification, the untangling and smoothing, the threads
/// and a progress callback that can cancel. `report` may be NULL. Errors:
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` for an unbuilt domain or an option out of range,
/// `IGAPARAM_STATUS_CANCELLED` when the callback cancels; `*out` is written only on success.
#[no_mangle]
pub extern "C" fn igaparam_spline_fit_domain_with(
    domain: *const igaparam_domain,
    options: *const igaparam_fit_options,
    out: *mut *mut igaparam_spline,
    report: *mut igaparam_fit_report,
) -> igaparam_status {
    run("igaparam_spline_fit_domain_with", || {
        let raw = options_or(options, igaparam_fit_options_default());
        fit_into(domain, &raw, out, report)
    })
}
