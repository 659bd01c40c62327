//! Benchmark of the THB-spline stages on the shared planar domains and on uniform trees: space
//! construction (Bézier extraction), fit, certification, per stage in seconds (median of 3);
//! then the checked fit of the domains whose first fit folds (Gran Canaria, the duck B-rep and
//! OBJ faces): interpolation, quasi-interpolation, certification and untangling, in seconds.
//!
//! `cargo bench --bench spline` runs all; `cargo bench --bench spline -- rotor` one case.

use std::path::Path;
use std::time::Instant;

use igaparam::boundary::{
    floater_parameterize, signed_areas, BoundaryLoop2, Coastline, SolidBoundary, TriMesh,
};
use igaparam::domain::{DomainOptions, PlanarDomain, PlanarOptions, SolidDomain};
use igaparam::spline::{QuadraticMap, SplineMap, ThbSpace, UntangleOptions, ValidityOptions};
use igaparam::tmesh::{TMesh, Tree};

/// CPU seconds (user + system) of this process so far, from `/proc/self/stat` (0 where that
/// is not readable): on a shared machine, wall-clock time over CPU time shows the contention.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the command name (which is in parentheses): utime is the 12th, stime the 13th.
    let rest = stat.rsplit(')').next().unwrap_or("");
    let fields: Vec<f64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|v| v.parse().ok())
        .collect();
    fields.iter().sum::<f64>() / 100.0
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn bench<const D: usize>(name: &str, mesh: &TMesh<D>, positions: &[[f64; D]]) {
    let source = QuadraticMap::new(mesh, positions).expect("map");
    let (mut build, mut fit, mut certify) = (Vec::new(), Vec::new(), Vec::new());
    let mut row = String::new();
    for _ in 0..3 {
        let t = Instant::now();
        let space = ThbSpace::new(mesh.tree().clone()).expect("space");
        build.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        let (map, report) = SplineMap::fit(space, |x| source.eval(x)).expect("fit");
        fit.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        let validity = map.validity(&ValidityOptions::default());
        certify.push(t.elapsed().as_secs_f64());
        row = format!(
            "{} | {} | {:.1e} | {} | {}",
            map.element_count(),
            map.basis_count(),
            report.reciprocal_condition,
            if report.least_squares {
                "least squares"
            } else {
                "interpolation"
            },
            validity.certified_positive
        );
    }
    println!(
        "| {name} | {row} | {:.4} | {:.4} | {:.4} |",
        median(build),
        median(fit),
        median(certify)
    );
}

/// One row of the checked fit: the uncertified elements of the plain fit, the control points
/// the untangling moved, the result and the seconds of `fit_tmesh_checked`.
fn bench_checked<const D: usize>(name: &str, mesh: &TMesh<D>, positions: &[[f64; D]]) {
    let source = QuadraticMap::new(mesh, positions).expect("map");
    let space = ThbSpace::new(mesh.tree().clone()).expect("space");
    let (plain, _) = SplineMap::fit(space, |x| source.eval(x)).expect("fit");
    let before = plain.validity(&ValidityOptions::default()).uncertified;
    // Small maps take tens of milliseconds: the median of several runs (one on a large map).
    let runs = if mesh.cell_count() < 2_000 { 5 } else { 1 };
    let mut timed = Vec::new();
    let mut last = None;
    for _ in 0..runs {
        let t = Instant::now();
        let cpu = cpu_seconds();
        let result = SplineMap::fit_tmesh_checked(
            mesh,
            positions,
            &ValidityOptions::default(),
            &UntangleOptions::default(),
        )
        .expect("checked fit");
        timed.push((
            t.elapsed().as_secs_f64(),
            cpu_seconds() - cpu,
            result.1.stages,
        ));
        last = Some(result);
    }
    let (map, report, validity) = last.expect("one run");
    timed.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (seconds, cpu, s) = timed[timed.len() / 2];
    println!(
        "| {name} | {} | {before} | {} | {:.3} | {} ({} uncertified) | {:.3} | {:.3} | {:.4} | {:.3} |",
        map.element_count(),
        report.untangled,
        report.boundary_offset,
        validity.certified_positive,
        validity.uncertified,
        validity.min_quality,
        validity.mean_quality,
        seconds,
        cpu
    );
    eprintln!(
        "  {name}: fit {:.4} s, certification {:.4} s, untangling {:.4} s, smoothing {:.4} s ({} \
         moved)",
        s.fit, s.certify, s.untangle, s.smooth, report.smoothed
    );
}

/// Floater's mean-value map of a bumpy `n × n` vertex grid surface (jittered triangulation)
/// onto the square: one face of a solid from a fine triangulation.
fn bench_floater(n: usize) {
    let mut vertices = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            let jitter = if i > 0 && j > 0 && i + 1 < n && j + 1 < n {
                0.3 / n as f64 * ((i * 7 + j * 13) as f64).sin()
            } else {
                0.0
            };
            let z = 0.2 * (3.0 * x).sin() * (2.0 * y).cos();
            vertices.push([x + jitter, y - jitter, z]);
        }
    }
    let mut triangles = Vec::with_capacity(2 * (n - 1) * (n - 1));
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let v = j * n + i;
            triangles.push([v, v + 1, v + n + 1]);
            triangles.push([v, v + n + 1, v + n]);
        }
    }
    let mesh = TriMesh::new(vertices, triangles).expect("mesh");
    let t = Instant::now();
    let uv = floater_parameterize(&mesh, [0, n - 1, n * n - 1, n * (n - 1)]).expect("floater");
    let seconds = t.elapsed().as_secs_f64();
    let folded = signed_areas(&mesh, &uv)
        .iter()
        .filter(|&&a| a <= 0.0)
        .count();
    println!(
        "| Floater map, {} vertices | {folded} folded triangles | {seconds:.3} |",
        n * n
    );
}

fn uniform<const D: usize>(level: u8) -> (TMesh<D>, Vec<[f64; D]>) {
    let mut tree = Tree::<D>::new();
    tree.refine_uniformly(level).expect("tree");
    let mesh = TMesh::new(tree).expect("mesh");
    let positions = mesh.parametric();
    (mesh, positions)
}

fn main() {
    let filter: Option<String> = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    let wanted = |name: &str| filter.as_ref().is_none_or(|f| name.contains(f.as_str()));
    println!(
        "| case | elements | basis | reciprocal condition | fit | certified | build s | fit s | certify s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for file in [
        "puzzle3_bdry.xml",
        "rotor_bdry.xml",
        "male_bdry.xml",
        "duck2d_BRep.xml",
    ] {
        if !wanted(file) {
            continue;
        }
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/boundary")
            .join(file);
        let boundary = BoundaryLoop2::from_gismo_file(path).expect("boundary");
        let (domain, _) =
            PlanarDomain::build(boundary, &PlanarOptions::default(), &mut |_, _| true)
                .expect("domain");
        bench(file, domain.mesh(), domain.positions());
        bench_checked(file, domain.mesh(), domain.positions());
    }
    if wanted("uniform") {
        let (mesh, positions) = uniform::<2>(6);
        bench("uniform 2D level 6", &mesh, &positions);
        let (mesh, positions) = uniform::<3>(3);
        bench("uniform 3D level 3", &mesh, &positions);
    }
    if wanted("floater") {
        println!();
        println!("| case | result | seconds |");
        println!("|---|---|---|");
        bench_floater(100);
        bench_floater(300);
    }
    println!();
    println!("| case | elements | uncertified after the fit | untangled | boundary move | certified | min q_S | mean q_S | checked fit s | CPU s |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/boundary");
    if wanted("gran_canaria") {
        let coast = Coastline::read(data.join("gran_canaria.txt")).expect("coastline");
        let boundary = BoundaryLoop2::from_coastline(&coast).expect("boundary");
        let (domain, _) =
            PlanarDomain::build(boundary, &PlanarOptions::default(), &mut |_, _| true)
                .expect("domain");
        bench_checked("gran_canaria.txt", domain.mesh(), domain.positions());
    }
    let options = DomainOptions {
        tolerance: 1e-4,
        max_level: 4,
        ..Default::default()
    };
    let fine = DomainOptions {
        tolerance: 1e-5,
        max_level: 5,
        ..Default::default()
    };
    for (name, boundary, options) in [
        ("duck3d_BRep.xml (1e-4, 4)", "duck3d_BRep.xml", &options),
        ("duck OBJ faces (1e-4, 4)", "duck_faces", &options),
        ("duck3d_BRep.xml (1e-5, 5)", "duck3d_BRep.xml", &fine),
    ] {
        if !wanted(name) {
            continue;
        }
        let path = data.join(boundary);
        let boundary = if path.is_dir() {
            SolidBoundary::from_obj_dir(path)
        } else {
            SolidBoundary::from_gismo_file(path)
        }
        .expect("boundary");
        let (domain, _) = SolidDomain::build(boundary, options, &mut |_, _| true).expect("domain");
        bench_checked(name, domain.mesh(), domain.positions());
    }
}
