//! The spline handle: the cubic THB-spline map S: [0,1]^d → Ω fitted to a built domain's T-mesh,
//! or read from G+Smo XML, and every query a host solver needs (values, Jacobians, mean ratio,
//! inverse, basis functions at a point, Bézier extraction, control points), h-refinement,
//! certified validity and output.

use std::ffi::c_char;

use super::domain::igaparam_domain;
use super::ffi::{
    c_path, check_capacity, non_null_mut, optional_out, run, slice, slice_mut, write_optional,
    Failure,
};
use super::handle::{acquire, handle_type, into_raw, release, Guarded, Held};
use super::{igaparam_fit_report, igaparam_status};
use crate::error::{Error, Result};
use crate::spline::{
    FitRecord, FitReport, SplineMap, SplineSpace, ValidityOptions, ValidityReport,
};

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
            $crate::capi::spline::AnyMap::Two($m) => $body,
            $crate::capi::spline::AnyMap::Three($m) => $body,
        }
    };
}

// After `with_map`, which the per-query files use.
mod adapt;
mod fit_with;
mod quality_bound;
mod query;
mod refit;
mod sensitivity;
mod validity;
pub use adapt::*;
pub use fit_with::*;
pub use query::*;
pub use refit::*;
pub use sensitivity::*;
pub use validity::*;

/// A cubic truncated hierarchical B-spline (THB) map `S: [0,1]^d → Ω`, d = 2 or 3 (opaque).
/// Create with `igaparam_spline_fit_domain` or `igaparam_spline_read_gismo`, release with
/// `igaparam_spline_free`. Parametric points are `d` doubles in [0,1]^d, physical points `d`
/// doubles; arrays of points are flat, `n × d` (x0 y0 x1 y1 ... in 2D). One call at a time
/// (see `IGAPARAM_STATUS_BUSY`).
#[allow(rustdoc::broken_intra_doc_links)]
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

/// The error of a spline and a domain of different dimensions.
fn dimension_mismatch(map: &AnyMap) -> Failure {
    let d = dim(map);
    Error::invalid(format!("the spline is {d}D and the domain {}D", 5 - d)).into()
}

fn dim(map: &AnyMap) -> usize {
    match map {
        AnyMap::Two(_) => 2,
        AnyMap::Three(_) => 3,
    }
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

/// Reads a THB-spline map written by `igaparam_spline_write_gismo` or by G+Smo (G+Smo XML, a
/// cubic `THBSpline2` or `THBSpline3` geometry whose level-0 knots are clamped and uniform with
/// 2^s spans; its tree as the file gives it, balanced or not) from `path` (NUL-terminated UTF-8)
/// and writes the new handle to `*out`. Fails with `IGAPARAM_STATUS_IO` if the file cannot be read or holds no
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
#[allow(rustdoc::broken_intra_doc_links)]
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
#[allow(rustdoc::broken_intra_doc_links)]
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
        write_optional(report, igaparam_fit_report::from(&r));
        handle.set_map(refined);
        Ok(())
    })
}

fn refine<const D: usize>(m: &SplineMap<D>, marked: &[usize]) -> Result<(SplineMap<D>, FitReport)> {
    if marked.is_empty() {
        return m.refine_uniformly();
    }
    // SplineMap::refine checks the indices (range, repeats) and names their positions.
    m.refine(marked)
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
