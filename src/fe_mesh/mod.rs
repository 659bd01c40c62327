//! Existing finite-element meshes of quadrilaterals or hexahedra (linear, serendipity or Lagrange
//! quadratic) whose boundary moves: the free nodes are relocated so that every cell stays valid
//! and well shaped, with the connectivity unchanged.

mod cell_type;
mod from_vtu;
mod newton;
mod node_order;
mod refine;
mod relocate;
mod sensitivity;

/// The scale rule of relocation: the mesh is optimized in coordinates multiplied by
/// `unit_of(extent)`, `extent` the largest side of the bounding box of the reference shape, so
/// that the optimizer always sees a mesh of size 1–2 and every tolerance inside it (the δ
/// rule's ε, validity, stopping rules) is relative to the mesh's own size.
pub(crate) use crate::optimize::single::unit_of;
pub use cell_type::CellType;
pub use node_order::NodeOrder;
pub use refine::{refined_grid, refined_grid_by};
pub(crate) use relocate::sweep_motion;
pub use relocate::{
    Method, Placement, RelocateOptions, RelocateReport, Stage, DEFAULT_NEWTON_TOLERANCE,
};

use std::sync::Arc;

use crate::error::{check_finite, Error, Result};
use crate::optimize::blocks::BlockLayout;
use crate::optimize::solver::SolverSetup;
use crate::optimize::{CellPattern, CellSpec, Problem, TargetKind};

/// A Hessian solver of either dimension (`HessianSolver<2>` or `<3>`), shared between a mesh
/// and its clones.
type Solver = Arc<dyn std::any::Any + Send + Sync>;

/// A [`Problem`] of either dimension (`Problem<2>` or `<3>`).
type AnyProblem = Arc<dyn std::any::Any + Send + Sync>;

/// Node positions with, where known, the solver of the Hessian there (for the constraints and
/// reference of the mesh when it was stored).
#[derive(Clone, Debug)]
struct State {
    positions: Vec<[f64; 3]>,
    solver: Option<Solver>,
    /// Whether `positions` are a stationary point of the objective (to the tolerance asked for).
    stationary: bool,
    /// Worker threads of the relocation that made this state.
    threads: usize,
}

/// A quad or hex mesh with one cell type, reference and current node positions, and per-node
/// constraints.
///
/// Points always have three coordinates, as in VTK and Gmsh; for quadrilaterals the z coordinate
/// is carried along unchanged.
#[derive(Clone, Debug)]
pub struct Mesh {
    cell_type: CellType,
    reference: Vec<[f64; 3]>,
    positions: Vec<[f64; 3]>,
    connectivity: Vec<u32>,
    fixed: Vec<u8>,
    /// The state of the last successful relocation: where `Placement::Incremental` starts.
    last: Option<State>,
    /// Whether the sensitivities of `last` hold for the mesh as it is; else why not.
    sensitivity: std::result::Result<(), String>,
    /// The optimum at the reference shape's prescribed coordinates, for the target it was
    /// computed with: where path following from the reference starts.
    reference_state: Option<(TargetKind, State)>,
    /// The layout of the Hessian (depends on the connectivity only), built when first needed.
    layout: Option<Arc<BlockLayout>>,
    /// The Hessian solvers' setup for the current constraints, built when first needed.
    setup: Option<Arc<SolverSetup>>,
    /// The optimizer's view of the mesh for the current constraints and reference shape, for
    /// the target it was built with; built when first needed.
    problem: Option<(TargetKind, AnyProblem)>,
    /// The node order the connectivity was given in (kept in VTK's order here).
    order: NodeOrder,
}

impl Mesh {
    /// Builds a mesh from `xyz` (`#nodes × 3`, flat) and `connectivity` (`#cells × nodes per
    /// cell`, VTK node order; see [`Mesh::new_ordered`] for others). The positions become the
    /// reference shape; all nodes start free. A mesh every cell of which is inverted or folded
    /// is refused: its node order or orientation is wrong.
    pub fn new(cell_type: CellType, xyz: &[f64], connectivity: &[i64]) -> Result<Mesh> {
        let mesh = Mesh::new_unchecked(cell_type, xyz, connectivity)?;
        mesh.check_orientation()?;
        Ok(mesh)
    }

    /// [`Mesh::new`] without the check of the cells' orientation.
    fn new_unchecked(cell_type: CellType, xyz: &[f64], connectivity: &[i64]) -> Result<Mesh> {
        if xyz.is_empty() || xyz.len() % 3 != 0 {
            return Err(Error::invalid(format!(
                "xyz has {} values, expected 3 per node and at least one node",
                xyz.len()
            )));
        }
        check_finite("xyz", xyz)?;
        let node_count = xyz.len() / 3;
        if node_count > u32::MAX as usize {
            return Err(Error::invalid("more than 2^32 - 1 nodes"));
        }
        let per_cell = cell_type.node_count();
        if connectivity.is_empty() || connectivity.len() % per_cell != 0 {
            return Err(Error::invalid(format!(
                "connectivity has {} entries, expected {per_cell} per {} cell and at least one cell",
                connectivity.len(),
                cell_type.name()
            )));
        }
        let mut conn = Vec::with_capacity(connectivity.len());
        for (i, &n) in connectivity.iter().enumerate() {
            if n < 0 || n as usize >= node_count {
                return Err(Error::mesh(format!(
                    "connectivity[{i}] = {n} (cell {}) is not a node index in 0..{node_count}",
                    i / per_cell
                )));
            }
            conn.push(n as u32);
        }
        for (c, cell) in conn.chunks(per_cell).enumerate() {
            for (i, n) in cell.iter().enumerate() {
                if cell[..i].contains(n) {
                    return Err(Error::mesh(format!("cell {c} uses node {n} twice")));
                }
            }
        }
        let positions: Vec<[f64; 3]> = xyz.chunks(3).map(|p| [p[0], p[1], p[2]]).collect();
        Ok(Mesh {
            cell_type,
            reference: positions.clone(),
            positions,
            connectivity: conn,
            fixed: vec![0; node_count],
            last: None,
            sensitivity: Err("no relocation has run yet".into()),
            reference_state: None,
            layout: None,
            setup: None,
            problem: None,
            order: NodeOrder::Vtk,
        })
    }

    /// [`Mesh::new`] for a connectivity whose cells list their nodes in `order`; the mesh keeps
    /// VTK's order inside and gives [`Mesh::connectivity_in`] back in any order.
    pub fn new_ordered(
        cell_type: CellType,
        xyz: &[f64],
        connectivity: &[i64],
        order: NodeOrder,
    ) -> Result<Mesh> {
        let per = cell_type.node_count();
        if connectivity.len() % per != 0 {
            // Mesh::new words the error.
            return Mesh::new(cell_type, xyz, connectivity);
        }
        let mut mesh = Mesh::new_unchecked(cell_type, xyz, &order.to_vtk(cell_type, connectivity))?;
        mesh.order = order;
        mesh.check_orientation()?;
        Ok(mesh)
    }

    /// The node order the connectivity was given in.
    pub fn node_order(&self) -> NodeOrder {
        self.order
    }

    /// The connectivity (`#cells × nodes per cell`) with the nodes of each cell in `order`.
    pub fn connectivity_in(&self, order: NodeOrder) -> Vec<i64> {
        let vtk: Vec<i64> = self.connectivity.iter().map(|&n| n as i64).collect();
        order.from_vtk(self.cell_type, &vtk)
    }

    /// Refuses a mesh every cell of which is inverted or folded in its reference shape: what a
    /// connectivity in another node order than the one given, or cells oriented the wrong way,
    /// look like.
    pub(super) fn check_orientation(&self) -> Result<()> {
        let cells = self.cell_count();
        if cells == 0 || self.invalid_cell_count()? < cells {
            return Ok(());
        }
        let plane = if self.dimension() == 2 {
            " (quadrilaterals are taken in the x-y plane)"
        } else {
            ""
        };
        Err(Error::mesh(format!(
            "all {cells} cells are inverted or folded in the given positions (det J <= 0 in every cell){plane}: \
             most likely a wrong node order (the connectivity lists the nodes of each cell in another order \
             than the {} node order it was given as; a Gmsh mesh needs the Gmsh node order) or cells oriented \
             the wrong way (clockwise quadrilaterals, left-handed hexahedra)",
            self.order.name()
        )))
    }

    /// The cell type.
    pub fn cell_type(&self) -> CellType {
        self.cell_type
    }

    /// Spatial dimension of the cells (2 or 3).
    pub fn dimension(&self) -> usize {
        self.cell_type.dimension()
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.connectivity.len() / self.cell_type.node_count()
    }

    /// Current node positions.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    /// Reference node positions (the shape the targets are taken from).
    pub fn reference(&self) -> &[[f64; 3]] {
        &self.reference
    }

    /// Per-node constraint masks (bit 0: x fixed, bit 1: y, bit 2: z).
    pub fn fixed(&self) -> &[u8] {
        &self.fixed
    }

    /// Sets the constraint mask of every node: bit 0 keeps x, bit 1 keeps y, bit 2 keeps z
    /// (0 free, 3 fixed in 2D, 7 fixed in 3D, 4 sliding in a plane z = const).
    pub fn set_fixed(&mut self, mask: &[u8]) -> Result<()> {
        check_mask(mask, self.node_count())?;
        if self.fixed != mask {
            self.fixed = mask.to_vec();
            self.setup = None;
            self.problem = None;
            self.forget_solvers();
            self.invalidate_sensitivity("the constraints were changed since the last relocation");
        }
        Ok(())
    }

    /// Sets the positions of some nodes: `xyz` holds 3 values per node; `indices` names the
    /// nodes, or `None` for nodes `0..xyz.len()/3`. Nothing changes on error. A free
    /// coordinate moved here is where the next relocation starts only with
    /// [`Placement::Current`]; [`Placement::Laplacian`] and [`Placement::Incremental`] compute
    /// the free coordinates from the prescribed motion (and the last result).
    pub fn move_nodes(&mut self, indices: Option<&[usize]>, xyz: &[f64]) -> Result<()> {
        if xyz.len() % 3 != 0 {
            return Err(Error::invalid(format!(
                "xyz has {} values, not a multiple of 3",
                xyz.len()
            )));
        }
        check_finite("xyz", xyz)?;
        let count = xyz.len() / 3;
        let n = self.node_count();
        match indices {
            Some(idx) => {
                if idx.len() != count {
                    return Err(Error::invalid(format!(
                        "{} indices for {count} positions",
                        idx.len()
                    )));
                }
                if let Some(i) = idx.iter().position(|&v| v >= n) {
                    return Err(Error::invalid(format!(
                        "indices[{i}] = {} is not a node index in 0..{n}",
                        idx[i]
                    )));
                }
                for (&v, p) in idx.iter().zip(xyz.chunks(3)) {
                    self.positions[v] = [p[0], p[1], p[2]];
                }
                self.invalidate_sensitivity(MOVED);
            }
            None => {
                if count > n {
                    return Err(Error::invalid(format!("{count} positions for {n} nodes")));
                }
                for (v, p) in xyz.chunks(3).enumerate() {
                    self.positions[v] = [p[0], p[1], p[2]];
                }
                self.invalidate_sensitivity(MOVED);
            }
        }
        Ok(())
    }

    /// Makes the current positions the reference shape (e.g. after an accepted step of a
    /// shape-optimization loop).
    pub fn reset_reference(&mut self) {
        self.reference = self.positions.clone();
        self.problem = None;
        self.forget_solvers();
        self.invalidate_sensitivity("the reference shape was reset since the last relocation");
    }

    /// Worker threads of the last relocation (0 before any): the sensitivity products of the C
    /// API use them.
    pub fn last_threads(&self) -> usize {
        self.last.as_ref().map_or(0, |last| last.threads)
    }

    /// Drops the sensitivities of the last relocation, if there are, saying why.
    fn invalidate_sensitivity(&mut self, why: &str) {
        if self.sensitivity.is_ok() {
            self.sensitivity = Err(why.to_string());
        }
    }

    /// Drops the stored Hessians (after a change of the constraints or of the targets).
    fn forget_solvers(&mut self) {
        self.reference_state = None;
        if let Some(last) = self.last.as_mut() {
            last.solver = None;
        }
    }

    /// [`Mesh::problem`], kept on the mesh until its constraints or reference shape change (a
    /// relocation in a loop reuses it).
    fn kept_problem<const D: usize>(&mut self, target: TargetKind) -> Result<Arc<Problem<D>>> {
        let kept = self.problem.as_ref().filter(|(t, _)| *t == target);
        if let Some(problem) = kept.and_then(|(_, p)| p.clone().downcast::<Problem<D>>().ok()) {
            return Ok(problem);
        }
        let problem = Arc::new(self.problem::<D>(target)?);
        self.problem = Some((target, problem.clone() as AnyProblem));
        Ok(problem)
    }

    /// The optimizer's view of the mesh in dimension `D`.
    fn problem<const D: usize>(&self, target: TargetKind) -> Result<Problem<D>> {
        problem_of(
            self.cell_type,
            &self.connectivity,
            &self.fixed,
            &self.reference,
            target,
            self.unit(),
        )
    }

    /// The factor that brings the mesh to unit size (see [`unit_of`]): a power of two fixed by
    /// the reference shape, so it changes only with the reference (which also drops the stored
    /// Hessians, made in the scaled coordinates).
    fn unit(&self) -> f64 {
        let (lo, hi) = cell_node_box(&self.connectivity, &self.reference, self.dimension());
        unit_of(extent(lo, hi))
    }

    /// Quality of every cell against the given target: 1/mean distortion over the
    /// Gauss–Lobatto points, 0 for a cell with `det J ≤ 0` somewhere.
    pub fn cell_quality(&self, target: TargetKind) -> Result<Vec<f64>> {
        match self.dimension() {
            2 => self.quality_d::<2>(target),
            _ => self.quality_d::<3>(target),
        }
    }

    fn quality_d<const D: usize>(&self, target: TargetKind) -> Result<Vec<f64>> {
        let problem = self.problem::<D>(target)?;
        let x = project::<D>(&self.positions, self.unit());
        Ok((0..self.cell_count())
            .map(|c| problem.cell_quality(c, &x))
            .collect())
    }

    /// Number of cells with `det J ≤ 0` at some Gauss–Lobatto point.
    pub fn invalid_cell_count(&self) -> Result<usize> {
        Ok(self
            .cell_quality(TargetKind::Master)?
            .iter()
            .filter(|&&q| q <= 0.0)
            .count())
    }
}

/// Checks a constraint mask per node (`count` of them; bits 0, 1, 2 only).
pub(crate) fn check_mask(mask: &[u8], count: usize) -> Result<()> {
    if mask.len() != count {
        return Err(Error::invalid(format!(
            "mask has {} entries, expected one per node ({count})",
            mask.len(),
        )));
    }
    match mask.iter().position(|&m| m > 7) {
        Some(i) => Err(Error::invalid(format!(
            "mask[{i}] = {} uses bits other than 0, 1, 2",
            mask[i]
        ))),
        None => Ok(()),
    }
}

/// The optimizer's view of cells of one type (`connectivity` in node indices) with per-node
/// constraint masks `fixed` and targets from `reference`.
pub(crate) fn problem_of<const D: usize>(
    cell_type: CellType,
    connectivity: &[u32],
    fixed: &[u8],
    reference: &[[f64; 3]],
    target: TargetKind,
    unit: f64,
) -> Result<Problem<D>> {
    let pattern = CellPattern::<D>::new(cell_type.lattice())
        .ok_or_else(|| Error::mesh("unsupported cell pattern"))?;
    let specs: Vec<CellSpec<'_>> = connectivity
        .chunks(cell_type.node_count())
        .map(|nodes| CellSpec { pattern: 0, nodes })
        .collect();
    let free = fixed.iter().map(|m| !m & ((1u8 << D) - 1)).collect();
    Problem::new(
        vec![pattern],
        &specs,
        &project::<D>(reference, unit),
        target,
        free,
    )
}

/// Why a mesh whose nodes were moved has no sensitivities.
const MOVED: &str = "nodes were moved since the last relocation";

/// The first `D` coordinates of each point times `unit` (a power of two: exact).
pub(crate) fn project<const D: usize>(points: &[[f64; 3]], unit: f64) -> Vec<[f64; D]> {
    points
        .iter()
        .map(|p| std::array::from_fn(|k| p[k] * unit))
        .collect()
}

/// `points` with the free coordinates of their first `D` replaced by `x / unit` (exact: `unit`
/// is a power of two); the coordinates whose bit is set in `fixed` keep their bits as given.
pub(crate) fn lift<const D: usize>(
    points: &[[f64; 3]],
    x: &[[f64; D]],
    unit: f64,
    fixed: &[u8],
) -> Vec<[f64; 3]> {
    points
        .iter()
        .zip(x)
        .zip(fixed)
        .map(|((p, q), &mask)| {
            let mut p = *p;
            for k in (0..D).filter(|&k| mask & 1 << k == 0) {
                p[k] = q[k] / unit;
            }
            p
        })
        .collect()
}

/// The bounding box, in its first `d` coordinates, of the points used by the cells.
pub(crate) fn cell_node_box(
    connectivity: &[u32],
    points: &[[f64; 3]],
    d: usize,
) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &n in connectivity {
        let p = points[n as usize];
        for k in 0..d {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// The largest side of a box (0 when it is empty or flat).
pub(crate) fn extent(lo: [f64; 3], hi: [f64; 3]) -> f64 {
    (0..3)
        .filter(|&k| hi[k] >= lo[k])
        .map(|k| hi[k] - lo[k])
        .fold(0.0, f64::max)
}
