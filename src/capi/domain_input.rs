//! The boundaries of domains from the host's data: files, polylines, triangulated faces, and
//! B-spline/NURBS curves and surfaces given as arrays; the constructors of the domain handle.
//! The boundary readers here also serve `igaparam_domain_set_boundary_*`.

use std::ffi::c_char;
use std::path::Path;

use super::domain::{igaparam_domain, DomainData};
use super::ffi::{c_path, non_null_mut, run, slice, Failure};
use super::igaparam_status;
use crate::boundary::{
    BSplineCurve, BSplineSurface, BoundaryLoop2, Coastline, CubeFaces, Curve2, Point2,
    SolidBoundary, TriMesh, CUBE_FACE_NAMES,
};
use crate::error::{check_finite, Error, Result};

/// A B-spline or NURBS curve of the plane given by arrays, read (and copied) by the functions
/// that take it. The curve is `C(t) = Σ w_i N_i(t) P_i / Σ w_i N_i(t)` over its knot domain
/// `[knots[degree], knots[control_point_count]]` (all `w_i` = 1 without weights).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_curve {
    /// Polynomial degree p, at least 1.
    pub degree: u32,
    /// Number of knots: `control_point_count + degree + 1`.
    pub knot_count: usize,
    /// `knot_count` knots: finite, non-decreasing, none repeated more than p + 1 times.
    pub knots: *const f64,
    /// Number of control points n.
    pub control_point_count: usize,
    /// `n × 2` doubles (x0 y0 x1 y1 ...), finite.
    pub control_points: *const f64,
    /// `n` positive finite weights (a NURBS curve), or NULL (a B-spline curve).
    pub weights: *const f64,
}

/// A tensor-product B-spline or NURBS surface in 3D given by arrays, read (and copied) by the
/// functions that take it. Control point `(i, j)` (i along u, j along v) is number
/// `i + j × control_point_count_u`: the first parameter runs fastest, as in G+Smo.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_surface {
    /// Degree in u, at least 1.
    pub degree_u: u32,
    /// Degree in v, at least 1.
    pub degree_v: u32,
    /// Number of knots in u: `control_point_count_u + degree_u + 1`.
    pub knot_count_u: usize,
    /// `knot_count_u` knots in u (finite, non-decreasing).
    pub knots_u: *const f64,
    /// Number of knots in v: `control_point_count_v + degree_v + 1`.
    pub knot_count_v: usize,
    /// `knot_count_v` knots in v (finite, non-decreasing).
    pub knots_v: *const f64,
    /// Control points in u, n_u.
    pub control_point_count_u: usize,
    /// Control points in v, n_v.
    pub control_point_count_v: usize,
    /// `n_u × n_v × 3` doubles (x y z of point (0, 0), then (1, 0), ...), finite.
    pub control_points: *const f64,
    /// `n_u × n_v` positive finite weights in the order of the control points (a NURBS
    /// surface), or NULL (a B-spline surface).
    pub weights: *const f64,
}

/// `e` with its message prefixed by `what`.
fn about(what: &str, e: Error) -> Error {
    Error::new(e.kind, format!("{what}: {}", e.message))
}

/// The knots of one direction, checked against the number of control points and the degree.
fn knots_of<'a>(
    what: &str,
    degree: u32,
    knots: (*const f64, usize),
    points: usize,
    name: &'static str,
) -> std::result::Result<(usize, &'a [f64]), Failure> {
    if degree == 0 {
        return Err(Error::invalid(format!(
            "{what}: degree 0 is not a continuous boundary; the degree must be at least 1"
        ))
        .into());
    }
    let degree = degree as usize;
    let needed = points.checked_add(degree + 1);
    if needed != Some(knots.1) {
        return Err(Error::invalid(format!(
            "{what}: {} knots for {points} control points of degree {degree}; {} are needed \
             (control points + degree + 1)",
            knots.1,
            needed.map_or("more than addressable".into(), |n| n.to_string())
        ))
        .into());
    }
    Ok((degree, slice(knots.0, knots.1, name)?))
}

/// The control points (`width` values each) and weights of a geometry with `count` points
/// (their values are checked by the geometry's constructor).
fn points_of<'a>(
    what: &str,
    count: usize,
    width: usize,
    (points, weights): (*const f64, *const f64),
) -> std::result::Result<(&'a [f64], Option<&'a [f64]>), Failure> {
    let len = count
        .checked_mul(width)
        .ok_or_else(|| Error::invalid(format!("{what}: {count} control points are too many")))?;
    let values = slice(points, len, "control_points")?;
    let weights = if weights.is_null() {
        None
    } else {
        Some(slice(weights, count, "weights")?)
    };
    Ok((values, weights))
}

/// Curve `i` of the C array.
fn curve_from_c(c: &igaparam_curve, i: usize) -> std::result::Result<Curve2, Failure> {
    let what = format!("curves[{i}]");
    let n = c.control_point_count;
    let (degree, knots) = knots_of(&what, c.degree, (c.knots, c.knot_count), n, "knots")?;
    let (points, weights) = points_of(&what, n, 2, (c.control_points, c.weights))?;
    let curve = BSplineCurve::new(
        degree,
        knots.to_vec(),
        2,
        points.to_vec(),
        weights.map(<[f64]>::to_vec),
    )
    .and_then(Curve2::spline)
    .map_err(|e| about(&what, e))?;
    Ok(curve)
}

/// Surface `i` of the C array.
fn surface_from_c(s: &igaparam_surface, i: usize) -> std::result::Result<BSplineSurface, Failure> {
    let what = format!("surfaces[{i}]");
    let (nu, nv) = (s.control_point_count_u, s.control_point_count_v);
    let u = knots_of(
        &what,
        s.degree_u,
        (s.knots_u, s.knot_count_u),
        nu,
        "knots_u",
    )?;
    let v = knots_of(
        &what,
        s.degree_v,
        (s.knots_v, s.knot_count_v),
        nv,
        "knots_v",
    )?;
    let count = nu.checked_mul(nv).ok_or_else(|| {
        Error::invalid(format!("{what}: {nu} × {nv} control points are too many"))
    })?;
    let (points, weights) = points_of(&what, count, 3, (s.control_points, s.weights))?;
    let surface = BSplineSurface::new(
        (u.0, u.1.to_vec()),
        (v.0, v.1.to_vec()),
        3,
        points.to_vec(),
        weights.map(<[f64]>::to_vec),
    )
    .map_err(|e| about(&what, e))?;
    Ok(surface)
}

/// Checks that `count` geometries of a boundary were given where `needed` are.
fn check_count(count: usize, needed: usize, what: &str) -> Result<()> {
    if count != needed {
        return Err(Error::invalid(format!(
            "{count} {what} given; the boundary of a {} has {needed}",
            if needed == 4 {
                "planar domain"
            } else {
                "solid"
            }
        )));
    }
    Ok(())
}

/// The planar boundary of `count` (= 4) curves.
pub(super) fn curves_boundary(
    count: usize,
    curves: *const igaparam_curve,
) -> std::result::Result<BoundaryLoop2, Failure> {
    check_count(count, 4, "curves")?;
    let curves = slice(curves, 4, "curves")?;
    let curves = curves
        .iter()
        .enumerate()
        .map(|(i, c)| curve_from_c(c, i))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    Ok(BoundaryLoop2::from_curves(curves)?)
}

/// The solid boundary of `count` (= 6) surfaces.
pub(super) fn surfaces_boundary(
    count: usize,
    surfaces: *const igaparam_surface,
) -> std::result::Result<SolidBoundary, Failure> {
    check_count(count, 6, "surfaces")?;
    let surfaces = slice(surfaces, 6, "surfaces")?;
    let surfaces = surfaces
        .iter()
        .enumerate()
        .map(|(i, s)| surface_from_c(s, i))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    Ok(SolidBoundary::from_surfaces(surfaces)?)
}

/// The planar boundary of a file: `.xml` (G+Smo, four curves) or `.txt` (coastline).
pub(super) fn planar_file_boundary(path: &Path) -> Result<BoundaryLoop2> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("xml") => BoundaryLoop2::from_gismo_file(path),
        Some("txt") => {
            let coast = Coastline::read(path)?;
            BoundaryLoop2::from_coastline(&coast).map_err(|e| about(&path.display().to_string(), e))
        }
        _ => Err(Error::invalid(format!(
            "{}: unknown extension; use .xml (G+Smo B-rep) or .txt (coastline)",
            path.display()
        ))),
    }
}

/// The planar boundary of four polylines (`counts`, `points`: 4 entries each).
pub(super) fn polylines_boundary(
    counts: *const usize,
    points: *const *const f64,
) -> std::result::Result<BoundaryLoop2, Failure> {
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
        curves.push(Curve2::polyline(pts).map_err(|e| about(&format!("polyline {i}"), e))?);
    }
    Ok(BoundaryLoop2::from_curves(curves)?)
}

/// The solid boundary of a `.xml` B-rep or a folder of faces, scaled by `scale` (NULL or 3
/// factors).
pub(super) fn solid_file_boundary(
    path: &Path,
    scale: *const f64,
) -> std::result::Result<SolidBoundary, Failure> {
    let scale = if scale.is_null() {
        None
    } else {
        let f = slice(scale, 3, "scale")?;
        Some([f[0], f[1], f[2]])
    };
    Ok(SolidBoundary::from_file_scaled(path, scale)?)
}

/// The solid boundary of six triangulated faces (6 entries in each array).
pub(super) fn triangulations_boundary(
    vertex_counts: *const usize,
    xyz: *const *const f64,
    triangle_counts: *const usize,
    triangles: *const *const u32,
) -> std::result::Result<SolidBoundary, Failure> {
    let vertex_counts = slice(vertex_counts, 6, "vertex_counts")?;
    let triangle_counts = slice(triangle_counts, 6, "triangle_counts")?;
    let xyz = slice(xyz, 6, "xyz")?;
    let triangles = slice(triangles, 6, "triangles")?;
    let mut faces = Vec::with_capacity(6);
    for f in 0..6 {
        let name = CUBE_FACE_NAMES[f];
        let nv = vertex_counts[f]
            .checked_mul(3)
            .ok_or_else(|| Error::invalid(format!("vertex_counts[{f}] is too large")))?;
        let nt = triangle_counts[f]
            .checked_mul(3)
            .ok_or_else(|| Error::invalid(format!("triangle_counts[{f}] is too large")))?;
        let points = slice(xyz[f], nv, "xyz[f]")?;
        check_finite(&format!("xyz[{f}] ({name})"), points)?;
        let tri = slice(triangles[f], nt, "triangles[f]")?;
        let mesh = TriMesh::new(
            points.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(),
            tri.chunks_exact(3)
                .map(|t| [t[0] as usize, t[1] as usize, t[2] as usize])
                .collect(),
        )
        .map_err(|e| about(&format!("face {name}"), e))?;
        faces.push(mesh);
    }
    let cube = CubeFaces {
        faces: faces
            .try_into()
            .map_err(|_| Error::invalid("six faces are needed"))?,
    };
    Ok(SolidBoundary::from_cube_faces(&cube)?)
}

/// Runs the body of constructor `function`: writes the handle of the domain it makes to
/// `*out`.
fn construct(
    function: &str,
    out: *mut *mut igaparam_domain,
    body: impl FnOnce() -> std::result::Result<DomainData, Failure>,
) -> igaparam_status {
    run(function, || {
        let out = non_null_mut(out, "out")?;
        let domain = body()?;
        *out = super::handle::into_raw::<igaparam_domain>(domain);
        Ok(())
    })
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
    construct("igaparam_domain_new_from_file", out, || {
        let boundary = planar_file_boundary(c_path(path, "path")?)?;
        Ok(DomainData::Planar(boundary, None))
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
/// for a polyline of fewer than two distinct points, a loop that does not close, one of zero area,
/// a loop that crosses or touches itself (the message names the two polylines and the point) or
/// a corner whose interior angle reaches 180 degrees. The arrays are copied.
#[no_mangle]
pub extern "C" fn igaparam_domain_new_from_polylines(
    counts: *const usize,
    points: *const *const f64,
    out: *mut *mut igaparam_domain,
) -> igaparam_status {
    construct("igaparam_domain_new_from_polylines", out, || {
        Ok(DomainData::Planar(
            polylines_boundary(counts, points)?,
            None,
        ))
    })
}

/// Creates a domain bounded by four B-spline or NURBS curves given as arrays (see
/// `igaparam_curve`).
///
/// - `count`: the number of curves, 4;
/// - `curves`: `count` curve descriptions;
/// - `out`: receives the new handle, to be released with `igaparam_domain_free`.
///
/// The curves are read as `igaparam_domain_new_from_file` reads those of a G+Smo file (a domain
/// made from the same curves is the same, bit for bit): in any order and direction, chained end
/// to end into a counter-clockwise loop, the first one becoming the side u = 0. Errors:
/// `IGAPARAM_STATUS_NULL_ARGUMENT` for a NULL array (weights may be NULL),
/// `IGAPARAM_STATUS_NOT_FINITE` for a NaN or infinite knot, coordinate or weight,
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` for a count other than 4, a degree of 0, a knot count
/// other than control points + degree + 1, decreasing knots or a knot repeated more than
/// degree + 1 times, a weight that is not positive, and curves whose ends do not meet, whose
/// loop encloses no area, crosses or touches itself (the curves' polygons are checked, sampled
/// 16 points per control point) or has a corner whose interior angle reaches 180 degrees (each
/// message names the curves or corner). The arrays are copied.
#[no_mangle]
pub extern "C" fn igaparam_domain_new_from_curves(
    count: usize,
    curves: *const igaparam_curve,
    out: *mut *mut igaparam_domain,
) -> igaparam_status {
    construct("igaparam_domain_new_from_curves", out, || {
        Ok(DomainData::Planar(curves_boundary(count, curves)?, None))
    })
}

/// Creates a solid from a boundary file or folder:
///
/// - a `.xml` file: a G+Smo XML B-rep of six B-spline surfaces (found and oriented from their
///   shared edges and corners);
/// - a folder: six triangulated faces `xmin, xmax, ymin, ymax, zmin, zmax` (`.obj`), each mapped
///   onto its face of the unit cube by Floater's mean-value parameterization.
///
/// `path` is a NUL-terminated UTF-8 path. `out` receives the new handle, to be released with
/// `igaparam_domain_free`. Errors: `IGAPARAM_STATUS_IO` when a file cannot be read or parsed,
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` for another kind of path, `IGAPARAM_STATUS_INVALID_MESH` when
/// the surfaces do not share their edges and corners (the message says which). Same as
/// `igaparam_domain_new_solid_from_file_scaled` with `scale` NULL.
#[no_mangle]
pub extern "C" fn igaparam_domain_new_solid_from_file(
    path: *const c_char,
    out: *mut *mut igaparam_domain,
) -> igaparam_status {
    construct("igaparam_domain_new_solid_from_file", out, || {
        let boundary = solid_file_boundary(c_path(path, "path")?, std::ptr::null())?;
        Ok(DomainData::Solid(Box::new(boundary), None))
    })
}

/// Creates a solid from a boundary file or folder as `igaparam_domain_new_solid_from_file`,
/// with every coordinate of the input multiplied by its axis' factor first: `scale` is NULL (no
/// scaling) or points to 3 doubles `fx, fy, fz`, each finite and positive. The vertices of
/// triangulated faces, or the control points of a B-rep's surfaces (exact for B-splines and
/// NURBS), are scaled before the faces are parameterized; the solid, its T-mesh and its spline
/// map are in the scaled coordinates. Use it for data whose axes are in different units (a
/// terrain in degrees and kilometres, say): Floater's map measures angles in the coordinates it
/// is given, so the T-mesh depends on them, not only on the solid's figure.
///
/// Errors: those of `igaparam_domain_new_solid_from_file`, and
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` for a factor that is NaN, infinite, zero or negative
/// (checked before any file is read). `*out` is left unchanged on error.
#[no_mangle]
pub extern "C" fn igaparam_domain_new_solid_from_file_scaled(
    path: *const c_char,
    scale: *const f64,
    out: *mut *mut igaparam_domain,
) -> igaparam_status {
    construct("igaparam_domain_new_solid_from_file_scaled", out, || {
        let boundary = solid_file_boundary(c_path(path, "path")?, scale)?;
        Ok(DomainData::Solid(Box::new(boundary), None))
    })
}

/// Creates a solid bounded by six triangulated faces, in the order `xmin, xmax, ymin, ymax, zmin,
/// zmax` of the unit cube's faces.
///
/// - `vertex_counts`, `triangle_counts`: 6 entries each;
/// - `xyz`: 6 pointers; `xyz[f]` holds `vertex_counts[f] × 3` doubles (x0 y0 z0 x1 ...);
/// - `triangles`: 6 pointers; `triangles[f]` holds `triangle_counts[f] × 3` vertex indices of
///   face f, counting from 0;
/// - `out`: receives the new handle, to be released with `igaparam_domain_free`.
///
/// Each face must be a disk; faces that touch share their edge vertices with identical
/// coordinates, and the vertex shared by three faces is a cube corner. Errors:
/// `IGAPARAM_STATUS_NULL_ARGUMENT` for a NULL array (a face's arrays may be NULL only when
/// empty), `IGAPARAM_STATUS_NOT_FINITE` for a NaN or infinite coordinate,
/// `IGAPARAM_STATUS_INVALID_MESH` for a triangle with an index out of range or a repeated vertex,
/// and for faces that do not match on their edges or corners. The arrays are copied.
#[no_mangle]
pub extern "C" fn igaparam_domain_new_solid_from_triangulations(
    vertex_counts: *const usize,
    xyz: *const *const f64,
    triangle_counts: *const usize,
    triangles: *const *const u32,
    out: *mut *mut igaparam_domain,
) -> igaparam_status {
    construct("igaparam_domain_new_solid_from_triangulations", out, || {
        let boundary = triangulations_boundary(vertex_counts, xyz, triangle_counts, triangles)?;
        Ok(DomainData::Solid(Box::new(boundary), None))
    })
}

/// Creates a solid bounded by six tensor-product B-spline or NURBS surfaces in 3D given as
/// arrays (see `igaparam_surface`).
///
/// - `count`: the number of surfaces, 6;
/// - `surfaces`: `count` surface descriptions;
/// - `out`: receives the new handle, to be released with `igaparam_domain_free`.
///
/// The surfaces are read as `igaparam_domain_new_solid_from_file` reads those of a G+Smo B-rep
/// (a solid made from the same surfaces is the same, bit for bit): their corners are matched
/// into the 8 corners of a cube, opposite surfaces found, each surface oriented onto its cube
/// face, and the surfaces must agree on their shared edges. Errors:
/// `IGAPARAM_STATUS_NULL_ARGUMENT` for a NULL array (weights may be NULL),
/// `IGAPARAM_STATUS_NOT_FINITE` for a NaN or infinite knot, coordinate or weight,
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` for a count other than 6, a degree of 0, knot counts
/// other than control points + degree + 1, decreasing knots, weights that are not positive,
/// `IGAPARAM_STATUS_INVALID_MESH` for surfaces whose corners do not form a cube or that do not
/// share their edges (the messages name the surfaces). The arrays are copied.
#[no_mangle]
pub extern "C" fn igaparam_domain_new_solid_from_surfaces(
    count: usize,
    surfaces: *const igaparam_surface,
    out: *mut *mut igaparam_domain,
) -> igaparam_status {
    construct("igaparam_domain_new_solid_from_surfaces", out, || {
        let boundary = surfaces_boundary(count, surfaces)?;
        Ok(DomainData::Solid(Box::new(boundary), None))
    })
}
