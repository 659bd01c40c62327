//! Planar domains: adapted, optimized T-meshes from four boundary curves.

use std::path::{Path, PathBuf};

use igaparam::boundary::{BoundaryLoop2, Coastline, Curve2};
use igaparam::domain::{PlanarDomain, PlanarOptions, PlanarReport};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/boundary")
        .join(name)
}

fn build(boundary: BoundaryLoop2, options: &PlanarOptions) -> (PlanarDomain, PlanarReport) {
    PlanarDomain::build(boundary, options, &mut |_, _| true).expect("domain")
}

/// The boundary of `[0,1]²` mapped by `f`, as four polylines of `n` segments.
fn mapped_square(f: impl Fn([f64; 2]) -> [f64; 2], n: usize) -> BoundaryLoop2 {
    let side = |a: [f64; 2], b: [f64; 2]| {
        let points = (0..=n)
            .map(|i| {
                let t = i as f64 / n as f64;
                f([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])])
            })
            .collect();
        Curve2::polyline(points).unwrap()
    };
    BoundaryLoop2::from_curves(vec![
        side([0.0, 0.0], [0.0, 1.0]),
        side([1.0, 0.0], [1.0, 1.0]),
        side([0.0, 0.0], [1.0, 0.0]),
        side([0.0, 1.0], [1.0, 1.0]),
    ])
    .unwrap()
}

#[test]
fn the_unit_square_gives_the_identity() {
    let (domain, report) = build(mapped_square(|p| p, 4), &PlanarOptions::default());
    assert_eq!(report.invalid_cells, 0);
    let worst = domain
        .mesh()
        .parametric()
        .iter()
        .zip(domain.positions())
        .map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs()))
        .fold(0.0, f64::max);
    assert!(worst < 1e-12, "moved by {worst}");
    assert!((report.min_quality - 1.0).abs() < 1e-12);
}

#[test]
fn shared_domains_give_valid_t_meshes_within_the_boundary_tolerance() {
    let options = PlanarOptions::default();
    let mut boundaries: Vec<(String, BoundaryLoop2)> = [
        "puzzle3_bdry.xml",
        "rotor_bdry.xml",
        "male_bdry.xml",
        "duck2d_BRep.xml",
    ]
    .iter()
    .map(|f| {
        (
            f.to_string(),
            BoundaryLoop2::from_gismo_file(data(f)).unwrap(),
        )
    })
    .collect();
    for f in ["gran_canaria.txt", "tenerife.txt"] {
        let coast = Coastline::read(data(f)).unwrap();
        boundaries.push((
            f.to_string(),
            BoundaryLoop2::from_coastline(&coast).unwrap(),
        ));
    }
    let reports: Vec<(String, PlanarReport)> = boundaries
        .into_iter()
        .map(|(name, boundary)| (name, build(boundary, &options).1))
        .collect();
    for (name, report) in &reports {
        println!("{name}: {report:?}");
    }
    for (name, report) in &reports {
        assert_eq!(report.invalid_cells, 0, "{name}: {report:?}");
        assert!(
            report.boundary_error <= options.tolerance || report.max_level == options.max_level,
            "{name}: {report:?}"
        );
    }
}
