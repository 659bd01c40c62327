//! The checked fit with options (`SplineMap::fit_checked_with`): the default options give the
//! plain checked fit bit for bit, the result does not depend on the thread count, the progress
//! callback sees every stage in order and cancels at any of them, and the switches do what
//! they say.

use std::f64::consts::PI;

use igaparam::boundary::BoundaryLoop2;
use igaparam::domain::{PlanarDomain, PlanarOptions};
use igaparam::error::ErrorKind;
use igaparam::spline::{
    FitChoice, FitOptions, FitStage, SplineMap, ThbSpace, UntangleOptions, ValidityOptions,
};
use igaparam::tmesh::Tree;

/// The uniform space of level 3 on the unit square.
fn space() -> ThbSpace<2> {
    let mut tree = Tree::<2>::new();
    tree.refine_uniformly(3).unwrap();
    ThbSpace::new(tree).unwrap()
}

/// A map of the unit square onto itself (the boundary is the identity's) whose Jacobian
/// determinant `1 + a cos(2πx) sin²(πy)` is negative around the centre for `a > 1`.
fn folding(a: f64) -> impl Fn([f64; 2]) -> Option<[f64; 2]> + Sync {
    move |[x, y]| {
        Some([
            x + a * (2.0 * PI * x).sin() * (PI * y).sin().powi(2) / (2.0 * PI),
            y,
        ])
    }
}

type Calls = Vec<(FitStage, usize, usize)>;

/// The checked fit of `folding(a)` with `options`, and the progress calls it made.
fn fit(a: f64, options: &FitOptions) -> (igaparam::error::Result<(SplineMap<2>, bool)>, Calls) {
    let mut calls = Vec::new();
    let result = SplineMap::fit_checked_with(space(), folding(a), options, &mut |s, d, t| {
        calls.push((s, d, t));
        true
    });
    let result = result.map(|(map, _, validity)| (map, validity.certified_positive));
    (result, calls)
}

#[test]
fn default_options_give_the_plain_checked_fit() {
    let options = FitOptions::default();
    for a in [0.5, 1.4] {
        let (plain, report, validity) = SplineMap::fit_checked(
            space(),
            folding(a),
            &ValidityOptions::default(),
            &UntangleOptions::default(),
        )
        .unwrap();
        let (with, with_report, with_validity) =
            SplineMap::fit_checked_with(space(), folding(a), &options, &mut |_, _, _| true)
                .unwrap();
        assert_eq!(plain.control_points(), with.control_points());
        assert_eq!(validity, with_validity);
        assert_eq!(report.untangled, with_report.untangled);
        assert_eq!(report.smoothed, with_report.smoothed);
    }
}

#[test]
fn threads_do_not_change_the_fit() {
    let one = FitOptions {
        threads: 1,
        ..Default::default()
    };
    let two = FitOptions {
        threads: 2,
        ..Default::default()
    };
    let (a, calls_one) = fit(1.4, &one);
    let (b, calls_two) = fit(1.4, &two);
    assert_eq!(a.unwrap().0.control_points(), b.unwrap().0.control_points());
    assert_eq!(calls_one, calls_two);
}

#[test]
fn progress_sees_every_stage_in_order() {
    let (result, calls) = fit(1.4, &FitOptions::default());
    let (_, certified) = result.unwrap();
    let stage = |s: FitStage| calls.iter().filter(|c| c.0 == s).collect::<Vec<_>>();
    let fits = stage(FitStage::Fit);
    // The interpolation folds: both rules are fitted and certified, 0..=4 of 4.
    assert_eq!(
        fits.iter().map(|c| (c.1, c.2)).collect::<Vec<_>>(),
        (0..=4).map(|d| (d, 4)).collect::<Vec<_>>()
    );
    let untangling = stage(FitStage::Untangling);
    assert!(!untangling.is_empty(), "{calls:?}");
    assert!(untangling
        .windows(2)
        .all(|w| w[0].1 < w[1].1 && w[0].2 == w[1].2));
    assert!(certified, "the untangled map is certified");
    assert!(!stage(FitStage::Smoothing).is_empty());
    // Stages come in order: fit, untangling, smoothing.
    let order: Vec<FitStage> = calls.iter().map(|c| c.0).collect();
    let first = |s| order.iter().position(|&x| x == s).unwrap();
    let last = |s| order.iter().rposition(|&x| x == s).unwrap();
    assert!(last(FitStage::Fit) < first(FitStage::Untangling));
    assert!(last(FitStage::Untangling) < first(FitStage::Smoothing));
    // A map certified as fitted: one rule, 0..=2 of 2 ... no untangling.
    let (result, calls) = fit(0.3, &FitOptions::default());
    assert!(result.unwrap().1);
    assert_eq!(calls[0], (FitStage::Fit, 0, 4));
    assert!(calls.iter().all(|c| c.0 != FitStage::Untangling));
}

#[test]
fn every_stage_can_cancel() {
    for (stage, a) in [
        (FitStage::Fit, 1.4),
        (FitStage::Untangling, 1.4),
        (FitStage::Smoothing, 0.3),
    ] {
        for threads in [0, 2] {
            let options = FitOptions {
                threads,
                ..Default::default()
            };
            let result =
                SplineMap::fit_checked_with(space(), folding(a), &options, &mut |s, _, _| {
                    s != stage
                });
            let error = result.map(|_| ()).expect_err("cancelled");
            assert_eq!(error.kind, ErrorKind::Cancelled, "{stage:?}");
        }
    }
}

#[test]
fn switches_do_what_they_say() {
    // No untangling: the folded fit is returned as it is, uncertified.
    let options = FitOptions {
        untangle: UntangleOptions {
            rounds: 0,
            ..Default::default()
        },
        ..Default::default()
    };
    let (result, calls) = fit(1.4, &options);
    assert!(!result.unwrap().1);
    assert!(calls.iter().all(|c| c.0 != FitStage::Untangling));
    // No smoothing.
    let options = FitOptions {
        untangle: UntangleOptions {
            smoothing_sweeps: 0,
            ..Default::default()
        },
        ..Default::default()
    };
    let (map, report, _) =
        SplineMap::fit_checked_with(space(), folding(0.3), &options, &mut |_, _, _| true).unwrap();
    assert_eq!(report.smoothed, 0);
    let (plain, _) = SplineMap::fit(space(), folding(0.3)).unwrap();
    assert_eq!(map.control_points(), plain.control_points());
    // One rule each: the flags say which, two fit steps.
    for (choice, quasi) in [
        (FitChoice::Interpolation, false),
        (FitChoice::QuasiInterpolation, true),
    ] {
        let options = FitOptions {
            choice,
            ..Default::default()
        };
        let mut calls = Vec::new();
        let (_, report, _) =
            SplineMap::fit_checked_with(space(), folding(1.4), &options, &mut |s, d, t| {
                calls.push((s, d, t));
                true
            })
            .unwrap();
        assert_eq!(report.quasi_interpolation, quasi, "{choice:?}");
        assert_eq!(calls[0], (FitStage::Fit, 0, 2));
    }
    // Out of range.
    let mut options = FitOptions::default();
    options.validity.samples = 1;
    assert_eq!(
        fit(0.3, &options).0.err().unwrap().kind,
        ErrorKind::InvalidArgument
    );
    for power in [0.5, 16.5, f64::NAN, f64::INFINITY] {
        let mut options = FitOptions::default();
        options.untangle.smoothing_power = power;
        let error = fit(0.3, &options).0.err().unwrap();
        assert_eq!(error.kind, ErrorKind::InvalidArgument, "{power}");
        assert!(
            error.message.contains("smoothing_power"),
            "{}",
            error.message
        );
    }
}

/// The smoothing's exponent, on the rotor's T-mesh: the default (p = 4 for a planar map) lifts the smallest
/// sampled mean ratio of the certified map above that of the mean-distortion smoothing (p = 1),
/// which lifts it above the map as fitted; all are certified.
#[test]
fn a_higher_smoothing_power_lifts_the_worst_quality() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/boundary/rotor_bdry.xml"
    );
    let boundary = BoundaryLoop2::from_gismo_file(path).unwrap();
    let (domain, _) =
        PlanarDomain::build(boundary, &PlanarOptions::default(), &mut |_, _| true).unwrap();
    let with = |sweeps: u32, power: f64| {
        let options = FitOptions {
            untangle: UntangleOptions {
                smoothing_sweeps: sweeps,
                smoothing_power: power,
                ..Default::default()
            },
            ..Default::default()
        };
        let (_, report, validity) = SplineMap::fit_tmesh_with(
            domain.mesh(),
            domain.positions(),
            &options,
            &mut |_, _, _| true,
        )
        .unwrap();
        assert!(validity.certified_positive);
        (validity.min_quality, report.smoothed)
    };
    let (fitted, _) = with(0, 0.0);
    let (mean, _) = with(8, 1.0);
    let (power, moved) = with(8, 0.0);
    assert_eq!(
        power,
        with(8, 4.0).0,
        "the automatic power of a planar map is 4"
    );
    assert!(moved > 0);
    assert!(
        fitted < mean && 1.5 * mean < power,
        "{fitted} {mean} {power}"
    );
}
