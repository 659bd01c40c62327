//! The Hessian restricted to the free coordinates, `H_ff`, as a sparse matrix factorised by faer's
//! sparse Cholesky (AMD ordering, supernodal, sequential so the result is the same for any thread
//! count), its solves by the crate's own loops (`supernodal.rs`). The matrix is scaled to a unit
//! diagonal first (`D^{-1/2} H D^{-1/2}`), so that one relative shift serves cells of every size;
//! where it is not positive definite, the smallest of the shifts `τ = 10⁻², 10⁻¹, 1, 10` of the
//! unit diagonal that makes it so gives the modified Newton step (where CG showed the matrix
//! indefinite, tried from the one below the shift of a nearby state's factor).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::reborrow::Reborrow;
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Par, Side};
use rayon::ThreadPool;

use super::blocks::{reserved, BlockLayout, BlockMatrix};
use super::csr::Csr;
use super::problem::Problem;
use super::subtrees::{self, Split};
use super::supernodal::{self, FactorRef};
use crate::error::{Error, ErrorKind, Result};

/// Marks a coordinate that is not free.
const NONE: u32 = u32::MAX;

/// The free coordinates of a mesh, numbered node by node, each node's components in order: the
/// one numbering of `H_ff`'s rows (its factor, the multigrid's finest level, the smoother's
/// node blocks).
#[derive(Clone, Debug)]
pub struct Coordinates {
    /// `id[v·d + k]`: index of the coordinate among the free ones, or `NONE`.
    id: Vec<u32>,
    count: usize,
    dimension: usize,
}

impl Coordinates {
    /// The coordinates whose bits are set in `free` (per node, its free components among
    /// `dimension`).
    pub fn of_mask(free: &[u8], dimension: usize) -> Result<Self> {
        let mut id = vec![NONE; free.len() * dimension];
        let mut count = 0usize;
        for (v, &mask) in free.iter().enumerate() {
            for k in (0..dimension).filter(|k| mask & (1 << k) != 0) {
                id[v * dimension + k] = u32::try_from(count)
                    .ok()
                    .filter(|&i| i != NONE)
                    .ok_or_else(|| Error::invalid("more than 2^32 - 2 free coordinates"))?;
                count += 1;
            }
        }
        Ok(Coordinates {
            id,
            count,
            dimension,
        })
    }

    /// Number of free coordinates.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Index of component `k` of node `v` among the free coordinates.
    pub fn of(&self, v: usize, k: usize) -> Option<usize> {
        let i = self.id[v * self.dimension + k];
        (i != NONE).then_some(i as usize)
    }

    /// The bits of node `v`'s free components.
    pub fn mask(&self, v: usize) -> u8 {
        let ids = &self.id[v * self.dimension..(v + 1) * self.dimension];
        (0..self.dimension)
            .filter(|&k| ids[k] != NONE)
            .fold(0, |mask, k| mask | 1 << k)
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.id.len() / self.dimension
    }

    /// The free coordinates, node by node: `(node, component, index among the free ones)`.
    pub fn free(&self) -> impl Iterator<Item = (usize, usize, usize)> + '_ {
        let d = self.dimension;
        self.id
            .iter()
            .enumerate()
            .filter(|&(_, &i)| i != NONE)
            .map(move |(at, &i)| (at / d, at % d, i as usize))
    }
}

/// Where one stored value of `H_ff`'s lower triangle comes from: block, row and column in it.
#[derive(Clone, Copy, Debug)]
struct Source {
    block: u32,
    a: u8,
    b: u8,
}

/// The lower triangle's structure of a symmetric matrix (compressed columns) with its symbolic
/// Cholesky factorisation, computed once and reused for every matrix of that structure.
pub struct CholeskyPattern {
    structure: SymbolicSparseColMat<usize>,
    /// Position of each column's diagonal value.
    diagonal: Vec<usize>,
    symbolic: SymbolicCholesky<usize>,
    /// The split of the factor's solves into two parallel parts (none for a small factor).
    split: Option<Split>,
}

/// The structure of `H_ff` (lower triangle, columns by free coordinate) and its symbolic
/// Cholesky factorisation, computed once per problem.
pub struct FreeHessian {
    coordinates: Coordinates,
    sources: Vec<Source>,
    pattern: CholeskyPattern,
}

/// Shifts of the unit diagonal tried, in order, where the scaled matrix is not positive definite.
const SHIFTS: [f64; 4] = [1e-2, 1e-1, 1.0, 10.0];

/// A numeric factorisation `D^{-1/2} A D^{-1/2} = L Lᵀ`, possibly of a modified matrix.
pub struct Factor {
    /// The factor's values, computed in double precision and kept in single: it serves as CG's
    /// preconditioner (and a modified Newton step), where its 10⁻⁷ relative error costs at most
    /// an iteration, and its solves stream it from memory, half the bytes. The 17,940-node
    /// refined airfoil: 1.16–1.23 → 1.02–1.03 s, peak 180 → 140 MB; 96,740 nodes: 965 → 755
    /// MB, the same iterations to a Newton step or two (runs alternated).
    values: Vec<f32>,
    /// `1 / L_jj` per column ([`supernodal::reciprocal_diagonal`]).
    inverse: Vec<f64>,
    /// `D^{-1/2}`, per unknown.
    scale: Vec<f64>,
    /// The shift of the diagonal: 0 for none, else `SHIFTS[level - 1]` (the matrix was not
    /// positive definite).
    pub level: usize,
    /// The level tried first (below `level`: the levels from `first` to `level − 1` were too
    /// small).
    pub first: usize,
}

impl Factor {
    /// Whether the diagonal was shifted (the matrix was not positive definite).
    pub fn modified(&self) -> bool {
        self.level > 0
    }
}

impl CholeskyPattern {
    /// The pattern of an `n × n` lower triangle given by columns (rows ascending, the diagonal
    /// first in each column).
    pub fn new(n: usize, col_ptr: Vec<usize>, row_idx: Vec<usize>) -> Result<Self> {
        let diagonal = col_ptr[..n].to_vec();
        if (0..n).any(|j| row_idx.get(diagonal[j]) != Some(&j)) {
            return Err(Error::invalid(
                "a column of the matrix has no diagonal value",
            ));
        }
        let structure = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let symbolic = factorize_symbolic_cholesky(
            structure.rb(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|e| Error::invalid(format!("cannot analyse the matrix's structure: {e:?}")))?;
        let mut pattern = CholeskyPattern {
            structure,
            diagonal,
            symbolic,
            split: None,
        };
        let split = |symbolic| Split::new(symbolic, subtrees::SMALLEST);
        pattern.split = pattern.supernodal().and_then(split);
        Ok(pattern)
    }

    /// The pattern of a symmetric matrix stored in full compressed rows (its upper triangle by
    /// rows is the lower triangle by columns), and the positions of those values in `a`.
    pub fn of_csr(a: &Csr) -> Result<(Self, Vec<usize>)> {
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        let mut positions = Vec::new();
        for j in 0..a.rows() {
            let (cols, _) = a.row(j);
            for (p, &c) in cols.iter().enumerate() {
                if c as usize >= j {
                    row_idx.push(c as usize);
                    positions.push(a.start[j] + p);
                }
            }
            col_ptr.push(row_idx.len());
        }
        Ok((CholeskyPattern::new(a.rows(), col_ptr, row_idx)?, positions))
    }

    /// Number of stored values of the Cholesky factor (memory: 12 bytes each while it is
    /// computed and rounded, 4 kept).
    pub fn factor_size(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Factorises the matrix with these lower-triangle `values`, scaled to a unit diagonal and
    /// shifted where it is not positive definite; `None` for a non-finite or non-positive
    /// diagonal value, or a matrix no shift helps. The shifts are tried from level `first` (0:
    /// none; see [`Factor::level`]) up: where the matrix is known to be indefinite, trying it
    /// unshifted only fails (the 96,740-node refined airfoil's relocation made 67
    /// factorisations, 38 of which failed, 24 of them unshifted; started from the level below a
    /// nearby state's, 45 and 16, the same iterations).
    pub fn factorize(&self, mut values: Vec<f64>, first: usize) -> Result<Option<Factor>> {
        let diagonal: Vec<f64> = self.diagonal.iter().map(|&p| values[p]).collect();
        if diagonal.iter().any(|d| !(d.is_finite() && *d > 0.0)) {
            return Ok(None);
        }
        let scale: Vec<f64> = diagonal.iter().map(|d| 1.0 / d.sqrt()).collect();
        let (col_ptr, row_idx) = (self.structure.col_ptr(), self.structure.row_idx());
        for j in 0..col_ptr.len() - 1 {
            for p in col_ptr[j]..col_ptr[j + 1] {
                values[p] *= scale[row_idx[p]] * scale[j];
            }
        }
        for (i, &shift) in [0.0].iter().chain(&SHIFTS).enumerate().skip(first) {
            if i > 0 {
                for &p in &self.diagonal {
                    values[p] = 1.0 + shift;
                }
            }
            let Some(l) = self.try_factorize(&values)? else {
                crate::diagnostics::note(|| format!("factor: shift level {i} too small"));
                continue;
            };
            let l = single(l)?;
            let inverse = self.supernodal().map_or(Vec::new(), |symbolic| {
                supernodal::reciprocal_diagonal(symbolic, &l)
            });
            return Ok(Some(Factor {
                values: l,
                inverse,
                scale,
                level: i,
                first,
            }));
        }
        Ok(None)
    }

    /// The factor of the matrix with these (scaled, shifted) lower-triangle `values` in double
    /// precision; `None` where it is not positive definite.
    fn try_factorize(&self, values: &[f64]) -> Result<Option<Vec<f64>>> {
        let mut l = reserved(self.symbolic.len_val(), "a Cholesky factor")?;
        l.resize(self.symbolic.len_val(), 0.0);
        let matrix = SparseColMatRef::new(self.structure.rb(), values);
        let scratch = self
            .symbolic
            .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default());
        let mut buffer = MemBuffer::try_new(scratch).map_err(|_| {
            Error::new(
                ErrorKind::LimitExceeded,
                "not enough memory to factorise a matrix",
            )
        })?;
        let result = self.symbolic.factorize_numeric_llt(
            &mut l,
            matrix,
            Side::Lower,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut buffer),
            Default::default(),
        );
        Ok(result.is_ok().then_some(l))
    }

    /// The supernodal structure of the factor (forced in `new`: faer analyses only an empty
    /// matrix as simplicial, and that one has none).
    fn supernodal(&self) -> Option<&SymbolicSupernodalCholesky<usize>> {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(symbolic) => Some(symbolic),
            SymbolicCholeskyRaw::Simplicial(_) => None,
        }
    }

    /// Solves with the factored (possibly modified) matrix in place, on two threads of `pool`
    /// where the factor is large enough (the same result on one).
    pub fn solve(&self, pool: &ThreadPool, factor: &Factor, b: &mut [f64]) {
        let Some(symbolic) = self.supernodal() else {
            return;
        };
        // The factor's ordering of the unknowns (AMD's): `x[i] = b[order(i)]`.
        let arrays = self.symbolic.perm().map(|p| p.arrays());
        let order = |i: usize| arrays.map_or(i, |(order, _)| order[i]);
        let position = |i: usize| arrays.map_or(i, |(_, position)| position[i]);
        let mut x: Vec<f64> = (0..b.len())
            .map(|i| b[order(i)] * factor.scale[order(i)])
            .collect();
        let values = FactorRef {
            symbolic,
            values: &factor.values,
            inverse: &factor.inverse,
        };
        supernodal::solve(pool, values, self.split.as_ref(), &mut x);
        for (i, v) in b.iter_mut().enumerate() {
            *v = x[position(i)] * factor.scale[i];
        }
    }
}

/// `values` rounded to single precision, `values` released before returning; refused where the
/// copy cannot be allocated.
fn single(values: Vec<f64>) -> Result<Vec<f32>> {
    let mut rounded = reserved(values.len(), "a Cholesky factor in single precision")?;
    rounded.extend(values.iter().map(|&v| v as f32));
    Ok(rounded)
}

impl FreeHessian {
    /// The structure of the free block (free components of node `v` given by the bits of
    /// `free[v]`) of `problem`'s Hessian, laid out by `layout`.
    pub fn new<const D: usize>(
        problem: &Problem<D>,
        layout: &BlockLayout,
        free: &[u8],
    ) -> Result<Self> {
        let coordinates = Coordinates::of_mask(free, D)?;
        let n = coordinates.count();
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        let mut sources = Vec::new();
        col_ptr.push(0);
        for w in 0..problem.node_count() {
            for l in 0..D {
                let Some(j) = coordinates.of(w, l) else {
                    continue;
                };
                let (blocks, neighbours) = layout.row(w);
                for (b, &v) in blocks.zip(neighbours) {
                    for k in 0..D {
                        match coordinates.of(v as usize, k) {
                            Some(i) if i >= j => {
                                row_idx.push(i);
                                // Block (w, v) holds ∂²F/∂x_wl∂x_vk at [l][k].
                                sources.push(Source {
                                    block: b as u32,
                                    a: l as u8,
                                    b: k as u8,
                                });
                            }
                            _ => {}
                        }
                    }
                }
                col_ptr.push(row_idx.len());
            }
        }
        Ok(FreeHessian {
            coordinates,
            sources,
            pattern: CholeskyPattern::new(n, col_ptr, row_idx)?,
        })
    }

    /// The free coordinates.
    pub fn coordinates(&self) -> &Coordinates {
        &self.coordinates
    }

    /// Number of stored values of the Cholesky factor ([`CholeskyPattern::factor_size`]).
    pub fn factor_size(&self) -> usize {
        self.pattern.factor_size()
    }

    /// Factorises `H_ff` of `hessian`, shifts tried from level `first` (see
    /// [`CholeskyPattern::factorize`]).
    pub fn factorize<const D: usize>(
        &self,
        hessian: &BlockMatrix<D>,
        first: usize,
    ) -> Result<Option<Factor>> {
        let values = self
            .sources
            .iter()
            .map(|s| hessian.blocks[s.block as usize][s.a as usize][s.b as usize])
            .collect();
        self.pattern.factorize(values, first)
    }

    /// Solves with a factor of `H_ff` in place (`b` over the free coordinates).
    pub fn solve(&self, pool: &ThreadPool, factor: &Factor, b: &mut [f64]) {
        self.pattern.solve(pool, factor, b);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::linalg::cholesky::LltRef;
    use faer::{Conj, MatMut};

    /// A matrix's size and its lower triangle by columns: pointers, rows, values.
    type Matrix = (usize, Vec<usize>, Vec<usize>, Vec<f64>);

    /// The lower triangle by columns of a symmetric positive definite matrix with the structure
    /// of a 2D grid's stiffness (two unknowns per node, nine-point coupling), entries from a
    /// fixed pseudo-random sequence; the last `dropped` unknowns left out (odd sizes).
    fn grid_matrix(m: usize, dropped: usize) -> Matrix {
        let mut seed = 12345u64;
        let mut random = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let n = 2 * m * m - dropped;
        let (mut col_ptr, mut row_idx, mut values) = (vec![0], Vec::new(), Vec::new());
        for j in 0..n {
            let (node, k) = (j / 2, j % 2);
            let (x, y) = (node % m, node / m);
            for i in j..n {
                let other = i / 2;
                let (ox, oy) = (other % m, other / m);
                if ox.abs_diff(x) <= 1 && oy.abs_diff(y) <= 1 {
                    row_idx.push(i);
                    // Off-diagonal entries below 0.5 in magnitude, at most 17 per row: a
                    // diagonal of 10 makes the matrix diagonally dominant.
                    values.push(if i == j { 10.0 + k as f64 } else { random() });
                }
            }
            col_ptr.push(row_idx.len());
        }
        (n, col_ptr, row_idx, values)
    }

    /// The supernodal solve gives faer's solution with the same factor to round-off, and a
    /// residual at the single-precision factor's round-off, whole and split in two parts (here
    /// whatever the factor's size), with the same result on one thread as on two.
    #[test]
    fn the_supernodal_solve_agrees_with_faer() {
        let grids = [(12, 0), (9, 1), (5, 3), (40, 0), (33, 5)].map(|(m, d)| grid_matrix(m, d));
        // Two grids side by side: a forest of two trees.
        let forest = [block_diagonal(&grids[1], &grids[4])];
        for matrix in grids.into_iter().chain(forest) {
            let (n, col_ptr, row_idx, _) = matrix.clone();
            let mut pattern = CholeskyPattern::new(n, col_ptr, row_idx).unwrap();
            assert!(pattern.split.is_none(), "{n}");
            check_solve(&pattern, matrix.clone());
            pattern.split = pattern.supernodal().and_then(|s| Split::new(s, 0));
            // A split where the tree has two balanced parts (which it has depends on faer's
            // ordering: asserted only for the larger grids).
            assert!(pattern.split.is_some() || n < 2000, "{n}");
            check_solve(&pattern, matrix);
        }
    }

    /// The matrix with `a` and `b` on its diagonal (lower triangles by columns).
    fn block_diagonal(a: &Matrix, b: &Matrix) -> Matrix {
        let (mut col_ptr, mut row_idx, mut values) = (a.1.clone(), a.2.clone(), a.3.clone());
        for j in 0..b.0 {
            row_idx.extend(b.2[b.1[j]..b.1[j + 1]].iter().map(|i| i + a.0));
            values.extend_from_slice(&b.3[b.1[j]..b.1[j + 1]]);
            col_ptr.push(row_idx.len());
        }
        (a.0 + b.0, col_ptr, row_idx, values)
    }

    fn check_solve(pattern: &CholeskyPattern, (n, col_ptr, row_idx, values): Matrix) {
        let factor = pattern.factorize(values.clone(), 0).unwrap().unwrap();
        assert!(!factor.modified());
        let b: Vec<f64> = (0..n).map(|i| ((i * 7919) % 101) as f64 - 50.0).collect();
        let solved = |threads| {
            let mut x = b.clone();
            pattern.solve(&crate::threads::pool(threads).unwrap(), &factor, &mut x);
            x
        };
        let x = solved(2);
        assert_eq!(x, solved(1));
        // faer's own solve of the scaled system.
        let mut y: Vec<f64> = b.iter().zip(&factor.scale).map(|(b, s)| b * s).collect();
        let stack = pattern.symbolic.solve_in_place_scratch::<f64>(1, Par::Seq);
        let stored: Vec<f64> = factor.values.iter().map(|&v| f64::from(v)).collect();
        LltRef::new(&pattern.symbolic, &stored).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut y, n, 1),
            Par::Seq,
            MemStack::new(&mut MemBuffer::new(stack)),
        );
        let size = crate::optimize::single::largest(x.iter().copied());
        for (i, (x, y)) in x.iter().zip(&y).enumerate() {
            assert!(
                (x - y * factor.scale[i]).abs() <= 1e-14 * size,
                "{i}: {x} {y}"
            );
        }
        // The residual of the symmetric matrix from its lower triangle.
        let mut r = b.clone();
        for j in 0..n {
            for p in col_ptr[j]..col_ptr[j + 1] {
                let i = row_idx[p];
                r[i] -= values[p] * x[j];
                if i != j {
                    r[j] -= values[p] * x[i];
                }
            }
        }
        let norm = |v: &[f64]| v.iter().map(|v| v * v).sum::<f64>().sqrt();
        // The factor kept in single precision: a residual at its round-off (this matrix is well
        // conditioned).
        assert!(
            norm(&r) <= 1e-6 * norm(&b),
            "residual {}",
            norm(&r) / norm(&b)
        );
    }
}
