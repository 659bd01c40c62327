//! Coastline text files (`igaparam::boundary::Coastline::parse`: a `corners` line and `x y`
//! points) and the planar boundary loop built from them.

use igaparam::boundary::{BoundaryLoop2, Coastline};

use crate::common::{assert_finite, checked, text};

/// Parses `data` as a coastline and builds its boundary loop.
pub fn run(data: &[u8]) {
    let Some(text) = text(data) else { return };
    let Some(coast) = checked("Coastline::parse", Coastline::parse(text)) else {
        return;
    };
    // What the parser promises: finite points, corners in range and in cyclic order.
    let n = coast.points.len();
    assert!(n >= 4, "a coastline of {n} points was accepted");
    for p in &coast.points {
        assert_finite("coastline point", p);
    }
    let rel = coast.corners.map(|c| {
        assert!(c < n, "corner {c} of {n} points accepted");
        (c + n - coast.corners[0]) % n
    });
    assert!(
        rel.windows(2).all(|w| w[0] < w[1]),
        "corners {:?}",
        coast.corners
    );
    if let Some(boundary) = checked(
        "BoundaryLoop2::from_coastline",
        BoundaryLoop2::from_coastline(&coast),
    ) {
        crate::gismo_xml::check_loop(&boundary);
        // The loop's corners are the coastline's corner points (in some rotation and direction),
        // to round-off.
        for c in boundary.corners() {
            let gap = coast
                .corners
                .iter()
                .map(|&k| (coast.points[k][0] - c[0]).hypot(coast.points[k][1] - c[1]))
                .fold(f64::INFINITY, f64::min);
            let scale = c[0].abs().max(c[1].abs()).max(f64::MIN_POSITIVE);
            assert!(
                gap <= boundary.tolerance() + 1e-12 * scale,
                "loop corner {c:?} is not a corner of the coastline ({gap:e} away)"
            );
        }
    }
}
