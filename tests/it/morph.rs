//! Shape-optimization loops: boundaries from arrays, the boundary of a built domain moved with
//! its tree kept (`Domain::update`), and the spline map refitted in the same space
//! (`SplineMap::refit_tmesh`).

use crate::common;
use crate::morph_cases as morph;

use common::{curved_box, MappedCube};
use igaparam::boundary::{BSplineCurve, BoundaryLoop2, SolidBoundary};
use igaparam::domain::{
    CubeMap, Domain, DomainOptions, DomainReport, PlanarDomain, SolidDomain, UpdateOptions,
    UpdateReport,
};
use igaparam::spline::{FitRecord, FitRule, SplineMap, ThbSpace, ValidityOptions, ValidityReport};
use morph::{elements, fit, untangle};

fn none() -> impl FnMut(usize, usize) -> bool {
    |_, _| true
}

/// Refits `map` to the domain with `record`, keeping the rule; returns the validity and the
/// record of the next refit.
fn refit<const D: usize, B: CubeMap<D>>(
    map: &mut SplineMap<D>,
    domain: &Domain<D, B>,
    record: &FitRecord,
) -> (ValidityReport, FitRecord) {
    let (_, validity, next) = map
        .refit_tmesh(
            domain.mesh(),
            domain.positions(),
            Some(record),
            &ValidityOptions::default(),
            &untangle(domain),
        )
        .expect("refit");
    assert_eq!(next.rule, record.rule, "the refit changed the rule");
    (validity, next)
}

/// The puzzle piece built with the default options.
fn puzzle() -> (PlanarDomain, DomainReport) {
    let boundary = morph::planar(&morph::puzzle_curves());
    PlanarDomain::build(boundary, &DomainOptions::default(), &mut none()).unwrap()
}

/// Runs `steps` steps of a morph (`boundary(s)`, s from 0 to 1), each checked by
/// [`morph::Loop::step`]; returns the last update's report.
fn morph_loop<const D: usize, B: CubeMap<D>>(
    options: &DomainOptions,
    steps: usize,
    boundary: impl Fn(f64) -> B,
) -> UpdateReport {
    let mut morph = morph::Loop::new(boundary(0.0), options);
    let mut last = UpdateReport::default();
    for i in 1..=steps {
        let step = morph.step(boundary(i as f64 / steps as f64), &UpdateOptions::default());
        assert!(step.update.boundary_motion > 0.0, "step {i}: nothing moved");
        last = step.update;
    }
    last
}

/// The largest coordinate difference of two lists of points.
fn max_difference<const D: usize>(a: &[[f64; D]], b: &[[f64; D]]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| (0..D).map(move |k| (p[k] - q[k]).abs()))
        .fold(0.0, f64::max)
}

#[test]
fn a_domain_from_curve_arrays_equals_the_one_read_from_their_file() {
    let curves = morph::puzzle_curves();
    // The same numbers through the arrays a host passes.
    let arrays: Vec<BSplineCurve> = curves
        .iter()
        .map(|c| {
            let coefs = (0..c.num_control_points())
                .flat_map(|i| c.control_point(i)[..2].to_vec())
                .collect();
            BSplineCurve::new(c.degree(), c.knot_vector().knots().to_vec(), 2, coefs, None).unwrap()
        })
        .collect();
    let options = DomainOptions::default();
    let path = common::boundary_data("puzzle3_bdry.xml");
    let (read, _) = PlanarDomain::build(
        BoundaryLoop2::from_gismo_file(path).unwrap(),
        &options,
        &mut none(),
    )
    .unwrap();
    let (made, _) = PlanarDomain::build(morph::planar(&arrays), &options, &mut none()).unwrap();
    assert!(read.positions() == made.positions(), "the T-meshes differ");
}

#[test]
fn an_update_to_the_same_boundary_keeps_the_tolerance_and_the_t_mesh() {
    let curves = morph::puzzle_curves();
    let (mut domain, built) = puzzle();
    let before = domain.positions().to_vec();
    let report = domain
        .update(
            morph::planar(&curves),
            &UpdateOptions::default(),
            &mut none(),
        )
        .unwrap();
    assert!(report.tolerance_met && report.cells_over_tolerance == 0);
    assert_eq!(report.boundary_motion, 0.0);
    assert_eq!(report.domain.cells, built.cells);
    assert_eq!(report.domain.invalid_cells, 0);
    assert_eq!(report.domain.boundary_error, built.boundary_error);
    // The optimum it started from moves by less than the sweeps' move tolerance.
    let size = domain.frame().diagonal();
    let moved = max_difference(&before, domain.positions());
    assert!(moved < 1e-2 * size, "moved by {moved}");
}

#[test]
fn the_puzzle_morphs_in_20_steps_with_the_same_space() {
    let curves = morph::puzzle_curves();
    let last = morph_loop(&DomainOptions::default(), 20, |s| {
        morph::planar(&morph::grown_puzzle(&curves, s))
    });
    // The knob grew 20% out: finer cells would be needed for the tolerance of the build.
    assert!(!last.tolerance_met && last.cells_over_tolerance > 0);
}

#[test]
fn the_duck_morphs_in_20_steps_with_the_same_space() {
    let surfaces = morph::duck_surfaces();
    morph_loop(&DomainOptions::solid(), 20, |s| {
        morph::solid(&morph::scaled_duck(&surfaces, s))
    });
}

#[test]
fn updates_are_the_same_for_any_thread_count() {
    let curves = morph::puzzle_curves();
    let run = |threads: usize| {
        let options = DomainOptions {
            threads,
            ..Default::default()
        };
        let (mut domain, _) =
            PlanarDomain::build(morph::planar(&curves), &options, &mut none()).unwrap();
        let update = UpdateOptions {
            threads,
            ..Default::default()
        };
        let grown = morph::planar(&morph::grown_puzzle(&curves, 0.5));
        let report = domain.update(grown, &update, &mut none()).unwrap();
        (domain.positions().to_vec(), report.domain.sweeps)
    };
    assert!(run(1) == run(2));
}

#[test]
fn refine_restores_the_tolerance_and_the_old_space_no_longer_refits() {
    let curves = morph::puzzle_curves();
    let (mut domain, built) = puzzle();
    let (mut map, record) = fit(&domain);
    let options = UpdateOptions {
        refine: true,
        ..Default::default()
    };
    let grown = morph::planar(&morph::grown_puzzle(&curves, 1.0));
    let report = domain.update(grown, &options, &mut none()).unwrap();
    assert!(report.tolerance_met, "{report:?}");
    assert!(report.refined_cells > 0 && report.domain.cells > built.cells);
    assert_eq!(report.domain.invalid_cells, 0);
    let old = map.control_points().to_vec();
    let error = map
        .refit_tmesh(
            domain.mesh(),
            domain.positions(),
            Some(&record),
            &ValidityOptions::default(),
            &untangle(&domain),
        )
        .unwrap_err();
    assert!(error.message.contains("refined after"), "{}", error.message);
    assert!(
        map.control_points() == old,
        "a failed refit changed the map"
    );
}

#[test]
fn a_mirrored_boundary_is_refused_and_the_domain_kept() {
    type Map = MappedCube<fn([f64; 3]) -> [f64; 3]>;
    let options = DomainOptions {
        tolerance: 1e-2,
        max_level: 3,
        ..DomainOptions::solid()
    };
    let (mut domain, _) =
        Domain::<3, Map>::build(MappedCube(curved_box), &options, &mut none()).unwrap();
    let before = domain.positions().to_vec();
    let mirrored: Map = MappedCube(|[x, y, z]| curved_box([1.0 - x, y, z]));
    let error = domain
        .update(mirrored, &UpdateOptions::default(), &mut none())
        .unwrap_err();
    assert!(error.message.contains("oriented"), "{}", error.message);
    assert!(domain.positions() == before);
    let flat: Map = MappedCube(|[x, y, _]| [x, y, 0.0]);
    let error = domain.check_boundary(&flat).unwrap_err();
    assert!(error.message.contains("extent"), "{}", error.message);
    // A cancelled update leaves the domain as it was.
    let grown: Map = MappedCube(|p| curved_box(p).map(|v| 1.1 * v));
    let error = domain
        .update(grown, &UpdateOptions::default(), &mut |_, _| false)
        .unwrap_err();
    assert_eq!(error.kind, igaparam::ErrorKind::Cancelled);
    assert!(domain.positions() == before);
}

/// The control points of `fit_by_rule` at positions `x` of the puzzle's T-mesh.
fn fit_at(domain: &PlanarDomain, rule: FitRule, x: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let source = igaparam::spline::QuadraticMap::new(domain.mesh(), x).unwrap();
    let space = ThbSpace::new(domain.mesh().tree().clone()).unwrap();
    let (map, report) = SplineMap::fit_by_rule(space, rule, |p| source.eval(p)).unwrap();
    assert_eq!(FitRule::of(&report), rule);
    map.control_points().to_vec()
}

#[test]
fn each_fit_rule_is_linear_in_the_t_mesh_vertices() {
    let (domain, _) = puzzle();
    let x = domain.positions();
    let mut lcg = common::Lcg(7);
    let dx: Vec<[f64; 2]> = x.iter().map(|_| [lcg.next(), lcg.next()]).collect();
    let combined: Vec<[f64; 2]> = x
        .iter()
        .zip(&dx)
        .map(|(p, d)| [p[0] + 0.5 * d[0], p[1] + 0.5 * d[1]])
        .collect();
    for rule in [
        FitRule::Interpolation,
        FitRule::LeastSquares,
        FitRule::QuasiInterpolation,
    ] {
        let (a, b, c) = (
            fit_at(&domain, rule, x),
            fit_at(&domain, rule, &dx),
            fit_at(&domain, rule, &combined),
        );
        let error = (0..a.len())
            .flat_map(|i| (0..2).map(move |k| (i, k)))
            .map(|(i, k)| (c[i][k] - a[i][k] - 0.5 * b[i][k]).abs())
            .fold(0.0, f64::max);
        // Round-off of the solves (the normal equations square the condition number).
        assert!(error < 1e-10, "{}: {error}", rule.name());
    }
}

#[test]
fn a_refit_of_the_fitted_t_mesh_gives_back_the_fit() {
    // The duck's first fit is untangled: its record's correction brings the rule's fit back
    // onto the untangled map.
    let surfaces = morph::duck_surfaces();
    let (domain, _) = SolidDomain::build(
        morph::solid(&surfaces),
        &DomainOptions::solid(),
        &mut none(),
    )
    .unwrap();
    let (mut map, record) = fit(&domain);
    assert!(!record.correction.is_empty());
    let first = map.control_points().to_vec();
    let (validity, _) = refit(&mut map, &domain, &record);
    assert!(validity.certified_positive);
    let scale = map.extent();
    let moved = max_difference(&first, map.control_points());
    assert!(moved <= 1e-12 * scale, "moved by {moved}");
}

#[test]
fn a_refined_spline_refits_as_the_refinement_of_the_refit() {
    let curves = morph::puzzle_curves();
    let (mut domain, _) = puzzle();
    let (coarse, record) = fit(&domain);
    let (mut fine, _) = coarse.refine_uniformly().unwrap();
    let grown = morph::planar(&morph::grown_puzzle(&curves, 0.5));
    domain
        .update(grown, &UpdateOptions::default(), &mut none())
        .unwrap();
    let mut coarse_refit = coarse.clone();
    refit(&mut coarse_refit, &domain, &record);
    let (expected, _) = coarse_refit.refine_uniformly().unwrap();
    let (basis, list) = (fine.basis_count(), elements(&fine));
    let (validity, _) = refit(&mut fine, &domain, &record);
    assert!(validity.certified_positive);
    assert_eq!(fine.basis_count(), basis);
    assert!(elements(&fine) == list);
    let scale = fine.extent();
    let error = max_difference(expected.control_points(), fine.control_points());
    assert!(error <= 1e-10 * scale, "differs by {error}");
}

#[test]
fn solids_from_surfaces_are_checked() {
    let mut surfaces = morph::duck_surfaces();
    assert!(SolidBoundary::from_surfaces(surfaces[..5].to_vec()).is_err());
    // Scaling a whole face breaks its shared edges.
    let f = &surfaces[5];
    let (ku, kv) = (f.knot_vector_u(), f.knot_vector_v());
    let (nu, nv) = f.num_control_points();
    let coefs = (0..nv)
        .flat_map(|j| (0..nu).map(move |i| (i, j)))
        .flat_map(|(i, j)| f.control_point(i, j).map(|v| 1.01 * v))
        .collect();
    surfaces[5] = igaparam::boundary::BSplineSurface::new(
        (ku.degree(), ku.knots().to_vec()),
        (kv.degree(), kv.knots().to_vec()),
        3,
        coefs,
        None,
    )
    .unwrap();
    let error = SolidBoundary::from_surfaces(surfaces).unwrap_err();
    assert_eq!(
        error.kind,
        igaparam::ErrorKind::InvalidMesh,
        "{}",
        error.message
    );
}
