//! The finest multigrid level's operator, for its smoother, stored by node blocks in bfloat16:
//! per free node, its free neighbours and one dense block of values per neighbour (the node's
//! free components by the neighbour's). A compressed-row matrix stores a column index beside
//! every value; here one index serves a whole block (on a 3D mesh 9 values: 2.4 bytes per
//! value).
//!
//! The smoother's products move the most data of a relocation: on the wing (tens of millions
//! of values in its finest level, about 160 products per relocation) they were 40% of a
//! relocation's time in single precision, on the 812,040-node refined wing half of it.
//! bfloat16 (single precision's exponent, 8 significant bits) halves that traffic: the wing's
//! relocation took 5.5–5.6 s instead of 6.9–7.2 s (alternated runs), with the same CG
//! iterations (2, 3, 7 and 11 in its four Newton steps) and the same optimum to 10⁻¹¹. The
//! smoother needs no more: it damps the oscillating part of the error and the coarse levels,
//! made from the double-precision Hessian, correct the rest; its eigenvalue estimate is made
//! with these same values.
//!
//! The arithmetic is single precision: the vector is rounded to it, bfloat16 values widen to it
//! by a shift, and a whole 3×3 block's first eight products go as two vectors of four (where
//! widening each value to double precision cost more than its load). Values and vector are first
//! scaled by powers of two to at most 1 and negligible ones made 0, so that no product is
//! subnormal (`single.rs`). The wing 4.47–4.92 → 4.07–4.35 s, the 812,040-node wing
//! 54.6–58.0 → 49.4 s (alternated runs), with the same CG iterations and optimum (its objective
//! the same to 10⁻¹²).
//!
//! Each row sums its values in the order of their columns, so the result does not depend on the
//! thread count.

use rayon::prelude::*;
use rayon::ThreadPool;

use super::blocks::{BlockLayout, BlockMatrix};
use super::csr::split_rows;
use super::single::{largest, normalising, rounded, NEGLIGIBLE};
use super::sparse::Coordinates;

/// A bfloat16 value: the upper half of a single-precision one. Written here rather than taken
/// from the `half` crate, which would bring a procedural-macro chain (zerocopy-derive, syn)
/// into the library's build for these two conversions.
#[derive(Clone, Copy, Debug)]
pub struct Bf16(u16);

impl From<f64> for Bf16 {
    /// `v` rounded to single precision, then to the nearest bfloat16 (ties to even; a value
    /// past bfloat16's largest rounds to infinity, as in single precision; NaN stays NaN).
    fn from(v: f64) -> Self {
        if v.is_nan() {
            return Bf16(0x7fc0);
        }
        let bits = (v as f32).to_bits();
        let rounded = bits.wrapping_add(0x7fff + ((bits >> 16) & 1));
        Bf16((rounded >> 16) as u16)
    }
}

impl Bf16 {
    /// `v` times the power of two `scale`, rounded, or 0 where that is below [`NEGLIGIBLE`].
    fn scaled(v: f64, scale: f64) -> Self {
        let v = v * scale;
        match v.abs() < NEGLIGIBLE {
            true => Bf16(0),
            false => Bf16::from(v),
        }
    }

    /// The value, exactly, in single precision.
    #[inline]
    pub fn single(self) -> f32 {
        f32::from_bits(u32::from(self.0) << 16)
    }
}

/// Nodes per parallel task of a product.
const RUN: usize = 256;

/// A symmetric operator over the free coordinates of the nodes, by node blocks.
#[derive(Clone, Debug, Default)]
pub struct BlockRows {
    /// Per free node: its first coordinate (coordinates are numbered node by node).
    first: Vec<u32>,
    /// Per free node: its number of free components.
    width: Vec<u8>,
    /// Per free node: the range of its blocks in `neighbour`.
    block_start: Vec<usize>,
    /// Per free node: where its blocks' values start in `value`.
    value_start: Vec<usize>,
    /// Per block: the free node it couples to.
    neighbour: Vec<u32>,
    /// The blocks' values, block after block, each row-major, in bfloat16 ([`Bf16`]).
    value: Vec<Bf16>,
    /// Number of free coordinates.
    rows: usize,
    /// The power of two the values were multiplied by (the diagonal's largest to at most 1).
    scale: f64,
}

impl BlockRows {
    /// The free-by-free part of `hessian` (its rows and columns the free `coordinates`), its
    /// values rounded to bfloat16. Nodes with no free component are left out.
    pub fn new<const D: usize>(
        pool: &ThreadPool,
        layout: &BlockLayout,
        hessian: &BlockMatrix<D>,
        coordinates: &Coordinates,
    ) -> Self {
        let node_count = coordinates.node_count();
        let free: Vec<u8> = (0..node_count).map(|v| coordinates.mask(v)).collect();
        let nodes: Vec<usize> = (0..node_count).filter(|&v| free[v] != 0).collect();
        let mut index = vec![u32::MAX; node_count];
        let mut out = BlockRows::default();
        for (i, &v) in nodes.iter().enumerate() {
            index[v] = i as u32;
            let first = (0..D)
                .find_map(|k| coordinates.of(v, k))
                .expect("a free component");
            out.first.push(first as u32);
            out.width.push(free[v].count_ones() as u8);
        }
        out.rows = coordinates.count();
        // The largest value of a positive semi-definite matrix is on its diagonal.
        let diagonal = nodes.iter().filter_map(|&v| layout.find(v, v));
        let diagonal = diagonal.flat_map(|b| (0..D).map(move |k| hessian.blocks[b][k][k]));
        out.scale = normalising(largest(diagonal));
        // Blocks and values per node first, then every node's blocks written in place.
        let couplings = |v: usize| {
            let (blocks, neighbours) = layout.row(v);
            blocks
                .zip(neighbours)
                .filter(|&(_, &w)| free[w as usize] != 0)
                .map(|(b, &w)| (b, w as usize))
        };
        let counts: Vec<(usize, usize)> = pool.install(|| {
            nodes
                .par_iter()
                .map(|&v| {
                    couplings(v).fold((0, 0), |(blocks, values), (_, w)| {
                        let size = free[v].count_ones() * free[w].count_ones();
                        (blocks + 1, values + size as usize)
                    })
                })
                .collect()
        });
        out.block_start.push(0);
        out.value_start.push(0);
        for &(blocks, values) in &counts {
            out.block_start
                .push(out.block_start[out.block_start.len() - 1] + blocks);
            out.value_start
                .push(out.value_start[out.value_start.len() - 1] + values);
        }
        out.neighbour = vec![0; out.block_start[nodes.len()]];
        // Zeros written in parallel (`vec!` writes them on one thread: on the 812,040-node
        // wing, a gigabyte of first touches, one page fault after the other).
        let count = out.value_start[nodes.len()];
        out.value = pool.install(|| (0..count).into_par_iter().map(|_| Bf16(0)).collect());
        let neighbours = split_rows(&mut out.neighbour, counts.iter().map(|c| c.0));
        let values = split_rows(&mut out.value, counts.iter().map(|c| c.1));
        let components = |mask: u8| (0..D).filter(move |k| mask & (1 << k) != 0);
        let scale = out.scale;
        pool.install(|| {
            nodes
                .par_iter()
                .zip(neighbours)
                .zip(values)
                .for_each(|((&v, n), x)| {
                    let mut at = 0;
                    for ((b, w), slot) in couplings(v).zip(n.iter_mut()) {
                        *slot = index[w];
                        for k in components(free[v]) {
                            for l in components(free[w]) {
                                x[at] = Bf16::scaled(hessian.blocks[b][k][l], scale);
                                at += 1;
                            }
                        }
                    }
                })
        });
        out
    }

    /// Number of rows (free coordinates).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// `y = A x`, multiplied in single precision (see the module's documentation) and scaled
    /// back in double; each row summed by the entries of its blocks in the order of its columns
    /// (see `node_product`), the same order for any thread count. Nodes run in parallel by runs
    /// of `RUN` (256), each node's rows together (one pass over its blocks).
    pub fn apply(&self, pool: &ThreadPool, x: &[f64], y: &mut [f64]) {
        let nodes = self.first.len();
        let starts: Vec<usize> = (0..nodes).step_by(RUN).collect();
        let end = |start: usize| (start + RUN).min(nodes);
        let lengths = starts
            .iter()
            .map(|&start| self.row_end(end(start)) - self.first[start] as usize);
        let runs = split_rows(y, lengths);
        let (x, scale) = rounded(x);
        let (x, unscale) = (&x[..], 1.0 / (scale * self.scale));
        pool.install(|| {
            starts.into_par_iter().zip(runs).for_each(|(start, out)| {
                let mut at = 0;
                for v in start..end(start) {
                    let height = self.width[v] as usize;
                    let row = self.node_product(v, x);
                    for (o, r) in out[at..at + height].iter_mut().zip(row) {
                        *o = f64::from(r) * unscale;
                    }
                    at += height;
                }
            })
        });
    }

    /// The rows of node `v` times `x` (the first `width[v]` entries). Each entry of a block
    /// has a running sum of its own (entry `(k, l)` in slot `3k + l`), the row's three added
    /// at the end: nine independent chains of one addition per block, where one sum per row
    /// made three chains of three additions per block, bound by the additions' latency.
    #[inline]
    fn node_product(&self, v: usize, x: &[f32]) -> [f32; 3] {
        let height = self.width[v] as usize;
        let mut slots = [-0.0f32; 9];
        let mut at = self.value_start[v];
        for &w in &self.neighbour[self.block_start[v]..self.block_start[v + 1]] {
            let (first, width) = (self.first[w as usize] as usize, self.width[w as usize]);
            let width = width as usize;
            let xs = &x[first..first + width];
            let block = &self.value[at..at + height * width];
            if let (Ok(b), Ok(xs)) = (<&[Bf16; 9]>::try_from(block), <&[f32; 3]>::try_from(xs)) {
                // Whole 3×3 blocks (most of a solid mesh): unrolled, the first eight slots
                // as two vectors of four.
                let xv = [xs[0], xs[1], xs[2], xs[0], xs[1], xs[2], xs[0], xs[1]];
                for j in 0..8 {
                    slots[j] += b[j].single() * xv[j];
                }
                slots[8] += b[8].single() * xs[2];
            } else {
                for (k, row) in block.chunks_exact(width).enumerate() {
                    for (l, (a, b)) in row.iter().zip(xs).enumerate() {
                        slots[3 * k + l] += a.single() * b;
                    }
                }
            }
            at += height * width;
        }
        std::array::from_fn(|k| (slots[3 * k] + slots[3 * k + 1]) + slots[3 * k + 2])
    }

    /// The end of the rows of the nodes before `node`.
    fn row_end(&self, node: usize) -> usize {
        match node < self.first.len() {
            true => self.first[node] as usize,
            false => self.rows,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe_mesh::{problem_of, CellType};
    use crate::optimize::global::GlobalObjective;
    use crate::optimize::problem::TargetKind;
    use crate::optimize::single::single;

    /// One cell of `cell_type` on its lattice (spacing ½, slightly bent so that the Hessian has
    /// no zero pattern of its own), with fixed, sliding and free nodes: the node blocks'
    /// product equals, to the last bit, the free-by-free Hessian scaled and rounded to bfloat16
    /// times the scaled vector in single precision, summed in column order by a sum per position
    /// of a column in its node, the row's sums added last, scaled back. A vector scaled by
    /// 2⁻⁶⁰⁰ (far below single precision's range) has its product scaled by 2⁻⁶⁰⁰, exactly.
    fn reproduces<const D: usize>(cell_type: CellType) {
        let reference: Vec<[f64; 3]> = cell_type
            .lattice()
            .iter()
            .map(|&l| {
                let p: [f64; 3] = std::array::from_fn(|k| (l / 3usize.pow(k as u32) % 3) as f64);
                [0.5 * p[0] + 0.03 * p[1] * p[1], 0.5 * p[1], 0.5 * p[2]]
            })
            .map(|p| [p[0], p[1], if D == 2 { 0.0 } else { p[2] }])
            .collect();
        let n = reference.len();
        let connectivity: Vec<u32> = (0..n as u32).collect();
        // Fixed masks: all, one or no component fixed, in turn.
        let fixed: Vec<u8> = (0..n).map(|v| [(1 << D) - 1, 1, 0, 0][v % 4]).collect();
        let problem = problem_of::<D>(
            cell_type,
            &connectivity,
            &fixed,
            &reference,
            TargetKind::Master,
            1.0,
        )
        .unwrap();
        let pool = crate::threads::pool(2).unwrap();
        let layout = BlockLayout::new(&pool, &problem);
        let x: Vec<[f64; D]> = reference
            .iter()
            .map(|p| std::array::from_fn(|k| p[k]))
            .collect();
        let objective = GlobalObjective::new(&problem, &layout, None, 0.0);
        let hessian = objective
            .evaluate(&pool, &x, true)
            .unwrap()
            .hessian
            .unwrap();
        let free: Vec<u8> = (0..n).map(|v| problem.free_mask(v)).collect();
        let coordinates = Coordinates::of_mask(&free, D).unwrap();
        let rows = BlockRows::new(&pool, &layout, &hessian, &coordinates);
        // The free coordinates, node by node.
        let coordinates: Vec<(usize, usize)> = (0..n)
            .flat_map(|v| (0..D).map(move |k| (v, k)))
            .filter(|&(v, k)| free[v] & (1 << k) != 0)
            .collect();
        assert_eq!(rows.rows(), coordinates.len());
        let input: Vec<f64> = (0..rows.rows())
            .map(|i| (0.7 * i as f64 + 0.3).sin())
            .collect();
        let input_scale = normalising(largest(input.iter().copied()));
        assert!(input.iter().all(|v| (v * input_scale).abs() >= NEGLIGIBLE));
        let mut y = vec![0.0; rows.rows()];
        rows.apply(&pool, &input, &mut y);
        for (i, &(v, k)) in coordinates.iter().enumerate() {
            // A running sum per position of a column within its node's free components.
            let mut slots = [-0.0f32; 3];
            for (j, &(w, l)) in coordinates.iter().enumerate() {
                if let Some(b) = layout.find(v, w) {
                    let position = (0..l).filter(|&m| free[w] & (1 << m) != 0).count();
                    let value = Bf16::scaled(hessian.blocks[b][k][l], rows.scale).single();
                    slots[position] += value * single(input[j] * input_scale);
                }
            }
            let sum = f64::from((slots[0] + slots[1]) + slots[2]) / (input_scale * rows.scale);
            assert_eq!(
                y[i].to_bits(),
                sum.to_bits(),
                "row {i} (node {v}, component {k})"
            );
        }
        let tiny = 2f64.powi(-600);
        let scaled: Vec<f64> = input.iter().map(|v| v * tiny).collect();
        let mut z = vec![0.0; rows.rows()];
        rows.apply(&pool, &scaled, &mut z);
        for (y, z) in y.iter().zip(&z) {
            assert_eq!((y * tiny).to_bits(), z.to_bits());
        }
    }

    /// Rounding to bfloat16: exact where 8 significant bits hold the value, to nearest (ties to
    /// even) within half a unit of the 8th bit, infinite past the largest, NaN kept.
    #[test]
    fn bfloat16_rounds_to_nearest() {
        for v in [0.0, -0.0, 1.0, -2.5, 0.0078125, 255.0, 1.5e-30] {
            let exact = f64::from(Bf16::from(v).single());
            assert!(
                exact == v || (exact - v).abs() <= v.abs() * 2f64.powi(-8),
                "{v}"
            );
        }
        assert_eq!(Bf16::from(257.0).single(), 256.0); // a tie: to the even 256
        assert_eq!(Bf16::from(259.0).single(), 260.0); // a tie: to the even 260
        assert_eq!(Bf16::from(258.9).single(), 258.0);
        let mut v = 0.3f64;
        for _ in 0..1000 {
            v = (v * 3.7 + 0.1).fract() * 1e3 - 500.0;
            assert!(
                (f64::from(Bf16::from(v).single()) - v).abs() <= v.abs() * 2f64.powi(-8),
                "{v}"
            );
        }
        assert_eq!(Bf16::from(1e39).single(), f32::INFINITY);
        assert!(Bf16::from(f64::NAN).single().is_nan());
    }

    #[test]
    fn node_blocks_reproduce_the_free_block_of_the_hessian() {
        reproduces::<2>(CellType::Quad9);
        reproduces::<3>(CellType::Hex27);
    }
}
