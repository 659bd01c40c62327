//! THB-spline fits of the optimized T-meshes of the shared planar domains: basis size,
//! interpolation residual, mean-ratio quality and certified validity (`--nocapture` prints the
//! table).

use std::path::{Path, PathBuf};
use std::time::Instant;

use igaparam::boundary::{BoundaryLoop2, Coastline};
use igaparam::domain::{PlanarDomain, PlanarOptions};
use igaparam::spline::{SplineMap, ValidityOptions};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/boundary")
        .join(name)
}

fn boundary(name: &str) -> BoundaryLoop2 {
    if name.ends_with(".txt") {
        BoundaryLoop2::from_coastline(&Coastline::read(data(name)).unwrap()).unwrap()
    } else {
        BoundaryLoop2::from_gismo_file(data(name)).unwrap()
    }
}

/// Builds the domain, fits the spline, certifies it; prints one table row and returns whether
/// it is certified positive.
fn fit_domain(name: &str) -> bool {
    let (domain, report) =
        PlanarDomain::build(boundary(name), &PlanarOptions::default(), &mut |_, _| true)
            .expect("domain");
    assert_eq!(report.invalid_cells, 0, "{name}: {report:?}");
    let start = Instant::now();
    {
        let space = igaparam::spline::ThbSpace::new(domain.mesh().tree().clone()).unwrap();
        let source = igaparam::spline::QuadraticMap::new(domain.mesh(), domain.positions()).unwrap();
        let r = SplineMap::fit_collocation(space, |x| source.eval(x));
        println!("collocation: {:?}", r.map(|r| r.1));
    }
    let (map, fit) = SplineMap::fit_tmesh(domain.mesh(), domain.positions()).unwrap();
    let validity = map.validity(&ValidityOptions::default());
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "| {name} | {} | {} | {:.1e} | {} | {:.3} | {:.3} | {} ({} uncertified) | {:.2} |",
        map.element_count(),
        fit.basis_count,
        fit.residual,
        if fit.least_squares { "least squares" } else { "interpolation" },
        validity.min_quality,
        validity.mean_quality,
        validity.certified_positive,
        validity.uncertified,
        seconds
    );
    assert!(fit.residual < 1e-8 * 10f64.max(1.0), "{name}: {fit:?}");
    for v in &validity.elements {
        assert!(v.det_lower_bound <= v.sampled_min_det + 1e-9);
    }
    validity.certified_positive
}

fn header() {
    println!("| domain | elements | basis | residual | fit | min q_S | mean q_S | certified | seconds (fit + certify) |");
    println!("|---|---|---|---|---|---|---|---|---|");
}

#[test]
fn shared_domains_give_certified_spline_maps() {
    header();
    let mut failed = Vec::new();
    for name in [
        "puzzle3_bdry.xml",
        "rotor_bdry.xml",
        "male_bdry.xml",
        "duck2d_BRep.xml",
        "gran_canaria.txt",
        "tenerife.txt",
    ] {
        if !fit_domain(name) {
            failed.push(name);
        }
    }
    assert!(failed.is_empty(), "not certified positive: {failed:?}");
}
