//! The domain handle: a planar domain bounded by four curves, its adapted and optimized T-mesh
//! parameterization, and read-back of that T-mesh.

use std::ffi::{c_char, c_int, c_void, CStr};
use std::path::Path;

use super::boundary::{check_capacity, non_null, non_null_mut, run, slice, slice_mut, Failure};
use super::{igaparam_progress_fn, igaparam_stage, igaparam_status};
use crate::boundary::{BoundaryLoop2, Coastline, Curve2, Point2};
use crate::domain::{PlanarDomain, PlanarOptions};
use crate::error::{check_finite, Error, Result};

/// A planar domain bounded by four curves, and once built its T-mesh parameterization (opaque).
/// Create with `igaparam_domain_new_from_file` or `igaparam_domain_new_from_polylines`, build with
/// `igaparam_domain_build`, release with `igaparam_domain_free`.
pub struct igaparam_domain {
    boundary: BoundaryLoop2,
    built: Option<PlanarDomain>,
}

/// Options of `igaparam_domain_build`; get the defaults from `igaparam_domain_options_default`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_domain_options {
    /// Boundary tolerance, positive: a boundary cell edge is refined while the triangle formed by
    /// its end images and the image of its parametric midpoint has an area above
    /// `tolerance × (bounding-box diagonal)²` (default 1e-5).
    pub tolerance: f64,
    /// Level of the initial uniform refinement (default 2).
    pub min_level: u32,
    /// Deepest level of the adaptation, at least `min_level` and at most 16 (default 9).
    pub max_level: u32,
    /// Largest number of optimization sweeps (default 200).
    pub max_sweeps: u32,
    /// Worker threads, at most 4096; 0 (default) uses one per core.
    pub threads: u32,
    /// Progress callback, or NULL (default). Called with `IGAPARAM_STAGE_OPTIMIZATION`, `done`
    /// sweeps so far and `total` 0; returning non-zero cancels the build.
    pub progress: igaparam_progress_fn,
    /// Passed to `progress` as its first argument.
    pub progress_user: *mut c_void,
}

/// What `igaparam_domain_build` did. Quality is the inverse mean distortion of a cell against its
/// parametric (square) cell: 1 is a square, 0 an inverted cell.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct igaparam_domain_report {
    /// Cells of the T-mesh.
    pub cells: usize,
    /// Vertices of the T-mesh, hanging ones included.
    pub vertices: usize,
    /// Deepest level of a cell.
    pub max_level: u32,
    /// Largest boundary error (triangle area over the squared bounding-box diagonal).
    pub boundary_error: f64,
    /// Invalid cells (det J <= 0 somewhere) after the Coons placement.
    pub invalid_after_placement: usize,
    /// Invalid cells after the optimization; 0 for a usable parameterization.
    pub invalid_cells: usize,
    /// Smallest cell quality.
    pub min_quality: f64,
    /// Mean cell quality.
    pub mean_quality: f64,
    /// Optimization sweeps performed.
    pub sweeps: u32,
    /// Wall-clock seconds of the call.
    pub seconds: f64,
}

/// The default domain options.
#[no_mangle]
pub extern "C" fn igaparam_domain_options_default() -> igaparam_domain_options {
    let d = PlanarOptions::default();
    igaparam_domain_options {
        tolerance: d.tolerance,
        min_level: d.min_level as u32,
        max_level: d.max_level as u32,
        max_sweeps: d.max_sweeps,
        threads: d.threads as u32,
        progress: None,
        progress_user: std::ptr::null_mut(),
    }
}

fn planar_options(o: &igaparam_domain_options) -> Result<PlanarOptions> {
    if !o.tolerance.is_finite() {
        return Err(Error::new(
            crate::error::ErrorKind::NotFinite,
            format!("tolerance is {}, it must be finite", o.tolerance),
        ));
    }
    if o.tolerance <= 0.0 {
        return Err(Error::invalid(format!(
            "tolerance = {} must be positive",
            o.tolerance
        )));
    }
    if o.min_level > o.max_level || o.max_level > 16 {
        return Err(Error::invalid(format!(
            "levels must satisfy min_level <= max_level <= 16, got min_level = {}, max_level = {}",
            o.min_level, o.max_level
        )));
    }
    if o.threads > 4096 {
        return Err(Error::invalid(format!(
            "threads = {} is above the limit of 4096",
            o.threads
        )));
    }
    Ok(PlanarOptions {
        tolerance: o.tolerance,
        min_level: o.min_level as u8,
        max_level: o.max_level as u8,
        max_sweeps: o.max_sweeps,
        threads: o.threads as usize,
        ..PlanarOptions::default()
    })
}

/// A path from a NUL-terminated C string that must not be NULL.
fn c_path<'a>(ptr: *const c_char, name: &'static str) -> std::result::Result<&'a Path, Failure> {
    non_null(ptr, name)?;
    // SAFETY: `ptr` is not NULL and the caller passes a NUL-terminated string (documented
    // contract) that outlives the call.
    let s = unsafe { CStr::from_ptr(ptr) };
    let s = s
        .to_str()
        .map_err(|_| Error::invalid(format!("`{name}` is not valid UTF-8")))?;
    if s.is_empty() {
        return Err(Error::invalid(format!("`{name}` is empty")).into());
    }
    Ok(Path::new(s))
}

fn new_handle(boundary: BoundaryLoop2, out: &mut *mut igaparam_domain) {
    *out = Box::into_raw(Box::new(igaparam_domain {
        boundary,
        built: None,
    }));
}

/// Creates a domain from a boundary file, chosen by its extension (case-insensitive):
///
/// - `.xml`: a G+Smo XML B-rep of four B-spline curves;
/// - `.txt`: a coastline (points with four marked corners).
///
/// `path` is a NUL-terminated UTF-8 path. `out` receives the new handle, to be released with
/// `igaparam_domain_free`. Errors: `IGAPARAM_STATUS_IO` when the file cannot be read or parsed
/// (the message says why), `IGAPARAM_STATUS_INVALID_ARGUMENT` for another extension or when the
/// curves do not make a closed loop with convex corners.
#[no_mangle]
pub extern "C" fn igaparam_domain_new_from_file(
    path: *const c_char,
    out: *mut *mut igaparam_domain,
) -> igaparam_status {
    run("igaparam_domain_new_from_file", || {
        let out = non_null_mut(out, "out")?;
        let path = c_path(path, "path")?;
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase());
        let boundary = match ext.as_deref() {
            Some("xml") => BoundaryLoop2::from_gismo_file(path)?,
            Some("txt") => {
                let coast = Coastline::read(path)?;
                BoundaryLoop2::from_coastline(&coast)
                    .map_err(|e| Error::new(e.kind, format!("{}: {}", path.display(), e.message)))?
            }
            _ => {
                return Err(Error::invalid(format!(
                    "{}: unknown extension; use .xml (G+Smo B-rep) or .txt (coastline)",
                    path.display()
                ))
                .into())
            }
        };
        new_handle(boundary, out);
        Ok(())
    })
}

/// Creates a domain bounded by four polylines.
///
/// - `counts`: 4 entries; `counts[i]` is the number of points of polyline i (at least 2).
/// - `points`: 4 pointers; `points[i]` holds `counts[i] × 2` doubles (x0 y0 x1 y1 ...).
/// - `out`: receives the new handle, to be released with `igaparam_domain_free`.
///
/// The polylines may be given in any order and direction: they are chained end to end into a
/// counter-clockwise loop, the first one becoming the side u = 0. Errors:
/// `IGAPARAM_STATUS_NOT_FINITE` for a NaN or infinite coordinate, `IGAPARAM_STATUS_INVALID_ARGUMENT`
/// for a polyline of fewer than two distinct points, a loop that does not close, one of zero area
/// or a corner whose interior angle reaches 180 degrees. The arrays are copied.
#[no_mangle]
pub extern "C" fn igaparam_domain_new_from_polylines(
    counts: *const usize,
    points: *const *const f64,
    out: *mut *mut igaparam_domain,
) -> igaparam_status {
    run("igaparam_domain_new_from_polylines", || {
        let out = non_null_mut(out, "out")?;
        let counts = slice(counts, 4, "counts")?;
        let points = slice(points, 4, "points")?;
        let mut curves = Vec::with_capacity(4);
        for i in 0..4 {
            let len = counts[i]
                .checked_mul(2)
                .ok_or_else(|| Error::invalid(format!("counts[{i}] is too large")))?;
            if counts[i] < 2 {
                return Err(Error::invalid(format!(
                    "counts[{i}] = {}, a polyline needs at least 2 points",
                    counts[i]
                ))
                .into());
            }
            let xy = slice(points[i], len, "points[i]")?;
            check_finite(&format!("points[{i}]"), xy)?;
            let pts: Vec<Point2> = xy.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
            curves.push(
                Curve2::polyline(pts)
                    .map_err(|e| Error::new(e.kind, format!("polyline {i}: {}", e.message)))?,
            );
        }
        new_handle(BoundaryLoop2::from_curves(curves)?, out);
        Ok(())
    })
}

/// Releases a domain. NULL is a no-op.
#[no_mangle]
pub extern "C" fn igaparam_domain_free(domain: *mut igaparam_domain) {
    if !domain.is_null() {
        // SAFETY: `domain` came from `igaparam_domain_new_*` (Box::into_raw) and is released once.
        drop(unsafe { Box::from_raw(domain) });
    }
}

/// The built domain, or an error if `igaparam_domain_build` has not succeeded yet.
fn built<'a>(domain: *const igaparam_domain) -> std::result::Result<&'a PlanarDomain, Failure> {
    non_null(domain, "domain")?.built.as_ref().ok_or_else(|| {
        Error::invalid("the domain has not been built: call igaparam_domain_build first").into()
    })
}

/// Adapts a T-mesh to the boundary (refining boundary cells until `options.tolerance` or
/// `options.max_level` is met), places its vertices (boundary ones on the curves, inner ones by
/// the Coons patch) and optimizes them; the result is kept in the handle, replacing that of an
/// earlier build. `options` may be NULL for the defaults; `report` may be NULL. On any error or
/// cancellation the handle is unchanged (an earlier build stays) and `*report` is not written.
#[no_mangle]
pub extern "C" fn igaparam_domain_build(
    domain: *mut igaparam_domain,
    options: *const igaparam_domain_options,
    report: *mut igaparam_domain_report,
) -> igaparam_status {
    run("igaparam_domain_build", || {
        let d = non_null_mut(domain, "domain")?;
        let raw = if options.is_null() {
            igaparam_domain_options_default()
        } else {
            *non_null(options, "options")?
        };
        let opts = planar_options(&raw)?;
        let mut progress = |done: usize, total: usize| match raw.progress {
            None => true,
            Some(f) => {
                // SAFETY: the caller supplied a valid callback and its user pointer.
                unsafe {
                    f(
                        raw.progress_user,
                        igaparam_stage::IGAPARAM_STAGE_OPTIMIZATION,
                        done,
                        total,
                    ) == 0
                }
            }
        };
        let (planar, r) = PlanarDomain::build(d.boundary.clone(), &opts, &mut progress)?;
        d.built = Some(planar);
        if !report.is_null() {
            *non_null_mut(report, "report")? = igaparam_domain_report {
                cells: r.cells,
                vertices: r.vertices,
                max_level: r.max_level as u32,
                boundary_error: r.boundary_error,
                invalid_after_placement: r.invalid_after_placement,
                invalid_cells: r.invalid_cells,
                min_quality: r.min_quality,
                mean_quality: r.mean_quality,
                sweeps: r.sweeps,
                seconds: r.seconds,
            };
        }
        Ok(())
    })
}

/// Writes the number of vertices of the built T-mesh (hanging ones included) to `*out`.
/// Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built.
#[no_mangle]
pub extern "C" fn igaparam_domain_vertex_count(
    domain: *const igaparam_domain,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_domain_vertex_count", || {
        let n = built(domain)?.mesh().vertex_count();
        *non_null_mut(out, "out")? = n;
        Ok(())
    })
}

/// Writes the number of cells of the built T-mesh to `*out`. Fails with
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built.
#[no_mangle]
pub extern "C" fn igaparam_domain_cell_count(
    domain: *const igaparam_domain,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_domain_cell_count", || {
        let n = built(domain)?.mesh().cell_count();
        *non_null_mut(out, "out")? = n;
        Ok(())
    })
}

/// Copies the vertices of the built T-mesh: `parametric` receives their (u, v) in [0,1]², and
/// `physical` their (x, y) in the domain, each `num_vertices × 2` doubles (u0 v0 u1 v1 ...).
/// Either may be NULL to skip it; `len_each` is the number of doubles each non-NULL buffer holds
/// (at least `2 × num_vertices`). Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has
/// not been built.
#[no_mangle]
pub extern "C" fn igaparam_domain_copy_vertices(
    domain: *const igaparam_domain,
    parametric: *mut f64,
    physical: *mut f64,
    len_each: usize,
) -> igaparam_status {
    run("igaparam_domain_copy_vertices", || {
        let d = built(domain)?;
        let needed = 2 * d.mesh().vertex_count();
        if !parametric.is_null() {
            check_capacity("parametric", len_each, needed)?;
        }
        if !physical.is_null() {
            check_capacity("physical", len_each, needed)?;
        }
        if !parametric.is_null() {
            let out = slice_mut(parametric, len_each, "parametric")?;
            for (o, p) in out.chunks_mut(2).zip(d.mesh().parametric()) {
                o.copy_from_slice(&p);
            }
        }
        if !physical.is_null() {
            let out = slice_mut(physical, len_each, "physical")?;
            for (o, p) in out.chunks_mut(2).zip(d.positions()) {
                o.copy_from_slice(p);
            }
        }
        Ok(())
    })
}

/// Copies the quality of every cell of the built T-mesh into `quality` (`len` doubles, at least
/// `num_cells`): the inverse mean distortion against its parametric cell, in (0, 1], or 0 for a
/// cell with det J <= 0 somewhere. Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain
/// has not been built.
#[no_mangle]
pub extern "C" fn igaparam_domain_copy_cell_quality(
    domain: *const igaparam_domain,
    quality: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_domain_copy_cell_quality", || {
        let d = built(domain)?;
        let q = d.quality();
        check_capacity("quality", len, q.len())?;
        slice_mut(quality, len, "quality")?[..q.len()].copy_from_slice(q);
        Ok(())
    })
}

/// Copies the cells of the built T-mesh, in the order of their qualities:
///
/// - `levels`: the refinement level of every cell (`num_cells` bytes), or NULL to skip it;
/// - `bounds`: the parametric box of every cell, `num_cells × 4` doubles `u0 v0 u1 v1` (lower
///   then upper corner), or NULL to skip it.
///
/// `len` is the number of cells the buffers hold (`levels` has `len` bytes, `bounds` `4 × len`
/// doubles), at least `num_cells`. Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has
/// not been built.
#[no_mangle]
pub extern "C" fn igaparam_domain_copy_cells(
    domain: *const igaparam_domain,
    levels: *mut u8,
    bounds: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_domain_copy_cells", || {
        let mesh = built(domain)?.mesh();
        let n = mesh.cell_count();
        check_capacity("levels/bounds (cells)", len, n)?;
        if !levels.is_null() {
            let out = slice_mut(levels, len, "levels")?;
            for (c, o) in out[..n].iter_mut().enumerate() {
                *o = mesh.cell_level(c);
            }
        }
        if !bounds.is_null() {
            let total = len
                .checked_mul(4)
                .ok_or_else(|| Error::invalid("len is too large"))?;
            let out = slice_mut(bounds, total, "bounds")?;
            for (c, o) in out.chunks_mut(4).take(n).enumerate() {
                let (lo, hi) = mesh.cell_bounds(c);
                o.copy_from_slice(&[lo[0], lo[1], hi[0], hi[1]]);
            }
        }
        Ok(())
    })
}

/// Writes the built T-mesh to a VTK XML unstructured grid (`.vtu`) at `path` (NUL-terminated
/// UTF-8): one polygon per cell through its corners and hanging vertices, at the physical
/// positions; point data `parametric` (u, v, 0), cell data `quality` and `level`. Fails with
/// `IGAPARAM_STATUS_IO` if the file cannot be written, `IGAPARAM_STATUS_INVALID_ARGUMENT` if the
/// domain has not been built.
#[no_mangle]
pub extern "C" fn igaparam_domain_write_vtu(
    domain: *const igaparam_domain,
    path: *const c_char,
) -> igaparam_status {
    run("igaparam_domain_write_vtu", || {
        let d = built(domain)?;
        let path = c_path(path, "path")?;
        crate::io::vtu::write(path, &d.to_grid())?;
        Ok(())
    })
}

/// Writes to `*out` 1 if the domain has been built (by a successful `igaparam_domain_build`),
/// else 0.
#[no_mangle]
pub extern "C" fn igaparam_domain_is_built(
    domain: *const igaparam_domain,
    out: *mut c_int,
) -> igaparam_status {
    run("igaparam_domain_is_built", || {
        let b = non_null(domain, "domain")?.built.is_some();
        *non_null_mut(out, "out")? = b as c_int;
        Ok(())
    })
}
