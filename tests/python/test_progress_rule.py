"""The progress rule, the same in every entry point taking ``progress=`` (Mesh.relocate,
Domain.build, Domain.update, Spline.fit, Spline.fit_adaptive): None or True go on, False (numpy's
too) cancels with Status.CANCELLED, and any other answer — an int above all, which C reads as
"non-zero cancels" and Python's truth the other way round — raises TypeError naming the rule,
which cancels the call. Small inputs: the whole file runs in about a second."""

import numpy as np
import pytest

from igaparam import Domain, IgaparamError, Mesh, Spline, Status


def bumped_grid():
    """A 4 x 4 grid of Q4 cells whose top side is pushed up: relocation sweeps."""
    n = 5
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    points = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    cells = [[j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i] for j in range(n - 1) for i in range(n - 1)]
    mesh = Mesh("Q4", points, np.array(cells))
    boundary = (points[:, 0] % 1 == 0) | (points[:, 1] % 1 == 0)
    mesh.set_fixed(np.where(boundary, 3, 0).astype(np.uint8))
    top = np.flatnonzero(points[:, 1] == 1)
    moved = points[top].copy()
    moved[:, 1] += 0.5 * np.sin(np.pi * moved[:, 0])
    mesh.move_nodes(moved, indices=top)
    return mesh


def wavy_square(amplitude=0.3):
    t = np.linspace(0, 1, 17)
    return [[[0, 0], [1, 0]], [[1, 0], [1, 1]], np.column_stack([1 - t, 1 + amplitude * np.sin(3 * np.pi * (1 - t))]),
            [[0, 1], [0, 0]]]


def built_domain():
    domain = Domain.from_polylines(wavy_square())
    domain.build(max_level=4, threads=2)
    return domain


def relocate(progress):
    with bumped_grid() as mesh:
        mesh.relocate(threads=2, progress=progress)


def build(progress):
    with Domain.from_polylines(wavy_square()) as domain:
        domain.build(max_level=4, threads=2, progress=progress)


def update(progress):
    with built_domain() as domain:
        domain.set_boundary(polylines=wavy_square(0.35))
        domain.update(threads=2, progress=progress)


def fit(progress):
    with built_domain() as domain:
        Spline.fit(domain, threads=2, progress=progress).close()


def fit_adaptive(progress):
    with built_domain() as domain:
        Spline.fit_adaptive(domain, target_quality=0.99, max_rounds=1, threads=2, progress=progress).close()


ENTRIES = [relocate, build, update, fit, fit_adaptive]


@pytest.mark.parametrize("entry", ENTRIES, ids=lambda e: e.__name__)
@pytest.mark.parametrize("answer", [None, True, np.True_], ids=repr)
def test_none_and_true_go_on(entry, answer):
    calls = []

    def progress(stage, done, total):
        calls.append(stage)
        return answer

    entry(progress)
    assert calls  # the callback was asked, and the call completed


@pytest.mark.parametrize("entry", ENTRIES, ids=lambda e: e.__name__)
@pytest.mark.parametrize("answer", [False, np.False_], ids=repr)
def test_false_cancels(entry, answer):
    with pytest.raises(IgaparamError) as error:
        entry(lambda stage, done, total: answer)
    assert error.value.status == Status.CANCELLED


@pytest.mark.parametrize("entry", ENTRIES, ids=lambda e: e.__name__)
@pytest.mark.parametrize("answer", [0, 1, -1, "stop", 0.0], ids=repr)
def test_other_answers_are_refused(entry, answer):
    """An int used to go on whatever its value (only `False` cancelled), so a C-minded `return 1`
    ran to the end in silence."""
    with pytest.raises(TypeError, match="return None or True to go on, False to cancel"):
        entry(lambda stage, done, total: answer)
