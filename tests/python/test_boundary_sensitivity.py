"""Sensitivities of a spline's control points to its domain's boundary in the Python bindings
(Spline.tangent / Spline.adjoint): against central finite differences of update + refit, the
adjoint as the tangent's transpose, and the refusals."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from igaparam import Curve, Domain, IgaparamError, Spline, Status

ROOT = Path(__file__).resolve().parents[2]
PUZZLE = ROOT / "tests" / "data" / "boundary" / "puzzle3_bdry.xml"

spec = importlib.util.spec_from_file_location("morph_loop", ROOT / "examples" / "python" / "morph_loop.py")
morph_loop = importlib.util.module_from_spec(spec)
spec.loader.exec_module(morph_loop)

# d/ds of the stretch (x, y) -> (x (1 + s), y (1 - s/2)) at s = 0.
STRETCH = np.array([1.0, -0.5])


def stretched(curves, s):
    """The curves with their control points stretched by (1 + s, 1 - s/2)."""
    factor = 1.0 + s * STRETCH
    return [Curve(c.degree, c.knots, np.asarray(c.control_points) * factor, c.weights) for c in curves]


def polished(curves):
    domain = Domain.from_curves(curves)
    report = domain.build(threads=2, boundary_offset=0.0, stationarity_tolerance=1e-12)
    assert report.invalid_cells == 0 and report.gradient_norm <= 1e-12
    return domain


def differentiable_fit(domain):
    spline = Spline.fit(domain)
    if spline.fit_report.untangled:
        # The untangling is not differentiated; a refit carries its correction as a constant.
        spline.refit(domain)
    assert spline.fit_report.untangled == 0
    return spline


def test_control_points_follow_a_stretch_as_finite_differences_say():
    curves = morph_loop.read_gismo(PUZZLE)
    with polished(stretched(curves, 0.0)) as domain:
        spline = differentiable_fit(domain)
        # The stretch moves every vertex at fixed parameters by x * STRETCH: on the boundary
        # that is the boundary vertices' motion (inner rows are ignored).
        motion = domain.physical_vertices * STRETCH
        dp = spline.tangent(domain, motion)
        assert dp.shape == (spline.basis_count, 2)
        w = np.cos(np.arange(dp.size, dtype=float)).reshape(dp.shape)
        g = spline.adjoint(domain, w)
        assert g.shape == (domain.vertex_count, 2)
        inner = np.all((domain.parametric_vertices > 0) & (domain.parametric_vertices < 1), axis=1)
        assert np.all(g[inner] == 0.0)
        assert np.isclose(np.sum(w * dp), np.sum(g * motion), rtol=1e-9, atol=0.0)
        h = 1e-4
        points = {}
        for s in (h, -h):
            domain.set_boundary(curves=stretched(curves, s))
            domain.update(threads=2)
            report = spline.refit(domain)
            assert report.fit.untangled == 0
            points[s] = spline.control_points
        fd = (points[h] - points[-h]) / (2 * h)
        assert np.max(np.abs(dp - fd)) <= 1e-6 * np.max(np.abs(fd))


def test_control_sensitivities_follow_the_curves_control_points():
    curves = morph_loop.read_gismo(PUZZLE)
    with polished(curves) as domain:
        spline = differentiable_fit(domain)
        # The stretch moves every curve control point by point * STRETCH per unit of s.
        dc = np.concatenate([np.asarray(c.control_points) * STRETCH for c in curves])
        assert dc.shape == (domain.control_count, 2)
        dp = spline.tangent_controls(domain, dc)
        # The same motion through the boundary vertices.
        assert np.allclose(dp, spline.tangent(domain, domain.physical_vertices * STRETCH), rtol=0, atol=1e-12 * np.max(np.abs(dp)))
        w = np.sin(np.arange(dp.size, dtype=float)).reshape(dp.shape)
        g = spline.adjoint_controls(domain, w)
        assert g.shape == dc.shape
        assert np.isclose(np.sum(w * dp), np.sum(g * dc), rtol=1e-9, atol=0.0)
        with pytest.raises(ValueError, match="dc"):
            spline.tangent_controls(domain, dc[:-1])


def test_sensitivities_refuse_bad_shapes_and_an_unpolished_domain():
    curves = morph_loop.read_gismo(PUZZLE)
    with Domain.from_curves(curves) as domain:
        domain.build(threads=2, boundary_offset=0.0)
        spline = Spline.fit(domain)
        with pytest.raises(ValueError, match="dx_boundary"):
            spline.tangent(domain, np.zeros((3, 2)))
        with pytest.raises(IgaparamError) as error:
            spline.tangent(domain, np.zeros((domain.vertex_count, 2)))
        assert error.value.status == Status.INVALID_ARGUMENT
        assert "stationarity_tolerance" in str(error.value)
        before = spline.control_points
        with pytest.raises(IgaparamError):
            spline.adjoint(domain, np.zeros((spline.basis_count, 2)))
        assert np.array_equal(before, spline.control_points)
