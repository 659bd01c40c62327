//! Per-axis scaling of boundary geometry: the check of the factors, and the scaling of points
//! stored one after another (the control points of curves and surfaces).

use crate::error::{Error, Result};

/// Checks per-axis scale factors: each must be finite and positive (an `InvalidArgument` error
/// naming the first bad one otherwise).
pub(crate) fn check_scale_factors(factors: [f64; 3]) -> Result<()> {
    match factors.iter().find(|f| !(f.is_finite() && **f > 0.0)) {
        Some(f) => Err(Error::invalid(format!(
            "scale factors must be finite and positive, got {f} in {factors:?}"
        ))),
        None => Ok(()),
    }
}

/// Multiplies points stored one after another (`dim` coordinates each) by `factors`, axis by
/// axis, after [`check_scale_factors`]; nothing changes on an error.
pub(crate) fn scale_points(points: &mut [f64], dim: usize, factors: [f64; 3]) -> Result<()> {
    check_scale_factors(factors)?;
    for p in points.chunks_exact_mut(dim) {
        for (x, f) in p.iter_mut().zip(factors) {
            *x *= f;
        }
    }
    Ok(())
}
