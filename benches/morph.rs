//! Benchmark of the shape-optimization loop: a boundary morphed in 20 steps, the domain updated
//! (`Domain::update`, the tree kept) and its spline map refitted in the same space
//! (`SplineMap::refit_tmesh`) at every step, against a cold build and checked fit of the same
//! boundary. Checks at every step the same basis count and element list and a map certified
//! valid; prints one row per step and the medians.
//!
//! `cargo bench --bench morph` runs the puzzle (its knob grown by 20%) and the 3D duck B-rep
//! (its back face scaled about its centre by up to 10%) at the solid defaults (tolerance 1e-3)
//! and at tolerance 1e-4, level 4 (`duck3d-fine`); `cargo bench --bench morph -- puzzle` runs
//! the cases whose name contains `puzzle`. Threads: one per core.

#[path = "../tests/common/morph.rs"]
mod morph;

use std::time::Instant;

use igaparam::domain::{CubeMap, Domain, DomainOptions, UpdateOptions};
use igaparam::spline::ValidityOptions;

const STEPS: usize = 20;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Runs the loop over the boundaries `step(s)`, `s = i / STEPS`, each step checked by
/// `morph::Loop::step`, against a cold build and fit of the same boundary.
fn run<const D: usize, B: CubeMap<D>>(
    name: &str,
    options: &DomainOptions,
    step: impl Fn(f64) -> B,
) {
    let mut morph = morph::Loop::new(step(0.0), options);
    let record = &morph.record;
    let untangled = record.correction.chunks_exact(D);
    println!(
        "\n{name}: {} cells, {} functions, first fit {} ({} control points untangled)",
        morph.built.cells,
        morph.map.basis_count(),
        record.rule.name(),
        untangled.filter(|c| c.iter().any(|&v| v != 0.0)).count()
    );
    println!("| step | boundary motion | update s | refit s | step s | cold s | sweeps | invalid | tolerance met | untangled | certified | min q_S | cold min q_S |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let (mut steps, mut colds) = (Vec::new(), Vec::new());
    let update_options = UpdateOptions {
        threads: options.threads,
        ..Default::default()
    };
    for i in 1..=STEPS {
        let s = i as f64 / STEPS as f64;
        let done = morph.step(step(s), &update_options);
        let step_seconds = done.update_seconds + done.refit_seconds;
        let clock = Instant::now();
        let (cold, _) = Domain::build(step(s), options, &mut |_, _| true).expect("cold build");
        let (cold_map, _) = morph::fit(&cold);
        let cold_seconds = clock.elapsed().as_secs_f64();
        let cold_quality = cold_map.validity(&ValidityOptions::default()).min_quality;
        println!(
            "| {i} | {:.4} | {:.3} | {:.3} | {step_seconds:.3} | {cold_seconds:.3} | {} | {} | {} | {} | {} | {:.3} | {cold_quality:.3} |",
            done.update.boundary_motion,
            done.update_seconds,
            done.refit_seconds,
            done.update.domain.sweeps,
            done.update.domain.invalid_cells,
            done.update.tolerance_met,
            done.refit.untangled,
            done.validity.certified_positive,
            done.validity.min_quality
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
    let surfaces = morph::duck_surfaces();
    let duck = |s| morph::solid(&morph::scaled_duck(&surfaces, s));
    if wanted("duck3d") {
        run("duck3d", &DomainOptions::solid(), duck);
    }
    if wanted("duck3d-fine") {
        let options = DomainOptions {
            tolerance: 1e-4,
            max_level: 4,
            ..DomainOptions::solid()
        };
        run("duck3d-fine (1e-4, 4)", &options, duck);
    }
}
