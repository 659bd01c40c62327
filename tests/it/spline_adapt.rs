//! The adaptive loop on the shared planar domains: the T-mesh is refined where the spline map is
//! of poor quality until every element is certified valid with a smallest mean ratio above the
//! target (`--nocapture` prints the rounds).

use crate::common;

use common::planar_boundary;
use igaparam::domain::{PlanarDomain, PlanarOptions};
use igaparam::spline::{adapt, AdaptOptions};
use igaparam::ErrorKind;

fn domain(name: &str) -> PlanarDomain {
    PlanarDomain::build(
        planar_boundary(name),
        &PlanarOptions::default(),
        &mut |_, _| true,
    )
    .expect("domain")
    .0
}

/// Adapts the domain and checks the loop's invariants: the map returned is the fit of the
/// domain's final T-mesh, rounds refine while the target is not met, and the target is reached.
fn adapt_reaches_target(name: &str, target: f64) {
    let mut d = domain(name);
    let options = AdaptOptions {
        target_quality: target,
        ..AdaptOptions::default()
    };
    let (map, report) = adapt(&mut d, &options, &mut |_, _| true).expect("adapt");
    for (i, r) in report.rounds.iter().enumerate() {
        println!(
            "{name} round {i}: {} elements, {} functions, certified {} ({} not), min q {:.3}, mean q {:.3}, refined {}, invalid T-mesh cells after {}",
            r.elements, r.basis, r.certified_positive, r.uncertified, r.min_quality, r.mean_quality, r.refined, r.invalid_cells
        );
    }
    let last = report.rounds.last().unwrap();
    assert_eq!(map.element_count(), d.mesh().cell_count(), "{name}");
    assert_eq!(last.refined, 0, "{name}");
    for r in &report.rounds[..report.rounds.len() - 1] {
        assert!(r.refined > 0 && r.invalid_cells == 0, "{name}: {r:?}");
    }
    assert!(
        report.reached && last.certified_positive && last.min_quality >= target,
        "{name}: {report:?}"
    );
}

#[test]
fn puzzle_reaches_target() {
    adapt_reaches_target("puzzle3_bdry.xml", 0.1);
}

/// The rotor's first map is certified with min q_S 0.34 after smoothing; 0.4 takes
/// refinement.
#[test]
fn rotor_reaches_target_after_refinement() {
    adapt_reaches_target("rotor_bdry.xml", 0.4);
}

#[test]
fn tenerife_reaches_target() {
    adapt_reaches_target("tenerife.txt", 0.05);
}

/// Gran Canaria's coastline is jagged at every scale: the C² spline fitted to the C⁰ T-mesh map
/// folds next to its kinks, and refining the T-mesh there only brings in new kinks; the
/// untangling of the fitted map's inner control points certifies the first map (min q_S 0.06).
#[test]
fn gran_canaria_reaches_target() {
    adapt_reaches_target("gran_canaria.txt", 0.05);
}

#[test]
fn a_met_target_refines_nothing() {
    let mut d = domain("male_bdry.xml");
    let cells = d.mesh().cell_count();
    let (_, report) = adapt(&mut d, &AdaptOptions::default(), &mut |_, _| true).unwrap();
    assert_eq!(report.rounds.len(), 1);
    assert!(report.reached);
    assert_eq!(d.mesh().cell_count(), cells);
}

#[test]
fn bad_options_and_cancellation() {
    let mut d = domain("rotor_bdry.xml");
    let cells = d.mesh().cell_count();
    let bad = AdaptOptions {
        target_quality: 1.5,
        ..AdaptOptions::default()
    };
    let e = adapt(&mut d, &bad, &mut |_, _| true).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidArgument);
    assert!(e.message.contains("target_quality"), "{}", e.message);
    // A target the first map does not meet, so that a refinement round (and its progress
    // call) comes.
    let demanding = AdaptOptions {
        target_quality: 0.5,
        ..AdaptOptions::default()
    };
    let e = adapt(&mut d, &demanding, &mut |_, _| false).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Cancelled);
    assert_eq!(
        d.mesh().cell_count(),
        cells,
        "a cancelled first round changed the T-mesh"
    );
}
