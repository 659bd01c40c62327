"""Refitting a :class:`~igaparam.Spline` in its own space after :meth:`Domain.update` moved the
domain's T-mesh: :class:`RefitReport` and the methods :meth:`Spline.refit` and
:attr:`Spline.fit_rule` (a mixin of :class:`~igaparam.Spline`)."""

from __future__ import annotations

import ctypes
import dataclasses
from typing import TYPE_CHECKING, Any

from . import _capi
from ._capi import FitRule
from ._mesh import _check

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
    """The refit of a spline (mixed into :class:`~igaparam.Spline`, which sets
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
