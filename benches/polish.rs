//! The Newton polish of domain builds, off and on, in one run: min and mean quality, sweeps,
//! Newton iterations, gradient norm and seconds for the bundled domains, and for the puzzle
//! piece scaled by factors that only perturb the round-off (1 ± ε, 1 ± 4ε, 1e11, 1e12, 1e13).
//!
//! `cargo bench --bench polish` runs every case; `cargo bench --bench polish -- puzzle` those
//! whose name contains `puzzle`.

use std::path::{Path, PathBuf};

use igaparam::boundary::{
    read_gismo_curves, BoundaryLoop2, Coastline, CubeFaces, Curve2, SolidBoundary,
};
use igaparam::domain::{DomainOptions, DomainReport, PlanarDomain, SolidDomain};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/boundary")
        .join(name)
}

/// The puzzle piece's four curves scaled by `s`.
fn puzzle(s: f64) -> BoundaryLoop2 {
    let mut curves = read_gismo_curves(data("puzzle3_bdry.xml")).expect("curves");
    let scaled: Vec<Curve2> = curves
        .iter_mut()
        .map(|c| {
            c.scale([s, s, 1.0]).expect("curve");
            Curve2::spline(c.clone()).expect("curve")
        })
        .collect();
    BoundaryLoop2::from_curves(scaled).expect("boundary")
}

/// Builds the boundary `name` (a folder of faces scaled by `scale` when given).
fn run(name: &str, options: &DomainOptions, scale: Option<[f64; 3]>) -> DomainReport {
    let path = data(name);
    let none = &mut |_: usize, _: usize| true;
    if name.ends_with(".txt") {
        let coast = Coastline::read(&path).expect("coastline");
        let boundary = BoundaryLoop2::from_coastline(&coast).expect("boundary");
        PlanarDomain::build(boundary, options, none)
            .expect("build")
            .1
    } else if name.ends_with("2d_BRep.xml") || name.ends_with("_bdry.xml") {
        let boundary = BoundaryLoop2::from_gismo_file(&path).expect("boundary");
        PlanarDomain::build(boundary, options, none)
            .expect("build")
            .1
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
        SolidDomain::build(boundary, options, none)
            .expect("build")
            .1
    }
}

fn row(name: &str, polish: bool, r: &DomainReport) {
    println!(
        "| {name} | {} | {} | {} | {:.7} | {:.7} | {} | {} | {:.1e} | {:.3} | {:.3} |",
        if polish { "on" } else { "off" },
        r.cells,
        r.invalid_cells,
        r.min_quality,
        r.mean_quality,
        r.sweeps,
        r.newton_iterations,
        r.gradient_norm,
        r.stages.polish,
        r.seconds
    );
}

fn main() {
    let filter: Option<String> = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    let wanted = |name: &str| filter.as_ref().is_none_or(|f| name.contains(f.as_str()));
    let off = |o: DomainOptions| DomainOptions {
        stationarity_tolerance: 0.0,
        ..o
    };
    println!("| case | polish | cells | invalid | min q | mean q | sweeps | newton | gradient | polish s | total s |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let eps = f64::EPSILON;
    let scaled = DomainOptions {
        max_level: 6,
        threads: 1,
        ..Default::default()
    };
    if wanted("puzzle") {
        for s in [
            1.0,
            1.0 + eps,
            1.0 - eps,
            1.0 + 4.0 * eps,
            1.0 - 4.0 * eps,
            1e11,
            1e12,
            1e13,
        ] {
            let name = format!("puzzle ×{s:e}");
            for polish in [false, true] {
                let options = if polish { scaled } else { off(scaled) };
                let r = PlanarDomain::build(puzzle(s), &options, &mut |_, _| true)
                    .expect("build")
                    .1;
                row(&name, polish, &r);
            }
        }
    }
    let defaults = DomainOptions::default();
    let solid = DomainOptions {
        tolerance: 1e-4,
        max_level: 4,
        ..Default::default()
    };
    let jacksboro = DomainOptions {
        tolerance: 1e-3,
        max_level: 3,
        ..Default::default()
    };
    let jacksboro_km = DomainOptions {
        tolerance: 1e-3,
        ..Default::default()
    };
    let km = Some([89273.3, 111200.0, 1.0]);
    let cases: [(&str, &DomainOptions, Option<[f64; 3]>); 10] = [
        ("gran_canaria.txt", &defaults, None),
        ("tenerife.txt", &defaults, None),
        ("puzzle3_bdry.xml", &defaults, None),
        ("rotor_bdry.xml", &defaults, None),
        ("male_bdry.xml", &defaults, None),
        ("duck2d_BRep.xml", &defaults, None),
        ("duck3d_BRep.xml", &solid, None),
        ("duck_faces", &solid, None),
        ("jacksboro_faces", &jacksboro, None),
        ("jacksboro_faces", &jacksboro_km, km),
    ];
    for (name, options, scale) in cases {
        if !wanted(name) {
            continue;
        }
        let label = match scale {
            Some(_) => format!("{name} in km"),
            None => name.to_string(),
        };
        for polish in [false, true] {
            let o = if polish { *options } else { off(*options) };
            row(&label, polish, &run(name, &o, scale));
        }
    }
}
