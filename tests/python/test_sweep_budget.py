"""The total sweep budget of a build (``max_total_sweeps``): the sweeps of all stages stop there,
the build succeeds with the T-mesh reached and its report says so; the budget's range is checked."""

import numpy as np
import pytest

from igaparam import Domain, IgaparamError, Status


def wavy_domain():
    t = np.linspace(0, 1, 33)
    top = np.column_stack([1 - t, 1 + 0.3 * np.sin(3 * np.pi * (1 - t))])
    return Domain.from_polylines([[[0, 0], [1, 0]], [[1, 0], [1, 1]], top, [[0, 1], [0, 0]]])


def test_budget_stops_the_sweeps_of_all_stages():
    with wavy_domain() as domain:
        full = domain.build(max_level=4)
        assert full.sweeps > 3 and not full.sweep_budget_exhausted
        seen = []
        cut = domain.build(max_level=4, max_total_sweeps=3, progress=lambda s, d, t: seen.append(d) or None)
        assert (cut.sweeps, cut.sweep_budget_exhausted) == (3, True)
        # Every sweep but the last is reported, numbered across the stages (0: adaptation rounds).
        assert [d for d in seen if d > 0] == [1, 2]
        assert cut.cells == full.cells


def test_budget_range():
    with wavy_domain() as domain:
        with pytest.raises(IgaparamError) as error:
            domain.build(max_total_sweeps=0)
        assert error.value.status == Status.INVALID_ARGUMENT and "max_total_sweeps" in error.value.message
        with pytest.raises(OverflowError):
            domain.build(max_total_sweeps=2**32)
        assert not domain.is_built
