//! Properties of mesh relocation: fixed points, invariances, untangling, constraints,
//! determinism, and the bundled airfoil case.

use crate::common;

use common::{boundary_mask, grid, load_case, Lcg};
use igaparam::{CellType, Mesh, Method, Placement, RelocateOptions, TargetKind};

fn no_progress() -> impl FnMut(igaparam::Stage, usize, usize) -> bool {
    |_, _, _| true
}

fn relocate(mesh: &mut Mesh, options: &RelocateOptions) -> igaparam::RelocateReport {
    mesh.relocate(options, &mut no_progress())
        .expect("relocation")
}

/// Moves every interior node of a unit grid by a random vector of length up to `amplitude`.
fn perturb_interior(xyz: &mut [f64], d: usize, amplitude: f64, seed: u64) {
    let mut rng = Lcg(seed);
    for p in xyz.chunks_mut(3) {
        if p[..d].iter().all(|&v| v > 0.0 && v < 1.0) {
            for v in &mut p[..d] {
                *v += amplitude * rng.next();
            }
        }
    }
}

/// A unit grid of `n` cells per side whose interior nodes moved as [`perturb_interior`] moves
/// them (the reference is the unperturbed grid), its boundary fixed.
fn tangled(cell_type: CellType, n: usize, amplitude: f64, seed: u64) -> Mesh {
    let d = cell_type.dimension();
    let (reference, conn) = grid(cell_type, n);
    let mut xyz = reference.clone();
    perturb_interior(&mut xyz, d, amplitude, seed);
    let mut mesh = Mesh::new(cell_type, &reference, &conn).unwrap();
    mesh.set_fixed(&boundary_mask(&reference, d)).unwrap();
    mesh.move_nodes(None, &xyz).unwrap();
    mesh
}

#[test]
fn a_mesh_at_its_target_does_not_move() {
    // With the initial shape as target every mesh is a fixed point, even a distorted one.
    for cell_type in CellType::ALL {
        let (mut xyz, conn) = grid(cell_type, 3);
        perturb_interior(&mut xyz, cell_type.dimension(), 0.02, 7);
        let mut mesh = Mesh::new(cell_type, &xyz, &conn).unwrap();
        mesh.set_fixed(&boundary_mask(&xyz, cell_type.dimension()))
            .unwrap();
        let before = mesh.positions().to_vec();
        let report = relocate(&mut mesh, &RelocateOptions::default());
        assert_eq!(mesh.positions(), &before[..], "{cell_type:?} moved");
        assert_eq!(report.invalid_after, 0);
        assert!(
            (report.min_quality - 1.0).abs() < 1e-9,
            "{cell_type:?}: {}",
            report.min_quality
        );
    }
    // A uniform grid is also ideal for the master target.
    let (xyz, conn) = grid(CellType::Hex27, 2);
    let mut mesh = Mesh::new(CellType::Hex27, &xyz, &conn).unwrap();
    mesh.set_fixed(&boundary_mask(&xyz, 3)).unwrap();
    let options = RelocateOptions {
        target: TargetKind::Master,
        ..Default::default()
    };
    relocate(&mut mesh, &options);
    assert_eq!(
        mesh.positions(),
        &xyz.chunks(3)
            .map(|p| [p[0], p[1], p[2]])
            .collect::<Vec<_>>()[..]
    );
}

/// A 2D Q9 case: the top side of a unit grid bent into a bump.
fn bent_grid() -> (Vec<f64>, Vec<i64>, Vec<u8>, Vec<f64>) {
    let (xyz, conn) = grid(CellType::Quad9, 6);
    let mask = boundary_mask(&xyz, 2);
    let mut moved = xyz.clone();
    for p in moved.chunks_mut(3) {
        if p[1] == 1.0 {
            p[1] -= 0.25 * (std::f64::consts::PI * p[0]).sin();
        }
    }
    (xyz, conn, mask, moved)
}

fn transform(xyz: &[f64], angle: f64, scale: f64, shift: [f64; 2]) -> Vec<f64> {
    let (c, s) = (angle.cos(), angle.sin());
    xyz.chunks(3)
        .flat_map(|p| {
            [
                scale * (c * p[0] - s * p[1]) + shift[0],
                scale * (s * p[0] + c * p[1]) + shift[1],
                p[2],
            ]
        })
        .collect()
}

#[test]
fn relocation_commutes_with_rotation_and_scaling() {
    let (xyz, conn, mask, moved) = bent_grid();
    let run = |xyz: &[f64], moved: &[f64]| {
        let mut mesh = Mesh::new(CellType::Quad9, xyz, &conn).unwrap();
        mesh.prescribe(&mask, moved).unwrap();
        // Tight tolerances: both runs must reach the same optimum, not merely stop near it.
        let options = RelocateOptions {
            move_tolerance: 1e-7,
            gradient_tolerance: 1e-10,
            max_sweeps: 1000,
            ..Default::default()
        };
        let report = relocate(&mut mesh, &options);
        (
            mesh.positions()
                .iter()
                .flat_map(|p| *p)
                .collect::<Vec<f64>>(),
            report,
        )
    };
    let (plain, report) = run(&xyz, &moved);
    assert_eq!(report.invalid_after, 0);
    assert!(report.converged && report.invalid_before > 0, "{report:?}");
    let (angle, scale, shift) = (0.7, 3.5, [10.0, -4.0]);
    let (turned, turned_report) = run(
        &transform(&xyz, angle, scale, shift),
        &transform(&moved, angle, scale, shift),
    );
    let expected = transform(&plain, angle, scale, shift);
    let worst = expected
        .iter()
        .zip(&turned)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        worst < 1e-6 * scale,
        "largest difference {worst}: {report:?} {turned_report:?}"
    );
    assert!((report.min_quality - turned_report.min_quality).abs() < 1e-7);
}

#[test]
fn randomly_tangled_grids_are_untangled() {
    for (cell_type, n, amplitude) in [
        (CellType::Quad4, 6, 0.12),
        (CellType::Quad8, 5, 0.07),
        (CellType::Quad9, 5, 0.07),
        (CellType::Hex8, 4, 0.15),
        (CellType::Hex20, 3, 0.1),
        (CellType::Hex27, 3, 0.1),
    ] {
        let mut mesh = tangled(cell_type, n, amplitude, 42);
        let options = RelocateOptions {
            placement: Placement::Current,
            ..Default::default()
        };
        let report = relocate(&mut mesh, &options);
        assert!(
            report.invalid_before > 0,
            "{cell_type:?}: the perturbation tangles nothing"
        );
        assert_eq!(report.invalid_after, 0, "{cell_type:?}: {report:?}");
        assert!(report.min_quality > 0.3, "{cell_type:?}: {report:?}");
    }
}

#[test]
fn constrained_coordinates_keep_their_bits() {
    // A hex grid whose top and bottom nodes slide in their planes and whose side nodes are
    // prescribed; the block is stretched unevenly upwards, z' = z(1.1 + 0.3xy).
    let (xyz, conn) = grid(CellType::Hex27, 3);
    let mut mask = boundary_mask(&xyz, 3);
    let mut moved = xyz.clone();
    for (p, m) in moved.chunks_mut(3).zip(mask.iter_mut()) {
        let side = p[0] == 0.0 || p[0] == 1.0 || p[1] == 0.0 || p[1] == 1.0;
        if !side && (p[2] == 0.0 || p[2] == 1.0) {
            *m = 4;
        }
        p[2] *= 1.1 + 0.3 * p[0] * p[1];
    }
    let mut mesh = Mesh::new(CellType::Hex27, &xyz, &conn).unwrap();
    mesh.prescribe(&mask, &moved).unwrap();
    let goal = mesh.positions().to_vec();
    let report = relocate(&mut mesh, &RelocateOptions::default());
    assert_eq!(report.invalid_after, 0, "{report:?}");
    let mut slid = 0;
    for ((p, g), &m) in mesh.positions().iter().zip(&goal).zip(&mask) {
        for k in 0..3 {
            if m & (1 << k) != 0 {
                assert_eq!(p[k].to_bits(), g[k].to_bits());
            }
        }
        if m == 4 && (p[0] != g[0] || p[1] != g[1]) {
            slid += 1;
        }
    }
    assert!(slid > 0, "no sliding node moved in its plane");
}

#[test]
fn the_result_does_not_depend_on_the_thread_count() {
    let run = |threads| {
        let mut mesh = load_case("airfoil_0012_q9.vtu");
        let options = RelocateOptions {
            threads,
            ..Default::default()
        };
        let report = relocate(&mut mesh, &options);
        (mesh.positions().to_vec(), report.sweeps, report.min_quality)
    };
    let one = run(1);
    let two = run(2);
    assert!(one == two, "1 and 2 threads give different meshes");
}

#[test]
fn the_rotated_airfoil_is_untangled() {
    let mut mesh = load_case("airfoil_0012_q9.vtu");
    assert_eq!((mesh.cell_count(), mesh.node_count()), (490, 2060));
    let mut laplacian = mesh.clone();
    let report = relocate(&mut mesh, &RelocateOptions::default());
    assert_eq!(report.invalid_before, 63);
    assert_eq!(report.invalid_after, 0, "{report:?}");
    assert!(report.min_quality > 0.2, "{report:?}");
    assert_eq!(mesh.invalid_cell_count().unwrap(), 0);
    // The Newton method places the motion by the tangent of the optimum at the reference shape:
    // no cell folds there.
    assert_eq!(report.invalid_after_placement, 0, "{report:?}");
    // The baseline: the Laplacian placement alone leaves cells inverted, the placement the
    // sweeps start from.
    let mut swept = laplacian.clone();
    let options = RelocateOptions {
        optimize: false,
        ..Default::default()
    };
    let baseline = relocate(&mut laplacian, &options);
    assert!(baseline.invalid_after > 0);
    let sweeps = RelocateOptions {
        method: Method::Sweeps,
        ..Default::default()
    };
    let report = relocate(&mut swept, &sweeps);
    assert_eq!(baseline.invalid_after, report.invalid_after_placement);
    assert_eq!(report.invalid_after, 0, "{report:?}");
}

#[test]
fn cancellation_leaves_the_mesh_unchanged() {
    let mut mesh = load_case("airfoil_0012_q9.vtu");
    let before = mesh.positions().to_vec();
    for method in [Method::Sweeps, Method::Newton] {
        let mut calls = 0;
        let options = RelocateOptions {
            method,
            ..Default::default()
        };
        let result = mesh.relocate(&options, &mut |stage, _, _| {
            calls += 1;
            stage == igaparam::Stage::Placement || calls < 5
        });
        assert_eq!(result.unwrap_err().kind, igaparam::ErrorKind::Cancelled);
        assert_eq!(mesh.positions(), &before[..]);
    }
}

#[test]
fn sweeps_stop_when_only_fixed_nodes_fold_a_cell() {
    // A Q4 grid whose corner cell has all four nodes prescribed, its inner corner pulled out
    // of the square: that cell and its two neighbours along the boundary are folded at corners
    // where only prescribed nodes act, whatever the free nodes do. The sweeps stop on small
    // moves (they used to run to `max_sweeps`).
    let (xyz, conn) = grid(CellType::Quad4, 6);
    let mut mask = boundary_mask(&xyz, 2);
    let mut moved = xyz.clone();
    let pulled = xyz
        .chunks(3)
        .position(|p| p[0] == 1.0 / 6.0 && p[1] == 1.0 / 6.0)
        .unwrap();
    mask[pulled] = 3;
    moved[3 * pulled] = -0.05;
    moved[3 * pulled + 1] = -0.05;
    let mut mesh = Mesh::new(CellType::Quad4, &xyz, &conn).unwrap();
    mesh.prescribe(&mask, &moved).unwrap();
    for placement in [Placement::Current, Placement::Laplacian] {
        let options = RelocateOptions {
            placement,
            method: Method::Sweeps,
            max_sweeps: 500,
            ..Default::default()
        };
        let report = relocate(&mut mesh.clone(), &options);
        assert_eq!(report.invalid_after, 3, "{placement:?}: {report:?}");
        assert!(!report.converged, "{placement:?}: {report:?}");
        assert!(report.sweeps < 100, "{placement:?}: {report:?}");
    }
}

/// Tangled grids' Newton stage from the few sweeps that untangle them: the first Hessian is
/// indefinite (its factor modified), and the later, definite ones must take their own Newton
/// steps, not the stale modified factor's (with which these took 100 iterations without
/// converging, a slow fixed-metric gradient descent, or 56 on the last one; now 7–11).
#[test]
fn newton_converges_after_an_indefinite_first_hessian() {
    for (seed, sweeps) in [(1, 2), (5, 2), (7, 2), (5, 3)] {
        let mut mesh = tangled(CellType::Quad4, 14, 0.9 / 14.0, seed);
        let options = RelocateOptions {
            placement: Placement::Current,
            max_sweeps: sweeps,
            stationarity_tolerance: 1e-6,
            ..Default::default()
        };
        let report = relocate(&mut mesh, &options);
        assert!(
            report.invalid_before > 0 && report.invalid_after == 0,
            "{report:?}"
        );
        // (`converged` stays false: the sweeps stopped at their limit, not on their rule.)
        assert!(report.gradient_norm <= 1e-6, "seed {seed}: {report:?}");
        assert!(report.newton_iterations <= 15, "seed {seed}: {report:?}");
    }
}

/// Untangling in place with the default method: a few sweeps untangle, then Newton's method ends
/// at a stationary point of the global objective (the sweeps alone stop at small moves, with a
/// scaled gradient around 1e-3); the sweeps-only method still gives a valid mesh.
#[test]
fn untangling_in_place_ends_at_a_stationary_point() {
    for method in [Method::Auto, Method::Sweeps] {
        let mut mesh = tangled(CellType::Quad4, 14, 0.9 / 14.0, 3);
        let options = RelocateOptions {
            placement: Placement::Current,
            method,
            ..Default::default()
        };
        let report = relocate(&mut mesh, &options);
        assert!(
            report.invalid_before > 0 && report.invalid_after == 0,
            "{report:?}"
        );
        assert!(report.converged && report.min_quality > 0.99, "{report:?}");
        if method == Method::Auto {
            assert!(
                report.sweeps <= 3 && report.newton_iterations > 0,
                "{report:?}"
            );
            assert!(
                report.gradient_norm <= igaparam::fe_mesh::DEFAULT_NEWTON_TOLERANCE,
                "{report:?}"
            );
        }
    }
}
