//! The spline handle: the cubic THB-spline map S: [0,1]^d → Ω fitted to a built domain's T-mesh,
//! or read from G+Smo XML, and every query a host solver needs (values, Jacobians, mean ratio,
//! inverse, basis functions at a point, Bézier extraction, control points), h-refinement,
//! certified validity and output.

use std::ffi::{c_char, c_void};

use super::boundary::{
    check_capacity, non_null, non_null_mut, optional_out, run, slice, slice_mut, Failure,
};
use super::domain::{adapt_domain, c_path, igaparam_domain};
use super::handle::{acquire, handle_type, into_raw, release, Guarded, Held};
use super::igaparam_status;
use super::mesh::call_progress;
use super::{igaparam_progress_fn, igaparam_stage};
use crate::error::{check_finite, Error, Result};
use crate::spline::{
    AdaptOptions, FitRecord, FitReport, SplineMap, SplineSpace, ValidityOptions, ValidityReport,
    HISTOGRAM_BINS,
};

mod fit_with;
mod refit;
pub use fit_with::*;
pub use refit::*;

/// The spline map of a 2D or 3D domain.
#[derive(Clone, Debug)]
pub(crate) enum AnyMap {
    /// A planar map.
    Two(SplineMap<2>),
    /// A solid map.
    Three(SplineMap<3>),
}

/// Runs `$body` with `$m` bound to the map of either dimension (the body is compiled for both).
macro_rules! with_map {
    ($map:expr, $m:ident => $body:expr) => {
        match &*$map {
            AnyMap::Two($m) => $body,
            AnyMap::Three($m) => $body,
        }
    };
}

/// A cubic truncated hierarchical B-spline (THB) map `S: [0,1]^d → Ω`, d = 2 or 3 (opaque).
/// Create with `igaparam_spline_fit_domain` or `igaparam_spline_read_gismo`, release with
/// `igaparam_spline_free`. Parametric points are `d` doubles in [0,1]^d, physical points `d`
/// doubles; arrays of points are flat, `n × d` (x0 y0 x1 y1 ... in 2D). One call at a time
/// (see `IGAPARAM_STATUS_BUSY`).
pub struct igaparam_spline(Guarded<SplineData>);
handle_type!(igaparam_spline, SplineData, "spline");

/// What a spline handle holds: the map, its known validity and the record of its fit.
#[derive(Clone)]
pub(crate) struct SplineData {
    map: AnyMap,
    /// The validity of `map` computed by the fit that produced it, with the options it was
    /// computed with; `igaparam_spline_check_validity` returns it for equal options. Every change
    /// of `map` goes through [`igaparam_spline::set_map`], which drops it.
    validity: Option<(ValidityOptions, ValidityReport)>,
    /// The rule (and untangling correction) of the fit that produced `map`, for
    /// `igaparam_spline_refit`; `None` for a map read from a file.
    fit: Option<FitRecord>,
}

impl SplineData {
    /// Replaces the map, dropping the validity kept for the old one.
    fn set_map(&mut self, map: AnyMap) {
        self.map = map;
        self.validity = None;
    }
}

/// What a fit (`igaparam_spline_fit_domain`, `igaparam_spline_refine`) did.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct igaparam_fit_report {
    /// Basis functions (= control points).
    pub basis_count: usize,
    /// Elements (the leaves of the hierarchical mesh).
    pub element_count: usize,
    /// Largest coordinate difference between the spline and the data at the fit points.
    pub residual: f64,
    /// 1 when a least-squares fit replaced a singular or badly conditioned interpolation at the
    /// Greville points, else 0.
    pub least_squares: i32,
    /// 1 when the control points come from the local quasi-interpolant (a fit whose map was
    /// certified valid, or less invalid, than that of the interpolation; and every
    /// `igaparam_spline_refine`), else 0.
    pub quasi_interpolation: i32,
    /// Control points that `igaparam_spline_fit_domain` moved to untangle a fitted map that was
    /// not certified valid (inner ones first; boundary ones, at most the domain's
    /// `boundary_offset` of the bounding box, only when that was not enough); 0 when the fitted
    /// map was kept as it was.
    pub untangled: usize,
    /// Largest move of a boundary control point by that untangling, relative to the bounding
    /// box (each axis scaled to 1); 0 when the boundary was kept.
    pub boundary_offset: f64,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Inner control points the smoothing stage moved (on the spline's own mean ratio, kept
    /// only when the map stays certified and its smallest sampled mean ratio rises); 0 when
    /// the map was kept as it was.
    pub smoothed: usize,
}

/// Options of `igaparam_spline_check_validity`; get the defaults from
/// `igaparam_validity_options_default`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_validity_options {
    /// Largest number of subdivisions of an element's Jacobian determinant polynomial when its
    /// Bernstein coefficients are inconclusive (default 5, at most 12).
    pub max_depth: u32,
    /// Sample points per direction and element for the mean ratio (default 5, from 2 to 64).
    pub samples: u32,
}

/// Number of bins of the quality histogram of `igaparam_validity_report`.
pub const IGAPARAM_HISTOGRAM_BINS: usize = 10;
const _: () = assert!(IGAPARAM_HISTOGRAM_BINS == HISTOGRAM_BINS);

/// Certified validity and quality of a spline map.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct igaparam_validity_report {
    /// 1 when `det J_S > 0` is proven on every element (Bernstein coefficients of the
    /// determinant, with subdivision), else 0.
    pub certified_positive: i32,
    /// Elements where positivity is not proven.
    pub uncertified: usize,
    /// Smallest lower bound of `det J_S` over the elements (Jacobian with respect to the
    /// parametric coordinates).
    pub det_lower_bound: f64,
    /// Smallest mean ratio `q_S = d·det(J)^(2/d)/‖J‖²` at the samples (0 where det ≤ 0).
    pub min_quality: f64,
    /// Mean of the element means of `q_S` at the samples.
    pub mean_quality: f64,
    /// Samples per quality bin `[i/10, (i+1)/10)` (the last bin includes 1).
    pub histogram: [usize; IGAPARAM_HISTOGRAM_BINS],
}

/// The default validity options.
#[no_mangle]
pub extern "C" fn igaparam_validity_options_default() -> igaparam_validity_options {
    let d = ValidityOptions::default();
    igaparam_validity_options {
        max_depth: d.max_depth,
        samples: d.samples as u32,
    }
}

fn fit_report(r: &FitReport) -> igaparam_fit_report {
    igaparam_fit_report {
        basis_count: r.basis_count,
        element_count: r.element_count,
        residual: r.residual,
        least_squares: r.least_squares as i32,
        quasi_interpolation: r.quasi_interpolation as i32,
        untangled: r.untangled,
        boundary_offset: r.boundary_offset,
        seconds: r.seconds,
        smoothed: r.smoothed,
    }
}

/// Writes a new handle to `*out`; `validity` is that of `map` with its options, when known.
fn new_handle(
    map: AnyMap,
    validity: Option<(ValidityOptions, ValidityReport)>,
    out: *mut *mut igaparam_spline,
) -> std::result::Result<(), Failure> {
    new_recorded_handle(map, validity, None, out)
}

/// Writes a new handle to `*out`, with the record of the fit that made `map`, when known.
fn new_recorded_handle(
    map: AnyMap,
    validity: Option<(ValidityOptions, ValidityReport)>,
    fit: Option<FitRecord>,
    out: *mut *mut igaparam_spline,
) -> std::result::Result<(), Failure> {
    let out = non_null_mut(out, "out")?;
    *out = into_raw::<igaparam_spline>(SplineData { map, validity, fit });
    Ok(())
}

/// The spline of handle `spline`, held for the call.
fn held<'a>(
    spline: *const igaparam_spline,
) -> std::result::Result<Held<'a, igaparam_spline>, Failure> {
    acquire(spline, "spline")
}

/// The map of handle `spline`, held for the call.
fn map<'a>(spline: *const igaparam_spline) -> std::result::Result<MapOf<'a>, Failure> {
    Ok(MapOf(held(spline)?))
}

/// The map of a held spline handle.
struct MapOf<'a>(Held<'a, igaparam_spline>);

impl std::ops::Deref for MapOf<'_> {
    type Target = AnyMap;
    fn deref(&self) -> &AnyMap {
        &self.0.map
    }
}

fn dim(map: &AnyMap) -> usize {
    match map {
        AnyMap::Two(_) => 2,
        AnyMap::Three(_) => 3,
    }
}

/// `n × width` doubles at `ptr`, with an overflow check.
fn points_in<'a>(
    ptr: *const f64,
    n: usize,
    width: usize,
    name: &'static str,
) -> std::result::Result<&'a [f64], Failure> {
    let len = n
        .checked_mul(width)
        .ok_or_else(|| Error::invalid(format!("`{name}`: count {n} is too large")))?;
    let values = slice(ptr, len, name)?;
    check_finite(name, values)?;
    Ok(values)
}

/// A writable buffer of `n × width` doubles, or `None` when `ptr` is NULL.
fn points_out<'a>(
    ptr: *mut f64,
    n: usize,
    width: usize,
    name: &'static str,
) -> std::result::Result<Option<&'a mut [f64]>, Failure> {
    if ptr.is_null() {
        return Ok(None);
    }
    let len = n
        .checked_mul(width)
        .ok_or_else(|| Error::invalid(format!("`{name}`: count {n} is too large")))?;
    Ok(Some(slice_mut(ptr, len, name)?))
}

/// Checks that `x` lies in the parametric domain [0,1]^d.
fn check_parameter<const D: usize>(x: [f64; D], i: usize) -> Result<()> {
    if x.iter().all(|v| (0.0..=1.0).contains(v)) {
        Ok(())
    } else {
        Err(Error::invalid(format!(
            "parametric point {i} {x:?} is outside [0,1]^{D}"
        )))
    }
}

fn point<const D: usize>(values: &[f64], i: usize) -> [f64; D] {
    std::array::from_fn(|k| values[D * i + k])
}

/// Fits the cubic THB spline space of a built domain's T-mesh to its optimized piecewise
/// quadratic map (interpolation at the Greville points, sparse LU; a least-squares fit when that
/// system is singular) and writes the new handle to `*out`. `report` may be NULL. Fails with
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built; `*out` is written only
/// on success. The spline does not refer to the domain afterwards. The fit certifies the map
/// as `igaparam_spline_check_validity` does with the default options, and the handle keeps that
/// result for it. When the interpolation's map is not certified, the local quasi-interpolant is
/// made too and the better kept; when that is still not certified, the map is untangled: the
/// control points around the uncertified elements move to lift det J (inner ones first, keeping
/// the boundary; then boundary ones, at most the `boundary_offset` the domain was built with,
/// relative to the bounding box, none when it is 0), kept only if fewer elements stay uncertified (`report->untangled`,
/// `report->boundary_offset`).
#[no_mangle]
pub extern "C" fn igaparam_spline_fit_domain(
    domain: *const igaparam_domain,
    out: *mut *mut igaparam_spline,
    report: *mut igaparam_fit_report,
) -> igaparam_status {
    run("igaparam_spline_fit_domain", || {
        fit_into(domain, &igaparam_fit_options_default(), out, report)
    })
}

/// Options of `igaparam_domain_fit_adaptive`; get the defaults from
/// `igaparam_adapt_options_default`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_adapt_options {
    /// Target: every element certified valid with a smallest sampled mean ratio of at least
    /// this, in [0, 1) (default 0.1). Elements below it or not certified are refined.
    pub target_quality: f64,
    /// Largest number of refinement rounds (default 4).
    pub max_rounds: u32,
    /// Cells at this level are not refined further, at most 16 (default 10).
    pub max_level: u32,
    /// Largest number of optimization sweeps after each refinement (default 200).
    pub max_sweeps: u32,
    /// Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per core.
    pub threads: u32,
    /// Progress callback, or NULL (default). Called with `IGAPARAM_STAGE_ADAPTATION`, `done`
    /// rounds and `total` = `max_rounds` before each refinement; returning non-zero cancels.
    pub progress: igaparam_progress_fn,
    /// Passed to `progress` as its first argument.
    pub progress_user: *mut c_void,
}

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
}

/// The default adaptation options.
#[no_mangle]
pub extern "C" fn igaparam_adapt_options_default() -> igaparam_adapt_options {
    let d = AdaptOptions::default();
    igaparam_adapt_options {
        target_quality: d.target_quality,
        max_rounds: d.max_rounds,
        max_level: d.max_level as u32,
        max_sweeps: d.domain.max_sweeps,
        threads: d.domain.threads as u32,
        progress: None,
        progress_user: std::ptr::null_mut(),
    }
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
        let raw = if options.is_null() {
            igaparam_adapt_options_default()
        } else {
            *non_null(options, "options")?
        };
        if !raw.target_quality.is_finite() {
            return Err(Error::new(
                crate::error::ErrorKind::NotFinite,
                format!("target_quality is {}", raw.target_quality),
            )
            .into());
        }
        if raw.max_level > 16 || raw.threads > 4096 {
            return Err(Error::invalid(format!(
                "max_level = {} (at most 16), threads = {} (at most 4096)",
                raw.max_level, raw.threads
            ))
            .into());
        }
        let defaults = AdaptOptions::default();
        let opts = AdaptOptions {
            target_quality: raw.target_quality,
            max_rounds: raw.max_rounds,
            max_level: raw.max_level as u8,
            domain: crate::domain::DomainOptions {
                max_sweeps: raw.max_sweeps,
                threads: raw.threads as usize,
                ..defaults.domain
            },
            ..defaults
        };
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
        if !report.is_null() {
            *non_null_mut(report, "report")? = igaparam_adapt_report {
                rounds: r.rounds.len().saturating_sub(1) as u32,
                reached: r.reached as i32,
                refined_cells: r.rounds.iter().map(|x| x.refined).sum(),
                elements: last.elements,
                basis: last.basis,
                certified_positive: last.certified_positive as i32,
                min_quality: last.min_quality,
                mean_quality: last.mean_quality,
                seconds: r.seconds,
            };
        }
        let validity = std::mem::take(&mut r.validity);
        new_recorded_handle(map, Some((opts.validity, validity)), Some(record), out)
    })
}

/// Reads a THB-spline map written by `igaparam_spline_write_gismo` (G+Smo XML, a
/// `THBSpline2` or `THBSpline3` geometry) from `path` (NUL-terminated UTF-8) and writes the new
/// handle to `*out`. Fails with `IGAPARAM_STATUS_IO` if the file cannot be read or holds no
/// such map.
#[no_mangle]
pub extern "C" fn igaparam_spline_read_gismo(
    path: *const c_char,
    out: *mut *mut igaparam_spline,
) -> igaparam_status {
    run("igaparam_spline_read_gismo", || {
        non_null_mut(out, "out")?;
        let path = c_path(path, "path")?;
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::io(format!("cannot read {}: {e}", path.display())))?;
        let map = if text.contains("THBSpline3") {
            AnyMap::Three(crate::spline::read_gismo_thb::<3>(&text)?)
        } else {
            AnyMap::Two(crate::spline::read_gismo_thb::<2>(&text)?)
        };
        new_handle(map, None, out)
    })
}

/// Releases a spline created by this library; NULL is a no-op. Called on a spline in use (from
/// the progress callback of a call on it, or from another thread), the release waits for that
/// call and happens as it returns; the handle must not be used after this call in either case.
#[no_mangle]
pub extern "C" fn igaparam_spline_free(spline: *mut igaparam_spline) {
    release(spline);
}

/// Writes to `*out` a new, independent copy of `spline` (to refine one while keeping the other).
#[no_mangle]
pub extern "C" fn igaparam_spline_clone(
    spline: *const igaparam_spline,
    out: *mut *mut igaparam_spline,
) -> igaparam_status {
    run("igaparam_spline_clone", || {
        let s = held(spline)?;
        new_recorded_handle(s.map.clone(), s.validity.clone(), s.fit.clone(), out)
    })
}

/// Writes the map's dimension d (2 or 3) to `*out`.
#[no_mangle]
pub extern "C" fn igaparam_spline_dimension(
    spline: *const igaparam_spline,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_spline_dimension", || {
        let d = dim(&*map(spline)?);
        *non_null_mut(out, "out")? = d;
        Ok(())
    })
}

/// Writes the number of basis functions (= control points) to `*out`.
#[no_mangle]
pub extern "C" fn igaparam_spline_basis_count(
    spline: *const igaparam_spline,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_spline_basis_count", || {
        let n = with_map!(map(spline)?, m => m.basis_count());
        *non_null_mut(out, "out")? = n;
        Ok(())
    })
}

/// Writes the number of elements (boxes on which every basis function is a polynomial) to
/// `*out`.
#[no_mangle]
pub extern "C" fn igaparam_spline_element_count(
    spline: *const igaparam_spline,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_spline_element_count", || {
        let n = with_map!(map(spline)?, m => m.element_count());
        *non_null_mut(out, "out")? = n;
        Ok(())
    })
}

/// Copies the control points, `num_basis × d` doubles, into `xyz` (`len` doubles).
#[no_mangle]
pub extern "C" fn igaparam_spline_copy_control_points(
    spline: *const igaparam_spline,
    xyz: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_spline_copy_control_points", || {
        let values: Vec<f64> =
            with_map!(map(spline)?, m => m.control_points().iter().flatten().copied().collect());
        check_capacity("xyz", len, values.len())?;
        slice_mut(xyz, len, "xyz")?[..values.len()].copy_from_slice(&values);
        Ok(())
    })
}

/// Copies the Greville points of the basis functions, `num_basis × d` doubles in [0,1]^d (in the
/// order of the global function indices), into `params` (`len` doubles). A function whose
/// Greville point lies inside (0,1)^d vanishes on the boundary of the parametric domain (the
/// knots are clamped): the functions with a Greville point on the boundary (some coordinate 0 or
/// 1) are the degrees of freedom a Dirichlet condition sets.
#[no_mangle]
pub extern "C" fn igaparam_spline_copy_greville_points(
    spline: *const igaparam_spline,
    params: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_spline_copy_greville_points", || {
        let values: Vec<f64> = with_map!(map(spline)?, m => {
            m.space().greville_points().iter().flatten().copied().collect()
        });
        check_capacity("params", len, values.len())?;
        slice_mut(params, len, "params")?[..values.len()].copy_from_slice(&values);
        Ok(())
    })
}

/// Copies the elements: `levels` receives the refinement level of each (`num_elements` bytes;
/// an element of level l has side 2^-l), `bounds` the parametric box of each,
/// `num_elements × 2d` doubles (lower corner then upper corner). Either may be NULL to skip it;
/// `len` is the number of elements the buffers hold, at least `num_elements`.
#[no_mangle]
pub extern "C" fn igaparam_spline_copy_elements(
    spline: *const igaparam_spline,
    levels: *mut u8,
    bounds: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_spline_copy_elements", || {
        let m = map(spline)?;
        let d = dim(&m);
        let n = with_map!(m, m => m.element_count());
        check_capacity("levels/bounds (elements)", len, n)?;
        if let Some(out) = optional_out(bounds, 2 * d * n) {
            with_map!(m, m => {
                for (e, o) in out.chunks_mut(2 * d).enumerate() {
                    let (lo, hi) = m.element_bounds(e);
                    o[..d].copy_from_slice(&lo);
                    o[d..].copy_from_slice(&hi);
                }
            });
        }
        if let Some(out) = optional_out(levels, n) {
            with_map!(m, m => {
                for (e, o) in out.iter_mut().enumerate() {
                    *o = m.element_level(e);
                }
            });
        }
        Ok(())
    })
}

/// Writes to `*out` the number of basis functions that are non-zero on element `element`: the
/// rows of its Bézier extraction operator (which has `4^d` columns).
#[no_mangle]
pub extern "C" fn igaparam_spline_element_function_count(
    spline: *const igaparam_spline,
    element: usize,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_spline_element_function_count", || {
        let n = with_map!(map(spline)?, m => {
            check_element(m.element_count(), element)?;
            m.extraction(element).0.len()
        });
        *non_null_mut(out, "out")? = n;
        Ok(())
    })
}

fn check_element(count: usize, element: usize) -> Result<()> {
    if element >= count {
        return Err(Error::invalid(format!(
            "element {element} is out of range (the map has {count} elements)"
        )));
    }
    Ok(())
}

/// Copies the Bézier extraction of element `element`: `functions` receives the global indices
/// of the `m` basis functions non-zero on it (increasing; `m` from
/// `igaparam_spline_element_function_count`, `len_functions` at least `m`), and `operator` the
/// `m × 4^d` matrix C (row-major, `len_operator` at least `m × 4^d` doubles) such that
/// `N_functions[i] = Σ_k C[i][k] B_k` on the element, with `B_k` the tensor Bernstein
/// polynomials of degree 3 on the element's box mapped to [0,1]^d, `k = k0 + 4 k1 (+ 16 k2)`.
/// Either buffer may be NULL to skip it.
#[no_mangle]
pub extern "C" fn igaparam_spline_copy_element_extraction(
    spline: *const igaparam_spline,
    element: usize,
    functions: *mut usize,
    len_functions: usize,
    operator: *mut f64,
    len_operator: usize,
) -> igaparam_status {
    run("igaparam_spline_copy_element_extraction", || {
        let (f, c): (Vec<usize>, Vec<f64>) = with_map!(map(spline)?, m => {
            check_element(m.element_count(), element)?;
            let (f, c) = m.extraction(element);
            (f.to_vec(), c.to_vec())
        });
        if !functions.is_null() {
            check_capacity("functions", len_functions, f.len())?;
        }
        if !operator.is_null() {
            check_capacity("operator", len_operator, c.len())?;
        }
        if !functions.is_null() {
            slice_mut(functions, len_functions, "functions")?[..f.len()].copy_from_slice(&f);
        }
        if !operator.is_null() {
            slice_mut(operator, len_operator, "operator")?[..c.len()].copy_from_slice(&c);
        }
        Ok(())
    })
}

/// Evaluates the map at `n` parametric points `params` (`n × d` doubles in [0,1]^d): `points`
/// receives `S(params)` (`n × d` doubles) and `jacobians` the Jacobian matrices `dS/du`
/// (`n × d × d` doubles, row-major: entry (i, j) = ∂S_i/∂u_j). Either may be NULL to skip it.
/// Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` when a point is outside [0,1]^d.
#[no_mangle]
pub extern "C" fn igaparam_spline_evaluate(
    spline: *const igaparam_spline,
    n: usize,
    params: *const f64,
    points: *mut f64,
    jacobians: *mut f64,
) -> igaparam_status {
    run("igaparam_spline_evaluate", || {
        let m = map(spline)?;
        let d = dim(&m);
        let input = points_in(params, n, d, "params")?;
        let values = with_map!(m, m => evaluate(m, input)?);
        if let Some(out) = points_out(points, n, d, "points")? {
            for (o, (y, _)) in out.chunks_mut(d).zip(&values) {
                o.copy_from_slice(y);
            }
        }
        if let Some(out) = points_out(jacobians, n, d * d, "jacobians")? {
            for (o, (_, j)) in out.chunks_mut(d * d).zip(&values) {
                o.copy_from_slice(j);
            }
        }
        Ok(())
    })
}

/// Values and row-major Jacobians of `m` at the flat parametric points `input`.
fn evaluate<const D: usize>(m: &SplineMap<D>, input: &[f64]) -> Result<Vec<(Vec<f64>, Vec<f64>)>> {
    let xs: Vec<[f64; D]> = (0..input.len() / D).map(|i| point(input, i)).collect();
    for (i, &x) in xs.iter().enumerate() {
        check_parameter(x, i)?;
    }
    m.eval_many(&xs)
        .into_iter()
        .enumerate()
        .map(|(i, r)| {
            let (y, j) =
                r.ok_or_else(|| Error::invalid(format!("point {i} cannot be evaluated")))?;
            Ok((y.to_vec(), j.iter().flatten().copied().collect()))
        })
        .collect()
}

/// Writes the mean ratio of the Jacobian, `q_S = d·det(J)^(2/d)/‖J‖²_F` in [0, 1] (1 for a
/// conformal map, 0 where det J ≤ 0), at `n` parametric points `params` (`n × d` doubles) into
/// `quality` (`n` doubles).
#[no_mangle]
pub extern "C" fn igaparam_spline_mean_ratio(
    spline: *const igaparam_spline,
    n: usize,
    params: *const f64,
    quality: *mut f64,
) -> igaparam_status {
    run("igaparam_spline_mean_ratio", || {
        let m = map(spline)?;
        let d = dim(&m);
        let input = points_in(params, n, d, "params")?;
        let q = with_map!(m, m => mean_ratios(m, input)?);
        slice_mut(quality, n, "quality")?.copy_from_slice(&q);
        Ok(())
    })
}

/// Mean ratios of `m` at the flat parametric points `input`.
fn mean_ratios<const D: usize>(m: &SplineMap<D>, input: &[f64]) -> Result<Vec<f64>> {
    Ok(evaluate(m, input)?
        .iter()
        .map(|(_, j)| {
            let jacobian: [[f64; D]; D] = std::array::from_fn(|a| point(j, a));
            crate::optimize::metric::mean_ratio(&jacobian)
        })
        .collect())
}

/// Inverts the map at `n` physical points `points` (`n × d` doubles): `params` receives the
/// parametric points whose images they are (`n × d` doubles), `found` (`n` ints) 1 where the
/// point was located and 0 where it is outside the domain (or Newton's method did not converge;
/// `params` is NaN there). `found` may be NULL. Newton's method starts from the nearest of
/// `samples^d` samples per element (`samples` from 2 to 32; 4 is a good choice).
#[no_mangle]
pub extern "C" fn igaparam_spline_invert(
    spline: *const igaparam_spline,
    n: usize,
    points: *const f64,
    samples: u32,
    params: *mut f64,
    found: *mut i32,
) -> igaparam_status {
    run("igaparam_spline_invert", || {
        let m = map(spline)?;
        let d = dim(&m);
        if !(2..=32).contains(&samples) {
            return Err(Error::invalid(format!("samples = {samples} is not in 2..=32")).into());
        }
        let input = points_in(points, n, d, "points")?;
        let located: Vec<Option<Vec<f64>>> = with_map!(m, m => {
            let inverse = m.inverse_map(samples as usize);
            (0..n).map(|i| inverse.locate(point(input, i)).map(|x| x.to_vec())).collect()
        });
        let out =
            points_out(params, n, d, "params")?.ok_or(super::boundary::NullArgument("params"))?;
        let flags = if found.is_null() {
            None
        } else {
            Some(slice_mut(found, n, "found")?)
        };
        for (o, x) in out.chunks_mut(d).zip(&located) {
            match x {
                Some(x) => o.copy_from_slice(x),
                None => o.fill(f64::NAN),
            }
        }
        if let Some(flags) = flags {
            for (f, x) in flags.iter_mut().zip(&located) {
                *f = x.is_some() as i32;
            }
        }
        Ok(())
    })
}

/// Writes to `*count` the number of basis functions non-zero on the element holding the
/// parametric point `param` (`d` doubles in [0,1]^d): the size of the buffers of
/// `igaparam_spline_basis_at`.
#[no_mangle]
pub extern "C" fn igaparam_spline_basis_count_at(
    spline: *const igaparam_spline,
    param: *const f64,
    count: *mut usize,
) -> igaparam_status {
    run("igaparam_spline_basis_count_at", || {
        let (f, _, _) = basis_at(spline, param)?;
        *non_null_mut(count, "count")? = f.len();
        Ok(())
    })
}

/// The basis functions non-zero on the element holding the parametric point `param` (`d`
/// doubles in [0,1]^d; on an element boundary the element on the upper side): `*count` receives
/// their number `m`, `functions` their global indices (`m` values), `values` their values (`m`
/// doubles) and `gradients` their gradients with respect to the parametric coordinates
/// (`m × d` doubles). The buffers hold `len` functions (`len ≥ m`, see
/// `igaparam_spline_basis_count_at`); any of them may be NULL to skip it. The values sum to 1,
/// and `Σ values[i] × control_point[functions[i]]` is the map's value at `param`. When the
/// buffers are too small (`IGAPARAM_STATUS_BUFFER_TOO_SMALL`) `*count` still receives `m` and
/// nothing else is written.
#[no_mangle]
pub extern "C" fn igaparam_spline_basis_at(
    spline: *const igaparam_spline,
    param: *const f64,
    count: *mut usize,
    functions: *mut usize,
    values: *mut f64,
    gradients: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_spline_basis_at", || {
        let (f, v, g) = basis_at(spline, param)?;
        let count = non_null_mut(count, "count")?;
        let m = f.len();
        *count = m;
        if !functions.is_null() || !values.is_null() || !gradients.is_null() {
            check_capacity("functions/values/gradients (functions)", len, m)?;
        }
        for (out, from) in [
            (optional_out(values, m), &v),
            (optional_out(gradients, g.len()), &g),
        ] {
            if let Some(out) = out {
                out.copy_from_slice(from);
            }
        }
        if let Some(out) = optional_out(functions, m) {
            out.copy_from_slice(&f);
        }
        Ok(())
    })
}

/// Functions, values and gradients (`d` per function) of the basis at a point.
type BasisAt = (Vec<usize>, Vec<f64>, Vec<f64>);

/// The functions non-zero at `param`, their values and their gradients.
fn basis_at(
    spline: *const igaparam_spline,
    param: *const f64,
) -> std::result::Result<BasisAt, Failure> {
    let m = map(spline)?;
    let d = dim(&m);
    let x = points_in(param, 1, d, "param")?;
    Ok(with_map!(m, m => {
        let p = point(x, 0);
        check_parameter(p, 0)?;
        let b = m.basis_at(p)
            .ok_or_else(|| Error::invalid("the point is outside the parametric domain"))?;
        (b.functions, b.values, b.gradients.iter().flatten().copied().collect())
    }))
}

/// h-refines the spline space, the map staying the same (the refined space contains the old
/// one; the new control points reproduce the map to round-off, see `report->residual`): the
/// elements listed in `elements` (`n` indices) are split into 2^d, and more where the mesh's
/// 2:1 balance requires it; `n = 0` (with `elements` NULL) refines every element once. An
/// element already at the deepest level, 20 (side 2^-20; see `igaparam_spline_copy_elements`),
/// is left as it is. Element and function indices change. `report` may be NULL. On failure the
/// spline is unchanged.
#[no_mangle]
pub extern "C" fn igaparam_spline_refine(
    spline: *mut igaparam_spline,
    n: usize,
    elements: *const usize,
    report: *mut igaparam_fit_report,
) -> igaparam_status {
    run("igaparam_spline_refine", || {
        let mut handle = held(spline)?;
        let marked = slice(elements, n, "elements")?;
        let (refined, r) = match &handle.map {
            AnyMap::Two(m) => refine(m, marked).map(|(m, r)| (AnyMap::Two(m), r))?,
            AnyMap::Three(m) => refine(m, marked).map(|(m, r)| (AnyMap::Three(m), r))?,
        };
        if !report.is_null() {
            *non_null_mut(report, "report")? = fit_report(&r);
        }
        handle.set_map(refined);
        Ok(())
    })
}

fn refine<const D: usize>(m: &SplineMap<D>, marked: &[usize]) -> Result<(SplineMap<D>, FitReport)> {
    if marked.is_empty() {
        return m.refine_uniformly();
    }
    for &e in marked {
        check_element(m.element_count(), e)?;
    }
    m.refine(marked)
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
        let raw = if options.is_null() {
            igaparam_validity_options_default()
        } else {
            *non_null(options, "options")?
        };
        if raw.max_depth > 12 || !(2..=64).contains(&raw.samples) {
            return Err(Error::invalid(format!(
                "options: max_depth = {} (at most 12), samples = {} (2 to 64)",
                raw.max_depth, raw.samples
            ))
            .into());
        }
        let opts = ValidityOptions {
            max_depth: raw.max_depth,
            samples: raw.samples as usize,
        };
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
        *out = igaparam_validity_report {
            certified_positive: v.certified_positive as i32,
            uncertified: v.uncertified,
            det_lower_bound: v.det_lower_bound,
            min_quality: v.min_quality,
            mean_quality: v.mean_quality,
            histogram: v.histogram,
        };
        Ok(())
    })
}

/// Writes the map sampled on `samples^d` sub-cells per element (`samples` from 1 to 32) to a VTK
/// XML unstructured grid (`.vtu`) at `path`: quads (2D) or hexahedra (3D) at the physical
/// positions, point data `quality` (q_S) and `det` (det J_S), cell data `level` and `element`.
#[no_mangle]
pub extern "C" fn igaparam_spline_write_vtu(
    spline: *const igaparam_spline,
    path: *const c_char,
    samples: u32,
) -> igaparam_status {
    run("igaparam_spline_write_vtu", || {
        let m = map(spline)?;
        if !(1..=32).contains(&samples) {
            return Err(Error::invalid(format!("samples = {samples} is not in 1..=32")).into());
        }
        let path = c_path(path, "path")?;
        let grid = with_map!(m, m => m.to_grid(samples as usize));
        crate::io::vtu::write(path, &grid)?;
        Ok(())
    })
}

/// Writes the map to G+Smo XML at `path` (a `THBSpline2`/`THBSpline3` geometry over a
/// `THBSplineBasis2`/`3`, readable by G+Smo's `gsReadFile` and by `igaparam_spline_read_gismo`).
#[no_mangle]
pub extern "C" fn igaparam_spline_write_gismo(
    spline: *const igaparam_spline,
    path: *const c_char,
) -> igaparam_status {
    run("igaparam_spline_write_gismo", || {
        let m = map(spline)?;
        let path = c_path(path, "path")?;
        with_map!(m, m => m.write_gismo(path))?;
        Ok(())
    })
}
