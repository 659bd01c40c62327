//! Benchmark of mesh relocation on the bundled cases: wall time and quality per thread count.
//!
//! `cargo bench --bench relocate` runs the airfoil (5 repetitions, the median is reported) and
//! the wing (one run) with 1 and 2 threads. `cargo bench --bench relocate -- airfoil` runs the
//! airfoil only.

use std::path::Path;

use igaparam::{io::vtu, Mesh, RelocateOptions, RelocateReport};

fn run(grid: &vtu::UnstructuredGrid, threads: usize) -> RelocateReport {
    let mut mesh = Mesh::from_grid_with_motion(grid).expect("mesh");
    let options = RelocateOptions {
        threads,
        ..Default::default()
    };
    mesh.relocate(&options, &mut |_, _, _| true)
        .expect("relocation")
}

fn main() {
    let filter: Option<String> = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!("machine: {cores} cores");
    println!(
        "| case | cells | threads | seconds (median) | invalid before | after Laplacian | after | min q | mean q | sweeps | steps |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, file, repetitions) in [
        ("airfoil Q9", "airfoil_0012_q9.vtu", 5),
        ("wing H27", "wing_0012_h27.vtu", 1),
    ] {
        if filter.as_ref().is_some_and(|f| !file.contains(f.as_str())) {
            continue;
        }
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(file);
        let grid = vtu::read(&path).expect("bundled mesh");
        for threads in [1, 2] {
            let mut reports: Vec<RelocateReport> =
                (0..repetitions).map(|_| run(&grid, threads)).collect();
            reports.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
            let r = reports[reports.len() / 2];
            println!(
                "| {name} | {} | {threads} | {:.3} | {} | {} | {} | {:.3} | {:.3} | {} | {} |",
                r.cells,
                r.seconds,
                r.invalid_before,
                r.invalid_after_placement,
                r.invalid_after,
                r.min_quality,
                r.mean_quality,
                r.sweeps,
                r.steps
            );
        }
    }
}
