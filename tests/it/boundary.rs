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
    let e = parse_gismo_xml("<xml><Geometry type=\"THBSpline2\"></Geometry></xml>").unwrap_err();
    assert_eq!(e.kind, ErrorKind::Io);
    assert!(e.message.contains("THBSpline2"), "{}", e.message);
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

fn assert_valid_loop(l: &BoundaryLoop2, what: &str) {
    let c = l.corners();
    let tol = 10.0 * l.tolerance() + 1e-12;
    // Sides join at the corners.
    let close = |a: Point2, b: Point2| distance(a, b) <= tol;
    assert!(
        close(l.eval(Side::V0, 0.0), c[0]) && close(l.eval(Side::U0, 0.0), c[0]),
        "{what}"
    );
    assert!(
        close(l.eval(Side::V0, 1.0), c[1]) && close(l.eval(Side::U1, 0.0), c[1]),
        "{what}"
    );
    assert!(
        close(l.eval(Side::U1, 1.0), c[2]) && close(l.eval(Side::V1, 1.0), c[2]),
        "{what}"
    );
    assert!(
        close(l.eval(Side::V1, 0.0), c[3]) && close(l.eval(Side::U0, 1.0), c[3]),
        "{what}"
    );
    for a in l.corner_angles_deg() {
        assert!(a > 0.0 && a < 180.0, "{what}: corner angle {a}");
    }
    // Counter-clockwise: positive signed area of the sampled loop (V0, U1, V1 back, U0 back).
    let mut pts = Vec::new();
    for (side, rev) in [
        (Side::V0, false),
        (Side::U1, false),
        (Side::V1, true),
        (Side::U0, true),
    ] {
        for i in 0..200 {
            let t = i as f64 / 200.0;
            pts.push(l.eval(side, if rev { 1.0 - t } else { t }));
        }
    }
    let area: f64 = (0..pts.len())
        .map(|i| {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum();
    assert!(area > 0.0, "{what}: area {area}");
}

#[test]
fn breps2d_load_into_valid_four_sided_loops() {
    for name in BREPS2D {
        let l = BoundaryLoop2::from_gismo_file(data(name)).unwrap();
        assert_valid_loop(&l, name);
    }
    // The duck's first curve is its u = 0 side, already running with v.
    let l = BoundaryLoop2::from_gismo_file(data("duck2d_BRep.xml")).unwrap();
    assert_eq!(l.corners()[0], [30.0, 80.0]);
    assert_eq!(l.corners()[3], [40.0, 292.0]);
    assert!(!l.side(Side::U0).is_reversed());
}

#[test]
fn coastlines_load_with_four_sides() {
    for (name, n) in [("gran_canaria.txt", 1170), ("tenerife.txt", 1541)] {
        let coast = Coastline::read(data(name)).unwrap();
        assert_eq!(coast.points.len(), n, "{name}");
        let l = BoundaryLoop2::from_coastline(&coast).unwrap();
        assert_valid_loop(&l, name);
        let c = coast.corners;
        assert_eq!(
            l.corners(),
            [c[0], c[1], c[2], c[3]].map(|i| coast.points[i])
        );
        // The four polylines hold every point once, plus the four shared corners.
        let total: usize = Side::all()
            .iter()
            .map(|&s| match l.side(s).kind() {
                CurveKind::Polyline(p) => p.points().len(),
                CurveKind::Spline(_) => unreachable!(),
            })
            .sum();
        assert_eq!(total, n + 4, "{name}");
    }
}

fn square_sides() -> Vec<Curve2> {
    vec![
        Curve2::polyline(vec![[0., 0.], [0., 0.5], [0., 1.]]).unwrap(),
        Curve2::polyline(vec![[1., 0.], [1., 1.]]).unwrap(),
        Curve2::polyline(vec![[0., 0.], [1., 0.]]).unwrap(),
        Curve2::polyline(vec![[0., 1.], [1., 1.]]).unwrap(),
    ]
}

#[test]
fn square_with_a_reversed_side_is_reoriented() {
    let mut sides = square_sides();
    sides[1] = Curve2::polyline(vec![[1., 1.], [1., 0.]]).unwrap();
    sides.swap(2, 3);
    let l = BoundaryLoop2::from_curves(sides).unwrap();
    assert_valid_loop(&l, "square");
    assert_eq!(l.corners(), [[0., 0.], [1., 0.], [1., 1.], [0., 1.]]);
    assert!(l.side(Side::U1).is_reversed());
    let p = l.eval(Side::U1, 0.25);
    assert!((p[0] - 1.0).abs() < 1e-15 && (p[1] - 0.25).abs() < 1e-15);
    let (_, d) = l.eval_deriv(Side::U1, 0.25);
    assert!((d[1] - 1.0).abs() < 1e-14, "derivative {d:?}");
    // A clockwise description of the same square gives the same map.
    let cw = vec![
        Curve2::polyline(vec![[0., 1.], [0., 0.]]).unwrap(),
        Curve2::polyline(vec![[1., 0.], [0., 0.]]).unwrap(),
        Curve2::polyline(vec![[1., 1.], [1., 0.]]).unwrap(),
        Curve2::polyline(vec![[0., 1.], [1., 1.]]).unwrap(),
    ];
    let l = BoundaryLoop2::from_curves(cw).unwrap();
    assert_eq!(l.corners(), [[0., 0.], [1., 0.], [1., 1.], [0., 1.]]);
}

#[test]
fn reflex_corner_is_refused() {
    // A dart: the corner at (0.5, 0.6) points inwards (interior angle > 180°).
    let sides = vec![
        Curve2::polyline(vec![[0., 0.], [0.5, 0.6]]).unwrap(),
        Curve2::polyline(vec![[0.5, 0.6], [1., 0.]]).unwrap(),
        Curve2::polyline(vec![[1., 0.], [0.5, 1.5]]).unwrap(),
        Curve2::polyline(vec![[0.5, 1.5], [0., 0.]]).unwrap(),
    ];
    let e = BoundaryLoop2::from_curves(sides).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidArgument);
    assert!(
        e.message.contains("interior angle") && e.message.contains("(0.500000, 0.600000)"),
        "{}",
        e.message
    );
    // Straight (180°) corner: also refused.
    let sides = vec![
        Curve2::polyline(vec![[0., 0.], [1., 0.]]).unwrap(),
        Curve2::polyline(vec![[1., 0.], [2., 0.]]).unwrap(),
        Curve2::polyline(vec![[2., 0.], [2., 1.], [0., 1.]]).unwrap(),
        Curve2::polyline(vec![[0., 1.], [0., 0.]]).unwrap(),
    ];
    let e = BoundaryLoop2::from_curves(sides).unwrap_err();
    assert!(e.message.contains("180.00°"), "{}", e.message);
}

#[test]
fn open_loop_is_refused() {
    let mut sides = square_sides();
    sides[3] = Curve2::polyline(vec![[0., 1.], [0.9, 1.]]).unwrap();
    let e = BoundaryLoop2::from_curves(sides).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidArgument);
    assert!(
        e.message.contains("open") || e.message.contains("not closed"),
        "{}",
        e.message
    );
    let e = BoundaryLoop2::from_curves(square_sides()[..3].to_vec()).unwrap_err();
    assert!(e.message.contains("exactly 4"), "{}", e.message);
}

#[test]
fn self_intersecting_loop_is_refused() {
    // The top side dips through the bottom one; every corner stays convex and the area positive,
    // so only the crossing check stands between this loop and a T-mesh with inverted cells.
    let mut sides = square_sides();
    let dip = vec![[0., 1.], [0.4, 1.], [0.5, -0.5], [0.6, 1.], [1., 1.]];
    sides[3] = Curve2::polyline(dip).unwrap();
    let e = BoundaryLoop2::from_curves(sides).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidArgument);
    assert!(
        e.message.contains("crosses itself")
            && e.message.contains("curve 2")
            && e.message.contains("curve 3"),
        "{}",
        e.message
    );
    // A loop that only touches itself (the top's lowest vertex on the bottom side) is refused
    // too; the same loop kept just clear of the bottom is accepted.
    for (y, refused) in [(0.0, true), (1e-9, false)] {
        let mut sides = square_sides();
        let touch = vec![[0., 1.], [0.4, 1.], [0.5, y], [0.6, 1.], [1., 1.]];
        sides[3] = Curve2::polyline(touch).unwrap();
        let r = BoundaryLoop2::from_curves(sides);
        assert_eq!(r.is_err(), refused, "lowest vertex at {y}: {:?}", r.err());
    }
}

#[test]
fn nan_coordinates_are_refused() {
    let e = Curve2::polyline(vec![[0., 0.], [f64::NAN, 1.]]).unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotFinite);
    assert!(e.message.contains("NaN"), "{}", e.message);
    let e = Coastline::parse("corners 0 1 2 3\n0 0\n1 0\nnan 1\n0 1\n").unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotFinite);
    assert!(e.message.contains("line 4"), "{}", e.message);
    let e = BSplineCurve::new(1, vec![0., 0., 1., 1.], 2, vec![0., 0., f64::NAN, 1.], None)
        .unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotFinite);
}

#[test]
fn coastline_format_errors() {
    let e = Coastline::parse("0 0\n1 0\n1 1\n0 1\n").unwrap_err();
    assert_eq!(e.kind, ErrorKind::Io);
    let e = Coastline::parse("corners 0 2 1 3\n0 0\n1 0\n1 1\n0 1\n").unwrap_err();
    assert!(e.message.contains("order"), "{}", e.message);
    let e = Coastline::parse("corners 0 1 2 9\n0 0\n1 0\n1 1\n0 1\n").unwrap_err();
    assert!(e.message.contains("out of range"), "{}", e.message);
    // Corners need not start at point 0.
    let c = Coastline::parse("corners 1 2 3 0\n0 1\n0 0\n1 0\n1 1\n").unwrap();
    let l = BoundaryLoop2::from_coastline(&c).unwrap();
    assert_eq!(l.corners(), [[0., 0.], [1., 0.], [1., 1.], [0., 1.]]);
}

fn half_circle() -> Curve2 {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let c = BSplineCurve::new(
        2,
        vec![0., 0., 0., 0.5, 0.5, 1., 1., 1.],
        2,
        vec![1., 0., 1., 1., 0., 1., -1., 1., -1., 0.],
        Some(vec![1., w, 1., w, 1.]),
    )
    .unwrap();
    Curve2::spline(c).unwrap()
}

#[test]
fn projection_finds_the_nearest_point_of_a_circle() {
    let c = half_circle();
    for k in 0..40 {
        let ang = 0.02 + 3.1 * k as f64 / 39.0;
        for r in [0.05, 0.3, 0.9, 1.0, 1.7, 4.0] {
            let p = [r * ang.cos(), r * ang.sin()];
            let q = c.closest_point(p);
            let exact = [ang.cos(), ang.sin()];
            assert!(
                distance(q.point, exact) < 1e-9,
                "angle {ang} r {r}: {:?}",
                q.point
            );
            assert!((q.distance - (r - 1.0).abs()).abs() < 1e-9);
            assert!(distance(c.eval(q.t), q.point) < 1e-14);
            // The reversed curve finds the same point at 1 - t.
            let qr = c.clone().reversed().closest_point(p);
            assert!((qr.t - (1.0 - q.t)).abs() < 1e-8 && distance(qr.point, q.point) < 1e-9);
        }
    }
    // Below the diameter the nearest point is an end point.
    let q = c.closest_point([2.0, -1.0]);
    assert!(q.t == 0.0 && distance(q.point, [1.0, 0.0]) < 1e-15);
}

#[test]
fn projection_on_a_wiggly_spline_beats_dense_sampling() {
    let curves = read_gismo_curves(data("puzzle3_bdry.xml")).unwrap();
    let c = Curve2::spline(curves[1].clone()).unwrap();
    let dense: Vec<Point2> = (0..=20000).map(|i| c.eval(i as f64 / 20000.0)).collect();
    for k in 0..25 {
        let p = [0.3 + 0.02 * (k % 5) as f64, -0.05 + 0.1 * (k / 5) as f64];
        let q = c.closest_point(p);
        let best = dense
            .iter()
            .map(|&x| distance(x, p))
            .fold(f64::INFINITY, f64::min);
        assert!(q.distance <= best + 1e-12, "{p:?}: {} > {best}", q.distance);
        assert!(best - q.distance < 1e-4);
    }
}

#[test]
fn projection_on_a_polyline_is_exact() {
    let c = Curve2::polyline(vec![[0., 0.], [2., 0.], [2., 2.]]).unwrap();
    let q = c.closest_point([1.5, -1.0]);
    assert_eq!(q.point, [1.5, 0.0]);
    assert!((q.t - 0.375).abs() < 1e-15 && (q.distance - 1.0).abs() < 1e-15);
    let q = c.clone().reversed().closest_point([3.0, 1.0]);
    assert_eq!(q.point, [2.0, 1.0]);
    assert!((q.t - 0.25).abs() < 1e-15);
    let (p, d) = c.clone().reversed().eval_deriv(0.5);
    assert_eq!(p, [2.0, 0.0]);
    assert_eq!(d, [-4.0, 0.0]); // at the vertex: the next segment in the direction of travel
}

const FACES: [&str; 6] = ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"];

#[test]
fn floater_maps_every_duck_face_one_to_one() {
    let meshes: Vec<TriMesh> = FACES
        .iter()
        .map(|f| TriMesh::read_obj(data(&format!("duck_faces/{f}.obj"))).unwrap())
        .collect();
    for (k, m) in meshes.iter().enumerate() {
        assert_eq!(m.vertices.len(), 625);
        let lp = m.boundary_loop().unwrap();
        assert_eq!(lp.len(), 96, "{}", FACES[k]);
        // Corners: boundary vertices found in two other faces.
        let corners: Vec<usize> = lp
            .iter()
            .copied()
            .filter(|&v| {
                let p = m.vertices[v];
                meshes
                    .iter()
                    .enumerate()
                    .filter(|&(o, om)| o != k && om.vertices.contains(&p))
                    .count()
                    == 2
            })
            .collect();
        assert_eq!(corners.len(), 4, "{}", FACES[k]);
        let uv = floater_parameterize(m, [corners[0], corners[1], corners[2], corners[3]]).unwrap();
        let areas = signed_areas(m, &uv);
        let min = areas.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(
            min > 0.0,
            "{}: an image triangle has signed area {min}",
            FACES[k]
        );
        let total: f64 = areas.iter().sum::<f64>() / 2.0;
        assert!(
            (total - 1.0).abs() < 1e-12,
            "{}: image area {total}",
            FACES[k]
        );
        for &v in &lp {
            let [u, w] = uv[v];
            let on_edge = u.abs() < 1e-15
                || (u - 1.0).abs() < 1e-15
                || w.abs() < 1e-15
                || (w - 1.0).abs() < 1e-15;
            assert!(on_edge, "boundary vertex {v} maps inside: {:?}", uv[v]);
        }
        assert_eq!(uv[corners[2]], [1.0, 1.0]);
    }
}

#[test]
fn obj_reader_handles_slash_forms_and_reports_errors() {
    let m = TriMesh::parse_obj("# square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\nf 1/1/1 2/2/2 5/5/5\nf 2//1 3//1 5//1\nf 3 4 5\nf -2 -5 -1\n").unwrap();
    assert_eq!(m.triangles.len(), 4);
    assert_eq!(m.triangles[3], [3, 0, 4]);
    assert_eq!(m.boundary_loop().unwrap(), vec![0, 1, 2, 3]);
    let uv = floater_parameterize(&m, [0, 1, 2, 3]).unwrap();
    assert!((uv[4][0] - 0.5).abs() < 1e-12 && (uv[4][1] - 0.5).abs() < 1e-12);
    let e = floater_parameterize(&m, [0, 2, 1, 3]).unwrap_err();
    assert!(e.message.contains("order"), "{}", e.message);
    let e = TriMesh::parse_obj("v 0 0 0\nv 1 0 0\nf 1 2 3\n").unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidMesh);
    let e = TriMesh::parse_obj("v 0 nan 0\n").unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotFinite);
    let e = TriMesh::parse_obj("v 0 0\n").unwrap_err();
    assert_eq!(e.kind, ErrorKind::Io);
    assert!(e.message.contains("line 1"), "{}", e.message);
}

#[test]
fn curve2_derivatives_match_finite_differences_both_ways() {
    let curves = read_gismo_curves(data("rotor_bdry.xml")).unwrap();
    for c in curves {
        let fwd = Curve2::spline(c).unwrap();
        for cur in [fwd.clone(), fwd.reversed()] {
            let h = 1e-6;
            for i in 1..50 {
                let t = i as f64 / 50.0 + 0.003;
                let [_, d1, d2] = cur.derivs2(t);
                let (a, b) = (cur.derivs2(t - h), cur.derivs2(t + h));
                for k in 0..2 {
                    let fd1 = (b[0][k] - a[0][k]) / (2.0 * h);
                    let fd2 = (b[1][k] - a[1][k]) / (2.0 * h);
                    assert!((fd1 - d1[k]).abs() < 1e-5 * (1.0 + d1[k].abs()), "t={t}");
                    assert!(
                        (fd2 - d2[k]).abs() < 1e-3 * (1.0 + d2[k].abs()),
                        "t={t}: {fd2} vs {}",
                        d2[k]
                    );
                }
            }
        }
    }
}

#[test]
fn duck_faces_map_consistently_into_the_cube() {
    let cube = CubeFaces::read_dir(data("duck_faces")).unwrap();
    let params = cube.parameterize().unwrap();
    // The same point gets the same cube coordinates from every face holding it.
    let mut seen: std::collections::HashMap<[u64; 3], [f64; 3]> = Default::default();
    let mut shared = 0;
    for (f, m) in cube.faces.iter().enumerate() {
        let axis = f / 2;
        for (v, p) in m.vertices.iter().enumerate() {
            let x = params[f][v];
            assert_eq!(x[axis], (f % 2) as f64);
            assert!(x.iter().all(|&c| (-1e-15..=1.0 + 1e-15).contains(&c)));
            if let Some(y) = seen.insert(p.map(f64::to_bits), x) {
                shared += 1;
                for d in 0..3 {
                    assert!(
                        (x[d] - y[d]).abs() < 1e-12,
                        "{}: {x:?} vs {y:?}",
                        CUBE_FACE_NAMES[f]
                    );
                }
            }
        }
        // One-to-one on the face: the image triangles all have the same orientation.
        let (a, b) = [(1, 2), (0, 2), (0, 1)][axis];
        let uv: Vec<Point2> = params[f].iter().map(|x| [x[a], x[b]]).collect();
        let areas = signed_areas(m, &uv);
        let pos = areas.iter().filter(|&&s| s > 0.0).count();
        let neg = areas.iter().filter(|&&s| s < 0.0).count();
        assert!(
            pos == areas.len() || neg == areas.len(),
            "{}: {pos} +, {neg} -",
            CUBE_FACE_NAMES[f]
        );
    }
    // 12 edges of 25 vertices: 8 corners seen 3 times, 12 × 23 edge vertices seen twice.
    assert_eq!(shared, 8 * 2 + 12 * 23);
    // The corner shared by xmin, ymin and zmin is (0,0,0).
    let m = &cube.faces[0];
    let origin = (0..m.vertices.len())
        .find(|&v| params[0][v] == [0.0, 0.0, 0.0])
        .unwrap();
    let p = m.vertices[origin];
    assert!(cube.faces[2].vertices.contains(&p) && cube.faces[4].vertices.contains(&p));
}

#[test]
fn gismo_reader_reads_a_nurbs_circle() {
    let xml = r#"<?xml version="1.0"?>
<xml>
 <Geometry type="Nurbs" id="7">
  <Basis type="NurbsBasis">
   <Basis type="BSplineBasis">
    <KnotVector degree="2">0 0 0 1 1 1</KnotVector>
   </Basis>
   <weights>1
     0.7071067811865476 1</weights>
  </Basis>
  <coefs geoDim="2">1 0
   1 1
   0 1</coefs>
 </Geometry>
</xml>"#;
    let g = parse_gismo_xml(xml).unwrap();
    let GismoGeometry::Curve(c) = &g[0] else {
        panic!("expected a curve")
    };
    assert!(c.weights().is_some());
    let p = c.eval(0.37);
    assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-15);
    let e = parse_gismo_xml(
        &xml.replace("<weights>1", "<nothing>1")
            .replace("</weights>", "</nothing>"),
    )
    .unwrap_err();
    assert!(e.message.contains("weights"), "{}", e.message);
}

#[test]
fn boundary_map_at_unit_square_points() {
    let l = BoundaryLoop2::from_gismo_file(data("duck2d_BRep.xml")).unwrap();
    assert_eq!(l.eval_at([0.0, 0.3]).unwrap(), l.eval(Side::U0, 0.3));
    assert_eq!(l.eval_at([0.7, 1.0]).unwrap(), l.eval(Side::V1, 0.7));
    assert_eq!(l.eval_at([1.0, 1.0]).unwrap(), l.corners()[2]);
    let e = l.eval_at([0.5, 0.5]).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidArgument);
    assert!(e.message.contains("not on the boundary"), "{}", e.message);
    assert_eq!(
        l.eval_at([f64::NAN, 0.0]).unwrap_err().kind,
        ErrorKind::NotFinite
    );
}
