//! The boundary of a solid on the boundary of the unit cube: G+Smo B-rep and triangulated faces.

use std::collections::HashMap;

use crate::common;

use igaparam::boundary::*;
use igaparam::spline::{
    FitReport, QuadraticMap, SplineMap, UntangleOptions, ValidityOptions, ValidityReport,
};
use igaparam::ErrorKind;

fn data(name: &str) -> String {
    format!("{}/tests/data/boundary/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The in-plane coordinates of a cube point on face `f` (increasing axis order).
fn in_plane(f: usize, p: [f64; 3]) -> (f64, f64) {
    match f / 2 {
        0 => (p[1], p[2]),
        1 => (p[0], p[2]),
        _ => (p[0], p[1]),
    }
}

/// The largest distance, relative to the bounding-box diagonal, between the evaluations of a
/// cube edge or corner point from the faces containing it (and from `eval`), over 20 points
/// per edge.
fn edge_mismatch(s: &SolidBoundary) -> f64 {
    let mut worst: f64 = 0.0;
    for axis in 0..3 {
        for other in 0..4 {
            for k in 0..20 {
                let mut p = [0.0; 3];
                p[axis] = k as f64 / 19.0;
                let (o1, o2) = ((axis + 1) % 3, (axis + 2) % 3);
                p[o1] = (other & 1) as f64;
                p[o2] = (other >> 1) as f64;
                let faces: Vec<usize> = (0..6).filter(|&f| p[f / 2] == (f % 2) as f64).collect();
                assert!(faces.len() >= 2);
                let reference = s.eval(p);
                for &f in &faces {
                    let (a, b) = in_plane(f, p);
                    let x = s.eval_face(f, a, b);
                    assert!(x.iter().all(|v| v.is_finite()));
                    worst = worst.max(dist(x, reference));
                }
            }
        }
    }
    worst / s.diagonal()
}

/// Every face is finite on a 30 × 30 grid and stays near the bounding box.
fn check_grid(s: &SolidBoundary) {
    let (lo, hi) = s.bounding_box();
    let slack = 1e-9 * s.diagonal();
    for f in 0..6 {
        for j in 0..30 {
            for i in 0..30 {
                let (a, b) = (i as f64 / 29.0, j as f64 / 29.0);
                let x = s.eval_face(f, a, b);
                for d in 0..3 {
                    assert!(x[d].is_finite(), "face {f} at ({a}, {b}) gives {x:?}");
                    assert!(x[d] >= lo[d] - slack && x[d] <= hi[d] + slack);
                }
            }
        }
    }
}

/// The surfaces' corner points, `[surface][s + 2t]`.
fn surface_corners(surfaces: &[BSplineSurface]) -> Vec<[[f64; 3]; 4]> {
    surfaces
        .iter()
        .map(|s| {
            let ((u0, u1), (v0, v1)) = s.domain();
            [
                s.eval(u0, v0),
                s.eval(u1, v0),
                s.eval(u0, v1),
                s.eval(u1, v1),
            ]
        })
        .collect()
}

#[test]
fn duck_brep_edges_and_corners() {
    let path = data("duck3d_BRep.xml");
    let s = SolidBoundary::from_gismo_file(&path).unwrap();
    assert!(s.vertex_parameters(0).is_none());
    let mismatch = edge_mismatch(&s);
    eprintln!("duck B-rep: largest edge mismatch {mismatch:.3e} of the diagonal");
    assert!(mismatch <= 1e-9, "{mismatch}");
    // The file is in G+Smo side order: cube corner (i, j, k) is the corner shared by surfaces
    // i (west/east), 2 + j (south/north) and 4 + k (front/back).
    let surfaces = read_gismo_surfaces(&path).unwrap();
    let sc = surface_corners(&surfaces);
    let tol = 1e-9 * s.diagonal();
    let corners = s.corners();
    for c in 0..8 {
        let (i, j, k) = (c & 1, (c >> 1) & 1, c >> 2);
        for surf in [i, 2 + j, 4 + k] {
            assert!(
                sc[surf].iter().any(|&q| dist(q, corners[c]) <= tol),
                "corner {c} is not a corner of surface {surf}"
            );
        }
        let p = [i as f64, j as f64, k as f64];
        assert!(dist(s.eval(p), corners[c]) <= tol);
        for d in 0..c {
            assert!(dist(corners[c], corners[d]) > 1e-3 * s.diagonal());
        }
    }
    check_grid(&s);
}

/// The OBJ checks: shared edges, corners (the vertex shared by faces x_i, y_j, z_k), and every
/// vertex returned at its cube-face coordinates. Returns the relative edge mismatch.
fn check_obj_solid(dir: &str) -> f64 {
    let s = SolidBoundary::from_obj_dir(dir).unwrap();
    let mismatch = edge_mismatch(&s);
    let cube = CubeFaces::read_dir(dir).unwrap();
    let key = |p: [f64; 3]| p.map(|x| if x == 0.0 { 0 } else { x.to_bits() });
    let mut owners: HashMap<[u64; 3], (u8, [f64; 3])> = HashMap::new();
    for (f, m) in cube.faces.iter().enumerate() {
        for &v in &m.vertices {
            owners.entry(key(v)).or_insert((0, v)).0 |= 1 << f;
        }
    }
    for (c, &corner) in s.corners().iter().enumerate() {
        let mask = (1u8 << (c & 1)) | (1 << (2 + ((c >> 1) & 1))) | (1 << (4 + (c >> 2)));
        let found: Vec<[f64; 3]> = owners
            .values()
            .filter(|o| o.0 & mask == mask)
            .map(|o| o.1)
            .collect();
        assert_eq!(found.len(), 1, "corner {c}");
        assert_eq!(corner, found[0], "corner {c}");
        let p = [(c & 1) as f64, ((c >> 1) & 1) as f64, (c >> 2) as f64];
        assert_eq!(s.eval(p), found[0]);
    }
    let diag = s.diagonal();
    let mut worst: f64 = 0.0;
    for (f, m) in cube.faces.iter().enumerate() {
        let par = s.vertex_parameters(f).unwrap();
        assert_eq!(par.len(), m.vertices.len());
        for (v, &[a, b]) in m.vertices.iter().zip(par.iter()) {
            worst = worst.max(dist(s.eval_face(f, a, b), *v));
            // Through `eval`, a vertex on an edge may be evaluated from another face.
            let mut p = [(f % 2) as f64; 3];
            let others: Vec<usize> = (0..3).filter(|&d| d != f / 2).collect();
            p[others[0]] = a;
            p[others[1]] = b;
            assert!(dist(s.eval(p), *v) <= 1e-9 * diag);
        }
    }
    eprintln!(
        "{dir}: largest edge mismatch {mismatch:.3e}, largest vertex error {:.3e} of the diagonal",
        worst / diag
    );
    assert!(worst <= 1e-12 * diag, "{}", worst / diag);
    check_grid(&s);
    mismatch
}

#[test]
fn duck_obj_edges_corners_vertices() {
    let dir = data("duck_faces");
    let mismatch = check_obj_solid(&dir);
    assert!(mismatch <= 1e-9, "{mismatch}");
    // A well-proportioned solid keeps the parameterization of `CubeFaces::parameterize` (up to
    // round-off: its iterative solve sums in hash-map order, which varies between runs).
    let s = SolidBoundary::from_obj_dir(&dir).unwrap();
    let params = CubeFaces::read_dir(&dir).unwrap().parameterize().unwrap();
    for (f, par) in params.iter().enumerate() {
        let got = s.vertex_parameters(f).unwrap();
        for (p, q) in par.iter().zip(got.iter()) {
            let (a, b) = in_plane(f, *p);
            assert!((a - q[0]).abs() <= 1e-12 && (b - q[1]).abs() <= 1e-12);
        }
    }
}

#[test]
fn jacksboro_obj_edges_corners_vertices() {
    let mismatch = check_obj_solid(&data("jacksboro_faces"));
    assert!(mismatch <= 1e-9, "{mismatch}");
}

/// The Jacksboro faces mix units (x, y in degrees / 1000, z in km): in the file's coordinates
/// the walls' triangles are slivers (angles whose sine is 2e-8), on which mean-value weights
/// measure nothing of the surface, so Floater's map refuses them and the solid uses the map of
/// the faces normalized to their bounding box.
#[test]
fn jacksboro_faces_map_in_the_normalized_box() {
    let cube = CubeFaces::read_dir(data("jacksboro_faces")).unwrap();
    let e = cube.parameterize().unwrap_err();
    assert!(e.message.contains("degenerate"), "{}", e.message);
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in cube.faces.iter().flat_map(|m| m.vertices.iter()) {
        for d in 0..3 {
            lo[d] = lo[d].min(v[d]);
            hi[d] = hi[d].max(v[d]);
        }
    }
    let mut normalized = cube.clone();
    for m in normalized.faces.iter_mut() {
        for v in m.vertices.iter_mut() {
            for d in 0..3 {
                v[d] = (v[d] - lo[d]) / (hi[d] - lo[d]);
            }
        }
    }
    let params = normalized.parameterize().unwrap();
    let solid = SolidBoundary::from_cube_faces(&cube).unwrap();
    for (f, face) in params.iter().enumerate() {
        // The face's in-plane axes, in increasing order.
        let (a, b) = match f / 2 {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let uv: Vec<[f64; 2]> = face.iter().map(|p| [p[a], p[b]]).collect();
        assert_eq!(solid.vertex_parameters(f).unwrap(), &uv[..], "face {f}");
    }
}

#[test]
fn eval_off_the_boundary_is_clamped_and_projected() {
    let s = SolidBoundary::from_obj_dir(data("duck_faces")).unwrap();
    // Nearest face of (0.3, 0.5, 0.5) is x = 0.
    assert_eq!(s.eval([0.3, 0.5, 0.5]), s.eval([0.0, 0.5, 0.5]));
    assert_eq!(s.eval([0.5, 1.7, 0.4]), s.eval([0.5, 1.0, 0.4]));
    assert!(s.eval([f64::NAN, 0.0, 0.0]).iter().all(|x| x.is_nan()));
}

#[test]
fn errors_are_clear() {
    // Too few surfaces.
    let mut surfaces = read_gismo_surfaces(data("duck3d_BRep.xml")).unwrap();
    let last = surfaces.pop().unwrap();
    let e = SolidBoundary::from_surfaces(surfaces.clone()).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidArgument);
    // A surface moved away: its corners are no longer shared.
    let (nu, nv) = last.num_control_points();
    let mut coefs = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let p = last.control_point(i, j);
            coefs.extend_from_slice(&[p[0] + 0.01, p[1], p[2]]);
        }
    }
    let ku = last.knot_vector_u();
    let kv = last.knot_vector_v();
    let moved = BSplineSurface::new(
        (ku.degree(), ku.knots().to_vec()),
        (kv.degree(), kv.knots().to_vec()),
        3,
        coefs,
        None,
    )
    .unwrap();
    surfaces.push(moved);
    let e = SolidBoundary::from_surfaces(surfaces).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidMesh);
    assert!(e.message.contains("share"), "{}", e.message);

    // A missing face and a NaN vertex.
    let dir = std::env::temp_dir().join(format!("igaparam_solid_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in CUBE_FACE_NAMES {
        std::fs::copy(
            data(&format!("duck_faces/{name}.obj")),
            dir.join(format!("{name}.obj")),
        )
        .unwrap();
    }
    std::fs::remove_file(dir.join("zmax.obj")).unwrap();
    let e = SolidBoundary::from_obj_dir(&dir).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Io);
    assert!(e.message.contains("zmax"), "{}", e.message);
    let text = std::fs::read_to_string(data("duck_faces/zmax.obj")).unwrap();
    let first_v = text.find("\nv ").unwrap() + 1;
    let end = first_v + text[first_v..].find('\n').unwrap();
    let bad = format!("{}v nan 0 0{}", &text[..first_v], &text[end..]);
    std::fs::write(dir.join("zmax.obj"), bad).unwrap();
    let e = SolidBoundary::from_obj_dir(&dir).unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotFinite, "{}", e.message);
    // Faces that do not share edges: zmax shifted.
    let shifted: String = text
        .lines()
        .map(|l| {
            if let Some(rest) = l.strip_prefix("v ") {
                let x: Vec<f64> = rest
                    .split_whitespace()
                    .map(|t| t.parse().unwrap())
                    .collect();
                format!("v {} {} {}\n", x[0] + 0.01, x[1], x[2])
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    std::fs::write(dir.join("zmax.obj"), shifted).unwrap();
    let e = SolidBoundary::from_obj_dir(&dir).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidMesh, "{}", e.message);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The surface with its two parameters exchanged.
fn transposed(s: &BSplineSurface) -> BSplineSurface {
    let (nu, nv) = s.num_control_points();
    let mut coefs = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            coefs.extend_from_slice(&s.control_point(i, j));
        }
    }
    let (ku, kv) = (s.knot_vector_u(), s.knot_vector_v());
    BSplineSurface::new(
        (kv.degree(), kv.knots().to_vec()),
        (ku.degree(), ku.knots().to_vec()),
        3,
        coefs,
        None,
    )
    .unwrap()
}

#[test]
fn brep_faces_found_from_adjacency_and_orientation_from_corners() {
    let surfaces = read_gismo_surfaces(data("duck3d_BRep.xml")).unwrap();
    let reference = SolidBoundary::from_surfaces(surfaces.clone()).unwrap();
    let tol = 1e-12 * reference.diagonal();

    // A transposed surface: same faces, its parameters reoriented.
    let mut t = surfaces.clone();
    t[2] = transposed(&t[2]);
    let s = SolidBoundary::from_surfaces(t).unwrap();
    assert!(edge_mismatch(&s) <= 1e-9);
    assert_eq!(s.corners(), reference.corners());
    for f in 0..6 {
        for k in 0..=10 {
            let (a, b) = (k as f64 / 10.0, (k * 7 % 11) as f64 / 10.0);
            assert!(dist(s.eval_face(f, a, b), reference.eval_face(f, a, b)) <= tol);
        }
    }

    // Surfaces out of G+Smo side order: faces come from adjacency, and the map is still a
    // consistent map of the cube's boundary onto the same solid.
    let perm = [3, 0, 5, 1, 4, 2];
    let shuffled: Vec<BSplineSurface> = perm.iter().map(|&k| surfaces[k].clone()).collect();
    let s = SolidBoundary::from_surfaces(shuffled).unwrap();
    let mismatch = edge_mismatch(&s);
    assert!(mismatch <= 1e-9, "{mismatch}");
    let mut got: Vec<[f64; 3]> = s.corners().to_vec();
    let mut want: Vec<[f64; 3]> = reference.corners().to_vec();
    got.sort_by(|a, b| a.partial_cmp(b).unwrap());
    want.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(got, want);
    // Face 0 (x = 0) is the first surface given, face 1 its opposite.
    for k in 0..=10 {
        let (a, b) = (k as f64 / 10.0, (k * 3 % 11) as f64 / 10.0);
        let x = s.eval_face(0, a, b);
        let ((u0, u1), (v0, v1)) = surfaces[3].domain();
        // The point lies on surface 3 at some parameter; check it is one of its reorientations.
        let cands = [
            (a, b),
            (b, a),
            (1.0 - a, b),
            (a, 1.0 - b),
            (1.0 - a, 1.0 - b),
        ]
        .into_iter()
        .chain([(1.0 - b, a), (b, 1.0 - a), (1.0 - b, 1.0 - a)]);
        let close = cands
            .map(|(p, q)| surfaces[3].eval(u0 + p * (u1 - u0), v0 + q * (v1 - v0)))
            .any(|y| dist(x, y) <= 1e-9 * s.diagonal());
        assert!(close, "face 0 at ({a}, {b}) is not on surface 3");
    }
}

/// Builds the T-mesh of a triangulated solid and checks that the seam relief opened every cell
/// while every boundary vertex stays within the allowed offset of its point on the boundary
/// (measured in the frame of the bounding box).
fn check_relieved_solid(
    dir: &str,
    tolerance: f64,
    max_level: u8,
    boundary_offset: f64,
) -> igaparam::domain::SolidDomain {
    let boundary = SolidBoundary::from_obj_dir(data(dir)).unwrap();
    check_relieved(boundary, tolerance, max_level, boundary_offset)
}

/// [`check_relieved_solid`] for a boundary at hand.
fn check_relieved(
    boundary: SolidBoundary,
    tolerance: f64,
    max_level: u8,
    boundary_offset: f64,
) -> igaparam::domain::SolidDomain {
    let options = igaparam::domain::SolidOptions {
        tolerance,
        max_level,
        boundary_offset,
        ..Default::default()
    };
    let (domain, report) =
        igaparam::domain::SolidDomain::build(boundary, &options, &mut |_, _| true).unwrap();
    println!("{report:?}");
    assert_eq!(report.invalid_cells, 0, "{report:?}");
    assert!(report.boundary_offset <= options.boundary_offset * (1.0 + 1e-9));
    let frame = domain.frame();
    let mut largest = 0.0f64;
    for (v, mut p) in domain.mesh().parametric().into_iter().enumerate() {
        if !domain.mesh().on_boundary(v) {
            continue;
        }
        if report.swapped {
            p.swap(0, 1);
        }
        let on_surface = frame.to_frame(domain.boundary().eval(p));
        let at = frame.to_frame(domain.positions()[v]);
        largest = largest.max(dist(on_surface, at));
    }
    assert!(
        largest <= options.boundary_offset * (1.0 + 1e-9),
        "{largest}"
    );
    assert!(
        (largest - report.boundary_offset).abs() <= 1e-9,
        "{largest}"
    );
    domain
}

/// The checked fit of a solid's T-mesh (default options), asserted certified valid.
fn certified_fit(
    domain: &igaparam::domain::SolidDomain,
) -> (SplineMap<3>, FitReport, ValidityReport) {
    let (map, fit, validity) = common::checked_fit(domain);
    println!("{fit:?}\n{validity:?}");
    assert!(
        validity.certified_positive,
        "{} uncertified",
        validity.uncertified
    );
    (map, fit, validity)
}

/// The triangulated duck, whose jittered faces meet at reflex angles along parts of the cube's
/// edges.
#[test]
fn duck_faces_give_a_valid_t_mesh_and_a_certified_spline_map() {
    let domain = check_relieved_solid("duck_faces", 1e-4, 4, 1e-2);
    // The fitted map folds next to the cube's edges, where the faces meet almost tangentially;
    // the untangling moves the control points there (boundary ones within the offset).
    let untangle = UntangleOptions::default();
    let (map, fit, validity) = certified_fit(&domain);
    assert!(fit.untangled > 0 && fit.boundary_offset <= untangle.boundary_offset * (1.0 + 1e-9));
    assert_eq!(validity, map.validity(&ValidityOptions::default()));
    // 0.173 (0.041 when the untangling moved the boundary control points of the edge-pinned
    // elements alone, which squeezed their neighbours).
    assert!(validity.min_quality > 0.15, "{}", validity.min_quality);
}

/// The Jacksboro block, whose terrain edge is jagged where it meets the side faces.
#[test]
fn jacksboro_faces_give_a_valid_t_mesh_within_the_boundary_offset() {
    check_relieved_solid("jacksboro_faces", 1e-3, 3, 1e-2);
}

/// The Jacksboro block on a coarser T-mesh whose seams may move 3% of the box: every cell's map
/// is proven valid (not only at its Gauss–Lobatto points) and the spline map is certified.
#[test]
fn jacksboro_faces_give_a_certified_spline_map_on_a_coarse_t_mesh() {
    let domain = check_relieved_solid("jacksboro_faces", 1e-2, 3, 3e-2);
    let cells = QuadraticMap::new(domain.mesh(), domain.positions()).unwrap();
    assert!(cells.uncertified_cells(5).is_empty());
    certified_fit(&domain);
}

/// km per unit of the Jacksboro faces' x and y: they are degrees / 1000 (the DEM's spacing is
/// 1/1200 degree), at latitude 36.6° N; z is in km.
const JACKSBORO_KM: [f64; 3] = [89273.3, 111200.0, 1.0];

/// The Jacksboro block with its axes in one unit (km): the terrain is then nearly flat at the
/// block's scale (0.8 km of relief over 30 km), Floater's map of it nearly a projection, and a
/// T-mesh at tolerance 1e-3 needs neither repair nor seam offsets; the spline map is certified
/// as fitted, with a smallest mean ratio near the paper's 3D figure (0.032).
#[test]
fn jacksboro_in_km_gives_a_certified_spline_map() {
    let mut faces = CubeFaces::read_dir(data("jacksboro_faces")).unwrap();
    faces.scale(JACKSBORO_KM).unwrap();
    let boundary = SolidBoundary::from_cube_faces(&faces).unwrap();
    let (lo, hi) = boundary.bounding_box();
    assert!((hi[0] - lo[0] - 29.98).abs() < 0.01 && (hi[1] - lo[1] - 31.88).abs() < 0.01);
    let domain = check_relieved(boundary, 1e-3, 3, 1e-2);
    let (_, fit, validity) = certified_fit(&domain);
    assert_eq!(fit.untangled, 0);
    assert!(validity.min_quality > 0.02, "{}", validity.min_quality);
}

#[test]
fn scale_factors_are_checked() {
    let mut faces = CubeFaces::read_dir(data("jacksboro_faces")).unwrap();
    let before = faces.faces[0].vertices.clone();
    for bad in [
        [0.0, 1.0, 1.0],
        [1.0, -2.0, 1.0],
        [1.0, 1.0, f64::NAN],
        [f64::INFINITY, 1.0, 1.0],
    ] {
        let e = faces.scale(bad).unwrap_err();
        assert_eq!(e.kind, ErrorKind::InvalidArgument);
        assert!(e.message.contains("finite and positive"), "{}", e.message);
    }
    assert_eq!(faces.faces[0].vertices, before);
    faces.scale([2.0, 3.0, 4.0]).unwrap();
    assert_eq!(faces.faces[0].vertices[1][2], before[1][2] * 4.0);
}

/// `SolidBoundary::from_file_scaled`: factors checked before any I/O; a folder of faces gives
/// the solid of the scaled faces; a B-rep's scaled surfaces are the scaled solid (exactly for a
/// factor 2, to round-off for others); no factors is `from_file`.
#[test]
fn solid_files_read_with_per_axis_factors() {
    let xml = data("duck3d_BRep.xml");
    for bad in [[0.0, 1.0, 1.0], [1.0, -1.0, 1.0], [1.0, 1.0, f64::NAN]] {
        for path in [xml.as_str(), "no/such/file.xml"] {
            let e = SolidBoundary::from_file_scaled(path, Some(bad)).unwrap_err();
            assert_eq!(e.kind, ErrorKind::InvalidArgument);
            assert!(e.message.contains("finite and positive"), "{}", e.message);
        }
    }
    let e = SolidBoundary::from_file_scaled(data("README.md"), Some([2.0; 3])).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidArgument);
    assert!(e.message.contains("not a folder"), "{}", e.message);

    let samples: Vec<(usize, f64, f64)> = (0..6)
        .flat_map(|f| {
            (0..=8).flat_map(move |i| (0..=8).map(move |j| (f, i as f64 / 8.0, j as f64 / 8.0)))
        })
        .collect();
    let plain = SolidBoundary::from_file(&xml).unwrap();
    for (factors, exact) in [([2.0, 2.0, 2.0], true), ([3.0, 0.1, 7.5], false)] {
        let scaled = SolidBoundary::from_file_scaled(&xml, Some(factors)).unwrap();
        let d = scaled.diagonal();
        for &(f, a, b) in &samples {
            let (p, q) = (plain.eval_face(f, a, b), scaled.eval_face(f, a, b));
            let want = [0, 1, 2].map(|k| p[k] * factors[k]);
            if exact {
                assert_eq!(q, want, "face {f} at ({a}, {b})");
            } else {
                assert!(
                    dist(q, want) <= 1e-14 * d,
                    "face {f} at ({a}, {b}): {q:?} {want:?}"
                );
            }
        }
        let corners = plain.corners();
        for (c, q) in scaled.corners().iter().enumerate() {
            let want = [0, 1, 2].map(|k| corners[c][k] * factors[k]);
            assert!(dist(*q, want) <= 1e-14 * d, "corner {c}");
        }
    }

    let dir = data("jacksboro_faces");
    let mut faces = CubeFaces::read_dir(&dir).unwrap();
    faces.scale(JACKSBORO_KM).unwrap();
    let by_hand = SolidBoundary::from_cube_faces(&faces).unwrap();
    let read = SolidBoundary::from_file_scaled(&dir, Some(JACKSBORO_KM)).unwrap();
    for f in 0..6 {
        assert_eq!(
            read.vertex_parameters(f),
            by_hand.vertex_parameters(f),
            "face {f}"
        );
    }
    for &(f, a, b) in &samples {
        assert_eq!(read.eval_face(f, a, b), by_hand.eval_face(f, a, b));
    }
    let unscaled = SolidBoundary::from_file_scaled(&dir, None).unwrap();
    let plain = SolidBoundary::from_obj_dir(&dir).unwrap();
    assert_eq!(unscaled.bounding_box(), plain.bounding_box());
    for f in 0..6 {
        assert_eq!(
            unscaled.vertex_parameters(f),
            plain.vertex_parameters(f),
            "face {f}"
        );
    }
}
