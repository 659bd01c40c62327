//! VTK XML unstructured grids (`igaparam::io::vtu::parse`, every storage) and the meshes built
//! from them (`igaparam::Mesh::from_grid_with_motion`, what `igaparam_mesh_read_vtu` does). An
//! accepted grid must be consistent, and written in any format it must read back the same.

use igaparam::io::vtu::{parse, to_bytes, DataArray, Encoding, Format, UnstructuredGrid};
use igaparam::Mesh;

use crate::common::checked;

/// Parses `data` as a `.vtu` file, writes it back in every format, and builds a mesh of it.
pub fn run(data: &[u8]) {
    let Some(grid) = checked("vtu::parse", parse(data)) else {
        return;
    };
    check_grid(&grid);
    for encoding in Encoding::all() {
        for zlib in [false, true] {
            let format = Format { encoding, zlib };
            let Some(bytes) = checked("vtu::to_bytes", to_bytes(&grid, format)) else {
                continue;
            };
            let again = parse(&bytes).unwrap_or_else(|e| {
                panic!(
                    "{format:?}: a written grid does not read back: {}",
                    e.message
                )
            });
            assert!(
                same_grid(&grid, &again),
                "{format:?}: the grid read back differs"
            );
        }
    }
    if let Some(mesh) = checked(
        "Mesh::from_grid_with_motion",
        Mesh::from_grid_with_motion(&grid),
    ) {
        assert_eq!(mesh.node_count(), grid.point_count());
        assert_eq!(mesh.cell_count(), grid.types.len());
        let _ = mesh.invalid_cell_count();
    }
}

/// What the reader promises of a grid: whole points, one offset per cell, offsets within the
/// connectivity, connectivity within the points, arrays of whole tuples.
fn check_grid(g: &UnstructuredGrid) {
    assert_eq!(g.points.len() % 3, 0, "points");
    assert_eq!(g.offsets.len(), g.types.len(), "offsets and types");
    assert!(
        g.offsets.windows(2).all(|w| w[0] <= w[1]),
        "offsets decrease"
    );
    let end = g.offsets.last().copied().unwrap_or(0);
    assert!(
        end >= 0 && end as usize <= g.connectivity.len(),
        "offsets past the connectivity"
    );
    let n = g.point_count() as i64;
    assert!(
        g.connectivity.iter().all(|&c| (0..n).contains(&c)),
        "connectivity"
    );
    for (arrays, tuples) in [
        (&g.point_data, g.point_count()),
        (&g.cell_data, g.types.len()),
    ] {
        for a in arrays.iter() {
            assert!(a.components > 0, "array `{}` of 0 components", a.name);
            assert_eq!(a.values.len(), a.components * tuples, "array `{}`", a.name);
        }
    }
}

fn same_values(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| x == y || (x.is_nan() && y.is_nan()))
}

fn same_arrays(a: &[DataArray], b: &[DataArray]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| {
            x.name == y.name && x.components == y.components && same_values(&x.values, &y.values)
        })
}

fn same_grid(a: &UnstructuredGrid, b: &UnstructuredGrid) -> bool {
    same_values(&a.points, &b.points)
        && a.connectivity == b.connectivity
        && a.offsets == b.offsets
        && a.types == b.types
        && same_arrays(&a.point_data, &b.point_data)
        && same_arrays(&a.cell_data, &b.cell_data)
}
