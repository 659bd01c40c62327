//! The supported finite-element cell types, with VTK's codes and node orderings.

/// A quadrilateral or hexahedral Lagrange/serendipity cell; the value is VTK's cell type code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CellType {
    /// Bilinear quadrilateral, 4 nodes (`VTK_QUAD`).
    Quad4 = 9,
    /// Serendipity quadratic quadrilateral, 8 nodes (`VTK_QUADRATIC_QUAD`).
    Quad8 = 23,
    /// Biquadratic quadrilateral, 9 nodes (`VTK_BIQUADRATIC_QUAD`).
    Quad9 = 28,
    /// Trilinear hexahedron, 8 nodes (`VTK_HEXAHEDRON`).
    Hex8 = 12,
    /// Serendipity quadratic hexahedron, 20 nodes (`VTK_QUADRATIC_HEXAHEDRON`).
    Hex20 = 25,
    /// Triquadratic hexahedron, 27 nodes (`VTK_TRIQUADRATIC_HEXAHEDRON`).
    Hex27 = 29,
}

/// Lattice point (`i + 3j`) of each node of a VTK quadrilateral, in VTK order: corners
/// counter-clockwise, then mid-edges 0-1, 1-2, 2-3, 3-0, then the centre.
const QUAD_LATTICE: [usize; 9] = [0, 2, 8, 6, 1, 5, 7, 3, 4];

/// Lattice point (`i + 3j + 9k`) of each node of a VTK hexahedron, in VTK order: corners of the
/// bottom then top face, mid-edges of the bottom, top, then vertical edges, then the face centres
/// x−, x+, y−, y+, z−, z+, then the body centre.
const HEX_LATTICE: [usize; 27] = [
    0, 2, 8, 6, 18, 20, 26, 24, // corners
    1, 5, 7, 3, 19, 23, 25, 21, 9, 11, 17, 15, // mid-edges
    12, 14, 10, 16, 4, 22, // face centres
    13, // body centre
];

impl CellType {
    /// All supported types.
    pub const ALL: [CellType; 6] = [
        CellType::Quad4,
        CellType::Quad8,
        CellType::Quad9,
        CellType::Hex8,
        CellType::Hex20,
        CellType::Hex27,
    ];

    /// The type with VTK code `code`, if supported.
    pub fn from_vtk(code: i64) -> Option<CellType> {
        Self::ALL.into_iter().find(|t| *t as i64 == code)
    }

    /// Spatial dimension: 2 for quadrilaterals, 3 for hexahedra.
    pub fn dimension(self) -> usize {
        match self {
            CellType::Quad4 | CellType::Quad8 | CellType::Quad9 => 2,
            _ => 3,
        }
    }

    /// Number of nodes of one cell.
    pub fn node_count(self) -> usize {
        match self {
            CellType::Quad4 => 4,
            CellType::Quad8 => 8,
            CellType::Quad9 => 9,
            CellType::Hex8 => 8,
            CellType::Hex20 => 20,
            CellType::Hex27 => 27,
        }
    }

    /// Lattice point of each node, in VTK node order.
    pub fn lattice(self) -> &'static [usize] {
        let all: &'static [usize] = if self.dimension() == 2 {
            &QUAD_LATTICE
        } else {
            &HEX_LATTICE
        };
        &all[..self.node_count()]
    }

    /// A short name, e.g. `"Q9"`.
    pub fn name(self) -> &'static str {
        match self {
            CellType::Quad4 => "Q4",
            CellType::Quad8 => "Q8",
            CellType::Quad9 => "Q9",
            CellType::Hex8 => "H8",
            CellType::Hex20 => "H20",
            CellType::Hex27 => "H27",
        }
    }
}
