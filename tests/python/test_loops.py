"""Shape-optimization loops from Python: warm-started relocation, the Newton stage, and the
sensitivity products Mesh.adjoint / Mesh.tangent against central differences."""

from pathlib import Path

import numpy as np
import pytest

import igaparam
from igaparam import IgaparamError, Mesh, Status

ROOT = Path(__file__).resolve().parents[2]
AIRFOIL = ROOT / "tests" / "data" / "airfoil_0012_q9.vtu"
TIGHT = 1e-12


def relocated(mesh, **options):
    report = mesh.relocate(threads=2, stationarity_tolerance=TIGHT, **options)
    assert report.invalid_after == 0 and report.gradient_norm <= TIGHT
    return report


def prescribed_motion(mesh, seed):
    rng = np.random.default_rng(seed)
    mask = mesh.fixed
    bits = (mask[:, None] >> np.arange(3)) & 1
    bits[:, mesh.dimension:] = 0
    return rng.uniform(-1, 1, (mesh.node_count, 3)) * bits


def moved_copy(mesh, motion, h):
    """A fresh mesh with `mesh`'s reference and constraints, its prescribed nodes at the
    positions of `mesh` moved by h * motion, relocated tightly."""
    copy = Mesh(mesh.cell_type, mesh.reference, mesh.cells)
    copy.set_fixed(mesh.fixed)
    copy.move_nodes(mesh.positions + h * motion)
    relocated(copy)
    return copy.positions


def test_adjoint_and_tangent_of_the_airfoil_match_central_differences():
    mesh = Mesh.read_vtu(AIRFOIL)
    relocated(mesh)
    rng = np.random.default_rng(3)
    w = rng.uniform(-1, 1, (mesh.node_count, 3))
    v = prescribed_motion(mesh, 4)
    tangent = mesh.tangent(v)
    adjoint = mesh.adjoint(w)
    assert tangent.shape == adjoint.shape == (mesh.node_count, 3)
    assert abs(np.sum(w * tangent) - np.sum(adjoint * v)) <= 1e-10 * abs(np.sum(w * tangent))
    h = 1e-6
    fd = (moved_copy(mesh, v, h) - moved_copy(mesh, v, -h)) / (2 * h)
    assert np.max(np.abs(fd - tangent)) <= 1e-6 * np.max(np.abs(tangent))
    assert abs(np.sum(w * fd) - np.sum(adjoint * v)) <= 1e-6 * abs(np.sum(adjoint * v))


def test_products_are_refused_without_a_stationary_point():
    mesh = Mesh.read_vtu(AIRFOIL)
    v = prescribed_motion(mesh, 1)
    with pytest.raises(IgaparamError) as error:
        mesh.tangent(v)
    assert error.value.status == Status.INVALID_ARGUMENT and "no relocation" in str(error.value)
    mesh.relocate(threads=2)
    with pytest.raises(IgaparamError, match="stationarity_tolerance"):
        mesh.adjoint(v)
    relocated(mesh)
    with pytest.raises(ValueError):
        mesh.adjoint(v[1:])
    bad = v.copy()
    bad[3, 1] = np.nan
    with pytest.raises(IgaparamError) as error:
        mesh.tangent(bad)
    assert error.value.status == Status.NOT_FINITE
    mesh.move_nodes(mesh.positions)
    with pytest.raises(IgaparamError, match="moved"):
        mesh.adjoint(v)


def test_options_are_checked():
    mesh = Mesh.read_vtu(AIRFOIL)
    with pytest.raises(ValueError):
        mesh.relocate(method="fastest")
    with pytest.raises(ValueError):
        mesh.relocate(placement="warm")
    with pytest.raises(IgaparamError) as error:
        mesh.relocate(stationarity_tolerance=-1.0)
    assert error.value.status == Status.INVALID_ARGUMENT


def rotated(points, prescribed, angle):
    """The prescribed nodes on the airfoil (inside the square [-1.9, 1.9]^2) rotated about the
    origin, the outer ones kept."""
    c, s = np.cos(angle), np.sin(angle)
    out = points.copy()
    inner = prescribed & (np.max(np.abs(points[:, :2]), axis=1) < 1.9)
    x, y = points[inner, 0], points[inner, 1]
    out[inner, 0], out[inner, 1] = c * x - s * y, s * x + c * y
    return out


def test_a_warm_loop_follows_the_cold_optima():
    """Ten 3-degree rotations of the airfoil relocated with placement='incremental': every step
    valid and equal (to 1e-8) to a cold relocation of the same boundary."""
    mesh = Mesh.read_vtu(AIRFOIL)
    reference = mesh.reference
    prescribed = mesh.fixed != 0
    mask = mesh.fixed
    for step in range(1, 11):
        target = rotated(reference, prescribed, np.radians(3 * step))
        mesh.move_nodes(target[prescribed], indices=np.flatnonzero(prescribed))
        warm = mesh.relocate(threads=2, stationarity_tolerance=1e-10, placement="incremental")
        assert warm.invalid_after == 0 and warm.converged
        cold = Mesh(mesh.cell_type, reference, mesh.cells)
        cold.set_fixed(mask)
        cold.move_nodes(target)
        cold.relocate(threads=2, stationarity_tolerance=1e-10)
        assert np.max(np.abs(mesh.positions - cold.positions)) < 1e-8


def test_stages_include_the_newton_stage():
    mesh = Mesh.read_vtu(AIRFOIL)
    stages = set()
    mesh.relocate(threads=2, stationarity_tolerance=1e-10, progress=lambda s, d, t: stages.add(s))
    assert igaparam.Stage.STATIONARITY in stages
