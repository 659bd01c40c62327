//! Benchmark of the domain pipeline: time per stage (boundary input, adaptation, placement,
//! optimization, repair) and the figures of the T-mesh, for the bundled planar domains,
//! coastlines and solids.
//!
//! `cargo bench --bench domain` runs every case once; `cargo bench --bench domain -- duck` runs
//! the cases whose name contains `duck`. Threads: one per core.

use std::path::{Path, PathBuf};
use std::time::Instant;

use igaparam::boundary::{BoundaryLoop2, Coastline, CubeFaces, SolidBoundary};
use igaparam::domain::{DomainOptions, DomainReport, PlanarDomain, SolidDomain};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/boundary")
        .join(name)
}

/// Reads the boundary (a folder of faces scaled by `scale` when given) and builds its T-mesh:
/// seconds of the input stage and the report.
fn run(name: &str, options: &DomainOptions, scale: Option<[f64; 3]>) -> (f64, DomainReport) {
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
            let mut faces = CubeFaces::read_dir(&path).expect("faces");
            if let Some(factors) = scale {
                faces.scale(factors).expect("scale");
            }
            SolidBoundary::from_cube_faces(&faces)
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
    let defaults = DomainOptions::default();
    let solid = DomainOptions {
        tolerance: 1e-4,
        max_level: 4,
        ..Default::default()
    };
    // The Jacksboro faces are slivers with a jagged terrain edge in the file's units (x, y in
    // degrees / 1000, z in km): a coarser tree; in km, tolerance 1e-3 (the adaptation stops at
    // level 3 by itself).
    let jacksboro = DomainOptions {
        tolerance: 1e-3,
        max_level: 3,
        ..Default::default()
    };
    let km = Some([89273.3, 111200.0, 1.0]);
    let jacksboro_km = DomainOptions {
        tolerance: 1e-3,
        ..Default::default()
    };
    let cases: [(&str, &DomainOptions, Option<[f64; 3]>); 10] = [
        ("puzzle3_bdry.xml", &defaults, None),
        ("rotor_bdry.xml", &defaults, None),
        ("male_bdry.xml", &defaults, None),
        ("duck2d_BRep.xml", &defaults, None),
        ("gran_canaria.txt", &defaults, None),
        ("tenerife.txt", &defaults, None),
        ("duck3d_BRep.xml", &solid, None),
        ("duck_faces", &solid, None),
        ("jacksboro_faces", &jacksboro, None),
        ("jacksboro_faces", &jacksboro_km, km),
    ];
    println!(
        "| domain | tolerance | max level | cells | vertices | level reached | invalid after placement | invalid after | min q | mean q | repair rounds | input s | adaptation s | placement s | optimization s | repair s | total s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, options, scale) in cases {
        if filter.as_ref().is_some_and(|f| !name.contains(f.as_str())) {
            continue;
        }
        let (input, r) = run(name, options, scale);
        let name = if scale.is_some() {
            format!("{name} in km")
        } else {
            name.to_string()
        };
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
