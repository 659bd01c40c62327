//! Planar domains: adapted, optimized T-meshes from four boundary curves.

use crate::common;

use common::{boundary_data, curved_box, mapped_square, MappedCube};
use igaparam::boundary::{BoundaryLoop2, Coastline};
use igaparam::domain::{PlanarDomain, PlanarOptions, PlanarReport};

fn build(boundary: BoundaryLoop2, options: &PlanarOptions) -> (PlanarDomain, PlanarReport) {
    PlanarDomain::build(boundary, options, &mut |_, _| true).expect("domain")
}

/// Largest coordinate difference between the physical and the parametric vertices.
fn distance_from_parametric<const D: usize, B: igaparam::domain::CubeMap<D>>(
    domain: &igaparam::domain::Domain<D, B>,
) -> f64 {
    distance_from(domain, |p| p)
}

#[test]
fn the_unit_square_gives_the_identity() {
    let (domain, report) = build(mapped_square(|p| p, 4), &PlanarOptions::default());
    assert_eq!(report.invalid_cells, 0);
    let worst = distance_from_parametric(&domain);
    assert!(worst < 1e-12, "moved by {worst}");
    assert!((report.min_quality - 1.0).abs() < 1e-12);
}

#[test]
fn a_negative_or_non_finite_boundary_offset_is_refused_and_zero_keeps_the_boundary() {
    for bad in [-1e-3, f64::NAN, f64::INFINITY] {
        let options = PlanarOptions {
            boundary_offset: bad,
            ..PlanarOptions::default()
        };
        let error = PlanarDomain::build(mapped_square(|p| p, 4), &options, &mut |_, _| true)
            .expect_err("a bad boundary_offset was accepted");
        assert!(
            error.message.contains("boundary_offset"),
            "{}",
            error.message
        );
    }
    let options = PlanarOptions {
        boundary_offset: 0.0,
        ..PlanarOptions::default()
    };
    let (_, report) = build(mapped_square(affine2, 4), &options);
    assert_eq!(report.boundary_offset, 0.0);
    assert_eq!(report.invalid_cells, 0);
}

#[test]
fn shared_domains_give_valid_t_meshes_within_the_boundary_tolerance() {
    let options = PlanarOptions::default();
    let mut boundaries: Vec<(String, BoundaryLoop2)> = [
        "puzzle3_bdry.xml",
        "rotor_bdry.xml",
        "male_bdry.xml",
        "duck2d_BRep.xml",
    ]
    .iter()
    .map(|f| {
        (
            f.to_string(),
            BoundaryLoop2::from_gismo_file(boundary_data(f)).unwrap(),
        )
    })
    .collect();
    for f in ["gran_canaria.txt", "tenerife.txt"] {
        let coast = Coastline::read(boundary_data(f)).unwrap();
        boundaries.push((
            f.to_string(),
            BoundaryLoop2::from_coastline(&coast).unwrap(),
        ));
    }
    let reports: Vec<(String, PlanarReport)> = boundaries
        .into_iter()
        .map(|(name, boundary)| (name, build(boundary, &options).1))
        .collect();
    for (name, report) in &reports {
        println!("{name}: {report:?}");
    }
    for (name, report) in &reports {
        assert_eq!(report.invalid_cells, 0, "{name}: {report:?}");
        // Every one of them meets the tolerance below the level cap (levels 6 and 7 of 9): the
        // tolerance is checked, not excused by the cap.
        assert!(
            report.boundary_error <= options.tolerance && report.max_level < options.max_level,
            "{name}: {report:?}"
        );
    }
}

/// A solid given by a map of the unit cube (only its boundary values are used).
#[test]
fn the_unit_cube_gives_the_identity() {
    let options = igaparam::domain::DomainOptions {
        min_level: 2,
        max_level: 3,
        ..Default::default()
    };
    let (domain, report) =
        igaparam::domain::Domain::build(MappedCube(|p: [f64; 3]| p), &options, &mut |_, _| true)
            .unwrap();
    assert_eq!(report.invalid_cells, 0);
    let worst = distance_from_parametric(&domain);
    assert!(worst < 1e-12, "moved by {worst}");
}

#[test]
fn a_curved_solid_gets_a_valid_adapted_octree() {
    let map = curved_box;
    let options = igaparam::domain::DomainOptions {
        tolerance: 1e-4,
        max_level: 5,
        ..Default::default()
    };
    let (domain, report) =
        igaparam::domain::Domain::build(MappedCube(map), &options, &mut |_, _| true).unwrap();
    println!("{report:?}");
    assert_eq!(report.invalid_cells, 0, "{report:?}");
    // The tolerance is met at level 3, below the cap of 5.
    assert!(
        report.boundary_error <= options.tolerance && report.max_level < options.max_level,
        "{report:?}"
    );
    assert!(
        report.max_level > options.min_level,
        "the curved boundary refined nothing"
    );
    assert!(domain.mesh().tree().is_balanced());
    // Boundary vertices lie on the boundary.
    for (v, p) in domain.mesh().parametric().iter().enumerate() {
        if domain.mesh().on_boundary(v) {
            let exact = map(*p);
            assert!((0..3).all(|k| (exact[k] - domain.positions()[v][k]).abs() < 1e-12));
        }
    }
}

/// The largest distance between the physical vertices and the image of their parametric ones by
/// `f`.
fn distance_from<const D: usize, B: igaparam::domain::CubeMap<D>>(
    domain: &igaparam::domain::Domain<D, B>,
    f: impl Fn([f64; D]) -> [f64; D],
) -> f64 {
    domain
        .mesh()
        .parametric()
        .iter()
        .zip(domain.positions())
        .map(|(p, x)| {
            let y = f(*p);
            (0..D).map(|k| (x[k] - y[k]).abs()).fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// An affine map that is not a similarity: shear and unequal stretch.
fn affine2([u, v]: [f64; 2]) -> [f64; 2] {
    [3.0 + 2.0 * u + 0.7 * v, -1.0 + 0.2 * u + 0.9 * v]
}

fn affine3([u, v, w]: [f64; 3]) -> [f64; 3] {
    [
        1.0 + 2.0 * u + 0.5 * v - 0.3 * w,
        0.4 * u + 1.2 * v + 0.2 * w,
        -2.0 + 0.1 * u - 0.3 * v + 0.8 * w,
    ]
}

/// On a uniform mesh an affine image of the square or cube is reproduced exactly: every cell has
/// the same Jacobian, and by symmetry each vertex's objective is stationary there. (On a T-mesh
/// it is not exactly: the cells around a hanging vertex are not symmetric and coarser ones weigh
/// 2, so the affine map is only near the optimum; the identity is exact there, see below.)
/// Exactly up to the rounding of the framed boundary points onto a grid of 2⁻³⁸ of the bounding
/// box, which moves the optimum by a few 10⁻¹² of the box.
#[test]
fn an_affine_image_gives_the_affine_map_on_uniform_meshes() {
    let uniform = |level| igaparam::domain::DomainOptions {
        min_level: level,
        max_level: level,
        ..Default::default()
    };
    let (planar, report) = build(mapped_square(affine2, 4), &uniform(3));
    assert_eq!(report.invalid_cells, 0);
    let worst = distance_from(&planar, affine2);
    assert!(
        worst < 1e-11 * planar.frame().diagonal(),
        "2D: moved by {worst}"
    );
    let (solid, report) =
        igaparam::domain::Domain::build(MappedCube(affine3), &uniform(2), &mut |_, _| true)
            .unwrap();
    assert_eq!(report.invalid_cells, 0);
    let worst = distance_from(&solid, affine3);
    assert!(
        worst < 1e-11 * solid.frame().diagonal(),
        "3D: moved by {worst}"
    );
}

/// The identity on T-meshes (hanging vertices, cells of two levels): refining cells of the unit
/// square or cube keeps the identity exactly; an affine image stays close to the affine map.
#[test]
fn refined_t_meshes_keep_the_identity() {
    let options = igaparam::domain::DomainOptions {
        min_level: 2,
        max_level: 2,
        ..Default::default()
    };
    let (mut square, _) = build(mapped_square(|p| p, 4), &options);
    let report = square
        .refine_cells(&[0, 5], &options, &mut |_, _| true)
        .unwrap();
    assert!(report.cells > 16 && report.max_level == 3, "{report:?}");
    let worst = distance_from_parametric(&square);
    assert!(worst < 1e-12, "2D: moved by {worst}");
    let (mut cube, _) =
        igaparam::domain::Domain::build(MappedCube(|p: [f64; 3]| p), &options, &mut |_, _| true)
            .unwrap();
    cube.refine_cells(&[0, 21], &options, &mut |_, _| true)
        .unwrap();
    let worst = distance_from_parametric(&cube);
    assert!(worst < 1e-12, "3D: moved by {worst}");
    let (mut affine, _) = build(mapped_square(affine2, 4), &options);
    affine
        .refine_cells(&[0, 5], &options, &mut |_, _| true)
        .unwrap();
    let worst = distance_from(&affine, affine2);
    println!("affine image on a T-mesh: largest deviation from the affine map {worst:.2e}");
    assert!(worst < 0.05, "2D affine on a T-mesh: moved by {worst}");
}

/// Refining cells: all cells valid after, the tree still balanced, the refined cells split,
/// vertices far from them barely moved.
#[test]
fn refining_cells_keeps_validity_and_balance_and_is_local() {
    let boundary = BoundaryLoop2::from_gismo_file(boundary_data("male_bdry.xml")).unwrap();
    let options = PlanarOptions::default();
    let (mut domain, before) = build(boundary, &options);
    assert_eq!(before.invalid_cells, 0);
    // The cells touching the parametric corner (0, 0).
    let near: Vec<usize> = (0..domain.mesh().cell_count())
        .filter(|&c| {
            let (lo, _) = domain.mesh().cell_bounds(c);
            lo[0] < 0.2 && lo[1] < 0.2
        })
        .collect();
    assert!(!near.is_empty());
    let old: std::collections::HashMap<[u64; 2], [f64; 2]> = domain
        .mesh()
        .parametric()
        .iter()
        .zip(domain.positions())
        .map(|(p, x)| (p.map(f64::to_bits), *x))
        .collect();
    let report = domain
        .refine_cells(&near, &options, &mut |_, _| true)
        .unwrap();
    println!("refined {} cells: {before:?} -> {report:?}", near.len());
    assert_eq!(report.invalid_cells, 0, "{report:?}");
    assert!(report.cells >= before.cells + 3 * near.len(), "{report:?}");
    assert!(domain.mesh().tree().is_balanced());
    let size = domain.frame().diagonal();
    let mut far_moves = 0.0f64;
    for (p, x) in domain.mesh().parametric().iter().zip(domain.positions()) {
        if p[0] > 0.6 || p[1] > 0.6 {
            let y = old[&p.map(f64::to_bits)];
            far_moves = far_moves.max(((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2)).sqrt());
        }
    }
    println!(
        "largest move of a far vertex: {:.2e} of the diagonal",
        far_moves / size
    );
    assert!(far_moves < 1e-2 * size, "{far_moves}");
    // A cell that does not exist.
    let e = domain
        .refine_cells(&[report.cells], &options, &mut |_, _| true)
        .unwrap_err();
    assert_eq!(e.kind, igaparam::ErrorKind::InvalidArgument);
}

/// The 3D duck (G+Smo B-rep): valid after the repair refines the cells whose Gauss–Lobatto
/// points on the cube's edges fold (the seams of the smooth surface are nearly flat there, and
/// only shorter chords open them).
#[test]
fn duck_brep_gives_a_valid_t_mesh() {
    let boundary =
        igaparam::boundary::SolidBoundary::from_gismo_file(boundary_data("duck3d_BRep.xml"))
            .unwrap();
    let options = igaparam::domain::SolidOptions {
        tolerance: 1e-4,
        max_level: 4,
        ..Default::default()
    };
    let (domain, report) =
        igaparam::domain::SolidDomain::build(boundary, &options, &mut |_, _| true).unwrap();
    println!("duck3d_BRep.xml: {report:?}");
    assert_eq!(report.invalid_cells, 0, "{report:?}");
    assert!(report.boundary_error <= options.tolerance, "{report:?}");
    assert!(domain.mesh().tree().is_balanced());
    // Its spline map folds at the cube's edges; untangled (boundary control points within the
    // offset) and smoothed, it is certified with min q_S 0.08 (0.077 before the untangling
    // moved the boundary control points of edge-pinned elements first, 0.006 when it moved
    // only those of the pinned elements), and the same for 1 and 2 threads.
    let fit = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| common::checked_fit(&domain))
    };
    let (one, report, validity) = fit(1);
    println!("{report:?}\n{validity:?}");
    assert!(
        validity.certified_positive && report.untangled > 0,
        "{validity:?}"
    );
    assert!(validity.min_quality > 0.075, "{}", validity.min_quality);
    let (two, _, validity_two) = fit(2);
    assert_eq!(one.control_points(), two.control_points());
    assert_eq!(validity, validity_two);
}

/// Triangulated faces that do not share their edges are refused with a face named (the one
/// whose corners no longer match).
#[test]
fn solid_faces_that_do_not_match_are_refused() {
    let mut cube = igaparam::boundary::CubeFaces::read_dir(boundary_data("duck_faces")).unwrap();
    for v in cube.faces[5].vertices.iter_mut() {
        v[2] += 0.01;
    }
    let e = igaparam::boundary::SolidBoundary::from_cube_faces(&cube).unwrap_err();
    assert!(
        e.kind == igaparam::ErrorKind::InvalidMesh
            || e.kind == igaparam::ErrorKind::InvalidArgument,
        "{e:?}"
    );
    let named = ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"]
        .iter()
        .any(|f| e.message.contains(&format!("face {f}")));
    assert!(named, "no face named: {}", e.message);
}

/// The Newton polish leaves a valid T-mesh at a stationary point of the global objective: its
/// scaled gradient norm, recomputed here from the physical positions, is within the tolerance,
/// where the sweeps alone stop far from it. A bad tolerance is refused.
#[test]
fn the_polished_t_mesh_is_valid_and_stationary() {
    use igaparam::optimize::blocks::BlockLayout;
    use igaparam::optimize::global::GlobalObjective;
    use igaparam::optimize::solver::SolverSetup;
    use igaparam::optimize::stationary::scaled_gradient_norm;
    let boundary = || BoundaryLoop2::from_gismo_file(boundary_data("rotor_bdry.xml")).unwrap();
    let norm = |domain: &PlanarDomain| {
        let problem = domain.mesh().problem().unwrap();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let layout = BlockLayout::new(&pool, &problem);
        let objective = GlobalObjective::new(&problem, &layout, None, 0.0);
        let frame = domain.frame();
        let x: Vec<[f64; 2]> = domain
            .positions()
            .iter()
            .map(|&p| frame.to_frame(p))
            .collect();
        let eval = objective.evaluate(&pool, &x, false).unwrap();
        scaled_gradient_norm(
            &objective,
            &SolverSetup::free_mask(&problem),
            &eval.gradient,
        )
    };
    let tolerance = 1e-8;
    let options = PlanarOptions {
        stationarity_tolerance: tolerance,
        ..PlanarOptions::default()
    };
    let (polished, report) = build(boundary(), &options);
    assert_eq!(report.invalid_cells, 0);
    assert!(report.newton_iterations > 0, "{report:?}");
    assert!(report.gradient_norm <= tolerance, "{report:?}");
    let recomputed = norm(&polished);
    assert!(recomputed <= 2.0 * tolerance, "{recomputed:e}");
    let off = PlanarOptions {
        stationarity_tolerance: 0.0,
        ..PlanarOptions::default()
    };
    let (swept, report) = build(boundary(), &off);
    assert_eq!((report.newton_iterations, report.gradient_norm), (0, 0.0));
    assert!(norm(&swept) > 1e3 * tolerance, "{:e}", norm(&swept));
    for bad in [-1e-8, f64::NAN] {
        let options = PlanarOptions {
            stationarity_tolerance: bad,
            ..PlanarOptions::default()
        };
        let error = PlanarDomain::build(boundary(), &options, &mut |_, _| true)
            .expect_err("a bad stationarity_tolerance was accepted");
        assert!(
            error.message.contains("stationarity_tolerance"),
            "{}",
            error.message
        );
    }
}
