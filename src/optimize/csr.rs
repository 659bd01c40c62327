//! A plain compressed-sparse-row matrix with the few operations the multigrid preconditioner
//! needs: a row-parallel product (each row sums in column order, so the result does not depend
//! on the thread count), the transpose, and the sparse product (Gustavson's row-by-row
//! algorithm). Hand-written because these are the hot loops of the preconditioner and faer's
//! sparse types add nothing to them.

use rayon::prelude::*;
use rayon::ThreadPool;

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

impl Csr {
    /// The matrix with its values rounded to single precision, for products only. Products
    /// are bound by memory traffic, 12 bytes per stored value in double precision and 8 in
    /// single (the wing's finest multigrid level holds 60 million values, and its products
    /// were 45% of the wing's relocation); the vectors and the rows' sums stay in double
    /// precision, so the product is a fixed linear map, within rounding of the values at
    /// 6·10⁻⁸.
    pub fn single(self) -> Csr<f32> {
        Csr {
            columns: self.columns,
            value: self.value.iter().map(|&v| v as f32).collect(),
            start: self.start,
            column: self.column,
        }
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
        let scratch = || Gustavson::new(b.columns);
        let lengths: Vec<usize> = pool.install(|| {
            (0..rows)
                .into_par_iter()
                .map_init(scratch, |g, i| g.pattern(row(i), b))
                .collect()
        });
        Csr::filled(pool, b.columns, &lengths, scratch, |g, i, c, v| {
            g.pattern(row(i), b);
            g.emit(row(i), b, c, v);
        })
    }

    /// The matrix of `columns` columns whose rows have the given `lengths`, each row `i`
    /// written in place by `fill(scratch, i, columns, values)` in parallel (`scratch` made by
    /// `init`, per task): the arrays are allocated once, at their size.
    pub fn filled<S>(
        pool: &ThreadPool,
        columns: usize,
        lengths: &[usize],
        init: impl Fn() -> S + Sync + Send,
        fill: impl Fn(&mut S, usize, &mut [u32], &mut [f64]) + Sync + Send,
    ) -> Csr {
        let mut start = Vec::with_capacity(lengths.len() + 1);
        start.push(0);
        for length in lengths {
            start.push(start[start.len() - 1] + length);
        }
        let stored = start[lengths.len()];
        let (mut column, mut value) = (vec![0u32; stored], vec![0.0; stored]);
        let row_columns = split_rows(&mut column, lengths.iter().copied());
        let row_values = split_rows(&mut value, lengths.iter().copied());
        pool.install(|| {
            row_columns
                .into_par_iter()
                .zip(row_values)
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

/// A dense scratch row of Gustavson's product `A B`: which columns a row of `A B` has, and its
/// values added in the order of `A`'s row.
struct Gustavson {
    dense: Vec<f64>,
    seen: Vec<bool>,
    touched: Vec<u32>,
}

impl Gustavson {
    fn new(columns: usize) -> Self {
        Gustavson {
            dense: vec![0.0; columns],
            seen: vec![false; columns],
            touched: Vec::new(),
        }
    }

    /// Records the columns of the row of `A B` whose row of `A` is `row`, sorted; returns how
    /// many.
    fn pattern(&mut self, row: impl Iterator<Item = (u32, f64)>, b: &Csr) -> usize {
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

    /// Writes the row of `A B` whose row of `A` is `row` (its pattern just recorded) into
    /// `columns` and `values`.
    fn emit(
        &mut self,
        row: impl Iterator<Item = (u32, f64)>,
        b: &Csr,
        columns: &mut [u32],
        values: &mut [f64],
    ) {
        for (k, a) in row {
            let (bc, bv) = b.row(k as usize);
            for (&j, &v) in bc.iter().zip(bv) {
                self.dense[j as usize] += a * v;
            }
        }
        for ((&j, c), v) in self.touched.iter().zip(columns).zip(values) {
            (*c, *v) = (j, std::mem::take(&mut self.dense[j as usize]));
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
}
