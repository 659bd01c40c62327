//! Preconditioned conjugate gradients over node vectors, and where they stop: a relative
//! residual, or the scaled max-norm of the residual that the Newton stage stops on.

use super::small_matrix::Vector;

/// How a solve went.
#[derive(Clone, Copy, Debug)]
pub struct SolveStats {
    /// CG iterations.
    pub iterations: usize,
    /// Relative residual `‖b − H y‖/‖b‖` reached.
    pub residual: f64,
    /// Whether CG met a direction of non-positive curvature (the matrix is not positive
    /// definite) and stopped there.
    pub negative_curvature: bool,
    /// The residual's scaled max-norm reached, where [`Stop::scales`] were given (else +∞).
    pub scaled: f64,
}

impl Default for SolveStats {
    /// No iteration yet: the relative residual 1, the scaled one not known (+∞).
    fn default() -> Self {
        SolveStats {
            iterations: 0,
            residual: 1.0,
            negative_curvature: false,
            scaled: f64::INFINITY,
        }
    }
}

/// Where CG stops, besides its iteration limit: at a relative residual, or at a scaled
/// max-norm of the residual, whichever comes first.
#[derive(Clone, Copy, Debug)]
pub struct Stop<'a> {
    /// The relative residual `‖b − H y‖/‖b‖` to reach.
    pub relative: f64,
    /// Per node a scale `s_v` (empty: no scaled target).
    pub scales: &'a [f64],
    /// The max-norm `max |r_vk| s_v` of the residual to reach, where `scales` are given: the
    /// quantity the Newton stage stops on, for the gradient that a step's solve leaves (the
    /// residual) is what the step's state will have to first order. (Plain fields, not an
    /// option: an option's absent value was read, speculatively, by the optimised code, and
    /// valgrind flagged the logarithm of the projection below.)
    pub scaled: f64,
}

impl Stop<'_> {
    /// At the relative residual `relative` only.
    pub fn relative(relative: f64) -> Self {
        Stop {
            relative,
            scales: &[],
            scaled: 0.0,
        }
    }

    /// The scaled max-norm of `r`, a residual over the free coordinates (+∞ where not asked
    /// for).
    fn scaled_norm<const D: usize>(&self, r: &[Vector<D>]) -> f64 {
        match self.scales.is_empty() {
            true => f64::INFINITY,
            false => scaled_max_norm(self.scales, None, r),
        }
    }

    /// Whether `stats` meet this.
    pub fn met(&self, stats: &SolveStats) -> bool {
        stats.residual <= self.relative || (!self.scales.is_empty() && stats.scaled <= self.scaled)
    }

    /// The iterations to meet this at the rate of `stats` (from `scaled_start`, the scaled norm
    /// of the right-hand side); +∞ before the residual falls.
    fn projected(&self, stats: &SolveStats, scaled_start: f64) -> f64 {
        let at_rate = |reached: f64, target: f64| match reached < 1.0 {
            true => stats.iterations as f64 * target.ln() / reached.ln(),
            false => f64::INFINITY,
        };
        let relative = at_rate(stats.residual, self.relative);
        match self.scales.is_empty() {
            true => relative,
            false => relative.min(at_rate(
                stats.scaled / scaled_start,
                self.scaled / scaled_start,
            )),
        }
    }
}

fn dot<const D: usize>(a: &[Vector<D>], b: &[Vector<D>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (0..D).map(|k| x[k] * y[k]).sum::<f64>())
        .sum()
}

fn norm<const D: usize>(a: &[Vector<D>]) -> f64 {
    dot(a, a).sqrt()
}

/// `max |x_vk|·scales[v]` over the components `k` that `free[v]`'s bits select (all where
/// `free` is `None`).
pub(super) fn scaled_max_norm<const D: usize>(
    scales: &[f64],
    free: Option<&[u8]>,
    x: &[Vector<D>],
) -> f64 {
    let mut norm = 0.0f64;
    for (v, (xv, &scale)) in x.iter().zip(scales).enumerate() {
        for (k, xk) in xv.iter().enumerate() {
            if free.is_none_or(|free| free[v] & (1 << k) != 0) {
                norm = norm.max(xk.abs() * scale);
            }
        }
    }
    norm
}

/// Preconditioned conjugate gradients from 0 until `stop`; stops at negative curvature
/// (returning the iterate so far), after `max_iterations`, or earlier where the rate so far
/// cannot meet `stop` within them.
pub(super) fn conjugate_gradients<const D: usize>(
    apply: &dyn Fn(&[Vector<D>], &mut [Vector<D>]),
    precondition: &dyn Fn(&[Vector<D>]) -> Vec<Vector<D>>,
    b: &[Vector<D>],
    stop: Stop<'_>,
    max_iterations: usize,
) -> (Vec<Vector<D>>, SolveStats) {
    let n = b.len();
    let b_norm = norm(b);
    let mut x = vec![[0.0; D]; n];
    let mut stats = SolveStats::default();
    if b_norm == 0.0 {
        // `x = 0` solves it exactly.
        (stats.residual, stats.scaled) = (0.0, 0.0);
        return (x, stats);
    }
    let scaled_start = stop.scaled_norm(b);
    stats.scaled = scaled_start;
    let mut r = b.to_vec();
    let mut z = precondition(&r);
    let mut p = z.clone();
    let mut rz = dot(&r, &z);
    let mut ap = vec![[0.0; D]; n];
    while stats.iterations < max_iterations && !stop.met(&stats) {
        apply(&p, &mut ap);
        let curvature = dot(&p, &ap);
        if curvature.is_nan() || curvature <= 0.0 {
            stats.negative_curvature = true;
            break;
        }
        let alpha = rz / curvature;
        for i in 0..n {
            for k in 0..D {
                x[i][k] += alpha * p[i][k];
                r[i][k] -= alpha * ap[i][k];
            }
        }
        stats.iterations += 1;
        stats.residual = norm(&r) / b_norm;
        stats.scaled = stop.scaled_norm(&r);
        if stats.iterations >= max_iterations || stop.met(&stats) {
            // Done: the next direction (one more preconditioner application) is not needed.
            break;
        }
        // At the rate so far (from the second iteration on), the iterations `stop` needs.
        let projected = stop.projected(&stats, scaled_start);
        if stats.iterations >= 2 && projected.is_finite() && projected > max_iterations as f64 {
            // `stop` is out of reach within `max_iterations`: give up early.
            break;
        }
        z = precondition(&r);
        let rz_next = dot(&r, &z);
        let beta = rz_next / rz;
        rz = rz_next;
        for i in 0..n {
            for k in 0..D {
                p[i][k] = z[i][k] + beta * p[i][k];
            }
        }
    }
    (x, stats)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// A diagonal system `diag(1..=n) y = 1` with a preconditioner that counts its applications.
    fn diagonal_solve(
        exact: bool,
        stop: Stop<'_>,
        max_iterations: usize,
    ) -> (Vec<Vector<1>>, SolveStats, usize) {
        let n = 50;
        let apply = |x: &[Vector<1>], y: &mut [Vector<1>]| {
            for (i, (y, x)) in y.iter_mut().zip(x).enumerate() {
                y[0] = (i + 1) as f64 * x[0];
            }
        };
        let calls = Cell::new(0);
        let precondition = |r: &[Vector<1>]| {
            calls.set(calls.get() + 1);
            r.iter()
                .enumerate()
                .map(|(i, r)| [if exact { r[0] / (i + 1) as f64 } else { r[0] }])
                .collect()
        };
        let b = vec![[1.0]; n];
        let (y, stats) = conjugate_gradients(&apply, &precondition, &b, stop, max_iterations);
        (y, stats, calls.get())
    }

    /// With the exact inverse as preconditioner, one iteration and one application: none after
    /// the last iteration.
    #[test]
    fn an_exact_preconditioner_is_applied_once() {
        let (y, stats, calls) = diagonal_solve(true, Stop::relative(1e-12), 10);
        assert_eq!((stats.iterations, calls), (1, 1));
        for (i, y) in y.iter().enumerate() {
            assert!((y[0] - 1.0 / (i + 1) as f64).abs() < 1e-14);
        }
    }

    /// Without preconditioning the residual falls slowly: with few iterations allowed CG gives up
    /// as soon as its rate shows the tolerance out of reach; with enough it gets there.
    #[test]
    fn conjugate_gradients_give_up_where_the_rate_cannot_reach_the_tolerance() {
        let (_, stats, _) = diagonal_solve(false, Stop::relative(1e-12), 8);
        assert!(stats.iterations < 8 && stats.residual > 1e-12, "{stats:?}");
        let (_, stats, _) = diagonal_solve(false, Stop::relative(1e-12), 1000);
        assert!(stats.residual <= 1e-12, "{stats:?}");
        assert_eq!(stats.scaled, f64::INFINITY);
    }

    /// A scaled target met before the relative one stops CG there, its residual's scaled
    /// max-norm within the target (the true residual, recomputed).
    #[test]
    fn conjugate_gradients_stop_at_a_scaled_residual() {
        let scales: Vec<f64> = (0..50).map(|i| 1.0 / (i + 1) as f64).collect();
        let target = 1e-3;
        let stop = Stop {
            relative: 1e-12,
            scales: &scales,
            scaled: target,
        };
        let (y, stats, _) = diagonal_solve(false, stop, 1000);
        let (_, relative, _) = diagonal_solve(false, Stop::relative(1e-12), 1000);
        assert!(stats.residual > 1e-12 && stats.iterations < relative.iterations);
        let residual = (0..50).map(|i| (1.0 - (i + 1) as f64 * y[i][0]).abs() * scales[i]);
        let largest = residual.fold(0.0, f64::max);
        assert!(
            largest <= target * (1.0 + 1e-9) && stats.scaled <= target,
            "{largest}"
        );
        // The give-up waits while either target is projected in reach: never sooner than for
        // the relative target alone.
        for budget in [4, 8, 16] {
            let (_, both, _) = diagonal_solve(false, stop, budget);
            let (_, alone, _) = diagonal_solve(false, Stop::relative(1e-12), budget);
            assert!(both.iterations >= alone.iterations || both.scaled <= target);
        }
    }
}
