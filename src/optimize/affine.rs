//! A node's terms stored by the invariants of their Jacobians at one position `x₀`: where a
//! term is `S(x) = J + (x − x₀) gᵀ`, its determinant is affine in `x` (the matrix determinant
//! lemma: `det S = det J + (cof(J) g)·u`, `u = x − x₀`) and its squared norm quadratic
//! (`‖S‖² = ‖J‖² + 2 (J g)·u + |g|² |u|²`). An evaluation then costs a few products per term
//! instead of forming `S`, its determinant and its cofactor: the spline smoothing evaluates
//! about a thousand terms per control point several times per Newton solve, so the invariants
//! are computed once when the terms are built.
//!
//! Expanding about `x₀` (the node's position when the terms are built) rather than the origin
//! keeps `u` as small as the node's move: no cancellation for data far from the origin.
//!
//! The terms are stored by blocks of four (`LANES`), each invariant of a block in one array,
//! and a block is evaluated lane by lane into per-lane sums that are added in lane order at the
//! end: the same arithmetic whatever the thread, and straight-line code the compiler turns into
//! vector instructions (the evaluation was 45% of the planar spline fit with one term at a
//! time). Written by hand because it is this hot path; the T-mesh optimizer's terms keep the
//! one-term [`Accumulator`](super::metric) of `metric.rs`.

use super::metric::{Lift, Local, NodeTerms};
use super::small_matrix::{cofactor, det, dot, frobenius2, mul_vec, Matrix, Vector};

/// Terms per block.
const LANES: usize = 4;

/// One value per lane.
type Lane = [f64; LANES];

/// `f(l)` for every lane `l`.
#[inline(always)]
fn lanes(mut f: impl FnMut(usize) -> f64) -> Lane {
    // A plain loop: `std::array::from_fn` left its closure a function call per lane.
    let mut out = [0.0; LANES];
    for (l, v) in out.iter_mut().enumerate() {
        *v = f(l);
    }
    out
}

/// [`LANES`] terms by their invariants at `x₀`.
#[derive(Clone, Copy, Debug)]
struct Block<const D: usize> {
    /// `det J`.
    sigma: Lane,
    /// `cof(J) g`, the gradient of `det S` with respect to the node, by component.
    grad_sigma: [Lane; D],
    /// `‖J‖²`.
    n: Lane,
    /// `J g`, by component.
    jg: [Lane; D],
    /// `|g|²`.
    gg: Lane,
    /// The terms' weights.
    w: Lane,
}

impl<const D: usize> Block<D> {
    /// A block of terms of weight 0 whose Jacobian is the identity: they add nothing.
    fn empty() -> Self {
        Block {
            sigma: [1.0; LANES],
            grad_sigma: [[0.0; LANES]; D],
            n: [D as f64; LANES],
            jg: [[0.0; LANES]; D],
            gg: [0.0; LANES],
            w: [0.0; LANES],
        }
    }
}

/// The terms of one node's objective, expanded about the node's position `x₀`.
#[derive(Clone, Debug)]
pub struct AffineTerms<const D: usize> {
    origin: Vector<D>,
    blocks: Vec<Block<D>>,
    len: usize,
}

/// Per-lane sums of the objective, its gradient and its Hessian.
struct LaneSums<const D: usize> {
    value: Lane,
    gradient: [Lane; D],
    hessian: [[Lane; D]; D],
}

/// The regularised determinant's part of one block's terms: `p = h^(-2/d)` and the factors
/// `∇p = dp ∇σ`, `∇²p = d2p ∇σ ∇σᵀ`; `valid` is false where `h ≤ 0` (the sum is then
/// infinite).
struct Regularised {
    p: Lane,
    dp: Lane,
    d2p: Lane,
    valid: bool,
}

impl Regularised {
    /// For the determinants `sigma` and the regularisation `delta`: `h = ½(σ + r)`,
    /// `r = √(σ² + 4δ²)`, computed as `2δ²/(r − σ)` for `σ < 0` (no cancellation); then
    /// `h'/h = 1/r`, `h'' = 2δ²/r³`, so `dp = −m p/r` and `d2p = m(m+1) p/r² − m p h''/h`
    /// with `m = 2/d`: two divisions and a root per term.
    #[inline(always)]
    fn of<const D: usize>(sigma: &Lane, delta: f64) -> Self {
        let (m, dd2) = (2.0 / D as f64, 2.0 * delta * delta);
        let r = lanes(|l| (sigma[l] * sigma[l] + 2.0 * dd2).sqrt());
        let d = lanes(|l| match sigma[l] >= 0.0 {
            true => sigma[l] + r[l],
            false => r[l] - sigma[l],
        });
        let q = lanes(|l| 1.0 / d[l]);
        let h = lanes(|l| match sigma[l] >= 0.0 {
            true => 0.5 * d[l],
            false => dd2 * q[l],
        });
        let valid = h.iter().all(|&v| v > 0.0);
        // `1/h`: `2/(σ + r)` or `(r − σ)/(2δ²)`.
        let inv_h = lanes(|l| match sigma[l] >= 0.0 {
            true => 2.0 * q[l],
            false => d[l] / dd2,
        });
        let inv_r = lanes(|l| 1.0 / r[l]);
        let p = lanes(|l| match D {
            2 => inv_h[l],
            _ => {
                let c = inverse_cube_root(h[l]);
                c * c
            }
        });
        let dp = lanes(|l| -m * p[l] * inv_r[l]);
        let d2p = lanes(|l| {
            let d2h_over_h = dd2 * inv_r[l] * inv_r[l] * inv_r[l] * inv_h[l];
            m * p[l] * ((m + 1.0) * inv_r[l] * inv_r[l] - d2h_over_h)
        });
        Regularised { p, dp, d2p, valid }
    }
}

/// `x^(-1/3)` for `x > 0`: a bit-level first guess refined by Newton steps
/// `y ← y (4 − x y³)/3`, which need no division; other `x` by the library's root.
#[inline(always)]
fn inverse_cube_root(x: f64) -> f64 {
    if !(x > 1e-290 && x < 1e290) {
        return 1.0 / x.cbrt();
    }
    let mut y = f64::from_bits(0x553E_F0FF_289D_D796 - x.to_bits() / 3);
    for _ in 0..4 {
        y *= (4.0 - x * y * y * y) * (1.0 / 3.0);
    }
    y
}

/// `η^(power − 1)` and `η^(power − 2)` (0 for `power` 1, where it is not needed) per lane.
#[inline(always)]
fn lifts(lift: Lift, eta: &Lane) -> (Lane, Lane) {
    match lift {
        Lift::Integer(0) => ([1.0; LANES], [0.0; LANES]),
        Lift::Integer(k) => {
            // Square and multiply over the bits of k − 1.
            let (mut low, mut base, mut k) = ([1.0; LANES], *eta, k - 1);
            while k > 0 {
                if k & 1 == 1 {
                    low = lanes(|l| low[l] * base[l]);
                }
                base = lanes(|l| base[l] * base[l]);
                k >>= 1;
            }
            (lanes(|l| low[l] * eta[l]), low)
        }
        Lift::Real(e) => {
            let high = lanes(|l| eta[l].powf(e));
            (high, lanes(|l| high[l] / eta[l]))
        }
    }
}

impl<const D: usize> AffineTerms<D> {
    /// No term yet, about the node position `origin`.
    pub fn new(origin: Vector<D>, capacity: usize) -> Self {
        AffineTerms {
            origin,
            blocks: Vec::with_capacity(capacity.div_ceil(LANES)),
            len: 0,
        }
    }

    /// Adds the term of weight `w` whose Jacobian is `j` with the node at `x₀` and changes by
    /// `e_i gᵀ` with component `i` of the node.
    pub fn push(&mut self, j: &Matrix<D>, g: Vector<D>, w: f64) {
        let l = self.len % LANES;
        if l == 0 {
            self.blocks.push(Block::empty());
        }
        let b = self.blocks.last_mut().expect("a block was pushed");
        let (grad_sigma, jg) = (mul_vec(&cofactor(j), &g), mul_vec(j, &g));
        b.sigma[l] = det(j);
        b.n[l] = frobenius2(j);
        b.gg[l] = dot(&g, &g);
        b.w[l] = w;
        for k in 0..D {
            b.grad_sigma[k][l] = grad_sigma[k];
            b.jg[k][l] = jg[k];
        }
        self.len += 1;
    }

    /// The sum of the terms' weights.
    pub fn weight_sum(&self) -> f64 {
        self.blocks.iter().flat_map(|b| b.w).sum()
    }

    /// `u = x − x₀`.
    fn offset(&self, x: &Vector<D>) -> Vector<D> {
        std::array::from_fn(|k| x[k] - self.origin[k])
    }

    /// `det S` of a block's terms at `u = x − x₀`.
    #[inline(always)]
    fn dets_of(b: &Block<D>, u: &Vector<D>) -> Lane {
        lanes(|l| b.sigma[l] + (0..D).map(|k| b.grad_sigma[k][l] * u[k]).sum::<f64>())
    }

    /// `det S` and `‖S‖²` of a block's terms at `u = x − x₀` (`uu = |u|²`).
    #[inline(always)]
    fn invariants(b: &Block<D>, u: &Vector<D>, uu: f64) -> (Lane, Lane) {
        let sigma = Self::dets_of(b, u);
        let n = lanes(|l| {
            let ju = (0..D).map(|k| b.jg[k][l] * u[k]).sum::<f64>();
            b.n[l] + 2.0 * ju + b.gg[l] * uu
        });
        (sigma, n)
    }

    /// Adds a block's derivatives to `sums`: with `∇N = 2(J g + |g|² u)`, `c = ∇σ` and
    /// `∇(N p) = p ∇N + N dp c`, the gradient gains `s₁ ∇(N p)` and the Hessian
    /// `s₁ (dp (∇N cᵀ + c ∇Nᵀ) + N d2p c cᵀ + 2|g|² p I) + s₂ ∇(N p) ∇(N p)ᵀ`, where
    /// `s₁ = w power η^(power−1)/d` and `s₂ = w power (power−1) η^(power−2)/d²`.
    #[inline(always)]
    fn add_derivatives(
        b: &Block<D>,
        u: &Vector<D>,
        n: &Lane,
        reg: &Regularised,
        s: [Lane; 2],
        sums: &mut LaneSums<D>,
    ) {
        let grad_n: [Lane; D] =
            std::array::from_fn(|k| lanes(|l| 2.0 * (b.jg[k][l] + b.gg[l] * u[k])));
        let c = &b.grad_sigma;
        let grad: [Lane; D] = std::array::from_fn(|k| {
            lanes(|l| grad_n[k][l] * reg.p[l] + n[l] * reg.dp[l] * c[k][l])
        });
        for i in 0..D {
            sums.gradient[i] = lanes(|l| sums.gradient[i][l] + s[0][l] * grad[i][l]);
            // The upper triangle: the lower one is its mirror.
            for j in i..D {
                sums.hessian[i][j] = lanes(|l| {
                    let mut h = reg.dp[l] * (grad_n[i][l] * c[j][l] + c[i][l] * grad_n[j][l])
                        + n[l] * reg.d2p[l] * c[i][l] * c[j][l];
                    if i == j {
                        h += 2.0 * b.gg[l] * reg.p[l];
                    }
                    sums.hessian[i][j][l] + s[0][l] * h + s[1][l] * grad[i][l] * grad[j][l]
                });
            }
        }
    }
}

impl<const D: usize> NodeTerms<D> for AffineTerms<D> {
    fn is_empty(&self) -> bool {
        self.len == 0
    }

    fn dets(&self, x: &Vector<D>) -> impl Iterator<Item = f64> {
        // Collected block by block (a nested iterator over the lanes was a quarter of the
        // planar spline fit).
        let u = self.offset(x);
        let mut out = Vec::with_capacity(self.blocks.len() * LANES);
        for b in &self.blocks {
            out.extend(Self::dets_of(b, &u));
        }
        out.truncate(self.len);
        out.into_iter()
    }

    fn evaluate(&self, x: &Vector<D>, delta: f64, derivatives: bool, power: f64) -> Local<D> {
        let u = self.offset(x);
        let uu = dot(&u, &u);
        let (lift, inv_d) = (Lift::new(power), 1.0 / D as f64);
        let mut sums = LaneSums {
            value: [0.0; LANES],
            gradient: [[0.0; LANES]; D],
            hessian: [[[0.0; LANES]; D]; D],
        };
        for b in &self.blocks {
            let (sigma, n) = Self::invariants(b, &u, uu);
            let reg = Regularised::of::<D>(&sigma, delta);
            if !reg.valid {
                return Local {
                    value: f64::INFINITY,
                    gradient: [0.0; D],
                    hessian: [[0.0; D]; D],
                };
            }
            let eta = lanes(|l| inv_d * n[l] * reg.p[l]);
            let (high, low) = lifts(lift, &eta);
            sums.value = lanes(|l| sums.value[l] + b.w[l] * eta[l] * high[l]);
            if derivatives {
                let s1 = lanes(|l| b.w[l] * inv_d * power * high[l]);
                let s2 = lanes(|l| b.w[l] * inv_d * inv_d * power * (power - 1.0) * low[l]);
                Self::add_derivatives(b, &u, &n, &reg, [s1, s2], &mut sums);
            }
        }
        let total = |v: &Lane| v.iter().sum::<f64>();
        Local {
            value: total(&sums.value),
            gradient: std::array::from_fn(|i| total(&sums.gradient[i])),
            hessian: std::array::from_fn(|i| {
                std::array::from_fn(|j| total(&sums.hessian[i.min(j)][i.max(j)]))
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimize::metric::{evaluate, Term};

    /// The same terms by their Jacobians and by their invariants give the same objective and
    /// derivatives at points away from the expansion point, in 2D and 3D, with powers 1 and 4
    /// and with a regularisation.
    fn agree<const D: usize>(
        jacobians: &[(Matrix<D>, Vector<D>)],
        origin: Vector<D>,
        settings: &[(f64, f64)],
    ) {
        let mut affine = AffineTerms::new(origin, jacobians.len());
        let mut plain = Vec::new();
        for (i, (j, g)) in jacobians.iter().enumerate() {
            let w = 0.5 + i as f64;
            affine.push(j, *g, w);
            // `S(x) = J + (x − x₀) gᵀ = (J − x₀ gᵀ) + x gᵀ`.
            let a = std::array::from_fn(|r| std::array::from_fn(|c| j[r][c] - origin[r] * g[c]));
            plain.push(Term { a, g: *g, w });
        }
        for shift in [0.0, 0.03, -0.07] {
            let x: Vector<D> = std::array::from_fn(|k| origin[k] + shift * (k as f64 + 1.0));
            for &(delta, power) in settings {
                let (a, b) = (
                    affine.evaluate(&x, delta, true, power),
                    evaluate(&plain, &x, delta, true, power),
                );
                let close = |p: f64, q: f64| (p - q).abs() <= 1e-11 * (1.0 + q.abs());
                assert!(close(a.value, b.value), "{} {}", a.value, b.value);
                for k in 0..D {
                    assert!(close(a.gradient[k], b.gradient[k]));
                    for l in 0..D {
                        assert!(close(a.hessian[k][l], b.hessian[k][l]));
                    }
                }
                for (p, q) in affine.dets(&x).zip(plain[..].dets(&x)) {
                    assert!(close(p, q));
                }
            }
        }
    }

    #[test]
    fn invariants_reproduce_the_jacobians_objective() {
        agree::<2>(
            &[
                ([[1.1, 0.3], [-0.2, 0.8]], [0.4, -0.9]),
                ([[0.7, -0.1], [0.3, 1.2]], [-0.2, 0.5]),
            ],
            [3.0, -2.0],
            ALL,
        );
        agree::<3>(
            &[
                (
                    [[1.0, 0.2, -0.1], [0.1, 0.9, 0.3], [-0.2, 0.1, 1.1]],
                    [0.5, -1.0, 0.25],
                ),
                (
                    [[0.8, -0.2, 0.1], [0.4, 1.1, 0.3], [0.2, 0.1, 0.9]],
                    [-0.3, 0.8, 1.5],
                ),
            ],
            [10.0, -4.0, 2.5],
            ALL,
        );
    }

    /// Regularisations and powers: the mean distortion unregularised, integer and fractional
    /// powers with small and large δ.
    const ALL: &[(f64, f64)] = &[
        (0.0, 1.0),
        (1e-3, 4.0),
        (0.3, 4.0),
        (0.05, 2.5),
        (1e-2, 2.0),
    ];

    /// Several blocks of terms, the last one partly filled, one term folded at the expansion
    /// point (a positive δ keeps its distortion finite).
    #[test]
    fn blocks_of_terms_with_a_fold_agree() {
        let planar: Vec<(Matrix<2>, Vector<2>)> = (0..11)
            .map(|i| {
                let t = i as f64;
                let sign = if i == 6 { -1.0 } else { 1.0 };
                let j = [
                    [1.0 + 0.1 * t, 0.2 - 0.03 * t],
                    [0.1 * t.sin(), sign * (0.9 + 0.05 * t)],
                ];
                (j, [0.3 * t.cos(), 0.5 - 0.07 * t])
            })
            .collect();
        agree::<2>(&planar, [0.5, 0.25], &ALL[1..]);
        let solid: Vec<(Matrix<3>, Vector<3>)> = (0..9)
            .map(|i| {
                let t = i as f64;
                let sign = if i == 4 { -1.0 } else { 1.0 };
                let j = [
                    [1.0 + 0.1 * t, 0.2, -0.1 * t.cos()],
                    [0.1, sign * (0.8 + 0.05 * t), 0.3],
                    [-0.2 * t.sin(), 0.1, 1.1],
                ];
                (j, [0.5 - 0.1 * t, -1.0, 0.25 * t])
            })
            .collect();
        agree::<3>(&solid, [-1.0, 2.0, 0.5], &ALL[1..]);
    }
}
