//! Exact summation of doubles: the sum does not depend on the order of the terms, so a sum over
//! a mesh split among any number of parts (threads, MPI ranks) gives the same bits.
//!
//! Hand-written because it is small and sits in the hot loop of the conjugate gradients: a
//! fixed-point accumulator over the whole range of `f64` (Kulisch's long accumulator) in 32-bit
//! limbs held in `i64`, so that limbs absorb carries for 2³⁰ additions before a normalisation.

/// Bits of weight per limb.
const LIMB_BITS: u32 = 32;
/// Limbs covering the exponents of every finite double and the carries above them.
const LIMBS: usize = 70;
/// Additions between two normalisations (each adds less than 2³² in magnitude per limb).
const RENORMALISE_EVERY: u32 = 1 << 30;

/// An exact sum of finite doubles. Non-finite terms make the sum NaN.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExactSum {
    limbs: [i64; LIMBS],
    pending: u32,
    not_finite: bool,
}

impl Default for ExactSum {
    fn default() -> Self {
        ExactSum {
            limbs: [0; LIMBS],
            pending: 0,
            not_finite: false,
        }
    }
}

impl ExactSum {
    /// The exact sum of `values`.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Self {
        let mut s = ExactSum::default();
        values.into_iter().for_each(|v| s.add(v));
        s
    }

    /// Adds `x` exactly.
    pub fn add(&mut self, x: f64) {
        if !x.is_finite() {
            self.not_finite = true;
            return;
        }
        let bits = x.to_bits();
        let exponent = ((bits >> 52) & 0x7ff) as u32;
        let fraction = bits & ((1u64 << 52) - 1);
        // x = ±mantissa · 2^(shift − 1074), shift ≥ 0.
        let (mantissa, shift) = match exponent {
            0 => (fraction, 0),
            e => (fraction | (1u64 << 52), e - 1),
        };
        if mantissa == 0 {
            return;
        }
        let limb = (shift / LIMB_BITS) as usize;
        let wide = (mantissa as u128) << (shift % LIMB_BITS);
        let negative = bits >> 63 == 1;
        for k in 0..3 {
            let piece = ((wide >> (LIMB_BITS * k as u32)) & 0xffff_ffff) as i64;
            self.limbs[limb + k] += if negative { -piece } else { piece };
        }
        self.pending += 1;
        if self.pending >= RENORMALISE_EVERY {
            self.normalise();
        }
    }

    /// Adds another exact sum.
    pub fn merge(&mut self, other: &ExactSum) {
        let mut other = other.clone();
        other.normalise();
        self.normalise();
        for (a, b) in self.limbs.iter_mut().zip(other.limbs) {
            *a += b;
        }
        self.not_finite |= other.not_finite;
        self.normalise();
    }

    /// Propagates carries so that every limb but the last is in `[0, 2³²)`.
    fn normalise(&mut self) {
        let mut carry = 0i64;
        for limb in self.limbs.iter_mut().take(LIMBS - 1) {
            let v = *limb + carry;
            *limb = v & 0xffff_ffff;
            carry = v >> LIMB_BITS;
        }
        self.limbs[LIMBS - 1] += carry;
        self.pending = 0;
    }

    /// The sum rounded to a double (within one unit of its last place; a function of the exact
    /// sum alone).
    pub fn value(&self) -> f64 {
        if self.not_finite {
            return f64::NAN;
        }
        let mut s = self.clone();
        s.normalise();
        let negative = s.limbs[LIMBS - 1] < 0;
        if negative {
            s.limbs.iter_mut().for_each(|l| *l = -*l);
            s.normalise();
        }
        let Some(top) = s.limbs.iter().rposition(|&l| l != 0) else {
            return 0.0;
        };
        let low = top.saturating_sub(2);
        let mut wide = 0u128;
        for k in (low..=top).rev() {
            wide = (wide << LIMB_BITS) | s.limbs[k] as u128;
        }
        let magnitude = scale(wide as f64, (low as i32) * LIMB_BITS as i32 - 1074);
        if negative {
            -magnitude
        } else {
            magnitude
        }
    }

    /// The limbs, normalised, and the non-finite flag: the sum's exact state, to send elsewhere.
    pub fn to_words(&self) -> Vec<i64> {
        let mut s = self.clone();
        s.normalise();
        let mut words = s.limbs.to_vec();
        words.push(s.not_finite as i64);
        words
    }

    /// The sum whose state [`ExactSum::to_words`] gave; `None` when `words` is not one.
    pub fn from_words(words: &[i64]) -> Option<Self> {
        if words.len() != LIMBS + 1 {
            return None;
        }
        let mut s = ExactSum::default();
        s.limbs.copy_from_slice(&words[..LIMBS]);
        s.not_finite = words[LIMBS] != 0;
        s.normalise();
        Some(s)
    }
}

/// `x · 2^n` by exact power-of-two steps (the last one may round into the subnormals).
fn scale(mut x: f64, mut n: i32) -> f64 {
    let power = |k: i32| f64::from_bits(((k + 1023) as u64) << 52);
    while n > 1000 {
        x *= power(1000);
        n -= 1000;
    }
    while n < -1000 {
        x *= power(-1000);
        n += 1000;
    }
    x * power(n)
}

/// The dot product of `a` and `b`, summed exactly (each product rounded once).
pub fn dot(a: &[f64], b: &[f64]) -> ExactSum {
    ExactSum::of(a.iter().zip(b).map(|(x, y)| x * y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_exactly_in_any_order() {
        let values = [1e300, 1.0, -1e300, 3e-310, 2.5, -1e-5, 7e15, -7e15];
        let forward = ExactSum::of(values);
        let backward = ExactSum::of(values.iter().rev().copied());
        assert_eq!(forward.value(), backward.value());
        assert_eq!(forward.value(), 3.5 - 1e-5);
        let mut halves = ExactSum::of(values[..3].iter().copied());
        halves.merge(&ExactSum::of(values[3..].iter().copied()));
        assert_eq!(halves.value(), forward.value());
        assert_eq!(ExactSum::of([-2.0, 0.5]).value(), -1.5);
        assert_eq!(ExactSum::of([5e-324, 5e-324]).value(), 1e-323);
        assert_eq!(ExactSum::of([]).value(), 0.0);
        assert!(ExactSum::of([1.0, f64::INFINITY]).value().is_nan());
    }

    #[test]
    fn words_round_trip() {
        let s = ExactSum::of([1.0, -3e-200, 1e200]);
        assert_eq!(
            ExactSum::from_words(&s.to_words()).unwrap().value(),
            s.value()
        );
        assert!(ExactSum::from_words(&[1, 2]).is_none());
    }
}
