"""Tests of igaparam.Domain for solids in the Python bindings: solids read from files (with
per-axis scale factors) and from triangulated faces, their T-mesh read-back and spline maps."""

from pathlib import Path

import numpy as np
import pytest

from igaparam import Domain, IgaparamError, Spline, Status
from test_domain import check_tmesh, written_piece

BOUNDARY = Path(__file__).resolve().parents[2] / "tests" / "data" / "boundary"
FACES = ("xmin", "xmax", "ymin", "ymax", "zmin", "zmax")
# The Jacksboro block's x and y are in degrees/1000, z in km: these factors put them in km.
KM = (89273.3, 111200.0, 1.0)
# Coarse options for the duck B-rep: every cell of level 1 is refined once at most.
COARSE = dict(tolerance=3e-3, min_level=1, max_level=3, threads=2)


def read_obj(path):
    """The vertices (n, 3) and triangles (m, 3, counting from 0) of an OBJ file of ``v`` and
    ``f`` lines."""
    vertices, triangles = [], []
    for line in Path(path).read_text().splitlines():
        fields = line.split()
        if fields and fields[0] == "v":
            vertices.append([float(x) for x in fields[1:4]])
        elif fields and fields[0] == "f":
            triangles.append([int(x.split("/")[0]) - 1 for x in fields[1:4]])
    return np.array(vertices), np.array(triangles)


def unit_cube_faces(k=4):
    """The unit cube's faces xmin ... zmax, each a (k+1) × (k+1) grid of vertices split into
    2k² triangles."""
    t = np.linspace(0.0, 1.0, k + 1)
    a, b = np.meshgrid(t, t, indexing="xy")
    a, b = a.ravel(), b.ravel()
    triangles = []
    for j in range(k):
        for i in range(k):
            v = i + (k + 1) * j
            triangles += [[v, v + 1, v + k + 2], [v, v + k + 2, v + k + 1]]
    faces = []
    for f in range(6):
        axis = f // 2
        inplane = [d for d in range(3) if d != axis]
        xyz = np.empty((a.size, 3))
        xyz[:, axis] = f % 2
        xyz[:, inplane[0]], xyz[:, inplane[1]] = a, b
        faces.append((xyz, np.array(triangles, dtype=np.int32)))
    return faces


def check_solid_tmesh(domain, report):
    """check_tmesh for a solid, and its hexahedra's corners."""
    assert domain.dimension == 3
    uvw, bounds = check_tmesh(domain, report)
    n, m = domain.vertex_count, domain.cell_count
    corners = domain.cell_corners
    assert corners.shape == (m, 8) and corners.min() >= 0 and corners.max() < n
    # VTK hexahedron order: corner 0 at the lower bound, corner 6 at the upper one.
    assert np.array_equal(uvw[corners[:, 0]], bounds[:, :3])
    assert np.array_equal(uvw[corners[:, 6]], bounds[:, 3:])


@pytest.fixture(scope="module")
def jacksboro_km():
    with Domain.solid_from_file(BOUNDARY / "jacksboro_faces", scale=KM) as domain:
        assert domain.dimension == 3 and not domain.is_built
        report = domain.build(tolerance=1e-3, max_level=3)
        yield domain, report


def test_jacksboro_in_km_builds(jacksboro_km):
    domain, report = jacksboro_km
    assert report.invalid_cells == 0
    check_solid_tmesh(domain, report)
    xyz = domain.physical_vertices
    extent = xyz.max(axis=0) - xyz.min(axis=0)
    # 29.98 km by 31.88 km: the factors reached the T-mesh.
    assert extent[0] == pytest.approx(29.98, abs=0.01) and extent[1] == pytest.approx(31.88, abs=0.01)
    assert "solid" in repr(domain)


def test_jacksboro_in_km_spline_is_certified(jacksboro_km):
    domain, _ = jacksboro_km
    with Spline.fit(domain) as spline:
        assert spline.dimension == 3
        assert spline.fit_report.untangled == 0
        validity = spline.check_validity()
        assert validity.certified_positive and validity.uncertified == 0
        # The map sends the parameter cube onto the block: its corners onto the T-mesh's.
        uvw, xyz = domain.parametric_vertices, domain.physical_vertices
        corner = np.all((uvw == 0.0) | (uvw == 1.0), axis=1)
        assert corner.sum() == 8
        assert np.allclose(spline.evaluate(uvw[corner]), xyz[corner], atol=1e-9)


def test_jacksboro_vtu(jacksboro_km, tmp_path):
    domain, report = jacksboro_km
    meshio = pytest.importorskip("meshio")
    written_piece(domain, report, tmp_path / "jacksboro.vtu")
    # The file is zlib-compressed binary: its cells are read through meshio.
    cells = meshio.read(tmp_path / "jacksboro.vtu").cells
    assert [block.type for block in cells] == ["hexahedron"]  # VTK_HEXAHEDRON
    assert len(cells[0].data) == report.cells


def test_scale_none_is_unscaled_and_uniform_scaling_commutes():
    path = BOUNDARY / "duck3d_BRep.xml"
    built = []
    for scale in (None, (1, 1, 1), [2.0, 2.0, 2.0]):
        with Domain.solid_from_file(path, scale=scale) as domain:
            report = domain.build(**COARSE)
            assert report.invalid_cells == 0
            check_solid_tmesh(domain, report)
            built.append((domain.parametric_vertices, domain.physical_vertices))
    for (uvw, xyz), factor in zip(built[1:], (1.0, 2.0)):
        assert np.array_equal(uvw, built[0][0])
        assert np.array_equal(xyz, factor * built[0][1])


def test_unit_cube_from_triangulations_is_the_identity():
    with Domain.solid_from_triangulations(unit_cube_faces()) as domain:
        assert domain.dimension == 3
        report = domain.build(min_level=2, max_level=2, threads=2)
        assert (report.cells, report.vertices, report.invalid_cells) == (64, 125, 0)
        check_solid_tmesh(domain, report)
        assert np.abs(domain.physical_vertices - domain.parametric_vertices).max() < 1e-12
        assert domain.cell_quality.min() == pytest.approx(1.0)
        with Spline.fit(domain) as spline:
            points = np.random.default_rng(1).random((20, 3))
            assert np.abs(spline.evaluate(points) - points).max() < 1e-12


def test_duck_faces_from_triangulations_match_the_folder():
    faces = [read_obj(BOUNDARY / "duck_faces" / f"{name}.obj") for name in FACES]
    options = dict(tolerance=1e-2, min_level=1, max_level=2, threads=2)
    with Domain.solid_from_triangulations(faces) as a, Domain.solid_from_file(BOUNDARY / "duck_faces") as b:
        ra, rb = a.build(**options), b.build(**options)
        assert ra.cells == rb.cells and ra.invalid_cells == 0
        check_solid_tmesh(a, ra)
        assert np.array_equal(a.parametric_vertices, b.parametric_vertices)
        assert np.array_equal(a.physical_vertices, b.physical_vertices)


def test_errors():
    xml = BOUNDARY / "duck3d_BRep.xml"
    for bad in ((1, 1), "abc", [[1, 1, 1]], ("x", "y", "z")):
        with pytest.raises(ValueError, match="scale"):
            Domain.solid_from_file(xml, scale=bad)
    for bad in ((np.nan, 1, 1), (1, 0, 1), (1, 1, -2), (np.inf, 1, 1)):
        with pytest.raises(IgaparamError, match="finite and positive") as error:
            Domain.solid_from_file(xml, scale=bad)
        assert error.value.status == Status.INVALID_ARGUMENT
        # Checked before the file is read.
        with pytest.raises(IgaparamError) as error:
            Domain.solid_from_file(BOUNDARY / "no_such_file.xml", scale=bad)
        assert error.value.status == Status.INVALID_ARGUMENT
    for scale in (None, KM):
        with pytest.raises(IgaparamError) as error:
            Domain.solid_from_file(BOUNDARY / "no_such_file.xml", scale=scale)
        assert error.value.status == Status.IO
        with pytest.raises(IgaparamError) as error:
            Domain.solid_from_file(BOUNDARY / "README.md", scale=scale)
        assert error.value.status == Status.INVALID_ARGUMENT

    faces = unit_cube_faces(2)
    with pytest.raises(ValueError, match="6 faces"):
        Domain.solid_from_triangulations(faces[:5])
    for index, face, match in (
        (1, faces[1][0], "pair"),
        (2, (faces[2][0][:, :2], faces[2][1]), r"vertices of face 2 \(ymin\).*shape"),
        (3, (faces[3][0].astype(str), faces[3][1]), "numeric"),
        (4, (faces[4][0], faces[4][1].astype(float)), "integer"),
        (5, (faces[5][0], faces[5][1][:, :2]), "shape"),
        (0, (faces[0][0], -faces[0][1]), "uint32"),
    ):
        bad = list(faces)
        bad[index] = face
        with pytest.raises(ValueError, match=match):
            Domain.solid_from_triangulations(bad)

    def rejected(index, vertices=None, triangles=None):
        bad = list(faces)
        v, t = bad[index]
        bad[index] = (v if vertices is None else vertices, t if triangles is None else triangles)
        with pytest.raises(IgaparamError) as error:
            Domain.solid_from_triangulations(bad)
        return error.value

    v = faces[2][0].copy()
    v[4, 1] = np.nan
    error = rejected(2, vertices=v)
    assert error.status == Status.NOT_FINITE and "ymin" in str(error)
    t = faces[4][1].copy()
    t[0, 0] = 9
    error = rejected(4, triangles=t)
    assert error.status == Status.INVALID_MESH and "zmin" in str(error)
    t[0, 0] = t[0, 1]
    assert rejected(4, triangles=t).status == Status.INVALID_MESH
    v = faces[5][0].copy()
    v[:, 2] = 1.25  # zmax lifted off the sides
    assert rejected(5, vertices=v).status == Status.INVALID_MESH

    # A solid that is not built has no T-mesh to read back.
    with Domain.solid_from_triangulations(faces) as domain:
        assert "not built" in repr(domain)
        with pytest.raises(IgaparamError) as error:
            domain.physical_vertices
        assert error.value.status == Status.INVALID_ARGUMENT
    assert repr(domain) == "<igaparam.Domain (closed)>"
    with pytest.raises(ValueError, match="closed"):
        domain.dimension


def test_solid_defaults():
    """A solid's build defaults to tolerance 1e-3 (a planar domain's is 1e-5)."""
    path = BOUNDARY / "duck3d_BRep.xml"
    with Domain.solid_from_file(path) as a, Domain.solid_from_file(path) as b:
        ra, rb = a.build(threads=2), b.build(tolerance=1e-3, threads=2)
        assert ra.as_dict() | {"seconds": 0} == rb.as_dict() | {"seconds": 0}
        assert ra.boundary_error <= 1e-3 and ra.invalid_cells == 0
