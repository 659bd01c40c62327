//! A certified lower bound of a spline map's mean ratio `q_S = d·det(J)^{2/d}/‖J‖²_F`.
//!
//! The sampled minimum quality ([`ValidityReport::min_quality`]) is an upper bound of the true
//! minimum: a finer grid can only find lower values. On each element `det J` and `‖J‖²_F` are
//! polynomials in tensor Bernstein form (`det J` as for the certification, `‖J‖²_F` as the sum
//! of the squared Jacobian entries, elevated to one degree); with `m` the smallest coefficient
//! of `det J` and `M` the largest of `‖J‖²_F`, `q_S ≥ d·m^{2/d}/M` on the element when `m > 0`.
//! The bound is refined by subdividing both polynomials (de Casteljau) where it is more than
//! `gap` below the map's sampled minimum, up to a depth: the true minimum then lies between
//! the bound and the sampled minimum.
//!
//! [`ValidityReport::min_quality`]: super::ValidityReport::min_quality

use rayon::prelude::*;

use super::bernstein::Bernstein;
use super::jacobian::{jacobian_determinant, jacobian_entries};
use super::map::SplineMap;
use super::space::SplineSpace;
use crate::error::{Error, Result};

/// Options of [`SplineMap::quality_bound`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QualityBoundOptions {
    /// Largest number of subdivisions of an element where the bound is loose (each halves
    /// every direction; default 6, at most [`MAX_BOUND_DEPTH`] = 8: 4^8 pieces of an element
    /// in 2D); solids use at most [`MAX_SOLID_DEPTH`] (3: 8^3 pieces per element), which
    /// bounds the work on any map.
    pub max_depth: u32,
    /// Sample points per direction and element for the sampled minimum (default 5, from 2
    /// to 64).
    pub samples: usize,
    /// Relative gap in [0, 1) (default 0.05): a piece is not subdivided once its bound is
    /// within this fraction of the map's sampled minimum.
    pub gap: f64,
}

/// The largest `max_depth` accepted.
pub const MAX_BOUND_DEPTH: u32 = 8;

/// The depth a solid's bound is subdivided to at most, whatever `max_depth` says.
pub const MAX_SOLID_DEPTH: u32 = 3;

impl Default for QualityBoundOptions {
    fn default() -> Self {
        QualityBoundOptions {
            // Depth 6 certifies the coastlines' maps above 0.1 (Gran Canaria: 0.095 at depth
            // 5, 0.104 at 6, 11 ms).
            max_depth: 6,
            samples: 5,
            gap: 0.05,
        }
    }
}

impl QualityBoundOptions {
    /// Checks the ranges of every field.
    pub fn validate(&self) -> Result<()> {
        if self.max_depth > MAX_BOUND_DEPTH {
            return Err(Error::invalid(format!(
                "max_depth = {} must be at most {MAX_BOUND_DEPTH}",
                self.max_depth
            )));
        }
        if !(2..=64).contains(&self.samples) {
            return Err(Error::invalid(format!(
                "samples = {} must be in [2, 64]",
                self.samples
            )));
        }
        if !(self.gap.is_finite() && (0.0..1.0).contains(&self.gap)) {
            return Err(Error::invalid(format!(
                "gap = {} must be in [0, 1)",
                self.gap
            )));
        }
        Ok(())
    }
}

/// What [`SplineMap::quality_bound`] found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct QualityBound {
    /// Certified lower bound of the mean ratio `q_S = d·det(J)^(2/d)/‖J‖²` over the whole map
    /// (0 when `det J_S > 0` is not proven somewhere).
    pub lower_bound: f64,
    /// Smallest mean ratio at the samples (an upper bound of the true minimum).
    pub sampled_min: f64,
    /// The element of the smallest bound (index into the map's elements).
    pub element: usize,
    /// Lower bound per element.
    pub elements: Vec<f64>,
}

impl<const D: usize, S: SplineSpace<D>> SplineMap<D, S> {
    /// A certified lower bound of the mean ratio of the map, with the sampled minimum it is
    /// refined towards (see the module documentation). In parallel over the elements; the
    /// result does not depend on the number of threads.
    pub fn quality_bound(&self, options: &QualityBoundOptions) -> Result<QualityBound> {
        options.validate()?;
        let sampled_min = self
            .element_min_quality(options.samples)
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let target = (1.0 - options.gap) * sampled_min;
        let depth = match D {
            2 => options.max_depth,
            _ => options.max_depth.min(MAX_SOLID_DEPTH),
        };
        let elements: Vec<f64> = (0..self.element_count())
            .into_par_iter()
            .map(|e| {
                let piece = self.piece(e);
                let components: Vec<Bernstein<D>> = (0..D).map(|a| piece.component(a)).collect();
                let (det, norm) = det_and_norm(&components, piece.lo, piece.hi);
                refined_bound(&det, &norm, depth, target)
            })
            .collect();
        let (element, lower_bound) =
            elements
                .iter()
                .copied()
                .enumerate()
                .fold(
                    (0, f64::INFINITY),
                    |best, (e, b)| {
                        if b < best.1 {
                            (e, b)
                        } else {
                            best
                        }
                    },
                );
        Ok(QualityBound {
            lower_bound: lower_bound.min(sampled_min),
            sampled_min,
            element,
            elements,
        })
    }
}

/// `det J` and `‖J‖²_F` of the map of Bernstein `patches` on the box `[lo, hi]`, as
/// polynomials on \[0,1\]^d (the norm elevated to degree `2p` in every direction).
fn det_and_norm<const D: usize>(
    patches: &[Bernstein<D>],
    lo: [f64; D],
    hi: [f64; D],
) -> (Bernstein<D>, Bernstein<D>) {
    let det = jacobian_determinant(patches, lo, hi);
    let degree = patches[0].degree.map(|p| 2 * p);
    let mut norm = Bernstein::zero(degree);
    for row in jacobian_entries(patches, lo, hi) {
        for entry in row {
            norm.add_scaled(1.0, &entry.mul(&entry).elevated(degree));
        }
    }
    (det, norm)
}

/// `d·m^{2/d}/M` for the smallest coefficient `m` of `det` and the largest `M` of `norm`; 0 when
/// `m ≤ 0` (positivity not proven on the piece).
fn piece_bound<const D: usize>(det: &Bernstein<D>, norm: &Bernstein<D>) -> f64 {
    let m = det.min_coef();
    let n = norm.max_coef();
    if !(m > 0.0 && n > 0.0 && m.is_finite() && n.is_finite()) {
        return 0.0;
    }
    let power = if D == 2 { m } else { m.cbrt().powi(2) };
    D as f64 * power / n
}

/// The bound of the piece, subdivided in every direction while it is below `target` and
/// `depth` allows; the smallest over the pieces.
fn refined_bound<const D: usize>(
    det: &Bernstein<D>,
    norm: &Bernstein<D>,
    depth: u32,
    target: f64,
) -> f64 {
    let bound = piece_bound(det, norm);
    if bound >= target || depth == 0 {
        return bound;
    }
    let mut pieces = vec![(det.clone(), norm.clone())];
    for k in 0..D {
        pieces = pieces
            .into_iter()
            .flat_map(|(p, q)| {
                let ((p0, p1), (q0, q1)) = (p.split(k), q.split(k));
                [(p0, q0), (p1, q1)]
            })
            .collect();
    }
    pieces
        .iter()
        .map(|(p, q)| refined_bound(p, q, depth - 1, target))
        .fold(f64::INFINITY, f64::min)
}
