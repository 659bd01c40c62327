//! The largest eigenvalue of a multigrid level's Jacobi-scaled operator `D⁻¹A`, the upper end of
//! its Chebyshev smoother's interval, by the Lanczos method on the symmetric `D^{-1/2} A D^{-1/2}`
//! (the same eigenvalues): ten products with `A` give its largest Ritz value, within a few
//! percent of the largest eigenvalue where twenty power iterations stay further below it (the
//! products are the cost: on the 812,040-node wing, 20 of the finest level's took 2.4 s).
//!
//! Sums run in a fixed order and the start vector is fixed, so the estimate does not depend on the
//! thread count.

/// Lanczos steps (products with `A`).
const STEPS: usize = 10;

/// Bisection steps on the tridiagonal matrix's largest eigenvalue (relative width `2⁻⁶⁰`).
const BISECTIONS: usize = 60;

/// `λ_max(D⁻¹A)` estimated from below by the largest Ritz value of [`STEPS`] Lanczos steps, with
/// a 10% margin; `apply(x, y)` sets `y = A x` for the symmetric `A` whose diagonal has the
/// inverses `inverse_diagonal` (0 where a diagonal value is not positive: such rows are left
/// out). NaN where a product is not finite.
pub fn largest_eigenvalue(
    n: usize,
    apply: impl Fn(&[f64], &mut [f64]),
    inverse_diagonal: &[f64],
) -> f64 {
    let scale: Vec<f64> = inverse_diagonal.iter().map(|d| d.sqrt()).collect();
    let mut v: Vec<f64> = (0..n)
        .map(|i| match scale[i] > 0.0 {
            true => 1.0 + ((i * 7919) % 13) as f64 / 13.0,
            false => 0.0,
        })
        .collect();
    let norm = dot(&v, &v).sqrt();
    if norm == 0.0 {
        return 0.0;
    }
    v.iter_mut().for_each(|x| *x /= norm);
    let (mut previous, mut scaled, mut w) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut alphas, mut betas) = (Vec::new(), Vec::new());
    let mut beta = 0.0;
    for _ in 0..STEPS {
        for ((s, &x), &c) in scaled.iter_mut().zip(&v).zip(&scale) {
            *s = c * x;
        }
        apply(&scaled, &mut w);
        w.iter_mut().zip(&scale).for_each(|(x, &c)| *x *= c);
        let alpha = dot(&w, &v);
        if !alpha.is_finite() {
            return f64::NAN; // The operator's values are not finite.
        }
        for ((x, &a), &b) in w.iter_mut().zip(&v).zip(&previous) {
            *x -= alpha * a + beta * b;
        }
        alphas.push(alpha);
        beta = dot(&w, &w).sqrt();
        if beta.is_nan() || beta <= 1e-12 * alpha.abs() {
            break; // An invariant subspace: its Ritz values are eigenvalues.
        }
        betas.push(beta);
        w.iter_mut().for_each(|x| *x /= beta);
        std::mem::swap(&mut previous, &mut v);
        std::mem::swap(&mut v, &mut w);
    }
    1.1 * tridiagonal_largest(&alphas, &betas)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The largest eigenvalue of the symmetric tridiagonal matrix with diagonal `alphas` and
/// off-diagonal `betas` (at least `alphas.len() - 1` of them; more are ignored), by bisection
/// with Sturm counts inside Gershgorin's bounds.
fn tridiagonal_largest(alphas: &[f64], betas: &[f64]) -> f64 {
    let m = alphas.len();
    let off = |i: usize| if i < m - 1 { betas[i].abs() } else { 0.0 };
    let radius = |i: usize| off(i) + if i > 0 { off(i - 1) } else { 0.0 };
    let (mut lo, mut hi) = (0..m).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), i| {
        (lo.min(alphas[i] - radius(i)), hi.max(alphas[i] + radius(i)))
    });
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        match eigenvalues_above(alphas, betas, mid) > 0 {
            true => lo = mid,
            false => hi = mid,
        }
    }
    hi
}

/// How many eigenvalues of the tridiagonal matrix exceed `x`: the negative pivots of the
/// factorisation of `T − x I` count those below it (Sturm).
fn eigenvalues_above(alphas: &[f64], betas: &[f64], x: f64) -> usize {
    let mut pivot = 1.0;
    let mut below = 0;
    for (i, &a) in alphas.iter().enumerate() {
        let coupling = if i > 0 {
            betas[i - 1] * betas[i - 1]
        } else {
            0.0
        };
        pivot = a - x - coupling / pivot;
        if pivot == 0.0 {
            pivot = -f64::EPSILON * (a.abs() + x.abs() + 1.0);
        }
        if pivot < 0.0 {
            below += 1;
        }
    }
    alphas.len() - below
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `y = A x` for the 1D Laplacian-like tridiagonal `A` with diagonal `diagonal` and −1 off
    /// the diagonal.
    fn tridiagonal(diagonal: &[f64]) -> impl Fn(&[f64], &mut [f64]) + '_ {
        move |x: &[f64], y: &mut [f64]| {
            let n = diagonal.len();
            for i in 0..n {
                let left = if i > 0 { x[i - 1] } else { 0.0 };
                let right = if i + 1 < n { x[i + 1] } else { 0.0 };
                y[i] = diagonal[i] * x[i] - left - right;
            }
        }
    }

    /// The 1D Laplacian, whose Jacobi-scaled largest eigenvalue is `1 + cos(π/(n+1))`: the
    /// bisection finds it from the tridiagonal matrix itself to round-off, and the estimate lies
    /// between 0.97 and 1 times it (before the margin), above the power method's 20 iterations;
    /// so too with an uneven diagonal.
    #[test]
    fn the_estimate_bounds_the_largest_eigenvalue_closely() {
        let n = 400;
        let exact = 1.0 + (std::f64::consts::PI / (n + 1) as f64).cos();
        let found = tridiagonal_largest(&vec![1.0; n], &vec![-0.5; n - 1]);
        assert!((found - exact).abs() < 1e-12, "{found} against {exact}");
        let diagonal = vec![2.0; n];
        let inverse = vec![0.5; n];
        let estimate = largest_eigenvalue(n, tridiagonal(&diagonal), &inverse) / 1.1;
        assert!(
            estimate <= exact * (1.0 + 1e-12) && estimate >= 0.97 * exact,
            "{estimate} against {exact}"
        );
        let mut v: Vec<f64> = (0..n)
            .map(|i| 1.0 + ((i * 7919) % 13) as f64 / 13.0)
            .collect();
        let mut w = vec![0.0; n];
        let mut power = 0.0;
        for _ in 0..20 {
            let norm = dot(&v, &v).sqrt();
            v.iter_mut().for_each(|x| *x /= norm);
            tridiagonal(&diagonal)(&v, &mut w);
            w.iter_mut().zip(&inverse).for_each(|(x, d)| *x *= d);
            power = dot(&w, &w).sqrt();
            std::mem::swap(&mut v, &mut w);
        }
        assert!(
            estimate >= power,
            "{estimate} against the power method's {power}"
        );
        // A varying diagonal: the Jacobi scaling is uneven; the exact value from the scaled
        // tridiagonal matrix by the bisection checked above.
        let diagonal: Vec<f64> = (0..n).map(|i| 2.0 + (i % 7) as f64 / 7.0).collect();
        let inverse: Vec<f64> = diagonal.iter().map(|d| 1.0 / d).collect();
        let betas: Vec<f64> = (0..n - 1)
            .map(|i| -(inverse[i] * inverse[i + 1]).sqrt())
            .collect();
        let exact = tridiagonal_largest(&vec![1.0; n], &betas);
        let estimate = largest_eigenvalue(n, tridiagonal(&diagonal), &inverse) / 1.1;
        assert!(
            estimate <= exact * (1.0 + 1e-12) && estimate >= 0.97 * exact,
            "{estimate} against {exact}"
        );
    }

    /// A diagonal operator with fewer distinct eigenvalues than steps: the Krylov space becomes
    /// invariant and the largest is found to round-off; rows without a positive diagonal are
    /// left out (all of them: 0); a non-finite product gives NaN.
    #[test]
    fn few_distinct_eigenvalues_are_found_exactly() {
        let values = [1.0, 2.0, 5.0];
        let n = 30;
        let apply = |x: &[f64], y: &mut [f64]| {
            for i in 0..n {
                y[i] = values[i % 3] * x[i];
            }
        };
        let estimate = largest_eigenvalue(n, apply, &vec![1.0; n]);
        assert!((estimate / 1.1 - 5.0).abs() < 1e-9, "{estimate}");
        // Rows without a positive diagonal are left out: here those of the eigenvalue 5.
        let inverse: Vec<f64> = (0..n).map(|i| if i % 3 == 2 { 0.0 } else { 1.0 }).collect();
        let estimate = largest_eigenvalue(n, apply, &inverse);
        assert!((estimate / 1.1 - 2.0).abs() < 1e-9, "{estimate}");
        assert_eq!(largest_eigenvalue(n, apply, &vec![0.0; n]), 0.0);
        let broken =
            |x: &[f64], y: &mut [f64]| y.iter_mut().zip(x).for_each(|(y, _)| *y = f64::NAN);
        assert!(largest_eigenvalue(n, broken, &vec![1.0; n]).is_nan());
    }
}
