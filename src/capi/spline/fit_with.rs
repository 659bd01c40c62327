//! The fit with options: `igaparam_spline_fit_domain_with` (rule, certification, untangling,
//! smoothing, threads, progress and cancellation); its options struct is generated from the
//! core's in `options_gen.rs`.

use super::{igaparam_spline, new_recorded_handle, AnyMap};
use crate::capi::domain::{current, igaparam_domain, Built};
use crate::capi::ffi::{non_null_mut, options_or, run, write_optional, Failure};
use crate::capi::progress::call_progress;
use crate::capi::{igaparam_fit_options, igaparam_fit_report, igaparam_stage, igaparam_status};
use crate::domain::{CubeMap, Domain};
use crate::error::Result;
use crate::spline::{
    FitOptions, FitProgress, FitRecord, FitReport, FitStage, SplineMap, ValidityReport,
};

/// The default fit options: those of `igaparam_spline_fit_domain`.
#[no_mangle]
pub extern "C" fn igaparam_fit_options_default() -> igaparam_fit_options {
    igaparam_fit_options {
        // The C sentinel: the boundary offset the domain was built with (see `fit_options`).
        boundary_offset: -1.0,
        ..igaparam_fit_options::from(&FitOptions::default())
    }
}

/// The core options of `raw` for a domain built with `boundary_offset`: a negative
/// `raw.boundary_offset` (the default) is that one.
fn fit_options(raw: &igaparam_fit_options, boundary_offset: f64) -> Result<FitOptions> {
    let mut options = raw.to_core()?;
    if raw.boundary_offset < 0.0 {
        options.untangle.boundary_offset = boundary_offset;
    }
    options.validate()?;
    Ok(options)
}

/// The fit of a built domain with `raw`, and its record.
fn fit<const D: usize, B: CubeMap<D> + Sync>(
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
    let (map, report, validity) = SplineMap::fit_domain_with(domain, &options, progress)?;
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
    write_optional(report, igaparam_fit_report::from(&r));
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
