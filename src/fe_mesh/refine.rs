//! Refinement of Lagrange-quadratic meshes (Q9, H27) with their prescribed motion: every cell
//! split into `s^d` children (or `s_0 s_1 s_2`, splits per cell axis) on its own quadratic map,
//! so that the refined mesh has the same geometry and boundary motion at any size (the scale
//! benchmark's meshes, convergence studies).

use std::collections::HashMap;

use super::from_vtu::grid_cell_type;
use super::CellType;
use crate::error::{Error, Result};
use crate::io::vtu::{DataArray, UnstructuredGrid};

/// Largest number of splits per direction.
const MAX_SPLITS: usize = 64;

/// Largest number of points of a refined grid (indices are 32-bit inside the library).
const MAX_POINTS: usize = 1 << 31;

/// The grid with each Q9 or H27 cell split into `splits^d` cells of the same type (`splits` from
/// 1 to 64): the new nodes are the cell's quadratic map at the children's lattice points, so the
/// geometry is unchanged.
/// Point arrays `fixed_components` (masks) and `moved` (prescribed positions), when present, are
/// carried over: a new node's `moved` is the quadratic interpolation of its cell's, and its mask
/// is the common bits of the nodes whose shape functions act at it — the nodes of the face or
/// edge it lies on (so a node inside a fixed boundary face is fixed as the face is), none inside a
/// cell. Other arrays are dropped. Nodes are numbered in the order the cells first meet them.
pub fn refined_grid(grid: &UnstructuredGrid, splits: usize) -> Result<UnstructuredGrid> {
    refined_grid_by(grid, [splits; 3])
}

/// [`refined_grid`] with a number of splits per local direction of the cells (`splits[k]`
/// along their axis ξ, η, ζ for `k` = 0, 1, 2; the third ignored for Q9 cells), e.g. a mesh
/// extruded along every cell's ζ refined more across the extrusion than along it. Cells that
/// share an edge must split it the same number of times, which holds where their local axes line
/// up; an edge split differently by two cells is an error that names it.
pub fn refined_grid_by(grid: &UnstructuredGrid, splits: [usize; 3]) -> Result<UnstructuredGrid> {
    let cell_type = lagrange_type(grid)?;
    let d = cell_type.dimension();
    // Axes past the dimension are not split.
    let splits: [usize; 3] = std::array::from_fn(|k| if k < d { splits[k] } else { 1 });
    if let Some(s) = splits.iter().find(|s| !(1..=MAX_SPLITS).contains(*s)) {
        return Err(Error::invalid(format!(
            "splits = {s}: expected 1 to {MAX_SPLITS}"
        )));
    }
    let per_cell: usize = splits[..d].iter().map(|s| 2 * s + 1).product();
    if grid.types.len().saturating_mul(per_cell) > MAX_POINTS {
        return Err(Error::invalid(format!(
            "{} cells split {:?} times would exceed {MAX_POINTS} points",
            grid.types.len(),
            &splits[..d]
        )));
    }
    let mask = point_array(grid, "fixed_components", 1)?;
    let moved = point_array(grid, "moved", 3)?;
    let mut out = Refinement {
        cell_type,
        splits,
        denominator: 2 * splits[..d].iter().fold(1, |l, &s| lcm(l, s)),
        ids: HashMap::new(),
        edges: HashMap::new(),
        points: Vec::new(),
        mask: mask.map(|_| Vec::new()),
        moved: moved.map(|_| Vec::new()),
        connectivity: Vec::new(),
    };
    let nodes = cell_type.node_count();
    for cell in grid.connectivity.chunks(nodes) {
        let lattice_nodes = lattice_nodes(cell_type, cell, grid.point_count())?;
        out.check_edges(&lattice_nodes)?;
        let source = Source {
            grid,
            nodes: &lattice_nodes,
            mask,
            moved,
        };
        out.cell(&source);
    }
    Ok(out.into_grid())
}

/// The least common multiple of `a` and `b` (both positive).
fn lcm(a: usize, b: usize) -> usize {
    let (mut x, mut y) = (a, b);
    while y != 0 {
        (x, y) = (y, x % y);
    }
    a / x * b
}

/// The cell type of a grid of Q9 or H27 cells ([`grid_cell_type`]'s checks) whose
/// connectivity holds exactly its cells.
fn lagrange_type(grid: &UnstructuredGrid) -> Result<CellType> {
    let cell_type = grid_cell_type(grid)?;
    if !matches!(cell_type, CellType::Quad9 | CellType::Hex27) {
        return Err(Error::invalid(
            "refinement needs Q9 or H27 cells (VTK types 28, 29)",
        ));
    }
    let nodes = cell_type.node_count();
    match grid.connectivity.len() == nodes * grid.types.len()
        && grid.offsets.len() == grid.types.len()
    {
        true => Ok(cell_type),
        false => Err(Error::invalid(format!(
            "refinement needs {nodes} nodes per cell"
        ))),
    }
}

/// The point array `name` with `components` per point, if present.
fn point_array<'g>(
    grid: &'g UnstructuredGrid,
    name: &str,
    components: usize,
) -> Result<Option<&'g [f64]>> {
    match grid.point_array(name) {
        Some(a)
            if a.components != components || a.values.len() != components * grid.point_count() =>
        {
            Err(Error::invalid(format!(
                "point array `{name}` needs {components} value(s) per point"
            )))
        }
        Some(a) => Ok(Some(&a.values)),
        None => Ok(None),
    }
}

/// The global node of each lattice point (`i + 3j + 9k`) of one cell.
fn lattice_nodes(cell_type: CellType, cell: &[i64], points: usize) -> Result<Vec<usize>> {
    let mut out = vec![0; cell.len()];
    for (&l, &node) in cell_type.lattice().iter().zip(cell) {
        out[l] = usize::try_from(node)
            .ok()
            .filter(|&n| n < points)
            .ok_or_else(|| Error::invalid(format!("node index {node} is out of range")))?;
    }
    Ok(out)
}

/// One parent cell: its lattice nodes and the grid's arrays.
struct Source<'a> {
    grid: &'a UnstructuredGrid,
    nodes: &'a [usize],
    mask: Option<&'a [f64]>,
    moved: Option<&'a [f64]>,
}

/// The refined grid being built.
struct Refinement {
    cell_type: CellType,
    /// Splits per local direction.
    splits: [usize; 3],
    /// Twice the least common multiple of the splits: a point's coordinate along a parent edge
    /// is an integer multiple of `1 / denominator`.
    denominator: usize,
    /// A new node's key: the parent's corner nodes with the integer weights of the point in
    /// their multilinear combination (in units of `1 / denominator^d`) — the same from every
    /// cell that shares the point, whatever its orientation.
    ids: HashMap<Vec<(usize, u64)>, u32>,
    /// Per parent edge (its two corner nodes, in order): its splits and the first cell's index.
    edges: HashMap<(usize, usize), (usize, usize)>,
    points: Vec<f64>,
    mask: Option<Vec<f64>>,
    moved: Option<Vec<f64>>,
    connectivity: Vec<i64>,
}

impl Refinement {
    /// Records the splits of the cell's edges (its lattice nodes `nodes`); an error where an
    /// edge was split differently by an earlier cell.
    fn check_edges(&mut self, nodes: &[usize]) -> Result<()> {
        let d = self.cell_type.dimension();
        let cell = self.connectivity.len() / self.cell_type.node_count() / self.children();
        for k in 0..d {
            for corner in (0..1usize << d).filter(|c| c >> k & 1 == 0) {
                let [a, b] = [corner, corner | 1 << k].map(|c| nodes[corner_lattice(c, d)]);
                let edge = (a.min(b), a.max(b));
                let (splits, first) = *self.edges.entry(edge).or_insert((self.splits[k], cell));
                if splits != self.splits[k] {
                    return Err(Error::invalid(format!(
                        "the edge between nodes {} and {} is divided into {splits} part(s) by \
                         cell {first} and {} by cell {cell}: their local axes do not line up \
                         (use the same splits in every direction)",
                        edge.0, edge.1, self.splits[k]
                    )));
                }
            }
        }
        Ok(())
    }

    /// Children per parent cell.
    fn children(&self) -> usize {
        self.splits[..self.cell_type.dimension()].iter().product()
    }

    /// Fine lattice points per direction, `2 s + 1`.
    fn fine_radix(&self) -> [usize; 3] {
        self.splits.map(|s| 2 * s + 1)
    }

    /// Adds the children of one cell.
    fn cell(&mut self, source: &Source<'_>) {
        let d = self.cell_type.dimension();
        let n = self.fine_radix();
        let fine: Vec<u32> = (0..n[..d].iter().product())
            .map(|f| self.node(source, &digits(f, n, d)))
            .collect();
        let lattice = self.cell_type.lattice();
        for child in 0..self.children() {
            let corner = digits(child, self.splits, d);
            for &l in lattice {
                let local = digits(l, [3; 3], d);
                let index = (0..d)
                    .rev()
                    .fold(0, |acc, k| acc * n[k] + 2 * corner[k] + local[k]);
                self.connectivity.push(fine[index] as i64);
            }
        }
    }

    /// The id of the point at fine lattice index `at` (per direction `k` in `0..=2 s_k`, the
    /// first `d` used) of the cell, created on first sight.
    fn node(&mut self, source: &Source<'_>, at: &[usize; 3]) -> u32 {
        let d = self.cell_type.dimension();
        // The point's coordinate along axis k in units of 1/denominator.
        let unit: Vec<u64> = (0..d)
            .map(|k| (at[k] * (self.denominator / (2 * self.splits[k]))) as u64)
            .collect();
        let whole = self.denominator as u64;
        let mut key: Vec<(usize, u64)> = (0..1usize << d)
            .map(|corner| {
                let weight = (0..d)
                    .map(|k| match corner >> k & 1 {
                        0 => whole - unit[k],
                        _ => unit[k],
                    })
                    .product();
                (source.nodes[corner_lattice(corner, d)], weight)
            })
            .filter(|&(_, w)| w > 0)
            .collect();
        key.sort_unstable();
        if let Some(&id) = self.ids.get(&key) {
            return id;
        }
        let id = self.ids.len() as u32;
        self.ids.insert(key, id);
        self.add_point(source, at);
        id
    }

    /// Appends the point at fine index `at`: position, `moved` and mask from the cell's nodes.
    fn add_point(&mut self, source: &Source<'_>, at: &[usize; 3]) {
        let d = self.cell_type.dimension();
        let basis: Vec<[f64; 3]> = (0..d)
            .map(|k| quadratic_basis(at[k], self.splits[k]))
            .collect();
        let mut position = [0.0; 3];
        let mut moved = [0.0; 3];
        let mut bits = 7u8;
        for (l, &node) in source.nodes.iter().enumerate() {
            let local = digits(l, [3; 3], d);
            let weight: f64 = (0..d).map(|k| basis[k][local[k]]).product();
            if weight == 0.0 {
                continue;
            }
            for k in 0..3 {
                position[k] += weight * source.grid.points[3 * node + k];
                if let Some(m) = source.moved {
                    moved[k] += weight * m[3 * node + k];
                }
            }
            if let Some(mask) = source.mask {
                bits &= mask[node] as u8;
            }
        }
        self.points.extend(position);
        if let Some(out) = self.moved.as_mut() {
            out.extend(moved);
        }
        if let Some(out) = self.mask.as_mut() {
            out.push(bits as f64);
        }
    }

    fn into_grid(self) -> UnstructuredGrid {
        let nodes = self.cell_type.node_count();
        let cells = self.connectivity.len() / nodes;
        let mut point_data = Vec::new();
        let mut uint8_arrays = Vec::new();
        if let Some(values) = self.mask {
            point_data.push(array("fixed_components", 1, values));
            uint8_arrays.push("fixed_components".to_string());
        }
        if let Some(values) = self.moved {
            point_data.push(array("moved", 3, values));
        }
        UnstructuredGrid {
            points: self.points,
            connectivity: self.connectivity,
            offsets: (1..=cells).map(|c| (c * nodes) as i64).collect(),
            types: vec![self.cell_type as u8; cells],
            point_data,
            cell_data: Vec::new(),
            uint8_arrays,
        }
    }
}

fn array(name: &str, components: usize, values: Vec<f64>) -> DataArray {
    DataArray {
        name: name.to_string(),
        components,
        values,
    }
}

/// The first `d` digits of `index` in the mixed radix `n` (digit `k` in `0..n[k]`), least
/// significant first.
fn digits(index: usize, n: [usize; 3], d: usize) -> [usize; 3] {
    let mut out = [0; 3];
    let mut rest = index;
    for (digit, n) in out.iter_mut().zip(n).take(d) {
        *digit = rest % n;
        rest /= n;
    }
    out
}

/// The lattice index (`i + 3j + 9k`) of corner `corner` (bit `k`: the far end along axis `k`).
fn corner_lattice(corner: usize, d: usize) -> usize {
    (0..d)
        .rev()
        .fold(0, |acc, k| acc * 3 + 2 * (corner >> k & 1))
}

/// The three 1D quadratic Lagrange functions (nodes −1, 0, 1) at fine index `i` of `0..=2s`
/// (`t = i/s − 1`): exactly 0 and 1 at the nodes.
fn quadratic_basis(i: usize, s: usize) -> [f64; 3] {
    if i % s == 0 {
        let mut exact = [0.0; 3];
        exact[i / s] = 1.0;
        return exact;
    }
    let t = i as f64 / s as f64 - 1.0;
    [0.5 * t * (t - 1.0), 1.0 - t * t, 0.5 * t * (t + 1.0)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Mesh;

    /// A structured grid of `nx × ny (× nz)` Lagrange cells on the map `f` of the box
    /// `[0, nx] × [0, ny] (× [0, nz])`, with mask 3 (7 in 3D) and `moved = motion(x)` on the
    /// boundary. `turned` lists cells whose local axes 0 and 1 are reversed (turned half a turn).
    fn structured(
        n: [usize; 3],
        d: usize,
        f: impl Fn([f64; 3]) -> [f64; 3],
        motion: impl Fn([f64; 3]) -> [f64; 3],
        turned: &[usize],
    ) -> UnstructuredGrid {
        let lattice_n: Vec<usize> = (0..3)
            .map(|k| if k < d { 2 * n[k] + 1 } else { 1 })
            .collect();
        let id = |i: usize, j: usize, k: usize| i + lattice_n[0] * (j + lattice_n[1] * k);
        let mut grid = UnstructuredGrid::default();
        let (mut mask, mut moved) = (Vec::new(), Vec::new());
        for k in 0..lattice_n[2] {
            for j in 0..lattice_n[1] {
                for i in 0..lattice_n[0] {
                    let x = f([i as f64 / 2.0, j as f64 / 2.0, k as f64 / 2.0]);
                    grid.points.extend(x);
                    let boundary = [i, j, k]
                        .iter()
                        .zip(&lattice_n)
                        .take(d)
                        .any(|(&a, &m)| a == 0 || a == m - 1);
                    mask.push(if boundary { ((1 << d) - 1) as f64 } else { 0.0 });
                    moved.extend(if boundary { motion(x) } else { x });
                }
            }
        }
        let cell_type = if d == 2 {
            CellType::Quad9
        } else {
            CellType::Hex27
        };
        let cells = n[0] * n[1] * if d == 3 { n[2] } else { 1 };
        for c in 0..cells {
            let (ci, cj, ck) = (c % n[0], (c / n[0]) % n[1], c / (n[0] * n[1]));
            for &l in cell_type.lattice() {
                let mut local = digits(l, [3; 3], d);
                if turned.contains(&c) {
                    local[0] = 2 - local[0];
                    local[1] = 2 - local[1];
                }
                let node = id(2 * ci + local[0], 2 * cj + local[1], 2 * ck + local[2]);
                grid.connectivity.push(node as i64);
            }
            grid.offsets.push(grid.connectivity.len() as i64);
            grid.types.push(cell_type as u8);
        }
        grid.point_data = vec![array("fixed_components", 1, mask), array("moved", 3, moved)];
        grid
    }

    /// The number of invalid cells of `grid`.
    fn invalid(grid: &UnstructuredGrid) -> usize {
        Mesh::from_grid(grid).unwrap().invalid_cell_count().unwrap()
    }

    fn curved(x: [f64; 3]) -> [f64; 3] {
        [x[0], x[1] + 0.1 * x[0] * x[0], x[2] + 0.05 * x[1] * x[1]]
    }

    fn affine(x: [f64; 3]) -> [f64; 3] {
        [
            1.1 * x[0] - 0.2 * x[1] + 0.3,
            0.1 * x[0] + 0.9 * x[1],
            x[2] - 0.05 * x[0],
        ]
    }

    /// The refined Q9 grid has the structured grid's point count, lies on the parent map at the
    /// fine lattice, carries an affine motion exactly and fixes its boundary only.
    #[test]
    fn q9_refinement_keeps_the_geometry_and_the_motion() {
        let grid = structured([2, 1, 1], 2, curved, affine, &[]);
        let s = 3;
        let fine = refined_grid(&grid, s).unwrap();
        assert_eq!(fine.point_count(), 13 * 7);
        assert_eq!(fine.types.len(), 2 * s * s);
        let mask = &fine.point_array("fixed_components").unwrap().values;
        let moved = &fine.point_array("moved").unwrap().values;
        for p in 0..fine.point_count() {
            let x = [fine.points[3 * p], fine.points[3 * p + 1], 0.0];
            let (u, v) = (x[0], x[1] - 0.1 * x[0] * x[0]);
            for t in [u, v] {
                assert!((t * 6.0 - (t * 6.0).round()).abs() < 1e-12, "{x:?}");
            }
            let boundary = [u, v, u - 2.0, v - 1.0].iter().any(|t| t.abs() < 1e-12);
            assert_eq!(mask[p], if boundary { 3.0 } else { 0.0 }, "{x:?}");
            if boundary {
                let m = affine(x);
                assert!((moved[3 * p] - m[0]).abs() < 1e-12);
                assert!((moved[3 * p + 1] - m[1]).abs() < 1e-12);
            }
        }
        let mut mesh = Mesh::from_grid_with_motion(&fine).unwrap();
        let report = mesh
            .relocate(&Default::default(), &mut |_, _, _| true)
            .unwrap();
        assert_eq!(report.invalid_after, 0);
    }

    /// H27 cells meeting with different local orientations share the new nodes of their face.
    #[test]
    fn h27_refinement_merges_faces_of_any_orientation() {
        let grid = structured([2, 1, 1], 3, curved, affine, &[1]);
        assert_eq!(invalid(&grid), 0);
        let fine = refined_grid(&grid, 2).unwrap();
        assert_eq!(fine.point_count(), 9 * 5 * 5);
        assert_eq!(fine.types.len(), 16);
        assert_eq!(invalid(&fine), 0);
        let once = refined_grid(&grid, 1).unwrap();
        assert_eq!(once.point_count(), grid.point_count());
        let sorted = |points: &[f64]| {
            let mut p: Vec<[u64; 3]> = points
                .chunks(3)
                .map(|x| [x[0].to_bits(), x[1].to_bits(), x[2].to_bits()])
                .collect();
            p.sort_unstable();
            p
        };
        assert_eq!(sorted(&once.points), sorted(&grid.points));
    }

    /// Splits per direction: the point and cell counts of the structured grid so refined, every
    /// point on the parent map's lattice of those splits, the cells valid; cells turned half a
    /// turn (axes reversed, still lined up) share their faces' new nodes.
    #[test]
    fn h27_refinement_by_direction_keeps_the_geometry() {
        let grid = structured([2, 1, 1], 3, curved, affine, &[1]);
        let fine = refined_grid_by(&grid, [2, 1, 3]).unwrap();
        assert_eq!(fine.point_count(), 9 * 3 * 7);
        assert_eq!(fine.types.len(), 2 * 2 * 3);
        assert_eq!(invalid(&fine), 0);
        for x in fine.points.chunks(3) {
            let v = x[1] - 0.1 * x[0] * x[0];
            let u = [x[0], v, x[2] - 0.05 * v * v];
            for (t, n) in u.iter().zip([4.0, 2.0, 6.0]) {
                assert!((t * n - (t * n).round()).abs() < 1e-12, "{x:?}");
            }
        }
    }

    /// A cell turned a quarter turn has its first axis along its neighbour's second: splits
    /// that differ between those axes are refused, naming the edge; equal ones are not.
    #[test]
    fn refinement_by_direction_refuses_axes_that_do_not_line_up() {
        let mut grid = structured([2, 1, 1], 2, curved, affine, &[]);
        let lattice = CellType::Quad9.lattice();
        let old: Vec<i64> = grid.connectivity[9..18].to_vec();
        let by_local = |i: usize, j: usize| {
            let at = lattice.iter().position(|&l| l == i + 3 * j).unwrap();
            old[at]
        };
        for (slot, &l) in lattice.iter().enumerate() {
            let (i, j) = (l % 3, l / 3);
            grid.connectivity[9 + slot] = by_local(j, 2 - i);
        }
        assert_eq!(invalid(&grid), 0);
        let error = refined_grid_by(&grid, [2, 1, 1]).unwrap_err().to_string();
        assert!(
            error.contains("into 1 part(s) by cell 0 and 2 by cell 1"),
            "{error}"
        );
        assert!(refined_grid_by(&grid, [3, 3, 1]).is_ok());
    }

    #[test]
    fn refinement_refuses_other_cells_and_splits() {
        let grid = structured([1, 1, 1], 2, curved, affine, &[]);
        assert!(refined_grid(&grid, 0).is_err());
        assert!(refined_grid(&grid, MAX_SPLITS + 1).is_err());
        // The third axis of Q9 cells is not split, whatever is asked for it.
        let q9 = refined_grid_by(&grid, [2, 3, usize::MAX]).unwrap();
        assert_eq!(q9.types.len(), 6);
        let mut linear = grid.clone();
        linear.types = vec![CellType::Quad4 as u8];
        assert!(refined_grid(&linear, 2).is_err());
        let mut short = grid;
        short.connectivity.pop();
        assert!(refined_grid(&short, 2).is_err());
    }
}
