"""The G+Smo XML written by igaparam.Spline.write_gismo, read back by G+Smo itself (its Python
module pygismo): the THB-spline basis it builds from the file has the library's functions,
elements and control points, and the map, its Jacobian and the basis functions agree with the
library's own evaluation at random parametric points. Skipped when pygismo is not installed
(a failure under IGAPARAM_NO_SKIP=1)."""

from pathlib import Path

import numpy as np
import pytest

from igaparam import Domain, Spline

from cube_gismo import cube_greville, write_cube_gismo

gs = pytest.importorskip("pygismo")

BOUNDARY = Path(__file__).resolve().parents[2] / "tests" / "data" / "boundary"


def fit_puzzle():
    with Domain.from_file(BOUNDARY / "puzzle3_bdry.xml") as domain:
        domain.build(threads=2)
        return Spline.fit(domain)


@pytest.fixture(scope="module")
def puzzle():
    with fit_puzzle() as spline:
        yield spline


@pytest.fixture(scope="module")
def puzzle_refined(puzzle):
    """The puzzle's map with a few elements refined, twice (one more level there)."""
    with puzzle.clone() as spline:
        spline.refine([0, puzzle.element_count // 3, puzzle.element_count - 1])
        spline.refine([spline.element_count // 2, spline.element_count - 2])
        yield spline


@pytest.fixture(scope="module")
def shell(tmp_path_factory):
    """A 3D map: a sheared sector of a thick cylindrical shell, refined locally to levels 1 to 4."""
    greville = cube_greville()
    r, t, z = 1 + greville[:, 0], greville[:, 1] * np.pi / 2, greville[:, 2]
    control = np.column_stack([r * np.cos(t), r * np.sin(t), z + 0.2 * greville[:, 0] * greville[:, 1]])
    path = tmp_path_factory.mktemp("shell") / "shell.xml"
    write_cube_gismo(path, control)
    with Spline.read_gismo(path) as spline:
        spline.refine([0])
        spline.refine([spline.element_count - 1, 3])
        spline.refine([0, 5])
        assert spline.element_levels.min() == 1 and spline.element_levels.max() == 4
        yield spline


@pytest.fixture(params=["puzzle", "puzzle_refined", "shell"])
def spline(request):
    return request.getfixturevalue(request.param)


@pytest.fixture
def gismo_patch(spline, tmp_path):
    """The spline written by the library and read by G+Smo (``gsReadFile``: a file holding one
    geometry gives a multipatch of one patch). The patch refers into the multipatch, which is
    kept until the test ends."""
    path = tmp_path / "map.xml"
    spline.write_gismo(path)
    patches = gs.core.gsMultiPatch()
    gs.io.gsReadFile(str(path), patches)
    assert patches.nPatches() == 1
    yield patches.patch(0)


def random_params(spline, n, seed):
    """n random points of [0,1]^d, the corners of the parametric domain first."""
    d = spline.dimension
    params = np.random.default_rng(seed).random((n, d))
    corners = np.array(np.meshgrid(*[[0.0, 1.0]] * d, indexing="ij")).reshape(d, -1).T
    params[: len(corners)] = corners
    return params


def extent(spline):
    return np.ptp(spline.control_points, axis=0).max()


def test_gismo_builds_the_same_basis(spline, gismo_patch):
    d = spline.dimension
    thb = {2: gs.hsplines.gsTHBSpline2, 3: gs.hsplines.gsTHBSpline3}[d]
    assert isinstance(gismo_patch, thb)
    assert (gismo_patch.parDim(), gismo_patch.geoDim()) == (d, d)
    basis = gismo_patch.basis()
    assert basis.size() == spline.basis_count
    assert basis.numElements(gs.core.boxSide(0)) == spline.element_count
    coefs = gismo_patch.coefs()
    assert coefs.shape == (spline.basis_count, d)
    assert np.abs(coefs - spline.control_points).max() <= 1e-15 * extent(spline)


def assert_same_map(spline, gismo_patch):
    """The map and its Jacobian agree with G+Smo's at 2000 random points."""
    d = spline.dimension
    params = random_params(spline, 2000, seed=7)
    points, jac = spline.evaluate(params, jacobians=True)
    columns = np.ascontiguousarray(params.T)  # G+Smo takes one point per column
    gismo_points = gismo_patch.eval(columns).T
    assert gismo_points.shape == points.shape
    assert np.abs(gismo_points - points).max() < 1e-10 * extent(spline)
    # deriv: row d i + j of a column is ∂S_i/∂u_j at the point.
    gismo_jac = gismo_patch.deriv(columns).T.reshape(-1, d, d)
    assert np.abs(gismo_jac - jac).max() < 1e-10 * np.abs(jac).max()


def test_gismo_evaluates_the_same_map(spline, gismo_patch):
    assert_same_map(spline, gismo_patch)


def assert_same_basis_functions(spline, gismo_patch):
    """The basis functions and their gradients agree with G+Smo's at 100 random points."""
    n, d = spline.basis_count, spline.dimension
    params = random_params(spline, 100, seed=8)
    columns = np.ascontiguousarray(params.T)
    basis = gismo_patch.basis()
    # G+Smo's active functions at a point include truncated ones that vanish there; the
    # columns are padded with function 0 and value 0, hence the sums.
    active, values, derivatives = basis.active(columns), basis.eval(columns), basis.deriv(columns)
    worst_value = worst_gradient = largest_gradient = 0.0
    for p, param in enumerate(params):
        gismo_values, ours_values = np.zeros(n), np.zeros(n)
        np.add.at(gismo_values, active[:, p], values[:, p])
        gismo_gradients, ours_gradients = np.zeros((n, d)), np.zeros((n, d))
        np.add.at(gismo_gradients, active[:, p], derivatives[:, p].reshape(-1, d))
        functions, function_values, function_gradients = spline.basis_at(param)
        ours_values[functions], ours_gradients[functions] = function_values, function_gradients
        worst_value = max(worst_value, np.abs(gismo_values - ours_values).max())
        worst_gradient = max(worst_gradient, np.abs(gismo_gradients - ours_gradients).max())
        largest_gradient = max(largest_gradient, np.abs(ours_gradients).max())
    assert worst_value < 1e-12
    assert worst_gradient < 1e-12 * largest_gradient


def test_gismo_evaluates_the_same_basis_functions(spline, gismo_patch):
    assert_same_basis_functions(spline, gismo_patch)


@pytest.fixture(params=["puzzle", "shell"])
def gismo_refined(request, tmp_path):
    """A map refined by G+Smo itself in one corner, deeper than its finest level (two levels in
    2D, one in 3D: G+Smo's 3D refinement takes minutes two levels down), written by G+Smo
    (``gsFileData.save``) and read by the library; with G+Smo's patch and its multipatch, kept
    until the test ends. G+Smo does not balance its trees: a reader that balanced them would
    build more functions than the file has coefficients for."""
    ours = request.getfixturevalue(request.param)
    path = tmp_path / "ours.xml"
    ours.write_gismo(path)
    patches = gs.core.gsMultiPatch()
    gs.io.gsReadFile(str(path), patches)
    patch = patches.patch(0)
    d = ours.dimension
    patch.refineElements([int(ours.element_levels.max()) + (2 if d == 2 else 1)] + [0] * d + [4] * d)
    data = gs.io.gsFileData()
    data.add(patches)
    data.save(str(tmp_path / "gismo"))
    with Spline.read_gismo(tmp_path / "gismo.xml") as spline:
        yield spline, patch, patches


def test_the_library_reads_a_map_refined_and_written_by_gismo(gismo_refined):
    spline, patch, _ = gismo_refined
    basis = patch.basis()
    assert spline.basis_count == basis.size()
    assert spline.element_count == basis.numElements(gs.core.boxSide(0))
    # G+Smo writes its coefficients to 16 digits.
    assert np.abs(spline.control_points - patch.coefs()).max() <= 1e-14 * extent(spline)
    assert_same_map(spline, patch)
    assert_same_basis_functions(spline, patch)
