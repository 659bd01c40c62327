//! A part built on all ranks together ([`Partition::new`]): the collective checks of the
//! partition and the plan of its ghost refreshes.
//!
//! Each global id has a home rank (`id mod ranks`) that gathers what every rank says about it:
//! who owns the node, which cells lie around it, which nodes a cell has. The homes find the
//! faults; every rank then agrees on the first one, so a bad partition fails everywhere with
//! one message instead of hanging.

use std::collections::HashMap;

use super::exchange::{read_words, words, Ranks};
use super::ghost::GhostPlan;
use super::{PartInput, Partition};
use crate::error::{Error, Result};

/// Marks a node whose owner was not found.
const NO_OWNER: u64 = u64::MAX;

impl Partition {
    /// Builds this rank's part. Collective: every rank calls it; a part that is bad anywhere (a
    /// node owned twice or by no rank, an owner lacking a cell around its node, cells whose
    /// nodes are absent, a cell with different nodes on two ranks) is refused on every rank
    /// with the same message.
    /// `input` is an error when the host's arguments were bad on this rank: that too is agreed.
    pub fn new(ranks: &mut Ranks<'_>, input: Result<&PartInput<'_>>) -> Result<Partition> {
        let local = input.and_then(Partition::local);
        ranks.agree(local.as_ref().map(|_| ()).map_err(Clone::clone))?;
        let Ok(mut part) = local else {
            return Err(Error::mesh("the part was refused"));
        };
        part.plan = check_and_plan(ranks, &part)?;
        let mut reference: Vec<f64> = part.reference.concat();
        part.plan.refresh(ranks, &mut reference, 3)?;
        for (r, p) in part.reference.iter_mut().zip(reference.chunks(3)) {
            *r = [p[0], p[1], p[2]];
        }
        part.positions = part.reference.clone();
        Ok(part)
    }
}

/// Checks the partition on all ranks together and plans the ghost refreshes.
fn check_and_plan(ranks: &mut Ranks<'_>, part: &Partition) -> Result<GhostPlan> {
    let p = ranks.size();
    let types = ranks.all_gather_words(&[part.cell_type as u64])?;
    if let Some(r) = types.iter().position(|t| t[0] != part.cell_type as u64) {
        return Err(Error::mesh(format!(
            "the cell types differ between ranks (rank {r} has VTK type {}, rank {} type {})",
            types[r][0],
            ranks.rank(),
            part.cell_type as u64
        )));
    }
    let owners = find_owners(ranks, part)?;
    check_cells(ranks, part)?;
    // Each ghost asks its owner; the owner answers with its local indices.
    let mut ask = vec![Vec::new(); p];
    let mut recv = vec![Vec::new(); p];
    for (v, &o) in owners.iter().enumerate() {
        if !part.owned[v] {
            ask[o as usize].push(part.gids[v]);
            recv[o as usize].push(v as u32);
        }
    }
    let asked = ranks.all_to_all(&ask.iter().map(|a| words(a)).collect::<Vec<_>>())?;
    let send = asked
        .iter()
        .map(|bytes| {
            read_words(bytes)
                .iter()
                .map(|g| part.gids.binary_search(g).map(|i| i as u32))
                .collect::<std::result::Result<Vec<u32>, usize>>()
        })
        .collect::<std::result::Result<Vec<_>, usize>>();
    let send = send.map_err(|_| Error::mesh("a ghost asked for a node its owner lacks"));
    ranks.agree(send.as_ref().map(|_| ()).map_err(Clone::clone))?;
    Ok(GhostPlan {
        send: send.unwrap_or_default(),
        recv,
    })
}

/// The owner rank of every local node; fails everywhere when a node is owned twice or by no
/// rank.
fn find_owners(ranks: &mut Ranks<'_>, part: &Partition) -> Result<Vec<u64>> {
    let p = ranks.size() as u64;
    let mut to_home = vec![Vec::new(); p as usize];
    for (v, &g) in part.gids.iter().enumerate() {
        to_home[(g % p) as usize].extend([g, part.owned[v] as u64]);
    }
    let got = ranks.all_to_all(&to_home.iter().map(|m| words(m)).collect::<Vec<_>>())?;
    // Per id at its home: the owner, the number of owners, and the ranks holding it.
    let mut seen: HashMap<u64, (u64, u32, Vec<usize>)> = HashMap::new();
    for (r, bytes) in got.iter().enumerate() {
        for pair in read_words(bytes).chunks_exact(2) {
            let entry = seen.entry(pair[0]).or_insert((NO_OWNER, 0, Vec::new()));
            entry.2.push(r);
            if pair[1] == 1 {
                entry.0 = entry.0.min(r as u64);
                entry.1 += 1;
            }
        }
    }
    let mut fault: Vec<(u64, String)> = Vec::new();
    for (&g, (_, count, holders)) in &seen {
        match count {
            0 => fault.push((
                g,
                format!("node {g} (held by ranks {holders:?}) is owned by no rank"),
            )),
            1 => {}
            _ => fault.push((
                g,
                format!("node {g} is owned by {count} ranks (of {holders:?})"),
            )),
        }
    }
    let first = fault.into_iter().min_by_key(|f| f.0);
    ranks.agree(first.map_or(Ok(()), |(_, m)| Err(Error::mesh(m))))?;
    let replies: Vec<Vec<u8>> = got
        .iter()
        .map(|bytes| {
            let ids = read_words(bytes);
            let owners: Vec<u64> = ids.chunks_exact(2).map(|q| seen[&q[0]].0).collect();
            words(&owners)
        })
        .collect();
    let answers = ranks.all_to_all(&replies)?;
    let mut at = vec![0usize; p as usize];
    let owners = part
        .gids
        .iter()
        .map(|&g| {
            let home = (g % p) as usize;
            at[home] += 1;
            read_words(&answers[home])[at[home] - 1]
        })
        .collect();
    Ok(owners)
}

/// Checks that the owner of every node holds every cell around it and that a cell has the same
/// nodes wherever it is held.
fn check_cells(ranks: &mut Ranks<'_>, part: &Partition) -> Result<()> {
    let p = ranks.size() as u64;
    let per = part.cell_type.node_count();
    let mut around: Vec<Vec<u64>> = vec![Vec::new(); part.node_count()];
    for (c, nodes) in part.connectivity.chunks(per).enumerate() {
        for &v in nodes {
            around[v as usize].push(part.cell_gids[c]);
        }
    }
    // Node section: id, owned, count, cells; then cell section: id, node ids.
    let mut nodes_to = vec![Vec::new(); p as usize];
    for (v, &g) in part.gids.iter().enumerate() {
        let m = &mut nodes_to[(g % p) as usize];
        m.extend([g, part.owned[v] as u64, around[v].len() as u64]);
        m.extend_from_slice(&around[v]);
    }
    let mut cells_to = vec![Vec::new(); p as usize];
    for (c, nodes) in part.connectivity.chunks(per).enumerate() {
        let m = &mut cells_to[(part.cell_gids[c] % p) as usize];
        m.push(part.cell_gids[c]);
        m.extend(nodes.iter().map(|&v| part.gids[v as usize]));
    }
    let send: Vec<Vec<u8>> = (0..p as usize)
        .map(|r| {
            let mut m = vec![nodes_to[r].len() as u64];
            m.extend_from_slice(&nodes_to[r]);
            m.extend_from_slice(&cells_to[r]);
            words(&m)
        })
        .collect();
    let got = ranks.all_to_all(&send)?;
    let fault = home_faults(&got, per);
    ranks.agree(fault.map_or(Ok(()), |m| Err(Error::mesh(m))))
}

/// The first fault the home of some ids finds in what the ranks sent it.
fn home_faults(got: &[Vec<u8>], per: usize) -> Option<String> {
    let mut all_cells: HashMap<u64, Vec<(u64, usize)>> = HashMap::new();
    let mut owner_cells: HashMap<u64, (usize, Vec<u64>)> = HashMap::new();
    let mut cell_nodes: HashMap<u64, (usize, Vec<u64>)> = HashMap::new();
    let mut faults: Vec<(u64, String)> = Vec::new();
    for (r, bytes) in got.iter().enumerate() {
        let w = read_words(bytes);
        let node_len = w.first().copied().unwrap_or(0) as usize;
        let (nodes, cells) = w[1..].split_at(node_len.min(w.len() - 1));
        let mut i = 0;
        while i + 3 <= nodes.len() {
            let (g, owned, k) = (nodes[i], nodes[i + 1], nodes[i + 2] as usize);
            let list = &nodes[i + 3..(i + 3 + k).min(nodes.len())];
            all_cells
                .entry(g)
                .or_default()
                .extend(list.iter().map(|&c| (c, r)));
            if owned == 1 {
                owner_cells.insert(g, (r, list.to_vec()));
            }
            i += 3 + k;
        }
        for cell in cells.chunks_exact(per + 1) {
            let ids = cell[1..].to_vec();
            match cell_nodes.get(&cell[0]) {
                Some((r0, first)) if *first != ids => faults.push((
                    cell[0],
                    format!("cell {} has different nodes on ranks {r0} and {r}", cell[0]),
                )),
                Some(_) => {}
                None => {
                    cell_nodes.insert(cell[0], (r, ids));
                }
            }
        }
    }
    for (g, cells) in &all_cells {
        let Some((owner, mine)) = owner_cells.get(g) else {
            continue;
        };
        if let Some(&(c, r)) = cells.iter().find(|(c, _)| !mine.contains(c)) {
            faults.push((
                *g,
                format!(
                    "rank {owner} owns node {g} but lacks its cell {c} (held by rank {r}); the owner of a node must hold every cell around it"
                ),
            ));
        }
    }
    faults.into_iter().min_by_key(|f| f.0).map(|f| f.1)
}
