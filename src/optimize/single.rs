//! Products in single precision whose operands stay normal numbers: the vector and the matrix
//! values are scaled by powers of two to at most 1 (exactly: only exponents change), and
//! magnitudes below `NEGLIGIBLE` are made 0. Subnormal operands take a slow path through the
//! processor: unscaled, the 812,040-node wing's last Newton step, whose conjugate-gradient
//! residuals fall to 10⁻³⁰ and below in places, took 30 s instead of 18 in the multigrid
//! smoother's products.

/// Scaled magnitudes below this (2⁻⁶⁰) are taken as 0: every product of two scaled nonzero
/// factors is then at least 2⁻¹²⁰, a normal single-precision number (the smallest is 2⁻¹²⁶).
pub(crate) const NEGLIGIBLE: f64 = 1.0 / (1u64 << 60) as f64;

/// The power of two `2^-k` with `2^k ≤ extent < 2^(k+1)`: `extent` times it is in [1, 2), and
/// a power of two makes the scaling exact both ways (the scale rule of relocation, `fe_mesh`).
/// 1 for an extent of 0 or not finite, and `k` is kept within ±1000 (extents near the ends of
/// the floating-point range).
pub(crate) fn unit_of(extent: f64) -> f64 {
    if !(extent.is_finite() && extent > 0.0) {
        return 1.0;
    }
    // floor(log2(extent)) from the exponent bits (exact, unlike log2 near powers of two);
    // subnormal extents are brought into the normal range first.
    let (x, shift) = match extent < f64::MIN_POSITIVE {
        true => (extent * 2f64.powi(64), 64),
        false => (extent, 0),
    };
    let k = ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023 - shift;
    2f64.powi(-k.clamp(-1000, 1000))
}

/// The power of two that brings `top`, a largest magnitude, to between ½ and 1 (1 where it is 0
/// or not finite; see `unit_of` for the ends of the range).
pub fn normalising(top: f64) -> f64 {
    0.5 * unit_of(top)
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
