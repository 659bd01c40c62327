//! How far the boundary of a domain's spline map strays from the domain's boundary.
//!
//! The boundary facets of the map's elements are sampled on a regular grid (ends included), and
//! each sample is projected onto the face of the domain's boundary that the facet
//! parameterizes: Gauss–Newton on that face's parameters, starting from the sample's own, with
//! finite-difference tangents (the faces may be piecewise linear: a Floater-mapped
//! triangulation), a step kept only when it comes closer. The distance to the point reached
//! bounds the true distance to the boundary from above; it is measured in the coordinates that
//! map the domain's bounding box onto the unit box, like the domain's `boundary_offset`.

use std::time::Instant;

use rayon::prelude::*;

use super::fit_options::{FitOptions, FitProgress};
use super::map::SplineMap;
use super::space::SplineSpace;
use super::thb::ThbSpace;
use super::validity::ValidityReport;
use super::FitReport;
use crate::domain::{CubeMap, Domain, Frame};
use crate::error::Result;

/// Samples per direction of a boundary facet of an element, ends included.
const SAMPLES: [usize; 2] = [9, 5];

/// Gauss–Newton iterations of one projection.
const ITERATIONS: usize = 12;

/// Halvings of a step that does not come closer before the projection stops.
const HALVINGS: usize = 8;

/// Finite-difference step along a face parameter (the faces are parameterized over \[0,1\]).
const STEP: f64 = 1e-7;

/// A point of a facet of \[0,1\]^d: coordinate `fixed` at its end, the others free.
struct FacetPoint<const D: usize> {
    at: [f64; D],
    fixed: usize,
}

impl<const D: usize> SplineMap<D, ThbSpace<D>> {
    /// Fits the spline map of a built domain's T-mesh with [`SplineMap::fit_tmesh_with`] and
    /// reports, in [`FitReport::boundary_distance`], how far the map's boundary strays from
    /// the domain's boundary ([`SplineMap::boundary_distance`]).
    pub fn fit_domain_with<B: CubeMap<D> + Sync>(
        domain: &Domain<D, B>,
        options: &FitOptions,
        progress: &mut FitProgress,
    ) -> Result<(Self, FitReport, ValidityReport)> {
        let (map, mut report, validity) =
            Self::fit_tmesh_with(domain.mesh(), domain.positions(), options, progress)?;
        let start = Instant::now();
        report.boundary_distance = match options.pool()? {
            Some(pool) => pool.install(|| map.boundary_distance(domain)),
            None => map.boundary_distance(domain),
        };
        report.seconds += start.elapsed().as_secs_f64();
        Ok((map, report, validity))
    }
}

impl<const D: usize, S: SplineSpace<D> + Sync> SplineMap<D, S> {
    /// Largest distance from the map's boundary to the boundary of `domain` (whose T-mesh's
    /// parametric domain the map shares), sampled on every boundary facet of its elements (9
    /// points per facet in 2D, 5 × 5 in 3D) and measured in the coordinates that map the
    /// domain's bounding box onto the unit box. An upper bound of the distance at the samples:
    /// each is projected onto the boundary face it parameterizes, and a closer point on another
    /// face (past a corner) is not sought. Infinite where the boundary is not finite.
    pub fn boundary_distance<B: CubeMap<D> + Sync>(&self, domain: &Domain<D, B>) -> f64 {
        let frame = domain.frame();
        (0..self.element_count())
            .into_par_iter()
            .map(|e| {
                facet_points(self.element_bounds(e))
                    .filter_map(|p| {
                        let x = self.eval(p.at)?;
                        Some(distance(&|q| domain.boundary_point(q), &frame, x, p))
                    })
                    .fold(0.0, f64::max)
            })
            .reduce(|| 0.0, f64::max)
    }
}

/// The sample points of the facets of the element `(lo, hi)` that lie on the boundary of
/// \[0,1\]^d.
fn facet_points<const D: usize>(
    (lo, hi): ([f64; D], [f64; D]),
) -> impl Iterator<Item = FacetPoint<D>> {
    let n = SAMPLES[D - 2];
    (0..D).flat_map(move |fixed| {
        [lo[fixed], hi[fixed]]
            .into_iter()
            .filter(|&v| v == 0.0 || v == 1.0)
            .flat_map(move |end| {
                (0..n.pow(D as u32 - 1)).map(move |s| {
                    let mut free = 0;
                    let at = std::array::from_fn(|k| {
                        if k == fixed {
                            return end;
                        }
                        let i = s / n.pow(free) % n;
                        free += 1;
                        lo[k] + (hi[k] - lo[k]) * i as f64 / (n - 1) as f64
                    });
                    FacetPoint { at, fixed }
                })
            })
    })
}

/// Squared distance of two points in frame coordinates.
fn squared<const D: usize>(frame: &Frame<D>, x: [f64; D], y: [f64; D]) -> f64 {
    (0..D)
        .map(|k| ((x[k] - y[k]) / frame.extent[k]).powi(2))
        .sum()
}

/// Distance in frame coordinates from `x` to the nearest point found on the face of `boundary`
/// through `from` (see the module's documentation).
fn distance<const D: usize>(
    boundary: &impl Fn([f64; D]) -> [f64; D],
    frame: &Frame<D>,
    x: [f64; D],
    from: FacetPoint<D>,
) -> f64 {
    let free: Vec<usize> = (0..D).filter(|&k| k != from.fixed).collect();
    let mut q = from.at;
    let mut b = boundary(q);
    let mut best = squared(frame, x, b);
    for _ in 0..ITERATIONS {
        let Some(step) = gauss_newton_step(boundary, frame, x, q, b, &free) else {
            break;
        };
        let mut scale = 1.0;
        let mut moved = false;
        for _ in 0..HALVINGS {
            let mut next = q;
            for (i, &k) in free.iter().enumerate() {
                next[k] = (q[k] + scale * step[i]).clamp(0.0, 1.0);
            }
            let image = boundary(next);
            let d = squared(frame, x, image);
            if d < best {
                (q, b, best, moved) = (next, image, d, true);
                break;
            }
            scale *= 0.5;
        }
        if !moved {
            break;
        }
    }
    // A non-finite distance (a boundary or a map not defined there) must not vanish in the
    // maximum, where NaN would be dropped.
    match best.is_nan() {
        true => f64::INFINITY,
        false => best.sqrt(),
    }
}

/// The Gauss–Newton step in the free parameters of `q` (one or two) towards `x`, from the
/// finite-difference tangents of the boundary in frame coordinates; `None` where they are
/// degenerate.
fn gauss_newton_step<const D: usize>(
    boundary: &impl Fn([f64; D]) -> [f64; D],
    frame: &Frame<D>,
    x: [f64; D],
    q: [f64; D],
    b: [f64; D],
    free: &[usize],
) -> Option<[f64; 2]> {
    let tangents: Vec<[f64; D]> = free
        .iter()
        .map(|&k| {
            let h = if q[k] + STEP <= 1.0 { STEP } else { -STEP };
            let mut moved = q;
            moved[k] += h;
            let image = boundary(moved);
            std::array::from_fn(|j| (image[j] - b[j]) / (h * frame.extent[j]))
        })
        .collect();
    let residual: [f64; D] = std::array::from_fn(|j| (x[j] - b[j]) / frame.extent[j]);
    let dot = |u: &[f64; D], v: &[f64; D]| (0..D).map(|j| u[j] * v[j]).sum::<f64>();
    let g: Vec<f64> = tangents.iter().map(|t| dot(t, &residual)).collect();
    let a = |i: usize, j: usize| dot(&tangents[i], &tangents[j]);
    let step = match free.len() {
        1 => [g[0] / a(0, 0), 0.0],
        _ => {
            let det = a(0, 0) * a(1, 1) - a(0, 1) * a(0, 1);
            [
                (a(1, 1) * g[0] - a(0, 1) * g[1]) / det,
                (a(0, 0) * g[1] - a(0, 1) * g[0]) / det,
            ]
        }
    };
    step.iter().all(|s| s.is_finite()).then_some(step)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_frame() -> Frame<2> {
        Frame {
            centre: [0.5; 2],
            extent: [1.0; 2],
        }
    }

    #[test]
    fn a_point_projects_onto_a_curved_face() {
        // The side v = 0 mapped onto the parabola y = x² − 1, x = 2u − 1: the point 0.3 from
        // (0.5, −0.75) along the normal there (less than the radius of curvature, √8 / 2) is
        // nearest that point, at u = 0.75; the search starts from u = 0.5.
        let parabola = |q: [f64; 2]| [2.0 * q[0] - 1.0, (2.0 * q[0] - 1.0).powi(2) - 1.0];
        let s = 0.3 / 2f64.sqrt();
        let from = FacetPoint {
            at: [0.5, 0.0],
            fixed: 1,
        };
        let d = distance(&parabola, &unit_frame(), [0.5 + s, -0.75 - s], from);
        assert!((d - 0.3).abs() < 1e-9, "{d}");
    }

    #[test]
    fn a_boundary_that_is_not_finite_gives_an_infinite_distance() {
        let broken = |_: [f64; 2]| [f64::NAN, 0.0];
        let from = FacetPoint {
            at: [0.5, 0.0],
            fixed: 1,
        };
        assert_eq!(
            distance(&broken, &unit_frame(), [0.0, 0.0], from),
            f64::INFINITY
        );
    }
}
