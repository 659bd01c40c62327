//! Local node orders: how the nodes of one cell are listed in a connectivity array. The mesh
//! keeps VTK's order inside; a connectivity in another order is converted on the way in and back
//! on the way out.
//!
//! Each order is a table giving, for each local node, its point of the cell's 3^d lattice
//! (`i + 3j + 9k`, with `i, j, k` ∈ {0, 1, 2} for the reference coordinates −1, 0, 1). Gmsh's
//! tables were read from Gmsh 4.15 (`gmsh.model.mesh.getElementProperties` of element types 3,
//! 16, 10, 5, 17, 12) and are checked against it by the Python tests. For quadrilaterals Gmsh's
//! order is VTK's; for hexahedra the corners agree and the mid-edge and face nodes do not.

use super::cell_type::CellType;
use crate::optimize::lattice;

/// How the nodes of a cell are listed in a connectivity array.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum NodeOrder {
    /// VTK's order (also meshio's and ParaView's), the library's own.
    #[default]
    Vtk,
    /// Gmsh's order (`.msh` files, the `gmsh` API).
    Gmsh,
}

/// Gmsh's hexahedron: corners of the bottom then top face, then the edges 0-1, 0-3, 0-4, 1-2,
/// 1-5, 2-3, 2-6, 3-7, 4-5, 4-7, 5-6, 6-7, then the face centres z−, y−, x−, x+, y+, z+, then the
/// body centre. The first 20 are the 20-node hexahedron, the first 8 the linear one.
const GMSH_HEX_LATTICE: [usize; 27] = [
    0, 2, 8, 6, 18, 20, 26, 24, // corners
    1, 3, 9, 5, 11, 7, 17, 15, 19, 21, 23, 25, // mid-edges
    4, 10, 12, 14, 16, 22, // face centres
    13, // body centre
];

impl NodeOrder {
    /// Lattice point of each local node of `cell_type` in this order.
    pub fn lattice(self, cell_type: CellType) -> &'static [usize] {
        match (self, cell_type.dimension()) {
            (NodeOrder::Gmsh, 3) => &GMSH_HEX_LATTICE[..cell_type.node_count()],
            // Quadrilaterals: Gmsh's order is VTK's (corners counter-clockwise, mid-edges 0-1,
            // 1-2, 2-3, 3-0, centre).
            _ => cell_type.lattice(),
        }
    }

    /// For each node of VTK's order, its place in this order: `vtk[i] = this[permutation[i]]`.
    pub fn permutation(self, cell_type: CellType) -> Vec<usize> {
        let own = self.lattice(cell_type);
        cell_type
            .lattice()
            .iter()
            .map(|l| {
                own.iter()
                    .position(|m| m == l)
                    .expect("same lattice points")
            })
            .collect()
    }

    /// Reference coordinates in [−1, 1]^d of each local node of `cell_type` in this order,
    /// `d` per node (d = 2 for quadrilaterals, 3 for hexahedra).
    pub fn reference_coordinates(self, cell_type: CellType) -> Vec<f64> {
        let d = cell_type.dimension();
        self.lattice(cell_type)
            .iter()
            .flat_map(|&l| {
                let c: Vec<usize> = if d == 2 {
                    lattice::coords::<2>(l).to_vec()
                } else {
                    lattice::coords::<3>(l).to_vec()
                };
                c.into_iter().map(|v| v as f64 - 1.0)
            })
            .collect()
    }

    /// `connectivity` (cells in this order) in VTK's order.
    pub fn to_vtk(self, cell_type: CellType, connectivity: &[i64]) -> Vec<i64> {
        let p = self.permutation(cell_type);
        connectivity
            .chunks(cell_type.node_count())
            .flat_map(|cell| p.iter().map(|&j| cell[j]).collect::<Vec<_>>())
            .collect()
    }

    /// `connectivity` (cells in VTK's order) in this order.
    pub fn from_vtk(self, cell_type: CellType, connectivity: &[i64]) -> Vec<i64> {
        let p = self.permutation(cell_type);
        let mut out = connectivity.to_vec();
        for (cell, vtk) in out
            .chunks_mut(cell_type.node_count())
            .zip(connectivity.chunks(cell_type.node_count()))
        {
            for (i, &j) in p.iter().enumerate() {
                cell[j] = vtk[i];
            }
        }
        out
    }

    /// The order's name, e.g. `"Gmsh"`.
    pub fn name(self) -> &'static str {
        match self {
            NodeOrder::Vtk => "VTK",
            NodeOrder::Gmsh => "Gmsh",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permutations_round_trip_and_agree_with_the_lattice() {
        for t in CellType::ALL {
            for order in [NodeOrder::Vtk, NodeOrder::Gmsh] {
                let n = t.node_count() as i64;
                let conn: Vec<i64> = (0..2 * n).map(|i| 100 - i).collect();
                assert_eq!(order.from_vtk(t, &order.to_vtk(t, &conn)), conn);
                let mut sorted = order.lattice(t).to_vec();
                sorted.sort();
                let mut vtk = t.lattice().to_vec();
                vtk.sort();
                assert_eq!(sorted, vtk, "{t:?} {order:?}");
            }
            assert_eq!(
                NodeOrder::Vtk.permutation(t),
                (0..t.node_count()).collect::<Vec<_>>()
            );
        }
        // Gmsh's 27-node hexahedron: VTK's node 9 (edge 1-2) is Gmsh's node 11.
        assert_eq!(NodeOrder::Gmsh.permutation(CellType::Hex27)[9], 11);
        assert_eq!(
            NodeOrder::Gmsh.reference_coordinates(CellType::Hex27)[3 * 20..3 * 21],
            [0.0, 0.0, -1.0]
        );
    }
}
