//! The mesh handle: create a quad/hex mesh, constrain and move nodes, read back positions,
//! constraints and cell qualities (the relocation is in `relocate.rs`).

use std::ffi::c_int;

use super::ffi::{check_capacity, non_null_mut, run, slice, slice_mut, Failure};
use super::handle::{acquire, handle_type, release, Guarded, Held};
use super::igaparam_status;
use crate::error::{Error, Result};
use crate::fe_mesh::{CellType, Mesh, NodeOrder};
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

pub(super) fn cell_type(code: igaparam_cell_type) -> Result<CellType> {
    CellType::from_vtk(code as i64).ok_or_else(|| {
        Error::invalid(format!(
            "cell type {code} is not supported; use IGAPARAM_CELL_QUAD4/QUAD8/QUAD9/HEX8/HEX20/HEX27 (VTK codes 9, 23, 28, 12, 25, 29)"
        ))
    })
}

pub(super) fn target(code: igaparam_target) -> Result<TargetKind> {
    match code {
        IGAPARAM_TARGET_INITIAL => Ok(TargetKind::Reference),
        IGAPARAM_TARGET_MASTER => Ok(TargetKind::Master),
        _ => Err(Error::invalid(format!(
            "target {code} is neither IGAPARAM_TARGET_INITIAL (0) nor IGAPARAM_TARGET_MASTER (1)"
        ))),
    }
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
    new_mesh(
        "igaparam_mesh_new",
        cell_type_code,
        Ok(NodeOrder::Vtk),
        num_nodes,
        xyz,
        num_cells,
        connectivity,
        out,
    )
}

/// The body of `igaparam_mesh_new` and `igaparam_mesh_new_ordered`, named `function` in messages
/// (the arguments of the entry points, passed on; `order` is the node order the caller read, or
/// why it could not, reported after the checks of `out` and the cell type).
#[allow(clippy::too_many_arguments)]
pub(super) fn new_mesh(
    function: &str,
    cell_type_code: igaparam_cell_type,
    order: Result<NodeOrder>,
    num_nodes: usize,
    xyz: *const f64,
    num_cells: usize,
    connectivity: *const i64,
    out: *mut *mut igaparam_mesh,
) -> igaparam_status {
    run(function, || {
        let out = non_null_mut(out, "out")?;
        let ct = cell_type(cell_type_code)?;
        let order = order?;
        let len = |n: usize, per: usize, what: &str| {
            n.checked_mul(per)
                .ok_or_else(|| Error::invalid(format!("{what} is too large")))
        };
        let xyz = slice(xyz, len(num_nodes, 3, "num_nodes")?, "xyz")?;
        let conn = slice(
            connectivity,
            len(num_cells, ct.node_count(), "num_cells")?,
            "connectivity",
        )?;
        let mesh = Mesh::new_ordered(ct, xyz, conn, order)?;
        *out = super::handle::into_raw::<igaparam_mesh>(mesh);
        Ok(())
    })
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
        let mut m = with_mesh(mesh)?;
        m.set_fixed(slice(mask, num_nodes, "mask")?)?;
        Ok(())
    })
}

/// Sets the positions of `count` nodes: node `indices[i]` moves to `xyz[3i..3i+3]`. `indices`
/// may be NULL, meaning nodes `0..count-1`. Typically used for the boundary nodes before
/// `igaparam_mesh_relocate`; the reference shape is not changed. A free coordinate moved here is
/// where the next relocation starts only with `IGAPARAM_PLACEMENT_CURRENT`: the default
/// `IGAPARAM_PLACEMENT_LAPLACIAN` computes every free coordinate from the motion of the
/// prescribed ones, and `IGAPARAM_PLACEMENT_INCREMENTAL` from the last relocation's result, so
/// there the move of a free coordinate has no effect.
#[no_mangle]
pub extern "C" fn igaparam_mesh_move_nodes(
    mesh: *mut igaparam_mesh,
    count: usize,
    indices: *const i64,
    xyz: *const f64,
) -> igaparam_status {
    run("igaparam_mesh_move_nodes", || {
        let mut m = with_mesh(mesh)?;
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
        with_mesh(mesh)?.reset_reference();
        Ok(())
    })
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
fn copy_points(points: &[[f64; 3]], xyz: *mut f64, len: usize) -> std::result::Result<(), Failure> {
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
