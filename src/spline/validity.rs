//! Certified validity and sampled quality of a spline map.
//!
//! On each element `det J_S` is a polynomial of degree `3d − 1` per direction (5×5 in 2D,
//! 8×8×8 in 3D): the sum over permutations of products of the derivative patches, formed by
//! Bernstein products. Its smallest Bernstein coefficient is a lower bound; when that bound is
//! not positive but the values sampled are, the polynomial is subdivided (de Casteljau) up to a
//! depth limit, the bound being the smallest over the pieces.

use rayon::prelude::*;

use super::bernstein::Bernstein;
use super::jacobian::lower_bound;
use super::map::SplineMap;
use super::piece::Piece;
use super::space::SplineSpace;
use crate::optimize::metric::mean_ratio;
use crate::optimize::small_matrix::det;

/// Number of bins of the quality histogram over [0, 1].
pub(crate) const HISTOGRAM_BINS: usize = 10;

/// Options of [`SplineMap::validity`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValidityOptions {
    /// Largest number of subdivisions of an element's Jacobian determinant polynomial when its
    /// Bernstein coefficients are inconclusive (each halves every direction; default 5, at
    /// most 12).
    pub max_depth: u32,
    /// Sample points per direction and element for the mean ratio and the sampled determinant
    /// (default 5, from 2 to 64).
    pub samples: usize,
}

impl Default for ValidityOptions {
    fn default() -> Self {
        ValidityOptions {
            max_depth: 5,
            samples: 5,
        }
    }
}

/// Validity and quality of one element.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementValidity {
    /// Whether `det J_S > 0` on the whole element is proven.
    pub certified_positive: bool,
    /// Lower bound of `det J_S` on the element (with respect to the parametric coordinates).
    pub det_lower_bound: f64,
    /// Smallest `det J_S` at the samples.
    pub sampled_min_det: f64,
    /// Smallest mean ratio at the samples.
    pub min_quality: f64,
    /// Mean of the mean ratio at the samples.
    pub mean_quality: f64,
}

/// Validity and quality of a whole map.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ValidityReport {
    /// Per element, in element order.
    pub elements: Vec<ElementValidity>,
    /// Whether `det J_S > 0` is proven on every element (Bernstein coefficients of the
    /// determinant, with subdivision; 1 in C, else 0).
    pub certified_positive: bool,
    /// Elements where positivity is not proven.
    pub uncertified: usize,
    /// Smallest lower bound of `det J_S` over the elements (Jacobian with respect to the
    /// parametric coordinates).
    pub det_lower_bound: f64,
    /// Smallest mean ratio `q_S = d·det(J)^(2/d)/‖J‖²` at the samples (0 where det ≤ 0).
    pub min_quality: f64,
    /// Mean of the element means of `q_S` at the samples (every element has as many).
    pub mean_quality: f64,
    /// Samples per quality bin `[i/10, (i+1)/10)` (the last bin includes 1).
    pub histogram: [usize; HISTOGRAM_BINS],
}

impl ValidityReport {
    /// Whether this map is the better of two: fewer uncertified elements, then a higher
    /// smallest sampled mean ratio.
    pub(crate) fn is_better_than(&self, other: &ValidityReport) -> bool {
        let rank = |v: &ValidityReport| (v.uncertified, -v.min_quality);
        rank(self).partial_cmp(&rank(other)) == Some(std::cmp::Ordering::Less)
    }
}

impl<const D: usize, S: SplineSpace<D>> SplineMap<D, S> {
    /// `det J_S` on element `e` as a Bernstein polynomial on the element mapped to \[0,1\]^d,
    /// the Jacobian taken with respect to the parametric coordinates.
    pub fn det_polynomial(&self, e: usize) -> Bernstein<D> {
        self.piece(e).det_polynomial()
    }

    /// Certified validity of element `e` and its sampled quality.
    pub fn element_validity(&self, e: usize, options: &ValidityOptions) -> ElementValidity {
        self.element_samples(e, options).0
    }

    /// [`SplineMap::element_validity`] with the histogram of its sampled mean ratios.
    fn element_samples(
        &self,
        e: usize,
        options: &ValidityOptions,
    ) -> (ElementValidity, [usize; HISTOGRAM_BINS]) {
        piece_samples(&self.piece(e), options)
    }

    /// Whether `det J > 0` is proven on element `e` for the map of this space with control
    /// points `control` (certified as [`SplineMap::validity`] does with `options`).
    pub(super) fn certified_with(
        &self,
        e: usize,
        control: &[[f64; D]],
        options: &ValidityOptions,
    ) -> bool {
        lower_bound(
            &self.piece_with(e, control).det_polynomial(),
            options.max_depth,
        ) > 0.0
    }

    /// Certified validity and sampled quality of every element (in parallel; the result does
    /// not depend on the number of threads).
    pub fn validity(&self, options: &ValidityOptions) -> ValidityReport {
        let (elements, histograms): (Vec<ElementValidity>, Vec<[usize; HISTOGRAM_BINS]>) = (0
            ..self.element_count())
            .into_par_iter()
            .map(|e| self.element_samples(e, options))
            .unzip();
        let mut histogram = [0; HISTOGRAM_BINS];
        for h in &histograms {
            for (total, count) in histogram.iter_mut().zip(h) {
                *total += count;
            }
        }
        let uncertified = elements.iter().filter(|v| !v.certified_positive).count();
        ValidityReport {
            certified_positive: uncertified == 0,
            uncertified,
            det_lower_bound: elements
                .iter()
                .map(|v| v.det_lower_bound)
                .fold(f64::INFINITY, f64::min),
            min_quality: elements
                .iter()
                .map(|v| v.min_quality)
                .fold(f64::INFINITY, f64::min),
            mean_quality: elements.iter().map(|v| v.mean_quality).sum::<f64>()
                / elements.len().max(1) as f64,
            histogram,
            elements,
        }
    }

    /// Smallest sampled mean ratio of every element: what an adaptive loop marks elements by.
    pub fn element_min_quality(&self, samples: usize) -> Vec<f64> {
        let options = ValidityOptions {
            max_depth: 0,
            samples,
        };
        (0..self.element_count())
            .into_par_iter()
            .map(|e| self.element_validity(e, &options).min_quality)
            .collect()
    }
}

/// [`SplineMap::element_validity`] of one piece, with the histogram of its sampled mean ratios.
fn piece_samples<const D: usize>(
    piece: &Piece<D>,
    options: &ValidityOptions,
) -> (ElementValidity, [usize; HISTOGRAM_BINS]) {
    let bound = lower_bound(&piece.det_polynomial(), options.max_depth);
    let (mut min_det, mut min_q, mut sum_q) = (f64::INFINITY, f64::INFINITY, 0.0);
    let mut histogram = [0; HISTOGRAM_BINS];
    let per = options.samples.max(2).pow(D as u32);
    for j in piece.grid_jacobians(options.samples) {
        let q = mean_ratio(&j);
        min_det = min_det.min(det(&j));
        min_q = min_q.min(q);
        sum_q += q;
        histogram[((q * HISTOGRAM_BINS as f64) as usize).min(HISTOGRAM_BINS - 1)] += 1;
    }
    let element = ElementValidity {
        certified_positive: bound > 0.0,
        det_lower_bound: bound,
        sampled_min_det: min_det,
        min_quality: min_q,
        mean_quality: sum_q / per as f64,
    };
    (element, histogram)
}
