//! The aggregation of smoothed-aggregation multigrid ([`Amg`](super::amg::Amg)): unknowns
//! grouped by node with the rigid motions as their near-null space, aggregates of strongly
//! coupled groups, and the tentative prolongator carrying the rigid motions restricted to each
//! aggregate (orthonormalised per aggregate) as its coarse functions.

use super::csr::Csr;
use super::small_matrix::Vector;
use super::sparse::Coordinates;

/// Strength threshold of the aggregation: `‖A_ij‖ ≥ θ √(‖A_ii‖‖A_jj‖)`.
const STRENGTH: f64 = 0.08;

/// A level's unknowns grouped by node (level 0) or aggregate: node `i` owns unknowns
/// `start[i]..start[i + 1]`.
pub(super) struct Grouping {
    pub(super) start: Vec<usize>,
}

impl Grouping {
    pub(super) fn count(&self) -> usize {
        self.start.len() - 1
    }

    pub(super) fn range(&self, i: usize) -> std::ops::Range<usize> {
        self.start[i]..self.start[i + 1]
    }
}

/// Groups the free `coordinates` by node, with the rigid motions at the nodes' positions `x`
/// (one per node of `coordinates`) as near-null space (row-major, `d(d+1)/2` values per unknown).
pub(super) fn node_grouping<const D: usize>(
    coordinates: &Coordinates,
    x: &[Vector<D>],
) -> (Grouping, Vec<f64>) {
    let modes = D * (D + 1) / 2;
    let mut start = vec![0usize];
    let mut null_space = Vec::new();
    debug_assert_eq!(x.len(), coordinates.node_count());
    for (v, xv) in x.iter().enumerate() {
        let mut owned = 0;
        for k in 0..D {
            if coordinates.of(v, k).is_none() {
                continue;
            }
            owned += 1;
            let mut row = vec![0.0; modes];
            row[k] = 1.0;
            // Rotations: in the plane of axes (a, b), component a gets −x_b and b gets x_a.
            for (m, (a, b)) in rotation_planes(D).into_iter().enumerate() {
                row[D + m] = match k {
                    k if k == a => -xv[b],
                    k if k == b => xv[a],
                    _ => 0.0,
                };
            }
            null_space.extend(row);
        }
        if owned > 0 {
            start.push(start.last().expect("start") + owned);
        }
    }
    (Grouping { start }, null_space)
}

/// The coordinate planes of the rotations: (0, 1) in 2D; (1, 2), (2, 0), (0, 1) in 3D.
fn rotation_planes(d: usize) -> Vec<(usize, usize)> {
    match d {
        2 => vec![(0, 1)],
        _ => vec![(1, 2), (2, 0), (0, 1)],
    }
}

/// Frobenius norm of the block of `a` between groups `i` and `j`.
fn block_norm(a: &Csr, grouping: &Grouping, i: usize, j: usize) -> f64 {
    let columns = grouping.range(j);
    grouping
        .range(i)
        .map(|row| {
            let (cols, vals) = a.row(row);
            cols.iter()
                .zip(vals)
                .filter(|(c, _)| columns.contains(&(**c as usize)))
                .map(|(_, v)| v * v)
                .sum::<f64>()
        })
        .sum::<f64>()
        .sqrt()
}

/// The groups coupled to each group, strongly or not.
fn group_graph(a: &Csr, grouping: &Grouping) -> Vec<Vec<usize>> {
    let mut owner = vec![0usize; a.rows()];
    for i in 0..grouping.count() {
        for d in grouping.range(i) {
            owner[d] = i;
        }
    }
    (0..grouping.count())
        .map(|i| {
            let mut neighbours: Vec<usize> = grouping
                .range(i)
                .flat_map(|row| a.row(row).0.iter().map(|&c| owner[c as usize]))
                .filter(|&j| j != i)
                .collect();
            neighbours.sort_unstable();
            neighbours.dedup();
            neighbours
        })
        .collect()
}

/// Greedy aggregation of the groups of `a` (Vaněk's three passes): the aggregate of every group.
pub(super) fn aggregate(a: &Csr, grouping: &Grouping) -> Vec<usize> {
    let n = grouping.count();
    let graph = group_graph(a, grouping);
    let own: Vec<f64> = (0..n).map(|i| block_norm(a, grouping, i, i)).collect();
    let strong: Vec<Vec<(usize, f64)>> = (0..n)
        .map(|i| {
            graph[i]
                .iter()
                .map(|&j| (j, block_norm(a, grouping, i, j)))
                .filter(|&(j, s)| s >= STRENGTH * (own[i] * own[j]).sqrt())
                .collect()
        })
        .collect();
    const NONE: usize = usize::MAX;
    let mut aggregate = vec![NONE; n];
    let mut count = 0;
    for i in 0..n {
        if aggregate[i] == NONE && strong[i].iter().all(|&(j, _)| aggregate[j] == NONE) {
            aggregate[i] = count;
            for &(j, _) in &strong[i] {
                aggregate[j] = count;
            }
            count += 1;
        }
    }
    let first = aggregate.clone();
    for i in 0..n {
        if aggregate[i] == NONE {
            let best = strong[i]
                .iter()
                .filter(|&&(j, _)| first[j] != NONE)
                .max_by(|x, y| x.1.total_cmp(&y.1));
            if let Some(&(j, _)) = best {
                aggregate[i] = first[j];
            }
        }
    }
    for i in 0..n {
        if aggregate[i] == NONE {
            aggregate[i] = count;
            for &(j, _) in &strong[i] {
                if aggregate[j] == NONE {
                    aggregate[j] = count;
                }
            }
            count += 1;
        }
    }
    aggregate
}

/// The tentative prolongator: per aggregate, the near-null space restricted to its unknowns,
/// orthonormalised (columns that are dependent there are dropped); the coarse level's grouping
/// (one group per aggregate) and near-null space (the triangular factors).
pub(super) fn tentative_prolongator(
    grouping: &Grouping,
    aggregates: &[usize],
    null_space: &[f64],
    modes: usize,
) -> (Csr, Grouping, Vec<f64>) {
    let count = aggregates.iter().max().map_or(0, |&m| m + 1);
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (group, &agg) in aggregates.iter().enumerate() {
        members[agg].extend(grouping.range(group));
    }
    let fine = grouping.start.last().copied().unwrap_or(0);
    let mut rows: Vec<Vec<(u32, f64)>> = vec![Vec::new(); fine];
    let mut start = vec![0usize];
    let mut coarse_null = Vec::new();
    for unknowns in &members {
        let first_column = *start.last().expect("start");
        // Modified Gram–Schmidt on the columns of the local near-null space.
        let mut q: Vec<Vec<f64>> = Vec::new();
        let mut r = vec![vec![0.0; modes]; modes];
        let mut kept = Vec::new();
        for m in 0..modes {
            let mut column: Vec<f64> = unknowns
                .iter()
                .map(|&u| null_space[u * modes + m])
                .collect();
            let original = column.iter().map(|v| v * v).sum::<f64>().sqrt();
            for (c, qc) in q.iter().enumerate() {
                let dot: f64 = qc.iter().zip(&column).map(|(a, b)| a * b).sum();
                r[c][m] = dot;
                for (v, qv) in column.iter_mut().zip(qc) {
                    *v -= dot * qv;
                }
            }
            let norm = column.iter().map(|v| v * v).sum::<f64>().sqrt();
            if norm > 1e-10 * original && norm > 0.0 {
                r[q.len()][m] = norm;
                column.iter_mut().for_each(|v| *v /= norm);
                q.push(column);
                kept.push(m);
            }
        }
        for (i, &u) in unknowns.iter().enumerate() {
            for (c, qc) in q.iter().enumerate() {
                rows[u].push(((first_column + c) as u32, qc[i]));
            }
        }
        for row in r.iter().take(q.len()) {
            coarse_null.extend_from_slice(row);
        }
        start.push(first_column + q.len());
    }
    let columns = *start.last().expect("start");
    (
        Csr::from_rows(columns, rows),
        Grouping { start },
        coarse_null,
    )
}
