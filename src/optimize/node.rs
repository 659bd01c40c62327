//! Minimisation of one node's objective: Newton with the analytic Hessian made positive definite
//! (modified Cholesky) and a backtracking line search that never accepts an increase.

use super::metric::{choose_delta, Local, NodeTerms};
use super::small_matrix::{dot, solve_spd_modified, Vector};

/// Stopping rules of the per-node solver.
#[derive(Clone, Copy, Debug)]
pub struct NodeSolverOptions {
    /// Stop when `‖∇K‖·L` (gradient scaled by the local length) falls below this.
    pub gradient_tolerance: f64,
    /// Largest number of Newton iterations per node and sweep.
    pub max_iterations: u32,
    /// Over-relaxation factor of the move (1: none).
    pub relaxation: f64,
    /// Exponent of the distortion in the objective, `Σ w η*^power` (1: the mean distortion; a
    /// larger one weighs the worst points more).
    pub power: f64,
}

/// Minimises `Σ w η*^power` over the terms starting from `x0`, moving only the components whose
/// bit is set in `free`. `weight_sum` normalises the objective, `length` scales the gradient and
/// bounds the step. Returns the new position, or `None` when the node stays where it is.
pub fn minimise<const D: usize, T: NodeTerms<D> + ?Sized>(
    terms: &T,
    x0: Vector<D>,
    free: u8,
    weight_sum: f64,
    length: f64,
    options: &NodeSolverOptions,
) -> Option<Vector<D>> {
    if terms.is_empty() || weight_sum <= 0.0 || length <= 0.0 || !length.is_finite() {
        return None;
    }
    let active: [bool; D] = std::array::from_fn(|k| free & (1 << k) != 0);
    if !active.iter().any(|&a| a) {
        return None;
    }
    let delta = choose_delta(terms, &x0);
    let scale = 1.0 / weight_sum;
    let objective = |x: &Vector<D>, derivatives: bool| {
        let mut l = terms.evaluate(x, delta, derivatives, options.power);
        l.value *= scale;
        for (k, &a) in active.iter().enumerate() {
            l.gradient[k] = if a { l.gradient[k] * scale } else { 0.0 };
            for v in &mut l.hessian[k] {
                *v *= scale;
            }
        }
        l
    };
    let start = objective(&x0, true);
    if !start.value.is_finite() {
        return None;
    }
    let mut x = x0;
    let mut current = start;
    for _ in 0..options.max_iterations {
        if dot(&current.gradient, &current.gradient).sqrt() * length < options.gradient_tolerance {
            break;
        }
        let mut step = solve_spd_modified(&current.hessian, &current.gradient, &active).map(|v| -v);
        let step_length = dot(&step, &step).sqrt();
        if step_length > length {
            step = step.map(|v| v * length / step_length);
        }
        let slope = dot(&current.gradient, &step);
        if slope.is_nan() || slope >= 0.0 {
            break;
        }
        let Some((next, local, has_derivatives)) =
            line_search(&objective, &x, &step, current.value, slope)
        else {
            break;
        };
        if next == x {
            break;
        }
        x = next;
        current = if has_derivatives {
            local
        } else {
            objective(&x, true)
        };
    }
    if !(x != x0 && current.value < start.value) {
        return None;
    }
    let omega = options.relaxation;
    if omega > 1.0 {
        // Over-relaxation speeds up the slow global smoothing of Gauss–Seidel sweeps; it is kept
        // only when the node's objective still decreased and no point it touches inverts.
        let over: Vector<D> = std::array::from_fn(|k| x0[k] + omega * (x[k] - x0[k]));
        if keeps_signs(terms, &x, &over) && objective(&over, false).value < start.value {
            return Some(over);
        }
    }
    Some(x)
}

/// Backtracking from `x` along the descent direction `step` (`slope` the directional
/// derivative there, `value` the objective): the first of the steps 1, ½, ¼, ... (40 at most)
/// that meets Armijo's condition. The full step is tried with derivatives (it is usually taken),
/// shorter ones by value. Returns the point, its evaluation, and whether that has derivatives.
#[inline]
fn line_search<const D: usize>(
    objective: &impl Fn(&Vector<D>, bool) -> Local<D>,
    x: &Vector<D>,
    step: &Vector<D>,
    value: f64,
    slope: f64,
) -> Option<(Vector<D>, Local<D>, bool)> {
    let mut alpha = 1.0;
    for attempt in 0..40 {
        let trial: Vector<D> = std::array::from_fn(|k| x[k] + alpha * step[k]);
        let local = objective(&trial, attempt == 0);
        if local.value.is_finite() && local.value <= value + 1e-4 * alpha * slope {
            return Some((trial, local, attempt == 0));
        }
        alpha *= 0.5;
    }
    None
}

/// Whether moving the node from `x` to `over` inverts none of the points of `terms` that are
/// not inverted at `x`.
fn keeps_signs<const D: usize, T: NodeTerms<D> + ?Sized>(
    terms: &T,
    x: &Vector<D>,
    over: &Vector<D>,
) -> bool {
    terms
        .dets(x)
        .zip(terms.dets(over))
        .all(|(before, after)| before <= 0.0 || after > 0.0)
}
