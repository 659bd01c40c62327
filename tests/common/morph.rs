//! The morphs of the shape-optimization loop tests and benchmark: the puzzle piece whose knob
//! on the side u = 0 grows, and the 3D duck whose largest face bulges.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use igaparam::boundary::{
    read_gismo_curves, read_gismo_surfaces, BSplineCurve, BSplineSurface, BoundaryLoop2, Curve2,
    SolidBoundary,
};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/boundary")
        .join(name)
}

/// The four curves of the puzzle piece, as in its file.
pub fn puzzle_curves() -> Vec<BSplineCurve> {
    read_gismo_curves(data("puzzle3_bdry.xml")).expect("puzzle")
}

/// The six surfaces of the duck's B-rep, as in its file.
pub fn duck_surfaces() -> Vec<BSplineSurface> {
    read_gismo_surfaces(data("duck3d_BRep.xml")).expect("duck")
}

/// The knob of the puzzle's first curve (control points 9 to 26, the neck's ends at half
/// weight) scaled by `1 + 0.2 s` about the point where it joins the side: at `s = 1` it
/// reaches 20% further out.
pub fn grown_puzzle(curves: &[BSplineCurve], s: f64) -> Vec<BSplineCurve> {
    let mut out = curves.to_vec();
    let c = &curves[0];
    let centre = [0.07, 0.2];
    let mut coefs = Vec::with_capacity(2 * c.num_control_points());
    for i in 0..c.num_control_points() {
        let p = c.control_point(i);
        let weight = match i {
            10..=25 => 1.0,
            9 | 26 => 0.5,
            _ => 0.0,
        };
        let f = 1.0 + 0.2 * s * weight;
        coefs.extend((0..2).map(|k| centre[k] + f * (p[k] - centre[k])));
    }
    let kv = c.knot_vector();
    out[0] = BSplineCurve::new(
        kv.degree(),
        kv.knots().to_vec(),
        2,
        coefs,
        c.weights().map(<[f64]>::to_vec),
    )
    .expect("grown curve");
    out
}

/// The duck's back face (surface 5) with its inner control points scaled about their centroid
/// by `1 + 0.1 s w`, `w = 16 a(1 − a) b(1 − b)` of the control point's place `(a, b)` in the
/// net (1 in its middle, 0 on the edge rows, which stay, so the faces still share their edges):
/// at `s = 1` the face's middle moves 10% further from the centre.
pub fn scaled_duck(surfaces: &[BSplineSurface], s: f64) -> Vec<BSplineSurface> {
    let mut out = surfaces.to_vec();
    let f = &surfaces[5];
    let (nu, nv) = f.num_control_points();
    let points: Vec<[f64; 3]> = (0..nv)
        .flat_map(|j| (0..nu).map(move |i| (i, j)))
        .map(|(i, j)| f.control_point(i, j))
        .collect();
    let centre: [f64; 3] =
        std::array::from_fn(|k| points.iter().map(|p| p[k]).sum::<f64>() / points.len() as f64);
    let mut coefs = Vec::with_capacity(3 * points.len());
    for (n, p) in points.iter().enumerate() {
        let a = (n % nu) as f64 / (nu - 1) as f64;
        let b = (n / nu) as f64 / (nv - 1) as f64;
        let factor = 1.0 + 0.1 * s * 16.0 * a * (1.0 - a) * b * (1.0 - b);
        coefs.extend((0..3).map(|k| centre[k] + factor * (p[k] - centre[k])));
    }
    let (ku, kv) = (f.knot_vector_u(), f.knot_vector_v());
    out[5] = BSplineSurface::new(
        (ku.degree(), ku.knots().to_vec()),
        (kv.degree(), kv.knots().to_vec()),
        3,
        coefs,
        f.weights().map(<[f64]>::to_vec),
    )
    .expect("scaled face");
    out
}

/// The planar boundary of four curves.
pub fn planar(curves: &[BSplineCurve]) -> BoundaryLoop2 {
    let curves = curves
        .iter()
        .cloned()
        .map(Curve2::spline)
        .collect::<igaparam::Result<Vec<_>>>()
        .expect("curves");
    BoundaryLoop2::from_curves(curves).expect("loop")
}

/// The solid boundary of six surfaces.
pub fn solid(surfaces: &[BSplineSurface]) -> SolidBoundary {
    SolidBoundary::from_surfaces(surfaces.to_vec()).expect("solid")
}
