//! The spline maps of the four planar G+Smo comparison boundaries against G+Smo's own
//! (`tests/data/peers/gismo`, computed by its barrier and PDE methods): the certified lower bound
//! of our default checked fit's mean ratio is at least the smallest mean ratio of the best G+Smo
//! map sampled on a 200 × 200 grid of its parameter domain, and our map's boundary keeps the
//! input boundary's control points (no boundary offset) and strays from it by at most 0.3% of
//! the box.

use std::path::Path;

use igaparam::boundary::{read_gismo_surfaces, BSplineSurface, BoundaryLoop2};
use igaparam::domain::{PlanarDomain, PlanarOptions};
use igaparam::spline::{FitOptions, QualityBoundOptions, SplineMap};

fn data() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data"))
}

/// The smallest mean ratio `2 det J / ‖J‖²_F` of a planar patch on an `n × n` grid of its
/// parameter domain (0 where `det J ≤ 0`).
fn sampled_min(patch: &BSplineSurface, n: usize) -> f64 {
    let ((u0, u1), (v0, v1)) = patch.domain();
    let mut min = f64::INFINITY;
    for j in 0..n {
        for i in 0..n {
            let u = u0 + (u1 - u0) * i as f64 / (n - 1) as f64;
            let v = v0 + (v1 - v0) * j as f64 / (n - 1) as f64;
            let (_, du, dv) = patch.eval_derivs(u, v);
            let det = du[0] * dv[1] - du[1] * dv[0];
            let norm = du[0] * du[0] + du[1] * du[1] + dv[0] * dv[0] + dv[1] * dv[1];
            min = min.min(if det > 0.0 { 2.0 * det / norm } else { 0.0 });
        }
    }
    min
}

#[test]
fn certified_quality_is_at_least_that_of_gismo_maps() {
    let cases = [
        ("puzzle3_bdry.xml", &["puzzle3_barrier.xml"][..]),
        (
            "rotor_bdry.xml",
            &["rotor_barrier.xml", "rotor_barrier_refined.xml"],
        ),
        ("male_bdry.xml", &["male_barrier.xml"]),
        ("duck2d_BRep.xml", &["duck_barrier.xml", "duck_pde.xml"]),
    ];
    for (boundary, peers) in cases {
        let theirs = peers
            .iter()
            .map(|file| {
                let patches = read_gismo_surfaces(data().join("peers/gismo").join(file)).unwrap();
                assert_eq!(patches.len(), 1, "{file}");
                sampled_min(&patches[0], 200)
            })
            .fold(0.0, f64::max);
        let path = data().join("boundary").join(boundary);
        let b = BoundaryLoop2::from_gismo_file(path).unwrap();
        let (domain, _) =
            PlanarDomain::build(b, &PlanarOptions::default(), &mut |_, _| true).unwrap();
        let (map, report, validity) =
            SplineMap::fit_domain_with(&domain, &FitOptions::default(), &mut |_, _, _| true)
                .unwrap();
        let bound = map
            .quality_bound(&QualityBoundOptions::default())
            .unwrap()
            .lower_bound;
        assert!(validity.certified_positive, "{boundary}");
        assert_eq!(
            report.boundary_offset, 0.0,
            "{boundary}: the boundary moved"
        );
        // The T-mesh's boundary facets, refined to the default tolerance 1e-5, stray up to
        // 1.3e-3 – 1.6e-3 of the box from these boundaries; the splines 0.85e-3 – 2.85e-3.
        assert!(
            report.boundary_distance <= 3e-3,
            "{boundary}: the boundary strays {:.3e}",
            report.boundary_distance
        );
        assert!(
            bound >= theirs,
            "{boundary}: certified min q_S {bound:.4} below G+Smo's sampled {theirs:.4}"
        );
    }
}
