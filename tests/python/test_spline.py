"""Tests of igaparam.Spline (cubic THB-spline maps) in the Python bindings: the maps of the male
rotor and puzzle domains, checked against their own basis queries, extraction, inversion,
refinement and file round trip; error handling; and the ctypes declarations against the C
header."""

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import pytest

import igaparam
from igaparam import Domain, FitReport, IgaparamError, Spline, Status, ValidityReport
from igaparam import _capi

from cube_gismo import cube_greville, write_cube_gismo

ROOT = Path(__file__).resolve().parents[2]
BOUNDARY = ROOT / "tests" / "data" / "boundary"
HEADER = ROOT / "include" / "igaparam.h"


def fit(name):
    """The spline map of a boundary file's domain; the domain is released first."""
    with Domain.from_file(BOUNDARY / name) as domain:
        report = domain.build(threads=2)
        assert report.invalid_cells == 0
        spline = Spline.fit(domain)
    return spline


@pytest.fixture(scope="module")
def male():
    with fit("male_bdry.xml") as spline:
        yield spline


@pytest.fixture(scope="module")
def puzzle():
    with fit("puzzle3_bdry.xml") as spline:
        yield spline


@pytest.fixture(scope="module", params=["male", "puzzle"])
def spline(request):
    return request.getfixturevalue(request.param)


def random_params(n, seed=1, margin=0.0):
    """n points of [margin, 1 - margin]^2, with the corners and edge points first when margin is 0."""
    params = margin + (1 - 2 * margin) * np.random.default_rng(seed).random((n, 2))
    if margin == 0.0:
        params[:6] = [[0, 0], [1, 1], [1, 0.5], [0.5, 1], [0, 0.3], [0.7, 0]]
    return params


def bernstein3(t):
    """Cubic Bernstein polynomials at t, shape (4,)."""
    s = 1.0 - t
    return np.array([s**3, 3 * t * s**2, 3 * t**2 * s, t**3])


# Construction and read-back.


def test_fit_report_and_sizes(spline):
    report = spline.fit_report
    assert isinstance(report, FitReport)
    assert not report.least_squares and report.seconds >= 0
    if report.quasi_interpolation:
        # Chosen over the interpolation only for a map certified valid.
        assert spline.check_validity().certified_positive
    else:
        assert report.residual < 1e-8
    assert spline.dimension == 2
    n, m = spline.basis_count, spline.element_count
    assert (n, m) == (report.basis_count, report.element_count) and n > 16 and m > 1
    assert report.as_dict()["basis_count"] == n
    # The spline's boundary strays a little from the input curves (relative to the box).
    assert 0 < report.boundary_distance < 3e-3
    control, greville = spline.control_points, spline.greville_points
    assert control.shape == greville.shape == (n, 2) and control.dtype == np.float64
    assert np.all(np.isfinite(control))
    assert greville.min() == 0.0 and greville.max() == 1.0
    levels, bounds = spline.element_levels, spline.element_bounds
    assert levels.shape == (m,) and levels.dtype == np.uint8
    assert bounds.shape == (m, 4)
    side = bounds[:, 2:] - bounds[:, :2]
    assert np.array_equal(side, np.repeat(0.5 ** levels.astype(float)[:, None], 2, axis=1))
    assert bounds.min() == 0.0 and bounds.max() == 1.0
    assert np.prod(side, axis=1).sum() == pytest.approx(1.0, abs=1e-14)  # the elements tile [0,1]^2
    assert "Spline d=2" in repr(spline)


def test_basis_agrees_with_evaluation(spline):
    """Σ N_i P_i = S, Σ ∇N_i P_i = J, Σ N_i = 1, N_i >= 0, and the mean ratio from J."""
    control = spline.control_points
    params = random_params(40)
    points, jac = spline.evaluate(params, jacobians=True)
    assert points.shape == (40, 2) and jac.shape == (40, 2, 2)
    assert np.array_equal(spline.evaluate(params), points)
    for p, x, j in zip(params, points, jac):
        functions, values, gradients = spline.basis_at(p)
        k = functions.size
        assert values.shape == (k,) and gradients.shape == (k, 2) and k >= 16
        assert np.all(np.diff(functions) > 0) and functions.max() < spline.basis_count
        assert abs(values.sum() - 1) < 1e-12
        assert values.min() > -1e-14
        assert np.abs(values @ control[functions] - x).max() < 1e-10
        assert np.abs(control[functions].T @ gradients - j).max() < 1e-8
    det = np.linalg.det(jac)
    expected = np.where(det > 0, 2 * det / np.sum(jac**2, axis=(1, 2)), 0.0)
    assert np.abs(spline.mean_ratio(params) - expected).max() < 1e-12


def test_corners_are_interpolated(spline):
    """The cubic clamped basis interpolates its corner control points."""
    corners = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], dtype=float)
    greville = spline.greville_points
    indices = [int(np.flatnonzero(np.all(greville == c, axis=1))[0]) for c in corners]
    assert np.abs(spline.evaluate(corners) - spline.control_points[indices]).max() < 1e-12


def test_extraction_reproduces_basis_values(spline):
    bounds = spline.element_bounds
    worst = 0.0
    for e in range(0, spline.element_count, 7):
        functions, operator = spline.extraction(e)
        k = functions.size
        assert operator.shape == (k, 16) and functions.dtype == np.int64
        t = np.array([0.3, 0.7])
        lower, upper = bounds[e, :2], bounds[e, 2:]
        point = lower + t * (upper - lower)
        bernstein = np.outer(bernstein3(t[1]), bernstein3(t[0])).ravel()  # index k0 + 4 k1
        at_functions, values, _ = spline.basis_at(point)
        assert np.array_equal(at_functions, functions)
        worst = max(worst, np.abs(operator @ bernstein - values).max())
        # The Bernstein polynomials sum to 1, so do the functions: the columns sum to 1.
        assert np.abs(operator.sum(axis=0) - 1).max() < 1e-12
    assert worst < 1e-12


def test_inner_greville_functions_vanish_on_the_boundary(spline):
    greville = spline.greville_points
    inner = np.all((greville > 0) & (greville < 1), axis=1)
    assert 8 < np.count_nonzero(~inner) < spline.basis_count
    for p in [[0, 0.37], [1, 0.61], [0.23, 0], [0.77, 1]]:
        functions, values, _ = spline.basis_at(p)
        assert np.abs(values[inner[functions]]).max(initial=0.0) < 1e-14


def test_invert_undoes_evaluate(spline):
    params = random_params(40, seed=2, margin=0.05)
    back, found = spline.invert(spline.evaluate(params))
    assert found.dtype == bool and found.all()
    assert np.abs(back - params).max() < 1e-9
    back, found = spline.invert([[1e6, 1e6], [-1e6, 0.0]], samples=3)
    assert not found.any() and np.isnan(back).all()


def test_refine_keeps_the_map(male):
    params = random_params(50, seed=3)
    before = male.evaluate(params)
    m = male.element_count
    # Selected elements on a copy: the original keeps its space.
    refined = male.clone()
    with refined:
        report = refined.refine([0, m // 2, m - 1])
        assert report is refined.fit_report and report.element_count == refined.element_count
        assert m + 9 <= refined.element_count and refined.basis_count > male.basis_count
        assert np.abs(refined.evaluate(params) - before).max() < 1e-9
        # Everything once: every element splits into four (at least).
        m = refined.element_count
        report = refined.refine()
        assert report.element_count >= 4 * m and report.residual < 1e-8
        assert np.abs(refined.evaluate(params) - before).max() < 1e-9
        assert refined.check_validity().certified_positive
    assert male.element_count == male.fit_report.element_count
    assert np.array_equal(male.evaluate(params), before)


def test_gismo_round_trip(male, tmp_path):
    path = tmp_path / "male.xml"
    male.write_gismo(path)
    root = ET.parse(path).getroot()
    assert root.find("Geometry").get("type") == "THBSpline2"
    with Spline.read_gismo(path) as read:
        assert read.fit_report is None
        assert (read.basis_count, read.element_count) == (male.basis_count, male.element_count)
        assert np.array_equal(read.element_bounds, male.element_bounds)
        assert np.abs(read.control_points - male.control_points).max() < 1e-12
        params = random_params(50, seed=4)
        assert np.abs(read.evaluate(params) - male.evaluate(params)).max() < 1e-10


def test_validity_certified_on_male(male):
    report = male.check_validity()
    assert isinstance(report, ValidityReport)
    assert report.certified_positive and report.uncertified == 0 and report.det_lower_bound > 0
    assert 0 < report.min_quality <= report.mean_quality <= 1
    m = male.element_count
    assert isinstance(report.histogram, tuple) and len(report.histogram) == 10
    assert sum(report.histogram) == m * 5**2  # samples^d points per element
    assert report.element_bounds.shape == report.element_quality.shape == (m,)
    assert report.element_bounds.min() == report.det_lower_bound
    assert report.element_quality.min() == report.min_quality
    # The certified lower bounds are below det J at points of the elements.
    bounds = male.element_bounds
    centers = (bounds[:, :2] + bounds[:, 2:]) / 2
    _, jac = male.evaluate(centers, jacobians=True)
    assert np.all(report.element_bounds <= np.linalg.det(jac) * (1 + 1e-12))
    coarse = male.check_validity(max_depth=0, samples=2)
    assert sum(coarse.histogram) == m * 2**2
    assert report.as_dict()["uncertified"] == 0


def test_validity_on_puzzle_agrees_with_its_elements(puzzle):
    report = puzzle.check_validity()
    uncertified = report.element_bounds <= 0
    assert report.uncertified == np.count_nonzero(uncertified)
    assert report.certified_positive == (report.uncertified == 0)
    assert report.element_bounds.min() == report.det_lower_bound


def test_write_vtu(male, tmp_path):
    path = tmp_path / "male.vtu"
    male.write_vtu(path, samples=3)
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    assert int(piece.get("NumberOfCells")) == male.element_count * 3**2
    names = {array.get("Name") for array in piece.iter("DataArray")}
    assert {"quality", "det", "level", "element"} <= names


# Errors.


def expect_error(status, function, *args, **kwargs):
    with pytest.raises(IgaparamError) as info:
        function(*args, **kwargs)
    assert info.value.status == status and info.value.message
    return info.value


def test_out_of_range_and_non_finite_points(male):
    for method in (male.evaluate, male.mean_ratio):
        error = expect_error(Status.INVALID_ARGUMENT, method, [[0.5, 0.5], [1.5, 0.5]])
        assert "outside" in error.message
        expect_error(Status.NOT_FINITE, method, [[np.nan, 0.5]])
        expect_error(Status.NOT_FINITE, method, [[0.5, np.inf]])
    expect_error(Status.INVALID_ARGUMENT, male.basis_at, [0.5, -0.1])
    expect_error(Status.NOT_FINITE, male.basis_at, [np.nan, 0.5])
    expect_error(Status.NOT_FINITE, male.invert, [[np.nan, 0.0]])
    expect_error(Status.INVALID_ARGUMENT, male.invert, [[0.0, 0.0]], samples=1)


def test_element_out_of_range(male):
    m, n = male.element_count, male.basis_count
    expect_error(Status.INVALID_ARGUMENT, male.extraction, m)
    expect_error(Status.INVALID_ARGUMENT, male.refine, [0, m])
    assert (male.element_count, male.basis_count) == (m, n)  # a failed refinement changes nothing
    with pytest.raises(ValueError):
        male.extraction(-1)
    with pytest.raises(ValueError):
        male.refine([-1])
    with pytest.raises(ValueError):
        male.refine([])
    with pytest.raises(ValueError):
        male.refine([0.5])


def test_options_out_of_range(male, tmp_path):
    expect_error(Status.INVALID_ARGUMENT, male.check_validity, samples=1)
    expect_error(Status.INVALID_ARGUMENT, male.check_validity, max_depth=13)
    expect_error(Status.INVALID_ARGUMENT, male.write_vtu, tmp_path / "x.vtu", samples=0)
    with pytest.raises(ValueError):
        male.check_validity(samples=-1)


def test_wrong_shapes(male):
    for bad in ([0.5, 0.5], [[0.5, 0.5, 0.5]], np.zeros((2, 3)), [["a", "b"]]):
        with pytest.raises(ValueError):
            male.evaluate(bad)
    with pytest.raises(ValueError):
        male.invert(np.zeros((1, 3)))
    with pytest.raises(ValueError):
        male.basis_at([[0.5, 0.5]])
    assert male.evaluate(np.zeros((0, 2))).shape == (0, 2)


def test_files_and_domains(tmp_path):
    expect_error(Status.IO, Spline.read_gismo, tmp_path / "missing.xml")
    (tmp_path / "empty.xml").write_text("<xml></xml>")
    expect_error(Status.IO, Spline.read_gismo, tmp_path / "empty.xml")
    with Domain.from_file(BOUNDARY / "male_bdry.xml") as domain:
        expect_error(Status.INVALID_ARGUMENT, Spline.fit, domain)  # not built
    with pytest.raises(ValueError):
        Spline.fit(domain)  # closed


def test_closed_handle(tmp_path):
    spline = fit("male_bdry.xml")
    copy = spline.clone()
    with spline:
        assert not spline.closed
    assert spline.closed and "closed" in repr(spline)
    spline.close()  # again: nothing
    calls = [
        lambda: spline.dimension,
        lambda: spline.control_points,
        lambda: spline.element_bounds,
        lambda: spline.extraction(0),
        lambda: spline.evaluate([[0.5, 0.5]]),
        lambda: spline.invert([[0.0, 0.0]]),
        lambda: spline.basis_at([0.5, 0.5]),
        lambda: spline.refine(),
        lambda: spline.check_validity(),
        lambda: spline.write_gismo(tmp_path / "closed.xml"),
        lambda: spline.clone(),
    ]
    for call in calls:
        with pytest.raises(ValueError, match="closed"):
            call()
    # The copy is independent of the closed original.
    with copy:
        assert copy.check_validity().certified_positive


# The ctypes declarations against the C header.


def header_prototypes():
    """{name: number of parameters} of the header's functions."""
    text = re.sub(r"/\*.*?\*/", "", HEADER.read_text(), flags=re.S)
    found = {}
    for match in re.finditer(r"^[\w ]+?\**\s*\b(igaparam_\w+)\(([^;]*?)\);", text, flags=re.M):
        parameters = " ".join(match.group(2).split())
        found[match.group(1)] = 0 if parameters in ("", "void") else parameters.count(",") + 1
    return found


def header_struct_fields(name):
    text = re.sub(r"/\*.*?\*/", "", HEADER.read_text(), flags=re.S)
    body = re.search(r"typedef struct \{([^}]*)\} " + name + ";", text).group(1)
    return re.findall(r"(\w+)(?:\[\w+\])?;", body)


def test_prototypes_match_header():
    prototypes = header_prototypes()
    spline_functions = {name for name in prototypes if name.startswith("igaparam_spline_")}
    assert len(spline_functions) >= 20 and spline_functions <= set(_capi._PROTOTYPES)
    for name, (_, argtypes) in _capi._PROTOTYPES.items():
        assert prototypes.get(name) == len(argtypes), name
    for struct, c_name in [
        (_capi.FitReport, "igaparam_fit_report"),
        (_capi.ValidityReport, "igaparam_validity_report"),
        (_capi.ValidityOptions, "igaparam_validity_options"),
        (_capi.AdaptOptions, "igaparam_adapt_options"),
        (_capi.AdaptReport, "igaparam_adapt_report"),
        (_capi.RefitReport, "igaparam_refit_report"),
        (_capi.Curve, "igaparam_curve"),
        (_capi.Surface, "igaparam_surface"),
        (_capi.DomainUpdateOptions, "igaparam_domain_update_options"),
        (_capi.DomainUpdateReport, "igaparam_domain_update_report"),
    ]:
        assert [field[0] for field in struct._fields_] == header_struct_fields(c_name), c_name
    for rule in _capi.FitRule:
        assert re.search(rf"IGAPARAM_FIT_{rule.name} = {int(rule)},", HEADER.read_text()), rule
    bins = re.search(r"#define IGAPARAM_HISTOGRAM_BINS (\d+)", HEADER.read_text()).group(1)
    assert int(bins) == _capi.HISTOGRAM_BINS


def test_exports():
    assert {"Spline", "FitReport", "ValidityReport", "AdaptReport"} <= set(igaparam.__all__)


def test_readme_spline_example(male, tmp_path, monkeypatch):
    """The spline example of bindings/python/README.md runs (in a temporary directory)."""
    text = (ROOT / "bindings" / "python" / "README.md").read_text()
    block = next(b for b in re.findall(r"```python\n(.*?)```", text, flags=re.S) if "Spline.fit" in b)
    code = "import numpy as np\nimport igaparam\n" + block.replace('"tests/data/boundary/', f'"{BOUNDARY}/')
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md", "exec"), {})
    with Spline.read_gismo(tmp_path / "male_spline.xml") as read:
        assert read.element_count > male.element_count  # the refined map was written
        # The .vtu read back (meshio): 4 x 4 quads per element of that map, the documented
        # arrays, q_S in [0, 1] and det J > 0 (the map is certified).
        written = meshio.read(tmp_path / "male_spline.vtu")
        assert len(written.cells_dict["quad"]) == 16 * read.element_count
        assert {"quality", "det"} <= set(written.point_data)
        assert {"level", "element"} <= set(written.cell_data)
        quality = np.asarray(written.point_data["quality"])
        assert quality.min() > 0 and quality.max() <= 1
        assert np.asarray(written.point_data["det"]).min() > 0
        element = np.asarray(written.cell_data["element"][0]).ravel()
        assert set(element.tolist()) == set(range(read.element_count))


# A 3D map: an affine map of the unit cube written as G+Smo XML. B-splines reproduce linear
# functions from their Greville points, so S(u) = A u + b exactly.

AFFINE = np.array([[2.0, 0.3, 0.0], [-0.2, 1.5, 0.1], [0.0, 0.4, 1.0]])
SHIFT = np.array([1.0, -2.0, 0.5])


@pytest.fixture(scope="module")
def cube(tmp_path_factory):
    greville = cube_greville()
    control = greville @ AFFINE.T + SHIFT
    path = tmp_path_factory.mktemp("cube") / "cube.xml"
    write_cube_gismo(path, control)
    with Spline.read_gismo(path) as spline:
        assert np.array_equal(spline.greville_points, greville)
        assert np.array_equal(spline.control_points, control)
        yield spline


def check_affine(spline, params):
    points, jac = spline.evaluate(params, jacobians=True)
    assert points.shape == (len(params), 3) and jac.shape == (len(params), 3, 3)
    assert np.abs(points - (params @ AFFINE.T + SHIFT)).max() < 1e-12
    assert np.abs(jac - AFFINE).max() < 1e-12
    return points


def test_3d_affine_map(cube):
    assert (cube.dimension, cube.basis_count, cube.element_count) == (3, 125, 8)
    assert np.array_equal(cube.element_levels, np.ones(8, dtype=np.uint8))
    bounds = cube.element_bounds
    assert bounds.shape == (8, 6) and np.array_equal(bounds[:, 3:] - bounds[:, :3], np.full((8, 3), 0.5))
    params = np.random.default_rng(5).random((30, 3))
    points = check_affine(cube, params)
    expected_q = 3 * np.linalg.det(AFFINE) ** (2 / 3) / np.sum(AFFINE**2)
    assert np.abs(cube.mean_ratio(params) - expected_q).max() < 1e-12
    back, found = cube.invert(points)
    assert found.all() and np.abs(back - params).max() < 1e-9
    functions, values, gradients = cube.basis_at(params[0])
    assert functions.size == 64 and gradients.shape == (64, 3)
    assert np.abs(values @ cube.control_points[functions] - points[0]).max() < 1e-12
    functions, operator = cube.extraction(7)
    assert operator.shape == (functions.size, 64)
    validity = cube.check_validity(samples=2)
    assert validity.certified_positive and sum(validity.histogram) == 8 * 2**3
    assert validity.det_lower_bound == pytest.approx(np.linalg.det(AFFINE), rel=1e-9)
    assert validity.min_quality == pytest.approx(expected_q, abs=1e-12)


def test_3d_refine_and_round_trip(cube, tmp_path):
    params = np.random.default_rng(6).random((30, 3))
    with cube.clone() as refined:
        refined.refine([0])
        assert refined.element_count == 15 and refined.element_levels.max() == 2
        check_affine(refined, params)
        refined.write_gismo(tmp_path / "refined.xml")
        refined.write_vtu(tmp_path / "refined.vtu", samples=1)
        piece = ET.parse(tmp_path / "refined.vtu").getroot().find("UnstructuredGrid/Piece")
        assert int(piece.get("NumberOfCells")) == 15
    with Spline.read_gismo(tmp_path / "refined.xml") as read:
        assert read.element_count == 15
        check_affine(read, params)


def test_fit_adaptive_on_rotor():
    """The adaptive loop refines the rotor's T-mesh until its map is certified with q_S >= 0.4
    (its first, smoothed map has 0.34); the domain keeps the refined T-mesh. A cancelled loop
    leaves the domain as it was."""
    with Domain.from_file(BOUNDARY / "rotor_bdry.xml") as domain:
        built = domain.build(threads=2)
        with pytest.raises(ValueError):
            Spline.fit_adaptive(domain, max_rounds=-1)
        with pytest.raises(IgaparamError) as error:
            Spline.fit_adaptive(
                domain, target_quality=0.4, threads=2, progress=lambda stage, done, total: False
            )
        assert error.value.status == Status.CANCELLED
        assert domain.cell_count == built.cells
        with Spline.fit_adaptive(domain, target_quality=0.4, threads=2) as spline:
            report = spline.adapt_report
            assert report.rounds >= 1 and report.refined_cells > 0
            assert report.reached and report.certified_positive and report.min_quality >= 0.4
            assert report.elements == spline.element_count == domain.cell_count > built.cells
            assert report.basis == spline.basis_count
            validity = spline.check_validity()
            assert validity.certified_positive
            assert validity.min_quality == pytest.approx(report.min_quality, rel=1e-12)
