"""The handle rules seen from Python: closing an object inside the progress callback of its own
running call, or calling it from there, raises a clear exception instead of crashing the
interpreter; integers that do not fit their C type raise instead of wrapping."""

import numpy as np
import pytest

from igaparam import Domain, IgaparamError, Mesh, Status


def bumped_grid(n=6):
    """A Q4 grid of the unit square, boundary fixed, top side pushed up by a bump."""
    x, y = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    points = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    cells = [
        [j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i]
        for j in range(n)
        for i in range(n)
    ]
    mesh = Mesh("Q4", points, cells)
    boundary = (points[:, 0] % 1 == 0) | (points[:, 1] % 1 == 0)
    mesh.set_fixed(np.where(boundary, 3, 0).astype(np.uint8))
    top = np.flatnonzero(points[:, 1] == 1)
    moved = points[top].copy()
    moved[:, 1] += 0.5 * np.sin(np.pi * moved[:, 0])
    mesh.move_nodes(moved, indices=top)
    return mesh


def square_domain():
    t = np.linspace(0, 1, 17)
    top = np.column_stack([1 - t, 1 + 0.3 * np.sin(3 * np.pi * (1 - t))])
    return Domain.from_polylines([[[0, 0], [1, 0]], [[1, 0], [1, 1]], top, [[0, 1], [0, 0]]])


def test_close_inside_relocate():
    mesh = bumped_grid()
    with pytest.raises(IgaparamError) as error:
        mesh.relocate(progress=lambda s, d, t: mesh.close())
    assert error.value.status == Status.CANCELLED
    assert "released" in error.value.message
    assert mesh.closed
    # The interpreter and the library go on.
    with bumped_grid() as other:
        assert other.relocate().invalid_after == 0


def test_calls_inside_relocate_are_busy():
    with bumped_grid() as mesh:
        seen = []

        def probe(stage, done, total):
            seen.append(mesh.node_count)

        with pytest.raises(IgaparamError) as error:
            mesh.relocate(progress=probe)
        assert error.value.status == Status.BUSY and not seen
        assert "igaparam_mesh_node_count" in error.value.message and "in use" in error.value.message
        assert mesh.relocate().invalid_after == 0


def test_close_inside_domain_build():
    domain = square_domain()
    with pytest.raises(IgaparamError) as error:
        domain.build(max_level=4, progress=lambda s, d, t: domain.close())
    assert error.value.status == Status.CANCELLED and domain.closed
    with square_domain() as other:
        assert other.build(max_level=4).invalid_cells == 0


@pytest.mark.parametrize(
    "call",
    [
        lambda m: m.relocate(max_sweeps=2**32),
        lambda m: m.relocate(threads=2**32),
        lambda m: m.relocate(max_newton_iterations=2**40 + 3),
    ],
)
def test_relocate_integers_do_not_wrap(call):
    with bumped_grid() as mesh:
        with pytest.raises(OverflowError, match="does not fit"):
            call(mesh)
        with pytest.raises(ValueError):  # the same error is a ValueError too
            call(mesh)


def test_integers_do_not_wrap():
    with square_domain() as domain:
        with pytest.raises(OverflowError, match="max_level"):
            domain.build(max_level=2**32 + 5)
        with pytest.raises(ValueError, match="max_sweeps"):
            domain.build(max_sweeps=-1)
        assert not domain.is_built
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float64)
    with pytest.raises(OverflowError, match="cell_type"):
        Mesh(2**40 + 9, points, [[0, 1, 2, 3]])
    with pytest.raises(TypeError):
        Mesh(9, points, [[0, 1, 2, 3]]).relocate(max_sweeps=2.5)


def test_cell_budget():
    with square_domain() as domain:
        with pytest.raises(IgaparamError) as error:
            domain.build(min_level=16, max_level=16)
        assert error.value.status == Status.LIMIT_EXCEEDED and "max_cells" in error.value.message
        with pytest.raises(IgaparamError) as error:
            domain.build(tolerance=1e-300, max_level=16, max_cells=200)
        assert error.value.status == Status.LIMIT_EXCEEDED
        assert not domain.is_built
