//! How relocation scales with the mesh: the bundled airfoil (Q9) and wing (H27), each cell split
//! into `s^d` cells on its own quadratic map (`igaparam::fe_mesh::refined_grid`), so that every
//! size has the same geometry and the same boundary motion; relocated with the default options,
//! and the larger wings by Newton's method too. The wing is the airfoil's mesh extruded along
//! every cell's third axis: split 2, 2 and 3 times along its cells' axes
//! (`igaparam::fe_mesh::refined_grid_by`) it has 1,214,040 nodes.
//!
//! `cargo bench --bench scale` runs every size; `-- airfoil` or `-- wing` one family;
//! `--max-nodes N` skips meshes of more nodes (an estimate before refining). Each size runs in a
//! process of its own, so that its peak memory (`VmHWM`, reset after the mesh is built, so the
//! relocation's own peak with the mesh it works on) is its own.

use std::path::Path;
use std::process::Command;

use igaparam::{fe_mesh::refined_grid_by, io::vtu, Mesh, Method, RelocateOptions};

/// The runs: name, bundled file, splits along the cells' axes, and whether the method is forced
/// to Newton's (else `AUTO`: the 812,040-node wing's Hessian is past its limit, so it is run both
/// ways; the sweeps of the 1,214,040-node one would take minutes).
const CASES: [(&str, &str, [usize; 3], bool); 7] = [
    ("airfoil Q9", "airfoil_0012_q9.vtu", [1; 3], false),
    ("airfoil Q9", "airfoil_0012_q9.vtu", [3; 3], false),
    ("airfoil Q9", "airfoil_0012_q9.vtu", [7; 3], false),
    ("wing H27", "wing_0012_h27.vtu", [1; 3], false),
    ("wing H27", "wing_0012_h27.vtu", [2; 3], false),
    ("wing H27", "wing_0012_h27.vtu", [2; 3], true),
    ("wing H27", "wing_0012_h27.vtu", [2, 2, 3], true),
];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(i) = args.iter().position(|a| a == "--case") {
        let splits: Vec<usize> = args[i + 2]
            .split(',')
            .map(|s| s.parse().expect("splits"))
            .collect();
        let splits = <[usize; 3]>::try_from(splits).expect("three splits");
        return child(&args[i + 1], splits, args[i + 3] == "newton");
    }
    let max_nodes: f64 = args
        .iter()
        .position(|a| a == "--max-nodes")
        .and_then(|i| args.get(i + 1))
        .map_or(f64::INFINITY, |v| v.parse().expect("--max-nodes N"));
    let filter = args
        .iter()
        .enumerate()
        .find(|(i, a)| !a.starts_with('-') && (*i == 0 || args[i - 1] != "--max-nodes"))
        .map(|(_, a)| a.clone());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "machine: {cores} cores; default options (method AUTO where the row does not say \
         otherwise, threads: all)"
    );
    println!("| mesh | splits | cells | nodes | method | seconds | µs per node | sweeps | Newton iterations | invalid after | min q | mean q | peak MB |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, file, s, newton) in CASES {
        if filter.as_ref().is_some_and(|f| !name.contains(f.as_str())) {
            continue;
        }
        let grid = vtu::read(&data(file)).expect("bundled mesh");
        let d = if name.contains("H27") { 3 } else { 2 };
        let product: usize = s[..d].iter().product();
        if (grid.point_count() * product) as f64 > max_nodes {
            continue;
        }
        let exe = std::env::current_exe().expect("own path");
        let method = if newton { "newton" } else { "auto" };
        let list = s.map(|s| s.to_string()).join(",");
        let out = Command::new(exe)
            .args(["--case", file, &list, method])
            .output()
            .expect("child process");
        let line = String::from_utf8_lossy(&out.stdout);
        let s = match s[..d].iter().all(|&k| k == s[0]) {
            true => s[0].to_string(),
            false => s[..d]
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join("×"),
        };
        match line.lines().find_map(|l| l.strip_prefix("RESULT ")) {
            Some(row) => println!("| {name} | {s} | {row} |"),
            None => println!(
                "| {name} | {s} | failed: {} |",
                String::from_utf8_lossy(&out.stderr).trim()
            ),
        }
    }
}

fn data(file: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(file)
}

/// One size: refines, relocates (by Newton's method where `newton`, else by `AUTO`'s choice)
/// and prints the row after `RESULT `.
fn child(file: &str, splits: [usize; 3], newton: bool) {
    let grid = vtu::read(&data(file)).expect("bundled mesh");
    let fine = refined_grid_by(&grid, splits).expect("refinement");
    drop(grid);
    let mut mesh = Mesh::from_grid_with_motion(&fine).expect("mesh");
    drop(fine);
    // Linux: "5" resets the peak resident size, so the peak is the relocation's.
    let _ = std::fs::write("/proc/self/clear_refs", "5");
    let options = RelocateOptions {
        method: if newton { Method::Newton } else { Method::Auto },
        ..Default::default()
    };
    let r = mesh
        .relocate(&options, &mut |_, _, _| true)
        .expect("relocation");
    let method = match r.sweeps {
        _ if newton => "Newton (`METHOD_NEWTON`)",
        0 => "Newton",
        _ if r.newton_iterations > 0 => "Newton, sweeps",
        _ => "sweeps",
    };
    println!(
        "RESULT {} | {} | {method} | {:.2} | {:.1} | {} | {} | {} | {:.3} | {:.3} | {:.0}",
        r.cells,
        r.nodes,
        r.seconds,
        1e6 * r.seconds / r.nodes as f64,
        r.sweeps,
        r.newton_iterations,
        r.invalid_after,
        r.min_quality,
        r.mean_quality,
        peak_megabytes()
    );
}

/// The process's peak resident size (`VmHWM`), in MB; NaN where unknown.
fn peak_megabytes() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}
