//! Benchmark of the domain pipeline: time per stage (boundary input, adaptation, placement,
//! optimization, repair) and the figures of the T-mesh, for the bundled planar domains,
//! coastlines and solids.
//!
//! `cargo bench --bench domain` runs every case once; `cargo bench --bench domain -- duck` runs
//! the cases whose name contains `duck`. Threads: one per core.

use std::path::{Path, PathBuf};
use std::time::Instant;

use igaparam::boundary::{BoundaryLoop2, Coastline, SolidBoundary};
use igaparam::domain::{DomainOptions, DomainReport, PlanarDomain, SolidDomain};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/boundary")
        .join(name)
}

/// Reads the boundary and builds its T-mesh: seconds of the input stage and the report.
fn run(name: &str, options: &DomainOptions) -> (f64, DomainReport) {
    let path = data(name);
    let start = Instant::now();
    let none = &mut |_: usize, _: usize| true;
    if name.ends_with(".txt") {
        let coast = Coastline::read(&path).expect("coastline");
        let boundary = BoundaryLoop2::from_coastline(&coast).expect("boundary");
        let input = start.elapsed().as_secs_f64();
        (
            input,
            PlanarDomain::build(boundary, options, none)
                .expect("build")
                .1,
        )
    } else if name.ends_with("2d_BRep.xml") || name.ends_with("_bdry.xml") {
        let boundary = BoundaryLoop2::from_gismo_file(&path).expect("boundary");
        let input = start.elapsed().as_secs_f64();
        (
            input,
            PlanarDomain::build(boundary, options, none)
                .expect("build")
                .1,
        )
    } else {
        let boundary = if path.is_dir() {
            SolidBoundary::from_obj_dir(&path)
        } else {
            SolidBoundary::from_gismo_file(&path)
        }
        .expect("boundary");
        let input = start.elapsed().as_secs_f64();
        (
            input,
            SolidDomain::build(boundary, options, none)
                .expect("build")
                .1,
        )
    }
}

fn main() {
    let filter: Option<String> = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!("machine: {cores} cores");
    let planar = DomainOptions::default();
    let solid = DomainOptions {
        tolerance: 1e-4,
        max_level: 4,
        ..Default::default()
    };
    // The Jacksboro faces are slivers with a jagged terrain edge: a coarser tree.
    let jacksboro = DomainOptions {
        tolerance: 1e-3,
        max_level: 3,
        ..Default::default()
    };
    let cases: [(&str, &DomainOptions); 9] = [
        ("puzzle3_bdry.xml", &planar),
        ("rotor_bdry.xml", &planar),
        ("male_bdry.xml", &planar),
        ("duck2d_BRep.xml", &planar),
        ("gran_canaria.txt", &planar),
        ("tenerife.txt", &planar),
        ("duck3d_BRep.xml", &solid),
        ("duck_faces", &solid),
        ("jacksboro_faces", &jacksboro),
    ];
    println!(
        "| domain | tolerance | max level | cells | vertices | level reached | invalid after placement | invalid after | min q | mean q | repair rounds | input s | adaptation s | placement s | optimization s | repair s | total s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, options) in cases {
        if filter.as_ref().is_some_and(|f| !name.contains(f.as_str())) {
            continue;
        }
        let (input, r) = run(name, options);
        let s = r.stages;
        println!(
            "| {name} | {:.0e} | {} | {} | {} | {} | {} | {} | {:.3} | {:.3} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} |",
            options.tolerance,
            options.max_level,
            r.cells,
            r.vertices,
            r.max_level,
            r.invalid_after_placement,
            r.invalid_cells,
            r.min_quality,
            r.mean_quality,
            r.repair_rounds,
            input,
            s.adaptation,
            s.placement,
            s.optimization,
            s.repair,
            input + r.seconds
        );
    }
}
