//! The method's adaptive loop from C: `igaparam_domain_fit_adaptive`, its default options (the
//! struct is generated from the core's in `options_gen.rs`) and its report.

use super::{igaparam_spline, new_recorded_handle, AnyMap};
use crate::capi::domain::{current, igaparam_domain, Built};
use crate::capi::ffi::{non_null_mut, options_or, run, write_optional, Failure};
use crate::capi::progress::call_progress;
use crate::capi::{igaparam_adapt_options, igaparam_stage, igaparam_status};
use crate::domain::{CubeMap, Domain};
use crate::error::Result;
use crate::spline::{adapt, AdaptOptions, AdaptReport, FitRecord, SplineMap};

/// What `igaparam_domain_fit_adaptive` did.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct igaparam_adapt_report {
    /// Refinement rounds done (0 when the first fit met the target).
    pub rounds: u32,
    /// 1 when the map returned meets the target, else 0 (the round or level limit stopped it).
    pub reached: i32,
    /// T-mesh cells refined over all rounds.
    pub refined_cells: usize,
    /// Elements of the map returned (= cells of the domain's final T-mesh).
    pub elements: usize,
    /// Basis functions of the map returned.
    pub basis: usize,
    /// 1 when every element of the map returned is certified valid.
    pub certified_positive: i32,
    /// Smallest sampled mean ratio of the map returned.
    pub min_quality: f64,
    /// Mean sampled mean ratio of the map returned.
    pub mean_quality: f64,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Control points moved to untangle the fit of the map returned (as
    /// `igaparam_fit_report.untangled`); 0 when that fit was kept.
    pub untangled: usize,
    /// Largest move of a boundary control point by that untangling, relative to the bounding
    /// box (as `igaparam_fit_report.boundary_offset`); 0 when the boundary was kept.
    pub boundary_offset: f64,
    /// Largest distance from the boundary of the map returned to the domain's boundary,
    /// relative to the bounding box (as `igaparam_fit_report.boundary_distance`).
    pub boundary_distance: f64,
}

/// The default adaptation options.
#[no_mangle]
pub extern "C" fn igaparam_adapt_options_default() -> igaparam_adapt_options {
    igaparam_adapt_options::from(&AdaptOptions::default())
}

/// The adaptive loop on a copy of `domain`, which takes the refined T-mesh on success only.
fn adapt_copy<const D: usize, B: CubeMap<D> + Sync>(
    domain: &mut Domain<D, B>,
    options: &AdaptOptions,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<(SplineMap<D>, AdaptReport, FitRecord)>
where
    Domain<D, B>: Clone,
{
    let mut copy = domain.clone();
    let (map, report) = adapt(&mut copy, options, progress)?;
    let record = map.fit_record(copy.mesh(), copy.positions(), &report.fit)?;
    *domain = copy;
    Ok((map, report, record))
}

/// Runs the adaptive loop on a copy of the built domain and, on success, keeps the refined
/// T-mesh in the handle (see `igaparam_domain_fit_adaptive`): a failed or cancelled call leaves
/// the handle as it was. Returns the map, the loop's report and the record of the map's fit.
fn adapt_domain(
    domain: *mut igaparam_domain,
    options: &AdaptOptions,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> std::result::Result<(AnyMap, AdaptReport, FitRecord), Failure> {
    let mut held = current(domain)?;
    let (d, watch) = held.split();
    let progress = &mut |done, total| progress(done, total) && !watch.requested();
    let explain = |e| Failure::from(watch.explain(e));
    Ok(match d.built_mut()? {
        Built::Planar((_, d)) => {
            let (map, report, record) = adapt_copy(d, options, progress).map_err(explain)?;
            (AnyMap::Two(map), report, record)
        }
        Built::Solid((_, d)) => {
            let (map, report, record) = adapt_copy(d, options, progress).map_err(explain)?;
            (AnyMap::Three(map), report, record)
        }
    })
}

/// The adaptive loop of the method: fits the spline map of the built domain, refines the T-mesh
/// cells whose spline element is not certified valid or has a sampled mean ratio under
/// `options->target_quality`, optimizes the T-mesh again and refits, for at most
/// `options->max_rounds` rounds. On success the domain keeps its refined T-mesh and `*out`
/// receives the spline of that T-mesh (`report` may be NULL; `options` may be NULL for the
/// defaults). Each fit untangles, and each refinement optimizes, by the rules the domain was
/// built with (its `boundary_offset`, relief and repair rounds: a domain built with
/// `boundary_offset = 0` keeps its boundary); `options` gives the threads and sweep limit. On
/// failure or cancellation (`IGAPARAM_STATUS_CANCELLED`) the domain is unchanged and `*out` is
/// not written.
#[no_mangle]
pub extern "C" fn igaparam_domain_fit_adaptive(
    domain: *mut igaparam_domain,
    options: *const igaparam_adapt_options,
    out: *mut *mut igaparam_spline,
    report: *mut igaparam_adapt_report,
) -> igaparam_status {
    run("igaparam_domain_fit_adaptive", || {
        non_null_mut(out, "out")?;
        let raw = options_or(options, igaparam_adapt_options_default());
        let opts = raw.to_core()?;
        opts.validate()?;
        let mut progress = |done: usize, total: usize| {
            call_progress(
                raw.progress,
                raw.progress_user,
                igaparam_stage::IGAPARAM_STAGE_ADAPTATION,
                done,
                total,
            )
        };
        let (map, mut r, record) = adapt_domain(domain, &opts, &mut progress)?;
        let last = r.rounds.last().copied().unwrap_or_default();
        write_optional(
            report,
            igaparam_adapt_report {
                rounds: r.rounds.len().saturating_sub(1) as u32,
                reached: r.reached as i32,
                refined_cells: r.rounds.iter().map(|x| x.refined).sum(),
                elements: last.elements,
                basis: last.basis,
                certified_positive: last.certified_positive as i32,
                min_quality: last.min_quality,
                mean_quality: last.mean_quality,
                seconds: r.seconds,
                untangled: r.fit.untangled,
                boundary_offset: r.fit.boundary_offset,
                boundary_distance: r.fit.boundary_distance,
            },
        );
        let validity = std::mem::take(&mut r.validity);
        new_recorded_handle(map, Some((opts.validity, validity)), Some(record), out)
    })
}
