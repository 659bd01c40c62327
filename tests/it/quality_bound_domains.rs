//! The certified lower bound of the mean ratio of every bundled domain's spline map (default
//! build and fit) against a dense evaluation: never above the smallest mean ratio on a grid of
//! 801² (planar) or 60³ (solid) points of the parameter domain, computed here independently of
//! the library; and at least 0.1 on the coastlines.

use rayon::prelude::*;

use igaparam::boundary::SolidBoundary;
use igaparam::domain::{CubeMap, Domain, DomainOptions, PlanarDomain, SolidDomain};
use igaparam::spline::{FitOptions, QualityBoundOptions, SplineMap};

use crate::common::{boundary_data, planar_boundary, PLANAR_DOMAINS};
use crate::quality_bound::mean_ratio;

/// The smallest mean ratio on the grid of `n` points per direction of \[0,1\]^d.
fn grid_min<const D: usize>(map: &SplineMap<D>, n: usize) -> f64 {
    (0..n.pow(D as u32))
        .into_par_iter()
        .map(|s| {
            let x = std::array::from_fn(|a| (s / n.pow(a as u32) % n) as f64 / (n - 1) as f64);
            mean_ratio(&map.eval_with_jacobian(x).unwrap().1)
        })
        .reduce(|| f64::INFINITY, f64::min)
}

/// The default fit of a built domain, its certified bound (asserted at most the grid's minimum)
/// and the grid's minimum.
fn bound_below_grid<const D: usize, B: CubeMap<D> + Sync>(
    name: &str,
    domain: &Domain<D, B>,
    n: usize,
) -> (f64, f64) {
    let (map, _, validity) =
        SplineMap::fit_domain_with(domain, &FitOptions::default(), &mut |_, _, _| true).unwrap();
    let bound = map.quality_bound(&QualityBoundOptions::default()).unwrap();
    let dense = grid_min(&map, n);
    println!(
        "{name}: bound {:.4e} <= grid {dense:.4e} (sampled {:.4e})",
        bound.lower_bound, bound.sampled_min
    );
    assert!(validity.certified_positive, "{name}");
    assert!(
        bound.lower_bound > 0.0 && bound.lower_bound <= dense,
        "{name}: bound {bound:?} above the grid's {dense}"
    );
    (bound.lower_bound, dense)
}

#[test]
fn the_bound_is_below_an_801_grid_on_every_planar_domain_and_above_0_1_on_coastlines() {
    for name in PLANAR_DOMAINS {
        let options = DomainOptions::default();
        let (domain, _) =
            PlanarDomain::build(planar_boundary(name), &options, &mut |_, _| true).unwrap();
        let (bound, _) = bound_below_grid(name, &domain, 801);
        if name.ends_with(".txt") {
            // Gran Canaria: 0.104 (0.095 with the bound's previous default depth 5).
            assert!(bound >= 0.1, "{name}: certified {bound}");
        }
    }
}

#[test]
fn the_bound_is_below_a_60_grid_on_every_solid() {
    // (folder or B-rep, tolerance, deepest level, seam offset): the settings of the solid tests.
    let cases = [
        ("duck3d_BRep.xml", 1e-4, 4, 1e-2),
        ("duck_faces", 1e-4, 4, 1e-2),
        ("jacksboro_faces", 1e-2, 3, 3e-2),
    ];
    for (name, tolerance, max_level, boundary_offset) in cases {
        let path = boundary_data(name);
        let boundary = match name.ends_with(".xml") {
            true => SolidBoundary::from_gismo_file(path).unwrap(),
            false => SolidBoundary::from_obj_dir(path).unwrap(),
        };
        let options = DomainOptions {
            tolerance,
            max_level,
            boundary_offset,
            ..DomainOptions::solid()
        };
        let (domain, report) = SolidDomain::build(boundary, &options, &mut |_, _| true).unwrap();
        assert_eq!(report.invalid_cells, 0, "{name}");
        bound_below_grid(name, &domain, 60);
    }
}
