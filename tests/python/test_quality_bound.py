"""The certified lower bound of a spline map's mean ratio from Python: on the bundled boundaries
of the G+Smo comparison it lies below every densely evaluated mean ratio and within a few percent
of the sampled minimum; bad options are refused."""

import os

import numpy as np
import pytest

from igaparam import Domain, IgaparamError, QualityBound, Spline, Status

DATA = os.path.join(os.path.dirname(__file__), "..", "data", "boundary")


def dense_min(spline, n):
    """The smallest mean ratio (computed here from the Jacobians) at n points per direction and
    element."""
    t = np.linspace(0.0, 1.0, n)
    lowest = np.inf
    for lo, hi in spline.element_bounds.reshape(-1, 2, 2):
        u, v = np.meshgrid(lo[0] + t * (hi[0] - lo[0]), lo[1] + t * (hi[1] - lo[1]))
        _, j = spline.evaluate(np.column_stack([u.ravel(), v.ravel()]), jacobians=True)
        det = j[:, 0, 0] * j[:, 1, 1] - j[:, 0, 1] * j[:, 1, 0]
        q = np.where(det > 0, 2 * det / np.einsum("nij,nij->n", j, j), 0.0)
        lowest = min(lowest, q.min())
    return lowest


@pytest.mark.parametrize("name", ["rotor_bdry.xml", "duck2d_BRep.xml"])
def test_bound_brackets_the_dense_minimum(name):
    with Domain.from_file(os.path.join(DATA, name)) as domain:
        domain.build()
        with Spline.fit(domain) as spline:
            b = spline.quality_bound()
            assert isinstance(b, QualityBound)
            dense = dense_min(spline, 21)
            print(f"{name}: bound {b.lower_bound:.4f} <= dense {dense:.4f} <= sampled {b.sampled_min:.4f}")
            assert 0 < b.lower_bound <= dense <= b.sampled_min + 1e-12
            assert b.lower_bound >= 0.9 * b.sampled_min
            assert 0 <= b.element < spline.element_count
            with pytest.raises(IgaparamError) as error:
                spline.quality_bound(gap=1.5)
            assert error.value.status == Status.INVALID_ARGUMENT and "gap" in error.value.message
            with pytest.raises(IgaparamError):
                spline.quality_bound(max_depth=9)
