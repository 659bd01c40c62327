//! The domain handle: a planar domain bounded by four curves or a solid bounded by six surfaces,
//! its adapted and optimized T-mesh parameterization, and read-back of that T-mesh.

use std::ffi::{c_char, c_int, c_void, CStr};
use std::path::Path;

use super::boundary::{
    check_capacity, non_null, non_null_mut, optional_out, run, slice_mut, Failure,
};
use super::handle::{acquire, handle_type, release, Guarded, Held, ReleaseWatch};
use super::mesh::call_progress;
use super::spline::AnyMap;
use super::{igaparam_progress_fn, igaparam_stage, igaparam_status};
use crate::boundary::{BoundaryLoop2, SolidBoundary};
use crate::domain::{DomainReport, PlanarDomain, PlanarOptions, SolidDomain, SolidOptions};
use crate::error::{Error, Result};
use crate::io::vtu::UnstructuredGrid;
use crate::spline::{FitRecord, UntangleOptions};

/// A planar domain bounded by four curves or a solid bounded by six surfaces, and once built
/// its T-mesh parameterization (opaque). Create a planar one with
/// `igaparam_domain_new_from_file` or `igaparam_domain_new_from_polylines`, a solid with
/// `igaparam_domain_new_solid_from_file`, `igaparam_domain_new_solid_from_file_scaled` or
/// `igaparam_domain_new_solid_from_triangulations`; build with `igaparam_domain_build`,
/// release with `igaparam_domain_free`. One call at a time (see `IGAPARAM_STATUS_BUSY`).
pub struct igaparam_domain(Guarded<DomainData>);
handle_type!(igaparam_domain, DomainData, "domain");

/// What a domain handle holds: its boundary and, once built, its T-mesh parameterization.
// The handle itself lives on the heap behind the C pointer; the variants' sizes do not matter.
#[allow(clippy::large_enum_variant)]
pub(crate) enum DomainData {
    /// Bounded by four curves.
    Planar(BoundaryLoop2, Option<PlanarDomain>),
    /// Bounded by six surfaces.
    Solid(Box<SolidBoundary>, Option<Box<SolidDomain>>),
}

/// What the read-back functions need of a built domain, whatever its dimension.
struct BuiltView {
    dim: usize,
    vertices: usize,
    parametric: Vec<f64>,
    physical: Vec<f64>,
    levels: Vec<u8>,
    bounds: Vec<f64>,
    corners: Vec<usize>,
}

impl DomainData {
    pub(super) fn dim(&self) -> usize {
        match self {
            DomainData::Planar(..) => 2,
            DomainData::Solid(..) => 3,
        }
    }

    fn is_built(&self) -> bool {
        match self {
            DomainData::Planar(_, b) => b.is_some(),
            DomainData::Solid(_, b) => b.is_some(),
        }
    }

    /// Whether the boundary was replaced (`igaparam_domain_set_boundary_*`) since the T-mesh
    /// was built or updated.
    fn pending(&self) -> bool {
        match self {
            DomainData::Planar(boundary, Some(b)) => b.boundary() != boundary,
            DomainData::Solid(boundary, Some(b)) => b.boundary() != boundary.as_ref(),
            _ => false,
        }
    }

    fn quality(&self) -> Option<&[f64]> {
        match self {
            DomainData::Planar(_, b) => b.as_ref().map(|d| d.quality()),
            DomainData::Solid(_, b) => b.as_ref().map(|d| d.quality()),
        }
    }

    fn grid(&self) -> Option<UnstructuredGrid> {
        match self {
            DomainData::Planar(_, b) => b.as_ref().map(|d| d.to_grid()),
            DomainData::Solid(_, b) => b.as_ref().map(|d| d.to_grid()),
        }
    }

    fn cell_count(&self) -> Option<usize> {
        match self {
            DomainData::Planar(_, b) => b.as_ref().map(|d| d.mesh().cell_count()),
            DomainData::Solid(_, b) => b.as_ref().map(|d| d.mesh().cell_count()),
        }
    }

    fn vertex_count(&self) -> Option<usize> {
        match self {
            DomainData::Planar(_, b) => b.as_ref().map(|d| d.mesh().vertex_count()),
            DomainData::Solid(_, b) => b.as_ref().map(|d| d.mesh().vertex_count()),
        }
    }

    fn view(&self) -> Option<BuiltView> {
        match self {
            DomainData::Planar(_, b) => b.as_ref().map(view_of),
            DomainData::Solid(_, b) => b.as_deref().map(view_of),
        }
    }
}

/// The flat arrays of a built domain.
fn view_of<const D: usize, B>(d: &crate::domain::Domain<D, B>) -> BuiltView
where
    B: crate::domain::CubeMap<D>,
{
    let mesh = d.mesh();
    let mut bounds = Vec::with_capacity(2 * D * mesh.cell_count());
    for c in 0..mesh.cell_count() {
        let (lo, hi) = mesh.cell_bounds(c);
        bounds.extend_from_slice(&lo);
        bounds.extend_from_slice(&hi);
    }
    // Corners: 2D polygons also list hanging vertices, so take the corner vertices directly.
    let corner_lattice: &[usize] = if D == 2 {
        &[0, 2, 8, 6]
    } else {
        &[0, 2, 8, 6, 18, 20, 26, 24]
    };
    let mut corners = Vec::with_capacity(corner_lattice.len() * mesh.cell_count());
    for c in 0..mesh.cell_count() {
        let (lattice_points, vertices) = mesh.cell_vertices(c);
        for l in corner_lattice {
            let i = lattice_points.iter().position(|x| x == l).unwrap_or(0);
            corners.push(vertices[i] as usize);
        }
    }
    BuiltView {
        dim: D,
        vertices: mesh.vertex_count(),
        parametric: mesh.parametric().iter().flatten().copied().collect(),
        physical: d.positions().iter().flatten().copied().collect(),
        levels: (0..mesh.cell_count()).map(|c| mesh.cell_level(c)).collect(),
        bounds,
        corners,
    }
}

/// Options of `igaparam_domain_build`; get the defaults from `igaparam_domain_options_default`
/// (planar) or `igaparam_domain_options_default_solid`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_domain_options {
    /// Boundary tolerance, positive: a boundary cell edge (planar domain) is refined while the
    /// triangle formed by its end images and the image of its parametric midpoint, or a boundary
    /// cell face (solid) while the four tetrahedra of consecutive corner images and the image of
    /// its centre, measured in coordinates that map the bounding box onto the unit box, exceed
    /// `tolerance × √d^d` (for a square or cube box: `tolerance × diagonal^d`; default 1e-5 for a
    /// planar domain, 1e-3 for a solid).
    pub tolerance: f64,
    /// Level of the initial uniform refinement (default 2).
    pub min_level: u32,
    /// Deepest level of the adaptation, at least `min_level` and at most 16 (default 9).
    pub max_level: u32,
    /// Largest number of optimization sweeps of one stage (default 200): the first
    /// optimization, each step of the growth from the bounding box, each round of the seam
    /// relief and of the repair.
    pub max_sweeps: u32,
    /// Largest number of sweeps of all stages together, at least 1 (default 5,000,
    /// `IGAPARAM_DEFAULT_MAX_TOTAL_SWEEPS`): once spent, the running stage stops after its
    /// sweep and no later stage starts; the build succeeds with the T-mesh the sweeps reached,
    /// and the report's `sweep_budget_exhausted` is 1 (check `invalid_cells`). The bundled
    /// domains need at most about 4,100; inputs that fold at every level stop here after
    /// seconds instead of running for minutes.
    pub max_total_sweeps: u32,
    /// Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per core.
    pub threads: u32,
    /// Rounds of repair after the optimization (default 6): while cells stay invalid, they are
    /// refined (past `max_level`, up to level 16) and the mesh optimized again; 0 disables it.
    pub repair_rounds: u32,
    /// Seam relief cap, finite and at least 0: the largest distance, in coordinates that map
    /// the bounding box onto the unit box, by which a boundary vertex may leave the boundary to
    /// open a cell that stays folded with every boundary vertex on it (default 1e-2); 0 keeps
    /// every boundary vertex on the boundary.
    pub boundary_offset: f64,
    /// Largest number of cells of the T-mesh (default 1,000,000): a build whose uniform
    /// refinement to `min_level` alone exceeds it (4^min_level cells for a planar domain,
    /// 8^min_level for a solid) is refused before any work, one whose adaptation or repair
    /// exceeds it stops there; both with `IGAPARAM_STATUS_LIMIT_EXCEEDED`. Raise it for finer
    /// T-meshes (time and memory grow with the cells: minutes and about a gigabyte at the
    /// default in 2D, more for a solid).
    pub max_cells: usize,
    /// The Newton polish after the sweeps, finite and at least 0 (default 0: off): when
    /// positive and every cell is valid, the inner vertices go to a stationary point of the
    /// global objective (the sum of the cells' mean distortions) to this scaled max-norm of its
    /// gradient (1e-8 is typical). It raises the mean cell quality and may lower the smallest.
    pub stationarity_tolerance: f64,
    /// Progress callback, or NULL (default). Called with `IGAPARAM_STAGE_OPTIMIZATION`, `done`
    /// sweeps so far and `total` 0, also between the rounds of the adaptation of the tree (with
    /// `done` 0); returning non-zero cancels the build.
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
    /// Largest boundary error, relative as `tolerance`.
    pub boundary_error: f64,
    /// Largest distance of a boundary vertex from its point on the boundary, in the coordinates
    /// of `boundary_offset` (at most the option; 0 when no seam relief was needed).
    pub boundary_offset: f64,
    /// Invalid cells (det J <= 0 somewhere) after the transfinite (Coons) placement.
    pub invalid_after_placement: usize,
    /// Invalid cells after the optimization; 0 for a usable parameterization.
    pub invalid_cells: usize,
    /// Smallest cell quality.
    pub min_quality: f64,
    /// Mean cell quality.
    pub mean_quality: f64,
    /// Optimization sweeps performed.
    pub sweeps: u32,
    /// 1 if the optimization stopped because it spent `max_total_sweeps` (the T-mesh is the
    /// state the sweeps reached: less optimized, possibly with invalid cells), else 0.
    pub sweep_budget_exhausted: c_int,
    /// Wall-clock seconds of the call.
    pub seconds: f64,
}

/// The default options of a planar domain (tolerance 1e-5).
#[no_mangle]
pub extern "C" fn igaparam_domain_options_default() -> igaparam_domain_options {
    c_options(&PlanarOptions::default())
}

/// The default options of a solid: those of `igaparam_domain_options_default` with a
/// tolerance of 1e-3 (a tolerance bounds a volume in 3D; 1e-5 refines for many minutes).
/// `igaparam_domain_build` with NULL options uses these for a solid.
#[no_mangle]
pub extern "C" fn igaparam_domain_options_default_solid() -> igaparam_domain_options {
    c_options(&SolidOptions::solid())
}

fn c_options(d: &PlanarOptions) -> igaparam_domain_options {
    igaparam_domain_options {
        tolerance: d.tolerance,
        min_level: d.min_level as u32,
        max_level: d.max_level as u32,
        max_sweeps: d.max_sweeps,
        max_total_sweeps: d.max_total_sweeps,
        threads: d.threads as u32,
        repair_rounds: d.repair_rounds,
        boundary_offset: d.boundary_offset,
        max_cells: d.max_cells,
        stationarity_tolerance: d.stationarity_tolerance,
        progress: None,
        progress_user: std::ptr::null_mut(),
    }
}

/// The core's options of C options `o` (a conversion; the core checks the ranges when it builds).
fn planar_options(o: &igaparam_domain_options) -> Result<PlanarOptions> {
    // A level above 255 becomes 255, which the core refuses as above 16 with the others.
    let level = |l: u32| u8::try_from(l).unwrap_or(u8::MAX);
    let options = PlanarOptions {
        tolerance: o.tolerance,
        min_level: level(o.min_level),
        max_level: level(o.max_level),
        max_sweeps: o.max_sweeps,
        max_total_sweeps: o.max_total_sweeps,
        threads: o.threads as usize,
        repair_rounds: o.repair_rounds,
        boundary_offset: o.boundary_offset,
        max_cells: o.max_cells,
        stationarity_tolerance: o.stationarity_tolerance,
    };
    options.validate()?;
    Ok(options)
}

/// A path from a NUL-terminated C string that must not be NULL.
pub(super) fn c_path<'a>(
    ptr: *const c_char,
    name: &'static str,
) -> std::result::Result<&'a Path, Failure> {
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

/// Releases a domain. NULL is a no-op. Called on a domain in use (from the progress callback of
/// `igaparam_domain_build`, `igaparam_domain_update` or `igaparam_domain_fit_adaptive`, or from
/// another thread), the release waits for that call: the call stops at its next progress point
/// with `IGAPARAM_STATUS_CANCELLED` and the domain is released as it returns; the handle must
/// not be used after this call in either case.
#[no_mangle]
pub extern "C" fn igaparam_domain_free(domain: *mut igaparam_domain) {
    release(domain);
}

/// The domain of handle `domain`, held for the call.
pub(super) fn held<'a>(
    domain: *const igaparam_domain,
) -> std::result::Result<Held<'a, igaparam_domain>, Failure> {
    acquire(domain, "domain")
}

/// The built domain, or an error if `igaparam_domain_build` has not succeeded yet.
fn built<'a>(
    domain: *const igaparam_domain,
) -> std::result::Result<Held<'a, igaparam_domain>, Failure> {
    let d = held(domain)?;
    if d.is_built() {
        Ok(d)
    } else {
        Err(
            Error::invalid("the domain has not been built: call igaparam_domain_build first")
                .into(),
        )
    }
}

/// The built domain whose T-mesh is on its current boundary, or an error if it has not been
/// built or its boundary was replaced since (fits need the T-mesh moved first).
pub(super) fn current<'a>(
    domain: *const igaparam_domain,
) -> std::result::Result<Held<'a, igaparam_domain>, Failure> {
    let d = built(domain)?;
    if d.pending() {
        return Err(Error::invalid(
            "the boundary was replaced (igaparam_domain_set_boundary_*) since the T-mesh was \
             built: call igaparam_domain_update (or igaparam_domain_build) first",
        )
        .into());
    }
    Ok(d)
}

/// The progress of the optimization of a T-mesh as the C callback `progress` sees it
/// (`IGAPARAM_STAGE_OPTIMIZATION`, sweeps done, total 0): false when it asks to cancel or the
/// handle's release was requested (`watch`).
pub(super) fn optimization_progress(
    progress: igaparam_progress_fn,
    user: *mut c_void,
    watch: ReleaseWatch<'_>,
) -> impl FnMut(usize, usize) -> bool + '_ {
    move |done, total| {
        call_progress(
            progress,
            user,
            igaparam_stage::IGAPARAM_STAGE_OPTIMIZATION,
            done,
            total,
        ) && !watch.requested()
    }
}

/// The C form of a build report.
pub(super) fn c_report(r: &DomainReport) -> igaparam_domain_report {
    igaparam_domain_report {
        cells: r.cells,
        vertices: r.vertices,
        max_level: r.max_level as u32,
        boundary_error: r.boundary_error,
        boundary_offset: r.boundary_offset,
        invalid_after_placement: r.invalid_after_placement,
        invalid_cells: r.invalid_cells,
        min_quality: r.min_quality,
        mean_quality: r.mean_quality,
        sweeps: r.sweeps,
        sweep_budget_exhausted: c_int::from(r.sweep_budget_exhausted),
        seconds: r.seconds,
    }
}

/// Runs the adaptive loop on a copy of the built domain and, on success, keeps the refined
/// T-mesh in the handle (see `igaparam_domain_fit_adaptive`): a failed or cancelled call leaves
/// the handle as it was. Returns the map, the loop's report and the record of the map's fit.
pub(super) fn adapt_domain(
    domain: *mut igaparam_domain,
    options: &crate::spline::AdaptOptions,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> std::result::Result<(AnyMap, crate::spline::AdaptReport, FitRecord), Failure> {
    use crate::spline::adapt;
    let mut held = current(domain)?;
    let (d, watch) = held.split();
    let progress = &mut |done, total| progress(done, total) && !watch.requested();
    match d {
        DomainData::Planar(_, Some(d)) => {
            let mut copy = d.clone();
            let (map, report) =
                adapt(&mut copy, options, progress).map_err(|e| watch.explain(e))?;
            let record = map.fit_record(copy.mesh(), copy.positions(), &report.fit)?;
            *d = copy;
            Ok((AnyMap::Two(map), report, record))
        }
        DomainData::Solid(_, Some(d)) => {
            let mut copy = d.clone();
            let (map, report) =
                adapt(&mut copy, options, progress).map_err(|e| watch.explain(e))?;
            let record = map.fit_record(copy.mesh(), copy.positions(), &report.fit)?;
            *d = copy;
            Ok((AnyMap::Three(map), report, record))
        }
        _ => Err(Error::invalid("the domain has not been built").into()),
    }
}

/// The untangling options of a built domain's fits: the defaults except the boundary offset,
/// which is the domain's own (a domain built to keep its boundary keeps it in the spline map
/// too).
pub(super) fn untangle_options<const D: usize, B: crate::domain::CubeMap<D>>(
    domain: &crate::domain::Domain<D, B>,
) -> UntangleOptions {
    UntangleOptions {
        boundary_offset: domain.options().boundary_offset,
        ..Default::default()
    }
}

/// Adapts a T-mesh to the boundary (refining boundary cells until `options.tolerance` or
/// `options.max_level` is met), places its vertices (boundary ones on the curves, inner ones by
/// the Coons patch) and optimizes them; the result is kept in the handle, replacing that of an
/// earlier build. `options` may be NULL for the defaults (`igaparam_domain_options_default`, or
/// `igaparam_domain_options_default_solid` for a solid); `report` may be NULL. On any error or
/// cancellation the handle is unchanged (an earlier build stays) and `*report` is not written.
#[no_mangle]
pub extern "C" fn igaparam_domain_build(
    domain: *mut igaparam_domain,
    options: *const igaparam_domain_options,
    report: *mut igaparam_domain_report,
) -> igaparam_status {
    run("igaparam_domain_build", || {
        let mut held = held(domain)?;
        let (d, watch) = held.split();
        let raw = if options.is_null() {
            match d {
                DomainData::Planar(..) => igaparam_domain_options_default(),
                DomainData::Solid(..) => igaparam_domain_options_default_solid(),
            }
        } else {
            *non_null(options, "options")?
        };
        let opts = planar_options(&raw)?;
        let mut progress = optimization_progress(raw.progress, raw.progress_user, watch);
        let r = match d {
            DomainData::Planar(boundary, built) => {
                let (planar, r) = PlanarDomain::build(boundary.clone(), &opts, &mut progress)
                    .map_err(|e| watch.explain(e))?;
                *built = Some(planar);
                r
            }
            DomainData::Solid(boundary, built) => {
                let (solid, r) =
                    SolidDomain::build(boundary.as_ref().clone(), &opts, &mut progress)
                        .map_err(|e| watch.explain(e))?;
                *built = Some(Box::new(solid));
                r
            }
        };
        if !report.is_null() {
            *non_null_mut(report, "report")? = c_report(&r);
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
        let n = built(domain)?.vertex_count().unwrap_or(0);
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
        let n = built(domain)?.cell_count().unwrap_or(0);
        *non_null_mut(out, "out")? = n;
        Ok(())
    })
}

/// Copies the vertices of the built T-mesh: `parametric` receives their parametric coordinates
/// in [0,1]^d (u, v; u, v, w for a solid), and `physical` their coordinates in the domain (x, y;
/// x, y, z), each `num_vertices × d` doubles (d = 2 for a planar domain, 3 for a solid; see
/// `igaparam_domain_dimension`). Either may be NULL to skip it; `len_each` is the number of
/// doubles each non-NULL buffer holds (at least `d × num_vertices`). Fails with
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built.
#[no_mangle]
pub extern "C" fn igaparam_domain_copy_vertices(
    domain: *const igaparam_domain,
    parametric: *mut f64,
    physical: *mut f64,
    len_each: usize,
) -> igaparam_status {
    run("igaparam_domain_copy_vertices", || {
        let v = built(domain)?
            .view()
            .ok_or_else(|| Error::invalid("the domain has not been built"))?;
        let needed = v.dim * v.vertices;
        for (ptr, name) in [(parametric, "parametric"), (physical, "physical")] {
            if !ptr.is_null() {
                check_capacity(name, len_each, needed)?;
            }
        }
        for (ptr, name, values) in [
            (parametric, "parametric", &v.parametric),
            (physical, "physical", &v.physical),
        ] {
            if !ptr.is_null() {
                slice_mut(ptr, len_each, name)?[..needed].copy_from_slice(values);
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
        let q = d.quality().unwrap_or_default();
        check_capacity("quality", len, q.len())?;
        slice_mut(quality, len, "quality")?[..q.len()].copy_from_slice(q);
        Ok(())
    })
}

/// Copies the cells of the built T-mesh, in the order of their qualities:
///
/// - `levels`: the refinement level of every cell (`num_cells` bytes), or NULL to skip it;
/// - `bounds`: the parametric box of every cell, `num_cells × 2d` doubles (lower then upper
///   corner: `u0 v0 u1 v1` for a planar domain, `u0 v0 w0 u1 v1 w1` for a solid), or NULL to
///   skip it.
///
/// `len` is the number of cells the buffers hold (`levels` has `len` bytes, `bounds` `2d × len`
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
        let v = built(domain)?
            .view()
            .ok_or_else(|| Error::invalid("the domain has not been built"))?;
        let n = v.levels.len();
        check_capacity("levels/bounds (cells)", len, n)?;
        if let Some(out) = optional_out(levels, n) {
            out.copy_from_slice(&v.levels);
        }
        if let Some(out) = optional_out(bounds, v.bounds.len()) {
            out.copy_from_slice(&v.bounds);
        }
        Ok(())
    })
}

/// Copies the corner vertices of every cell of the built T-mesh into `corners`: `num_cells × 2^d`
/// vertex indices (4 per cell for a planar domain, counter-clockwise from the lower-left corner;
/// 8 per cell for a solid, in VTK's hexahedron order), indices into the vertices of
/// `igaparam_domain_copy_vertices`. Hanging vertices on a cell's edges or faces are not listed.
/// `len` is the number of entries `corners` holds, at least `2^d × num_cells`. Fails with
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built.
#[no_mangle]
pub extern "C" fn igaparam_domain_copy_cell_corners(
    domain: *const igaparam_domain,
    corners: *mut usize,
    len: usize,
) -> igaparam_status {
    run("igaparam_domain_copy_cell_corners", || {
        let v = built(domain)?
            .view()
            .ok_or_else(|| Error::invalid("the domain has not been built"))?;
        check_capacity("corners", len, v.corners.len())?;
        slice_mut(corners, len, "corners")?[..v.corners.len()].copy_from_slice(&v.corners);
        Ok(())
    })
}

/// Writes to `*out` the dimension of the domain: 2 for a planar domain, 3 for a solid.
#[no_mangle]
pub extern "C" fn igaparam_domain_dimension(
    domain: *const igaparam_domain,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_domain_dimension", || {
        let d = held(domain)?.dim();
        *non_null_mut(out, "out")? = d;
        Ok(())
    })
}

/// Writes the built T-mesh to a VTK XML unstructured grid (`.vtu`) at `path` (NUL-terminated
/// UTF-8): for a planar domain one polygon per cell through its corners and hanging vertices,
/// for a solid one hexahedron per cell through its corners, at the physical positions; point data
/// `parametric` (u, v, 0 or u, v, w), cell data `quality` and `level`. Fails with
/// `IGAPARAM_STATUS_IO` if the file cannot be written, `IGAPARAM_STATUS_INVALID_ARGUMENT` if the
/// domain has not been built.
#[no_mangle]
pub extern "C" fn igaparam_domain_write_vtu(
    domain: *const igaparam_domain,
    path: *const c_char,
) -> igaparam_status {
    run("igaparam_domain_write_vtu", || {
        let grid = built(domain)?.grid().unwrap_or_default();
        let path = c_path(path, "path")?;
        crate::io::vtu::write(path, &grid)?;
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
        let b = held(domain)?.is_built();
        *non_null_mut(out, "out")? = b as c_int;
        Ok(())
    })
}
