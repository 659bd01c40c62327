//! Shared helpers of the integration tests: structured grids in VTK node order, a small
//! deterministic random generator, the bundled boundaries and mapped cubes.
#![allow(dead_code)]

use igaparam::optimize::lattice;
use igaparam::CellType;

/// A structured grid of `n^d` cells of the given type on [0,1]^d: flat `xyz` (3 per node) and
/// connectivity. Quadratic types use a `(2n+1)^d` node lattice, linear ones `(n+1)^d`; nodes a
/// serendipity cell does not use stay unconnected.
pub fn grid(cell_type: CellType, n: usize) -> (Vec<f64>, Vec<i64>) {
    let d = cell_type.dimension();
    let quadratic = cell_type.node_count() > 1 << d;
    let per = if quadratic { 2 } else { 1 };
    let m = per * n + 1;
    let count = m.pow(d as u32);
    let index = |c: &[usize]| c.iter().rev().fold(0, |acc, &ck| acc * m + ck);
    let mut xyz = Vec::with_capacity(3 * count);
    for i in 0..count {
        let mut rest = i;
        for _ in 0..3 {
            let c = if xyz.len() % 3 < d { rest % m } else { 0 };
            rest /= m;
            xyz.push(c as f64 / (m - 1) as f64);
        }
    }
    let mut conn = Vec::new();
    for cell in 0..n.pow(d as u32) {
        let mut rest = cell;
        let base: Vec<usize> = (0..d)
            .map(|_| {
                let c = rest % n;
                rest /= n;
                c * per
            })
            .collect();
        for &l in cell_type.lattice() {
            let lc: Vec<usize> = if d == 2 {
                lattice::coords::<2>(l).to_vec()
            } else {
                lattice::coords::<3>(l).to_vec()
            };
            let c: Vec<usize> = (0..d)
                .map(|k| base[k] + if quadratic { lc[k] } else { lc[k] / 2 })
                .collect();
            conn.push(index(&c) as i64);
        }
    }
    (xyz, conn)
}

/// Mask fixing every coordinate of the nodes on the boundary of [0,1]^d.
pub fn boundary_mask(xyz: &[f64], d: usize) -> Vec<u8> {
    xyz.chunks(3)
        .map(|p| {
            let on_boundary = p[..d].iter().any(|&v| v == 0.0 || v == 1.0);
            if on_boundary {
                (1u8 << d) - 1
            } else {
                0
            }
        })
        .collect()
}

/// `xyz` (3 per node, on [0,1]^d) with the top side (2D) or face (3D) pushed down by
/// `depth · Π sin(π t)` over its other coordinates: a bump or a dome.
pub fn bump_top(xyz: &[f64], d: usize, depth: f64) -> Vec<f64> {
    let mut moved = xyz.to_vec();
    for p in moved.chunks_mut(3) {
        if p[d - 1] == 1.0 {
            let bump: f64 = p[..d - 1]
                .iter()
                .map(|&t| (std::f64::consts::PI * t).sin())
                .product();
            p[d - 1] -= depth * bump;
        }
    }
    moved
}

/// A small linear congruential generator, uniform in [-1, 1).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// Reads a bundled test mesh with its prescribed motion.
pub fn load_case(name: &str) -> igaparam::Mesh {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    let grid = igaparam::io::vtu::read(&path).expect("test mesh");
    igaparam::Mesh::from_grid_with_motion(&grid).expect("test mesh motion")
}

/// Path of a file in `tests/data/boundary`.
pub fn boundary_data(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/boundary")
        .join(name)
}

/// The bundled planar boundaries: the four G+Smo comparison domains and two coastlines.
pub const PLANAR_DOMAINS: [&str; 6] = [
    "puzzle3_bdry.xml",
    "rotor_bdry.xml",
    "male_bdry.xml",
    "duck2d_BRep.xml",
    "tenerife.txt",
    "gran_canaria.txt",
];

/// The planar boundary of a bundled file: a coastline (`.txt`) or a G+Smo B-rep.
pub fn planar_boundary(name: &str) -> igaparam::boundary::BoundaryLoop2 {
    use igaparam::boundary::{BoundaryLoop2, Coastline};
    if name.ends_with(".txt") {
        BoundaryLoop2::from_coastline(&Coastline::read(boundary_data(name)).unwrap()).unwrap()
    } else {
        BoundaryLoop2::from_gismo_file(boundary_data(name)).unwrap()
    }
}

/// The boundary of the unit cube mapped by a function.
pub struct MappedCube<F>(pub F);

impl<F: Fn([f64; 3]) -> [f64; 3]> igaparam::domain::CubeMap<3> for MappedCube<F> {
    fn boundary_point(&self, p: [f64; 3]) -> [f64; 3] {
        (self.0)(p)
    }
}

/// A box whose top bulges and whose sides are sheared and waved.
pub fn curved_box([x, y, z]: [f64; 3]) -> [f64; 3] {
    use std::f64::consts::PI;
    [
        2.0 * x + 0.3 * z + 0.1 * (PI * y).sin(),
        y + 0.15 * (2.0 * PI * x).sin() * z,
        z * (1.0 + 0.4 * (PI * x).sin() * (PI * y).sin()),
    ]
}

/// The boundary of `[0,1]²` mapped by `f`, as four polylines of `n` segments.
pub fn mapped_square(
    f: impl Fn([f64; 2]) -> [f64; 2],
    n: usize,
) -> igaparam::boundary::BoundaryLoop2 {
    let side = |a: [f64; 2], b: [f64; 2]| {
        let points = (0..=n)
            .map(|i| {
                let t = i as f64 / n as f64;
                f([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])])
            })
            .collect();
        igaparam::boundary::Curve2::polyline(points).unwrap()
    };
    igaparam::boundary::BoundaryLoop2::from_curves(vec![
        side([0.0, 0.0], [0.0, 1.0]),
        side([1.0, 0.0], [1.0, 1.0]),
        side([0.0, 0.0], [1.0, 0.0]),
        side([0.0, 1.0], [1.0, 1.0]),
    ])
    .unwrap()
}

/// The spline map fitted to a domain's optimized T-mesh, certified and untangled where needed,
/// with the default options (`SplineMap::fit_tmesh_checked`): the map, the fit's report and
/// the validity report.
pub fn checked_fit<const D: usize, B: igaparam::domain::CubeMap<D>>(
    domain: &igaparam::domain::Domain<D, B>,
) -> (
    igaparam::spline::SplineMap<D>,
    igaparam::spline::FitReport,
    igaparam::spline::ValidityReport,
) {
    igaparam::spline::SplineMap::fit_tmesh_checked(
        domain.mesh(),
        domain.positions(),
        &igaparam::spline::ValidityOptions::default(),
        &igaparam::spline::UntangleOptions::default(),
    )
    .unwrap()
}

/// A structured grid of `n^d` cells on [0,1]^d (`grid`) whose top side is bent into a bump (2D)
/// or whose top face is domed (3D) by `depth` (`bump_top`), with the boundary prescribed;
/// everything scaled by `s`.
pub fn bumped(cell_type: CellType, n: usize, depth: f64, s: f64) -> igaparam::Mesh {
    let d = cell_type.dimension();
    let (xyz, conn) = grid(cell_type, n);
    let mask = boundary_mask(&xyz, d);
    let scaled: Vec<f64> = xyz.iter().map(|v| v * s).collect();
    let mut mesh = igaparam::Mesh::new(cell_type, &scaled, &conn).unwrap();
    mesh.set_fixed(&mask).unwrap();
    let moved: Vec<f64> = bump_top(&xyz, d, depth).iter().map(|v| v * s).collect();
    mesh.move_nodes(None, &moved).unwrap();
    mesh
}
