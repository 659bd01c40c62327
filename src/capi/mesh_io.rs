//! Meshes from and to files: `.vtu` reading and writing, so that a C host without VTK can use
//! the files VTK, ParaView, meshio and Gmsh exchange.

use std::ffi::{c_char, c_int};

use super::ffi::{c_path, non_null_mut, run};
use super::igaparam_status;
use super::mesh::{igaparam_cell_type, igaparam_mesh, with_mesh};
use crate::error::{Error, Result};
use crate::fe_mesh::Mesh;
use crate::io::vtu::{Encoding, Format};

/// The storage of a written `.vtu` file: one of `IGAPARAM_VTU_ASCII`, `IGAPARAM_VTU_BINARY`,
/// `IGAPARAM_VTU_APPENDED`, `IGAPARAM_VTU_APPENDED_BASE64`, the binary ones optionally OR-ed with
/// `IGAPARAM_VTU_ZLIB`.
pub type igaparam_vtu_format = c_int;
/// Numbers as text: large, for reading by eye.
pub const IGAPARAM_VTU_ASCII: igaparam_vtu_format = 0;
/// Base64 inside each array (`format="binary"`): valid XML, read by VTK, ParaView and meshio.
pub const IGAPARAM_VTU_BINARY: igaparam_vtu_format = 1;
/// Raw bytes in an appended section: the smallest, VTK's own default (not valid XML).
pub const IGAPARAM_VTU_APPENDED: igaparam_vtu_format = 2;
/// Base64 in an appended section.
pub const IGAPARAM_VTU_APPENDED_BASE64: igaparam_vtu_format = 3;
/// Flag: zlib-compress the binary data (`vtkZLibDataCompressor`).
pub const IGAPARAM_VTU_ZLIB: igaparam_vtu_format = 16;
/// The default: `IGAPARAM_VTU_BINARY | IGAPARAM_VTU_ZLIB`.
pub const IGAPARAM_VTU_DEFAULT: igaparam_vtu_format = 17;

fn vtu_format(code: igaparam_vtu_format) -> Result<Format> {
    let encoding = match code & !IGAPARAM_VTU_ZLIB {
        IGAPARAM_VTU_ASCII => Encoding::Ascii,
        IGAPARAM_VTU_BINARY => Encoding::Binary,
        IGAPARAM_VTU_APPENDED => Encoding::Appended,
        IGAPARAM_VTU_APPENDED_BASE64 => Encoding::AppendedBase64,
        _ => {
            return Err(Error::invalid(format!(
            "format {code} is not an IGAPARAM_VTU_* value (0 to 3, optionally | IGAPARAM_VTU_ZLIB)"
        )))
        }
    };
    let zlib = code & IGAPARAM_VTU_ZLIB != 0;
    if zlib && encoding == Encoding::Ascii {
        return Err(Error::invalid(
            "IGAPARAM_VTU_ASCII cannot be combined with IGAPARAM_VTU_ZLIB",
        ));
    }
    Ok(Format { encoding, zlib })
}

/// Reads a mesh from a VTK XML unstructured grid (`.vtu`) at `path` (NUL-terminated UTF-8), in
/// any storage VTK and meshio write: ASCII, inline base64, appended raw or base64 data,
/// uncompressed or zlib-compressed. The cells must all have one supported type (node order VTK's).
/// The point arrays `fixed_components` (integer masks, see `igaparam_mesh_set_fixed`) and `moved`
/// (3 components), when present, are applied: every node's fixed coordinates are set to `moved`
/// and its mask is set; a mask without `moved` fixes the nodes where they are. The file's points
/// are the reference shape. `out` receives the new handle (release with `igaparam_mesh_free`).
/// Fails with `IGAPARAM_STATUS_IO` for a file that cannot be read or is not understood,
/// `IGAPARAM_STATUS_INVALID_MESH` for unsupported or mixed cells or bad masks.
#[no_mangle]
pub extern "C" fn igaparam_mesh_read_vtu(
    path: *const c_char,
    out: *mut *mut igaparam_mesh,
) -> igaparam_status {
    run("igaparam_mesh_read_vtu", || {
        let out = non_null_mut(out, "out")?;
        let mesh = Mesh::read_vtu(c_path(path, "path")?)?;
        *out = super::handle::into_raw::<igaparam_mesh>(mesh);
        Ok(())
    })
}

/// Writes the mesh to a `.vtu` file at `path` (NUL-terminated UTF-8) in format `format` (an
/// `IGAPARAM_VTU_*` value): the current positions and the cells (VTK node order), point data
/// `displacement` (current minus reference positions) and `fixed_components` (UInt8 masks),
/// cell data `quality` (against the cells' reference shapes, 0 for an invalid cell).
/// Fails with `IGAPARAM_STATUS_IO` if the file cannot be written.
#[no_mangle]
pub extern "C" fn igaparam_mesh_write_vtu_format(
    mesh: *const igaparam_mesh,
    path: *const c_char,
    format: igaparam_vtu_format,
) -> igaparam_status {
    run("igaparam_mesh_write_vtu_format", || {
        let m = with_mesh(mesh)?;
        let path = c_path(path, "path")?;
        m.write_vtu(path, vtu_format(format)?)?;
        Ok(())
    })
}

/// `igaparam_mesh_write_vtu_format` with `IGAPARAM_VTU_DEFAULT` (zlib-compressed base64).
#[no_mangle]
pub extern "C" fn igaparam_mesh_write_vtu(
    mesh: *const igaparam_mesh,
    path: *const c_char,
) -> igaparam_status {
    run("igaparam_mesh_write_vtu", || {
        let m = with_mesh(mesh)?;
        m.write_vtu(c_path(path, "path")?, Format::default())?;
        Ok(())
    })
}

/// Writes the mesh's cell type (an `IGAPARAM_CELL_*` value) to `*out`.
#[no_mangle]
pub extern "C" fn igaparam_mesh_cell_type(
    mesh: *const igaparam_mesh,
    out: *mut igaparam_cell_type,
) -> igaparam_status {
    run("igaparam_mesh_cell_type", || {
        let t = with_mesh(mesh)?.cell_type();
        *non_null_mut(out, "out")? = t as igaparam_cell_type;
        Ok(())
    })
}
