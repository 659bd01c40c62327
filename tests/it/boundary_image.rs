//! The T-mesh's image of a planar boundary: a build whose boundary facets cut across the
//! boundary, so that cells stay invalid, fails and says where; finer cells build valid.
use igaparam::boundary::{BoundaryLoop2, Curve2};
use igaparam::domain::{PlanarDomain, PlanarOptions};
use igaparam::error::ErrorKind;

/// A U-shaped strip 0.2 wide whose inner wall's facets keep the wall's corner (3.8, 0.2) while
/// the chord of the outer wall's first facet, from (3.5, 0) to (4, 2), cuts across it.
fn strip() -> BoundaryLoop2 {
    let poly = |p: &[[f64; 2]]| Curve2::polyline(p.to_vec()).unwrap();
    let end = 3.8 - 6.4 / 3.0;
    BoundaryLoop2::from_curves(vec![
        poly(&[[1.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]]),
        poly(&[[0.0, 3.0], [0.0, 2.8]]),
        poly(&[[0.0, 2.8], [3.8, 2.8], [3.8, 0.2], [end, 0.2]]),
        poly(&[[end, 0.2], [1.0, 0.0]]),
    ])
    .unwrap()
}

fn options(tolerance: f64, level: u8) -> PlanarOptions {
    PlanarOptions {
        tolerance,
        min_level: level,
        max_level: level,
        repair_rounds: 0,
        ..Default::default()
    }
}

#[test]
fn facets_cutting_across_the_boundary_fail_the_build_and_say_where() {
    for level in [1, 2] {
        let Err(e) = PlanarDomain::build(strip(), &options(0.1, level), &mut |_, _| true) else {
            panic!("level {level}: the cells cannot all be valid");
        };
        assert_eq!(e.kind, ErrorKind::InvalidArgument, "{}", e.message);
        assert!(
            e.message.contains("cut across the boundary"),
            "{}",
            e.message
        );
        assert!(e.message.contains("cells stay invalid"), "{}", e.message);
    }
}

#[test]
fn cells_that_resolve_the_strip_build_valid() {
    let fine = PlanarOptions {
        tolerance: 1e-3,
        min_level: 2,
        max_level: 6,
        ..Default::default()
    };
    let (domain, report) = PlanarDomain::build(strip(), &fine, &mut |_, _| true).unwrap();
    assert_eq!(report.invalid_cells, 0, "{report:?}");
    assert!(domain.quality().iter().all(|&q| q > 0.0));
}
