//! Refitting a spline in its own space after `igaparam_domain_update` moved the domain's
//! T-mesh: `igaparam_spline_refit`, and the rule a spline's control points come from.

use super::{dim, igaparam_spline, AnyMap};
use crate::capi::domain::{current, igaparam_domain, untangle_options, Built};
use crate::capi::ffi::{non_null_mut, run, write_optional, Failure};
use crate::capi::{igaparam_fit_report, igaparam_status};
use crate::domain::{CubeMap, Domain};
use crate::error::{Error, Result};
use crate::spline::{FitRecord, FitReport, FitRule, SplineMap, ValidityOptions, ValidityReport};

/// How the control points of a spline come from the T-mesh's map.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum igaparam_fit_rule {
    /// Interpolation at the Greville points.
    IGAPARAM_FIT_INTERPOLATION = 0,
    /// Least squares at the Greville points and 4^d points per element.
    IGAPARAM_FIT_LEAST_SQUARES = 1,
    /// The local quasi-interpolant.
    IGAPARAM_FIT_QUASI_INTERPOLATION = 2,
}

impl From<FitRule> for igaparam_fit_rule {
    fn from(rule: FitRule) -> Self {
        match rule {
            FitRule::Interpolation => igaparam_fit_rule::IGAPARAM_FIT_INTERPOLATION,
            FitRule::LeastSquares => igaparam_fit_rule::IGAPARAM_FIT_LEAST_SQUARES,
            FitRule::QuasiInterpolation => igaparam_fit_rule::IGAPARAM_FIT_QUASI_INTERPOLATION,
        }
    }
}

/// What `igaparam_spline_refit` did.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_refit_report {
    /// The fit: basis and element counts (unchanged), residual, the rule's flags
    /// (`least_squares`, `quasi_interpolation`), the control points this refit's untangling
    /// moved (`untangled`, 0 when the correction carried over from an earlier untangling kept
    /// the map certified) and seconds.
    pub fit: igaparam_fit_report,
    /// The rule the control points came from: the rule of the spline's first fit.
    pub rule: igaparam_fit_rule,
    /// Control points carrying the correction of an untangling (this refit's or an earlier
    /// one's): the map is `A X + c` with `A` the rule's linear map of the T-mesh vertices `X`
    /// and `c` that correction, non-zero at these control points; 0 when the map is the
    /// rule's own fit.
    pub corrected: usize,
    /// 1 when every element of the new map is certified valid (`det J > 0`), else 0.
    pub certified_positive: i32,
    /// Elements where positivity is not proven.
    pub uncertified: usize,
    /// Smallest sampled mean ratio `q_S` of the new map.
    pub min_quality: f64,
    /// Mean sampled mean ratio of the new map.
    pub mean_quality: f64,
}

/// Refits `map` to the built domain `domain` with `record` (see
/// [`SplineMap::refit_tmesh`]), the domain's own boundary offset for the untangling.
fn refit<const D: usize, B: CubeMap<D>>(
    map: &mut SplineMap<D>,
    domain: &Domain<D, B>,
    record: Option<&FitRecord>,
    options: &ValidityOptions,
) -> Result<(FitReport, ValidityReport, FitRecord)> {
    map.refit_tmesh(
        domain.mesh(),
        domain.positions(),
        record,
        options,
        &untangle_options(domain),
    )
}

/// Recomputes the control points of `spline` from the domain's current T-mesh (after
/// `igaparam_domain_update`), in the spline's own space: the same basis functions, elements,
/// Bézier extraction and Greville points, so the basis count and element list never change.
/// The control points come by the rule of the spline's first fit (`report->rule`; a spline
/// read from a file gets the first fit's choice, kept for its next refits), plus the
/// correction an earlier untangling made, if any; the map is then certified as
/// `igaparam_spline_check_validity` does with the default options (the handle keeps the result
/// for it) and, where it is not certified, untangled as `igaparam_spline_fit_domain` does. With
/// the rule fixed the control points are a linear function of the T-mesh's vertices, plus the
/// correction (see `igaparam_refit_report`). A spline refined (`igaparam_spline_refine`) after
/// its fit is fitted in the T-mesh's space and carried exactly into its own.
///
/// `report` may be NULL. Errors: `IGAPARAM_STATUS_INVALID_ARGUMENT` when the domain has not
/// been built, its boundary was replaced without `igaparam_domain_update`, its dimension is not
/// the spline's, or its T-mesh has cells the spline's elements do not refine (the domain was
/// refined after the fit, or is another domain). On error the spline is unchanged.
#[no_mangle]
pub extern "C" fn igaparam_spline_refit(
    spline: *mut igaparam_spline,
    domain: *const igaparam_domain,
    report: *mut igaparam_refit_report,
) -> igaparam_status {
    run("igaparam_spline_refit", || {
        let d = current(domain)?;
        let mut held = super::held(spline)?;
        let s = &mut *held;
        let options = ValidityOptions::default();
        let record = s.fit.as_ref();
        let (fit, validity, record) = match (&mut s.map, d.built()?) {
            (AnyMap::Two(m), Built::Planar((_, b))) => refit(m, b, record, &options)?,
            (AnyMap::Three(m), Built::Solid((_, b))) => refit(m, b, record, &options)?,
            (map, _) => return Err(super::dimension_mismatch(map)),
        };
        write_optional(
            report,
            igaparam_refit_report {
                fit: igaparam_fit_report::from(&fit),
                rule: record.rule.into(),
                corrected: corrected(&record, dim(&s.map)),
                certified_positive: validity.certified_positive as i32,
                uncertified: validity.uncertified,
                min_quality: validity.min_quality,
                mean_quality: validity.mean_quality,
            },
        );
        s.validity = Some((options, validity));
        s.fit = Some(record);
        Ok(())
    })
}

/// The control points a record's correction moves.
fn corrected(record: &FitRecord, d: usize) -> usize {
    record
        .correction
        .chunks_exact(d)
        .filter(|c| c.iter().any(|&v| v != 0.0))
        .count()
}

/// Writes to `*out` the rule the control points of `spline` come from (that of its first fit,
/// which `igaparam_spline_refit` uses). Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` for a
/// spline read from a file and never refitted (its fit is unknown).
#[no_mangle]
pub extern "C" fn igaparam_spline_fit_rule(
    spline: *const igaparam_spline,
    out: *mut igaparam_fit_rule,
) -> igaparam_status {
    run("igaparam_spline_fit_rule", || {
        let s = super::held(spline)?;
        let record = s.fit.as_ref().ok_or_else(|| {
            Failure::from(Error::invalid(
                "the spline was read from a file: its fit rule is unknown until \
                 igaparam_spline_refit chooses one",
            ))
        })?;
        *non_null_mut(out, "out")? = record.rule.into();
        Ok(())
    })
}
