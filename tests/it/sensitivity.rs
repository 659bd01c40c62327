//! Sensitivities of relocation: the adjoint and tangent products against central differences of
//! full relocations, their duality, the Newton stage's stationarity, warm starts, and refusals.

use crate::common;

use common::{load_case, Lcg};
use igaparam::{CellType, ErrorKind, Mesh, Placement, RelocateOptions, RelocateReport};

/// Tight stationarity: the finite differences below resolve the optimum's motion to ~1e-8.
const TOLERANCE: f64 = 1e-12;

fn options(threads: usize, placement: Placement) -> RelocateOptions {
    RelocateOptions {
        threads,
        placement,
        stationarity_tolerance: TOLERANCE,
        ..Default::default()
    }
}

fn relocate(mesh: &mut Mesh, options: &RelocateOptions) -> RelocateReport {
    let report = mesh
        .relocate(options, &mut |_, _, _| true)
        .expect("relocation");
    assert_eq!(report.invalid_after, 0);
    assert!(
        report.gradient_norm <= TOLERANCE,
        "gradient {}",
        report.gradient_norm
    );
    report
}

/// A unit grid with its top side bent into a bump of depth 0.2 (`common::bumped`).
fn bumped(cell_type: CellType, n: usize) -> Mesh {
    common::bumped(cell_type, n, 0.2, 1.0)
}

/// A random motion of the prescribed coordinates (zero at free ones), scaled to `size`.
fn prescribed_motion(mesh: &Mesh, size: f64, seed: u64) -> Vec<f64> {
    let mut rng = Lcg(seed);
    let d = mesh.dimension();
    let mut v = vec![0.0; 3 * mesh.node_count()];
    for (node, &mask) in mesh.fixed().iter().enumerate() {
        for k in 0..d {
            if mask & (1 << k) != 0 {
                v[3 * node + k] = size * rng.next();
            }
        }
    }
    v
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Relocates `base` (a relocated mesh) after moving its prescribed coordinates by `t·v`.
fn moved_by(base: &Mesh, v: &[f64], t: f64) -> Vec<f64> {
    let mut mesh = base.clone();
    let xyz: Vec<f64> = mesh
        .positions()
        .iter()
        .flatten()
        .zip(v)
        .map(|(x, dv)| x + t * dv)
        .collect();
    mesh.move_nodes(None, &xyz).unwrap();
    relocate(&mut mesh, &options(2, Placement::Incremental));
    mesh.positions().iter().flatten().copied().collect()
}

/// Checks `tangent` and `adjoint` at the relocated state of `mesh` against central differences
/// with step `h` (relative to the motion `v`), and their duality.
fn check_sensitivities(mut mesh: Mesh, h: f64, fd_tolerance: f64) {
    relocate(&mut mesh, &options(2, Placement::Laplacian));
    let n = 3 * mesh.node_count();
    let mut rng = Lcg(99);
    let w: Vec<f64> = (0..n).map(|_| rng.next()).collect();
    let v = prescribed_motion(&mesh, 1.0, 5);
    let tangent = mesh.tangent(2, &v).unwrap();
    let adjoint = mesh.adjoint(2, &w).unwrap();
    let (wt, av) = (dot(&w, &tangent), dot(&adjoint, &v));
    assert!(
        (wt - av).abs() <= 1e-10 * wt.abs().max(av.abs()),
        "duality: {wt} vs {av}"
    );
    // Free coordinates carry no adjoint (nodes in no cell pass it through), prescribed ones keep
    // their motion.
    for (node, &mask) in mesh.fixed().iter().enumerate() {
        for k in 0..mesh.dimension() {
            let i = 3 * node + k;
            match mask & (1 << k) {
                0 => assert!(adjoint[i] == 0.0 || adjoint[i] == w[i]),
                _ => assert_eq!(tangent[i], v[i]),
            }
        }
    }
    let (plus, minus) = (moved_by(&mesh, &v, h), moved_by(&mesh, &v, -h));
    let fd: Vec<f64> = plus
        .iter()
        .zip(&minus)
        .map(|(p, m)| (p - m) / (2.0 * h))
        .collect();
    let error = fd
        .iter()
        .zip(&tangent)
        .map(|(f, t)| (f - t).abs())
        .fold(0.0, f64::max);
    let scale = tangent.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    assert!(
        error <= fd_tolerance * scale,
        "tangent vs central differences: {error:e} of {scale:e}"
    );
    let fd_j = dot(&w, &fd);
    assert!(
        (fd_j - av).abs() <= fd_tolerance * av.abs().max(1e-300),
        "adjoint vs central differences: {fd_j} vs {av}"
    );
}

#[test]
fn q9_sensitivities_match_central_differences() {
    check_sensitivities(bumped(CellType::Quad9, 6), 1e-5, 1e-6);
}

#[test]
fn q4_and_q8_sensitivities_match_central_differences() {
    check_sensitivities(bumped(CellType::Quad4, 8), 1e-5, 1e-6);
    check_sensitivities(bumped(CellType::Quad8, 5), 1e-5, 1e-6);
}

#[test]
fn h27_box_sensitivities_match_central_differences() {
    check_sensitivities(bumped(CellType::Hex27, 3), 1e-5, 1e-6);
}

#[test]
fn airfoil_sensitivities_match_central_differences() {
    check_sensitivities(load_case("airfoil_0012_q9.vtu"), 1e-6, 1e-6);
}

/// An H27 box of 15³ cells (29,791 nodes, 73,167 free coordinates): past the direct solver's
/// 3D limit (60,000 free coordinates), so the Newton stage and the products solve by
/// multigrid-preconditioned conjugate gradients, as on the bundled wing (12,250 cells).
#[test]
fn multigrid_sensitivities_match_central_differences() {
    check_sensitivities(bumped(CellType::Hex27, 15), 1e-6, 1e-6);
}

/// An H8 box of 29³ cells (27,000 nodes, 65,856 free coordinates), past the same limit with
/// linear cells: no corner prolongator, so the multigrid's first level aggregates the fine rows
/// copied into compressed rows (filled in parallel).
#[test]
fn linear_cell_multigrid_sensitivities_match_central_differences() {
    check_sensitivities(bumped(CellType::Hex8, 29), 1e-6, 1e-6);
}

#[test]
fn the_newton_stage_gives_the_same_result_for_one_and_two_threads() {
    let mut one = bumped(CellType::Hex27, 3);
    let mut two = one.clone();
    relocate(&mut one, &options(1, Placement::Laplacian));
    relocate(&mut two, &options(2, Placement::Laplacian));
    assert_eq!(one.positions(), two.positions());
    let v = prescribed_motion(&one, 1.0, 3);
    assert_eq!(one.tangent(1, &v).unwrap(), two.tangent(2, &v).unwrap());
}

/// The same past the direct solver's limit, where the default method follows the optimum with
/// multigrid-preconditioned solves (the hierarchy's fine level filled in parallel).
#[test]
fn the_multigrid_newton_method_gives_the_same_result_for_one_and_two_threads() {
    let mut one = bumped(CellType::Hex27, 15);
    let mut two = one.clone();
    let default = |threads| RelocateOptions {
        threads,
        ..Default::default()
    };
    let a = one.relocate(&default(1), &mut |_, _, _| true).unwrap();
    let b = two.relocate(&default(2), &mut |_, _, _| true).unwrap();
    assert!(a.newton_iterations > 0 && a.sweeps == 0, "{a:?}");
    assert_eq!(a.newton_iterations, b.newton_iterations);
    assert_eq!(one.positions(), two.positions());
    // A second cold relocation starts from the reference state kept on the handle without its
    // Hessian (evaluated again there, with the kept preconditioner): the same path.
    let once = one.positions().to_vec();
    let c = one.relocate(&default(1), &mut |_, _, _| true).unwrap();
    assert!(
        c.sweeps == 0 && c.newton_iterations <= a.newton_iterations,
        "{c:?}"
    );
    assert_eq!(one.positions(), once);
}

#[test]
fn sensitivities_are_refused_without_a_stationary_point() {
    let mut mesh = bumped(CellType::Quad9, 4);
    let v = prescribed_motion(&mesh, 1.0, 1);
    let refused = |mesh: &Mesh, what: &str| {
        let e = mesh.tangent(1, &v).unwrap_err();
        assert_eq!(e.kind, ErrorKind::InvalidArgument);
        assert!(e.message.contains(what), "{}", e.message);
    };
    refused(&mesh, "no relocation");
    mesh.relocate(&RelocateOptions::default(), &mut |_, _, _| true)
        .unwrap();
    refused(&mesh, "stationarity_tolerance = 0");
    relocate(&mut mesh, &options(1, Placement::Laplacian));
    assert!(mesh.tangent(1, &v).is_ok());
    // Wrong sizes and non-finite values.
    assert_eq!(
        mesh.tangent(1, &v[1..]).unwrap_err().kind,
        ErrorKind::InvalidArgument
    );
    let mut nan = v.clone();
    nan[7] = f64::NAN;
    assert_eq!(
        mesh.adjoint(1, &nan).unwrap_err().kind,
        ErrorKind::NotFinite
    );
    let xyz: Vec<f64> = mesh.positions().iter().flatten().copied().collect();
    mesh.move_nodes(None, &xyz).unwrap();
    refused(&mesh, "moved");
}
