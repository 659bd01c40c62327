//! Cubic B-spline knot vectors of the tree levels (clamped, uniform, dyadic), their blossoms, the
//! 1D matrices built from them (Bézier extraction, two-scale relation), and tensor Bernstein
//! polynomials of any degree with products and subdivision.

/// Spline degree in every direction.
pub(crate) const DEGREE: usize = 3;

/// Functions (and Bernstein polynomials) of one direction that are non-zero on one knot span.
pub(crate) const SPAN_FUNCTIONS: usize = DEGREE + 1;

/// Number of cubic B-splines of one direction at `level`: `2^level + 3`.
pub fn function_count(level: u8) -> usize {
    (1usize << level) + DEGREE
}

/// Knot `j` of the clamped uniform knot vector of `level`: `clamp(j − 3, 0, 2^level) / 2^level`.
pub fn knot(level: u8, j: i64) -> f64 {
    let m = 1i64 << level;
    (j - DEGREE as i64).clamp(0, m) as f64 / m as f64
}

/// Knot spans (of `level`) in the support of function `i`: `lo..hi`.
pub fn support_spans(level: u8, i: usize) -> (usize, usize) {
    let m = 1i64 << level;
    let i = i as i64;
    (
        (i - DEGREE as i64).clamp(0, m) as usize,
        (i + 1).clamp(0, m) as usize,
    )
}

/// Greville abscissa of function `i` of `level`: the mean of its three inner knots.
pub fn greville(level: u8, i: usize) -> f64 {
    let i = i as i64;
    (knot(level, i + 1) + knot(level, i + 2) + knot(level, i + 3)) / 3.0
}

/// Blossom at `args` of the polynomial piece on span `span` of `level` of the spline whose
/// coefficients on the four functions `span..span + 4` are `coef` (de Boor's algorithm with one
/// argument per stage).
pub fn blossom(level: u8, span: usize, coef: [f64; 4], args: [f64; 3]) -> f64 {
    let mu = span as i64 + DEGREE as i64;
    let mut d = coef;
    for (r, &x) in args.iter().enumerate() {
        let r = r + 1;
        // d[q] holds the value of index j = mu − 3 + q; update from the top down.
        for q in (r..=DEGREE).rev() {
            let j = mu - DEGREE as i64 + q as i64;
            let (tj, tk) = (knot(level, j), knot(level, j + 4 - r as i64));
            let alpha = (x - tj) / (tk - tj);
            d[q] = (1.0 - alpha) * d[q - 1] + alpha * d[q];
        }
    }
    d[DEGREE]
}

/// Blossoms at `args` of the four cubic Bernstein polynomials of [0, 1]: entry `k` is the sum,
/// over the subsets `K` of `{0, 1, 2}` with `k` elements, of `Π_{r∈K} x_r Π_{r∉K} (1 − x_r)`.
/// Hence the blossom of `Σ b_k B_k` is `Σ b_k β_k`.
pub fn bernstein_blossom(args: [f64; 3]) -> [f64; 4] {
    let mut out = [0.0; 4];
    for subset in 0..8usize {
        let product: f64 = (0..3)
            .map(|r| {
                if subset >> r & 1 == 1 {
                    args[r]
                } else {
                    1.0 - args[r]
                }
            })
            .product();
        out[subset.count_ones() as usize] += product;
    }
    out
}

/// A 4×4 matrix of one direction, `m[row][column]`.
pub type Matrix4 = [[f64; 4]; 4];

fn unit(i: usize) -> [f64; 4] {
    std::array::from_fn(|k| if k == i { 1.0 } else { 0.0 })
}

/// Bézier extraction of span `span` of `level`: row `i` holds the Bernstein coefficients (on the
/// span) of function `span + i`.
pub fn extraction(level: u8, span: usize) -> Matrix4 {
    let (u0, u1) = (knot(level, span as i64 + 3), knot(level, span as i64 + 4));
    std::array::from_fn(|i| {
        std::array::from_fn(|b| {
            let args = std::array::from_fn(|r| if r < DEGREE - b { u0 } else { u1 });
            blossom(level, span, unit(i), args)
        })
    })
}

/// Two-scale relation on one span: row `j` holds the coefficients of function `span + j` of
/// `level` on the functions `child + q` of `level + 1` that are non-zero on `child`, one of the
/// two halves (`2·span` or `2·span + 1`) of `span`.
pub fn two_scale(level: u8, span: usize, child: usize) -> Matrix4 {
    std::array::from_fn(|j| {
        std::array::from_fn(|q| {
            let i = (child + q) as i64;
            let args = std::array::from_fn(|r| knot(level + 1, i + 1 + r as i64));
            blossom(level, span, unit(j), args)
        })
    })
}

/// Values and first derivatives of the four cubic Bernstein polynomials at `t ∈ \[0,1\]`.
pub fn bernstein3(t: f64) -> ([f64; 4], [f64; 4]) {
    let s = 1.0 - t;
    (
        [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t],
        [
            -3.0 * s * s,
            3.0 * s * s - 6.0 * t * s,
            6.0 * t * s - 3.0 * t * t,
            3.0 * t * t,
        ],
    )
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// A polynomial on \[0,1\]^d in tensor Bernstein form: `degree[k]` in direction `k`, coefficient
/// of multi-index `i` at `Σ i_k · stride_k` with direction 0 fastest.
#[derive(Clone, Debug, PartialEq)]
pub struct Bernstein<const D: usize> {
    /// Degree in each direction.
    pub degree: [usize; D],
    /// Coefficients, direction 0 fastest.
    pub coef: Vec<f64>,
}

impl<const D: usize> Bernstein<D> {
    /// The zero polynomial of the given degrees.
    pub fn zero(degree: [usize; D]) -> Self {
        let n = degree.iter().map(|p| p + 1).product();
        Bernstein {
            degree,
            coef: vec![0.0; n],
        }
    }

    fn strides(&self) -> [usize; D] {
        let mut s = [1; D];
        for k in 1..D {
            s[k] = s[k - 1] * (self.degree[k - 1] + 1);
        }
        s
    }

    fn multi_index(&self, mut flat: usize) -> [usize; D] {
        std::array::from_fn(|k| {
            let v = flat % (self.degree[k] + 1);
            flat /= self.degree[k] + 1;
            v
        })
    }

    /// Derivative in direction `k` (degree one lower there).
    pub fn derivative(&self, k: usize) -> Self {
        let mut degree = self.degree;
        degree[k] -= 1;
        let mut out = Bernstein::zero(degree);
        let stride = self.strides()[k];
        let p = self.degree[k] as f64;
        for flat in 0..out.coef.len() {
            let idx = out.multi_index(flat);
            let src: usize = idx
                .iter()
                .zip(self.strides())
                .map(|(i, s)| i * s)
                .sum::<usize>();
            out.coef[flat] = p * (self.coef[src + stride] - self.coef[src]);
        }
        out
    }

    /// The product of two polynomials (degrees add): in the basis scaled by the binomial
    /// coefficients the product is a plain convolution, and the index of a product term is the
    /// sum of the offsets of its factors in the product's layout.
    pub fn mul(&self, other: &Self) -> Self {
        let degree = std::array::from_fn(|k| self.degree[k] + other.degree[k]);
        let mut out = Bernstein::zero(degree);
        let os = out.strides();
        let layout = |b: &Self| -> (Vec<f64>, Vec<usize>) {
            // The binomials of each direction's degree, once (not per coefficient).
            let binomials: [Vec<f64>; D] = std::array::from_fn(|k| {
                (0..=b.degree[k])
                    .map(|i| binomial(b.degree[k], i))
                    .collect()
            });
            b.coef
                .iter()
                .enumerate()
                .map(|(f, &c)| {
                    let i = b.multi_index(f);
                    let scaled = (0..D).fold(c, |acc, k| acc * binomials[k][i[k]]);
                    (scaled, (0..D).map(|k| i[k] * os[k]).sum::<usize>())
                })
                .unzip()
        };
        let (a, oa) = layout(self);
        let (b, ob) = layout(other);
        for (&ca, &base) in a.iter().zip(&oa) {
            if ca == 0.0 {
                continue;
            }
            for (&cb, &offset) in b.iter().zip(&ob) {
                out.coef[base + offset] += ca * cb;
            }
        }
        let unscale: [Vec<f64>; D] = std::array::from_fn(|k| {
            (0..=degree[k])
                .map(|i| 1.0 / binomial(degree[k], i))
                .collect()
        });
        for f in 0..out.coef.len() {
            let i = out.multi_index(f);
            out.coef[f] *= (0..D).map(|k| unscale[k][i[k]]).product::<f64>();
        }
        out
    }

    /// `self + s·other` (same degrees).
    pub fn add_scaled(&mut self, s: f64, other: &Self) {
        for (a, b) in self.coef.iter_mut().zip(&other.coef) {
            *a += s * b;
        }
    }

    /// Splits at the middle of direction `k` by de Casteljau: the polynomials on the lower and
    /// upper halves, each reparameterized to \[0,1\].
    pub fn split(&self, k: usize) -> (Self, Self) {
        let (mut lo, mut hi) = (self.clone(), self.clone());
        let stride = self.strides()[k];
        let p = self.degree[k];
        for flat in 0..self.coef.len() {
            if self.multi_index(flat)[k] != 0 {
                continue;
            }
            let mut stage: Vec<f64> = (0..=p).map(|i| self.coef[flat + i * stride]).collect();
            lo.coef[flat] = stage[0];
            hi.coef[flat + p * stride] = stage[p];
            for r in 1..=p {
                for i in 0..=p - r {
                    stage[i] = 0.5 * (stage[i] + stage[i + 1]);
                }
                lo.coef[flat + r * stride] = stage[0];
                hi.coef[flat + (p - r) * stride] = stage[p - r];
            }
        }
        (lo, hi)
    }

    /// Value at `t ∈ \[0,1\]^d`.
    pub fn eval(&self, t: [f64; D]) -> f64 {
        let mut acc = 0.0;
        for (f, &c) in self.coef.iter().enumerate() {
            let i = self.multi_index(f);
            let mut w = c;
            for k in 0..D {
                let p = self.degree[k];
                w *= binomial(p, i[k])
                    * t[k].powi(i[k] as i32)
                    * (1.0 - t[k]).powi((p - i[k]) as i32);
            }
            acc += w;
        }
        acc
    }

    /// Smallest coefficient: a lower bound of the polynomial on \[0,1\]^d.
    pub fn min_coef(&self) -> f64 {
        self.coef.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// Largest coefficient: an upper bound of the polynomial on \[0,1\]^d.
    pub fn max_coef(&self) -> f64 {
        self.coef.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }

    /// The same polynomial in the Bernstein basis of degree `degree` (each at least the
    /// current one), by repeated degree elevation:
    /// `c'_i = (i/(n+1))·c_{i−1} + (1 − i/(n+1))·c_i` in the elevated direction.
    pub fn elevated(&self, degree: [usize; D]) -> Self {
        let mut p = self.clone();
        for (k, &target) in degree.iter().enumerate() {
            while p.degree[k] < target {
                p = p.elevate(k);
            }
        }
        p
    }

    /// Degree elevation by one in direction `k`.
    fn elevate(&self, k: usize) -> Self {
        let mut degree = self.degree;
        degree[k] += 1;
        let n1 = degree[k] as f64;
        let mut out = Bernstein::zero(degree);
        let stride = self.strides()[k];
        for flat in 0..out.coef.len() {
            let idx = out.multi_index(flat);
            let i = idx[k];
            let base: usize = (0..D)
                .filter(|&m| m != k)
                .map(|m| idx[m] * self.strides()[m])
                .sum();
            let below = if i > 0 {
                self.coef[base + (i - 1) * stride]
            } else {
                0.0
            };
            let here = if i < degree[k] {
                self.coef[base + i * stride]
            } else {
                0.0
            };
            let t = i as f64 / n1;
            out.coef[flat] = t * below + (1.0 - t) * here;
        }
        out
    }
}

/// Values and slopes of the four cubic Bernstein polynomials at the `n` uniform points of
/// \[0, 1\], its ends included: what the gradients of a cubic at the points of a box's uniform
/// grid are made of (the same for every box; the slopes scale with the box's sides).
pub(super) struct GridTables {
    n: usize,
    /// Per point, the four values.
    pub(super) values: Vec<[f64; 4]>,
    /// Per point, the four slopes (on \[0, 1\]).
    pub(super) slopes: Vec<[f64; 4]>,
}

impl GridTables {
    /// The tables of `n` points per direction (at least 2).
    pub(super) fn new(n: usize) -> Self {
        let n = n.max(2);
        let (values, slopes) = (0..n)
            .map(|i| bernstein3(i as f64 / (n - 1) as f64))
            .unzip();
        GridTables { n, values, slopes }
    }

    /// The number of points per direction.
    pub(super) fn points(&self) -> usize {
        self.n
    }

    /// Writes the gradients of the cubic `coef` (tensor Bernstein coefficients on a box of
    /// sides `h`, `4^d`, direction 0 fastest) at the `n^d` grid points of the box to
    /// `out[s * stride + at]`, by sum factorisation (`scratch`: two buffers it may reuse).
    pub(super) fn gradients<const D: usize>(
        &self,
        coef: &[f64],
        h: [f64; D],
        scratch: &mut [Vec<f64>; 2],
        out: &mut [[f64; D]],
        (stride, at): (usize, usize),
    ) {
        let n = self.n;
        for c in 0..D {
            let [cur, next] = scratch;
            cur.clear();
            cur.extend_from_slice(coef);
            for k in 0..D {
                let table = if k == c { &self.slopes } else { &self.values };
                // Directions before k are already on the grid (n points), k and after are not.
                let before = n.pow(k as u32);
                let after = 4usize.pow((D - k - 1) as u32);
                next.clear();
                next.resize(before * n * after, 0.0);
                for outer in 0..after {
                    for (i, row) in table.iter().enumerate() {
                        for inner in 0..before {
                            next[inner + before * (i + n * outer)] = (0..4)
                                .map(|b| row[b] * cur[inner + before * (b + 4 * outer)])
                                .sum();
                        }
                    }
                }
                std::mem::swap(cur, next);
            }
            for (s, v) in cur.iter().enumerate() {
                out[s * stride + at][c] = v / h[c];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elevation_keeps_the_polynomial() {
        let p = Bernstein::<2> {
            degree: [2, 1],
            coef: vec![1.0, -2.0, 0.5, 3.0, 0.25, -1.0],
        };
        let q = p.elevated([4, 3]);
        assert_eq!(q.degree, [4, 3]);
        for t in [[0.0, 0.0], [0.3, 0.7], [1.0, 0.2], [0.9, 1.0]] {
            assert!((p.eval(t) - q.eval(t)).abs() < 1e-14, "{t:?}");
        }
        // Elevation narrows the coefficients' range towards the polynomial's.
        assert!(q.max_coef() <= p.max_coef() && q.min_coef() >= p.min_coef());
    }

    #[test]
    fn extraction_rows_sum_to_bernstein_partition() {
        for level in 0..4u8 {
            for span in 0..1usize << level {
                let e = extraction(level, span);
                for b in 0..4 {
                    let s: f64 = e.iter().map(|row| row[b]).sum();
                    assert!((s - 1.0).abs() < 1e-14);
                }
            }
        }
        // Level 0 is the Bernstein basis itself.
        let e = extraction(0, 0);
        for (i, row) in e.iter().enumerate() {
            for (b, &v) in row.iter().enumerate() {
                assert_eq!(v, if i == b { 1.0 } else { 0.0 });
            }
        }
    }

    #[test]
    fn bernstein_blossom_at_inner_knots_inverts_the_extraction() {
        // The coefficient of function span + q in a polynomial given by Bernstein coefficients
        // on the span is the blossom at the function's inner knots (de Boor–Fix): applied to
        // the Bernstein coefficients of every function, it must give the identity.
        for level in 0..4u8 {
            for span in 0..1usize << level {
                let (u0, u1) = (knot(level, span as i64 + 3), knot(level, span as i64 + 4));
                let e = extraction(level, span);
                for q in 0..4 {
                    let i = (span + q) as i64;
                    let args =
                        std::array::from_fn(|r| (knot(level, i + 1 + r as i64) - u0) / (u1 - u0));
                    let dual = bernstein_blossom(args);
                    for (j, row) in e.iter().enumerate() {
                        let v: f64 = row.iter().zip(&dual).map(|(a, b)| a * b).sum();
                        let expected = if j == q { 1.0 } else { 0.0 };
                        assert!(
                            (v - expected).abs() < 1e-12,
                            "level {level} span {span} {j} {q}: {v}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn two_scale_of_level_zero_is_midpoint_knot_insertion() {
        // Inserting ½ once into [0,0,0,0,1,1,1,1]: c'_i = ½(c_{i−1} + c_i) for i = 1, 2, 3.
        let r = two_scale(0, 0, 0);
        let expected = [
            [1.0, 0.5, 0.0, 0.0],
            [0.0, 0.5, 0.5, 0.0],
            [0.0, 0.0, 0.5, 0.5],
            [0.0, 0.0, 0.0, 0.5],
        ];
        for j in 0..4 {
            for q in 0..4 {
                assert!((r[j][q] - expected[j][q]).abs() < 1e-15, "{r:?}");
            }
        }
    }

    #[test]
    fn split_and_product_agree_with_evaluation() {
        let mut a = Bernstein::<2>::zero([2, 3]);
        let mut b = Bernstein::<2>::zero([3, 1]);
        for (i, c) in a.coef.iter_mut().enumerate() {
            *c = (i as f64 * 0.7).sin();
        }
        for (i, c) in b.coef.iter_mut().enumerate() {
            *c = (i as f64 * 1.3).cos();
        }
        let ab = a.mul(&b);
        let (lo, hi) = ab.split(1);
        for t in [[0.1, 0.2], [0.7, 0.9], [0.5, 0.3]] {
            let v = a.eval(t) * b.eval(t);
            assert!((ab.eval(t) - v).abs() < 1e-13);
            let (half, u) = if t[1] < 0.5 {
                (&lo, 2.0 * t[1])
            } else {
                (&hi, 2.0 * t[1] - 1.0)
            };
            assert!((half.eval([t[0], u]) - v).abs() < 1e-13);
        }
        let da = a.derivative(0);
        let h = 1e-6;
        let fd = (a.eval([0.3 + h, 0.4]) - a.eval([0.3 - h, 0.4])) / (2.0 * h);
        assert!((da.eval([0.3, 0.4]) - fd).abs() < 1e-7);
    }

    #[test]
    fn grid_gradients_match_the_bernstein_derivatives() {
        let coef: Vec<f64> = (0..64).map(|i| (i as f64 * 0.37).sin()).collect();
        let p = Bernstein::<3> {
            degree: [3; 3],
            coef: coef.clone(),
        };
        let (lo, hi): ([f64; 3], [f64; 3]) = ([0.25, 0.5, 0.0], [0.5, 0.75, 0.5]);
        let n = 3;
        let mut g = vec![[0.0; 3]; 27];
        let h = std::array::from_fn(|k| hi[k] - lo[k]);
        GridTables::new(n).gradients(&coef, h, &mut [Vec::new(), Vec::new()], &mut g, (1, 0));
        for (s, gs) in g.iter().enumerate() {
            let t: [f64; 3] = std::array::from_fn(|k| (s / n.pow(k as u32) % n) as f64 / 2.0);
            for c in 0..3 {
                let expected = p.derivative(c).eval(t) / (hi[c] - lo[c]);
                assert!(
                    (gs[c] - expected).abs() < 1e-12,
                    "{s} {c}: {} {expected}",
                    gs[c]
                );
            }
        }
    }
}
