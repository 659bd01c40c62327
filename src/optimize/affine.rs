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

use super::metric::{Accumulator, Local, NodeTerms, TermSlopes};
use super::small_matrix::{cofactor, det, dot, frobenius2, mul_vec, Matrix, Vector};

/// One term by its invariants at `x₀`.
#[derive(Clone, Copy, Debug)]
struct AffineTerm<const D: usize> {
    /// `det J`.
    sigma: f64,
    /// `cof(J) g`, the gradient of `det S` with respect to the node.
    grad_sigma: Vector<D>,
    /// `‖J‖²`.
    n: f64,
    /// `J g`.
    jg: Vector<D>,
    /// `|g|²`.
    gg: f64,
    /// The term's weight.
    w: f64,
}

/// The terms of one node's objective, expanded about the node's position `x₀`.
#[derive(Clone, Debug)]
pub struct AffineTerms<const D: usize> {
    origin: Vector<D>,
    terms: Vec<AffineTerm<D>>,
}

impl<const D: usize> AffineTerms<D> {
    /// No term yet, about the node position `origin`.
    pub fn new(origin: Vector<D>, capacity: usize) -> Self {
        AffineTerms {
            origin,
            terms: Vec::with_capacity(capacity),
        }
    }

    /// Adds the term of weight `w` whose Jacobian is `j` with the node at `x₀` and changes by
    /// `e_i gᵀ` with component `i` of the node.
    pub fn push(&mut self, j: &Matrix<D>, g: Vector<D>, w: f64) {
        self.terms.push(AffineTerm {
            sigma: det(j),
            grad_sigma: mul_vec(&cofactor(j), &g),
            n: frobenius2(j),
            jg: mul_vec(j, &g),
            gg: dot(&g, &g),
            w,
        });
    }

    /// The sum of the terms' weights.
    pub fn weight_sum(&self) -> f64 {
        self.terms.iter().map(|t| t.w).sum()
    }

    /// `u = x − x₀`.
    fn offset(&self, x: &Vector<D>) -> Vector<D> {
        std::array::from_fn(|k| x[k] - self.origin[k])
    }
}

impl<const D: usize> NodeTerms<D> for AffineTerms<D> {
    fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    fn dets(&self, x: &Vector<D>) -> impl Iterator<Item = f64> {
        let u = self.offset(x);
        self.terms
            .iter()
            .map(move |t| t.sigma + dot(&t.grad_sigma, &u))
    }

    fn evaluate(&self, x: &Vector<D>, delta: f64, derivatives: bool, power: f64) -> Local<D> {
        let u = self.offset(x);
        let uu = dot(&u, &u);
        let mut sum = Accumulator::new(delta, derivatives, power);
        for t in &self.terms {
            let ju = dot(&t.jg, &u);
            let sigma = t.sigma + dot(&t.grad_sigma, &u);
            let n = t.n + 2.0 * ju + t.gg * uu;
            let slopes = || TermSlopes {
                grad_n: std::array::from_fn(|k| 2.0 * (t.jg[k] + t.gg * u[k])),
                grad_sigma: t.grad_sigma,
                gg: t.gg,
            };
            if !sum.add(t.w, sigma, n, slopes) {
                break;
            }
        }
        sum.out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimize::metric::{evaluate, Term};

    /// The same terms by their Jacobians and by their invariants give the same objective and
    /// derivatives at points away from the expansion point, in 2D and 3D, with powers 1 and 4
    /// and with a regularisation.
    fn agree<const D: usize>(jacobians: &[(Matrix<D>, Vector<D>)], origin: Vector<D>) {
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
            for (delta, power) in [(0.0, 1.0), (1e-3, 4.0), (0.3, 4.0)] {
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
        );
    }
}
