//! Benchmark of the shape-optimization loop: a boundary morphed in 20 steps, the domain updated
//! (`Domain::update`, the tree kept) and its spline map refitted in the same space
//! (`SplineMap::refit_tmesh`) at every step, against a cold build and checked fit of the same
//! boundary. Checks at every step the same basis count and element list and a map certified
//! valid; prints one row per step and the medians.
//!
//! `cargo bench --bench morph` runs the puzzle (its knob grown by 20%) and the 3D duck B-rep
//! (its back face scaled about its centre by up to 10%); `cargo bench --bench morph -- duck`
//! one of them. Threads: one per core.

#[path = "../tests/common/morph.rs"]
mod morph;

use std::time::Instant;

use igaparam::domain::{CubeMap, Domain, DomainOptions, UpdateOptions};
use igaparam::spline::{SplineMap, UntangleOptions, ValidityOptions, ValidityReport};

const STEPS: usize = 20;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The levels and boxes of a map's elements.
fn elements<const D: usize>(map: &SplineMap<D>) -> Vec<(u8, [f64; D], [f64; D])> {
    (0..map.element_count())
        .map(|e| {
            let (lo, hi) = map.element_bounds(e);
            (map.element_level(e), lo, hi)
        })
        .collect()
}

/// The checked fit of a domain, untangled within its own boundary offset.
fn fit<const D: usize, B: CubeMap<D>>(
    domain: &Domain<D, B>,
) -> (SplineMap<D>, igaparam::spline::FitReport, ValidityReport) {
    SplineMap::fit_tmesh_checked(
        domain.mesh(),
        domain.positions(),
        &ValidityOptions::default(),
        &untangle(domain),
    )
    .expect("fit")
}

fn untangle<const D: usize, B: CubeMap<D>>(domain: &Domain<D, B>) -> UntangleOptions {
    UntangleOptions {
        boundary_offset: domain.options().boundary_offset,
        ..Default::default()
    }
}

/// Runs the loop over the boundaries `step(s)`, `s = i / STEPS`.
fn run<const D: usize, B: CubeMap<D>>(
    name: &str,
    options: &DomainOptions,
    step: impl Fn(f64) -> B,
) {
    let none = &mut |_: usize, _: usize| true;
    let (mut domain, built) = Domain::build(step(0.0), options, none).expect("build");
    let (mut map, first, _) = fit(&domain);
    let mut record = map
        .fit_record(domain.mesh(), domain.positions(), &first)
        .expect("record");
    let rule = record.rule;
    let (basis, list) = (map.basis_count(), elements(&map));
    println!(
        "\n{name}: {} cells, {basis} functions, first fit {} ({} control points untangled)",
        built.cells,
        rule.name(),
        first.untangled
    );
    println!("| step | boundary motion | update s | refit s | step s | cold s | sweeps | invalid | tolerance met | untangled | certified | min q_S |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    let (mut steps, mut colds) = (Vec::new(), Vec::new());
    let update_options = UpdateOptions {
        threads: options.threads,
        ..Default::default()
    };
    for i in 1..=STEPS {
        let s = i as f64 / STEPS as f64;
        let clock = Instant::now();
        let updated = domain
            .update(step(s), &update_options, none)
            .expect("update");
        let update_seconds = clock.elapsed().as_secs_f64();
        let (refit, validity, next) = map
            .refit_tmesh(
                domain.mesh(),
                domain.positions(),
                Some(&record),
                &ValidityOptions::default(),
                &untangle(&domain),
            )
            .expect("refit");
        record = next;
        let step_seconds = clock.elapsed().as_secs_f64();
        assert_eq!(map.basis_count(), basis, "{name}: basis count changed");
        assert!(elements(&map) == list, "{name}: element list changed");
        assert!(
            validity.certified_positive,
            "{name}: step {i} not certified"
        );
        let clock = Instant::now();
        let (cold, _) = Domain::build(step(s), options, none).expect("cold build");
        let _ = fit(&cold);
        let cold_seconds = clock.elapsed().as_secs_f64();
        println!(
            "| {i} | {:.4} | {update_seconds:.3} | {:.3} | {step_seconds:.3} | {cold_seconds:.3} | {} | {} | {} | {} | {} | {:.3} |",
            updated.boundary_motion,
            step_seconds - update_seconds,
            updated.domain.sweeps,
            updated.domain.invalid_cells,
            updated.tolerance_met,
            refit.untangled,
            validity.certified_positive,
            validity.min_quality
        );
        steps.push(step_seconds);
        colds.push(cold_seconds);
    }
    let (step, cold) = (median(steps), median(colds));
    println!(
        "{name}: median step {step:.3} s, median cold build + fit {cold:.3} s, ratio {:.3}",
        step / cold
    );
}

fn main() {
    let filter: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let wanted = |name: &str| filter.is_empty() || filter.iter().any(|f| name.contains(f.as_str()));
    if wanted("puzzle") {
        let curves = morph::puzzle_curves();
        run("puzzle", &DomainOptions::default(), |s| {
            morph::planar(&morph::grown_puzzle(&curves, s))
        });
    }
    if wanted("duck") {
        let surfaces = morph::duck_surfaces();
        run("duck3d", &DomainOptions::solid(), |s| {
            morph::solid(&morph::scaled_duck(&surfaces, s))
        });
    }
}
