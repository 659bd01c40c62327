//! G+Smo XML B-reps (`igaparam::boundary::parse_gismo_xml`): B-spline and NURBS curves and
//! tensor surfaces, and what the library builds from them: the planar boundary loop of four
//! curves (`BoundaryLoop2`), the solid boundary of six surfaces (`SolidBoundary`). Accepted
//! inputs must evaluate to finite points.

use igaparam::boundary::{
    parse_gismo_xml, BoundaryLoop2, Curve2, GismoGeometry, Side, SolidBoundary,
};

use crate::common::{assert_finite, checked, params, text};

/// Parses `data` as a G+Smo B-rep and builds the loop or solid it describes.
pub fn run(data: &[u8]) {
    let Some(text) = text(data) else { return };
    let Some(geometries) = checked("parse_gismo_xml", parse_gismo_xml(text)) else {
        return;
    };
    let (mut curves, mut surfaces) = (Vec::new(), Vec::new());
    for g in geometries {
        match g {
            GismoGeometry::Curve(c) => curves.push(c),
            GismoGeometry::Surface(s) => surfaces.push(s),
        }
    }
    let (curve_count, surface_count) = (curves.len(), surfaces.len());
    if curve_count == 4 && surface_count == 0 {
        let curves: Option<Vec<Curve2>> = curves
            .into_iter()
            .map(|c| checked("Curve2::spline", Curve2::spline(c)))
            .collect();
        if let Some(boundary) = curves
            .and_then(|c| checked("BoundaryLoop2::from_curves", BoundaryLoop2::from_curves(c)))
        {
            check_loop(&boundary);
        }
    }
    if surface_count == 6 && curve_count == 0 {
        if let Some(solid) = checked(
            "SolidBoundary::from_surfaces",
            SolidBoundary::from_surfaces(surfaces),
        ) {
            check_solid(&solid);
        }
    }
}

/// An accepted loop evaluates to finite points, and its sides meet at its corners.
pub fn check_loop(boundary: &BoundaryLoop2) {
    for side in Side::all() {
        for t in params(16) {
            let (p, d) = boundary.eval_deriv(side, t);
            assert_finite("boundary loop", &[p[0], p[1], d[0], d[1]]);
        }
    }
    let c = boundary.corners();
    let tol = 2.0 * boundary.tolerance().max(0.0) + 1e-12;
    let ends = [
        (boundary.eval(Side::U0, 0.0), c[0]),
        (boundary.eval(Side::U1, 0.0), c[1]),
        (boundary.eval(Side::U1, 1.0), c[2]),
        (boundary.eval(Side::U0, 1.0), c[3]),
    ];
    for (p, q) in ends {
        let gap = (p[0] - q[0]).hypot(p[1] - q[1]);
        let scale = 1.0 + p[0].abs().max(p[1].abs());
        assert!(
            gap <= tol + 1e-9 * scale,
            "the sides u = 0, 1 do not meet the corners: {p:?} vs {q:?}"
        );
    }
}

/// An accepted solid boundary evaluates to finite points on every face.
fn check_solid(solid: &SolidBoundary) {
    for face in 0..6 {
        for a in params(4) {
            for b in params(4) {
                assert_finite("solid boundary", &solid.eval_face(face, a, b));
            }
        }
    }
    let (lo, hi) = solid.bounding_box();
    assert_finite("bounding box", &[lo, hi].concat());
}
