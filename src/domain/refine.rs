//! Local refinement of a built domain: refine given cells, rebalance, place the new vertices
//! (on the boundary, or on the current piecewise map inside) and optimize again. The repair of
//! [`Domain::build`] and the adaptive loops of later stages go through it.

use std::collections::HashMap;
use std::time::Instant;

use rayon::ThreadPool;

use super::build::Domain;
use super::cube_map::CubeMap;
use super::options::{
    cells_within, sweep_options, thread_pool, DomainOptions, DomainReport, MAX_REPAIR_LEVEL,
};
use crate::error::{Error, Result};
use crate::optimize::motion::optimize_in_place;
use crate::optimize::{invalid_cells, lattice, QualitySummary};
use crate::tmesh::{TMesh, UNIT};

/// Integer coordinates of a parametric point of the tree's half-grid.
fn grid_point<const D: usize>(p: [f64; D]) -> [u32; D] {
    p.map(|v| (v * UNIT as f64).round() as u32)
}

/// 1D quadratic Lagrange basis on \[0,1\] with nodes 0, ½, 1.
fn lagrange(t: f64) -> [f64; 3] {
    [
        2.0 * (t - 0.5) * (t - 1.0),
        -4.0 * t * (t - 1.0),
        2.0 * t * (t - 0.5),
    ]
}

/// The piecewise quadratic map of a T-mesh (positions `x`) at the parametric point `p`: the map
/// of the leaf holding `p`, its virtual nodes completed by the Coons rules.
fn evaluate<const D: usize>(
    mesh: &TMesh<D>,
    cell_of_leaf: &HashMap<usize, usize>,
    x: &[[f64; D]],
    p: [f64; D],
) -> Result<[f64; D]> {
    let integer = grid_point(p).map(|v| v as i64);
    let leaf = mesh
        .tree()
        .leaf_at(&integer)
        .ok_or_else(|| Error::invalid(format!("the point {p:?} is outside [0,1]^d")))?;
    let c = cell_of_leaf[&leaf];
    let (lattice_points, vertices) = mesh.cell_vertices(c);
    let rows = lattice::completion::<D>(lattice_points)
        .ok_or_else(|| Error::mesh("a T-mesh cell misses a corner"))?;
    let (lo, hi) = mesh.cell_bounds(c);
    let basis: Vec<[f64; 3]> = (0..D)
        .map(|k| lagrange((p[k] - lo[k]) / (hi[k] - lo[k])))
        .collect();
    let mut out = [0.0; D];
    for (l, row) in rows.iter().enumerate() {
        let lc = lattice::coords::<D>(l);
        let weight: f64 = (0..D).map(|k| basis[k][lc[k]]).product();
        if weight == 0.0 {
            continue;
        }
        for &(r, coefficient) in row {
            let node = x[vertices[r] as usize];
            for k in 0..D {
                out[k] += weight * coefficient * node[k];
            }
        }
    }
    Ok(out)
}

impl<const D: usize, B: CubeMap<D>> Domain<D, B> {
    /// Refines the given cells (indices into the current cells; a cell at level 16 is left as
    /// it is), rebalances the tree, places the new boundary vertices on the boundary and the new
    /// inner ones on the current piecewise map, and optimizes the whole T-mesh again with
    /// `options` (its tolerance and levels are not used, beyond being checked). The cell and
    /// vertex numbering changes; old vertices keep their positions before the optimization.
    /// Returns the report of the refined T-mesh (`invalid_after_placement` counts the invalid
    /// cells before the optimization). `progress(sweeps, 0)` is called after every sweep;
    /// returning false cancels, leaving the domain unchanged.
    pub fn refine_cells(
        &mut self,
        cells: &[usize],
        options: &DomainOptions,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Result<DomainReport> {
        let start = Instant::now();
        options.validate()?;
        if let Some(&c) = cells.iter().find(|&&c| c >= self.mesh.cell_count()) {
            return Err(Error::invalid(format!(
                "cell {c} does not exist: the T-mesh has {} cells",
                self.mesh.cell_count()
            )));
        }
        let pool = thread_pool(options)?;
        let (placement_invalid, sweeps) =
            self.refine_with(cells, options, &pool, &mut |d| progress(d, 0))?;
        let mut report = self.report(&pool)?;
        report.invalid_after_placement = placement_invalid;
        report.sweeps = sweeps;
        report.seconds = start.elapsed().as_secs_f64();
        report.stages.repair = report.seconds;
        Ok(report)
    }

    /// [`Domain::refine_cells`] for the repair of a build, the pool given: returns the cells
    /// still invalid and the sweeps done.
    pub(super) fn refine_in_place(
        &mut self,
        cells: &[usize],
        options: &DomainOptions,
        pool: &ThreadPool,
        progress: &mut dyn FnMut(usize) -> bool,
    ) -> Result<(Vec<usize>, u32)> {
        let (_, sweeps) = self.refine_with(cells, options, pool, progress)?;
        let problem = self.mesh.problem()?;
        Ok((invalid_cells(pool, &problem, &self.framed), sweeps))
    }

    /// Refines, places and optimizes; returns the invalid cells after the placement and the
    /// sweeps. `self` changes only on success.
    fn refine_with(
        &mut self,
        cells: &[usize],
        options: &DomainOptions,
        pool: &ThreadPool,
        progress: &mut dyn FnMut(usize) -> bool,
    ) -> Result<(usize, u32)> {
        let old = &self.mesh;
        let leaves = old.tree().leaves();
        let cell_of_leaf: HashMap<usize, usize> =
            leaves.iter().enumerate().map(|(c, &l)| (l, c)).collect();
        let mut tree = old.tree().clone();
        let mut targets: Vec<usize> = cells
            .iter()
            .copied()
            .filter(|&c| old.cell_level(c) < MAX_REPAIR_LEVEL)
            .collect();
        targets.sort_unstable();
        targets.dedup();
        let refined = leaves.len() + targets.len() * ((1 << D) - 1);
        cells_within(options, refined, "the refinement of the T-mesh")?;
        for &c in &targets {
            tree.refine(leaves[c])?;
        }
        tree.balance()?;
        cells_within(options, tree.leaves().len(), "the refinement of the T-mesh")?;
        let mesh = TMesh::new(tree)?;
        let old_ids: HashMap<[u32; D], usize> = old
            .parametric()
            .into_iter()
            .enumerate()
            .map(|(v, p)| (grid_point(p), v))
            .collect();
        let framed = self.framed_boundary();
        let mut x = Vec::with_capacity(mesh.vertex_count());
        for (v, p) in mesh.parametric().into_iter().enumerate() {
            x.push(match old_ids.get(&grid_point(p)) {
                Some(&w) => self.framed[w],
                None if mesh.on_boundary(v) => framed.boundary_point(p),
                None => evaluate(old, &cell_of_leaf, &self.framed, p)?,
            });
        }
        let problem = mesh.problem()?;
        let placement_invalid = invalid_cells(pool, &problem, &x).len();
        let stats = optimize_in_place(pool, &problem, &mut x, &sweep_options(options), progress)?;
        self.quality = QualitySummary::of(pool, &problem, &x).quality;
        self.mesh = mesh;
        self.set_framed(x);
        Ok((placement_invalid, stats.sweeps))
    }
}
