//! Scale invariance: a mesh relocated, a domain built and a spline fitted at any uniform scale in
//! [1e-100, 1e100] give the unit-scale result scaled (to round-off): the same invalid counts, the
//! same qualities, the positions scaled. Every tolerance of the library is relative to the data's
//! own size, so none of this may change with the units.

use crate::common;

use common::{boundary_data, bumped, curved_box, grid, MappedCube};
use igaparam::boundary::{read_gismo_curves, BoundaryLoop2, Curve2};
use igaparam::domain::{
    CubeMap, Domain, DomainOptions, DomainReport, PlanarDomain, PlanarOptions, PlanarReport,
};
use igaparam::spline::{QuadraticMap, SplineMap, ThbSpace, UntangleOptions, ValidityOptions};
use igaparam::tmesh::TMesh;
use igaparam::{CellType, Mesh, Method, Placement, RelocateOptions, RelocateReport};

/// The scales checked, the unit first. At powers of two the scaled data are the unit data
/// exactly, and so must be the results, bit for bit; at the others the data differ by their
/// round-off.
const SCALES: [f64; 7] = [1.0, 1e-100, 1e-10, 1e10, 1e100, TWO_M333, TWO_333];
/// 2^-333 and 2^333, from their exponent bits.
const TWO_M333: f64 = f64::from_bits((1023 - 333) << 52);
const TWO_333: f64 = f64::from_bits((1023 + 333) << 52);

/// Relative agreement asked of converged figures (Newton's method to a stationary point, the
/// spline fit) and of positions (relative to the mesh's size).
const ROUND_OFF: f64 = 1e-9;

/// Relative agreement asked of the sweeps' results at scales that are not powers of two: they
/// stop at a move tolerance of 10⁻³ of the local size, and the round-off of the scaled data
/// moves where they stop by a few 10⁻⁹.
const SWEEPS_ROUND_OFF: f64 = 1e-7;

/// Whether `s` is a power of two.
fn exact(s: f64) -> bool {
    s.to_bits() & ((1u64 << 52) - 1) == 0
}

fn relocate(mesh: &mut Mesh, options: &RelocateOptions) -> RelocateReport {
    mesh.relocate(options, &mut |_, _, _| true)
        .expect("relocation")
}

/// Largest difference between `positions / s` and the unit positions.
fn position_error(positions: &[[f64; 3]], unit: &[[f64; 3]], s: f64) -> f64 {
    positions
        .iter()
        .flatten()
        .zip(unit.iter().flatten())
        .map(|(p, u)| (p / s - u).abs())
        .fold(0.0, f64::max)
}

/// What one relocation at scale `s` gives: report, positions, and the sensitivity products for
/// a fixed motion of the prescribed coordinates when the result is stationary.
struct Run {
    report: RelocateReport,
    invalid: usize,
    positions: Vec<[f64; 3]>,
    tangent: Option<Vec<f64>>,
}

fn run(cell_type: CellType, n: usize, depth: f64, s: f64, options: &RelocateOptions) -> Run {
    let mut mesh = bumped(cell_type, n, depth, s);
    let report = relocate(&mut mesh, options);
    let tangent = (options.stationarity_tolerance > 0.0).then(|| {
        let v: Vec<f64> = mesh
            .fixed()
            .iter()
            .enumerate()
            .flat_map(|(node, &m)| {
                (0..3).map(move |k| match m & (1 << k) {
                    0 => 0.0,
                    _ => s * ((node * 3 + k) as f64 * 0.37).sin(),
                })
            })
            .collect();
        mesh.tangent(1, &v).expect("tangent")
    });
    Run {
        invalid: mesh.invalid_cell_count().unwrap(),
        report,
        positions: mesh.positions().to_vec(),
        tangent,
    }
}

/// Relocates the bumped mesh at every scale and compares with the unit scale: bit for bit at
/// powers of two, else to `tolerance` (relative).
fn check_relocation(
    cell_type: CellType,
    n: usize,
    depth: f64,
    options: &RelocateOptions,
    tolerance: f64,
) {
    check_relocation_at(&SCALES, cell_type, n, depth, options, tolerance);
}

/// [`check_relocation`] at the given scales.
fn check_relocation_at(
    scales: &[f64],
    cell_type: CellType,
    n: usize,
    depth: f64,
    options: &RelocateOptions,
    tolerance: f64,
) {
    let unit = run(cell_type, n, depth, 1.0, options);
    assert_eq!(unit.invalid, unit.report.invalid_after);
    for &s in scales {
        let tolerance = if exact(s) { 0.0 } else { tolerance };
        let r = run(cell_type, n, depth, s, options);
        let name = format!("{} at scale {s:e} ({:?})", cell_type.name(), options.method);
        assert_eq!(r.report.invalid_after, r.invalid, "{name}: report vs count");
        assert_eq!(
            r.report.invalid_before, unit.report.invalid_before,
            "{name}"
        );
        assert_eq!(
            r.report.invalid_after_placement, unit.report.invalid_after_placement,
            "{name}"
        );
        assert_eq!(r.report.invalid_after, unit.report.invalid_after, "{name}");
        let dq = (r.report.min_quality - unit.report.min_quality).abs();
        assert!(
            dq <= tolerance * unit.report.min_quality,
            "{name}: min quality {} vs {} at unit scale",
            r.report.min_quality,
            unit.report.min_quality
        );
        let error = position_error(&r.positions, &unit.positions, s);
        assert!(error <= tolerance, "{name}: positions differ by {error:e}");
        if let (Some(t), Some(u)) = (&r.tangent, &unit.tangent) {
            let e = t
                .iter()
                .zip(u)
                .map(|(a, b)| (a / s - b).abs())
                .fold(0.0, f64::max);
            let limit = if exact(s) { 0.0 } else { 1e-7 };
            assert!(e <= limit, "{name}: tangent differs by {e:e}");
        }
        println!("{name}: {:?}", r.report);
    }
}

fn options(method: Method, stationarity_tolerance: f64) -> RelocateOptions {
    RelocateOptions {
        method,
        stationarity_tolerance,
        threads: 1,
        ..Default::default()
    }
}

#[test]
fn a_bumped_q9_grid_relocates_alike_at_every_scale() {
    let sweeps = options(Method::Sweeps, 0.0);
    check_relocation(CellType::Quad9, 4, 0.6, &sweeps, SWEEPS_ROUND_OFF);
    let newton = options(Method::Newton, 1e-10);
    check_relocation(CellType::Quad9, 4, 0.6, &newton, ROUND_OFF);
    let polished = options(Method::Sweeps, 1e-10);
    check_relocation(CellType::Quad9, 4, 0.6, &polished, ROUND_OFF);
}

#[test]
fn a_domed_hex_box_relocates_alike_at_every_scale() {
    let sweeps = options(Method::Sweeps, 0.0);
    check_relocation(CellType::Hex27, 2, 0.4, &sweeps, SWEEPS_ROUND_OFF);
    let newton = options(Method::Newton, 1e-10);
    check_relocation(CellType::Hex8, 3, 0.4, &newton, ROUND_OFF);
}

#[test]
fn incremental_placement_is_alike_at_every_scale() {
    let steps = |s: f64| {
        let mut mesh = bumped(CellType::Quad9, 4, 0.3, s);
        let first = options(Method::Auto, 1e-10);
        relocate(&mut mesh, &first);
        let (xyz, _) = grid(CellType::Quad9, 4);
        let moved: Vec<f64> = mesh
            .positions()
            .iter()
            .zip(xyz.chunks(3))
            .flat_map(|(p, u)| {
                let lift = if u[1] == 1.0 {
                    -0.1 * s * (std::f64::consts::PI * u[0]).sin()
                } else {
                    0.0
                };
                [p[0], p[1] + lift, p[2]]
            })
            .collect();
        mesh.move_nodes(None, &moved).unwrap();
        let warm = RelocateOptions {
            placement: Placement::Incremental,
            ..first
        };
        let report = relocate(&mut mesh, &warm);
        (report, mesh.positions().to_vec())
    };
    let (unit, unit_positions) = steps(1.0);
    for s in SCALES {
        let (report, positions) = steps(s);
        assert_eq!(report.invalid_after, unit.invalid_after, "scale {s:e}");
        let dq = (report.min_quality - unit.min_quality).abs();
        assert!(dq <= ROUND_OFF, "scale {s:e}: {report:?} vs {unit:?}");
        let error = position_error(&positions, &unit_positions, s);
        assert!(
            error <= ROUND_OFF,
            "scale {s:e}: positions differ by {error:e}"
        );
    }
}

/// Far outside [1e-100, 1e100], where the squares of the coordinates under- or overflow (the
/// audit found every cell counted invalid at 1e-160 and the report disagreeing with the count at
/// 1e160): the relocation still gives the unit result, and its report agrees with the count.
#[test]
fn relocation_reports_alike_at_extreme_scales() {
    let sweeps = options(Method::Sweeps, 0.0);
    let extreme = [1e-300, 1e-160, 1e160, 1e300];
    check_relocation_at(&extreme, CellType::Quad9, 4, 0.6, &sweeps, SWEEPS_ROUND_OFF);
    check_relocation_at(
        &[1e-110, 1e110],
        CellType::Hex27,
        2,
        0.4,
        &sweeps,
        SWEEPS_ROUND_OFF,
    );
}

#[test]
fn a_valid_reference_mesh_is_valid_at_every_scale() {
    for s in [1e-300, 1e-160, 1e-110, 1e110, 1e160, 1e300] {
        for cell_type in [CellType::Quad9, CellType::Hex27] {
            let (xyz, conn) = grid(cell_type, 2);
            let scaled: Vec<f64> = xyz.iter().map(|v| v * s).collect();
            let mesh = Mesh::new(cell_type, &scaled, &conn).unwrap();
            assert_eq!(mesh.invalid_cell_count().unwrap(), 0, "scale {s:e}");
        }
    }
}

/// The puzzle piece's four curves scaled by `s`.
fn puzzle(s: f64) -> BoundaryLoop2 {
    let mut curves = read_gismo_curves(boundary_data("puzzle3_bdry.xml")).unwrap();
    let scaled: Vec<Curve2> = curves
        .iter_mut()
        .map(|c| {
            c.scale([s, s, 1.0]).unwrap();
            Curve2::spline(c.clone()).unwrap()
        })
        .collect();
    BoundaryLoop2::from_curves(scaled).unwrap()
}

fn puzzle_options() -> PlanarOptions {
    PlanarOptions {
        max_level: 6,
        threads: 1,
        ..Default::default()
    }
}

fn build(s: f64) -> (PlanarDomain, PlanarReport) {
    PlanarDomain::build(puzzle(s), &puzzle_options(), &mut |_, _| true).expect("domain")
}

/// The smallest sampled quality, certification and uncertified elements of the spline fitted
/// to `mesh` with vertex positions `positions`.
fn fit<const D: usize>(mesh: &TMesh<D>, positions: &[[f64; D]]) -> (f64, bool, usize) {
    let source = QuadraticMap::new(mesh, positions).unwrap();
    let space = ThbSpace::new(mesh.tree().clone()).unwrap();
    let (_, _, validity) = SplineMap::fit_checked(
        space,
        |x| source.eval(x),
        &ValidityOptions::default(),
        &UntangleOptions::default(),
    )
    .unwrap();
    (
        validity.min_quality,
        validity.certified_positive,
        validity.uncertified,
    )
}

/// The scales of the domain builds: those of [`SCALES`], and factors whose products round
/// differently from the unit data's (3, π·10⁷).
const DOMAIN_SCALES: [f64; 9] = [
    1.0,
    3.0,
    1e-10,
    1e10,
    1e100,
    1e-100,
    std::f64::consts::PI * 1e7,
    TWO_M333,
    TWO_333,
];

/// Relative agreement asked of domain builds at any scale: their framed boundary data are
/// rounded onto a fixed grid of the frame, so the optimizer sees the same numbers at every
/// scale and only the mapping back to physical coordinates rounds.
const BUILD_ROUND_OFF: f64 = 1e-12;

/// A boundary map moved by a translation.
struct Shifted<B>(B, [f64; 2]);

impl<B: CubeMap<2>> CubeMap<2> for Shifted<B> {
    fn boundary_point(&self, p: [f64; 2]) -> [f64; 2] {
        let x = self.0.boundary_point(p);
        [x[0] + self.1[0], x[1] + self.1[1]]
    }
}

/// Checks a build at scale `s` (report and physical positions, moved back by `shift`) against
/// the unit build: the same T-mesh and sweeps, the same qualities and scaled positions to
/// [`BUILD_ROUND_OFF`].
fn check_build<const D: usize>(
    name: &str,
    (positions, report): (&[[f64; D]], &DomainReport),
    (unit_positions, unit): (&[[f64; D]], &DomainReport),
    s: f64,
    shift: [f64; D],
) {
    println!("{name}: {report:?}");
    assert_eq!(report.cells, unit.cells, "{name}");
    assert_eq!(report.max_level, unit.max_level, "{name}");
    assert_eq!(report.invalid_cells, unit.invalid_cells, "{name}");
    assert_eq!(report.sweeps, unit.sweeps, "{name}");
    for (a, b) in [
        (report.min_quality, unit.min_quality),
        (report.mean_quality, unit.mean_quality),
        (report.boundary_error, unit.boundary_error),
    ] {
        assert!(
            (a - b).abs() <= BUILD_ROUND_OFF * b,
            "{name}: {report:?} vs {unit:?}"
        );
    }
    let size = unit_positions
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let error = positions
        .iter()
        .zip(unit_positions)
        .flat_map(|(p, u)| (0..D).map(move |k| ((p[k] - shift[k]) / s - u[k]).abs()))
        .fold(0.0, f64::max);
    assert!(
        error <= BUILD_ROUND_OFF * size,
        "{name}: positions differ by {error:e}"
    );
}

/// The build is framed (its optimizer sees the bounding box as a unit box), and the framed
/// boundary data are rounded onto a fixed dyadic grid of the frame: at any scale, and moved by
/// a translation of its own size, the puzzle piece gives the unit build. Without the rounding,
/// the untangling of its 94 folded cells followed the round-off of the scaled data (a change of
/// the data by one unit of the last place moved the min quality between 0.03 and 0.53).
#[test]
fn the_puzzle_builds_alike_at_every_scale() {
    let (unit_domain, unit) = build(1.0);
    assert_eq!(unit.invalid_cells, 0);
    let unit_run = (unit_domain.positions(), &unit);
    for s in DOMAIN_SCALES {
        let (domain, report) = build(s);
        let name = format!("puzzle at scale {s:e}");
        check_build(&name, (domain.positions(), &report), unit_run, s, [0.0; 2]);
        let shift = [0.37 * s, -0.21 * s];
        let (domain, report) =
            Domain::build(Shifted(puzzle(s), shift), &puzzle_options(), &mut |_, _| {
                true
            })
            .expect("domain");
        let name = format!("puzzle at scale {s:e}, moved");
        check_build(&name, (domain.positions(), &report), unit_run, s, shift);
    }
}

/// The curved box (a solid whose placement folds cells) built at every scale gives the unit
/// build.
#[test]
fn a_curved_box_builds_alike_at_every_scale() {
    let options = DomainOptions {
        tolerance: 1e-4,
        min_level: 1,
        max_level: 3,
        threads: 1,
        ..DomainOptions::solid()
    };
    let solid = |s: f64| {
        let map = move |p: [f64; 3]| curved_box(p).map(|v| v * s);
        Domain::build(MappedCube(map), &options, &mut |_, _| true).expect("solid")
    };
    let (unit_domain, unit) = solid(1.0);
    assert_eq!(unit.invalid_cells, 0);
    for s in DOMAIN_SCALES {
        let (domain, report) = solid(s);
        let name = format!("curved box at scale {s:e}");
        check_build(
            &name,
            (domain.positions(), &report),
            (unit_domain.positions(), &unit),
            s,
            [0.0; 3],
        );
    }
}

/// The spline fit of one T-mesh with its positions scaled: the same certification and sampled
/// quality at every scale.
fn check_fit<const D: usize>(mesh: &TMesh<D>, positions: &[[f64; D]]) {
    let unit = fit(mesh, positions);
    assert!(unit.1, "{unit:?}");
    for s in SCALES {
        let scaled: Vec<[f64; D]> = positions.iter().map(|p| p.map(|v| v * s)).collect();
        let f = fit(mesh, &scaled);
        println!("fit at scale {s:e}: {f:?}");
        assert_eq!((f.1, f.2), (unit.1, unit.2), "scale {s:e}: fit {f:?}");
        let tolerance = if exact(s) { 0.0 } else { ROUND_OFF };
        assert!(
            (f.0 - unit.0).abs() <= tolerance * unit.0,
            "scale {s:e}: fit {f:?} vs {unit:?}"
        );
    }
}

#[test]
fn the_puzzle_fits_alike_at_every_scale() {
    let (domain, _) = build(1.0);
    check_fit(domain.mesh(), domain.positions());
}

#[test]
fn a_curved_box_fits_alike_at_every_scale() {
    let options = DomainOptions {
        min_level: 1,
        max_level: 2,
        threads: 1,
        ..DomainOptions::solid()
    };
    let (domain, _) = Domain::build(MappedCube(curved_box), &options, &mut |_, _| true).unwrap();
    check_fit(domain.mesh(), domain.positions());
}
