//! The regularised mean-ratio distortion of a Jacobian, its derivatives with respect to one node,
//! and the per-node choice of the regularisation parameter δ.
//!
//! For a Jacobian `S` (already composed with the inverse of the target), the mean ratio is
//! `q = d·det(S)^{2/d} / ‖S‖²_F ∈ (0, 1]` and the distortion `η = 1/q`. The regularised
//! distortion replaces `σ = det S` by `h(σ) = ½(σ + √(σ² + 4δ²))`, which stays positive, so the
//! objective is finite on tangled meshes and untangling and smoothing are one minimisation.

use super::single::{largest, unit_of};
use super::small_matrix::{cofactor, det, dot, frobenius2, mul_vec, Matrix, Vector};

/// `ε` of the δ rule: 10⁶ machine epsilons, for Jacobians normalised by their targets.
pub const DELTA_EPSILON: f64 = 1e6 * f64::EPSILON;

/// Mean ratio `d·det(S)^{2/d}/‖S‖²` of a Jacobian; 0 when `det S ≤ 0`. Computed on `S` scaled
/// by the power of two that brings its largest entry into [1, 2) (`unit_of`; exactly: the
/// ratio is invariant), so that `det S` neither under- nor overflows for Jacobians of any size.
pub fn mean_ratio<const D: usize>(s: &Matrix<D>) -> f64 {
    let unit = unit_of(largest(s.iter().flatten().copied()));
    let s: Matrix<D> = s.map(|row| row.map(|v| v * unit));
    let sigma = det(&s);
    let n = frobenius2(&s);
    if sigma <= 0.0 || n == 0.0 || !sigma.is_finite() {
        return 0.0;
    }
    let power = match D {
        2 => sigma,
        _ => {
            let c = super::small_matrix::cube_root(sigma);
            c * c
        }
    };
    D as f64 * power / n
}

/// `h(σ) = ½(σ + √(σ²+4δ²))` and its first two derivatives, evaluated without cancellation.
pub(super) fn regularised_det(sigma: f64, delta: f64) -> (f64, f64, f64) {
    let r = (sigma * sigma + 4.0 * delta * delta).sqrt();
    let h = if sigma >= 0.0 {
        0.5 * (sigma + r)
    } else {
        2.0 * delta * delta / (r - sigma)
    };
    if r == 0.0 {
        return (0.0, 0.5, 0.0);
    }
    (h, h / r, 2.0 * delta * delta / (r * r * r))
}

/// `h^{-2/d}` without the general power function (the hot path of the optimizer).
pub(super) fn inverse_power<const D: usize>(h: f64) -> f64 {
    match D {
        2 => 1.0 / h,
        3 => {
            let c = super::small_matrix::cube_root(h);
            1.0 / (c * c)
        }
        _ => h.powf(-2.0 / D as f64),
    }
}

/// One term of a node's objective: the Jacobian at one point of one cell, as a function of
/// the node position `x`: `S(x) = a + x gᵀ`, weighted by `w`.
#[derive(Clone, Copy, Debug)]
pub struct Term<const D: usize> {
    /// The part of `S` that does not depend on the node.
    pub a: Matrix<D>,
    /// How `S` changes with the node: `∂S/∂x_i = e_i gᵀ`.
    pub g: Vector<D>,
    /// The weight of the term (cell weight over the number of points).
    pub w: f64,
}

impl<const D: usize> Term<D> {
    /// `S(x)`.
    pub fn jacobian(&self, x: &Vector<D>) -> Matrix<D> {
        super::small_matrix::add_outer(&self.a, x, &self.g)
    }
}

/// Value, gradient and Hessian of a node objective.
#[derive(Clone, Copy, Debug)]
pub struct Local<const D: usize> {
    /// Objective value.
    pub value: f64,
    /// Gradient with respect to the node position.
    pub gradient: Vector<D>,
    /// Hessian with respect to the node position.
    pub hessian: Matrix<D>,
}

/// The terms of one node's objective, whatever their representation: what the per-node solver
/// (`node.rs`) asks of them.
pub trait NodeTerms<const D: usize>: Sync {
    /// Whether there is no term.
    fn is_empty(&self) -> bool;
    /// `det S` of every term at the node position `x`.
    fn dets(&self, x: &Vector<D>) -> impl Iterator<Item = f64>;
    /// `Σ w η*(S(x))^power`, with its gradient and Hessian if `derivatives` (see [`evaluate`]).
    fn evaluate(&self, x: &Vector<D>, delta: f64, derivatives: bool, power: f64) -> Local<D>;
}

impl<const D: usize> NodeTerms<D> for [Term<D>] {
    fn is_empty(&self) -> bool {
        <[Term<D>]>::is_empty(self)
    }

    fn dets(&self, x: &Vector<D>) -> impl Iterator<Item = f64> {
        self.iter().map(move |t| det(&t.jacobian(x)))
    }

    fn evaluate(&self, x: &Vector<D>, delta: f64, derivatives: bool, power: f64) -> Local<D> {
        evaluate(self, x, delta, derivatives, power)
    }
}

/// What the sum of the terms' `w η*^power` needs besides each term's invariants: the
/// regularisation, the power and how to raise to it, and whether derivatives are wanted.
pub(super) struct Accumulator<const D: usize> {
    delta: f64,
    power: f64,
    lift: Lift,
    derivatives: bool,
    /// The sum so far.
    pub(super) out: Local<D>,
}

/// A term's Jacobian's derivatives with respect to the node: `∇N = 2 S g` (`N = ‖S‖²`),
/// `∇σ = cof(S) g` (`σ = det S`) and `|g|²` (`∇²N = 2|g|² I`, `∇²σ = 0`).
pub(super) struct TermSlopes<const D: usize> {
    pub(super) grad_n: Vector<D>,
    pub(super) grad_sigma: Vector<D>,
    pub(super) gg: f64,
}

impl<const D: usize> Accumulator<D> {
    /// An empty sum.
    pub(super) fn new(delta: f64, derivatives: bool, power: f64) -> Self {
        Accumulator {
            delta,
            power,
            lift: Lift::new(power),
            derivatives,
            out: Local {
                value: 0.0,
                gradient: [0.0; D],
                hessian: [[0.0; D]; D],
            },
        }
    }

    /// Adds the term of weight `w` whose Jacobian has determinant `sigma` and squared norm `n`
    /// (its `slopes` computed only when derivatives are wanted). Returns `false`, with the
    /// value made `+∞`, where `h(σ) ≤ 0`: the sum is then infinite and the caller stops.
    #[inline]
    pub(super) fn add(
        &mut self,
        w: f64,
        sigma: f64,
        n: f64,
        slopes: impl FnOnce() -> TermSlopes<D>,
    ) -> bool {
        let (m, inv_d, power) = (2.0 / D as f64, 1.0 / D as f64, self.power);
        let (h, dh, d2h) = regularised_det(sigma, self.delta);
        if h <= 0.0 {
            self.out.value = f64::INFINITY;
            return false;
        }
        let p = inverse_power::<D>(h);
        // With `power` ≠ 1 the term is `w η^power`: its derivatives are those of `η` times
        // `power η^(power-1)` (`lift` is `η^(power-1)`), plus `power (power-1) η^(power-2)
        // ∇η ∇ηᵀ` in the Hessian (`curvature` is `(power-1)/η` times the scale of `∇η`). The
        // mean distortion (`power` 1, the T-mesh optimizer's hot path) computes none of these.
        let (value, lift, curvature) = match power == 1.0 {
            true => (w * inv_d * n * p, 1.0, 0.0),
            false => {
                let eta = inv_d * n * p;
                let lift = self.lift.of(eta);
                (w * eta * lift, lift, (power - 1.0) * inv_d / eta)
            }
        };
        self.out.value += value;
        if !self.derivatives {
            return true;
        }
        let TermSlopes {
            grad_n,
            grad_sigma: c,
            gg,
        } = slopes();
        let dp = -m * p / h * dh;
        let d2p = m * (m + 1.0) * p / (h * h) * dh * dh - m * p / h * d2h;
        let scale = w * inv_d * power * lift;
        let grad: Vector<D> = std::array::from_fn(|i| grad_n[i] * p + n * dp * c[i]);
        for i in 0..D {
            self.out.gradient[i] += scale * grad[i];
            for j in 0..D {
                let mut hij = dp * (grad_n[i] * c[j] + c[i] * grad_n[j]) + n * d2p * c[i] * c[j];
                if i == j {
                    hij += 2.0 * gg * p;
                }
                if curvature != 0.0 {
                    hij += curvature * grad[i] * grad[j];
                }
                self.out.hessian[i][j] += scale * hij;
            }
        }
        true
    }
}

/// `Σ w η*(S(x))^power` over the terms, with value only (`derivatives = false`) or also gradient
/// and Hessian. The value is `+∞` when `δ = 0` and some `det S ≤ 0`. `power` 1 is the mean
/// distortion; a larger one weighs the worst points more (a smoothed maximum).
pub fn evaluate<const D: usize>(
    terms: &[Term<D>],
    x: &Vector<D>,
    delta: f64,
    derivatives: bool,
    power: f64,
) -> Local<D> {
    let mut sum = Accumulator::new(delta, derivatives, power);
    for t in terms {
        let s = t.jacobian(x);
        let slopes = || TermSlopes {
            grad_n: mul_vec(&s, &t.g).map(|v| 2.0 * v),
            grad_sigma: mul_vec(&cofactor(&s), &t.g),
            gg: dot(&t.g, &t.g),
        };
        if !sum.add(t.w, det(&s), frobenius2(&s), slopes) {
            break;
        }
    }
    sum.out
}

/// How `η^(power − 1)` is computed, chosen once per evaluation: by multiplications for an
/// integer power (the default 4 of the spline smoothing, where `powf` was most of the cost of a
/// term, and a per-term test of the power's kind and `powi`'s library call a fifth of it).
#[derive(Clone, Copy)]
pub(super) enum Lift {
    /// `η^k` for an integer `k` from 0 to 63.
    Integer(u32),
    /// `η^e` for any other exponent `e`.
    Real(f64),
}

impl Lift {
    /// The lift of the distortion raised to `power`.
    pub(super) fn new(power: f64) -> Self {
        match power.fract() == 0.0 && (1.0..=64.0).contains(&power) {
            true => Lift::Integer(power as u32 - 1),
            false => Lift::Real(power - 1.0),
        }
    }

    /// `eta^(power − 1)`.
    fn of(self, eta: f64) -> f64 {
        match self {
            Lift::Integer(k) => {
                // Square and multiply over the bits of k.
                let (mut result, mut base, mut k) = (1.0, eta, k);
                while k > 0 {
                    if k & 1 == 1 {
                        result *= base;
                    }
                    base *= base;
                    k >>= 1;
                }
                result
            }
            Lift::Real(e) => eta.powf(e),
        }
    }
}

/// The per-node δ: with `σ_min` and the mean `|σ|` over the node's terms,
/// `δ₀ = √(ε(ε − σ_min))` if `σ_min < ε` (else 0) and `δ = max(δ₀, 10⁻⁴·mean|σ|)`.
pub fn choose_delta<const D: usize, T: NodeTerms<D> + ?Sized>(terms: &T, x: &Vector<D>) -> f64 {
    if terms.is_empty() {
        return 0.0;
    }
    let (mut sigma_min, mut mean_abs, mut count) = (f64::INFINITY, 0.0, 0usize);
    for sigma in terms.dets(x) {
        sigma_min = sigma_min.min(sigma);
        mean_abs += sigma.abs();
        count += 1;
    }
    mean_abs /= count as f64;
    let eps = DELTA_EPSILON;
    let delta0 = if sigma_min < eps {
        (eps * (eps - sigma_min)).sqrt()
    } else {
        0.0
    };
    delta0.max(1e-4 * mean_abs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_terms() -> Vec<Term<3>> {
        vec![
            Term {
                a: [[1.0, 0.2, -0.1], [0.1, 0.9, 0.3], [-0.2, 0.1, 1.1]],
                g: [0.5, -1.0, 0.25],
                w: 0.7,
            },
            Term {
                a: [[0.3, -0.2, 0.1], [0.4, -0.5, 0.3], [0.2, 0.1, -0.4]],
                g: [-0.3, 0.8, 1.5],
                w: 1.3,
            },
        ]
    }

    #[test]
    fn mean_ratio_is_one_for_scaled_rotations() {
        let (c, s) = (0.3f64.cos(), 0.3f64.sin());
        let r = [[2.0 * c, -2.0 * s], [2.0 * s, 2.0 * c]];
        assert!((mean_ratio(&r) - 1.0).abs() < 1e-14);
        assert!(mean_ratio(&[[1.0, 0.0], [0.0, 2.0]]) < 1.0);
        assert_eq!(mean_ratio(&[[1.0, 0.0], [0.0, -2.0]]), 0.0);
        // Invariant under scaling to the ends of the range, subnormal entries included.
        let scaled = |m: [[f64; 2]; 2], e: i32| m.map(|row| row.map(|v| v * 2f64.powi(e)));
        for e in [-1000, 1000] {
            assert_eq!(mean_ratio(&scaled(r, e)), mean_ratio(&r), "2^{e}");
        }
        let diagonal = [[1.0, 0.0], [0.0, 2.0]];
        assert_eq!(mean_ratio(&scaled(diagonal, -1070)), mean_ratio(&diagonal));
        assert_eq!(mean_ratio(&[[0.0; 2]; 2]), 0.0);
    }

    #[test]
    fn gradient_and_hessian_match_finite_differences() {
        let terms = sample_terms();
        let x = [0.1, -0.2, 0.3];
        for (delta, power) in [(0.0, 1.0), (1e-3, 1.0), (0.5, 1.0), (1e-3, 3.0), (0.5, 6.5)] {
            let l = evaluate(&terms, &x, delta, true, power);
            if !l.value.is_finite() {
                continue;
            }
            let h = 1e-6;
            for i in 0..3 {
                let mut xp = x;
                let mut xm = x;
                xp[i] += h;
                xm[i] -= h;
                let (fp, fm) = (
                    evaluate(&terms, &xp, delta, true, power),
                    evaluate(&terms, &xm, delta, true, power),
                );
                let fd = (fp.value - fm.value) / (2.0 * h);
                assert!(
                    (fd - l.gradient[i]).abs() < 1e-6 * (1.0 + fd.abs()),
                    "grad {i} (power {power})"
                );
                for j in 0..3 {
                    let fdh = (fp.gradient[j] - fm.gradient[j]) / (2.0 * h);
                    assert!(
                        (fdh - l.hessian[i][j]).abs() < 1e-5 * (1.0 + fdh.abs()),
                        "hess {i}{j}"
                    );
                }
            }
        }
    }

    #[test]
    fn delta_is_positive_only_when_needed() {
        let ideal = [Term {
            a: [[1.0, 0.0], [0.0, 1.0]],
            g: [0.0, 0.0],
            w: 1.0,
        }];
        let d = choose_delta(&ideal[..], &[0.0, 0.0]);
        assert!((d - 1e-4).abs() < 1e-18);
        let tangled = [Term {
            a: [[1.0, 0.0], [0.0, -1.0]],
            g: [0.0, 0.0],
            w: 1.0,
        }];
        assert!(
            choose_delta(&tangled[..], &[0.0, 0.0])
                >= (DELTA_EPSILON * (DELTA_EPSILON + 1.0)).sqrt()
        );
    }
}
