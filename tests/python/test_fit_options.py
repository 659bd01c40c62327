"""Tests of Spline.fit with options (igaparam_spline_fit_domain_with) in the Python bindings: on
Gran Canaria, whose fitted map folds and is untangled, the defaults give the plain fit, the
thread count does not change it, progress sees the fit, untangling and smoothing stages and
cancels at each, an exception in it is re-raised, and options out of range are refused."""

from pathlib import Path

import numpy as np
import pytest

from igaparam import Domain, FitChoice, IgaparamError, Spline, Stage, Status

ROOT = Path(__file__).resolve().parents[2]
BOUNDARY = ROOT / "tests" / "data" / "boundary"


@pytest.fixture(scope="module")
def island():
    with Domain.from_file(BOUNDARY / "gran_canaria.txt") as domain:
        domain.build(threads=2)
        yield domain


def control(spline):
    with spline:
        return spline.control_points.copy()


def test_defaults_and_threads_give_the_plain_fit(island):
    plain = control(Spline.fit(island))
    one = control(Spline.fit(island, threads=1))
    two = control(Spline.fit(island, threads=2))
    assert np.array_equal(plain, one) and np.array_equal(one, two)


def test_progress_sees_every_stage(island):
    calls = []
    with Spline.fit(island, threads=2, progress=lambda s, d, t: calls.append((s, d, t))) as spline:
        assert spline.fit_report.untangled > 0
        assert spline.check_validity().certified_positive
    stages = [c[0] for c in calls]
    assert all(isinstance(s, Stage) for s in stages)
    assert [c[1:] for c in calls if c[0] == Stage.FIT] == [(d, 4) for d in range(5)]
    assert Stage.UNTANGLING in stages and Stage.SMOOTHING in stages
    assert stages.index(Stage.UNTANGLING) > max(i for i, s in enumerate(stages) if s == Stage.FIT)
    assert all(d <= t for _, d, t in calls)


@pytest.mark.parametrize("stage", [Stage.FIT, Stage.UNTANGLING, Stage.SMOOTHING])
def test_each_stage_cancels(island, stage):
    with pytest.raises(IgaparamError) as error:
        Spline.fit(island, progress=lambda s, d, t: s != stage)
    assert error.value.status == Status.CANCELLED


def test_an_exception_in_progress_is_raised(island):
    def fail(stage, done, total):
        raise KeyError("stop")

    with pytest.raises(KeyError):
        Spline.fit(island, progress=fail)


def test_switches(island):
    with Spline.fit(island, untangle_rounds=0) as spline:
        v = spline.check_validity()
        assert not v.certified_positive and v.uncertified > 0
        assert spline.fit_report.untangled == 0
    with Spline.fit(island, choice=FitChoice.QUASI_INTERPOLATION, smoothing_sweeps=0) as spline:
        assert spline.fit_report.quasi_interpolation and spline.fit_report.smoothed == 0


def test_options_out_of_range(island):
    for kwargs in [{"samples": 1}, {"max_depth": 13}, {"threads": 5000}, {"choice": 9},
                   {"smoothing_power": 0.5}, {"smoothing_power": float("nan")}]:
        with pytest.raises((IgaparamError, ValueError)):
            Spline.fit(island, **kwargs)
    for kwargs in [{"untangle_rounds": -1}, {"boundary_offset": float("nan")}, {"boundary_offset": -1}]:
        with pytest.raises(ValueError):
            Spline.fit(island, **kwargs)


def test_adaptive_report_carries_the_untangling(island):
    """With target 0 the loop keeps its first, certified fit (no round): its report gives that
    fit's untangling, as the plain fit's report does (it used to be absent)."""
    plain = Spline.fit(island)
    with plain, Domain.from_file(BOUNDARY / "gran_canaria.txt") as domain:
        domain.build(threads=2)
        with Spline.fit_adaptive(domain, target_quality=0.0, threads=2) as adaptive:
            report = adaptive.adapt_report
            assert report.rounds == 0 and report.reached
            assert report.untangled == plain.fit_report.untangled > 0
            assert report.boundary_offset == plain.fit_report.boundary_offset
            assert np.array_equal(adaptive.control_points, plain.control_points)


def test_smoothing_power_lifts_the_worst_quality(island):
    """The default smoothing (power 4) lifts the smallest q_S of the untangled map above the
    mean-distortion smoothing's (power 1)."""
    with Spline.fit(island, smoothing_power=1) as mean, Spline.fit(island) as default:
        low, high = mean.check_validity(), default.check_validity()
        assert low.certified_positive and high.certified_positive
        assert high.min_quality > 1.5 * low.min_quality
