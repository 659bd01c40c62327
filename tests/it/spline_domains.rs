//! THB-spline fits of the optimized T-meshes of the shared planar domains: basis size,
//! interpolation residual, mean-ratio quality and certified validity (`--nocapture` prints the
//! table).

use std::time::Instant;

use crate::common;

use common::{curved_box, planar_boundary, MappedCube};
use igaparam::domain::{PlanarDomain, PlanarOptions};
use igaparam::spline::{
    QuadraticMap, SplineMap, SplineSpace, ThbSpace, UntangleOptions, ValidityOptions,
    ValidityReport,
};
use igaparam::tmesh::TMesh;

/// Builds the domain and runs [`fit_and_certify`] on it.
fn fit_domain(name: &str, rounds: usize) -> bool {
    let (domain, report) = PlanarDomain::build(
        planar_boundary(name),
        &PlanarOptions::default(),
        &mut |_, _| true,
    )
    .expect("domain");
    assert_eq!(report.invalid_cells, 0, "{name}: {report:?}");
    fit_and_certify(
        name,
        domain.mesh(),
        domain.positions(),
        report.seconds,
        rounds,
    )
}

/// Fits the spline to the T-mesh's piecewise quadratic map and certifies it, refining the
/// spline space (not the T-mesh) at uncertified elements at most `rounds` times; prints one
/// table row per fit and returns whether the last map is certified positive.
fn fit_and_certify<const D: usize>(
    name: &str,
    mesh: &TMesh<D>,
    positions: &[[f64; D]],
    mesh_seconds: f64,
    rounds: usize,
) -> bool {
    let size = positions
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let start = Instant::now();
    let source = QuadraticMap::new(mesh, positions).unwrap();
    let options = ValidityOptions::default();
    let untangle = UntangleOptions::default();
    let mut space = ThbSpace::new(mesh.tree().clone()).unwrap();
    let mut refinements = 0;
    loop {
        let (map, fit, validity) =
            SplineMap::fit_checked(space.clone(), |x| source.eval(x), &options, &untangle).unwrap();
        if !fit.least_squares && !fit.quasi_interpolation && fit.untangled == 0 {
            assert!(fit.residual < 1e-12 * size, "{name}: {fit:?}");
        }
        for v in &validity.elements {
            let tolerance = 1e-9 * v.sampled_min_det.abs().max(size.powi(D as i32) * 1e-6);
            assert!(
                v.det_lower_bound <= v.sampled_min_det + tolerance,
                "{name}: {v:?}"
            );
        }
        println!(
            "| {name} | {} | {} | {} | {:.1e} ({}) | {} | {} | {:.3} | {:.3} | {} ({} uncertified) | {:.2} | {:.2} |",
            mesh.cell_count(),
            map.element_count(),
            fit.basis_count,
            fit.residual / size,
            if fit.quasi_interpolation {
                "quasi-interpolation"
            } else if fit.least_squares {
                "least squares"
            } else {
                "interpolation"
            },
            refinements,
            fit.untangled,
            validity.min_quality,
            validity.mean_quality,
            validity.certified_positive,
            validity.uncertified,
            mesh_seconds,
            start.elapsed().as_secs_f64()
        );
        let marked: Vec<usize> = (0..map.element_count())
            .filter(|&e| !validity.elements[e].certified_positive)
            .collect();
        if marked.is_empty() || refinements == rounds {
            return validity.certified_positive;
        }
        space = space.refine(&marked).unwrap();
        refinements += 1;
    }
}

fn header() {
    println!("| domain | T-mesh cells | spline elements | basis | relative residual (fit) | spline refinements | control points untangled | min q_S | mean q_S | certified | T-mesh seconds | spline seconds (cumulative fit + certify) |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
}

#[test]
fn shared_domains_give_certified_spline_maps() {
    header();
    // puzzle3 and tenerife fold at a few elements next to sharp boundary features until the
    // spline space is refined there or the map untangled; Gran Canaria's dense, kinked coastline
    // makes the C2 fit fold next to the coast until its inner control points are untangled.
    let failed: Vec<&str> = crate::common::PLANAR_DOMAINS
        .into_iter()
        .filter(|name| !fit_domain(name, 3))
        .collect();
    assert!(failed.is_empty(), "not certified positive: {failed:?}");
}

/// A solid given by a map of the unit cube (only its boundary values are used).
#[test]
fn a_curved_solid_gives_a_certified_spline_map() {
    let map = curved_box;
    let options = igaparam::domain::DomainOptions {
        tolerance: 1e-4,
        max_level: 4,
        ..Default::default()
    };
    let (domain, report) =
        igaparam::domain::Domain::build(MappedCube(map), &options, &mut |_, _| true).unwrap();
    assert_eq!(report.invalid_cells, 0);
    header();
    assert!(fit_and_certify(
        "curved solid (3D)",
        domain.mesh(),
        domain.positions(),
        report.seconds,
        3
    ));
}

/// `det J` by cofactors (an independent computation, not the library's).
fn det<const D: usize>(j: &[[f64; D]; D]) -> f64 {
    match D {
        2 => j[0][0] * j[1][1] - j[0][1] * j[1][0],
        3 => {
            j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
        }
        _ => unreachable!(),
    }
}

/// Checks a certification against a dense evaluation of the map's Jacobians at a grid of
/// `4k + 1` points per direction and element, which holds the certification's 5 samples per
/// direction (multiples of 1/4 of the element): a certified map has det J > 0 at every point;
/// each element's certified lower bound is at most its dense minimum of det J; the mean ratio
/// recomputed at the samples is the element's sampled minimum; and the dense minimum of the
/// mean ratio is at most the reported (sampled) one, the samples being a subset of the grid.
fn check_dense<const D: usize>(map: &SplineMap<D>, validity: &ValidityReport, k: usize) {
    assert_eq!(ValidityOptions::default().samples, 5);
    let n = 4 * k + 1;
    let mut dense_min_q = f64::INFINITY;
    for e in 0..map.element_count() {
        let (lo, hi) = map.element_bounds(e);
        let (mut min_det, mut sample_min_q) = (f64::INFINITY, f64::INFINITY);
        for s in 0..n.pow(D as u32) {
            let index: [usize; D] = std::array::from_fn(|a| s / n.pow(a as u32) % n);
            let x =
                std::array::from_fn(|a| lo[a] + (hi[a] - lo[a]) * index[a] as f64 / (n - 1) as f64);
            let (_, j) = map.eval_with_jacobian(x).expect("inside [0,1]^d");
            let d = det(&j);
            let norm2: f64 = j.iter().flatten().map(|v| v * v).sum();
            let q = if d > 0.0 {
                D as f64 * d.powf(2.0 / D as f64) / norm2
            } else {
                0.0
            };
            min_det = min_det.min(d);
            dense_min_q = dense_min_q.min(q);
            if index.iter().all(|i| i % k == 0) {
                sample_min_q = sample_min_q.min(q);
            }
        }
        let element = &validity.elements[e];
        if validity.certified_positive {
            assert!(
                min_det > 0.0,
                "element {e}: certified, but det J = {min_det} at a dense point"
            );
        }
        let bound = element.det_lower_bound;
        assert!(
            min_det >= bound - 1e-9 * bound.abs(),
            "element {e}: det J {min_det} < certified bound {bound}"
        );
        assert!(
            (sample_min_q - element.min_quality).abs() <= 1e-9,
            "element {e}: recomputed sampled min q {sample_min_q}, reported {}",
            element.min_quality
        );
    }
    assert!(
        dense_min_q <= validity.min_quality + 1e-12,
        "dense min q {dense_min_q} above the sampled minimum {}",
        validity.min_quality
    );
}

/// The certification of cubic maps against the dense evaluation: Gran Canaria (untangled
/// before it is certified) and a curved solid.
#[test]
fn certification_agrees_with_a_dense_evaluation() {
    let (domain, _) = PlanarDomain::build(
        planar_boundary("gran_canaria.txt"),
        &PlanarOptions::default(),
        &mut |_, _| true,
    )
    .unwrap();
    let (map, fit, validity) = common::checked_fit(&domain);
    assert!(fit.untangled > 0 && validity.certified_positive);
    check_dense(&map, &validity, 4);

    let options = igaparam::domain::DomainOptions {
        tolerance: 1e-2,
        max_level: 3,
        ..igaparam::domain::DomainOptions::solid()
    };
    let (solid, _) =
        igaparam::domain::Domain::build(MappedCube(curved_box), &options, &mut |_, _| true)
            .unwrap();
    let (map, _, validity) = common::checked_fit(&solid);
    assert!(validity.certified_positive);
    check_dense(&map, &validity, 2);
}
