"""Tests of the Python bindings (bindings/python). The library is found through IGAPARAM_LIBRARY
(see scripts/test.sh) or the other places the package looks in."""

import dataclasses
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import igaparam
from igaparam import IgaparamError, Mesh, Status

ROOT = Path(__file__).resolve().parents[2]
AIRFOIL = ROOT / "tests" / "data" / "airfoil_0012_q9.vtu"
EXAMPLE = Path(os.environ.get("IGAPARAM_BUILD_DIR", ROOT / "build")) / "examples-c" / "igaparam_relocate"

try:
    import meshio
except ImportError:  # optional
    meshio = None


# --- Reading the test data -------------------------------------------------------------------


def read_ascii_vtu(path):
    """A tiny reader of ASCII VTK XML unstructured grids with one cell type: returns
    (points (n, 3), cells (m, k), cell type code, {point array name: array})."""
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    n = int(piece.get("NumberOfPoints"))
    m = int(piece.get("NumberOfCells"))

    def values(array):
        assert array.get("format") == "ascii", f"{array.get('Name')}: only ASCII arrays are supported"
        dtype = {"UInt8": np.uint8, "Int64": np.int64, "Int32": np.int32, "Float64": np.float64,
                 "Float32": np.float32}[array.get("type")]
        flat = np.array((array.text or "").split(), dtype=np.float64 if dtype in (np.float32, np.float64) else np.int64)
        components = int(array.get("NumberOfComponents", "1"))
        flat = flat.astype(dtype)
        return flat.reshape(-1, components) if components > 1 else flat

    point_data = {a.get("Name"): values(a) for a in piece.findall("PointData/DataArray")}
    points = values(piece.find("Points/DataArray"))
    cell_arrays = {a.get("Name"): values(a) for a in piece.findall("Cells/DataArray")}
    types = cell_arrays["types"]
    assert points.shape == (n, 3) and types.shape == (m,)
    assert np.all(types == types[0]), "mixed cell types"
    offsets = cell_arrays["offsets"]
    k = int(offsets[0])
    assert np.all(offsets == k * np.arange(1, m + 1))
    cells = cell_arrays["connectivity"].reshape(m, k)
    return points.astype(np.float64), cells.astype(np.int64), int(types[0]), point_data


def read_airfoil():
    """The airfoil mesh, its mask and the moved positions of its constrained nodes."""
    if meshio is not None:
        mesh = meshio.read(AIRFOIL)
        assert len(mesh.cells) == 1 and mesh.cells[0].type == "quad9"
        points, cells, code = mesh.points, mesh.cells[0].data, 28
        data = mesh.point_data
    else:
        points, cells, code, data = read_ascii_vtu(AIRFOIL)
    mask = np.asarray(data["fixed_components"]).reshape(-1).astype(np.uint8)
    moved = np.asarray(data["moved"], dtype=np.float64).reshape(-1, 3)
    return np.asarray(points, dtype=np.float64), np.asarray(cells, dtype=np.int64), code, mask, moved


def airfoil_mesh():
    """A Mesh of the airfoil with its boundary moved and constrained (as igaparam_relocate does:
    for a node with a non-zero mask, its fixed components are set to `moved`)."""
    points, cells, code, mask, moved = read_airfoil()
    mesh = Mesh(code, points, cells)
    constrained = np.flatnonzero(mask)
    bits = (mask[constrained, None] >> np.arange(3)) & 1
    targets = np.where(bits == 1, moved[constrained], points[constrained])
    mesh.move_nodes(targets, indices=constrained)
    mesh.set_fixed(mask)
    return mesh, points, mask, targets, constrained


def unit_square_q4():
    return np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64), np.array([[0, 1, 2, 3]])


# --- Airfoil ---------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def airfoil_result():
    mesh, points, mask, targets, constrained = airfoil_mesh()
    with mesh:
        report = mesh.relocate()
        return {
            "report": report,
            "positions": mesh.positions,
            "quality": mesh.cell_quality(),
            "invalid": mesh.invalid_cell_count,
            "points": points,
            "mask": mask,
            "targets": targets,
            "constrained": constrained,
        }


def test_airfoil_relocation(airfoil_result):
    r = airfoil_result["report"]
    assert r.cells == 490 and r.nodes == 2060
    assert r.invalid_before > 0
    assert r.invalid_after == 0
    assert r.min_quality > 0.2
    assert 0 < r.min_quality <= r.mean_quality <= 1
    assert airfoil_result["invalid"] == 0
    quality = airfoil_result["quality"]
    assert quality.shape == (490,)
    assert quality.min() == pytest.approx(r.min_quality, abs=1e-12)
    assert quality.mean() == pytest.approx(r.mean_quality, abs=1e-12)


def test_airfoil_constrained_nodes_stay(airfoil_result):
    positions = airfoil_result["positions"]
    assert positions.shape == (2060, 3) and positions.dtype == np.float64
    constrained, mask, targets = airfoil_result["constrained"], airfoil_result["mask"], airfoil_result["targets"]
    fixed_bits = ((mask[constrained, None] >> np.arange(3)) & 1) == 1
    assert np.array_equal(positions[constrained][fixed_bits], targets[fixed_bits])
    # z of a quadrilateral mesh is carried unchanged.
    assert np.array_equal(positions[:, 2], airfoil_result["points"][:, 2])


@pytest.mark.skipif(not EXAMPLE.exists(), reason=f"{EXAMPLE} not built (needs VTK)")
def test_airfoil_same_as_cpp_example(airfoil_result, tmp_path):
    output = tmp_path / "airfoil_out.vtu"
    run = subprocess.run([str(EXAMPLE), str(AIRFOIL), str(output)], capture_output=True, text=True, check=True)
    expected = json.loads(run.stdout.strip().splitlines()[-1])
    r = airfoil_result["report"]
    for key in ("cells", "nodes", "free_nodes", "invalid_before", "invalid_after_placement", "invalid_after",
                "sweeps", "steps"):
        assert getattr(r, key) == expected[key], key
    assert r.converged == expected["converged"]
    # The example prints the qualities with 10 significant digits ("%.10g"): the same text means
    # the same value to that precision.
    for key in ("min_quality", "mean_quality"):
        assert float("%.10g" % getattr(r, key)) == expected[key], key
        assert getattr(r, key) == pytest.approx(expected[key], abs=1e-9)
    if meshio is not None:
        # The positions the example wrote (binary, exact): the same to 1e-12.
        written = meshio.read(output)
        assert np.allclose(written.points, airfoil_result["positions"], rtol=0, atol=1e-12)


def test_airfoil_threads_do_not_change_the_result(airfoil_result):
    """1, 2 and 4 explicit threads give the same positions and report, bit for bit (the
    fixture's default, one thread per core, too)."""
    runs = []
    for threads in (1, 2, 4):
        mesh, *_ = airfoil_mesh()
        with mesh:
            report = mesh.relocate(threads=threads)
            assert report.invalid_after == 0
            runs.append((mesh.positions, dataclasses.replace(report, seconds=0.0)))
    for positions, report in runs[1:]:
        assert np.array_equal(positions, runs[0][0])
        assert report == runs[0][1]
    assert np.array_equal(runs[0][0], airfoil_result["positions"])


def test_airfoil_laplacian_only():
    mesh, *_ = airfoil_mesh()
    with mesh:
        report = mesh.relocate(laplacian_only=True)
        assert report.sweeps == 0 and report.cells == 490
        assert report.invalid_after == report.invalid_after_placement


@pytest.mark.parametrize(
    "method, stage",
    [("sweeps", igaparam.Stage.OPTIMIZATION), ("newton", igaparam.Stage.STATIONARITY)],
)
def test_progress_and_cancel(method, stage):
    mesh, *_ = airfoil_mesh()
    with mesh:
        before = mesh.positions
        calls = []

        def progress(s, done, total):
            calls.append((s, done, total))
            return s != stage  # cancel at the first sweep / Newton iteration

        with pytest.raises(IgaparamError) as error:
            mesh.relocate(progress=progress, method=method)
        assert error.value.status == Status.CANCELLED
        assert calls and calls[-1][0] == stage
        assert np.array_equal(mesh.positions, before)  # unchanged

        def broken(stage, done, total):
            raise RuntimeError("from the callback")

        with pytest.raises(RuntimeError, match="from the callback"):
            mesh.relocate(progress=broken)
        assert np.array_equal(mesh.positions, before)


# --- Small meshes, properties and errors -----------------------------------------------------


def test_version():
    assert igaparam.version() == "0.1.0" == igaparam.__version__


def test_q4_properties_and_relocation():
    points, cells = unit_square_q4()
    with Mesh("Q4", points, cells) as mesh:
        assert (mesh.node_count, mesh.cell_count, mesh.dimension, mesh.cell_type) == (4, 1, 2, 9)
        assert np.array_equal(mesh.fixed, np.zeros(4, np.uint8))
        mesh.set_fixed(np.full(4, 3, dtype=np.uint8))
        assert np.array_equal(mesh.fixed, np.full(4, 3))
        mesh.move_nodes([[1.2, 1.1, 0.0]], indices=[2])
        assert np.array_equal(mesh.reference, points)
        assert np.array_equal(mesh.positions[2], [1.2, 1.1, 0.0])
        report = mesh.relocate(target="master", threads=1, max_sweeps=5)
        assert isinstance(report, igaparam.RelocateReport)
        assert report.as_dict()["cells"] == 1 and report.invalid_after == 0 and report.free_nodes == 0
        assert mesh.cell_quality("master").shape == (1,)
        assert mesh.cell_quality("initial")[0] < 1
        mesh.reset_reference()
        assert np.array_equal(mesh.reference, mesh.positions)
        assert mesh.cell_quality("initial")[0] == pytest.approx(1.0)
        # move_nodes without indices: the first k nodes.
        mesh.move_nodes(points[:2] + [0.0, -0.1, 0.0])
        assert np.allclose(mesh.positions[:2], points[:2] + [0.0, -0.1, 0.0])
    assert mesh.closed
    with pytest.raises(ValueError):
        mesh.node_count
    mesh.close()  # again: nothing


def test_cell_type_codes_and_names():
    assert igaparam.nodes_per_cell("Q9") == 9 and igaparam.nodes_per_cell(29) == 27
    assert [igaparam.nodes_per_cell(n) for n in ("Q4", "Q8", "H8", "H20", "H27")] == [4, 8, 8, 20, 27]
    with pytest.raises(ValueError):
        igaparam.cell_type_code("T3")
    with pytest.raises(IgaparamError) as error:
        igaparam.nodes_per_cell(5)  # VTK_TRIANGLE
    assert error.value.status == Status.INVALID_ARGUMENT and error.value.message


def test_hex8():
    points = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=float)
    cells = np.array([[0, 1, 3, 2, 4, 5, 7, 6]])
    with Mesh("H8", points, cells) as mesh:
        assert mesh.dimension == 3 and mesh.invalid_cell_count == 0
        mesh.set_fixed(np.ones(8, dtype=bool))
        assert np.array_equal(mesh.fixed, np.full(8, 7))


def test_nan_points():
    points, cells = unit_square_q4()
    points[1, 0] = np.nan
    with pytest.raises(IgaparamError) as error:
        Mesh("Q4", points, cells)
    assert error.value.status == Status.NOT_FINITE == 3
    assert error.value.message and error.value.message in str(error.value)


def test_nan_move():
    points, cells = unit_square_q4()
    with Mesh("Q4", points, cells) as mesh:
        with pytest.raises(IgaparamError) as error:
            mesh.move_nodes([[np.inf, 0, 0]], indices=[0])
        assert error.value.status == Status.NOT_FINITE
        assert np.array_equal(mesh.positions, points)


def test_wrong_shapes():
    points, cells = unit_square_q4()
    for bad_points in (points.reshape(-1), points[:, :1], np.zeros((4, 4))):
        with pytest.raises(ValueError):
            Mesh("Q4", bad_points, cells)
    with pytest.raises(ValueError):
        Mesh("Q4", points, cells.reshape(-1))
    with pytest.raises(ValueError):
        Mesh("Q9", points, cells)  # 4 nodes per cell, 9 expected
    with pytest.raises(ValueError):
        Mesh("Q4", points, cells.astype(float))
    with pytest.raises(IgaparamError) as error:
        Mesh("Q4", points, [[0, 1, 2, 7]])
    assert error.value.status == Status.INVALID_MESH
    with Mesh("Q4", points, cells) as mesh:
        with pytest.raises((ValueError, IgaparamError)):
            mesh.set_fixed(np.zeros(3, dtype=np.uint8))
        with pytest.raises(ValueError):
            mesh.set_fixed(np.zeros((4, 1), dtype=np.uint8))
        with pytest.raises(ValueError):
            mesh.move_nodes(np.zeros((2, 3)), indices=[0])
        with pytest.raises((ValueError, IgaparamError)):
            mesh.move_nodes(np.zeros((1, 3)), indices=[9])
        with pytest.raises(ValueError):
            mesh.relocate(target="no such target")


def test_2d_points_are_padded():
    points, cells = unit_square_q4()
    with Mesh(9, points[:, :2], cells) as mesh:
        assert np.array_equal(mesh.positions, points)


def test_library_lookup_respects_environment(tmp_path):
    # A wrong IGAPARAM_LIBRARY is reported, not replaced by another library.
    code = "import igaparam\ntry:\n    igaparam.version()\nexcept OSError as e:\n    print('OSError', e)\n"
    env = dict(os.environ, IGAPARAM_LIBRARY=str(tmp_path / "missing.so"))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    assert out.startswith("OSError") and "IGAPARAM_LIBRARY" in out
