//! The distance from a fitted spline map's boundary to the domain's boundary
//! (`SplineMap::boundary_distance`, reported by the fit of a domain): zero where the spline
//! reproduces the boundary, the value of a dense search at the same samples elsewhere, and on
//! the fit's report.

use igaparam::domain::{Domain, PlanarDomain, PlanarOptions};
use igaparam::spline::{FitOptions, SplineMap, SplineSpace};

use crate::common::{mapped_square, planar_boundary};

fn build(boundary: igaparam::boundary::BoundaryLoop2) -> PlanarDomain {
    PlanarDomain::build(boundary, &PlanarOptions::default(), &mut |_, _| true)
        .unwrap()
        .0
}

fn fit<B: igaparam::domain::CubeMap<2> + Sync>(
    domain: &Domain<2, B>,
) -> (SplineMap<2>, igaparam::spline::FitReport) {
    let (map, report, _) =
        SplineMap::fit_domain_with(domain, &FitOptions::default(), &mut |_, _, _| true).unwrap();
    (map, report)
}

#[test]
fn a_straight_sided_domain_is_reproduced_to_round_off() {
    // A parallelogram: the T-mesh's map is affine, and so is the cubic fit.
    let domain = build(mapped_square(|[x, y]| [3.0 * x + 0.5 * y, 0.4 * x + y], 1));
    let (map, report) = fit(&domain);
    assert!(report.boundary_distance < 1e-12, "{report:?}");
    assert_eq!(report.boundary_distance, map.boundary_distance(&domain));
}

/// The distance in frame coordinates from `x` to the nearest of `points`.
fn nearest(points: &[[f64; 2]], x: [f64; 2]) -> f64 {
    points
        .iter()
        .map(|q| (q[0] - x[0]).powi(2) + (q[1] - x[1]).powi(2))
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

#[test]
fn the_distance_is_that_of_a_dense_search_at_the_same_samples() {
    // The rotor's boundary turns by 34° within 1e-4 of a side's parameter: the spline cannot
    // follow it there.
    let domain = build(planar_boundary("rotor_bdry.xml"));
    let (map, report) = fit(&domain);
    let frame = domain.frame();
    let n = 20_000;
    let side = |s: usize, t: f64| match s {
        0 => [t, 0.0],
        1 => [1.0, t],
        2 => [t, 1.0],
        _ => [0.0, t],
    };
    let dense: Vec<[f64; 2]> = (0..4)
        .flat_map(|s| (0..=n).map(move |i| side(s, i as f64 / n as f64)))
        .map(|p| frame.to_frame(domain.boundary_point(p)))
        .collect();
    // The samples of `boundary_distance`: 9 per boundary facet of an element, ends included.
    let mut largest = 0.0f64;
    for e in 0..map.element_count() {
        let (lo, hi) = map.space().element_bounds(e);
        for k in 0..2 {
            for end in [lo[k], hi[k]].into_iter().filter(|&v| v == 0.0 || v == 1.0) {
                for i in 0..9 {
                    let mut p = [0.0; 2];
                    p[k] = end;
                    p[1 - k] = lo[1 - k] + (hi[1 - k] - lo[1 - k]) * i as f64 / 8.0;
                    largest = largest.max(nearest(&dense, frame.to_frame(map.eval(p).unwrap())));
                }
            }
        }
    }
    // The dense points are 1e-4 apart at most (in parameter; the sides are at most a few frame
    // units long): the search's distance exceeds the true one by at most ~2e-4.
    let d = report.boundary_distance;
    assert!(d > 1e-3, "{d}");
    assert!(
        d <= largest + 1e-9 && d >= largest - 2e-4,
        "projection {d:.6e}, dense search {largest:.6e}"
    );
}
