//! Benchmark of mesh relocation on the bundled cases: wall time and quality per thread count.
//!
//! `cargo bench --bench relocate` runs the airfoil (5 repetitions, the median is reported) and
//! the wing (one run) with 1 and 2 threads, each with the default method (`Auto`) and with the
//! sweeps (the method before), one after the other. `cargo bench --bench relocate -- airfoil`
//! runs the airfoil only.
//!
//! Where `python3` (or the interpreter `IGAPARAM_PYTHON` names) imports PyMFEM (`mfem`), MFEM
//! TMOP relocates the airfoil from the same harmonic placement in the same run
//! (`benches/tmop.py`: its mesh-optimizer setup, metric 22 then 2, the cells' reference shapes as
//! targets), and the ratio of its time to ours is printed; otherwise that row is skipped.

use std::path::Path;

use std::process::Command;

use igaparam::io::vtu::{self, DataArray, Format};
use igaparam::{Mesh, Method, RelocateOptions, RelocateReport};

fn run(grid: &vtu::UnstructuredGrid, threads: usize, method: Method) -> RelocateReport {
    let mut mesh = Mesh::from_grid_with_motion(grid).expect("mesh");
    let options = RelocateOptions {
        threads,
        method,
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
        "| case | cells | method | threads | seconds (median) | invalid before | after Laplacian | after | min q | mean q | sweeps | newton | steps |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
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
        let mut fastest = f64::INFINITY;
        // The default method beside the sweeps (the method before), one after the other.
        for (threads, method) in [1, 2]
            .into_iter()
            .flat_map(|t| [(t, Method::Auto), (t, Method::Sweeps)])
        {
            let mut reports: Vec<RelocateReport> = (0..repetitions)
                .map(|_| run(&grid, threads, method))
                .collect();
            reports.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
            let r = reports[reports.len() / 2];
            if method == Method::Auto {
                fastest = fastest.min(r.seconds);
            }
            println!(
                "| {name} | {} | {method:?} | {threads} | {:.3} | {} | {} | {} | {:.3} | {:.3} | {} | {} | {} |",
                r.cells,
                r.seconds,
                r.invalid_before,
                r.invalid_after_placement,
                r.invalid_after,
                r.min_quality,
                r.mean_quality,
                r.sweeps,
                r.newton_iterations,
                r.steps
            );
        }
        if file.contains("q9") {
            tmop(&grid, fastest);
        }
    }
}

/// MFEM TMOP on the same Q9 case from the same harmonic placement, with the ratio of its time
/// to `ours` (seconds); skipped where PyMFEM cannot be imported.
fn tmop(grid: &vtu::UnstructuredGrid, ours: f64) {
    let python = std::env::var("IGAPARAM_PYTHON").unwrap_or_else(|_| "python3".into());
    let importable = Command::new(&python)
        .args(["-c", "import mfem.ser, mfem._ser.tmop"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !importable {
        println!("MFEM TMOP: skipped ({python} cannot import mfem; `pip install mfem` adds it)");
        return;
    }
    let mut mesh = Mesh::from_grid_with_motion(grid).expect("mesh");
    let placement = RelocateOptions {
        optimize: false,
        ..Default::default()
    };
    mesh.relocate(&placement, &mut |_, _, _| true)
        .expect("placement");
    let start = mesh.positions().to_vec();
    mesh.relocate(&RelocateOptions::default(), &mut |_, _, _| true)
        .expect("relocation");
    let mut case = grid.clone();
    for (name, positions) in [("start", &start[..]), ("relocated", mesh.positions())] {
        case.point_data.push(DataArray {
            name: name.into(),
            components: 3,
            values: positions.iter().flatten().copied().collect(),
        });
    }
    let path = std::env::temp_dir().join(format!("igaparam_tmop_{}.vtu", std::process::id()));
    vtu::write_as(&path, &case, Format::ASCII).expect("case file");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/tmop.py");
    let out = Command::new(&python).arg(&script).arg(&path).output();
    let _ = std::fs::remove_file(&path);
    let out = out.expect("python");
    let text = String::from_utf8_lossy(&out.stdout);
    match text.lines().find_map(|l| l.strip_prefix("TMOP ")) {
        Some(row) => {
            let seconds = row
                .split_whitespace()
                .find_map(|f| f.strip_prefix("seconds="))
                .and_then(|v| v.parse::<f64>().ok())
                .unwrap_or(f64::NAN);
            println!(
                "MFEM TMOP from the same placement: {row}; TMOP / igaparam time {:.0}",
                seconds / ours
            );
        }
        None => println!(
            "MFEM TMOP: failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        ),
    }
}
