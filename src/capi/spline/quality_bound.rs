//! The certified lower bound of a spline map's mean ratio from C:
//! `igaparam_spline_quality_bound`, its default options (the struct is generated from the core's
//! in `options_gen.rs`) and its report.

use super::{held, igaparam_spline};
use crate::capi::ffi::{non_null_mut, options_or, run};
use crate::capi::{igaparam_quality_bound_options, igaparam_status};
use crate::spline::QualityBoundOptions;

/// What `igaparam_spline_quality_bound` found: the true smallest mean ratio of the map lies in
/// `[lower_bound, sampled_min]`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct igaparam_quality_bound_report {
    /// Certified lower bound of the mean ratio `q_S = d·det(J)^(2/d)/‖J‖²` over the whole map
    /// (0 when `det J_S > 0` is not proven somewhere).
    pub lower_bound: f64,
    /// Smallest mean ratio at the samples (an upper bound of the true minimum).
    pub sampled_min: f64,
    /// The element of the smallest bound (index into the map's elements).
    pub element: usize,
}

/// The default options of `igaparam_spline_quality_bound`.
#[no_mangle]
pub extern "C" fn igaparam_quality_bound_options_default() -> igaparam_quality_bound_options {
    igaparam_quality_bound_options::from(&QualityBoundOptions::default())
}

/// A certified lower bound of the map's mean ratio: on each element `det J_S` and `‖J‖²` in
/// Bernstein form bound `q_S` from below by `d·(min coefficient of det)^(2/d) / (max
/// coefficient of ‖J‖²)`, refined by subdivision where it is more than `gap` below the sampled
/// minimum. The sampled minimum of `igaparam_spline_check_validity` is an upper bound of the
/// true minimum only (finer samples find lower values); this gives the interval. `options` may
/// be NULL for the defaults. Errors: `IGAPARAM_STATUS_INVALID_ARGUMENT` for options out of
/// range, `IGAPARAM_STATUS_NULL_ARGUMENT`.
#[no_mangle]
pub extern "C" fn igaparam_spline_quality_bound(
    spline: *const igaparam_spline,
    options: *const igaparam_quality_bound_options,
    report: *mut igaparam_quality_bound_report,
) -> igaparam_status {
    run("igaparam_spline_quality_bound", || {
        let s = held(spline)?;
        let raw = options_or(options, igaparam_quality_bound_options_default());
        let opts = raw.to_core()?;
        let out = non_null_mut(report, "report")?;
        let b = with_map!(&s.map, m => m.quality_bound(&opts))?;
        *out = igaparam_quality_bound_report {
            lower_bound: b.lower_bound,
            sampled_min: b.sampled_min,
            element: b.element,
        };
        Ok(())
    })
}
