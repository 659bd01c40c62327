//! Symmetric matrices over node coordinates stored in d×d node blocks: the layout of a mesh's
//! Hessian (which node pairs couple, and where each cell's pairs go) and the products with the
//! parts of it that free and prescribed coordinates select.
//!
//! Two real nodes of a cell couple when some Gauss–Lobatto point's Jacobian depends on both.
//! Blocks are stored for both triangles, so a row-wise product needs no transposition and
//! parallelises with a result independent of the thread count.

use rayon::prelude::*;
use rayon::ThreadPool;

use super::csr::split_rows;
use super::problem::Problem;
use super::small_matrix::{Matrix, Vector};
use crate::error::{Error, ErrorKind, Result};
use crate::threads;

/// Marks a pair of a cell's nodes that does not couple.
pub(super) const NONE: u32 = u32::MAX;

/// Where the blocks of a mesh's Hessian are: the neighbours of node `v` are
/// `columns[start[v]..start[v + 1]]`, sorted, `v` itself included; and, for every cell, the block
/// of each ordered pair of its real nodes.
#[derive(Clone, Debug)]
pub struct BlockLayout {
    start: Vec<usize>,
    columns: Vec<u32>,
    /// Per cell, `first[c]..first[c + 1]` indexes `cell_blocks`: the block of each pair `(r, s)`
    /// of its real nodes, row-major, or [`NONE`].
    first: Vec<usize>,
    cell_blocks: Vec<u32>,
    /// Cells per chunk ([`cell_chunk`]).
    chunk: usize,
    /// Per chunk of cells (`chunk_touches[k]..chunk_touches[k + 1]` indexes `touches`), the
    /// order in which the assembly adds its cells' rows.
    chunk_touches: Vec<usize>,
    touches: Vec<Touch>,
}

/// Cells whose Hessian contributions are computed together, then added to the global Hessian
/// in cell order (the sums do not depend on it): 512 in 2D; 128 in 3D, where an H27 cell's
/// contributions are 52 kB and 512 cells' (27 MB) left the cache between being computed and
/// added (the wing 4.86–5.01 → 4.75–4.87 s and 587 → 569 MB, alternated runs).
const fn cell_chunk(dimension: usize) -> usize {
    match dimension {
        2 => 512,
        _ => 128,
    }
}

/// A row of one cell's local Hessian: its node, the cell's place in its chunk and the node's
/// place in the cell.
pub(super) type Touch = (u32, u32, u32);

impl BlockLayout {
    /// The layout of `problem`'s Hessian (it depends on the connectivity only), made by nodes
    /// and cells in parallel (sequential, it was 1.6 s of the 812,040-node wing's relocation);
    /// the same for any thread count. Its arrays are allocated once, at their size: vectors per
    /// row or cell, made on the workers, stayed in their allocator's arenas (190 MB more at the
    /// peak of that relocation).
    pub fn new<const D: usize>(pool: &ThreadPool, problem: &Problem<D>) -> Self {
        let cells = problem.cell_count();
        let mut first = Vec::with_capacity(cells + 1);
        first.push(0);
        for c in 0..cells {
            let count = problem.cell_nodes(c).len();
            first.push(first[c] + count * count);
        }
        // Which pairs of each cell's nodes couple, indexed like `cell_blocks`.
        let mut couplings = vec![false; first[cells]];
        let parts = split_rows(&mut couplings, first.windows(2).map(|w| w[1] - w[0]));
        pool.install(|| {
            parts
                .into_par_iter()
                .enumerate()
                .for_each(|(c, part)| coupling(problem, c, part))
        });
        let (start, columns) = rows(pool, problem, (&first, &couplings));
        let mut layout = BlockLayout {
            start,
            columns,
            first,
            cell_blocks: Vec::new(),
            chunk: cell_chunk(D),
            chunk_touches: vec![0],
            touches: Vec::new(),
        };
        layout.cell_blocks = layout.cell_block_map(pool, problem, &couplings);
        layout.order_touches(pool, problem);
        layout
    }

    /// Per cell, the block of each pair of its real nodes (row-major), [`NONE`] where the pair
    /// does not couple; cells in parallel, each writing its own part.
    fn cell_block_map<const D: usize>(
        &self,
        pool: &ThreadPool,
        problem: &Problem<D>,
        couplings: &[bool],
    ) -> Vec<u32> {
        let mut map = vec![NONE; self.first[problem.cell_count()]];
        let lengths = self.first.windows(2).map(|w| w[1] - w[0]);
        let parts = split_rows(&mut map, lengths);
        pool.install(|| {
            parts.into_par_iter().enumerate().for_each(|(c, part)| {
                let nodes = problem.cell_nodes(c);
                let pairs = nodes
                    .iter()
                    .flat_map(|&v| nodes.iter().map(move |&w| (v, w)));
                let couples = &couplings[self.first[c]..self.first[c + 1]];
                for ((slot, (v, w)), &couples) in part.iter_mut().zip(pairs).zip(couples) {
                    if couples {
                        *slot = self.find(v as usize, w as usize).map_or(NONE, |b| b as u32);
                    }
                }
            })
        });
        map
    }

    /// The touches of every chunk of cells, by node then cell: the same for every evaluation,
    /// so sorted once (sorting them per evaluation was a tenth of an evaluation of the airfoil's
    /// Hessian, on the thread that waits for the others). Chunks in parallel.
    fn order_touches<const D: usize>(&mut self, pool: &ThreadPool, problem: &Problem<D>) {
        let cells: Vec<usize> = (0..problem.cell_count()).collect();
        for chunk in cells.chunks(self.chunk) {
            let count: usize = chunk.iter().map(|&c| problem.cell_nodes(c).len()).sum();
            self.chunk_touches
                .push(self.chunk_touches[self.chunk_touches.len() - 1] + count);
        }
        self.touches = vec![(0, 0, 0); self.chunk_touches[self.chunk_touches.len() - 1]];
        let lengths = self.chunk_touches.windows(2).map(|w| w[1] - w[0]);
        let parts = split_rows(&mut self.touches, lengths);
        pool.install(|| {
            parts
                .into_par_iter()
                .zip(cells.par_chunks(self.chunk))
                .for_each(|(touches, chunk)| {
                    let nodes = chunk.iter().enumerate().flat_map(|(i, &c)| {
                        let nodes = problem.cell_nodes(c).iter().enumerate();
                        nodes.map(move |(r, &v)| (v, i as u32, r as u32))
                    });
                    for (slot, touch) in touches.iter_mut().zip(nodes) {
                        *slot = touch;
                    }
                    touches.sort_unstable();
                })
        });
    }

    /// Cells per chunk: the assembly computes and adds the cells' contributions chunk by chunk.
    pub fn chunk(&self) -> usize {
        self.chunk
    }

    /// The touches of the `k`-th chunk of cells ([`BlockLayout::chunk`] to a chunk), by node
    /// then cell.
    pub fn chunk_touches(&self, k: usize) -> &[Touch] {
        &self.touches[self.chunk_touches[k]..self.chunk_touches[k + 1]]
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.start.len() - 1
    }

    /// The block indices and neighbours of node `v`.
    pub fn row(&self, v: usize) -> (std::ops::Range<usize>, &[u32]) {
        let range = self.start[v]..self.start[v + 1];
        (range.clone(), &self.columns[range])
    }

    /// Number of stored blocks.
    pub fn block_count(&self) -> usize {
        self.columns.len()
    }

    /// Index of block `(v, w)`, if stored.
    pub fn find(&self, v: usize, w: usize) -> Option<usize> {
        let (range, cols) = self.row(v);
        cols.binary_search(&(w as u32))
            .ok()
            .map(|i| range.start + i)
    }

    /// The blocks of the ordered pairs of cell `c`'s real nodes (row-major), `NONE` (`u32::MAX`)
    /// where a pair does not couple.
    pub fn cell_blocks(&self, c: usize) -> &[u32] {
        &self.cell_blocks[self.first[c]..self.first[c + 1]]
    }
}

/// The layout's rows, `v` and the nodes it couples with, sorted: their starts and their
/// columns, the lengths found first, then each row written in place (nodes in parallel).
/// `(first, couplings)`: per cell, where its pairs start, and which of them couple.
fn rows<const D: usize>(
    pool: &ThreadPool,
    problem: &Problem<D>,
    (first, couplings): (&[usize], &[bool]),
) -> (Vec<usize>, Vec<u32>) {
    let row = |v: usize, row: &mut Vec<u32>| {
        row.clear();
        row.push(v as u32);
        for &(c, r) in problem.incident_cells(v) {
            let nodes = problem.cell_nodes(c as usize);
            let pairs = &couplings[first[c as usize] + r as usize * nodes.len()..][..nodes.len()];
            let coupled = nodes
                .iter()
                .zip(pairs)
                .filter(|&(&w, &p)| p && w != v as u32);
            row.extend(coupled.map(|(&w, _)| w));
        }
        row.sort_unstable();
        row.dedup();
    };
    let n = problem.node_count();
    let lengths: Vec<usize> = pool.install(|| {
        (0..n)
            .into_par_iter()
            .map_init(Vec::new, |scratch, v| {
                row(v, scratch);
                scratch.len()
            })
            .collect()
    });
    let mut start = Vec::with_capacity(n + 1);
    start.push(0);
    for length in &lengths {
        start.push(start[start.len() - 1] + length);
    }
    let mut columns = vec![0u32; start[n]];
    let parts = split_rows(&mut columns, lengths.iter().copied());
    pool.install(|| {
        parts
            .into_par_iter()
            .enumerate()
            .for_each_init(Vec::new, |scratch, (v, part)| {
                row(v, scratch);
                part.copy_from_slice(scratch);
            })
    });
    (start, columns)
}

/// Marks in `couples` (row-major `r·n + s`, false on entry) the pairs of cell `c`'s real nodes
/// that enter one Jacobian together.
fn coupling<const D: usize>(problem: &Problem<D>, c: usize, couples: &mut [bool]) {
    let pattern = problem.pattern(c);
    let n = pattern.real_count;
    for stencil in &pattern.jacobian {
        for &(r, _) in stencil {
            for &(s, _) in stencil {
                couples[r as usize * n + s as usize] = true;
            }
        }
    }
}

/// `count` zero blocks, or a refusal where they cannot be allocated: a Hessian larger than the
/// machine's memory and swap (several million quadratic solid nodes) would otherwise abort the
/// process. The request is tried first
/// ([`memory_probe`]), then made zeroed by the allocator (fresh pages, untouched: the evaluation
/// stores its zeros in order, see
/// [`GlobalObjective::evaluate_into`](super::global::GlobalObjective::evaluate_into)).
fn zero_blocks<const D: usize>(count: usize) -> Result<Vec<Matrix<D>>> {
    let values = count.saturating_mul(D * D);
    let bytes = count.saturating_mul(std::mem::size_of::<Matrix<D>>());
    memory_probe(bytes, &format!("a Hessian of {values} values"))?;
    Ok(vec![[[0.0; D]; D]; count])
}

/// Whether `bytes` can be allocated now, found by reserving them and releasing them at once (no
/// page is touched); where not, a refusal ([`ErrorKind::LimitExceeded`]) naming `what`, to which
/// each caller adds what can be done instead (relocation: the sweeps, which keep no Hessian): an
/// allocation past the machine's memory and swap would abort the process. A reservation fails
/// where it exceeds an address-space limit (`ulimit -v`), the commit limit under strict
/// overcommit, or (Linux's default) the machine's memory and swap on its own; memory that other
/// allocations or a container's limit take is not seen until pages are touched.
pub(super) fn memory_probe(bytes: usize, what: &str) -> Result<()> {
    let probe = reserved::<u8>(bytes, what)?;
    // Seen from outside, so that the compiler cannot drop the reservation as unused.
    std::hint::black_box(probe.as_ptr());
    Ok(())
}

/// An empty vector with room for exactly `count` values, or a refusal
/// ([`ErrorKind::LimitExceeded`]) naming `what` where that room cannot be had (an infallible
/// allocation would abort the process).
pub(super) fn reserved<T>(count: usize, what: &str) -> Result<Vec<T>> {
    let mut room = Vec::new();
    std::hint::black_box(&mut room)
        .try_reserve_exact(count)
        .map_err(|_| {
            let bytes = count.saturating_mul(std::mem::size_of::<T>());
            Error::new(
                ErrorKind::LimitExceeded,
                format!(
                    "not enough memory for {what} ({:.1} GB)",
                    bytes as f64 * 1e-9
                ),
            )
        })?;
    Ok(room)
}

/// A symmetric matrix over node coordinates, in the blocks of a [`BlockLayout`].
#[derive(Clone, Debug)]
pub struct BlockMatrix<const D: usize> {
    /// Block `b` of row `v` couples `v` with the layout's `b`-th column.
    pub blocks: Vec<Matrix<D>>,
}

impl<const D: usize> BlockMatrix<D> {
    /// The zero matrix of `layout`; refused ([`ErrorKind::LimitExceeded`]) where its storage
    /// cannot be allocated.
    pub fn zero(layout: &BlockLayout) -> Result<Self> {
        Ok(BlockMatrix {
            blocks: zero_blocks(layout.block_count())?,
        })
    }

    /// `y = M x` restricted to the coordinates selected by `rows` (bit `k` of `rows[v]` selects
    /// component `k` of node `v`) on both sides, i.e. `x` is read where `columns` selects and `y`
    /// is written where `rows` selects, zero elsewhere. Rows run in parallel (those of a
    /// small matrix on the calling thread); each sums its blocks in column order, so the result
    /// does not depend on the thread count.
    pub fn product(
        &self,
        pool: &ThreadPool,
        layout: &BlockLayout,
        rows: &[u8],
        columns: &[u8],
        x: &[Vector<D>],
        y: &mut [Vector<D>],
    ) {
        let work = self.blocks.len() * D * D;
        threads::for_each_mut(pool, work, y, |v, yv| {
            *yv = [0.0; D];
            if rows[v] == 0 {
                return;
            }
            let (blocks, neighbours) = layout.row(v);
            let full = (1u8 << D) - 1;
            for (block, &w) in self.blocks[blocks].iter().zip(neighbours) {
                let (w, mask) = (w as usize, columns[w as usize]);
                if mask == 0 {
                    continue;
                }
                // Plain loops: an array built by a closure per block was not inlined.
                let mut xw = x[w];
                if mask != full {
                    for (l, xl) in xw.iter_mut().enumerate() {
                        if mask & (1 << l) == 0 {
                            *xl = 0.0;
                        }
                    }
                }
                for (yk, row) in yv.iter_mut().zip(block) {
                    *yk += row.iter().zip(&xw).map(|(b, x)| b * x).sum::<f64>();
                }
            }
            for (k, yk) in yv.iter_mut().enumerate() {
                if rows[v] & (1 << k) == 0 {
                    *yk = 0.0;
                }
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Hessian whose storage cannot be had is refused, not an abort.
    #[test]
    fn a_hessian_past_memory_is_refused() {
        let e = zero_blocks::<3>(usize::MAX / 64).unwrap_err();
        assert_eq!(e.kind, ErrorKind::LimitExceeded);
        assert!(e.message.contains("for a Hessian of "), "{}", e.message);
        assert_eq!(zero_blocks::<2>(3).unwrap(), vec![[[0.0; 2]; 2]; 3]);
        let e = memory_probe(usize::MAX / 2, "the multigrid").unwrap_err();
        assert_eq!(e.kind, ErrorKind::LimitExceeded);
        assert!(e.message.contains("for the multigrid ("), "{}", e.message);
        assert!(memory_probe(1 << 20, "a megabyte").is_ok());
    }
}
