//! Tests of the boundary-input module: B-splines, G+Smo XML, boundary loops, projection.

use igaparam::boundary::*;
use igaparam::ErrorKind;

/// Bernstein control points of the cubic (t, t³ - t) on [0,1], inserted knots do not change it.
#[test]
fn bspline_reproduces_a_cubic_polynomial_curve() {
    // Bezier control points of x = t, y = t^3 - t: x: 0, 1/3, 2/3, 1; y: 0, -1/3, -2/3, 0.
    let c = BSplineCurve::new(
        3,
        vec![0., 0., 0., 0., 1., 1., 1., 1.],
        2,
        vec![0., 0., 1. / 3., -1. / 3., 2. / 3., -2. / 3., 1., 0.],
        None,
    )
    .unwrap();
    for i in 0..=50 {
        let t = i as f64 / 50.0;
        let (p, d) = c.eval_deriv(t);
        assert!((p[0] - t).abs() < 1e-14 && (p[1] - (t * t * t - t)).abs() < 1e-14);
        assert!((d[0] - 1.0).abs() < 1e-12 && (d[1] - (3.0 * t * t - 1.0)).abs() < 1e-12);
    }
    // A quadratic B-spline with interior knots reproduces y = x² when its control points are
    // the Greville abscissae with ordinates from the blossom: y_i = t_{i+1} t_{i+2}.
    let knots = vec![0., 0., 0., 0.25, 0.6, 0.6, 1., 1., 1.];
    let n = knots.len() - 3;
    let mut coefs = Vec::new();
    for i in 0..n {
        let (a, b) = (knots[i + 1], knots[i + 2]);
        coefs.push(0.5 * (a + b));
        coefs.push(a * b);
    }
    let c = BSplineCurve::new(2, knots, 2, coefs, None).unwrap();
    for i in 0..=40 {
        let t = i as f64 / 40.0;
        let p = c.eval(t);
        assert!((p[0] - t).abs() < 1e-14, "x({t}) = {}", p[0]);
        assert!((p[1] - t * t).abs() < 1e-14, "y({t}) = {}", p[1]);
    }
}

#[test]
fn bspline_partition_of_unity() {
    let kv = KnotVector::new(2, vec![0., 0., 0., 0.1, 0.1, 0.7, 1., 1., 1.]).unwrap();
    for i in 0..=200 {
        let t = i as f64 / 200.0;
        let (_, d) = kv.basis_derivs(t, 1);
        assert!((d[0].iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }
}

#[test]
fn nurbs_circle_and_derivative_match_finite_differences() {
    // Quarter circle as a rational quadratic.
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let c = BSplineCurve::new(
        2,
        vec![0., 0., 0., 1., 1., 1.],
        2,
        vec![1., 0., 1., 1., 0., 1.],
        Some(vec![1., w, 1.]),
    )
    .unwrap();
    for i in 0..=20 {
        let t = 0.025 + 0.95 * i as f64 / 20.0;
        let (p, d) = c.eval_deriv(t);
        assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-14);
        let h = 1e-6;
        let (a, b) = (c.eval(t - h), c.eval(t + h));
        for k in 0..2 {
            let fd = (b[k] - a[k]) / (2.0 * h);
            assert!((fd - d[k]).abs() < 1e-7, "t={t} k={k}: {fd} vs {}", d[k]);
        }
    }
}

#[test]
fn surface_partials_match_finite_differences() {
    let ku = vec![0., 0., 0., 0.5, 1., 1., 1.];
    let kv = vec![0., 0., 1., 1.];
    let mut coefs = Vec::new();
    for j in 0..2 {
        for i in 0..4 {
            coefs.extend_from_slice(&[i as f64, j as f64 * 2.0, ((i * 7 + j * 3) % 5) as f64]);
        }
    }
    let s = BSplineSurface::new((2, ku), (1, kv), 3, coefs, None).unwrap();
    let h = 1e-6;
    for &(u, v) in &[(0.2, 0.3), (0.7, 0.9), (0.5001, 0.5)] {
        let (_, du, dv) = s.eval_derivs(u, v);
        let fu = s.eval(u + h, v);
        let bu = s.eval(u - h, v);
        let fv = s.eval(u, v + h);
        let bv = s.eval(u, v - h);
        for k in 0..3 {
            assert!(((fu[k] - bu[k]) / (2.0 * h) - du[k]).abs() < 1e-6);
            assert!(((fv[k] - bv[k]) / (2.0 * h) - dv[k]).abs() < 1e-6);
        }
    }
}

#[test]
fn bspline_validation_errors_are_readable() {
    let e = BSplineCurve::new(2, vec![0., 0., 1., 0.5, 1., 1.], 2, vec![0.; 6], None).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidArgument);
    assert!(e.message.contains("non-decreasing"), "{}", e.message);
    let e =
        BSplineCurve::new(1, vec![0., 0., 1., f64::INFINITY], 2, vec![0.; 4], None).unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotFinite);
}

fn data(name: &str) -> String {
    format!("{}/tests/data/boundary/{name}", env!("CARGO_MANIFEST_DIR"))
}

const BREPS2D: [&str; 4] = [
    "duck2d_BRep.xml",
    "male_bdry.xml",
    "puzzle3_bdry.xml",
    "rotor_bdry.xml",
];

#[test]
fn gismo_breps2d_have_four_planar_curves() {
    for name in BREPS2D {
        let curves = read_gismo_curves(data(name)).unwrap();
        assert_eq!(curves.len(), 4, "{name}");
        for c in &curves {
            assert_eq!(c.dim(), 2);
            assert!(c.is_clamped());
        }
    }
    let duck = read_gismo_curves(data("duck2d_BRep.xml")).unwrap();
    assert_eq!(duck[0].degree(), 2);
    assert_eq!(duck[0].num_control_points(), 10);
    assert_eq!(duck[0].eval(0.0), [30.0, 80.0, 0.0]);
    assert_eq!(duck[0].eval(1.0), [40.0, 292.0, 0.0]);
}

#[test]
fn gismo_duck3d_surfaces_share_their_edges() {
    let s = read_gismo_surfaces(data("duck3d_BRep.xml")).unwrap();
    assert_eq!(s.len(), 6);
    // Sample the four edges of every face; each must coincide with an edge of another face.
    let edge = |k: usize, e: usize| -> Vec<[f64; 3]> {
        let ((u0, u1), (v0, v1)) = s[k].domain();
        (0..=6)
            .map(|i| {
                let t = i as f64 / 6.0;
                let (u, v) = match e {
                    0 => (u0, v0 + t * (v1 - v0)),
                    1 => (u1, v0 + t * (v1 - v0)),
                    2 => (u0 + t * (u1 - u0), v0),
                    _ => (u0 + t * (u1 - u0), v1),
                };
                s[k].eval(u, v)
            })
            .collect()
    };
    let same = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        let close = |p: &[f64; 3], q: &[f64; 3]| (0..3).all(|d| (p[d] - q[d]).abs() < 1e-6);
        a.iter().zip(b).all(|(p, q)| close(p, q))
            || a.iter().zip(b.iter().rev()).all(|(p, q)| close(p, q))
    };
    for (k, face) in s.iter().enumerate() {
        assert_eq!(face.dim(), 3);
        for e in 0..4 {
            let a = edge(k, e);
            let matches = (0..6)
                .filter(|&m| m != k)
                .flat_map(|m| (0..4).map(move |f| (m, f)))
                .filter(|&(m, f)| same(&a, &edge(m, f)))
                .count();
            assert_eq!(matches, 1, "face {k} edge {e}");
        }
    }
}

#[test]
fn gismo_reader_rejects_unknown_types_and_missing_parts() {
    let e = parse_gismo_xml("<xml><Geometry type=\"Nurbs\"></Geometry></xml>").unwrap_err();
    assert_eq!(e.kind, ErrorKind::Io);
    assert!(e.message.contains("Nurbs"), "{}", e.message);
    let e = parse_gismo_xml(
        "<xml>\n<Geometry type=\"BSpline\">\n<KnotVector degree=\"1\">0 0 1 1</KnotVector>\n</Geometry></xml>",
    )
    .unwrap_err();
    assert!(e.message.contains("coefs"), "{}", e.message);
    let e = parse_gismo_xml(
        "<xml><Geometry type=\"BSpline\"><KnotVector degree=\"1\">0 0 1 1</KnotVector><coefs geoDim=\"2\">0 0 1 1 2 2</coefs></Geometry></xml>",
    )
    .unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidArgument);
    assert!(e.message.contains("control points"), "{}", e.message);
    let e = read_gismo_xml(data("no_such_file.xml")).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Io);
}
