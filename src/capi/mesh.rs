//! The mesh handle: create a quad/hex mesh, constrain and move nodes, relocate, read back.

use std::ffi::{c_int, c_void};

use super::boundary::{check_capacity, non_null, non_null_mut, run, slice, slice_mut, Failure};
use super::handle::{acquire, handle_type, release, Guarded, Held};
use super::igaparam_status;
use crate::error::{Error, Result};
use crate::homesh::{CellType, Mesh, Method, Placement, RelocateOptions, Stage};
use crate::optimize::TargetKind;

/// A quadrilateral or hexahedral finite-element mesh with node constraints (opaque).
/// Create with `igaparam_mesh_new`, release with `igaparam_mesh_free`. One call at a time
/// (see `IGAPARAM_STATUS_BUSY`).
pub struct igaparam_mesh(Guarded<Mesh>);
handle_type!(igaparam_mesh, Mesh, "mesh");

/// A cell type: one of the `IGAPARAM_CELL_*` values (VTK's cell type codes). The local order of
/// each type's nodes, VTK's and Gmsh's, is tabulated at `igaparam_node_order`.
pub type igaparam_cell_type = c_int;
/// Bilinear quadrilateral, 4 nodes (VTK_QUAD).
pub const IGAPARAM_CELL_QUAD4: igaparam_cell_type = 9;
/// Serendipity quadratic quadrilateral, 8 nodes (VTK_QUADRATIC_QUAD).
pub const IGAPARAM_CELL_QUAD8: igaparam_cell_type = 23;
/// Biquadratic quadrilateral, 9 nodes (VTK_BIQUADRATIC_QUAD).
pub const IGAPARAM_CELL_QUAD9: igaparam_cell_type = 28;
/// Trilinear hexahedron, 8 nodes (VTK_HEXAHEDRON).
pub const IGAPARAM_CELL_HEX8: igaparam_cell_type = 12;
/// Serendipity quadratic hexahedron, 20 nodes (VTK_QUADRATIC_HEXAHEDRON).
pub const IGAPARAM_CELL_HEX20: igaparam_cell_type = 25;
/// Triquadratic hexahedron, 27 nodes (VTK_TRIQUADRATIC_HEXAHEDRON).
pub const IGAPARAM_CELL_HEX27: igaparam_cell_type = 29;

/// The ideal shape of a cell: one of the `IGAPARAM_TARGET_*` values.
pub type igaparam_target = c_int;
/// The cell's own shape in the reference positions (those given to `igaparam_mesh_new`, or set by
/// `igaparam_mesh_reset_reference`): keeps size grading and anisotropy.
pub const IGAPARAM_TARGET_INITIAL: igaparam_target = 0;
/// The master square/cube (scaled to the cell's size).
pub const IGAPARAM_TARGET_MASTER: igaparam_target = 1;

/// Where free nodes start: one of the `IGAPARAM_PLACEMENT_*` values.
pub type igaparam_placement = c_int;
/// Harmonic extension of the prescribed displacements (a discrete Laplace equation).
pub const IGAPARAM_PLACEMENT_LAPLACIAN: igaparam_placement = 0;
/// The current positions, as they are.
pub const IGAPARAM_PLACEMENT_CURRENT: igaparam_placement = 1;
/// Warm start for loops: the positions of the last successful relocation plus the harmonic
/// extension of the prescribed motion since then (the first relocation of a mesh starts as
/// `IGAPARAM_PLACEMENT_LAPLACIAN`); the targets stay the reference shapes. Use it when the
/// boundary moves a little at every call, as in a shape-optimization loop.
pub const IGAPARAM_PLACEMENT_INCREMENTAL: igaparam_placement = 2;

/// How the free nodes are carried to the optimum: one of the `IGAPARAM_METHOD_*` values.
pub type igaparam_method = c_int;
/// `IGAPARAM_METHOD_NEWTON` where the Hessian's Cholesky factor is small (2D meshes, 3D meshes
/// up to about 20,000 nodes), else `IGAPARAM_METHOD_SWEEPS` (default).
pub const IGAPARAM_METHOD_AUTO: igaparam_method = 0;
/// The per-node optimizer's coloured Gauss–Seidel sweeps, large motions in steps placed
/// harmonically; with `stationarity_tolerance > 0`, followed by the Newton stage.
pub const IGAPARAM_METHOD_SWEEPS: igaparam_method = 1;
/// Path following of the optimum of the global objective: each step predicted by the tangent of
/// the optimum (the linearised response of the mesh to the motion) and corrected by Newton's
/// method; the sweeps are the fallback where a step cannot be made (e.g. a tangled start).
pub const IGAPARAM_METHOD_NEWTON: igaparam_method = 2;

/// A stage of long work, passed to the progress callback.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum igaparam_stage {
    /// First placement of the free nodes.
    IGAPARAM_STAGE_PLACEMENT = 0,
    /// Optimization sweeps: `done` sweeps so far over all steps; `total` is 0 (not known in
    /// advance, as large motions may be split into more steps).
    IGAPARAM_STAGE_OPTIMIZATION = 1,
    /// Adaptive refinement of a domain's T-mesh from the quality of its spline map: `done`
    /// rounds of `total` at most.
    IGAPARAM_STAGE_ADAPTATION = 2,
    /// Newton iterations on the global objective (`stationarity_tolerance`): `done` so far,
    /// `total` 0.
    IGAPARAM_STAGE_STATIONARITY = 3,
    /// The fits and certifications of `igaparam_spline_fit_domain_with`: `done` of `total`.
    IGAPARAM_STAGE_FIT = 4,
    /// Untangling rounds of a fitted map that is not certified: `done` of at most `total`.
    IGAPARAM_STAGE_UNTANGLING = 5,
    /// Smoothing sweeps of a certified map: `done` of at most `total`.
    IGAPARAM_STAGE_SMOOTHING = 6,
}

/// Progress callback: `user` is the options' `progress_user`; `done` of `total` steps of `stage`
/// are complete. Return 0 to go on, non-zero to cancel (the call then returns
/// `IGAPARAM_STATUS_CANCELLED` and leaves the mesh unchanged). Called on the calling thread.
pub type igaparam_progress_fn = Option<
    unsafe extern "C" fn(
        user: *mut c_void,
        stage: igaparam_stage,
        done: usize,
        total: usize,
    ) -> c_int,
>;

/// Calls the progress callback `f` (none: go on) with `user`; true to go on.
pub(super) fn call_progress(
    f: igaparam_progress_fn,
    user: *mut c_void,
    stage: igaparam_stage,
    done: usize,
    total: usize,
) -> bool {
    match f {
        None => true,
        // SAFETY: the caller supplied a valid callback and its user pointer.
        Some(f) => unsafe { f(user, stage, done, total) == 0 },
    }
}

/// Options of `igaparam_mesh_relocate`; get the defaults from `igaparam_relocate_options_default`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct igaparam_relocate_options {
    /// `IGAPARAM_TARGET_INITIAL` (default) or `IGAPARAM_TARGET_MASTER`.
    pub target: igaparam_target,
    /// `IGAPARAM_PLACEMENT_LAPLACIAN` (default), `IGAPARAM_PLACEMENT_CURRENT` or
    /// `IGAPARAM_PLACEMENT_INCREMENTAL`.
    pub placement: igaparam_placement,
    /// Non-zero (default) runs the optimizer after the placement; 0 stops after the placement.
    pub optimize: c_int,
    /// Largest number of Gauss–Seidel sweeps (default 100 per step).
    pub max_sweeps: u32,
    /// Stop when the mesh is valid and no node moved more than this fraction of its local cell
    /// size in a sweep (default 1e-3).
    pub move_tolerance: f64,
    /// A node's Newton iteration stops when the gradient of its objective times its local cell
    /// size is below this (default 1e-3: nodes are revisited by the following sweeps, so an
    /// inexact solve per sweep suffices).
    pub gradient_tolerance: f64,
    /// Largest number of Newton iterations per node and sweep (default 150).
    pub max_newton_iterations: u32,
    /// Over-relaxation of each node's move, in [1, 2) (default 1.8; 1 disables it). A relaxed
    /// move is kept only if it lowers the node's objective and inverts nothing.
    pub relaxation: f64,
    /// Worker threads, at most 4096, capped to the machine's cores; 0 (default) uses one per
    /// core. The result does not depend on it.
    pub threads: u32,
    /// When positive, the result is a stationary point of the one global objective
    /// F = sum over cells of their mean distortion (regularisation 0, so F is infinite at a
    /// fold): the report's `gradient_norm` is at most this (e.g. 1e-10), reached by Newton's
    /// method with the sparse Hessian on a valid mesh; `igaparam_mesh_adjoint` and
    /// `igaparam_mesh_tangent` then differentiate the result. 0 (default): no such guarantee
    /// (the sweeps stop on their own rule, the Newton method at 1e-8).
    pub stationarity_tolerance: f64,
    /// `IGAPARAM_METHOD_AUTO` (default), `IGAPARAM_METHOD_SWEEPS` or `IGAPARAM_METHOD_NEWTON`.
    pub method: igaparam_method,
    /// Progress callback, or NULL (default).
    pub progress: igaparam_progress_fn,
    /// Passed to `progress` as its first argument.
    pub progress_user: *mut c_void,
}

/// What `igaparam_mesh_relocate` did. Quality is the inverse mean distortion of a cell against its
/// target over its Gauss–Lobatto points: 1 is the target shape, 0 an inverted cell.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct igaparam_relocate_report {
    /// Number of cells.
    pub cells: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Nodes with at least one free coordinate.
    pub free_nodes: usize,
    /// Cells with det J <= 0 at a Gauss–Lobatto point when the call started.
    pub invalid_before: usize,
    /// Invalid cells after the first placement.
    pub invalid_after_placement: usize,
    /// Invalid cells at the end.
    pub invalid_after: usize,
    /// Smallest cell quality at the end.
    pub min_quality: f64,
    /// Mean cell quality at the end.
    pub mean_quality: f64,
    /// Optimization sweeps performed (over all steps).
    pub sweeps: u32,
    /// Steps the prescribed motion was applied in (large motions are split so that no prescribed
    /// node moves more than about one cell size per step).
    pub steps: u32,
    /// 1 when the sweeps met their stopping rule (valid mesh, small moves) and, when asked for,
    /// the Newton stage its `stationarity_tolerance`; else 0.
    pub converged: c_int,
    /// Scaled max-norm of the gradient of F at the end: over the free coordinates,
    /// |dF/dx| times the node's local cell size divided by its number of cells (the gradient of
    /// the node's own objective times its size; dimensionless). Infinite for an invalid mesh.
    pub gradient_norm: f64,
    /// Newton iterations of the stationarity stage.
    pub newton_iterations: u32,
    /// Wall-clock seconds of the call.
    pub seconds: f64,
}

/// The default relocation options.
#[no_mangle]
pub extern "C" fn igaparam_relocate_options_default() -> igaparam_relocate_options {
    let d = RelocateOptions::default();
    igaparam_relocate_options {
        target: IGAPARAM_TARGET_INITIAL,
        placement: IGAPARAM_PLACEMENT_LAPLACIAN,
        optimize: 1,
        max_sweeps: d.max_sweeps,
        move_tolerance: d.move_tolerance,
        gradient_tolerance: d.gradient_tolerance,
        max_newton_iterations: d.max_newton_iterations,
        relaxation: d.relaxation,
        threads: d.threads as u32,
        stationarity_tolerance: d.stationarity_tolerance,
        method: IGAPARAM_METHOD_AUTO,
        progress: None,
        progress_user: std::ptr::null_mut(),
    }
}

pub(super) fn cell_type(code: igaparam_cell_type) -> Result<CellType> {
    CellType::from_vtk(code as i64).ok_or_else(|| {
        Error::invalid(format!(
            "cell type {code} is not supported; use IGAPARAM_CELL_QUAD4/QUAD8/QUAD9/HEX8/HEX20/HEX27 (VTK codes 9, 23, 28, 12, 25, 29)"
        ))
    })
}

fn target(code: igaparam_target) -> Result<TargetKind> {
    match code {
        IGAPARAM_TARGET_INITIAL => Ok(TargetKind::Reference),
        IGAPARAM_TARGET_MASTER => Ok(TargetKind::Master),
        _ => Err(Error::invalid(format!(
            "target {code} is neither IGAPARAM_TARGET_INITIAL (0) nor IGAPARAM_TARGET_MASTER (1)"
        ))),
    }
}

pub(super) fn relocate_options(o: &igaparam_relocate_options) -> Result<RelocateOptions> {
    let placement = match o.placement {
        IGAPARAM_PLACEMENT_LAPLACIAN => Placement::Laplacian,
        IGAPARAM_PLACEMENT_CURRENT => Placement::Current,
        IGAPARAM_PLACEMENT_INCREMENTAL => Placement::Incremental,
        p => {
            return Err(Error::invalid(format!(
                "placement {p} is not IGAPARAM_PLACEMENT_LAPLACIAN (0), IGAPARAM_PLACEMENT_CURRENT (1) or IGAPARAM_PLACEMENT_INCREMENTAL (2)"
            )))
        }
    };
    Ok(RelocateOptions {
        target: target(o.target)?,
        placement,
        optimize: o.optimize != 0,
        max_sweeps: o.max_sweeps,
        move_tolerance: o.move_tolerance,
        gradient_tolerance: o.gradient_tolerance,
        max_newton_iterations: o.max_newton_iterations,
        relaxation: o.relaxation,
        threads: o.threads as usize,
        stationarity_tolerance: o.stationarity_tolerance,
        method: match o.method {
            IGAPARAM_METHOD_AUTO => Method::Auto,
            IGAPARAM_METHOD_SWEEPS => Method::Sweeps,
            IGAPARAM_METHOD_NEWTON => Method::Newton,
            m => {
                return Err(Error::invalid(format!(
                    "method {m} is not IGAPARAM_METHOD_AUTO (0), IGAPARAM_METHOD_SWEEPS (1) or IGAPARAM_METHOD_NEWTON (2)"
                )))
            }
        },
    })
}

/// Creates a mesh of `num_cells` cells of one type.
///
/// - `xyz`: `num_nodes × 3` coordinates, flat (x0 y0 z0 x1 ...); always 3 per node, as in VTK; for
///   quadrilaterals z is carried unchanged. These positions are the reference shape.
/// - `connectivity`: `num_cells × n` node indices (n = nodes per cell of `cell_type`), in VTK's
///   node order, each in `0..num_nodes`.
/// - `out`: receives the new handle, to be released with `igaparam_mesh_free`.
///
/// All nodes start free (see `igaparam_mesh_set_fixed`). The arrays are copied. For Gmsh's node
/// order see `igaparam_mesh_new_ordered`; a mesh every cell of which is inverted or folded is
/// refused with `IGAPARAM_STATUS_INVALID_MESH` (likely a connectivity in another node order, or
/// cells oriented the wrong way).
#[no_mangle]
pub extern "C" fn igaparam_mesh_new(
    cell_type_code: igaparam_cell_type,
    num_nodes: usize,
    xyz: *const f64,
    num_cells: usize,
    connectivity: *const i64,
    out: *mut *mut igaparam_mesh,
) -> igaparam_status {
    super::node_order::new_mesh(
        "igaparam_mesh_new",
        cell_type_code,
        super::node_order::IGAPARAM_ORDER_VTK,
        num_nodes,
        xyz,
        num_cells,
        connectivity,
        out,
    )
}

/// Releases a mesh. NULL is a no-op. Called on a mesh in use (from the progress callback of
/// `igaparam_mesh_relocate`, or from another thread), the release waits for that call: the call
/// stops at its next progress point with `IGAPARAM_STATUS_CANCELLED` and the mesh is released
/// as it returns; the handle must not be used after this call in either case.
#[no_mangle]
pub extern "C" fn igaparam_mesh_free(mesh: *mut igaparam_mesh) {
    release(mesh);
}

/// The mesh of handle `mesh`, held for the call.
pub(super) fn with_mesh<'a>(
    mesh: *const igaparam_mesh,
) -> std::result::Result<Held<'a, igaparam_mesh>, Failure> {
    acquire(mesh, "mesh")
}

fn with_mesh_mut<'a>(
    mesh: *mut igaparam_mesh,
) -> std::result::Result<Held<'a, igaparam_mesh>, Failure> {
    acquire(mesh, "mesh")
}

/// Writes the number of nodes to `*out`.
#[no_mangle]
pub extern "C" fn igaparam_mesh_node_count(
    mesh: *const igaparam_mesh,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_mesh_node_count", || {
        *non_null_mut(out, "out")? = with_mesh(mesh)?.node_count();
        Ok(())
    })
}

/// Writes the number of cells to `*out`.
#[no_mangle]
pub extern "C" fn igaparam_mesh_cell_count(
    mesh: *const igaparam_mesh,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_mesh_cell_count", || {
        *non_null_mut(out, "out")? = with_mesh(mesh)?.cell_count();
        Ok(())
    })
}

/// Writes the spatial dimension of the cells (2 or 3) to `*out`.
#[no_mangle]
pub extern "C" fn igaparam_mesh_dimension(
    mesh: *const igaparam_mesh,
    out: *mut c_int,
) -> igaparam_status {
    run("igaparam_mesh_dimension", || {
        *non_null_mut(out, "out")? = with_mesh(mesh)?.dimension() as c_int;
        Ok(())
    })
}

/// Sets the constraint of every node: `mask` has `num_nodes` entries; bit 0 keeps x, bit 1 keeps
/// y, bit 2 keeps z (0 free, 3 fixed in 2D, 7 fixed in 3D, 4 sliding in its plane z = const).
/// `num_nodes` must equal the mesh's node count.
#[no_mangle]
pub extern "C" fn igaparam_mesh_set_fixed(
    mesh: *mut igaparam_mesh,
    num_nodes: usize,
    mask: *const u8,
) -> igaparam_status {
    run("igaparam_mesh_set_fixed", || {
        let mut m = with_mesh_mut(mesh)?;
        m.set_fixed(slice(mask, num_nodes, "mask")?)?;
        Ok(())
    })
}

/// Sets the positions of `count` nodes: node `indices[i]` moves to `xyz[3i..3i+3]`. `indices`
/// may be NULL, meaning nodes `0..count-1`. Typically used for the boundary nodes before
/// `igaparam_mesh_relocate`; the reference shape is not changed.
#[no_mangle]
pub extern "C" fn igaparam_mesh_move_nodes(
    mesh: *mut igaparam_mesh,
    count: usize,
    indices: *const i64,
    xyz: *const f64,
) -> igaparam_status {
    run("igaparam_mesh_move_nodes", || {
        let mut m = with_mesh_mut(mesh)?;
        let xyz = slice(
            xyz,
            count
                .checked_mul(3)
                .ok_or_else(|| Error::invalid("count is too large"))?,
            "xyz",
        )?;
        let idx = if indices.is_null() {
            None
        } else {
            let raw = slice(indices, count, "indices")?;
            Some(
                raw.iter()
                    .enumerate()
                    .map(|(i, &v)| {
                        usize::try_from(v)
                            .map_err(|_| Error::invalid(format!("indices[{i}] = {v} is negative")))
                    })
                    .collect::<Result<Vec<usize>>>()?,
            )
        };
        m.move_nodes(idx.as_deref(), xyz)?;
        Ok(())
    })
}

/// Makes the current positions the reference shape of the targets (e.g. after an accepted step of
/// a shape-optimization loop).
#[no_mangle]
pub extern "C" fn igaparam_mesh_reset_reference(mesh: *mut igaparam_mesh) -> igaparam_status {
    run("igaparam_mesh_reset_reference", || {
        with_mesh_mut(mesh)?.reset_reference();
        Ok(())
    })
}

/// Relocates the free coordinates of the nodes so that every cell is valid and close to its
/// target shape, keeping the connectivity. `options` may be NULL for the defaults; `report` may
/// be NULL. On any error or cancellation the mesh is unchanged and `*report` is not written.
///
/// Units: the result does not depend on them. The mesh is optimized in coordinates scaled by
/// the power of two `2^-k` with `2^k <= L < 2^(k+1)`, L the largest side of the bounding box of
/// the reference shape's cell nodes, so every tolerance inside (and every option's tolerance,
/// given relative to a local cell size) is relative to the mesh's size; a mesh scaled by a
/// power of two relocates to the same result scaled bit for bit, by any other factor to the
/// same result to round-off. Prescribed coordinates are returned with the bits they were
/// given.
#[no_mangle]
pub extern "C" fn igaparam_mesh_relocate(
    mesh: *mut igaparam_mesh,
    options: *const igaparam_relocate_options,
    report: *mut igaparam_relocate_report,
) -> igaparam_status {
    run("igaparam_mesh_relocate", || {
        let mut handle = with_mesh_mut(mesh)?;
        let raw = if options.is_null() {
            igaparam_relocate_options_default()
        } else {
            *non_null(options, "options")?
        };
        let opts = relocate_options(&raw)?;
        let (handle, watch) = handle.split();
        let mut relocation = relocation_progress(&raw);
        let mut progress = |stage: Stage, done: usize, total: usize| {
            relocation(stage, done, total) && !watch.requested()
        };
        // Mesh::relocate changes nothing on error or cancellation.
        let r = handle
            .relocate(&opts, &mut progress)
            .map_err(|e| watch.explain(e))?;
        if !report.is_null() {
            *non_null_mut(report, "report")? = report_of(&r);
        }
        Ok(())
    })
}

/// The relocation's progress as the options' callback sees it.
pub(super) fn relocation_progress(
    raw: &igaparam_relocate_options,
) -> impl FnMut(Stage, usize, usize) -> bool + '_ {
    |stage: Stage, done: usize, total: usize| {
        let stage = match stage {
            Stage::Placement => igaparam_stage::IGAPARAM_STAGE_PLACEMENT,
            Stage::Optimization => igaparam_stage::IGAPARAM_STAGE_OPTIMIZATION,
            Stage::Stationarity => igaparam_stage::IGAPARAM_STAGE_STATIONARITY,
        };
        call_progress(raw.progress, raw.progress_user, stage, done, total)
    }
}

/// The C form of a relocation's report.
pub(super) fn report_of(r: &crate::homesh::RelocateReport) -> igaparam_relocate_report {
    igaparam_relocate_report {
        cells: r.cells,
        nodes: r.nodes,
        free_nodes: r.free_nodes,
        invalid_before: r.invalid_before,
        invalid_after_placement: r.invalid_after_placement,
        invalid_after: r.invalid_after,
        min_quality: r.min_quality,
        mean_quality: r.mean_quality,
        sweeps: r.sweeps,
        steps: r.steps,
        converged: r.converged as c_int,
        gradient_norm: r.gradient_norm,
        newton_iterations: r.newton_iterations,
        seconds: r.seconds,
    }
}

/// Copies the current node positions into `xyz` (`len` doubles, at least `3 × num_nodes`; x0 y0
/// z0 x1 ...).
#[no_mangle]
pub extern "C" fn igaparam_mesh_copy_positions(
    mesh: *const igaparam_mesh,
    xyz: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_mesh_copy_positions", || {
        let m = with_mesh(mesh)?;
        copy_points(m.positions(), xyz, len)
    })
}

/// Copies points into a caller's buffer of `len` doubles.
fn copy_points(
    points: &[[f64; 3]],
    xyz: *mut f64,
    len: usize,
) -> std::result::Result<(), super::boundary::Failure> {
    check_capacity("xyz", len, 3 * points.len())?;
    let out = slice_mut(xyz, len, "xyz")?;
    for (o, p) in out.chunks_mut(3).zip(points) {
        o.copy_from_slice(p);
    }
    Ok(())
}

/// Copies the quality of every cell against `target` (an `IGAPARAM_TARGET_*` value) into
/// `quality` (`len` doubles, at least `num_cells`): the inverse mean distortion over the cell's
/// Gauss–Lobatto points, in (0, 1], or 0 for a cell with det J <= 0 somewhere.
#[no_mangle]
pub extern "C" fn igaparam_mesh_copy_cell_quality(
    mesh: *const igaparam_mesh,
    target_kind: igaparam_target,
    quality: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_mesh_copy_cell_quality", || {
        let m = with_mesh(mesh)?;
        let t = target(target_kind)?;
        check_capacity("quality", len, m.cell_count())?;
        let out = slice_mut(quality, len, "quality")?;
        let q = m.cell_quality(t)?;
        out[..q.len()].copy_from_slice(&q);
        Ok(())
    })
}

/// Copies the reference positions (the shape the targets are taken from) into `xyz` (`len`
/// doubles, at least `3 × num_nodes`).
#[no_mangle]
pub extern "C" fn igaparam_mesh_copy_reference(
    mesh: *const igaparam_mesh,
    xyz: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_mesh_copy_reference", || {
        let m = with_mesh(mesh)?;
        copy_points(m.reference(), xyz, len)
    })
}

/// Copies the constraint mask of every node (see `igaparam_mesh_set_fixed`) into `mask` (`len`
/// bytes, at least `num_nodes`).
#[no_mangle]
pub extern "C" fn igaparam_mesh_copy_fixed(
    mesh: *const igaparam_mesh,
    mask: *mut u8,
    len: usize,
) -> igaparam_status {
    run("igaparam_mesh_copy_fixed", || {
        let m = with_mesh(mesh)?;
        check_capacity("mask", len, m.node_count())?;
        slice_mut(mask, len, "mask")?[..m.node_count()].copy_from_slice(m.fixed());
        Ok(())
    })
}

/// Writes to `*out` the number of nodes of one cell of type `cell_type_code`, e.g. 9 for
/// `IGAPARAM_CELL_QUAD9`.
#[no_mangle]
pub extern "C" fn igaparam_cell_type_node_count(
    cell_type_code: igaparam_cell_type,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_cell_type_node_count", || {
        let out = non_null_mut(out, "out")?;
        *out = cell_type(cell_type_code)?.node_count();
        Ok(())
    })
}

/// Writes to `*out` the number of cells with det J <= 0 at some Gauss–Lobatto point.
#[no_mangle]
pub extern "C" fn igaparam_mesh_invalid_cell_count(
    mesh: *const igaparam_mesh,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_mesh_invalid_cell_count", || {
        let m = with_mesh(mesh)?;
        let n = m.invalid_cell_count()?;
        *non_null_mut(out, "out")? = n;
        Ok(())
    })
}

/// The adjoint product of the last relocation: `dj_dx` holds the partial derivatives dJ/dx of a
/// scalar J of the node positions (`size` = 3 × num_nodes doubles, x0 y0 z0 x1 ...);
/// `dj_dprescribed` (`size` doubles) receives the total derivative of J with respect to every
/// prescribed coordinate, dJ/dx_p = dJ/dx_p (partial) − H_pf H_ff⁻¹ dJ/dx_f, through the
/// relocation's dependence of the free coordinates on the prescribed ones (implicit function
/// theorem at the stationary point; H the Hessian of F), and 0 at the free coordinates.
///
/// Free coordinates: those whose constraint bit is clear, of nodes that belong to a cell
/// (sliding nodes have both kinds); all others are prescribed, and z of every node of a 2D mesh.
/// Needs a last relocation with `stationarity_tolerance > 0` that reached it on a valid mesh;
/// `igaparam_mesh_move_nodes`, `igaparam_mesh_set_fixed`, `igaparam_mesh_reset_reference` and
/// a new relocation invalidate the state (the call then fails and says why). The factorisation
/// of H_ff (2D meshes and small 3D ones) is kept on the handle, so further products at one
/// state cost a solve each; larger 3D meshes solve by preconditioned conjugate gradients.
/// Uses the thread count of the last relocation.
#[no_mangle]
pub extern "C" fn igaparam_mesh_adjoint(
    mesh: *const igaparam_mesh,
    size: usize,
    dj_dx: *const f64,
    dj_dprescribed: *mut f64,
) -> igaparam_status {
    run("igaparam_mesh_adjoint", || {
        let handle = with_mesh(mesh)?;
        // The input is read before the output is written, so the two may be one array.
        let threads = handle.last_threads();
        let result = handle.adjoint(threads, slice(dj_dx, size, "dj_dx")?)?;
        slice_mut(dj_dprescribed, size, "dj_dprescribed")?.copy_from_slice(&result);
        Ok(())
    })
}

/// The tangent product of the last relocation (the transpose of `igaparam_mesh_adjoint`):
/// `dx_prescribed` (`size` = 3 × num_nodes doubles) is a motion of the prescribed coordinates
/// (its entries at free coordinates are ignored); `dx` (`size` doubles) receives the first-order
/// motion of every node: the given motion at prescribed coordinates, −H_ff⁻¹ H_fp dx_p at free
/// ones. Same conditions as `igaparam_mesh_adjoint`.
#[no_mangle]
pub extern "C" fn igaparam_mesh_tangent(
    mesh: *const igaparam_mesh,
    size: usize,
    dx_prescribed: *const f64,
    dx: *mut f64,
) -> igaparam_status {
    run("igaparam_mesh_tangent", || {
        let handle = with_mesh(mesh)?;
        // The input is read before the output is written, so the two may be one array.
        let threads = handle.last_threads();
        let result = handle.tangent(threads, slice(dx_prescribed, size, "dx_prescribed")?)?;
        slice_mut(dx, size, "dx")?.copy_from_slice(&result);
        Ok(())
    })
}
