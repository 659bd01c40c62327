//! Triangulated surfaces read from OBJ files, their boundary loop, and Floater's mean-value
//! parameterization of a disk-like triangulation onto the unit square.

// Index loops over coordinates and vertices read best in this numerical code.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;
use std::path::Path;

use super::bspline::Vec3;
use super::curve::Point2;
use crate::error::{Error, ErrorKind, Result};

/// A triangle mesh: vertex positions and 0-based vertex triples.
#[derive(Clone, Debug, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub vertices: Vec<Vec3>,
    /// Triangles as 0-based vertex indices.
    pub triangles: Vec<[usize; 3]>,
}

fn sub3(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn norm3(a: Vec3) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

fn cross3(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot3(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl TriMesh {
    /// Validates a mesh: finite coordinates, indices in range, no triangle repeating a vertex.
    pub fn new(vertices: Vec<Vec3>, triangles: Vec<[usize; 3]>) -> Result<Self> {
        for (i, v) in vertices.iter().enumerate() {
            if v.iter().any(|x| !x.is_finite()) {
                return Err(Error::new(
                    ErrorKind::NotFinite,
                    format!("vertex {i} is {v:?}, coordinates must be finite"),
                ));
            }
        }
        for (t, tri) in triangles.iter().enumerate() {
            if let Some(&i) = tri.iter().find(|&&i| i >= vertices.len()) {
                return Err(Error::mesh(format!(
                    "triangle {t} uses vertex {i}, but there are {} vertices",
                    vertices.len()
                )));
            }
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
                return Err(Error::mesh(format!(
                    "triangle {t} repeats a vertex: {tri:?}"
                )));
            }
        }
        Ok(TriMesh {
            vertices,
            triangles,
        })
    }

    /// Parses OBJ text: `v x y z` vertex lines and `f a b c` triangle lines (1-based, negative
    /// indices relative to the end; `a/b/c` and `a//c` forms accepted, only the vertex index is
    /// used); other lines are ignored. Faces with more than three vertices are fanned into
    /// triangles.
    pub fn parse_obj(text: &str) -> Result<Self> {
        let mut vertices: Vec<Vec3> = Vec::new();
        let mut triangles = Vec::new();
        for (ln, line) in text.lines().enumerate() {
            let ln = ln + 1;
            let mut toks = line.split_whitespace();
            match toks.next() {
                Some("v") => {
                    let vals: Vec<f64> = toks
                        .take(3)
                        .map(|t| t.parse::<f64>())
                        .collect::<std::result::Result<_, _>>()
                        .map_err(|_| Error::io(format!("line {ln}: bad vertex '{line}'")))?;
                    if vals.len() != 3 {
                        return Err(Error::io(format!(
                            "line {ln}: a vertex needs 3 coordinates: '{line}'"
                        )));
                    }
                    vertices.push([vals[0], vals[1], vals[2]]);
                }
                Some("f") => {
                    let mut idx = Vec::new();
                    for t in toks {
                        let first = t.split('/').next().unwrap_or("");
                        let i: i64 = first
                            .parse()
                            .map_err(|_| Error::io(format!("line {ln}: bad face index '{t}'")))?;
                        let n = vertices.len() as i64;
                        let i0 = if i > 0 { i - 1 } else { n + i };
                        if i == 0 || i0 < 0 {
                            return Err(Error::io(format!(
                                "line {ln}: face index {i} is out of range"
                            )));
                        }
                        idx.push(i0 as usize);
                    }
                    if idx.len() < 3 {
                        return Err(Error::io(format!(
                            "line {ln}: a face needs at least 3 vertices"
                        )));
                    }
                    for k in 1..idx.len() - 1 {
                        triangles.push([idx[0], idx[k], idx[k + 1]]);
                    }
                }
                _ => {}
            }
        }
        Self::new(vertices, triangles)
    }

    /// Reads an OBJ file (see [`parse_obj`](Self::parse_obj)).
    pub fn read_obj(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::io(format!("cannot read {}: {e}", path.display())))?;
        Self::parse_obj(&text)
            .map_err(|e| Error::new(e.kind, format!("{}: {}", path.display(), e.message)))
    }

    /// The boundary of a disk-like mesh as one closed vertex loop, in the direction of the
    /// triangles' edges (the interior on the left when the triangles are counter-clockwise).
    /// An error if the boundary is empty, not a single loop, or an edge is used by more than two
    /// triangles or twice in the same direction.
    pub fn boundary_loop(&self) -> Result<Vec<usize>> {
        let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
        for tri in &self.triangles {
            for k in 0..3 {
                let e = (tri[k], tri[(k + 1) % 3]);
                let c = directed.entry(e).or_insert(0);
                *c += 1;
                if *c > 1 {
                    return Err(Error::mesh(format!(
                        "edge {}-{} is used twice in the same direction (inconsistent orientation or non-manifold)",
                        e.0, e.1
                    )));
                }
            }
        }
        let mut next: HashMap<usize, usize> = HashMap::new();
        for &(a, b) in directed.keys() {
            if !directed.contains_key(&(b, a)) && next.insert(a, b).is_some() {
                return Err(Error::mesh(format!(
                    "vertex {a} starts two boundary edges (the boundary is not a simple loop)"
                )));
            }
        }
        let Some(&start) = next.keys().min() else {
            return Err(Error::mesh("the mesh has no boundary (closed surface)"));
        };
        let mut lp = vec![start];
        let mut v = next[&start];
        while v != start {
            lp.push(v);
            v = *next.get(&v).ok_or_else(|| {
                Error::mesh(format!("boundary ends at vertex {v} without closing"))
            })?;
            if lp.len() > next.len() {
                return Err(Error::mesh("boundary does not close"));
            }
        }
        if lp.len() != next.len() {
            return Err(Error::mesh(format!(
                "the boundary has several loops ({} of its {} edges in the first); the mesh is not a disk",
                lp.len(),
                next.len()
            )));
        }
        Ok(lp)
    }
}

/// Smallest sine of a triangle's angle that [`floater_parameterize`] accepts: thinner triangles
/// (those of faces whose coordinates mix units, a terrain in degrees and metres) are refused as
/// degenerate, as one with an angle of 180° is, so that a caller can retry in other
/// coordinates.
pub(crate) const SLIVER: f64 = 1e-7;

/// Floater's mean-value parameterization of a disk-like triangulation onto the unit square.
///
/// `corners` are the vertices sent to (0,0), (1,0), (1,1), (0,1); they must lie on the boundary
/// loop in that cyclic order along [`TriMesh::boundary_loop`] (then counter-clockwise triangles
/// keep a positive orientation). The boundary vertices between two corners are placed on the
/// square's side by chord length; every interior vertex is the weighted mean of its neighbours
/// with w_ij = (tan(α/2) + tan(β/2)) / |v_j − v_i|, α and β the angles at v_i of the two
/// triangles sharing edge ij; a triangle with an angle whose sine is under 10⁻⁷ is an
/// error. The sparse linear system (an irreducibly diagonally dominant
/// M-matrix) is solved by a sparse LU. Returns the (u, v) of every vertex.
pub fn floater_parameterize(mesh: &TriMesh, corners: [usize; 4]) -> Result<Vec<Point2>> {
    let lp = mesh.boundary_loop()?;
    let cpos = corner_positions(&lp, corners)?;
    let (mut uv, fixed) = boundary_by_chord_length(mesh, &lp, cpos)?;
    let weights = mean_value_weights(mesh, &fixed)?;
    solve_mean_value(&weights, &fixed, &mut uv)?;
    // Floater's theorem makes the map one-to-one; where the triangles are so thin that their
    // angles round to 0 or π, the computed one can fold: say so rather than return it.
    let folded = signed_areas(mesh, &uv)
        .iter()
        .filter(|&&a| a.is_nan() || a <= 0.0)
        .count();
    if folded > 0 {
        return Err(Error::mesh(format!(
            "the mean-value map folds {folded} of {} triangles (degenerate triangles: angles \
             that round to 0 or π)",
            mesh.triangles.len()
        )));
    }
    Ok(uv)
}

/// The places of the `corners` along the boundary loop `lp`; fails unless they are distinct
/// and in that cyclic order.
fn corner_positions(lp: &[usize], corners: [usize; 4]) -> Result<[usize; 4]> {
    let pos: HashMap<usize, usize> = lp.iter().enumerate().map(|(k, &v)| (v, k)).collect();
    let mut cpos = [0usize; 4];
    for k in 0..4 {
        cpos[k] = *pos.get(&corners[k]).ok_or_else(|| {
            Error::invalid(format!(
                "corner vertex {} is not on the boundary loop",
                corners[k]
            ))
        })?;
    }
    let n = lp.len();
    let rel = cpos.map(|c| (c + n - cpos[0]) % n);
    if !(rel[0] < rel[1] && rel[1] < rel[2] && rel[2] < rel[3]) {
        return Err(Error::invalid(format!(
            "corners {corners:?} are not distinct and in order along the boundary loop"
        )));
    }
    Ok(cpos)
}

/// The start of the map: the boundary vertices between two corners (at `cpos` along the loop
/// `lp`) placed on the square's side by chord length and marked fixed, the others at the centre.
fn boundary_by_chord_length(
    mesh: &TriMesh,
    lp: &[usize],
    cpos: [usize; 4],
) -> Result<(Vec<Point2>, Vec<bool>)> {
    let n = lp.len();
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let nv = mesh.vertices.len();
    let mut uv = vec![[0.5, 0.5]; nv];
    let mut fixed = vec![false; nv];
    for s in 0..4 {
        let (a, b) = (cpos[s], cpos[(s + 1) % 4]);
        let len = (b + n - a) % n;
        let run: Vec<usize> = (0..=len).map(|k| lp[(a + k) % n]).collect();
        let mut acc = vec![0.0];
        for w in run.windows(2) {
            let d = norm3(sub3(mesh.vertices[w[1]], mesh.vertices[w[0]]));
            acc.push(acc.last().unwrap() + d);
        }
        let total = *acc.last().unwrap();
        if total <= 0.0 {
            return Err(Error::invalid(format!(
                "side {s} of the boundary has zero length"
            )));
        }
        let (p, q) = (square[s], square[(s + 1) % 4]);
        for (k, &v) in run.iter().enumerate() {
            let r = acc[k] / total;
            uv[v] = [p[0] + r * (q[0] - p[0]), p[1] + r * (q[1] - p[1])];
            fixed[v] = true;
        }
    }
    Ok((uv, fixed))
}

/// The mean-value weights of the free vertices, as triplets `(i, j, w_ij)` (duplicates add up in
/// the sparse matrix); fails on a triangle with a zero-length edge or a sliver.
fn mean_value_weights(mesh: &TriMesh, fixed: &[bool]) -> Result<Vec<(usize, usize, f64)>> {
    let mut weights: Vec<(usize, usize, f64)> = Vec::new();
    for tri in &mesh.triangles {
        for k in 0..3 {
            let (i, j, l) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            if fixed[i] {
                continue;
            }
            let (ej, el) = (
                sub3(mesh.vertices[j], mesh.vertices[i]),
                sub3(mesh.vertices[l], mesh.vertices[i]),
            );
            let (nj, nl) = (norm3(ej), norm3(el));
            if nj == 0.0 || nl == 0.0 {
                return Err(Error::mesh(format!(
                    "triangle {tri:?} has a zero-length edge"
                )));
            }
            // tan(α/2) = |a×b| / (|a||b| + a·b), or (|a||b| − a·b) / |a×b| for obtuse angles:
            // no cancellation, finite for angles up to (not including) π.
            let (cross, dot) = (norm3(cross3(ej, el)), dot3(ej, el));
            if cross < SLIVER * nj * nl {
                return Err(Error::mesh(format!(
                    "triangle {tri:?} is degenerate (an angle whose sine is {:.1e}, under \
                     {SLIVER:e})",
                    cross / (nj * nl)
                )));
            }
            let half_tan = if dot >= 0.0 {
                cross / (nj * nl + dot)
            } else {
                (nj * nl - dot) / cross
            };
            weights.push((i, j, half_tan / nj));
            weights.push((i, l, half_tan / nl));
        }
    }
    Ok(weights)
}

/// Solves the mean-value system for the free vertices: `Σ_j w_ij (uv_i − uv_j) = 0` for every
/// free vertex `i` with weights (`weights`: `(i, j, w_ij)`, repeated pairs adding up), the fixed
/// ones keeping their `uv`. The matrix is an irreducibly diagonally dominant M-matrix,
/// non-symmetric (w_ij ≠ w_ji): sparse LU by faer, both coordinates at once.
fn solve_mean_value(
    weights: &[(usize, usize, f64)],
    fixed: &[bool],
    uv: &mut [Point2],
) -> Result<()> {
    let mut sum = vec![0.0f64; uv.len()];
    for &(i, _, w) in weights {
        sum[i] += w;
    }
    // Unknowns: the free vertices with neighbours, in vertex order.
    let mut unknown = vec![usize::MAX; uv.len()];
    let mut free = Vec::new();
    for i in 0..uv.len() {
        if !fixed[i] && sum[i] != 0.0 {
            unknown[i] = free.len();
            free.push(i);
        }
    }
    if let Some(&i) = free
        .iter()
        .find(|&&i| !(sum[i] > 0.0 && sum[i].is_finite()))
    {
        return Err(Error::mesh(format!(
            "vertex {i} has degenerate neighbouring triangles"
        )));
    }
    if free.is_empty() {
        return Ok(());
    }
    // Rows scaled by the weight sums: unit diagonal, off-diagonal −w_ij / Σ_j w_ij.
    let mut entries: Vec<(usize, usize, f64)> = (0..free.len()).map(|k| (k, k, 1.0)).collect();
    let mut rhs = vec![[0.0; 2]; free.len()];
    for &(i, j, w) in weights {
        let r = unknown[i];
        let c = w / sum[i];
        if unknown[j] != usize::MAX {
            entries.push((r, unknown[j], -c));
        } else {
            for k in 0..2 {
                rhs[r][k] += c * uv[j][k];
            }
        }
    }
    let lu = crate::sparse::SparseSolver::lu(free.len(), &entries)
        .map_err(|e| Error::mesh(format!("mean-value parameterization: {}", e.message)))?;
    lu.solve(&mut rhs);
    if rhs.iter().flatten().any(|v| !v.is_finite()) {
        return Err(Error::mesh(
            "mean-value parameterization: the solution is not finite",
        ));
    }
    for (&i, x) in free.iter().zip(rhs) {
        uv[i] = x;
    }
    Ok(())
}

/// Twice the signed area of the image of every triangle under `uv` (positive when
/// counter-clockwise).
pub fn signed_areas(mesh: &TriMesh, uv: &[Point2]) -> Vec<f64> {
    mesh.triangles
        .iter()
        .map(|t| {
            let (a, b, c) = (uv[t[0]], uv[t[1]], uv[t[2]]);
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        })
        .collect()
}

/// The names of the six faces of the parametric cube, in the order of [`CubeFaces`]: the face
/// `xmin` is x = 0, and so on.
pub const CUBE_FACE_NAMES: [&str; 6] = ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"];

/// The six triangulated faces of a solid bounded like the cube \[0,1\]^3, in the order of
/// [`CUBE_FACE_NAMES`]; faces that touch share their edge vertices with identical coordinates.
#[derive(Clone, Debug)]
pub struct CubeFaces {
    /// The faces.
    pub faces: [TriMesh; 6],
}

fn key(p: Vec3) -> [u64; 3] {
    // +0.0 and -0.0 are the same point.
    p.map(|x| if x == 0.0 { 0 } else { x.to_bits() })
}

/// The corners of face `f` (mesh `m`, boundary loop `lp`): its loop vertices shared with two
/// other faces (`owners` telling which faces hold each point), each with its square coordinates
/// in the face's in-plane axes `(a, b)`. Fails unless there are four that sit at cube corners.
fn face_corners(
    m: &TriMesh,
    f: usize,
    (a, b): (usize, usize),
    lp: &[usize],
    owners: &HashMap<[u64; 3], u8>,
) -> Result<Vec<(usize, [usize; 2])>> {
    let name = CUBE_FACE_NAMES[f];
    let mut corners: Vec<(usize, [usize; 2])> = Vec::new();
    for &v in lp {
        let mask = owners[&key(m.vertices[v])];
        if (mask & !(1 << f)).count_ones() != 2 {
            continue;
        }
        let mut sq = [usize::MAX; 2];
        for g in 0..6 {
            if mask & (1 << g) != 0 && g != f {
                let gaxis = g / 2;
                let k = if gaxis == a {
                    0
                } else if gaxis == b {
                    1
                } else {
                    usize::MAX
                };
                if k == usize::MAX || sq[k] != usize::MAX {
                    return Err(Error::mesh(format!(
                        "face {name}: vertex {v} is shared with faces that do not meet at a cube corner"
                    )));
                }
                sq[k] = g % 2;
            }
        }
        corners.push((v, sq));
    }
    if corners.len() != 4 {
        return Err(Error::mesh(format!(
            "face {name} has {} vertices shared with two other faces, expected 4 corners",
            corners.len()
        )));
    }
    Ok(corners)
}

impl CubeFaces {
    /// Reads `xmin.obj`, `xmax.obj`, ..., `zmax.obj` from a folder.
    pub fn read_dir(dir: impl AsRef<Path>) -> Result<Self> {
        let dir = dir.as_ref();
        let mut faces = Vec::with_capacity(6);
        for name in CUBE_FACE_NAMES {
            faces.push(TriMesh::read_obj(dir.join(format!("{name}.obj")))?);
        }
        Ok(CubeFaces {
            faces: faces.try_into().expect("six faces"),
        })
    }

    /// Multiplies the coordinates of every vertex by `factors`, axis by axis: for data whose
    /// axes have different units (a terrain in degrees and metres, say). Floater's
    /// parameterization measures the faces' angles in these coordinates, so the T-mesh and the
    /// spline map depend on them, not only their physical figures. Shared vertices stay shared.
    /// An error if a factor is not finite and positive; then nothing changes.
    pub fn scale(&mut self, factors: Vec3) -> Result<()> {
        super::scale::check_scale_factors(factors)?;
        for m in self.faces.iter_mut() {
            for v in m.vertices.iter_mut() {
                for (x, f) in v.iter_mut().zip(factors) {
                    *x *= f;
                }
            }
        }
        Ok(())
    }

    /// Maps every vertex of every face into the cube \[0,1\]^3: the face's own coordinate is 0 or
    /// 1, the other two come from [`floater_parameterize`] onto the unit square (in increasing
    /// axis order, e.g. (y, z) on `xmin`), with the face's corners — its vertices shared with two
    /// other faces — sent to the cube corners those faces meet at. Errors when a face does not
    /// have exactly four such corners, or a corner is not where the faces it touches say.
    pub fn parameterize(&self) -> Result<[Vec<Vec3>; 6]> {
        // Which faces hold each point.
        let mut owners: HashMap<[u64; 3], u8> = HashMap::new();
        for (f, m) in self.faces.iter().enumerate() {
            for &v in &m.vertices {
                *owners.entry(key(v)).or_insert(0) |= 1 << f;
            }
        }
        let mut out: Vec<Vec<Vec3>> = Vec::with_capacity(6);
        for f in 0..6 {
            out.push(self.parameterize_face(f, &owners)?);
        }
        Ok(out.try_into().expect("six faces"))
    }

    /// Face `f` mapped onto its cube face, `owners` telling which faces hold each point.
    fn parameterize_face(&self, f: usize, owners: &HashMap<[u64; 3], u8>) -> Result<Vec<Vec3>> {
        let m = &self.faces[f];
        let name = CUBE_FACE_NAMES[f];
        let axis = f / 2;
        let (a, b) = match axis {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let lp = m.boundary_loop()?;
        let corners = face_corners(m, f, (a, b), &lp, owners)?;
        let find = |s: [usize; 2]| -> Result<usize> {
            corners
                .iter()
                .find(|c| c.1 == s)
                .map(|c| c.0)
                .ok_or_else(|| {
                    Error::mesh(format!(
                        "face {name} has no corner at square position {s:?}"
                    ))
                })
        };
        let (c00, c10, c11, c01) = (find([0, 0])?, find([1, 0])?, find([1, 1])?, find([0, 1])?);
        // Along the loop after c00 comes c10 (counter-clockwise) or c01 (then swap axes).
        let pos = |v: usize| lp.iter().position(|&x| x == v).unwrap();
        let n = lp.len();
        let d = |v: usize| (pos(v) + n - pos(c00)) % n;
        let swap = d(c01) < d(c10);
        let uv = if swap {
            floater_parameterize(m, [c00, c01, c11, c10])?
                .into_iter()
                .map(|p| [p[1], p[0]])
                .collect::<Vec<_>>()
        } else {
            floater_parameterize(m, [c00, c10, c11, c01])?
        };
        Ok(uv
            .into_iter()
            .map(|p| {
                let mut x = [0.0; 3];
                x[axis] = (f % 2) as f64;
                x[a] = p[0];
                x[b] = p[1];
                x
            })
            .collect())
    }
}
