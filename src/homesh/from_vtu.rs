//! Meshes and boundary motions read from `.vtu` grids.

use super::{CellType, Mesh};
use crate::error::{Error, Result};
use crate::io::vtu::UnstructuredGrid;

impl Mesh {
    /// Builds a mesh from a grid whose cells all have one supported type.
    pub fn from_grid(grid: &UnstructuredGrid) -> Result<Mesh> {
        let first = *grid
            .types
            .first()
            .ok_or_else(|| Error::mesh("the grid has no cells"))?;
        let cell_type = CellType::from_vtk(first as i64).ok_or_else(|| {
            Error::mesh(format!(
                "VTK cell type {first} is not a supported quad/hex type"
            ))
        })?;
        if let Some(c) = grid.types.iter().position(|&t| t != first) {
            return Err(Error::mesh(format!(
                "cell {c} has VTK type {}, but cell 0 has type {first}: one cell type per mesh",
                grid.types[c]
            )));
        }
        let per_cell = cell_type.node_count() as i64;
        for (c, &end) in grid.offsets.iter().enumerate() {
            if end != (c as i64 + 1) * per_cell {
                return Err(Error::mesh(format!(
                    "cell {c} does not have {per_cell} nodes"
                )));
            }
        }
        Mesh::new(cell_type, &grid.points, &grid.connectivity)
    }

    /// Applies a prescribed boundary motion: `mask` as in [`Mesh::set_fixed`], `moved`
    /// (`#nodes × 3`) the new positions; every fixed coordinate takes its `moved` value, free
    /// coordinates keep theirs.
    pub fn prescribe(&mut self, mask: &[u8], moved: &[f64]) -> Result<()> {
        if moved.len() != 3 * self.node_count() {
            return Err(Error::invalid(format!(
                "moved has {} values, expected 3 per node ({})",
                moved.len(),
                3 * self.node_count()
            )));
        }
        crate::error::check_finite("moved", moved)?;
        self.set_fixed(mask)?;
        for ((p, m), &bits) in self.positions.iter_mut().zip(moved.chunks(3)).zip(mask) {
            for k in 0..3 {
                if bits & (1 << k) != 0 {
                    p[k] = m[k];
                }
            }
        }
        Ok(())
    }

    /// Builds a mesh from a grid and applies the motion given by its point arrays
    /// `fixed_components` and `moved`, when present.
    pub fn from_grid_with_motion(grid: &UnstructuredGrid) -> Result<Mesh> {
        let mut mesh = Mesh::from_grid(grid)?;
        if let (Some(mask), Some(moved)) = (
            grid.point_array("fixed_components"),
            grid.point_array("moved"),
        ) {
            let bits: Vec<u8> = mask.values.iter().map(|&v| v as u8).collect();
            mesh.prescribe(&bits, &moved.values)?;
        }
        Ok(mesh)
    }
}
