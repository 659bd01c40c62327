//! Meshes and boundary motions read from `.vtu` grids, and meshes written as `.vtu` files.

use std::path::Path;

use super::{CellType, Mesh};
use crate::error::{Error, Result};
use crate::io::vtu::{self, DataArray, Format, UnstructuredGrid};
use crate::optimize::TargetKind;

impl Mesh {
    /// Builds a mesh from a grid whose cells all have one supported type.
    pub fn from_grid(grid: &UnstructuredGrid) -> Result<Mesh> {
        let cell_type = grid_cell_type(grid)?;
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
    /// `fixed_components` (the constraint masks, integers in 0..=7) and `moved` (3 components:
    /// the new positions of the fixed coordinates), when present; a mask without `moved` fixes
    /// the nodes where they are.
    pub fn from_grid_with_motion(grid: &UnstructuredGrid) -> Result<Mesh> {
        let mut mesh = Mesh::from_grid(grid)?;
        let Some(mask) = grid.point_array("fixed_components") else {
            return Ok(mesh);
        };
        if mask.components != 1 {
            return Err(Error::mesh(format!(
                "point array `fixed_components` has {} components, expected 1",
                mask.components
            )));
        }
        let bits = mask
            .values
            .iter()
            .enumerate()
            .map(|(i, &v)| {
                (v.fract() == 0.0 && (0.0..=7.0).contains(&v))
                    .then_some(v as u8)
                    .ok_or_else(|| {
                        Error::mesh(format!(
                            "fixed_components[{i}] = {v} is not a mask in 0..=7"
                        ))
                    })
            })
            .collect::<Result<Vec<u8>>>()?;
        match grid.point_array("moved") {
            Some(moved) if moved.components != 3 => Err(Error::mesh(format!(
                "point array `moved` has {} components, expected 3",
                moved.components
            ))),
            Some(moved) => mesh.prescribe(&bits, &moved.values),
            None => mesh.set_fixed(&bits),
        }?;
        Ok(mesh)
    }

    /// Reads a mesh and its prescribed motion from a `.vtu` file in any storage (see
    /// [`crate::io::vtu`]): one supported cell type, node order VTK's; the point arrays
    /// `fixed_components` and `moved`, when present, as in [`Mesh::from_grid_with_motion`].
    pub fn read_vtu(path: &Path) -> Result<Mesh> {
        Mesh::from_grid_with_motion(&vtu::read(path)?)
    }

    /// The mesh as a grid: its current positions and cells (VTK node order), point data
    /// `displacement` (current minus reference positions) and `fixed_components` (UInt8
    /// masks), cell data `quality` (against the cells' reference shapes, 0 for invalid cells).
    pub fn to_grid(&self) -> Result<UnstructuredGrid> {
        let per = self.cell_type.node_count();
        let displacement = self
            .positions
            .iter()
            .zip(&self.reference)
            .flat_map(|(p, r)| [p[0] - r[0], p[1] - r[1], p[2] - r[2]])
            .collect();
        let array = |name: &str, components, values| DataArray {
            name: name.to_string(),
            components,
            values,
        };
        Ok(UnstructuredGrid {
            points: self.positions.iter().flatten().copied().collect(),
            connectivity: self.connectivity.iter().map(|&n| n as i64).collect(),
            offsets: (1..=self.cell_count()).map(|c| (c * per) as i64).collect(),
            types: vec![self.cell_type as u8; self.cell_count()],
            point_data: vec![
                array("displacement", 3, displacement),
                array(
                    "fixed_components",
                    1,
                    self.fixed.iter().map(|&m| m as f64).collect(),
                ),
            ],
            cell_data: vec![array(
                "quality",
                1,
                self.cell_quality(TargetKind::Reference)?,
            )],
            uint8_arrays: vec!["fixed_components".into()],
        })
    }

    /// Writes the mesh (see [`Mesh::to_grid`]) as a `.vtu` file in format `format`.
    pub fn write_vtu(&self, path: &Path, format: Format) -> Result<()> {
        vtu::write_as(path, &self.to_grid()?, format)
    }
}

/// The one supported cell type of a grid's cells, each with that type's node count (offsets
/// checked).
pub(super) fn grid_cell_type(grid: &UnstructuredGrid) -> Result<CellType> {
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
    Ok(cell_type)
}
