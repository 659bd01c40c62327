"""Refitting a :class:`~igaparam.Spline` in its own space after :meth:`Domain.update` moved the
domain's T-mesh: :class:`RefitReport` and the methods :meth:`Spline.refit` and
:attr:`Spline.fit_rule` (a mixin of :class:`~igaparam.Spline`)."""

from __future__ import annotations

import ctypes
import dataclasses
from typing import TYPE_CHECKING, Any

from . import _capi
from ._capi import FitRule
import numpy as np
import numpy.typing as npt

from ._mesh import _check, _ptr

if TYPE_CHECKING:
    from ._domain import Domain

__all__ = ["FitRule", "RefitReport"]


@dataclasses.dataclass(frozen=True)
class RefitReport:
    """What :meth:`Spline.refit` did (``igaparam_refit_report``).

    Attributes:
        fit: the :class:`FitReport` of the refit (the same basis and element counts; its
            ``untangled`` counts the control points this refit's untangling moved, 0 when the
            correction of an earlier untangling kept the map certified).
        rule: the :class:`FitRule` the control points came from, that of the first fit.
        corrected: control points carrying the correction of an untangling (the map is the
            rule's linear fit of the T-mesh plus that fixed correction); 0 when none.
        certified_positive: True when every element of the new map is certified valid.
        uncertified: elements where positivity is not proven.
        min_quality: smallest sampled mean ratio q_S of the new map.
        mean_quality: mean sampled mean ratio of the new map.
    """

    fit: Any
    rule: FitRule
    corrected: int
    certified_positive: bool
    uncertified: int
    min_quality: float
    mean_quality: float

    def as_dict(self) -> dict:
        """The report as a dict (the fit's report nested)."""
        return dataclasses.asdict(self)


class _Refit:
    """The refit of a spline and the sensitivities of its control points (mixed into :class:`~igaparam.Spline`, which sets
    ``_fit_report_type`` to its :class:`FitReport`)."""

    _fit_report_type: Any

    def refit(self, domain: "Domain") -> RefitReport:
        """Recomputes the control points from the domain's T-mesh after :meth:`Domain.update`,
        in this spline's own space (the same basis functions, elements, Bézier extraction and
        Greville points: the basis count and the element list never change), by the rule of
        the first fit plus the correction of an earlier untangling, if any; then certifies the
        map and untangles it where it folds, as the first fit did. A spline read from a file
        gets the first fit's choice of rule. ``fit_report`` becomes the refit's.

        Raises:
            IgaparamError: ``Status.INVALID_ARGUMENT`` when the domain is not built, its
                boundary was replaced without :meth:`Domain.update`, its dimension is not the
                spline's, or its T-mesh was refined after the fit. The spline is then
                unchanged.
        """
        report = _capi.RefitReport()
        _check(self._lib.igaparam_spline_refit(self._h(), domain._h(), ctypes.byref(report)))
        fit = self._fit_report_type._from_c(report.fit)
        self.fit_report = fit
        return RefitReport(
            fit=fit,
            rule=FitRule(report.rule),
            corrected=report.corrected,
            certified_positive=bool(report.certified_positive),
            uncertified=report.uncertified,
            min_quality=report.min_quality,
            mean_quality=report.mean_quality,
        )

    @property
    def fit_rule(self) -> FitRule:
        """The rule the control points come from (that of the first fit, which
        :meth:`refit` uses).

        Raises:
            IgaparamError: ``Status.INVALID_ARGUMENT`` for a spline read from a file and never
                refitted.
        """
        rule = ctypes.c_int()
        _check(self._lib.igaparam_spline_fit_rule(self._h(), ctypes.byref(rule)))
        return FitRule(rule.value)

    def _boundary_product(self, function, domain, values, name, rows_in, rows_out):
        d = self.dimension
        array = np.ascontiguousarray(values, dtype=np.float64)
        if array.shape != (rows_in, d):
            raise ValueError(f"{name} has shape {array.shape}, expected ({rows_in}, {d})")
        out = np.empty((rows_out, d), dtype=np.float64)
        _check(
            function(
                self._h(),
                domain._h(),
                array.size,
                _ptr(array, ctypes.c_double),
                out.size,
                _ptr(out, ctypes.c_double),
            )
        )
        return out

    def tangent(self, domain: "Domain", dx_boundary: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The first-order motion of the control points of a refit to ``domain`` for a motion of
        its boundary vertices (``igaparam_spline_tangent``): through the T-mesh's optimum
        (implicit function theorem) and the fit rule.

        Args:
            domain: the domain this spline was fitted or refitted to.
            dx_boundary: (num_vertices, d) motion of the T-mesh's vertices, in the order of
                :attr:`Domain.physical_vertices`; rows of inner vertices are ignored. A boundary
                vertex has a parametric coordinate 0 or 1 and sits at its parameters' point
                on the boundary.

        Returns:
            (basis_count, d) float64 motion of the control points.

        Raises:
            IgaparamError: ``Status.INVALID_ARGUMENT`` unless the domain was built or updated
                with ``stationarity_tolerance > 0`` (converged) and no seam relief offset
                (``boundary_offset=0``), and this spline's last fit or refit did not untangle
                (then one more :meth:`refit` carries the correction as a constant).
        """
        return self._boundary_product(
            self._lib.igaparam_spline_tangent,
            domain,
            dx_boundary,
            "dx_boundary",
            domain.vertex_count,
            self.basis_count,
        )

    def adjoint(self, domain: "Domain", dj_dp: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The total derivative of a scalar J of the control points with respect to the
        boundary vertices of ``domain``'s T-mesh (``igaparam_spline_adjoint``, the transpose of
        :meth:`tangent`, with its conditions; not for a quasi-interpolation fit).

        Args:
            domain: the domain this spline was fitted or refitted to.
            dj_dp: (basis_count, d) partial derivatives of J with respect to the control points.

        Returns:
            (num_vertices, d) float64: dJ/dx at the boundary vertices, 0 at inner ones.
        """
        return self._boundary_product(
            self._lib.igaparam_spline_adjoint,
            domain,
            dj_dp,
            "dj_dp",
            self.basis_count,
            domain.vertex_count,
        )

    def tangent_controls(self, domain: "Domain", dc: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The first-order motion of the control points of a refit to ``domain`` for a motion
        of its boundary's own control points (``igaparam_spline_tangent_controls``; weights and
        knots fixed), with the conditions of :meth:`tangent`.

        Args:
            domain: the domain this spline was fitted or refitted to, made from B-spline or
                NURBS curves or surfaces.
            dc: (:attr:`Domain.control_count`, d) motion of the boundary's control points: the
                curves' or surfaces' control points one after the other, in the order the
                domain was made from (a shared corner or edge row appears once per curve or
                surface: move the copies alike).

        Returns:
            (basis_count, d) float64 motion of the spline's control points.
        """
        return self._boundary_product(
            self._lib.igaparam_spline_tangent_controls,
            domain,
            dc,
            "dc",
            domain.control_count,
            self.basis_count,
        )

    def adjoint_controls(self, domain: "Domain", dj_dp: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The total derivative of a scalar J of the spline's control points with respect to
        the control points of ``domain``'s boundary curves or surfaces
        (``igaparam_spline_adjoint_controls``, the transpose of :meth:`tangent_controls`).

        Args:
            domain: the domain this spline was fitted or refitted to.
            dj_dp: (basis_count, d) partial derivatives of J with respect to the control points.

        Returns:
            (:attr:`Domain.control_count`, d) float64.
        """
        return self._boundary_product(
            self._lib.igaparam_spline_adjoint_controls,
            domain,
            dj_dp,
            "dj_dp",
            self.basis_count,
            domain.control_count,
        )
