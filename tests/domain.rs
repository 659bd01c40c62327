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

/// Largest coordinate difference between the physical and the parametric vertices.
fn distance_from_parametric<const D: usize, B: igaparam::domain::CubeMap<D>>(
    domain: &igaparam::domain::Domain<D, B>,
) -> f64 {
    domain
        .mesh()
        .parametric()
        .iter()
        .zip(domain.positions())
        .map(|(a, b)| (0..D).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max)
}

#[test]
fn the_unit_square_gives_the_identity() {
    let (domain, report) = build(mapped_square(|p| p, 4), &PlanarOptions::default());
    assert_eq!(report.invalid_cells, 0);
    let worst = distance_from_parametric(&domain);
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

/// A solid given by a map of the unit cube (only its boundary values are used).
struct MappedCube<F>(F);

impl<F: Fn([f64; 3]) -> [f64; 3]> igaparam::domain::CubeMap<3> for MappedCube<F> {
    fn boundary_point(&self, p: [f64; 3]) -> [f64; 3] {
        (self.0)(p)
    }
}

#[test]
fn the_unit_cube_gives_the_identity() {
    let options = igaparam::domain::DomainOptions {
        min_level: 2,
        max_level: 3,
        ..Default::default()
    };
    let (domain, report) =
        igaparam::domain::Domain::build(MappedCube(|p: [f64; 3]| p), &options, &mut |_, _| true)
            .unwrap();
    assert_eq!(report.invalid_cells, 0);
    let worst = distance_from_parametric(&domain);
    assert!(worst < 1e-12, "moved by {worst}");
}

#[test]
fn a_curved_solid_gets_a_valid_adapted_octree() {
    use std::f64::consts::PI;
    // A box whose top bulges and whose sides are sheared and waved.
    let map = |[x, y, z]: [f64; 3]| {
        [
            2.0 * x + 0.3 * z + 0.1 * (PI * y).sin(),
            y + 0.15 * (2.0 * PI * x).sin() * z,
            z * (1.0 + 0.4 * (PI * x).sin() * (PI * y).sin()),
        ]
    };
    let options = igaparam::domain::DomainOptions {
        tolerance: 1e-4,
        max_level: 5,
        ..Default::default()
    };
    let (domain, report) =
        igaparam::domain::Domain::build(MappedCube(map), &options, &mut |_, _| true).unwrap();
    println!("{report:?}");
    assert_eq!(report.invalid_cells, 0, "{report:?}");
    assert!(report.boundary_error <= options.tolerance || report.max_level == options.max_level);
    assert!(
        report.max_level > options.min_level,
        "the curved boundary refined nothing"
    );
    assert!(domain.mesh().tree().is_balanced());
    // Boundary vertices lie on the boundary.
    for (v, p) in domain.mesh().parametric().iter().enumerate() {
        if domain.mesh().on_boundary(v) {
            let exact = map(*p);
            assert!((0..3).all(|k| (exact[k] - domain.positions()[v][k]).abs() < 1e-12));
        }
    }
}
