//! Products in single precision whose operands stay normal numbers: the vector and the matrix
//! values are scaled by powers of two to at most 1 (exactly: only exponents change), and
//! magnitudes below `NEGLIGIBLE` are made 0. Subnormal operands take a slow path through the
//! processor: unscaled, the 812,040-node wing's last Newton step, whose conjugate-gradient
//! residuals fall to 10⁻³⁰ and below in places, took 30 s instead of 18 in the multigrid
//! smoother's products.

/// Scaled magnitudes below this (2⁻⁶⁰) are taken as 0: every product of two scaled nonzero
/// factors is then at least 2⁻¹²⁰, a normal single-precision number (the smallest is 2⁻¹²⁶).
pub(crate) const NEGLIGIBLE: f64 = 1.0 / (1u64 << 60) as f64;

/// The power of two that brings `top`, a largest magnitude, to between ½ and 1 (1 where it is 0
/// or not finite).
pub fn normalising(top: f64) -> f64 {
    match top > 0.0 && top.is_finite() {
        true => 2f64.powi(-(top.log2().floor() as i32) - 1),
        false => 1.0,
    }
}

/// `v` (scaled) in single precision, 0 where below `NEGLIGIBLE`.
pub fn single(v: f64) -> f32 {
    match v.abs() < NEGLIGIBLE {
        true => 0.0,
        false => v as f32,
    }
}

/// The largest magnitude of `values`.
pub fn largest(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |m, v| m.max(v.abs()))
}

/// `x` scaled to at most 1 and rounded to single precision, with the power of two it was
/// multiplied by. On one thread: rounded in parallel, the wing's relocation took 4.51–4.63 s
/// instead of 4.27–4.38 s.
pub fn rounded(x: &[f64]) -> (Vec<f32>, f64) {
    let scale = normalising(largest(x.iter().copied()));
    (x.iter().map(|&v| single(v * scale)).collect(), scale)
}
