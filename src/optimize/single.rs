//! Scaling by powers of two, and products in single precision whose operands stay normal
//! numbers. `unit_of` is the one scale rule (relocation's coordinates, the mean ratio's
//! Jacobians, the products below): only exponents change, so scaling is exact both ways. For
//! the products, the vector and the matrix values are scaled to at most 1 and magnitudes below
//! `NEGLIGIBLE` are made 0. Subnormal operands take a slow path through the processor:
//! unscaled, the 812,040-node wing's last Newton step, whose conjugate-gradient residuals fall
//! to 10⁻³⁰ and below in places, took 30 s instead of 18 in the multigrid smoother's products.

/// Scaled magnitudes below this (2⁻⁶⁰) are taken as 0: every product of two scaled nonzero
/// factors is then at least 2⁻¹²⁰, a normal single-precision number (the smallest is 2⁻¹²⁶).
pub(crate) const NEGLIGIBLE: f64 = 1.0 / (1u64 << 60) as f64;

/// The power of two `2^-k` with `2^k ≤ extent < 2^(k+1)`: `extent` times it is in [1, 2), and
/// a power of two makes the scaling exact both ways (the scale rule of relocation, `fe_mesh`,
/// and of the mean ratio's Jacobians, `metric.rs`). 1 for an extent of 0 or not finite, and `k`
/// is kept within ±1000 (extents near the ends of the floating-point range).
#[inline]
pub(crate) fn unit_of(extent: f64) -> f64 {
    if !(extent.is_finite() && extent > 0.0) {
        return 1.0;
    }
    // floor(log2(extent)) from the exponent bits (exact, unlike log2 near powers of two);
    // subnormal extents are brought into the normal range first.
    let (x, shift) = match extent < f64::MIN_POSITIVE {
        true => (extent * power_of_two(64), 64),
        false => (extent, 0),
    };
    let k = ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023 - shift;
    power_of_two(-k.clamp(-1000, 1000))
}

/// `2^e` for `|e| ≤ 1022`, from its exponent bits (the mean ratio scales every Jacobian it
/// rates by one, where `powi` is a library call).
#[inline]
fn power_of_two(e: i32) -> f64 {
    f64::from_bits(((1023 + e) as u64) << 52)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Over the whole range (subnormal extents included), at and between powers of two: the
    /// unit is the power of two `2^-k` of `floor(log2(extent)) = k`, `k` kept within ±1000, and
    /// scales the extent into [1, 2) wherever `k` is within that range.
    #[test]
    fn the_unit_is_the_power_of_two_of_the_extent() {
        for e in -1074..=1023 {
            let power = 2f64.powi(e);
            for extent in [power, 1.5 * power, power * (2.0 - f64::EPSILON)] {
                if !extent.is_finite() || extent == 0.0 {
                    continue;
                }
                let unit = unit_of(extent);
                assert_eq!(unit, 2f64.powi(-e.clamp(-1000, 1000)), "extent 2^{e}");
                if (-1000..=1000).contains(&e) {
                    assert!((1.0..2.0).contains(&(extent * unit)), "extent 2^{e}");
                }
            }
        }
        for extent in [0.0, -1.0, f64::INFINITY, f64::NAN] {
            assert_eq!(unit_of(extent), 1.0);
        }
    }
}
