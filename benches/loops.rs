//! Benchmark of shape-optimization loops on the bundled meshes.
//!
//! `cargo bench --bench loops` runs:
//! - the warm loop: the airfoil's profile rotated 3° per step, 20 steps to 60°, each step
//!   relocated with `Placement::Incremental`, beside a cold relocation of the same boundary
//!   (default options, from the reference shape) and the previous method's cold relocation
//!   (`Method::Sweeps`, the library's behaviour before the Newton method);
//! - the sensitivities: relocation to a stationary point, then a first and a second adjoint
//!   product and a tangent product, on the airfoil and (`-- wing`) the wing, with the process's
//!   peak memory.

use std::path::Path;
use std::time::Instant;

use igaparam::{Mesh, Method, Placement, RelocateOptions, RelocateReport};

fn load(name: &str) -> Mesh {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    Mesh::read_vtu(&path).expect("bundled mesh")
}

fn relocate(mesh: &mut Mesh, options: &RelocateOptions) -> RelocateReport {
    mesh.relocate(options, &mut |_, _, _| true)
        .expect("relocation")
}

/// The airfoil's prescribed nodes on the profile rotated by `angle` about the origin.
fn rotated(reference: &[[f64; 3]], fixed: &[u8], angle: f64) -> (Vec<usize>, Vec<f64>) {
    let (c, s) = (angle.cos(), angle.sin());
    let mut indices = Vec::new();
    let mut xyz = Vec::new();
    for (v, p) in reference.iter().enumerate() {
        if fixed[v] != 0 && p[0].abs().max(p[1].abs()) < 1.9 {
            indices.push(v);
            xyz.extend_from_slice(&[c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]);
        }
    }
    (indices, xyz)
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// The prescribed motion of step `step` (1 to 20) of the loop: the profile at 3·step degrees.
fn step_motion(reference: &[[f64; 3]], fixed: &[u8], step: usize) -> (Vec<usize>, Vec<f64>) {
    rotated(reference, fixed, (3.0 * step as f64).to_radians())
}

/// The 20 steps relocated warm, back to back as in a host's loop; their reports.
fn warm_steps(
    base: &Mesh,
    options: &dyn Fn(Placement, Method) -> RelocateOptions,
) -> Vec<RelocateReport> {
    let reference = base.reference().to_vec();
    let mut warm = base.clone();
    // The bundled file's positions are the rotated state: the loop starts from the reference.
    let xyz: Vec<f64> = reference.iter().flatten().copied().collect();
    warm.move_nodes(None, &xyz).unwrap();
    relocate(&mut warm, &options(Placement::Laplacian, Method::Auto));
    (1..=20)
        .map(|step| {
            let (indices, xyz) = step_motion(&reference, base.fixed(), step);
            warm.move_nodes(Some(&indices), &xyz).unwrap();
            relocate(&mut warm, &options(Placement::Incremental, Method::Auto))
        })
        .collect()
}

/// A cold relocation of the state of `step` with `method`.
fn cold_step(
    base: &Mesh,
    step: usize,
    options: &dyn Fn(Placement, Method) -> RelocateOptions,
    method: Method,
) -> RelocateReport {
    let (indices, xyz) = step_motion(base.reference(), base.fixed(), step);
    let mut cold = base.clone();
    cold.move_nodes(Some(&indices), &xyz).unwrap();
    relocate(&mut cold, &options(Placement::Laplacian, method))
}

fn warm_loop(threads: usize) {
    let base = load("airfoil_0012_q9.vtu");
    let options = |placement, method| RelocateOptions {
        threads,
        placement,
        method,
        ..Default::default()
    };
    // The loop alone first (its steps timed as a host's loop sees them), then the cold
    // relocations of every step's state for comparison.
    let warm = warm_steps(&base, &options);
    println!("| step | angle | warm ms | newton | warm min q | cold ms | cold min q | sweeps (previous method) ms |");
    println!("|---|---|---|---|---|---|---|---|");
    let (mut step_ratios, mut worst_gap) = (Vec::new(), 0.0f64);
    for (step, w) in (1..=20).zip(&warm) {
        let c = cold_step(&base, step, &options, Method::Auto);
        let o = cold_step(&base, step, &options, Method::Sweeps);
        assert!(w.invalid_after == 0 && c.invalid_after == 0 && o.invalid_after == 0);
        worst_gap = worst_gap.max((c.min_quality - w.min_quality) / c.min_quality);
        step_ratios.push(w.seconds / c.seconds);
        println!(
            "| {step} | {}° | {:.1} | {} | {:.3} | {:.1} | {:.3} | {:.1} |",
            3 * step,
            1e3 * w.seconds,
            w.newton_iterations,
            w.min_quality,
            1e3 * c.seconds,
            c.min_quality,
            1e3 * o.seconds
        );
    }
    // The final state's cold relocations, repeated: one timing on a shared machine is noise.
    let repeated = |method| {
        let times = (0..5).map(|_| cold_step(&base, 20, &options, method).seconds);
        median(times.collect())
    };
    let (final_cold, final_old) = (repeated(Method::Auto), repeated(Method::Sweeps));
    let warm = median(warm.iter().map(|r| r.seconds).collect());
    println!(
        "\nwarm median {:.1} ms; cold relocation of the final state {:.1} ms (median of 5; ratio \
         {:.2}; median over the steps of warm / cold at the same angle {:.2}); previous method's \
         cold relocation of it {:.1} ms (ratio {:.3}); largest min-quality gap to the cold result \
         {:.2}%",
        1e3 * warm,
        1e3 * final_cold,
        warm / final_cold,
        median(step_ratios),
        1e3 * final_old,
        warm / final_old,
        100.0 * worst_gap
    );
}

/// Peak resident memory of the process so far, in MB (Linux; 0 elsewhere).
fn peak_memory_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(0.0, |kb| kb / 1024.0)
}

fn sensitivities(name: &str, threads: usize) {
    let mut mesh = load(name);
    let before = peak_memory_mb();
    let options = RelocateOptions {
        threads,
        stationarity_tolerance: 1e-10,
        method: Method::Newton,
        ..Default::default()
    };
    let report = relocate(&mut mesh, &options);
    let n = 3 * mesh.node_count();
    let w: Vec<f64> = (0..n)
        .map(|i| ((i * 7919) % 1000) as f64 / 1000.0 - 0.5)
        .collect();
    let time = |f: &mut dyn FnMut()| {
        let start = Instant::now();
        f();
        start.elapsed().as_secs_f64()
    };
    let first = time(&mut || {
        mesh.adjoint(threads, &w).unwrap();
    });
    let second = time(&mut || {
        mesh.adjoint(threads, &w).unwrap();
    });
    let tangent = time(&mut || {
        mesh.tangent(threads, &w).unwrap();
    });
    println!(
        "| {name} | {} | {:.3} | {} | {:.3} | {:.3} | {:.3} | {:.0} → {:.0} |",
        report.cells,
        report.seconds,
        report.newton_iterations,
        first,
        second,
        tangent,
        before,
        peak_memory_mb()
    );
}

fn main() {
    let filter: Option<String> = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    let threads = 2;
    let wanted = |case: &str| filter.as_ref().is_none_or(|f| case.contains(f.as_str()));
    if wanted("loop") {
        warm_loop(threads);
    }
    println!("\n| mesh | cells | relocation to 1e-10 s | newton | first adjoint s | second adjoint s | tangent s | peak MB |");
    println!("|---|---|---|---|---|---|---|---|");
    if wanted("airfoil") {
        sensitivities("airfoil_0012_q9.vtu", threads);
    }
    if filter.as_deref() == Some("wing") {
        sensitivities("wing_0012_h27.vtu", threads);
    }
}
