//! Meshes partitioned over the ranks of the host's MPI job: each rank holds a part (its cells,
//! their nodes with global ids, which of them it owns), and relocation runs on all ranks
//! together through the host's [`Exchange`], with the same result, bit for bit, as the whole
//! mesh relocated in one process by the sweeps.
//!
//! A part must hold every cell around each node it owns (a halo of one cell layer), so that
//! the owner can optimize its nodes; the other nodes of its cells are its ghosts, refreshed from
//! their owners. Global node ids fix the order of the colouring and of every sum, so the split
//! does not show in the result.

mod check;
mod exchange;
mod ghost;
mod relocate;
mod team;

pub use exchange::{Exchange, Ranks};
pub use relocate::PartitionReport;

use ghost::GhostPlan;

use crate::error::{check_finite, Error, Result};
use crate::fe_mesh::CellType;

/// A rank's part of a partitioned mesh.
#[derive(Clone, Debug)]
pub struct Partition {
    cell_type: CellType,
    /// Global ids of the local nodes, ascending (local node order).
    gids: Vec<u64>,
    /// Whether each local node is owned here.
    owned: Vec<bool>,
    /// The local index of each node as given.
    local_of_input: Vec<usize>,
    reference: Vec<[f64; 3]>,
    positions: Vec<[f64; 3]>,
    fixed: Vec<u8>,
    /// Global ids of the local cells, ascending (local cell order).
    cell_gids: Vec<u64>,
    /// Local node indices of the local cells, VTK order.
    connectivity: Vec<u32>,
    /// Where ghost values come from and go to.
    plan: GhostPlan,
    /// Positions of the last successful relocation (for `Placement::Incremental`).
    last: Option<Vec<[f64; 3]>>,
}

/// A part as given by the host, in its own node and cell order.
pub struct PartInput<'a> {
    /// The cell type (the same on every rank).
    pub cell_type: CellType,
    /// Global id of each local node.
    pub node_ids: &'a [u64],
    /// Per local node: 1 when this rank owns it, else 0.
    pub owned: &'a [u8],
    /// Reference positions of the local nodes, 3 per node.
    pub xyz: &'a [f64],
    /// Global id of each local cell.
    pub cell_ids: &'a [u64],
    /// Local node indices of each cell, VTK node order.
    pub connectivity: &'a [i64],
}

impl Partition {
    /// The part in local order (ascending global ids), checked on this rank alone.
    fn local(input: &PartInput<'_>) -> Result<Partition> {
        let n = input.node_ids.len();
        let per = input.cell_type.node_count();
        if input.owned.len() != n || input.xyz.len() != 3 * n {
            return Err(Error::invalid(format!(
                "{n} node ids, {} owned flags and {} coordinates: one flag and 3 coordinates per node are needed",
                input.owned.len(),
                input.xyz.len()
            )));
        }
        if n > u32::MAX as usize {
            return Err(Error::invalid("more than 2^32 - 1 local nodes"));
        }
        if input.connectivity.len() != per * input.cell_ids.len() {
            return Err(Error::invalid(format!(
                "{} cell ids and {} connectivity entries: {per} per {} cell are needed",
                input.cell_ids.len(),
                input.connectivity.len(),
                input.cell_type.name()
            )));
        }
        if let Some(i) = input.owned.iter().position(|&o| o > 1) {
            return Err(Error::invalid(format!("owned[{i}] is neither 0 nor 1")));
        }
        check_finite("xyz", input.xyz)?;
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_unstable_by_key(|&i| input.node_ids[i]);
        if let Some(w) = order
            .windows(2)
            .find(|w| input.node_ids[w[0]] == input.node_ids[w[1]])
        {
            return Err(Error::mesh(format!(
                "node id {} is given twice (local nodes {} and {})",
                input.node_ids[w[0]], w[0], w[1]
            )));
        }
        let mut local_of_input = vec![0; n];
        for (l, &i) in order.iter().enumerate() {
            local_of_input[i] = l;
        }
        let connectivity = Partition::local_cells(input, &local_of_input)?;
        let reference: Vec<[f64; 3]> = order
            .iter()
            .map(|&i| [input.xyz[3 * i], input.xyz[3 * i + 1], input.xyz[3 * i + 2]])
            .collect();
        Ok(Partition {
            cell_type: input.cell_type,
            gids: order.iter().map(|&i| input.node_ids[i]).collect(),
            owned: order.iter().map(|&i| input.owned[i] == 1).collect(),
            local_of_input,
            positions: reference.clone(),
            reference,
            fixed: vec![0; n],
            cell_gids: {
                let mut ids = input.cell_ids.to_vec();
                ids.sort_unstable();
                ids
            },
            connectivity,
            plan: GhostPlan::default(),
            last: None,
        })
    }

    /// The connectivity in local node indices, cells sorted by global id.
    fn local_cells(input: &PartInput<'_>, local_of_input: &[usize]) -> Result<Vec<u32>> {
        let per = input.cell_type.node_count();
        let n = local_of_input.len();
        let mut cells: Vec<usize> = (0..input.cell_ids.len()).collect();
        cells.sort_unstable_by_key(|&c| input.cell_ids[c]);
        if let Some(w) = cells
            .windows(2)
            .find(|w| input.cell_ids[w[0]] == input.cell_ids[w[1]])
        {
            return Err(Error::mesh(format!(
                "cell id {} is given twice (local cells {} and {})",
                input.cell_ids[w[0]], w[0], w[1]
            )));
        }
        let mut connectivity = Vec::with_capacity(input.connectivity.len());
        for &c in &cells {
            let nodes = &input.connectivity[c * per..(c + 1) * per];
            for (i, &v) in nodes.iter().enumerate() {
                if v < 0 || v as usize >= n {
                    return Err(Error::mesh(format!(
                        "cell {c} (id {}) refers to local node {v}, but the part has {n} nodes",
                        input.cell_ids[c]
                    )));
                }
                if nodes[..i].contains(&v) {
                    return Err(Error::mesh(format!("cell {c} uses node {v} twice")));
                }
                connectivity.push(local_of_input[v as usize] as u32);
            }
        }
        Ok(connectivity)
    }

    /// Number of local nodes (owned and ghosts).
    pub fn node_count(&self) -> usize {
        self.gids.len()
    }

    /// Number of local cells.
    pub fn cell_count(&self) -> usize {
        self.cell_gids.len()
    }

    /// The cell type.
    pub fn cell_type(&self) -> CellType {
        self.cell_type
    }

    /// Sets the constraint mask of every local node, in the order given to
    /// [`Partition::new`] (see `Mesh::set_fixed`). A ghost's mask is taken from its owner.
    pub fn set_fixed(&mut self, mask: &[u8]) -> Result<()> {
        crate::fe_mesh::check_mask(mask, self.node_count())?;
        for (i, &m) in mask.iter().enumerate() {
            self.fixed[self.local_of_input[i]] = m;
        }
        Ok(())
    }

    /// Sets the positions of all local nodes (3 values per node, in the order given to
    /// [`Partition::new`]). A ghost's position is taken from its owner.
    pub fn set_positions(&mut self, xyz: &[f64]) -> Result<()> {
        if xyz.len() != 3 * self.node_count() {
            return Err(Error::invalid(format!(
                "xyz has {} values, expected 3 per local node ({})",
                xyz.len(),
                self.node_count()
            )));
        }
        check_finite("xyz", xyz)?;
        for (i, p) in xyz.chunks(3).enumerate() {
            self.positions[self.local_of_input[i]] = [p[0], p[1], p[2]];
        }
        Ok(())
    }

    /// The positions of the local nodes, 3 per node, in the order given to [`Partition::new`].
    pub fn positions(&self) -> Vec<f64> {
        self.local_of_input
            .iter()
            .flat_map(|&l| self.positions[l])
            .collect()
    }
}
