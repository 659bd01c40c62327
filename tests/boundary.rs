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
