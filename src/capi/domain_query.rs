//! Reading back a built domain: its T-mesh's vertices, cells, qualities and corners, and its
//! VTU output.

use std::ffi::c_char;

use super::domain::{held, igaparam_domain, with_built, BuiltRef};
use super::ffi::{c_path, check_capacity, non_null_mut, optional_out, run, slice_mut};
use super::igaparam_status;
use crate::domain::{CubeMap, Domain};

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

/// The flat arrays of a built domain.
fn view_of<const D: usize, B: CubeMap<D>>(d: &Domain<D, B>) -> BuiltView {
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

/// The flat arrays of a built domain of either dimension.
fn view(built: BuiltRef<'_>) -> BuiltView {
    with_built!(built, d => view_of(d))
}

/// Writes the number of vertices of the built T-mesh (hanging ones included) to `*out`.
/// Fails with `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built.
#[no_mangle]
pub extern "C" fn igaparam_domain_vertex_count(
    domain: *const igaparam_domain,
    out: *mut usize,
) -> igaparam_status {
    run("igaparam_domain_vertex_count", || {
        let out = non_null_mut(out, "out")?;
        *out = with_built!(held(domain)?.built()?, d => d.mesh().vertex_count());
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
        let out = non_null_mut(out, "out")?;
        *out = with_built!(held(domain)?.built()?, d => d.mesh().cell_count());
        Ok(())
    })
}

/// Copies the vertices of the built T-mesh: `parametric` receives their parametric coordinates
/// in [0,1]^d (u, v; u, v, w for a solid), and `physical` their coordinates in the domain (x, y;
/// x, y, z), each `num_vertices × d` doubles (d = 2 for a planar domain, 3 for a solid; see
/// `igaparam_domain_dimension`). Either may be NULL to skip it; `len_each` is the number of
/// doubles each non-NULL buffer holds (at least `d × num_vertices`). Fails with
/// `IGAPARAM_STATUS_INVALID_ARGUMENT` if the domain has not been built.
#[allow(rustdoc::broken_intra_doc_links)]
#[no_mangle]
pub extern "C" fn igaparam_domain_copy_vertices(
    domain: *const igaparam_domain,
    parametric: *mut f64,
    physical: *mut f64,
    len_each: usize,
) -> igaparam_status {
    run("igaparam_domain_copy_vertices", || {
        let v = view(held(domain)?.built()?);
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
        let d = held(domain)?;
        let q = with_built!(d.built()?, d => d.quality());
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
        let v = view(held(domain)?.built()?);
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
        let v = view(held(domain)?.built()?);
        check_capacity("corners", len, v.corners.len())?;
        slice_mut(corners, len, "corners")?[..v.corners.len()].copy_from_slice(&v.corners);
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
        let path = c_path(path, "path")?;
        let grid = with_built!(held(domain)?.built()?, d => d.to_grid());
        crate::io::vtu::write(path, &grid)?;
        Ok(())
    })
}
