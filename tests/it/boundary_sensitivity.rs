//! Sensitivities of a spline map's control points to its domain's boundary
//! (`SplineMap::boundary_tangent` / `boundary_adjoint`): against central finite differences of
//! update + refit along a morph of the boundary, and the adjoint as the tangent's transpose.

use crate::common;
use crate::morph_cases as morph;

use common::{curved_box, MappedCube};
use igaparam::boundary::{BSplineCurve, BSplineSurface, SolidBoundary};
use igaparam::domain::{
    BoundaryControls, CubeMap, Domain, DomainOptions, PlanarDomain, SolidDomain, UpdateOptions,
};
use igaparam::spline::{FitRecord, FitRule, SplineMap, ValidityOptions};

/// Options whose T-mesh is a stationary point with every boundary vertex on the boundary.
fn stationary(tolerance: f64, max_level: u8) -> DomainOptions {
    DomainOptions {
        tolerance,
        max_level,
        boundary_offset: 0.0,
        stationarity_tolerance: 1e-12,
        ..DomainOptions::default()
    }
}

/// Updates `domain` onto `boundary` and refits `map` (fitted to the domain's first state) with
/// `record`; returns the control points and the updated T-mesh's vertex positions. The update
/// ends at the stationary point of the new boundary whatever state it starts from.
fn refit_after_update<const D: usize, B: CubeMap<D>>(
    domain: &mut Domain<D, B>,
    map: &SplineMap<D>,
    record: &FitRecord,
    boundary: B,
) -> (Vec<[f64; D]>, Vec<[f64; D]>) {
    domain
        .update(boundary, &UpdateOptions::default(), &mut |_, _| true)
        .expect("update");
    let mut map = map.clone();
    let (report, _, next) = map
        .refit_tmesh(
            domain.mesh(),
            domain.positions(),
            Some(record),
            &ValidityOptions::default(),
            &morph::untangle(domain),
        )
        .expect("refit");
    assert_eq!(report.untangled, 0, "the refit untangled");
    assert!(next.differentiable);
    (map.control_points().to_vec(), domain.positions().to_vec())
}

/// `(a − b) / (2h)`, point by point.
fn central<const D: usize>(a: &[[f64; D]], b: &[[f64; D]], h: f64) -> Vec<[f64; D]> {
    a.iter()
        .zip(b)
        .map(|(p, q)| std::array::from_fn(|k| (p[k] - q[k]) / (2.0 * h)))
        .collect()
}

fn dot<const D: usize>(a: &[[f64; D]], b: &[[f64; D]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (0..D).map(|k| p[k] * q[k]).sum::<f64>())
        .sum()
}

fn max_abs<const D: usize>(a: &[[f64; D]]) -> f64 {
    a.iter().flatten().fold(0.0, |m, v| m.max(v.abs()))
}

/// Deterministic weights in [−1, 1] for a scalar of the control points.
fn weights<const D: usize>(n: usize) -> Vec<[f64; D]> {
    (0..n)
        .map(|i| std::array::from_fn(|k| ((7 * i + 3 * k) % 13) as f64 / 6.0 - 1.0))
        .collect()
}

/// A differentiable fit of a domain at its first boundary, and the central differences of
/// update + refit along a morph.
struct Differences<const D: usize> {
    map: SplineMap<D>,
    record: FitRecord,
    /// Of the refitted control points.
    fd: Vec<[f64; D]>,
    /// Of the T-mesh's vertices (at the boundary vertices, their motion).
    boundary_motion: Vec<[f64; D]>,
}

/// Fits `domain` (refitting once if the fit untangled), takes central differences of update +
/// refit along `morph(s)` at s = ±h, and moves the domain back to `morph(0)`, where it is at
/// its first stationary point again.
fn differences<const D: usize, B: CubeMap<D>>(
    domain: &mut Domain<D, B>,
    morph: impl Fn(f64) -> B,
    h: f64,
) -> Differences<D> {
    let (mut map, mut record) = morph::fit(domain);
    if !record.differentiable {
        // The first fit untangled: a refit to the same T-mesh carries the untangling's
        // correction as a constant, and the map is linear in the T-mesh again.
        let (_, _, next) = map
            .refit_tmesh(
                domain.mesh(),
                domain.positions(),
                Some(&record),
                &ValidityOptions::default(),
                &morph::untangle(domain),
            )
            .expect("refit");
        record = next;
    }
    assert!(record.differentiable, "the refit untangled again");
    let before = domain.positions().to_vec();
    let (plus, x_plus) = refit_after_update(domain, &map, &record, morph(h));
    let (minus, x_minus) = refit_after_update(domain, &map, &record, morph(-h));
    domain
        .update(morph(0.0), &UpdateOptions::default(), &mut |_, _| true)
        .expect("update back");
    let back = max_abs(&central(domain.positions(), &before, 0.5));
    assert!(
        back < 1e-9 * domain.frame().diagonal(),
        "back by {back:.3e}"
    );
    let fd = central(&plus, &minus, h);
    assert!(max_abs(&fd) > 0.0, "the morph moves no control point");
    Differences {
        map,
        record,
        fd,
        // The boundary vertices at fixed parameters are linear in the control points, so
        // their central difference is their motion (the inner vertices' entries are ignored).
        boundary_motion: central(&x_plus, &x_minus, h),
    }
}

/// Checks that `tangent` agrees with the central differences `fd` to a relative 1e-6.
fn close_to_differences<const D: usize>(tangent: &[[f64; D]], fd: &[[f64; D]]) {
    let scale = max_abs(fd);
    let error = max_abs(&central(tangent, fd, 0.5));
    assert!(
        error <= 1e-6 * scale,
        "tangent vs finite differences: {error:.3e} of {scale:.3e}"
    );
}

/// Checks the tangent against central differences of update + refit along `morph(s)` at
/// s = ±h, and the adjoint against the tangent (`w · dP = adjoint(w) · dX_b`).
fn check<const D: usize, B: CubeMap<D>>(
    mut domain: Domain<D, B>,
    morph: impl Fn(f64) -> B,
    h: f64,
) {
    let Differences {
        map,
        record,
        fd,
        boundary_motion,
    } = differences(&mut domain, morph, h);
    let tangent = map
        .boundary_tangent(&domain, &record, 1, &boundary_motion)
        .expect("tangent");
    close_to_differences(&tangent, &fd);
    if record.rule != FitRule::QuasiInterpolation {
        let w = weights::<D>(map.basis_count());
        let adjoint = map
            .boundary_adjoint(&domain, &record, 2, &w)
            .expect("adjoint");
        let (a, b) = (dot(&w, &tangent), dot(&adjoint, &boundary_motion));
        assert!(
            (a - b).abs() <= 1e-9 * a.abs().max(b.abs()),
            "w·dP = {a:.15e}, adjoint·dX_b = {b:.15e}"
        );
        for (v, g) in adjoint.iter().enumerate() {
            if !domain.mesh().on_boundary(v) {
                assert_eq!(*g, [0.0; D], "inner vertex {v} has a total derivative");
            }
        }
    }
}

/// Checks the tangent with respect to the boundary's control points, for the motion `dc` of
/// them that `morph` makes per unit of s, against central differences of update + refit, and
/// its adjoint against it (`w · dP = adjoint(w) · dc`).
fn check_controls<const D: usize, B: BoundaryControls<D>>(
    mut domain: Domain<D, B>,
    morph: impl Fn(f64) -> B,
    dc: &[[f64; D]],
    h: f64,
) {
    let Differences {
        map, record, fd, ..
    } = differences(&mut domain, morph, h);
    let tangent = map
        .control_tangent(&domain, &record, 1, dc)
        .expect("tangent");
    close_to_differences(&tangent, &fd);
    let w = weights::<D>(map.basis_count());
    let adjoint = map
        .control_adjoint(&domain, &record, 2, &w)
        .expect("adjoint");
    let (a, b) = (dot(&w, &tangent), dot(&adjoint, dc));
    assert!(
        (a - b).abs() <= 1e-9 * a.abs().max(b.abs()),
        "w·dP = {a:.15e}, adjoint·dc = {b:.15e}"
    );
}

/// The control points of curves, concatenated in their order.
fn curve_controls(curves: &[BSplineCurve]) -> Vec<[f64; 2]> {
    curves
        .iter()
        .flat_map(|c| {
            (0..c.num_control_points()).map(move |i| {
                let p = c.control_point(i);
                [p[0], p[1]]
            })
        })
        .collect()
}

/// The box [0,2]×[0,1]×[0,1] as six biquadratic B-spline surfaces, the middle control point of
/// the top face raised by `0.3 s`.
fn box_surfaces(s: f64) -> Vec<BSplineSurface> {
    let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    (0..6)
        .map(|face| {
            let (axis, a, b) = match face / 2 {
                0 => (0, 1, 2),
                1 => (1, 0, 2),
                _ => (2, 0, 1),
            };
            let mut coefs = Vec::new();
            for j in 0..3 {
                for i in 0..3 {
                    let mut p = [0.0; 3];
                    p[axis] = (face % 2) as f64;
                    p[a] = i as f64 / 2.0;
                    p[b] = j as f64 / 2.0;
                    p[0] *= 2.0;
                    if face == 5 && i == 1 && j == 1 {
                        p[2] += 0.3 * s;
                    }
                    coefs.extend_from_slice(&p);
                }
            }
            BSplineSurface::new((2, knots.clone()), (2, knots.clone()), 3, coefs, None).unwrap()
        })
        .collect()
}

#[test]
fn puzzle_control_points_follow_its_curves_control_points() {
    let curves = morph::puzzle_curves();
    let boundary = |s: f64| morph::planar(&morph::grown_puzzle(&curves, s));
    let (domain, _) =
        PlanarDomain::build(boundary(0.0), &stationary(1e-5, 9), &mut |_, _| true).unwrap();
    // The knob grows linearly in s: its control points move by grown(1) − grown(0) per unit.
    let dc = central(
        &curve_controls(&morph::grown_puzzle(&curves, 1.0)),
        &curve_controls(&curves),
        0.5,
    );
    assert_eq!(dc.len(), domain.boundary().control_count().unwrap());
    check_controls(domain, boundary, &dc, 1e-4);
}

#[test]
fn box_control_points_follow_its_top_surface_control_point() {
    let boundary = |s: f64| SolidBoundary::from_surfaces(box_surfaces(s)).unwrap();
    let (domain, report) =
        SolidDomain::build(boundary(0.0), &stationary(1e-3, 3), &mut |_, _| true).unwrap();
    assert!(
        report.gradient_norm <= 1e-12 && report.invalid_cells == 0,
        "{report:?}"
    );
    let mut dc = vec![[0.0; 3]; domain.boundary().control_count().unwrap()];
    dc[5 * 9 + 4] = [0.0, 0.0, 0.3];
    check_controls(domain, boundary, &dc, 1e-4);
}

#[test]
fn control_sensitivities_are_refused_for_polylines() {
    let boundary = common::mapped_square(|[u, v]| [u + 0.1 * v, v], 8);
    let (domain, _) =
        PlanarDomain::build(boundary, &stationary(1e-4, 5), &mut |_, _| true).unwrap();
    let (map, record) = morph::fit(&domain);
    let error = map
        .control_adjoint(&domain, &record, 1, &vec![[0.0; 2]; map.basis_count()])
        .unwrap_err();
    assert!(error.message.contains("polylines"), "{error}");
}

#[test]
fn puzzle_control_points_follow_the_knob_as_finite_differences_say() {
    let curves = morph::puzzle_curves();
    let boundary = |s: f64| -> igaparam::boundary::BoundaryLoop2 {
        morph::planar(&morph::grown_puzzle(&curves, s))
    };
    let (domain, report) =
        PlanarDomain::build(boundary(0.0), &stationary(1e-5, 9), &mut |_, _| true).unwrap();
    assert!(report.gradient_norm <= 1e-12 && report.invalid_cells == 0);
    check(domain, boundary, 1e-4);
}

/// The curved box of the solid tests with its top bulging by `1 + s/10` in the middle.
fn bulging_box(s: f64) -> MappedCube<impl Fn([f64; 3]) -> [f64; 3]> {
    MappedCube(move |p: [f64; 3]| {
        let [x, y, z] = curved_box(p);
        let bump = (std::f64::consts::PI * p[0]).sin() * (std::f64::consts::PI * p[1]).sin();
        [x, y, z * (1.0 + 0.1 * s * bump * p[2])]
    })
}

#[test]
fn solid_control_points_follow_a_bulging_face_as_finite_differences_say() {
    let (domain, report) =
        Domain::build(bulging_box(0.0), &stationary(1e-3, 3), &mut |_, _| true).unwrap();
    assert!(
        report.gradient_norm <= 1e-12 && report.invalid_cells == 0,
        "{report:?}"
    );
    check(domain, bulging_box, 1e-4);
}

#[test]
fn sensitivities_are_refused_without_the_polish_or_with_relief_offsets() {
    let curves: Vec<BSplineCurve> = morph::puzzle_curves();
    let options = DomainOptions {
        boundary_offset: 0.0,
        ..DomainOptions::default()
    };
    let (domain, _) =
        PlanarDomain::build(morph::planar(&curves), &options, &mut |_, _| true).unwrap();
    let (map, record) = morph::fit(&domain);
    let motion = vec![[0.0; 2]; domain.mesh().vertex_count()];
    let error = map
        .boundary_tangent(&domain, &record, 1, &motion)
        .unwrap_err();
    assert!(error.message.contains("stationarity_tolerance"), "{error}");
    let w = vec![[0.0; 2]; map.basis_count() + 1];
    let polished = stationary(1e-5, 9);
    let (domain, _) =
        PlanarDomain::build(morph::planar(&curves), &polished, &mut |_, _| true).unwrap();
    let error = map.boundary_adjoint(&domain, &record, 1, &w).unwrap_err();
    assert!(error.message.contains("control points"), "{error}");
    let untangled = FitRecord {
        differentiable: false,
        ..record
    };
    let error = map
        .boundary_tangent(&domain, &untangled, 1, &motion)
        .unwrap_err();
    assert!(error.message.contains("untangled"), "{error}");
}
