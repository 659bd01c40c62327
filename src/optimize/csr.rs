//! A plain compressed-sparse-row matrix with the few operations the multigrid preconditioner
//! needs: a row-parallel product (each row sums in column order, so the result does not depend
//! on the thread count), the transpose, and the sparse product (Gustavson's algorithm, row by
//! row or by groups of rows that share their columns). Hand-written because these are the hot
//! loops of the preconditioner and faer's sparse types add nothing to them.

use rayon::prelude::*;
use rayon::ThreadPool;

use super::single::{largest, normalising, rounded, single};

/// `values` cut into consecutive rows of the given `lengths` (which add up to at most its
/// length), for rows to be written in parallel, each into its own slice.
pub fn split_rows<T>(values: &mut [T], lengths: impl IntoIterator<Item = usize>) -> Vec<&mut [T]> {
    let mut rest = values;
    lengths
        .into_iter()
        .map(|length| {
            let (row, tail) = std::mem::take(&mut rest).split_at_mut(length);
            rest = tail;
            row
        })
        .collect()
}

/// A sparse matrix in compressed rows, its values in double precision (`T = f64`, every
/// operation) or single (`T = f32`, products only: the operator of a multigrid level's
/// smoother, see [`Csr::single`]).
#[derive(Clone, Debug, Default)]
pub struct Csr<T = f64> {
    /// Number of columns.
    pub columns: usize,
    /// Row `i` holds `start[i]..start[i + 1]` of `column` and `value`.
    pub start: Vec<usize>,
    /// Column of each stored value, ascending within a row.
    pub column: Vec<u32>,
    /// Stored values.
    pub value: Vec<T>,
}

impl<T: Copy + Into<f64> + Send + Sync> Csr<T> {
    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.start.len() - 1
    }

    /// Number of stored values.
    pub fn stored(&self) -> usize {
        self.value.len()
    }

    /// The columns and values of row `i`.
    pub fn row(&self, i: usize) -> (&[u32], &[T]) {
        let range = self.start[i]..self.start[i + 1];
        (&self.column[range.clone()], &self.value[range])
    }

    /// `y = A x`, each row summed in double precision.
    pub fn apply(&self, pool: &ThreadPool, x: &[f64], y: &mut [f64]) {
        pool.install(|| {
            y.par_iter_mut().enumerate().for_each(|(i, yi)| {
                let (cols, vals) = self.row(i);
                *yi = cols
                    .iter()
                    .zip(vals)
                    .map(|(&c, &v)| v.into() * x[c as usize])
                    .sum();
            })
        });
    }
}

impl Csr<f32> {
    /// `y = A x / scale` for the matrix of [`Csr::single`] and its `scale`: multiplied in
    /// single precision, `x` rounded to it (`single.rs`), each row summed by four running sums
    /// in the order of its columns (the same for any thread count; one sum is a chain of
    /// dependent additions), and scaled back in double precision.
    pub fn apply_single(&self, pool: &ThreadPool, scale: f64, x: &[f64], y: &mut [f64]) {
        let (x, x_scale) = rounded(x);
        let unscale = 1.0 / (scale * x_scale);
        pool.install(|| {
            y.par_iter_mut().enumerate().for_each(|(i, yi)| {
                let (cols, vals) = self.row(i);
                let mut sums = [-0.0f32; 4];
                let (c4, v4) = (cols.chunks_exact(4), vals.chunks_exact(4));
                let (ct, vt) = (c4.remainder(), v4.remainder());
                for (c, v) in c4.zip(v4) {
                    for k in 0..4 {
                        sums[k] += v[k] * x[c[k] as usize];
                    }
                }
                for (k, (&c, &v)) in ct.iter().zip(vt).enumerate() {
                    sums[k] += v * x[c as usize];
                }
                *yi = f64::from((sums[0] + sums[1]) + (sums[2] + sums[3])) * unscale;
            })
        });
    }
}

impl Csr {
    /// The matrix with its values scaled by a power of two to at most 1 and rounded to single
    /// precision (`single.rs`), for [`Csr::apply_single`]; with that power of two. Products
    /// are bound by memory traffic, 12 bytes per stored value in double precision and 8 in
    /// single (the wing's finest multigrid level holds tens of millions of values, and its
    /// products were 45% of the wing's relocation).
    pub fn single(self) -> (Csr<f32>, f64) {
        let scale = normalising(largest(self.value.iter().copied()));
        let matrix = Csr {
            columns: self.columns,
            value: self.value.iter().map(|&v| single(v * scale)).collect(),
            start: self.start,
            column: self.column,
        };
        (matrix, scale)
    }

    /// Builds a matrix from rows given as `(column, value)` lists (sorted, no repeats).
    pub fn from_rows(columns: usize, rows: Vec<Vec<(u32, f64)>>) -> Self {
        // Reserved exactly: grown by doubling, the arrays of a fine level's product (hundreds of
        // megabytes) would peak at twice their size, copied as they grow.
        let stored = rows.iter().map(Vec::len).sum();
        let mut m = Csr {
            columns,
            start: Vec::with_capacity(rows.len() + 1),
            column: Vec::with_capacity(stored),
            value: Vec::with_capacity(stored),
        };
        m.start.push(0);
        for row in rows {
            for (c, v) in row {
                m.column.push(c);
                m.value.push(v);
            }
            m.start.push(m.column.len());
        }
        m
    }

    /// The diagonal (0 where not stored).
    pub fn diagonal(&self) -> Vec<f64> {
        (0..self.rows())
            .map(|i| {
                let (cols, vals) = self.row(i);
                cols.binary_search(&(i as u32)).map_or(0.0, |p| vals[p])
            })
            .collect()
    }

    /// `Aᵀ`.
    pub fn transpose(&self) -> Csr {
        let mut counts = vec![0usize; self.columns + 1];
        for &c in &self.column {
            counts[c as usize + 1] += 1;
        }
        for i in 0..self.columns {
            counts[i + 1] += counts[i];
        }
        let mut fill = counts.clone();
        let mut column = vec![0u32; self.stored()];
        let mut value = vec![0.0; self.stored()];
        for i in 0..self.rows() {
            let (cols, vals) = self.row(i);
            for (&c, &v) in cols.iter().zip(vals) {
                let p = fill[c as usize];
                column[p] = i as u32;
                value[p] = v;
                fill[c as usize] += 1;
            }
        }
        Csr {
            columns: self.rows(),
            start: counts,
            column,
            value,
        }
    }

    /// `A B` (rows in parallel, each accumulated in a dense scratch row and emitted sorted).
    pub fn product(&self, pool: &ThreadPool, b: &Csr) -> Csr {
        let row = |i: usize| {
            let (cols, vals) = self.row(i);
            cols.iter().copied().zip(vals.iter().copied())
        };
        Csr::product_of(pool, self.rows(), row, b)
    }

    /// `A B` for the `rows × b.rows()` matrix `A` whose row `i` is given by `row(i)` (column,
    /// value pairs, the columns in any order): the product of [`Csr::product`] without `A` in
    /// compressed rows (each row's values are added in the order `row` gives them). Two passes:
    /// the rows' lengths, then their values written in place, so the product's arrays are
    /// allocated once at their size (a fine level's product is hundreds of megabytes; collected
    /// row by row and then copied, it took 2.3 times its size).
    pub fn product_of<I: Iterator<Item = (u32, f64)>>(
        pool: &ThreadPool,
        rows: usize,
        row: impl Fn(usize) -> I + Sync,
        b: &Csr,
    ) -> Csr {
        let entries = |i: usize| row(i).map(|(k, a)| (k, [a]));
        Csr::grouped_product_of::<1, _>(pool, &vec![1; rows], entries, b)
    }

    /// [`Csr::product_of`] for rows of `A` in groups that share their columns (a node's rows:
    /// its free components): group `g` is `sizes[g]` consecutive rows (at most `W`) whose
    /// entries `group(g)` give a column with the group's values in it. The pattern is found once
    /// per group and each entry of `B` read once for the group; each row's values are added in
    /// the order of the entries, as [`Csr::product_of`] adds them: the same result to the last
    /// bit. (Row by row, the finest level's `A P` was 4.5 s of the 812,040-node wing's
    /// relocation.)
    pub fn grouped_product_of<const W: usize, I: Iterator<Item = (u32, [f64; W])>>(
        pool: &ThreadPool,
        sizes: &[usize],
        group: impl Fn(usize) -> I + Sync,
        b: &Csr,
    ) -> Csr {
        debug_assert!(sizes.iter().all(|&size| size <= W));
        let scratch = || Gustavson::<W>::new(b.columns);
        let patterns: Vec<usize> = pool.install(|| {
            (0..sizes.len())
                .into_par_iter()
                .map_init(scratch, |g, i| g.pattern(group(i), b))
                .collect()
        });
        let lengths: Vec<usize> = sizes
            .iter()
            .zip(&patterns)
            .flat_map(|(&size, &length)| std::iter::repeat_n(length, size))
            .collect();
        Csr::filled_in_groups(pool, b.columns, (&lengths, sizes), scratch, |g, i, c, v| {
            g.pattern(group(i), b);
            g.emit(group(i), b, sizes[i], (c, v));
        })
    }

    /// The matrix of `columns` columns whose row `i` has the entries `row(i)` (column, value,
    /// the columns ascending): the rows' lengths counted first, then every row written in
    /// place, in parallel.
    pub fn collected<I: Iterator<Item = (u32, f64)>>(
        pool: &ThreadPool,
        columns: usize,
        rows: usize,
        row: impl Fn(usize) -> I + Sync + Send,
    ) -> Csr {
        let lengths: Vec<usize> =
            pool.install(|| (0..rows).into_par_iter().map(|i| row(i).count()).collect());
        Csr::filled(
            pool,
            columns,
            &lengths,
            || (),
            |_, i, c, v| {
                for ((ci, vi), (d, h)) in c.iter_mut().zip(v.iter_mut()).zip(row(i)) {
                    (*ci, *vi) = (d, h);
                }
            },
        )
    }

    /// The matrix of `columns` columns whose rows have the given `lengths`, each row `i`
    /// written in place by `fill(scratch, i, columns, values)` in parallel (`scratch` made by
    /// `init`, per task): the arrays are allocated once, at their size.
    fn filled<S>(
        pool: &ThreadPool,
        columns: usize,
        lengths: &[usize],
        init: impl Fn() -> S + Sync + Send,
        fill: impl Fn(&mut S, usize, &mut [u32], &mut [f64]) + Sync + Send,
    ) -> Csr {
        Csr::filled_in_groups(
            pool,
            columns,
            (lengths, &vec![1; lengths.len()]),
            init,
            fill,
        )
    }

    /// [`Csr::filled`] by groups of consecutive rows (`sizes[g]` rows in group `g`): `fill`
    /// writes a whole group, its rows one after the other in the slices it is given.
    fn filled_in_groups<S>(
        pool: &ThreadPool,
        columns: usize,
        (lengths, sizes): (&[usize], &[usize]),
        init: impl Fn() -> S + Sync + Send,
        fill: impl Fn(&mut S, usize, &mut [u32], &mut [f64]) + Sync + Send,
    ) -> Csr {
        let mut start = Vec::with_capacity(lengths.len() + 1);
        start.push(0);
        for length in lengths {
            start.push(start[start.len() - 1] + length);
        }
        let stored = start[lengths.len()];
        let mut first = 0;
        let group_lengths: Vec<usize> = sizes
            .iter()
            .map(|&size| {
                first += size;
                start[first] - start[first - size]
            })
            .collect();
        let (mut column, mut value) = (vec![0u32; stored], vec![0.0; stored]);
        let group_columns = split_rows(&mut column, group_lengths.iter().copied());
        let group_values = split_rows(&mut value, group_lengths.iter().copied());
        pool.install(|| {
            group_columns
                .into_par_iter()
                .zip(group_values)
                .enumerate()
                .for_each_init(init, |s, (i, (c, v))| fill(s, i, c, v))
        });
        Csr {
            columns,
            start,
            column,
            value,
        }
    }
}

/// Dense scratch rows of Gustavson's product `A B` for a group of `W` rows of `A` that share
/// their columns: which columns the rows of `A B` have, and their values added in the order of
/// `A`'s entries.
struct Gustavson<const W: usize> {
    dense: Vec<[f64; W]>,
    seen: Vec<bool>,
    touched: Vec<u32>,
}

impl<const W: usize> Gustavson<W> {
    fn new(columns: usize) -> Self {
        Gustavson {
            dense: vec![[0.0; W]; columns],
            seen: vec![false; columns],
            touched: Vec::new(),
        }
    }

    /// Records the columns of the rows of `A B` whose rows of `A` have the entries `row`,
    /// sorted; returns how many.
    fn pattern<V>(&mut self, row: impl Iterator<Item = (u32, V)>, b: &Csr) -> usize {
        for &j in &self.touched {
            self.seen[j as usize] = false;
        }
        self.touched.clear();
        for (k, _) in row {
            for &j in b.row(k as usize).0 {
                if !std::mem::replace(&mut self.seen[j as usize], true) {
                    self.touched.push(j);
                }
            }
        }
        self.touched.sort_unstable();
        self.touched.len()
    }

    /// Writes the first `rows` rows of `A B` whose rows of `A` have the entries `row` (their
    /// pattern just recorded) into `columns` and `values`, one row after the other.
    fn emit(
        &mut self,
        row: impl Iterator<Item = (u32, [f64; W])>,
        b: &Csr,
        rows: usize,
        (columns, values): (&mut [u32], &mut [f64]),
    ) {
        for (k, a) in row {
            let (bc, bv) = b.row(k as usize);
            for (&j, &v) in bc.iter().zip(bv) {
                let dense = &mut self.dense[j as usize];
                for (d, a) in dense.iter_mut().zip(&a).take(rows) {
                    *d += a * v;
                }
            }
        }
        let length = self.touched.len();
        for (t, &j) in self.touched.iter().enumerate() {
            let dense = std::mem::replace(&mut self.dense[j as usize], [0.0; W]);
            for (s, d) in dense.iter().enumerate().take(rows) {
                (columns[s * length + t], values[s * length + t]) = (j, *d);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool() -> ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap()
    }

    /// Rows in groups that share their columns give, to the last bit, the product of the same
    /// rows one by one.
    #[test]
    fn a_grouped_product_is_the_product_of_its_rows() {
        let b = Csr::from_rows(
            4,
            (0..7)
                .map(|i| {
                    (0..4)
                        .filter(|j| (i + j) % 3 != 0)
                        .map(|j| (j, 0.3 * (i * j) as f64 + 0.1))
                        .collect()
                })
                .collect(),
        );
        let sizes = [3, 1, 2, 3];
        // Group g: its columns of A (any order) and a value per row.
        let group = |g: usize| {
            [5u32, 0, 3, 6].into_iter().take(2 + g).map(move |k| {
                let values: [f64; 3] =
                    std::array::from_fn(|s| ((g + s) as f64 * 1.7 + k as f64).sin());
                (k, values)
            })
        };
        let grouped = Csr::grouped_product_of::<3, _>(&pool(), &sizes, group, &b);
        let rows: Vec<(usize, usize)> = sizes
            .iter()
            .enumerate()
            .flat_map(|(g, &n)| (0..n).map(move |s| (g, s)))
            .collect();
        let row = |i: usize| {
            let (g, s) = rows[i];
            group(g).map(move |(k, a)| (k, a[s]))
        };
        let single = Csr::product_of(&pool(), rows.len(), row, &b);
        assert_eq!(grouped.start, single.start);
        assert_eq!(grouped.column, single.column);
        let bits = |m: &Csr| m.value.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&grouped), bits(&single));
    }

    #[test]
    fn products_and_transposes_agree_with_dense_arithmetic() {
        let a = Csr::from_rows(
            3,
            vec![
                vec![(0, 1.0), (2, 2.0)],
                vec![(1, -1.0)],
                vec![(0, 3.0), (1, 4.0)],
            ],
        );
        let b = Csr::from_rows(
            2,
            vec![vec![(0, 1.0)], vec![(0, 2.0), (1, 1.0)], vec![(1, 5.0)]],
        );
        let c = a.product(&pool(), &b);
        // Dense: a = [[1,0,2],[0,-1,0],[3,4,0]], b = [[1,0],[2,1],[0,5]].
        assert_eq!(c.row(0), (&[0u32, 1][..], &[1.0, 10.0][..]));
        assert_eq!(c.row(1), (&[0u32, 1][..], &[-2.0, -1.0][..]));
        assert_eq!(c.row(2), (&[0u32, 1][..], &[11.0, 4.0][..]));
        let t = a.transpose();
        assert_eq!(t.row(0), (&[0u32, 2][..], &[1.0, 3.0][..]));
        let mut y = vec![0.0; 3];
        a.apply(&pool(), &[1.0, 2.0, 3.0], &mut y);
        assert_eq!(y, vec![7.0, -2.0, 11.0]);
        assert_eq!(a.diagonal(), vec![1.0, -1.0, 0.0]);
    }

    /// The single-precision product: exact on small integers at any power-of-two scale of
    /// the values or of the vector (2⁻⁶⁰⁰ and 2⁶⁰⁰ are far outside single precision's range),
    /// within single precision's rounding elsewhere, its rows summed in a fixed order.
    #[test]
    fn single_precision_products_keep_their_scale() {
        let rows: Vec<Vec<(u32, f64)>> = (0..7u32)
            .map(|i| {
                (0..7u32)
                    .map(|j| (j, f64::from((i * 3 + j * 5) % 11) - 5.0))
                    .collect()
            })
            .collect();
        let x: Vec<f64> = (0..7).map(|j| f64::from(j * 2 % 7) - 3.0).collect();
        let a = Csr::from_rows(7, rows.clone());
        let mut exact = vec![0.0; 7];
        a.apply(&pool(), &x, &mut exact);
        for (value_scale, x_scale) in [(1.0, 1.0), (2f64.powi(-600), 1.0), (1.0, 2f64.powi(600))] {
            let scaled =
                |r: &Vec<(u32, f64)>| r.iter().map(|&(j, v)| (j, v * value_scale)).collect();
            let b = Csr::from_rows(7, rows.iter().map(scaled).collect());
            let (single, scale) = b.single();
            let bx: Vec<f64> = x.iter().map(|v| v * x_scale).collect();
            let mut y = vec![0.0; 7];
            single.apply_single(&pool(), scale, &bx, &mut y);
            for (y, e) in y.iter().zip(&exact) {
                assert_eq!(*y, e * value_scale * x_scale);
            }
        }
        let rough: Vec<f64> = (0..7).map(|j| (0.3 + f64::from(j)).sin()).collect();
        let (single, scale) = a.clone().single();
        let (mut y, mut z) = (vec![0.0; 7], vec![0.0; 7]);
        single.apply_single(&pool(), scale, &rough, &mut y);
        a.apply(&pool(), &rough, &mut z);
        for (y, z) in y.iter().zip(&z) {
            assert!((y - z).abs() <= 1e-6 * 40.0, "{y} {z}");
        }
    }
}
