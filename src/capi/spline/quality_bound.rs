//! The certified lower bound of a spline map's mean ratio from C:
//! `igaparam_spline_quality_bound` and its default options (the options and report structs are
//! generated from the core's in `options_gen.rs` and `reports_gen.rs`).

use super::{held, igaparam_spline};
use crate::capi::ffi::{non_null_mut, options_or, run};
use crate::capi::{igaparam_quality_bound_options, igaparam_quality_bound_report, igaparam_status};
use crate::spline::QualityBoundOptions;

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
        *out = igaparam_quality_bound_report::from(&b);
        Ok(())
    })
}
