//! Node orders at the C boundary: meshes created from a connectivity in VTK's or Gmsh's node
//! order, the connectivity copied back in either, and the reference coordinates of each order's
//! local nodes (the documented tables, in machine-readable form).

use std::ffi::c_int;

use super::ffi::{check_capacity, non_null_mut, run, slice_mut};
use super::igaparam_status;
use super::mesh::{cell_type, igaparam_cell_type, igaparam_mesh, new_mesh, with_mesh};
use crate::error::{Error, Result};
use crate::fe_mesh::NodeOrder;

/// A local node order: one of the `IGAPARAM_ORDER_*` values.
///
/// VTK order (the library's own; meshio's and ParaView's), nodes by reference coordinates in
/// [-1,1]^d (xi, eta[, zeta]):
/// - Q4: 0 (-1,-1), 1 (1,-1), 2 (1,1), 3 (-1,1); Q8 adds the mid-edges 4 (0,-1), 5 (1,0),
///   6 (0,1), 7 (-1,0); Q9 adds the centre 8 (0,0).
/// - H8: 0-3 the corners of the face zeta = -1 as in Q4, 4-7 those of zeta = 1;
///   H20 adds the mid-edges 8-11 of the bottom face (edges 0-1, 1-2, 2-3, 3-0), 12-15 of the top
///   face (4-5, 5-6, 6-7, 7-4), 16-19 of the vertical edges (0-4, 1-5, 2-6, 3-7);
///   H27 adds the face centres 20 (xi = -1), 21 (xi = 1), 22 (eta = -1), 23 (eta = 1),
///   24 (zeta = -1), 25 (zeta = 1) and the body centre 26.
///
/// Gmsh order: quadrilaterals as VTK. Hexahedra: the same corners 0-7, then the mid-edges of the
/// edges 0-1, 0-3, 0-4, 1-2, 1-5, 2-3, 2-6, 3-7, 4-5, 4-7, 5-6, 6-7 (8-19), then the face centres
/// zeta = -1, eta = -1, xi = -1, xi = 1, eta = 1, zeta = 1 (20-25) and the body centre 26.
/// `igaparam_cell_type_copy_node_coordinates` gives these tables.
pub type igaparam_node_order = c_int;
/// VTK's node order (the default of `igaparam_mesh_new`).
pub const IGAPARAM_ORDER_VTK: igaparam_node_order = 0;
/// Gmsh's node order (`.msh` files, the Gmsh API).
pub const IGAPARAM_ORDER_GMSH: igaparam_node_order = 1;

fn node_order(code: igaparam_node_order) -> Result<NodeOrder> {
    match code {
        IGAPARAM_ORDER_VTK => Ok(NodeOrder::Vtk),
        IGAPARAM_ORDER_GMSH => Ok(NodeOrder::Gmsh),
        _ => Err(Error::invalid(format!(
            "node order {code} is neither IGAPARAM_ORDER_VTK (0) nor IGAPARAM_ORDER_GMSH (1)"
        ))),
    }
}

fn order_code(order: NodeOrder) -> igaparam_node_order {
    match order {
        NodeOrder::Vtk => IGAPARAM_ORDER_VTK,
        NodeOrder::Gmsh => IGAPARAM_ORDER_GMSH,
    }
}

/// `igaparam_mesh_new` for a connectivity whose cells list their nodes in `order` (an
/// `IGAPARAM_ORDER_*` value, see `igaparam_node_order` for the tables). The mesh keeps the order:
/// `igaparam_mesh_copy_connectivity` gives the cells back in it. A mesh every cell of which is
/// inverted or folded in the given positions is refused (`IGAPARAM_STATUS_INVALID_MESH`, with a
/// message naming the likely cause: a connectivity in another node order, or cells oriented the
/// wrong way).
#[no_mangle]
pub extern "C" fn igaparam_mesh_new_ordered(
    cell_type_code: igaparam_cell_type,
    order: igaparam_node_order,
    num_nodes: usize,
    xyz: *const f64,
    num_cells: usize,
    connectivity: *const i64,
    out: *mut *mut igaparam_mesh,
) -> igaparam_status {
    new_mesh(
        "igaparam_mesh_new_ordered",
        cell_type_code,
        node_order(order),
        num_nodes,
        xyz,
        num_cells,
        connectivity,
        out,
    )
}

/// Writes to `*out` the node order the mesh's connectivity was given in (`IGAPARAM_ORDER_VTK`
/// for meshes from `igaparam_mesh_new` and `igaparam_mesh_read_vtu`).
#[no_mangle]
pub extern "C" fn igaparam_mesh_order(
    mesh: *const igaparam_mesh,
    out: *mut igaparam_node_order,
) -> igaparam_status {
    run("igaparam_mesh_order", || {
        let order = with_mesh(mesh)?.node_order();
        *non_null_mut(out, "out")? = order_code(order);
        Ok(())
    })
}

/// Copies the connectivity into `connectivity` (`len` values, at least `num_cells × nodes per
/// cell`), each cell's nodes in `order` (an `IGAPARAM_ORDER_*` value; pass the one of
/// `igaparam_mesh_order` to get the cells back as given).
#[no_mangle]
pub extern "C" fn igaparam_mesh_copy_connectivity(
    mesh: *const igaparam_mesh,
    order: igaparam_node_order,
    connectivity: *mut i64,
    len: usize,
) -> igaparam_status {
    run("igaparam_mesh_copy_connectivity", || {
        let m = with_mesh(mesh)?;
        let order = node_order(order)?;
        let needed = m.cell_count() * m.cell_type().node_count();
        check_capacity("connectivity", len, needed)?;
        let out = slice_mut(connectivity, len, "connectivity")?;
        out[..needed].copy_from_slice(&m.connectivity_in(order));
        Ok(())
    })
}

/// Copies the reference coordinates in [-1,1]^d of the local nodes of `cell_type_code` in
/// `order` into `xi` (`len` doubles, at least `nodes per cell × d`; d = 2 for quadrilaterals,
/// 3 for hexahedra): node i at `xi[d i .. d i + d]`.
#[no_mangle]
pub extern "C" fn igaparam_cell_type_copy_node_coordinates(
    cell_type_code: igaparam_cell_type,
    order: igaparam_node_order,
    xi: *mut f64,
    len: usize,
) -> igaparam_status {
    run("igaparam_cell_type_copy_node_coordinates", || {
        let ct = cell_type(cell_type_code)?;
        let coords = node_order(order)?.reference_coordinates(ct);
        check_capacity("xi", len, coords.len())?;
        slice_mut(xi, len, "xi")?[..coords.len()].copy_from_slice(&coords);
        Ok(())
    })
}
