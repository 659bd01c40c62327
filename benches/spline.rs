//! Benchmark of the THB-spline stages on the shared planar domains and on uniform trees: space
//! construction (Bézier extraction), fit, certification, per stage in seconds (median of 3);
//! then the checked fit of the domains whose first fit folds (Gran Canaria, the duck B-rep and
//! OBJ faces): interpolation, quasi-interpolation, certification and untangling, in seconds.
//!
//! `cargo bench --bench spline` runs all; `cargo bench --bench spline -- rotor` one case.

use std::path::Path;
use std::time::Instant;

use igaparam::boundary::{BoundaryLoop2, Coastline, SolidBoundary};
use igaparam::domain::{DomainOptions, PlanarDomain, PlanarOptions, SolidDomain};
use igaparam::spline::{QuadraticMap, SplineMap, ThbSpace, UntangleOptions, ValidityOptions};
use igaparam::tmesh::{TMesh, Tree};

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
            "{} | {} | {} | {} | {}",
            map.element_count(),
            map.basis_count(),
            report.bandwidth,
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
    let t = Instant::now();
    let (map, report, validity) = SplineMap::fit_tmesh_checked(
        mesh,
        positions,
        &ValidityOptions::default(),
        &UntangleOptions::default(),
    )
    .expect("checked fit");
    println!(
        "| {name} | {} | {before} | {} | {:.3} | {} ({} uncertified) | {:.3} | {:.2} |",
        map.element_count(),
        report.untangled,
        report.boundary_offset,
        validity.certified_positive,
        validity.uncertified,
        validity.min_quality,
        t.elapsed().as_secs_f64()
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
        "| case | elements | basis | bandwidth | fit | certified | build s | fit s | certify s |"
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
    }
    if wanted("uniform") {
        let (mesh, positions) = uniform::<2>(6);
        bench("uniform 2D level 6", &mesh, &positions);
        let (mesh, positions) = uniform::<3>(3);
        bench("uniform 3D level 3", &mesh, &positions);
    }
    println!();
    println!("| case | elements | uncertified after the fit | untangled | boundary move | certified | min q_S | checked fit s |");
    println!("|---|---|---|---|---|---|---|---|");
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
    for (name, boundary) in [
        ("duck3d_BRep.xml (1e-4, 4)", "duck3d_BRep.xml"),
        ("duck OBJ faces (1e-4, 4)", "duck_faces"),
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
        let (domain, _) = SolidDomain::build(boundary, &options, &mut |_, _| true).expect("domain");
        bench_checked(name, domain.mesh(), domain.positions());
    }
}
