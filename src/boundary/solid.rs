//! The boundary of a solid mapped onto the boundary of the unit cube \[0,1\]^3: six B-spline
//! surfaces of a G+Smo B-rep, or six triangulated faces with a mean-value parameterization each.
//!
//! Every cube face has two in-plane coordinates `(a, b)`, the two coordinates other than the
//! face's own in increasing axis order (`(y, z)` on `x = 0` and `x = 1`, `(x, z)` on `y = 0`
//! and `y = 1`, `(x, y)` on `z = 0` and `z = 1`), as in [`CubeFaces::parameterize`]. Faces are
//! numbered in the order of [`CUBE_FACE_NAMES`]: 0 is x = 0, 1 is x = 1, ..., 5 is z = 1.

// Index loops over coordinates and corners read best in this numerical code.
#![allow(clippy::needless_range_loop)]

use std::path::Path;

use super::bspline::{BSplineSurface, Vec3};
use super::face::{Face, MeshFace, Orientation, SplineFace};
use super::gismo_xml::read_gismo_surfaces;
use super::trimesh::{signed_areas, CubeFaces, CUBE_FACE_NAMES};
use crate::error::{Error, ErrorKind, Result};
use crate::optimize::small_matrix::bounding_box;

/// The boundary of a solid as a map from the boundary of the unit cube \[0,1\]^3: six faces,
/// each mapping its cube face onto one side of the solid, agreeing on the cube's edges.
#[derive(Clone, Debug, PartialEq)]
pub struct SolidBoundary {
    faces: [Face; 6],
    corners: [Vec3; 8],
    bbox: (Vec3, Vec3),
}

/// The face's own axis and its two in-plane axes `(a, b)`.
fn face_axes(face: usize) -> (usize, usize, usize) {
    match face / 2 {
        0 => (0, 1, 2),
        1 => (1, 0, 2),
        _ => (2, 0, 1),
    }
}

/// The point of the cube on `face` with in-plane coordinates `(a, b)`.
fn cube_point(face: usize, a: f64, b: f64) -> Vec3 {
    let (ax, ia, ib) = face_axes(face);
    let mut p = [0.0; 3];
    p[ax] = (face % 2) as f64;
    p[ia] = a;
    p[ib] = b;
    p
}

fn dist3(a: Vec3, b: Vec3) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// `e` with its message prefixed by the file or folder it is about.
fn in_file(path: &Path, e: Error) -> Error {
    Error::new(e.kind, format!("{}: {}", path.display(), e.message))
}

/// The number of samples per cube edge used by the constructors' shared-edge check.
const EDGE_SAMPLES: usize = 21;

/// The relative tolerance (to the bounding-box diagonal) of the constructors' checks.
const REL_TOL: f64 = 1e-9;

/// Checks that there are six surfaces, all in 3D.
fn check_surfaces(surfaces: &[BSplineSurface]) -> Result<()> {
    if surfaces.len() != 6 {
        return Err(Error::invalid(format!(
            "a solid boundary needs 6 surfaces, got {}",
            surfaces.len()
        )));
    }
    for (i, s) in surfaces.iter().enumerate() {
        if s.dim() != 3 {
            return Err(Error::invalid(format!(
                "surface {i} is {}D, a solid boundary needs 3D surfaces",
                s.dim()
            )));
        }
    }
    Ok(())
}

/// The surfaces' corner points (s, t) ∈ {0,1}^2 clustered within `tol`: the clusters'
/// representatives, and per surface the cluster of its corner `s + 2t`. Fails unless there are
/// the 8 of a cube.
fn corner_clusters(surfaces: &[BSplineSurface], tol: f64) -> Result<(Vec<Vec3>, [[usize; 4]; 6])> {
    let unit = |s: &BSplineSurface, a: f64, b: f64| {
        SplineFace {
            surface: s.clone(),
            orientation: Orientation {
                swap: false,
                flip_s: false,
                flip_t: false,
            },
            origin: 0,
        }
        .eval(a, b)
    };
    let mut reps: Vec<Vec3> = Vec::new();
    let mut cid = [[0usize; 4]; 6];
    for (f, s) in surfaces.iter().enumerate() {
        for c in 0..4 {
            let p = unit(s, (c & 1) as f64, (c >> 1) as f64);
            if p.iter().any(|x| !x.is_finite()) {
                return Err(Error::new(
                    ErrorKind::NotFinite,
                    format!("surface {f}: corner {c} evaluates to {p:?}"),
                ));
            }
            cid[f][c] = match reps.iter().position(|&q| dist3(p, q) <= tol) {
                Some(k) => k,
                None => {
                    reps.push(p);
                    reps.len() - 1
                }
            };
        }
    }
    if reps.len() != 8 {
        return Err(Error::mesh(format!(
            "the surfaces' corners form {} distinct points, a cube has 8: the surfaces do not share edges",
            reps.len()
        )));
    }
    Ok((reps, cid))
}

/// The surface opposite each one (the first that shares no corner with it), from the corner
/// clusters `cid`; fails where two surfaces share other than 0 or 2 corners.
fn opposite_surfaces(cid: &[[usize; 4]; 6]) -> Result<[usize; 6]> {
    let shared = |f: usize, g: usize| cid[f].iter().filter(|c| cid[g].contains(c)).count();
    let mut opposite = [usize::MAX; 6];
    for f in 0..6 {
        for g in 0..6 {
            if g == f {
                continue;
            }
            match shared(f, g) {
                0 if opposite[f] == usize::MAX => opposite[f] = g,
                2 => {}
                n => {
                    return Err(Error::mesh(format!(
                        "surfaces {f} and {g} share {n} corners; faces of a cube share 2 (adjacent) or 0 (opposite, one each)"
                    )))
                }
            }
        }
        if opposite[f] == usize::MAX {
            return Err(Error::mesh(format!(
                "surface {f} touches all the others: the surfaces do not bound a cube"
            )));
        }
    }
    Ok(opposite)
}

/// The surface of each cube face (`order[face] = surface`): G+Smo's side order when the
/// surfaces are in it, else the first free surface and its opposite per axis.
fn face_order(opposite: &[usize; 6]) -> [usize; 6] {
    if opposite[0] == 1 && opposite[2] == 3 && opposite[4] == 5 {
        return [0, 1, 2, 3, 4, 5];
    }
    let mut order = [0usize; 6];
    let mut used = [false; 6];
    for axis in 0..3 {
        let f = (0..6).find(|&f| !used[f]).expect("a free surface");
        order[2 * axis] = f;
        order[2 * axis + 1] = opposite[f];
        used[f] = true;
        used[opposite[f]] = true;
    }
    order
}

/// The corner cluster of each cube corner (i, j, k): the one shared by the faces x = i, y = j,
/// z = k.
fn cube_corner_clusters(order: &[usize; 6], cid: &[[usize; 4]; 6]) -> Result<[usize; 8]> {
    let mut corner_cluster = [0usize; 8];
    for c in 0..8 {
        let fs = [order[c & 1], order[2 + ((c >> 1) & 1)], order[4 + (c >> 2)]];
        let common: Vec<usize> = (0..8)
            .filter(|k| fs.iter().all(|&f| cid[f].contains(k)))
            .collect();
        if common.len() != 1 {
            return Err(Error::mesh(format!(
                "surfaces {fs:?} share {} corners, expected exactly one",
                common.len()
            )));
        }
        corner_cluster[c] = common[0];
    }
    Ok(corner_cluster)
}

/// The faces x = 0, ..., z = 1: each cube face's surface, oriented so that its corners land on
/// the cube face's corners.
fn oriented_faces(
    surfaces: &[BSplineSurface],
    order: &[usize; 6],
    cid: &[[usize; 4]; 6],
    corner_cluster: &[usize; 8],
) -> Result<Vec<Face>> {
    let mut faces: Vec<Face> = Vec::with_capacity(6);
    for face in 0..6 {
        let sidx = order[face];
        let orientation = Orientation::all().find(|o| {
            (0..4).all(|c| {
                let (a, b) = ((c & 1) as f64, (c >> 1) as f64);
                let p = cube_point(face, a, b);
                let cube = p[0] as usize + 2 * p[1] as usize + 4 * p[2] as usize;
                let (s, t) = o.apply(a, b);
                cid[sidx][s as usize + 2 * t as usize] == corner_cluster[cube]
            })
        });
        let orientation = orientation.ok_or_else(|| {
            Error::mesh(format!(
                "surface {sidx}: its corners are not those of cube face {}",
                CUBE_FACE_NAMES[face]
            ))
        })?;
        faces.push(Face::Spline(SplineFace {
            surface: surfaces[sidx].clone(),
            orientation,
            origin: sidx,
        }));
    }
    Ok(faces)
}

impl SolidBoundary {
    /// Reads a G+Smo XML B-rep of exactly six 3D `TensorBSpline2` surfaces bounding a solid.
    ///
    /// The surfaces' corner points are matched (within 1e-9 of the control points' bounding-box
    /// diagonal); they must form the 8 corners of a topological cube, each shared by three
    /// surfaces. When the file's surfaces are in G+Smo side order (west, east, south, north,
    /// front, back: opposite surfaces share no corner) they become the faces x = 0, x = 1,
    /// y = 0, y = 1, z = 0, z = 1; otherwise the first surface is x = 0, its opposite x = 1, the
    /// first remaining surface y = 0, and so on. The cube corner (i, j, k) is the point shared
    /// by the faces x = i, y = j, z = k, and each surface's parameters (with its knot domain
    /// rescaled to \[0,1\]^2) are oriented so that its corners land on those cube corners.
    /// Errors: I/O and parse errors, not six surfaces, not 3D, corners that do not form a cube,
    /// and surfaces that do not agree on their shared edges (checked at 21 points an edge,
    /// within 1e-9 of the bounding-box diagonal).
    pub fn from_gismo_file(path: impl AsRef<Path>) -> Result<Self> {
        Self::read_gismo_file(path.as_ref(), None)
    }

    /// [`SolidBoundary::from_gismo_file`], the surfaces scaled by [`BSplineSurface::scale`]
    /// first when `scale` is given.
    fn read_gismo_file(path: &Path, scale: Option<Vec3>) -> Result<Self> {
        let mut surfaces = read_gismo_surfaces(path)?;
        if let Some(factors) = scale {
            for s in surfaces.iter_mut() {
                s.scale(factors)?;
            }
        }
        Self::from_surfaces(surfaces).map_err(|e| in_file(path, e))
    }

    /// Reads a solid from `path`: a folder of six triangulated faces (as
    /// [`SolidBoundary::from_obj_dir`]) or a `.xml` file (any case), a G+Smo B-rep of six
    /// surfaces (as [`SolidBoundary::from_gismo_file`]).
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self> {
        Self::from_file_scaled(path, None)
    }

    /// [`SolidBoundary::from_file`] with every coordinate of the input multiplied by its axis'
    /// factor (`[fx, fy, fz]`) before anything else, when `scale` is given: the vertices of
    /// triangulated faces (see [`CubeFaces::scale`]) or the control points of the B-rep's
    /// surfaces (see [`BSplineSurface::scale`]; exact for B-splines and NURBS). Use it for data
    /// whose axes are in different units: Floater's map of triangulated faces measures angles in
    /// the coordinates given, so their parameterization, and everything built on it, depends on
    /// the units. The solid's coordinates (and those of any T-mesh or spline map built from it)
    /// are the scaled ones. Errors: `InvalidArgument` for a factor that is not finite and
    /// positive (checked before any I/O) or a path that is neither a folder nor a `.xml` file,
    /// then the errors of the two readers.
    pub fn from_file_scaled(path: impl AsRef<Path>, scale: Option<Vec3>) -> Result<Self> {
        let path = path.as_ref();
        if let Some(factors) = scale {
            super::scale::check_scale_factors(factors)?;
        }
        let is_xml = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("xml"));
        if path.is_dir() {
            Self::read_obj_dir(path, scale)
        } else if is_xml {
            Self::read_gismo_file(path, scale)
        } else {
            Err(Error::invalid(format!(
                "{}: not a folder of six .obj faces nor a .xml G+Smo B-rep",
                path.display()
            )))
        }
    }

    /// Builds the map from six B-spline surfaces, as [`SolidBoundary::from_gismo_file`] does.
    pub fn from_surfaces(surfaces: Vec<BSplineSurface>) -> Result<Self> {
        check_surfaces(&surfaces)?;
        let cps = surfaces.iter().flat_map(|s| {
            let (nu, nv) = s.num_control_points();
            (0..nv).flat_map(move |j| (0..nu).map(move |i| s.control_point(i, j)))
        });
        let bbox = bounding_box(cps);
        let tol = REL_TOL * dist3(bbox.0, bbox.1);
        let (reps, cid) = corner_clusters(&surfaces, tol)?;
        let opposite = opposite_surfaces(&cid)?;
        let order = face_order(&opposite);
        let corner_cluster = cube_corner_clusters(&order, &cid)?;
        let faces = oriented_faces(&surfaces, &order, &cid, &corner_cluster)?;
        let corners = corner_cluster.map(|k| reps[k]);
        Self::finish(faces, corners, bbox)
    }

    /// Reads the six triangulated faces `xmin.obj`, ..., `zmax.obj` of a folder (see
    /// [`CubeFaces::read_dir`]) and parameterizes each onto its cube face with
    /// [`CubeFaces::parameterize`]. When that fails (as for solids so much thinner in one axis
    /// than another that triangle angles round to 0 or π), the faces are parameterized again
    /// in coordinates normalized to the bounding box, each axis scaled to \[0,1\]; the
    /// parameter points used are [`SolidBoundary::vertex_parameters`]. A point of a face evaluates to the barycentric interpolation
    /// of the vertex positions over the triangle of the face's parameter-space triangulation
    /// holding it (found with a uniform bucket grid; a point outside every triangle by round-off
    /// takes the nearest one). Evaluation at a vertex's parameter point returns the vertex
    /// exactly. Errors: I/O and parse errors, a missing face, faces that do not meet at cube
    /// corners, a degenerate or folded parameterization, and faces that do not agree on their
    /// shared edges (checked at 21 points an edge, within 1e-9 of the bounding-box diagonal).
    pub fn from_obj_dir(dir: impl AsRef<Path>) -> Result<Self> {
        Self::read_obj_dir(dir.as_ref(), None)
    }

    /// [`SolidBoundary::from_obj_dir`], the faces scaled by [`CubeFaces::scale`] first when
    /// `scale` is given.
    fn read_obj_dir(dir: &Path, scale: Option<Vec3>) -> Result<Self> {
        let mut cube = CubeFaces::read_dir(dir)?;
        if let Some(factors) = scale {
            cube.scale(factors)?;
        }
        Self::from_cube_faces(&cube).map_err(|e| in_file(dir, e))
    }

    /// The solid bounded by six triangulated faces, in the order `xmin, xmax, ymin, ymax, zmin,
    /// zmax`, parameterized as by [`SolidBoundary::from_obj_dir`] (same rules and errors, without
    /// the I/O).
    pub fn from_cube_faces(cube: &CubeFaces) -> Result<Self> {
        let bbox = bounding_box(cube.faces.iter().flat_map(|m| m.vertices.iter().copied()));
        let params = match cube.parameterize() {
            Ok(p) => p,
            Err(first) => {
                // Retry in coordinates normalized to the unit box: shared vertices stay
                // identical, and a solid far flatter in one axis than the others no longer
                // has triangles whose angles round to 0 or π.
                let mut scaled = cube.clone();
                for m in scaled.faces.iter_mut() {
                    for v in m.vertices.iter_mut() {
                        for d in 0..3 {
                            let w = bbox.1[d] - bbox.0[d];
                            if w > 0.0 {
                                v[d] = (v[d] - bbox.0[d]) / w;
                            }
                        }
                    }
                }
                scaled.parameterize().map_err(|e| {
                    Error::new(
                        e.kind,
                        format!(
                            "{} (and in coordinates normalized to the bounding box: {})",
                            first.message, e.message
                        ),
                    )
                })?
            }
        };
        let mut faces: Vec<Face> = Vec::with_capacity(6);
        for (face, (mesh, par)) in cube.faces.iter().zip(params.iter()).enumerate() {
            let name = CUBE_FACE_NAMES[face];
            let (_, ia, ib) = face_axes(face);
            let uv: Vec<[f64; 2]> = par.iter().map(|p| [p[ia], p[ib]]).collect();
            if let Some(i) = uv.iter().position(|p| p.iter().any(|x| !x.is_finite())) {
                return Err(Error::new(
                    ErrorKind::NotFinite,
                    format!("face {name}: vertex {i} has parameter {:?}", uv[i]),
                ));
            }
            let areas = signed_areas(mesh, &uv);
            let pos = areas.iter().filter(|&&a| a > 0.0).count();
            let neg = areas.iter().filter(|&&a| a < 0.0).count();
            if (pos != 0 && neg != 0) || pos + neg != areas.len() || areas.is_empty() {
                return Err(Error::mesh(format!(
                    "face {name}: the parameterization has {} degenerate and {} folded triangles",
                    areas.len() - pos - neg,
                    pos.min(neg)
                )));
            }
            faces.push(Face::Mesh(MeshFace::new(
                uv,
                mesh.vertices.clone(),
                mesh.triangles.clone(),
            )));
        }
        let mut corners = [[0.0; 3]; 8];
        for c in 0..8 {
            let face = c & 1; // x = 0 or x = 1: in-plane (y, z)
            corners[c] = faces[face].eval(((c >> 1) & 1) as f64, (c >> 2) as f64);
        }
        Self::finish(faces, corners, bbox)
    }

    /// Checks that the faces agree on the cube's edges and corners, and assembles the map.
    fn finish(faces: Vec<Face>, corners: [Vec3; 8], bbox: (Vec3, Vec3)) -> Result<Self> {
        let faces: [Face; 6] = match faces.try_into() {
            Ok(f) => f,
            Err(_) => return Err(Error::invalid("a solid boundary needs 6 faces")),
        };
        let solid = SolidBoundary {
            faces,
            corners,
            bbox,
        };
        let tol = REL_TOL * solid.diagonal();
        for (edge, (f, g)) in cube_edges().into_iter().enumerate() {
            for k in 0..EDGE_SAMPLES {
                let s = k as f64 / (EDGE_SAMPLES - 1) as f64;
                let p = edge_point(edge, s);
                let x = solid.eval_on_face(f, p);
                let y = solid.eval_on_face(g, p);
                if x.iter().chain(y.iter()).any(|v| !v.is_finite()) {
                    return Err(Error::new(
                        ErrorKind::NotFinite,
                        format!("the point {p:?} of the cube evaluates to {x:?} / {y:?}"),
                    ));
                }
                let d = dist3(x, y);
                if d > tol {
                    return Err(Error::mesh(format!(
                        "faces {} and {} do not share their edge: at the cube point {p:?} they give {x:?} and {y:?}, {d:.3e} apart (tolerance {tol:.3e})",
                        CUBE_FACE_NAMES[f], CUBE_FACE_NAMES[g]
                    )));
                }
            }
        }
        for c in 0..8 {
            let p = [(c & 1) as f64, ((c >> 1) & 1) as f64, (c >> 2) as f64];
            for f in 0..6 {
                if p[f / 2] == (f % 2) as f64 && dist3(solid.eval_on_face(f, p), corners[c]) > tol {
                    return Err(Error::mesh(format!(
                        "face {} does not reach the solid's corner {c} at the cube corner {p:?}",
                        CUBE_FACE_NAMES[f]
                    )));
                }
            }
        }
        Ok(solid)
    }

    /// The physical point of a point `p` of the cube's boundary.
    ///
    /// Contract: `p` is on the boundary of \[0,1\]^3 when at least one coordinate is exactly 0
    /// or 1 and the others are in \[0,1\]. The face used is the first, in the order x = 0,
    /// x = 1, y = 0, y = 1, z = 0, z = 1, whose coordinate equals its value; on the cube's
    /// edges and corners all faces containing the point agree to within round-off (see the
    /// constructors). A point not on the boundary is first clamped to \[0,1\]^3, then projected
    /// onto the nearest face (the first of the order above on ties); this never fails. A NaN
    /// coordinate gives NaN in every coordinate.
    pub fn eval(&self, p: [f64; 3]) -> [f64; 3] {
        if p.iter().any(|x| x.is_nan()) {
            return [f64::NAN; 3];
        }
        let (f, a, b) = self.face_coordinates(p);
        self.eval_face(f, a, b)
    }

    /// The face [`SolidBoundary::eval`] evaluates at the cube point `p` and the in-plane
    /// coordinates there: the first face `p` lies on, or for a point off the boundary the
    /// nearest face at the point clamped to the cube.
    pub(super) fn face_coordinates(&self, p: [f64; 3]) -> (usize, f64, f64) {
        let (f, q) = match (0..6).find(|&f| p[f / 2] == (f % 2) as f64) {
            Some(f) => (f, p),
            None => {
                let q = p.map(|x| x.clamp(0.0, 1.0));
                let mut best = 0;
                let mut dbest = f64::INFINITY;
                for f in 0..6 {
                    let d = (q[f / 2] - (f % 2) as f64).abs();
                    if d < dbest {
                        dbest = d;
                        best = f;
                    }
                }
                (best, q)
            }
        };
        let (_, ia, ib) = face_axes(f);
        (f, q[ia], q[ib])
    }

    /// Face `f` (0 to 5).
    pub(super) fn face(&self, f: usize) -> &Face {
        &self.faces[f]
    }

    /// The physical point of face `face` (0 to 5, in the order of [`CUBE_FACE_NAMES`]) at its
    /// in-plane coordinates `(a, b)` (clamped to \[0,1\]; see the module documentation for which
    /// cube coordinates they are). Panics when `face` > 5.
    pub fn eval_face(&self, face: usize, a: f64, b: f64) -> [f64; 3] {
        self.faces[face].eval(a.clamp(0.0, 1.0), b.clamp(0.0, 1.0))
    }

    /// Evaluates face `f` at the in-plane coordinates of the cube point `p`.
    fn eval_on_face(&self, f: usize, p: Vec3) -> Vec3 {
        let (_, ia, ib) = face_axes(f);
        self.eval_face(f, p[ia], p[ib])
    }

    /// For a solid read with [`SolidBoundary::from_obj_dir`], the in-plane parameter points
    /// `(a, b)` of the vertices of face `face` (in the face's OBJ vertex order), at which
    /// [`SolidBoundary::eval_face`] returns the vertices exactly; `None` for B-spline faces.
    /// Panics when `face` > 5.
    pub fn vertex_parameters(&self, face: usize) -> Option<&[[f64; 2]]> {
        match &self.faces[face] {
            Face::Mesh(m) => Some(&m.uv),
            Face::Spline(_) => None,
        }
    }

    /// The solid's corners: cube corner (i, j, k) at index i + 2j + 4k.
    pub fn corners(&self) -> [[f64; 3]; 8] {
        self.corners
    }

    /// A box `(min, max)` containing the boundary: the vertices' box for triangulated faces, the
    /// control points' box for B-spline surfaces (which holds the surfaces by the convex hull
    /// property).
    pub fn bounding_box(&self) -> ([f64; 3], [f64; 3]) {
        self.bbox
    }

    /// The length of the diagonal of [`SolidBoundary::bounding_box`], the length scale of the
    /// constructors' tolerances.
    pub fn diagonal(&self) -> f64 {
        dist3(self.bbox.0, self.bbox.1)
    }
}

/// The 12 edges of the cube as the pairs of faces meeting there.
fn cube_edges() -> [(usize, usize); 12] {
    let mut out = [(0, 0); 12];
    let mut n = 0;
    for f in 0..6 {
        for g in f + 1..6 {
            if f / 2 != g / 2 {
                out[n] = (f, g);
                n += 1;
            }
        }
    }
    out
}

/// The point at parameter `s` ∈ \[0,1\] along edge number `edge` of [`cube_edges`].
fn edge_point(edge: usize, s: f64) -> Vec3 {
    let (f, g) = cube_edges()[edge];
    let free = 3 - f / 2 - g / 2;
    let mut p = [0.0; 3];
    p[f / 2] = (f % 2) as f64;
    p[g / 2] = (g % 2) as f64;
    p[free] = s;
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edges_of_the_cube() {
        let e = cube_edges();
        assert_eq!(e.len(), 12);
        for k in 0..12 {
            let p = edge_point(k, 0.25);
            assert_eq!(p.iter().filter(|&&x| x == 0.25).count(), 1);
        }
    }
}
