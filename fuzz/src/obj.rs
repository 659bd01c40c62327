//! OBJ triangulations (`igaparam::boundary::TriMesh::parse_obj`), their boundary loop and
//! Floater parameterization, and the solid bounded by six of them
//! (`SolidBoundary::from_cube_faces`, what a folder of `xmin.obj` ... `zmax.obj` makes). The
//! input holds up to six OBJ texts separated by NUL bytes.

use igaparam::boundary::{floater_parameterize, CubeFaces, SolidBoundary, TriMesh};

use crate::common::{assert_finite, checked, params, text};

/// Parses each NUL-separated part of `data` as an OBJ text; six of them make a solid.
pub fn run(data: &[u8]) {
    let parts: Vec<&[u8]> = data.split(|&b| b == 0).take(7).collect();
    let meshes: Vec<Option<TriMesh>> = parts
        .iter()
        .map(|p| text(p).and_then(|t| checked("TriMesh::parse_obj", TriMesh::parse_obj(t))))
        .collect();
    for mesh in meshes.iter().flatten() {
        check_mesh(mesh);
    }
    if meshes.len() == 1 {
        if let Some(mesh) = &meshes[0] {
            parameterize(mesh);
        }
    }
    if meshes.len() == 6 && meshes.iter().all(Option::is_some) {
        let faces: Vec<TriMesh> = meshes.into_iter().flatten().collect();
        let cube = CubeFaces {
            faces: faces.try_into().expect("six faces"),
        };
        if let Some(solid) = checked("from_cube_faces", SolidBoundary::from_cube_faces(&cube)) {
            for face in 0..6 {
                for a in params(4) {
                    for b in params(4) {
                        assert_finite("solid boundary", &solid.eval_face(face, a, b));
                    }
                }
            }
        }
    }
}

/// What the parser promises: finite vertices, triangles of three distinct vertices in range.
fn check_mesh(mesh: &TriMesh) {
    for v in &mesh.vertices {
        assert_finite("OBJ vertex", v);
    }
    for t in &mesh.triangles {
        assert!(t.iter().all(|&i| i < mesh.vertices.len()), "triangle {t:?}");
        assert!(
            t[0] != t[1] && t[1] != t[2] && t[0] != t[2],
            "triangle {t:?}"
        );
    }
}

/// The boundary loop, and Floater's map with four loop vertices as corners: finite parameters.
fn parameterize(mesh: &TriMesh) {
    let Some(boundary) = checked("boundary_loop", mesh.boundary_loop()) else {
        return;
    };
    assert!(
        boundary.iter().all(|&v| v < mesh.vertices.len()),
        "boundary loop"
    );
    let n = boundary.len();
    if n < 4 {
        return;
    }
    let corners = [0, n / 4, n / 2, 3 * n / 4].map(|i| boundary[i]);
    if let Some(uv) = checked("floater_parameterize", floater_parameterize(mesh, corners)) {
        assert_eq!(uv.len(), mesh.vertices.len());
        for p in &uv {
            assert_finite("Floater parameter", p);
        }
    }
}
