//! The project's sparse direct solves, by faer: LU (fill-reducing column ordering, partial
//! pivoting) for square non-symmetric systems (the spline collocation, Floater's mean-value
//! map) and Cholesky for symmetric positive definite ones (the least-squares normal equations),
//! assembled from triplets (duplicates summed) or from dense blocks, each with an estimate of
//! its reciprocal condition number in the 1-norm (Hager and Higham's estimator, a handful of
//! solves) by which the spline fit judges a system badly conditioned.
//!
//! faer runs here without its own thread pool: these systems are small (thousands to a few
//! hundred thousand unknowns, solved in milliseconds to a second), and a sequential
//! factorisation gives the same bits whatever the number of threads.

use faer::linalg::solvers::SolveCore;
use faer::sparse::linalg::solvers::{Llt, Lu};
use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMat, Triplet};
use faer::{Conj, Mat, Side};

use crate::error::{Error, Result};

/// Reciprocal condition number under which a system is declared singular.
const SINGULAR: f64 = 1e-13;

/// One entry of a sparse matrix: row, column, value (entries at the same place add up).
pub type Entry = (usize, usize, f64);

/// The factorisation behind a [`SparseSolver`].
#[derive(Clone, Debug)]
enum Factor {
    Lu(Box<Lu<usize, f64>>),
    Cholesky(Llt<usize, f64>),
}

/// A factorised sparse square matrix `A`: solves `A x = b` for several right-hand sides.
#[derive(Clone, Debug)]
pub struct SparseSolver {
    n: usize,
    factor: Factor,
    reciprocal_condition: f64,
}

/// The `n × n` CSC matrix of `entries`, checked.
fn matrix(n: usize, entries: &[Entry]) -> Result<SparseColMat<usize, f64>> {
    if let Some(&(i, j, _)) = entries.iter().find(|&&(i, j, _)| i >= n || j >= n) {
        return Err(Error::invalid(format!(
            "sparse matrix entry ({i}, {j}) outside the {n} × {n} matrix"
        )));
    }
    if let Some(&(i, j, v)) = entries.iter().find(|e| !e.2.is_finite()) {
        return Err(Error::invalid(format!(
            "sparse matrix entry ({i}, {j}) is {v}"
        )));
    }
    let triplets: Vec<Triplet<usize, usize, f64>> = entries
        .iter()
        .map(|&(row, col, val)| Triplet { row, col, val })
        .collect();
    SparseColMat::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| Error::invalid(format!("sparse matrix: {e:?}")))
}

/// Largest absolute column sum: the 1-norm of the matrix.
fn norm_one(n: usize, entries: &[Entry]) -> f64 {
    let mut columns = vec![0.0f64; n];
    for &(_, j, v) in entries {
        columns[j] += v.abs();
    }
    columns.into_iter().fold(0.0, f64::max)
}

impl SparseSolver {
    /// Factors the general `n × n` matrix given by `entries` by sparse LU with partial
    /// pivoting. Fails with a message containing "singular" when the matrix is (numerically)
    /// singular.
    pub fn lu(n: usize, entries: &[Entry]) -> Result<Self> {
        let a = matrix(n, entries)?;
        let lu = a
            .sp_lu()
            .map_err(|e| Error::invalid(format!("the collocation matrix is singular ({e:?})")))?;
        Self::new(
            n,
            norm_one(n, entries),
            Factor::Lu(Box::new(lu)),
            "collocation",
        )
    }

    /// Factors the symmetric positive definite `n × n` matrix given by `entries` by sparse
    /// Cholesky; only the entries with row ≥ column (the lower triangle) are read. Fails with a
    /// message containing "singular" when it is not (numerically) positive definite.
    pub fn cholesky(n: usize, entries: &[Entry]) -> Result<Self> {
        let lower: Vec<Entry> = entries.iter().copied().filter(|e| e.0 >= e.1).collect();
        let a = matrix(n, &lower)?;
        Self::cholesky_of(a.as_ref())
    }

    /// The Cholesky factorisation of the symmetric matrix whose lower triangle is `a`.
    fn cholesky_of(a: SparseColMatRef<'_, usize, f64>) -> Result<Self> {
        let n = a.nrows();
        let mut columns = vec![0.0f64; n];
        for j in 0..n {
            for (&i, &v) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
                columns[j] += v.abs();
                if i != j {
                    columns[i] += v.abs();
                }
            }
        }
        let norm = columns.into_iter().fold(0.0, f64::max);
        let llt = a.sp_cholesky(Side::Lower).map_err(|e| {
            Error::invalid(format!(
                "the normal equations are singular (not positive definite: {e:?})"
            ))
        })?;
        Self::new(n, norm, Factor::Cholesky(llt), "normal-equation")
    }

    fn new(n: usize, norm: f64, factor: Factor, what: &str) -> Result<Self> {
        let mut solver = SparseSolver {
            n,
            factor,
            reciprocal_condition: 1.0,
        };
        if n > 0 {
            let inverse = solver.inverse_norm_one();
            solver.reciprocal_condition = 1.0 / (norm * inverse);
        }
        let rc = solver.reciprocal_condition;
        if rc.is_nan() || rc < SINGULAR {
            return Err(Error::invalid(format!(
                "the {what} matrix is singular: reciprocal condition number {rc:e} of {n} unknowns"
            )));
        }
        Ok(solver)
    }

    /// Number of unknowns.
    pub fn size(&self) -> usize {
        self.n
    }

    /// Estimate of `1 / (‖A‖₁ ‖A⁻¹‖₁)`, in (0, 1]: small when the system is badly conditioned.
    pub fn reciprocal_condition(&self) -> f64 {
        self.reciprocal_condition
    }

    /// Solves `A x = b` (or `Aᵀ x = b`) in place for the columns of `b`.
    fn solve_mat(&self, b: &mut Mat<f64>, transpose: bool) {
        let solver: &dyn SolveCore<f64> = match &self.factor {
            Factor::Lu(lu) => lu.as_ref(),
            Factor::Cholesky(llt) => llt,
        };
        if transpose {
            solver.solve_transpose_in_place_with_conj(Conj::No, b.as_mut());
        } else {
            solver.solve_in_place_with_conj(Conj::No, b.as_mut());
        }
    }

    /// Solves `A x = b` for `D` right-hand sides at once: `b[i][k]` is row `i` of the `k`-th.
    pub fn solve<const D: usize>(&self, b: &mut [[f64; D]]) {
        let mut m = Mat::from_fn(self.n, D, |i, k| b[i][k]);
        self.solve_mat(&mut m, false);
        for (i, row) in b.iter_mut().enumerate() {
            for (k, v) in row.iter_mut().enumerate() {
                *v = m[(i, k)];
            }
        }
    }

    /// `‖A⁻¹‖₁` estimated by Hager's method as refined by Higham (LAPACK's `dlacn2`): at most
    /// five pairs of solves with `A` and `Aᵀ`, then the alternating test vector.
    fn inverse_norm_one(&self) -> f64 {
        let n = self.n;
        let solve = |x: &[f64], transpose: bool| -> Vec<f64> {
            let mut m = Mat::from_fn(n, 1, |i, _| x[i]);
            self.solve_mat(&mut m, transpose);
            (0..n).map(|i| m[(i, 0)]).collect()
        };
        let norm = |y: &[f64]| y.iter().map(|v| v.abs()).sum::<f64>();
        let mut x = vec![1.0 / n as f64; n];
        let mut estimate = 0.0f64;
        let mut last = usize::MAX;
        for _ in 0..5 {
            let y = solve(&x, false);
            let value = norm(&y);
            if !value.is_finite() {
                return f64::INFINITY;
            }
            if value <= estimate && last != usize::MAX {
                break;
            }
            estimate = value;
            let signs: Vec<f64> = y
                .iter()
                .map(|&v| if v >= 0.0 { 1.0 } else { -1.0 })
                .collect();
            let z = solve(&signs, true);
            let j = (0..n)
                .max_by(|&a, &b| z[a].abs().total_cmp(&z[b].abs()).then(b.cmp(&a)))
                .unwrap_or(0);
            if j == last {
                break;
            }
            last = j;
            x.iter_mut().for_each(|v| *v = 0.0);
            x[j] = 1.0;
        }
        let alternating: Vec<f64> = (0..n)
            .map(|i| {
                let s = if i % 2 == 0 { 1.0 } else { -1.0 };
                s * (1.0 + i as f64 / (n.max(2) - 1) as f64)
            })
            .collect();
        let tail = 2.0 * norm(&solve(&alternating, false)) / (3.0 * n as f64);
        if tail.is_finite() {
            estimate.max(tail)
        } else {
            f64::INFINITY
        }
    }
}

/// The lower triangle of a symmetric sparse matrix whose pattern is the union of dense blocks
/// (the normal equations of a fit: one block per element, its functions), in CSC form.
#[derive(Clone, Debug)]
pub struct SymmetricAssembly {
    n: usize,
    col_ptr: Vec<usize>,
    /// Row indices, increasing within each column.
    rows: Vec<usize>,
    values: Vec<f64>,
}

impl SymmetricAssembly {
    /// The zero matrix with the pattern of the `blocks` (each a list of distinct indices
    /// below `n`, increasing): entry `(i, j)`, `i ≥ j`, exists when one block holds both.
    pub fn new(n: usize, blocks: &[&[usize]]) -> Result<Self> {
        if let Some(b) = blocks
            .iter()
            .find(|b| b.windows(2).any(|w| w[0] >= w[1]) || b.last().is_some_and(|&i| i >= n))
        {
            return Err(Error::invalid(format!(
                "block {b:?} is not increasing below {n}"
            )));
        }
        let mut of_index = vec![Vec::new(); n];
        for (k, b) in blocks.iter().enumerate() {
            for &j in b.iter() {
                of_index[j].push(k);
            }
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut rows = Vec::new();
        let mut mark = vec![usize::MAX; n];
        for (j, holding) in of_index.iter().enumerate() {
            let start = rows.len();
            for &k in holding {
                for &i in blocks[k].iter().filter(|&&i| i >= j) {
                    if mark[i] != j {
                        mark[i] = j;
                        rows.push(i);
                    }
                }
            }
            rows[start..].sort_unstable();
            col_ptr.push(rows.len());
        }
        let values = vec![0.0; rows.len()];
        Ok(SymmetricAssembly {
            n,
            col_ptr,
            rows,
            values,
        })
    }

    /// Adds the dense symmetric block `values` (row-major, `indices.len()` squared; the
    /// entries of its lower triangle are read) at rows and columns `indices`, which must be
    /// one of the blocks of the pattern (or part of one).
    pub fn add_block(&mut self, indices: &[usize], values: &[f64]) {
        let m = indices.len();
        for (b, &j) in indices.iter().enumerate() {
            let column = self.col_ptr[j]..self.col_ptr[j + 1];
            let rows = &self.rows[column.clone()];
            for (a, &i) in indices.iter().enumerate().skip(b) {
                let at = rows
                    .binary_search(&i)
                    .expect("the block is part of the pattern");
                self.values[column.start + at] += values[a * m + b];
            }
        }
    }

    /// Factors the matrix by sparse Cholesky (see [`SparseSolver::cholesky`]).
    pub fn cholesky(self) -> Result<SparseSolver> {
        if let Some(v) = self.values.iter().find(|v| !v.is_finite()) {
            return Err(Error::invalid(format!("normal-equation entry {v}")));
        }
        let symbolic =
            SymbolicSparseColMat::new_checked(self.n, self.n, self.col_ptr, None, self.rows);
        SparseSolver::cholesky_of(SparseColMatRef::new(symbolic.as_ref(), &self.values))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A permuted tridiagonal matrix, diagonally dominant.
    fn tridiagonal(n: usize, symmetric: bool) -> Vec<Entry> {
        let perm = |i: usize| (i * 7) % n;
        let mut entries = Vec::new();
        for i in 0..n {
            entries.push((perm(i), perm(i), 4.0 + i as f64 * 0.01));
            if i > 0 {
                entries.push((perm(i), perm(i - 1), 1.5));
                entries.push((perm(i - 1), perm(i), if symmetric { 1.5 } else { -0.5 }));
            }
        }
        entries
    }

    fn check_solves(n: usize, entries: &[Entry], solver: &SparseSolver) {
        let x: Vec<[f64; 2]> = (0..n)
            .map(|i| [(i as f64).sin(), (i as f64).cos()])
            .collect();
        let mut b = vec![[0.0; 2]; n];
        for &(i, j, v) in entries {
            for k in 0..2 {
                b[i][k] += v * x[j][k];
            }
        }
        solver.solve(&mut b);
        for i in 0..n {
            for k in 0..2 {
                assert!((b[i][k] - x[i][k]).abs() < 1e-12, "{i}: {b:?}");
            }
        }
    }

    #[test]
    fn lu_and_cholesky_solve_permuted_tridiagonal_systems() {
        let n = 30;
        let general = tridiagonal(n, false);
        let lu = SparseSolver::lu(n, &general).unwrap();
        check_solves(n, &general, &lu);
        let symmetric = tridiagonal(n, true);
        let llt = SparseSolver::cholesky(n, &symmetric).unwrap();
        check_solves(n, &symmetric, &llt);
        // The same matrix assembled from 2 × 2 blocks, one per off-diagonal pair.
        let pairs: Vec<Vec<usize>> = symmetric
            .iter()
            .filter(|e| e.0 > e.1)
            .map(|e| vec![e.1, e.0])
            .collect();
        let blocks: Vec<&[usize]> = pairs.iter().map(|b| &b[..]).collect();
        let mut assembly = SymmetricAssembly::new(n, &blocks).unwrap();
        let mut diagonal_done = vec![false; n];
        for b in &pairs {
            let d = |i: usize, done: &mut Vec<bool>| {
                let first = !done[i];
                done[i] = true;
                if first {
                    4.0 + (0..n).find(|&k| (k * 7) % n == i).unwrap() as f64 * 0.01
                } else {
                    0.0
                }
            };
            let (a, c) = (d(b[0], &mut diagonal_done), d(b[1], &mut diagonal_done));
            assembly.add_block(b, &[a, 1.5, 1.5, c]);
        }
        let assembled = assembly.cholesky().unwrap();
        check_solves(n, &symmetric, &assembled);
        // Diagonally dominant by a factor of about 4/3: well conditioned.
        assert!(
            lu.reciprocal_condition() > 0.05,
            "{}",
            lu.reciprocal_condition()
        );
        assert!(llt.reciprocal_condition() > 0.05);
    }

    #[test]
    fn the_condition_estimate_is_that_of_a_diagonal_matrix() {
        // For a diagonal matrix the estimate is exact: min |d| / max |d|.
        let entries: Vec<Entry> = (0..10).map(|i| (i, i, 10f64.powi(-(i as i32)))).collect();
        let lu = SparseSolver::lu(10, &entries).unwrap();
        assert!((lu.reciprocal_condition() - 1e-9).abs() < 1e-20);
    }

    #[test]
    fn singular_and_malformed_matrices_are_refused() {
        let singular = [(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 4.0)];
        let e = SparseSolver::lu(2, &singular).unwrap_err();
        assert!(e.message.contains("singular"), "{}", e.message);
        let e = SparseSolver::cholesky(2, &singular).unwrap_err();
        assert!(e.message.contains("singular"), "{}", e.message);
        // Structurally singular: an empty column.
        let e = SparseSolver::lu(2, &[(0, 0, 1.0), (1, 0, 1.0)]).unwrap_err();
        assert!(e.message.contains("singular"), "{}", e.message);
        assert!(SparseSolver::lu(2, &[(0, 2, 1.0)]).is_err());
        assert!(SymmetricAssembly::new(2, &[&[1, 0]]).is_err());
        assert!(SparseSolver::lu(1, &[(0, 0, f64::NAN)]).is_err());
    }
}
