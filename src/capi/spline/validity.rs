//! Certified validity of a spline map from C: `igaparam_spline_check_validity` and its default
//! options (the option and report structs are generated from the core's in `options_gen.rs` and
//! `reports_gen.rs`).

use super::{held, igaparam_spline};
use crate::capi::ffi::{check_capacity, non_null_mut, options_or, run, slice_mut};
use crate::capi::{igaparam_status, igaparam_validity_options, igaparam_validity_report};
use crate::spline::ValidityOptions;

/// The default validity options.
#[no_mangle]
pub extern "C" fn igaparam_validity_options_default() -> igaparam_validity_options {
    igaparam_validity_options::from(&ValidityOptions::default())
}

/// Certifies the sign of the Jacobian determinant on every element (lower bounds from the
/// Bernstein coefficients of det J_S, a polynomial of degree 5×5 in 2D and 8×8×8 in 3D per
/// element, subdividing when inconclusive) and samples the mean ratio; writes the summary to
/// `*report`. `options` may be NULL for the defaults. `element_bounds` (may be NULL) receives
/// each element's lower bound of det J_S and `element_quality` (may be NULL) each element's
/// smallest sampled mean ratio, `len` doubles each, at least `num_elements`: what an adaptive
/// loop marks elements by. A spline from `igaparam_spline_fit_domain` or
/// `igaparam_domain_fit_adaptive` (and its clones) keeps the validity its fit computed with the
/// default options, returned without recomputing for equal options until the map changes
/// (`igaparam_spline_refine`); the result is the same either way.
#[no_mangle]
pub extern "C" fn igaparam_spline_check_validity(
    spline: *const igaparam_spline,
    options: *const igaparam_validity_options,
    report: *mut igaparam_validity_report,
    element_bounds: *mut f64,
    element_quality: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_spline_check_validity", || {
        let s = held(spline)?;
        let opts = options_or(options, igaparam_validity_options_default()).to_core()?;
        opts.validate()?;
        let out = non_null_mut(report, "report")?;
        // The validity the fit computed, when it used the same options; else compute it.
        let computed;
        let v = match &s.validity {
            Some((kept, v)) if *kept == opts => v,
            _ => {
                computed = with_map!(&s.map, m => m.validity(&opts));
                &computed
            }
        };
        let n = v.elements.len();
        if !element_bounds.is_null() {
            check_capacity("element_bounds", len, n)?;
        }
        if !element_quality.is_null() {
            check_capacity("element_quality", len, n)?;
        }
        if !element_bounds.is_null() {
            let o = slice_mut(element_bounds, len, "element_bounds")?;
            for (o, e) in o.iter_mut().zip(&v.elements) {
                *o = e.det_lower_bound;
            }
        }
        if !element_quality.is_null() {
            let o = slice_mut(element_quality, len, "element_quality")?;
            for (o, e) in o.iter_mut().zip(&v.elements) {
                *o = e.min_quality;
            }
        }
        *out = igaparam_validity_report::from(v);
        Ok(())
    })
}
