"""The library's .vtu reader and writer against the files meshio and VTK write, and the other way
round: the airfoil case in eight storages (meshio: ASCII, binary, zlib; VTK: ASCII, inline binary,
appended raw, appended base64, appended raw + zlib) is read and relocated by the C example
(relocate_vtu.c, no VTK) and the Rust example (examples/relocate_vtu.rs), with identical results,
and read alike by the Python binding; every storage the library writes is read back by meshio and VTK."""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import igaparam

meshio = pytest.importorskip("meshio")
vtk = pytest.importorskip("vtk")
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
AIRFOIL = ROOT / "tests" / "data" / "airfoil_0012_q9.vtu"
BUILD = Path(os.environ.get("IGAPARAM_BUILD_DIR", ROOT / "build"))
C_EXAMPLE = BUILD / "examples-c" / "relocate_vtu"
RUST_EXAMPLE = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release" / "examples" / "relocate_vtu"


def vtk_read(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    grid = reader.GetOutput()
    assert grid.GetNumberOfPoints() > 0, f"VTK could not read {path}"
    return grid


def vtk_write(grid, path, mode, encode=True, zlib=False):
    writer = vtk.vtkXMLUnstructuredGridWriter()
    writer.SetFileName(str(path))
    writer.SetInputData(grid)
    getattr(writer, f"SetDataModeTo{mode}")()
    writer.SetEncodeAppendedData(encode)
    if zlib:
        writer.SetCompressorTypeToZLib()
    else:
        writer.SetCompressorTypeToNone()
    assert writer.Write() == 1


@pytest.fixture(scope="module")
def variants(tmp_path_factory):
    """The airfoil case in eight storages: {name: path}."""
    out = tmp_path_factory.mktemp("variants")
    m = meshio.read(AIRFOIL)
    paths = {}
    for name, kwargs in [("meshio_ascii", dict(binary=False)), ("meshio_binary", dict(binary=True, compression=None)),
                         ("meshio_zlib", dict(binary=True, compression="zlib"))]:
        paths[name] = out / f"{name}.vtu"
        meshio.write(paths[name], m, file_format="vtu", **kwargs)
    grid = vtk_read(AIRFOIL)
    for name, args in [("vtk_ascii", ("Ascii",)), ("vtk_inline", ("Binary",)),
                       ("vtk_appended_raw", ("Appended", False)), ("vtk_appended_base64", ("Appended", True)),
                       ("vtk_compressed", ("Appended", False, True))]:
        paths[name] = out / f"{name}.vtu"
        vtk_write(grid, paths[name], *args)
    text = paths["vtk_appended_raw"].read_bytes()
    assert b'encoding="raw"' in text and b'compressor' not in text.split(b"<UnstructuredGrid")[0]
    assert b"vtkZLibDataCompressor" in paths["vtk_compressed"].read_bytes()[:400]
    return paths


def run_example(program, source, target):
    if not program.exists():
        pytest.skip(f"{program} not built")
    run = subprocess.run([str(program), str(source), str(target), "2"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout.strip().splitlines()[-1])


def test_every_variant_is_read_and_relocated_alike_from_c_rust_and_python(variants, tmp_path):
    original = meshio.read(AIRFOIL)
    with igaparam.Mesh.read_vtu(AIRFOIL) as mesh:
        mesh.relocate(threads=2)
        expected = mesh.positions
    for name, path in variants.items():
        c_report = run_example(C_EXAMPLE, path, tmp_path / f"{name}_c.vtu")
        rust_report = run_example(RUST_EXAMPLE, path, tmp_path / f"{name}_rust.vtu")
        c_points = meshio.read(tmp_path / f"{name}_c.vtu").points
        rust_points = meshio.read(tmp_path / f"{name}_rust.vtu").points
        assert c_report == rust_report, name
        assert np.array_equal(c_points, rust_points), name
        assert c_report["invalid_after"] == 0 and c_report["invalid_before"] == 63
        # The relocation is the same wherever the file holds the original's numbers exactly;
        # meshio's ASCII writer rounds them, which moves the result by round-off only.
        with igaparam.Mesh.read_vtu(path) as mesh:
            assert mesh.cell_type == igaparam.CellType.Q9 and mesh.node_count == 2060
            assert np.allclose(mesh.reference, original.points, rtol=0, atol=1e-9)
            exact = np.array_equal(mesh.reference, original.points)
            assert np.array_equal(mesh.fixed, np.asarray(original.point_data["fixed_components"]).reshape(-1))
        assert exact or name == "meshio_ascii", name
        if exact:
            assert np.array_equal(c_points, expected), name
        else:
            assert np.allclose(c_points, expected, rtol=0, atol=1e-8), name


FORMATS = [("binary", True), ("binary", False), ("appended", True), ("appended", False),
           ("appended-base64", True), ("appended-base64", False), ("ascii", False)]


@pytest.mark.parametrize("encoding,compress", FORMATS)
def test_written_files_are_read_by_meshio_vtk_and_the_library(encoding, compress, tmp_path):
    path = tmp_path / "airfoil.vtu"
    with igaparam.Mesh.read_vtu(AIRFOIL) as mesh:
        mesh.relocate(threads=2)
        positions, reference, fixed = mesh.positions, mesh.reference, mesh.fixed
        quality = mesh.cell_quality()
        mesh.write_vtu(path, encoding=encoding, compress=compress)
    exact = encoding != "ascii"
    same = np.array_equal if exact else (lambda a, b: np.allclose(a, b, rtol=1e-15, atol=1e-15))
    grid = vtk_read(path)
    assert grid.GetNumberOfCells() == 490 and grid.GetCellType(0) == 28
    assert same(vtk_to_numpy(grid.GetPoints().GetData()), positions)
    mask = grid.GetPointData().GetArray("fixed_components")
    assert mask.GetDataTypeAsString() == "unsigned char"
    assert np.array_equal(vtk_to_numpy(mask), fixed)
    assert same(vtk_to_numpy(grid.GetPointData().GetArray("displacement")), positions - reference)
    assert same(vtk_to_numpy(grid.GetCellData().GetArray("quality")), quality)
    m = meshio.read(path)
    assert same(m.points, positions)
    assert m.cells[0].type == "quad9" and m.cells[0].data.shape == (490, 9)
    assert np.array_equal(np.asarray(m.point_data["fixed_components"]).reshape(-1), fixed)
    with igaparam.Mesh.read_vtu(path) as back:
        assert same(back.positions, positions) and np.array_equal(back.fixed, fixed)


def test_compressed_output_is_smaller(tmp_path):
    with igaparam.Mesh.read_vtu(AIRFOIL) as mesh:
        sizes = {}
        for encoding, compress in FORMATS:
            path = tmp_path / f"{encoding}_{compress}.vtu"
            mesh.write_vtu(path, encoding=encoding, compress=compress)
            sizes[encoding, compress] = path.stat().st_size
    assert sizes["appended", True] < sizes["binary", True] < 0.6 * sizes["binary", False]
    assert sizes["binary", True] < 0.6 * sizes["ascii", False]


def test_bad_files_and_formats(tmp_path):
    bad = tmp_path / "bad.vtu"
    bad.write_text("<VTKFile type='UnstructuredGrid'><UnstructuredGrid><Piece NumberOfPoints='1'")
    with pytest.raises(igaparam.IgaparamError) as error:
        igaparam.Mesh.read_vtu(bad)
    assert error.value.status == igaparam.Status.IO and "bad.vtu" in error.value.message
    with pytest.raises(igaparam.IgaparamError) as error:
        igaparam.Mesh.read_vtu(tmp_path / "missing.vtu")
    assert error.value.status == igaparam.Status.IO
    with igaparam.Mesh.read_vtu(AIRFOIL) as mesh:
        with pytest.raises(ValueError):
            mesh.write_vtu(tmp_path / "x.vtu", encoding="ascii", compress=True)
        with pytest.raises(ValueError):
            mesh.write_vtu(tmp_path / "x.vtu", encoding="hdf5")
        with pytest.raises(igaparam.IgaparamError) as error:
            mesh.write_vtu(tmp_path / "no" / "such" / "dir.vtu")
        assert error.value.status == igaparam.Status.IO
