"""Tests of igaparam.Domain (planar domains) in the Python bindings."""

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import igaparam
from igaparam import Domain, IgaparamError, Spline, Status

BOUNDARY = Path(__file__).resolve().parents[2] / "tests" / "data" / "boundary"


def check_tmesh(domain, report):
    """Shapes, ranges and agreement of the read-back arrays with the report (2D or 3D)."""
    d = domain.dimension
    n, m = domain.vertex_count, domain.cell_count
    assert (n, m) == (report.vertices, report.cells) and m > 0
    uv, xy = domain.parametric_vertices, domain.physical_vertices
    assert uv.shape == xy.shape == (n, d) and uv.dtype == xy.dtype == np.float64
    assert uv.min() == 0.0 and uv.max() == 1.0
    assert np.all(np.isfinite(xy))
    quality = domain.cell_quality
    assert quality.shape == (m,)
    assert np.all(quality >= 0) and np.all(quality <= 1 + 1e-12)
    if report.invalid_cells == 0:
        assert np.all(quality > 0)
    assert quality.min() == pytest.approx(report.min_quality, abs=1e-12)
    assert quality.mean() == pytest.approx(report.mean_quality, abs=1e-12)
    levels, bounds = domain.cell_levels, domain.cell_bounds
    assert levels.shape == (m,) and levels.dtype == np.uint8 and levels.max() == report.max_level
    assert bounds.shape == (m, 2 * d)
    size = bounds[:, d:] - bounds[:, :d]
    assert np.allclose(size, (0.5 ** levels.astype(float))[:, None])
    # The cells tile the parameter square or cube.
    assert np.prod(size, axis=1).sum() == pytest.approx(1.0)
    return uv, bounds


@pytest.fixture(scope="module")
def puzzle():
    with Domain.from_file(BOUNDARY / "puzzle3_bdry.xml") as domain:
        assert not domain.is_built
        report = domain.build(threads=2)
        yield domain, report


def test_puzzle(puzzle):
    domain, report = puzzle
    assert domain.is_built
    assert isinstance(report, igaparam.DomainReport)
    assert report.invalid_cells == 0
    assert report.invalid_after_placement > 0  # the optimization had folds to undo
    assert report.sweeps > 0 and report.as_dict()["cells"] == report.cells
    check_tmesh(domain, report)


def written_piece(domain, report, path):
    """The <Piece> of the .vtu the domain writes to `path`, checked to hold every cell."""
    domain.write_vtu(path)
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    assert int(piece.get("NumberOfCells")) == report.cells
    return piece


def test_puzzle_vtu(puzzle, tmp_path):
    domain, report = puzzle
    piece = written_piece(domain, report, tmp_path / "puzzle.vtu")
    names = {a.get("Name") for a in piece.findall("CellData/DataArray")}
    assert {"quality", "level"} <= names
    with pytest.raises(IgaparamError) as error:
        domain.write_vtu(tmp_path / "no_such_directory" / "x.vtu")
    assert error.value.status == Status.IO and error.value.message


def test_gran_canaria():
    with Domain.from_file(str(BOUNDARY / "gran_canaria.txt")) as domain:
        report = domain.build()
        assert report.invalid_cells == 0
        check_tmesh(domain, report)
        # Rebuilding with a coarser tolerance replaces the T-mesh.
        coarse = domain.build(tolerance=1e-3)
        assert coarse.invalid_cells == 0 and coarse.cells < report.cells
        assert domain.cell_count == coarse.cells


def test_gran_canaria_spline_is_untangled_inside():
    # The C2 fit folds next to the kinked coastline; untangling the inner control points
    # certifies the map without moving its boundary.
    with Domain.from_file(str(BOUNDARY / "gran_canaria.txt")) as domain:
        domain.build()
        with Spline.fit(domain) as spline:
            report = spline.fit_report
            assert report.untangled > 0 and report.boundary_offset == 0.0
            assert spline.check_validity().certified_positive


def annulus_quarter(k=9):
    """Four polylines bounding a quarter annulus (radii 1 and 2), in a shuffled order and
    direction."""
    t = np.linspace(0, np.pi / 2, k)
    inner = np.column_stack([np.cos(t), np.sin(t)])
    outer = 2 * inner
    return [outer[::-1], [[1, 0], [2, 0]], inner, [[0, 2], [0, 1]]]


def test_polylines():
    with Domain.from_polylines(annulus_quarter()) as domain:
        report = domain.build(max_level=6)
        assert report.invalid_cells == 0 and report.max_level <= 6
        check_tmesh(domain, report)
        r = np.hypot(*domain.physical_vertices.T)
        assert r.min() == pytest.approx(1.0, abs=1e-9) and r.max() == pytest.approx(2.0, abs=1e-9)


def test_progress_and_cancel():
    with Domain.from_polylines(annulus_quarter()) as domain:
        calls = []

        def cancel(stage, done, total):
            calls.append(stage)
            return False

        with pytest.raises(IgaparamError) as error:
            domain.build(progress=cancel)
        assert error.value.status == Status.CANCELLED and calls
        assert not domain.is_built

        def broken(stage, done, total):
            raise RuntimeError("from the callback")

        with pytest.raises(RuntimeError, match="from the callback"):
            domain.build(progress=broken)
        assert not domain.is_built


def test_errors(tmp_path):
    with pytest.raises(IgaparamError) as error:
        Domain.from_file(tmp_path / "missing.xml")
    assert error.value.status == Status.IO and "missing.xml" in error.value.message
    with pytest.raises(IgaparamError) as error:
        Domain.from_file(BOUNDARY / "README.md")
    assert error.value.status == Status.INVALID_ARGUMENT
    with pytest.raises(ValueError):
        Domain.from_polylines(annulus_quarter()[:3])
    with pytest.raises(ValueError):
        Domain.from_polylines([np.zeros((3, 3))] * 4)
    bad = annulus_quarter()
    bad[1] = [[1, 0], [np.nan, 0]]
    with pytest.raises(IgaparamError) as error:
        Domain.from_polylines(bad)
    assert error.value.message
    gap = annulus_quarter()
    gap[1] = [[1.5, 0], [2, 0]]  # does not reach the inner arc
    with pytest.raises(IgaparamError) as error:
        Domain.from_polylines(gap)
    assert error.value.status == Status.INVALID_ARGUMENT
    with Domain.from_polylines(annulus_quarter()) as domain:
        for read in ("vertex_count", "cell_count", "physical_vertices", "cell_quality", "cell_levels"):
            with pytest.raises(IgaparamError) as error:
                getattr(domain, read)
            assert error.value.status == Status.INVALID_ARGUMENT, read
        with pytest.raises(IgaparamError) as error:
            domain.build(tolerance=-1)
        assert error.value.status == Status.INVALID_ARGUMENT and "tolerance" in error.value.message
        with pytest.raises(IgaparamError):
            domain.build(min_level=5, max_level=3)
        with pytest.raises(ValueError):
            domain.build(threads=-1)
    assert domain.closed
    with pytest.raises(ValueError):
        domain.cell_count
    domain.close()


def test_boundary_offset():
    """The seam relief cap goes through the options to the build and comes back in the report;
    a bad one is refused by the library with a message naming it, the domain keeping its
    T-mesh."""
    defaults = igaparam._capi.library().igaparam_domain_options_default()
    assert defaults.boundary_offset > 0 and defaults.repair_rounds > 0
    with Domain.from_polylines(annulus_quarter()) as domain:
        report = domain.build(max_level=6, boundary_offset=0, repair_rounds=2)
        assert report.boundary_offset == 0.0 and report.as_dict()["boundary_offset"] == 0.0
        assert report.invalid_cells == 0
        xy = domain.physical_vertices
        for bad, status in ((-1e-3, Status.INVALID_ARGUMENT), (float("nan"), Status.NOT_FINITE),
                            (float("inf"), Status.NOT_FINITE)):
            with pytest.raises(IgaparamError) as error:
                domain.build(max_level=4, boundary_offset=bad)
            assert error.value.status == status and "boundary_offset" in error.value.message
            assert domain.cell_count == report.cells
            assert np.array_equal(domain.physical_vertices, xy)
        with pytest.raises(ValueError):
            domain.build(repair_rounds=-1)
        capped = domain.build(max_level=6, boundary_offset=defaults.boundary_offset)
        assert 0.0 <= capped.boundary_offset <= defaults.boundary_offset
