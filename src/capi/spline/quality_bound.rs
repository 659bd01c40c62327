//! The certified lower bound of a spline map's mean ratio from C:
//! `igaparam_spline_quality_bound`, its options and its report.

use super::{held, igaparam_spline};
use crate::capi::ffi::{non_null_mut, options_or, run};
use crate::capi::igaparam_status;
use crate::spline::QualityBoundOptions;

/// Options of `igaparam_spline_quality_bound`; get the defaults from
/// `igaparam_quality_bound_options_default`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_quality_bound_options {
    /// Largest number of subdivisions of an element where the bound is loose (each halves
    /// every direction; default 5, at most 6; solids use at most 3, 8^3 pieces per element).
    pub max_depth: u32,
    /// Sample points per direction and element for the sampled minimum (default 5, from 2
    /// to 64).
    pub samples: u32,
    /// Relative gap in [0, 1) (default 0.05): a piece is not subdivided once its bound is
    /// within this fraction of the map's sampled minimum.
    pub gap: f64,
}

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
    let d = QualityBoundOptions::default();
    igaparam_quality_bound_options {
        max_depth: d.max_depth,
        samples: d.samples as u32,
        gap: d.gap,
    }
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
        let opts = QualityBoundOptions {
            max_depth: raw.max_depth,
            samples: raw.samples as usize,
            gap: raw.gap,
        };
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
