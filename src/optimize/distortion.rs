//! The regularised mean-ratio distortion `η*(S) = ‖S‖²/(d·h(σ)^{2/d})` as a function of the whole
//! Jacobian `S` (`σ = det S`): value, gradient `∂η/∂S` (d×d) and Hessian `∂²η/∂S²` (d²×d²).
//!
//! The per-node solver needs derivatives with respect to one node only, where `det S` is affine
//! (`metric.rs`); the global objective couples the nodes of a cell, and there the second
//! derivative of the determinant enters: `∂²σ/∂S_ai∂S_bj = ε_ab ε_ij` in 2D and
//! `Σ_ck ε_abc ε_ijk S_ck` in 3D.

use super::metric::{inverse_power, regularised_det};
use super::small_matrix::{cofactor, det, frobenius2, Matrix};

/// `∂²η/∂S_ai∂S_bj`, stored as `[a][i][b][j]`.
pub type Hessian<const D: usize> = [[[[f64; D]; D]; D]; D];

/// Value, gradient and Hessian of `η*` at one Jacobian.
#[derive(Clone, Copy, Debug)]
pub struct Derivatives<const D: usize> {
    /// `η*(S)`; `+∞` where `h(σ) = 0` (δ = 0 and `det S ≤ 0`).
    pub value: f64,
    /// `∂η*/∂S`.
    pub gradient: Matrix<D>,
    /// `∂²η*/∂S²`.
    pub hessian: Hessian<D>,
}

/// `∂²det S/∂S_ai∂S_bj`.
fn det_second<const D: usize>(s: &Matrix<D>, a: usize, i: usize, b: usize, j: usize) -> f64 {
    match D {
        // ε_pq in 2D is q − p on {0, 1}.
        2 => (b as f64 - a as f64) * (j as f64 - i as f64),
        // Σ_ck ε_abc ε_ijk S_ck: non-zero only for a ≠ b and i ≠ j, with c and k the third
        // indices; ε_abc is +1 when (a, b, c) is a cyclic shift of (0, 1, 2).
        3 if a != b && i != j => {
            let (c, k) = (3 - a - b, 3 - i - j);
            let sign = |p: usize, q: usize| if (p + 1) % 3 == q { 1.0 } else { -1.0 };
            sign(a, b) * sign(i, j) * s[c][k]
        }
        3 => 0.0,
        _ => unreachable!("only d = 2 and 3 are supported"),
    }
}

/// `η*(S)` alone; `+∞` where `h(σ) = 0`.
pub fn value<const D: usize>(s: &Matrix<D>, delta: f64) -> f64 {
    let (h, _, _) = regularised_det(det(s), delta);
    if h <= 0.0 || !h.is_finite() {
        return f64::INFINITY;
    }
    frobenius2(s) * inverse_power::<D>(h) / D as f64
}

/// `η*`, `∂η*/∂S` and `∂²η*/∂S²` at `s` with regularisation `delta` (0: the plain distortion,
/// finite only where `det S > 0`).
pub fn derivatives<const D: usize>(s: &Matrix<D>, delta: f64) -> Derivatives<D> {
    let mut out = Derivatives {
        value: f64::INFINITY,
        gradient: [[0.0; D]; D],
        hessian: [[[[0.0; D]; D]; D]; D],
    };
    let sigma = det(s);
    let (h, dh, d2h) = regularised_det(sigma, delta);
    if h <= 0.0 || !h.is_finite() {
        return out;
    }
    let inv_d = 1.0 / D as f64;
    let m = 2.0 * inv_d;
    let n = frobenius2(s);
    let p = inverse_power::<D>(h);
    let dp = -m * p / h * dh;
    let d2p = m * (m + 1.0) * p / (h * h) * dh * dh - m * p / h * d2h;
    let c = cofactor(s);
    out.value = n * p / D as f64;
    for a in 0..D {
        for i in 0..D {
            out.gradient[a][i] = inv_d * (2.0 * s[a][i] * p + n * dp * c[a][i]);
        }
    }
    // The upper triangle (pairs α = (a, i) ≤ β = (b, j)), mirrored: exactly symmetric.
    for alpha in 0..D * D {
        let (a, i) = (alpha / D, alpha % D);
        for beta in alpha..D * D {
            let (b, j) = (beta / D, beta % D);
            let mut v = 2.0 * dp * (s[a][i] * c[b][j] + c[a][i] * s[b][j])
                + n * d2p * c[a][i] * c[b][j]
                + n * dp * det_second(s, a, i, b, j);
            if alpha == beta {
                v += 2.0 * p;
            }
            out.hessian[a][i][b][j] = inv_d * v;
            out.hessian[b][j][a][i] = inv_d * v;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check<const D: usize>(s: Matrix<D>, delta: f64) {
        let d = derivatives(&s, delta);
        assert!(d.value.is_finite());
        let h = 1e-6;
        for a in 0..D {
            for i in 0..D {
                let (mut sp, mut sm) = (s, s);
                sp[a][i] += h;
                sm[a][i] -= h;
                let (dp, dm) = (derivatives(&sp, delta), derivatives(&sm, delta));
                let fd = (dp.value - dm.value) / (2.0 * h);
                assert!((fd - d.gradient[a][i]).abs() < 1e-6 * (1.0 + fd.abs()));
                for b in 0..D {
                    for j in 0..D {
                        let fd = (dp.gradient[b][j] - dm.gradient[b][j]) / (2.0 * h);
                        let an = d.hessian[a][i][b][j];
                        assert!(
                            (fd - an).abs() < 1e-5 * (1.0 + fd.abs()),
                            "D={D} δ={delta} [{a}{i}][{b}{j}]: {fd} vs {an}"
                        );
                        assert_eq!(an, d.hessian[b][j][a][i], "symmetry");
                    }
                }
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for delta in [0.0, 1e-3, 0.4] {
            check::<2>([[1.1, 0.3], [-0.2, 0.8]], delta);
            check::<3>([[1.0, 0.2, -0.1], [0.1, 0.9, 0.3], [-0.2, 0.1, 1.1]], delta);
        }
        // Tangled Jacobians are finite only with δ > 0.
        check::<2>([[1.0, 0.0], [0.0, -0.5]], 0.2);
        check::<3>([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -0.3]], 0.2);
        assert!(derivatives::<2>(&[[1.0, 0.0], [0.0, -0.5]], 0.0)
            .value
            .is_infinite());
    }

    #[test]
    fn the_distortion_of_a_scaled_rotation_is_one() {
        let (c, s) = (0.7f64.cos(), 0.7f64.sin());
        let d = derivatives::<2>(&[[3.0 * c, -3.0 * s], [3.0 * s, 3.0 * c]], 0.0);
        assert!((d.value - 1.0).abs() < 1e-14);
        // A minimum: the gradient vanishes.
        assert!(d.gradient.iter().flatten().all(|g| g.abs() < 1e-14));
    }
}
