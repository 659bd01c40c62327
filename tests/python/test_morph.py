"""Tests of the shape-optimization loop in the Python bindings: domains from curve and surface
arrays, Domain.set_boundary / update, Spline.refit, and the loop example
examples/python/morph_loop.py."""

import importlib.util
import io
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import igaparam
from igaparam import Curve, Domain, FitRule, IgaparamError, Spline, Status, Surface

ROOT = Path(__file__).resolve().parents[2]
BOUNDARY = ROOT / "tests" / "data" / "boundary"
EXAMPLE = ROOT / "examples" / "python" / "morph_loop.py"

spec = importlib.util.spec_from_file_location("morph_loop", EXAMPLE)
morph_loop = importlib.util.module_from_spec(spec)
spec.loader.exec_module(morph_loop)


def test_curves_from_arrays_give_the_domain_of_their_file():
    path = BOUNDARY / "puzzle3_bdry.xml"
    curves = morph_loop.read_gismo(path)
    assert len(curves) == 4 and all(isinstance(c, Curve) for c in curves)
    with Domain.from_file(path) as read, Domain.from_curves(curves) as made:
        read.build(threads=2)
        made.build(threads=2)
        assert np.array_equal(read.physical_vertices, made.physical_vertices)
    # Tuples do as well as Curve objects.
    tuples = [(c.degree, c.knots, c.control_points) for c in curves]
    with Domain.from_curves(tuples) as domain:
        assert domain.dimension == 2


def test_surfaces_from_arrays_give_the_solid_of_their_file():
    path = BOUNDARY / "duck3d_BRep.xml"
    surfaces = morph_loop.read_gismo(path)
    assert len(surfaces) == 6 and all(isinstance(s, Surface) for s in surfaces)
    with Domain.solid_from_file(path) as read, Domain.solid_from_surfaces(surfaces) as made:
        for domain in (read, made):
            domain.build(tolerance=1e-2, max_level=2, threads=2)
        assert np.array_equal(read.physical_vertices, made.physical_vertices)


def test_the_loop_example_keeps_the_space_and_certifies_every_step():
    out = io.StringIO()
    summary = morph_loop.run(BOUNDARY / "puzzle3_bdry.xml", steps=20, threads=2, out=out)
    assert summary["all_certified_same_space"], out.getvalue()
    assert summary["basis"] == 381 and summary["elements"] == 373
    rows = [line for line in out.getvalue().splitlines() if line[:5].strip().isdigit()]
    assert len(rows) == 20


def test_the_loop_example_runs_as_a_program():
    run = subprocess.run(
        [sys.executable, str(EXAMPLE), str(BOUNDARY / "puzzle3_bdry.xml"), "--steps", "3", "--threads", "2"],
        capture_output=True, text=True,
    )
    assert run.returncode == 0, run.stderr
    summary = json.loads(run.stdout.splitlines()[-1])
    assert summary["steps"] == 3 and summary["all_certified_same_space"]


@pytest.fixture
def loop():
    """A built quarter annulus of four curves (NURBS arcs) and its spline."""
    domain = Domain.from_curves(quarter_annulus(2.0))
    domain.build(threads=2)
    spline = Spline.fit(domain)
    yield domain, spline
    spline.close()
    domain.close()


def quarter_annulus(outer):
    w = math.sqrt(0.5)
    line, arc = [0, 0, 1, 1], [0, 0, 0, 1, 1, 1]
    return [
        Curve(1, line, [[0, outer], [0, 1]]),
        Curve(1, line, [[1, 0], [outer, 0]]),
        Curve(2, arc, [[outer, 0], [outer, outer], [0, outer]], [1, w, 1]),
        Curve(2, arc, [[0, 1], [1, 1], [1, 0]], [1, w, 1]),
    ]


def test_update_and_refit(loop):
    domain, spline = loop
    rule, basis, bounds = spline.fit_rule, spline.basis_count, spline.element_bounds
    assert isinstance(rule, FitRule)
    domain.set_boundary(curves=quarter_annulus(2.2))
    with pytest.raises(IgaparamError) as error:
        spline.refit(domain)  # the T-mesh has not moved yet
    assert error.value.status == Status.INVALID_ARGUMENT and "update" in str(error.value)
    report = domain.update(threads=2)
    assert report.domain.invalid_cells == 0 and report.boundary_motion > 0 and report.refined_cells == 0
    assert isinstance(report.domain, igaparam.DomainReport) and "tolerance_met" in report.as_dict()
    refit = spline.refit(domain)
    assert refit.rule == rule and refit.certified_positive and refit.fit.basis_count == basis
    assert spline.basis_count == basis and np.array_equal(spline.element_bounds, bounds)
    assert spline.fit_report is refit.fit
    corners = spline.evaluate([[0, 0], [1, 0], [1, 1], [0, 1]])
    assert np.hypot(corners[:, 0], corners[:, 1]).max() == pytest.approx(2.2, abs=1e-9)
    # The polylines of the same boundary replace the curves; nothing moves on a second update.
    t = np.linspace(0, 0.5 * np.pi, 40)
    domain.set_boundary(polylines=[
        np.column_stack([np.zeros(2), [2.2, 1.0]]),
        np.column_stack([[1.0, 2.2], np.zeros(2)]),
        np.column_stack([2.2 * np.cos(t), 2.2 * np.sin(t)]),
        np.column_stack([np.sin(t), np.cos(t)]),
    ])
    assert domain.update(threads=2, max_sweeps=50).domain.invalid_cells == 0


def test_bad_boundaries_leave_the_domain_unchanged(loop, tmp_path):
    domain, spline = loop
    before = domain.physical_vertices
    curves = quarter_annulus(2.1)
    with pytest.raises(ValueError, match="exactly one"):
        domain.set_boundary(curves=curves, polylines=[])
    with pytest.raises(ValueError, match="exactly one"):
        domain.set_boundary()
    with pytest.raises(ValueError, match="shape"):
        domain.set_boundary(curves=[Curve(1, [0, 0, 1, 1], [0, 1, 2])] + curves[1:])
    cases = [
        (curves[:3], Status.INVALID_ARGUMENT),  # three curves: another topology
        ([Curve(2, [0, 0, 0, 0.8, 0.2, 1, 1], curves[2].control_points)] + curves[1:], Status.INVALID_ARGUMENT),
        ([Curve(1, [0, 0, 1, 1], [[0, np.nan], [0, 1]])] + curves[1:], Status.NOT_FINITE),
        ([Curve(0, [0, 1, 1], [[0, 2.1], [0, 1]])] + curves[1:], Status.INVALID_ARGUMENT),
    ]
    for bad, status in cases:
        with pytest.raises(IgaparamError) as error:
            domain.set_boundary(curves=bad)
        assert error.value.status == status, str(error.value)
    # A reflex corner: the straight side x = 0 bent outwards past the corner (0, 1).
    reflex = [Curve(2, [0, 0, 0, 1, 1, 1], [[0, 2.1], [-0.5, 0.5], [0, 1]])] + curves[1:]
    with pytest.raises(IgaparamError, match="convex"):
        domain.set_boundary(curves=reflex)
    with pytest.raises(IgaparamError) as error:
        domain.set_boundary(faces=[([[0, 0, 0]], [[0, 0, 0]])] * 6)
    assert error.value.status == Status.INVALID_ARGUMENT and "planar" in str(error.value)
    with pytest.raises(IgaparamError):
        domain.set_boundary_from_file(BOUNDARY / "duck3d_BRep.xml", scale=[1, 1, 1])
    assert domain.update(threads=2).boundary_motion == 0
    assert np.abs(domain.physical_vertices - before).max() < 1e-2


def test_update_before_build_and_cancel():
    with Domain.from_curves(quarter_annulus(2.0)) as domain:
        with pytest.raises(IgaparamError) as error:
            domain.update()
        assert error.value.status == Status.INVALID_ARGUMENT and "build" in str(error.value)
        domain.build(threads=2)
        before = domain.physical_vertices
        domain.set_boundary(curves=quarter_annulus(2.3))
        with pytest.raises(IgaparamError) as error:
            domain.update(progress=lambda stage, done, total: False)
        assert error.value.status == Status.CANCELLED
        assert np.array_equal(domain.physical_vertices, before)


def test_a_read_spline_gets_its_rule_at_its_first_refit(loop, tmp_path):
    domain, spline = loop
    spline.write_gismo(tmp_path / "annulus.xml")
    with Spline.read_gismo(tmp_path / "annulus.xml") as read:
        with pytest.raises(IgaparamError):
            read.fit_rule
        report = read.refit(domain)
        assert report.rule == spline.fit_rule == read.fit_rule and report.certified_positive


def test_exports():
    assert {"Curve", "Surface", "UpdateReport", "RefitReport", "FitRule"} <= set(igaparam.__all__)


def test_the_loop_example_checks_the_sensitivities_against_finite_differences():
    out = io.StringIO()
    summary = morph_loop.sensitivity_check(BOUNDARY / "puzzle3_bdry.xml", threads=2, out=out)
    assert summary["central"] != 0.0
    assert summary["relative_error"] <= 1e-6, out.getvalue()
