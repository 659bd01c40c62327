"""The :class:`Spline` class: a cubic truncated hierarchical B-spline (THB) map of [0,1]^d onto a
domain, with its fit and validity reports."""

from __future__ import annotations

import ctypes
import dataclasses
import os
from typing import TYPE_CHECKING, Callable, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _capi
from ._handle import _Handle
from ._ints import c_int_value
from ._capi import FitChoice, Stage
from ._mesh import _attach_progress, _check, _ptr, _set_counts
from ._refit import _Refit

if TYPE_CHECKING:
    from ._domain import Domain

__all__ = ["Spline", "FitReport", "ValidityReport", "AdaptReport"]

# size_t as a numpy dtype, for the buffers of function indices.
_SIZE_T = np.dtype(f"u{ctypes.sizeof(ctypes.c_size_t)}")


class _StructReport:
    """A report read field by field from the C struct of the same field names."""

    @classmethod
    def _from_c(cls, report):
        values = {}
        for field in dataclasses.fields(cls):
            value = getattr(report, field.name)
            values[field.name] = bool(value) if field.type in (bool, "bool") else value
        return cls(**values)

    def as_dict(self):
        """The report as a dict."""
        return dataclasses.asdict(self)


@dataclasses.dataclass(frozen=True)
class FitReport(_StructReport):
    """What a fit (:meth:`Spline.fit`, :meth:`Spline.refine`) did (``igaparam_fit_report``).

    Attributes:
        basis_count: basis functions (= control points) of the spline space.
        element_count: elements (leaves of the hierarchical mesh).
        residual: largest coordinate difference between the spline and the data at the fit
            points (for a refinement: between the refined and the previous map).
        least_squares: True when a least-squares fit replaced a singular or badly conditioned
            interpolation at the Greville points.
        quasi_interpolation: True when the control points come from the local
            quasi-interpolant (chosen when its map is certified valid and the interpolation's
            is not, or less invalid; and on every refinement).
        untangled: control points moved to untangle a fitted map that was not certified
            valid (inner ones first, boundary ones only when that was not enough); 0 when the
            fitted map was kept.
        boundary_offset: largest move of a boundary control point by that untangling,
            relative to the bounding box; 0 when the boundary was kept.
        seconds: wall-clock seconds of the call.
        smoothed: inner control points moved by the smoothing stage (kept only when the map
            stays certified and its smallest sampled mean ratio rises); 0 when the map was kept.
        boundary_distance: largest distance from the spline's boundary to the domain's
            boundary, relative to the bounding box (each axis scaled to 1), sampled on every
            boundary facet of the elements (an upper bound at the samples); 0 for a
            refinement.
    """

    basis_count: int
    element_count: int
    residual: float
    least_squares: bool
    quasi_interpolation: bool
    untangled: int
    boundary_offset: float
    seconds: float
    smoothed: int
    boundary_distance: float



@dataclasses.dataclass(frozen=True)
class AdaptReport(_StructReport):
    """What :meth:`Spline.fit_adaptive` did (``igaparam_adapt_report``).

    Attributes:
        rounds: refinement rounds done (0 when the first fit met the target).
        reached: True when the map returned meets the target (every element certified valid
            with a smallest sampled mean ratio of at least ``target_quality``).
        refined_cells: T-mesh cells refined over all rounds.
        elements: elements of the map returned (= cells of the domain's final T-mesh).
        basis: basis functions of the map returned.
        certified_positive: True when every element of the map returned is certified valid.
        min_quality: smallest sampled mean ratio of the map returned.
        mean_quality: mean sampled mean ratio of the map returned.
        seconds: wall-clock seconds of the call.
        untangled: control points moved to untangle the fit of the map returned (as
            :attr:`FitReport.untangled`); 0 when that fit was kept.
        boundary_offset: largest move of a boundary control point by that untangling,
            relative to the bounding box; 0 when the boundary was kept.
        boundary_distance: largest distance from the boundary of the map returned to the
            domain's boundary, relative to the bounding box (as
            :attr:`FitReport.boundary_distance`).
    """

    rounds: int
    reached: bool
    refined_cells: int
    elements: int
    basis: int
    certified_positive: bool
    min_quality: float
    mean_quality: float
    seconds: float
    untangled: int
    boundary_offset: float
    boundary_distance: float



@dataclasses.dataclass(frozen=True)
class QualityBound:
    """What :meth:`Spline.quality_bound` found (``igaparam_quality_bound_report``): the true
    smallest mean ratio of the map lies in ``[lower_bound, sampled_min]``."""

    #: Certified lower bound of the mean ratio over the map (0 where det J > 0 is not proven).
    lower_bound: float
    #: Smallest mean ratio at the samples: an upper bound of the true minimum.
    sampled_min: float
    #: The element of the smallest bound.
    element: int


@dataclasses.dataclass(frozen=True)
class ValidityReport:
    """Certified validity and quality of a spline map (:meth:`Spline.check_validity`,
    ``igaparam_validity_report`` and the per-element arrays).

    Attributes:
        certified_positive: True when ``det J_S > 0`` is proven on every element (Bernstein
            coefficients of the determinant, with subdivision).
        uncertified: elements where positivity is not proven.
        det_lower_bound: smallest lower bound of ``det J_S`` over the elements (Jacobian with
            respect to the parametric coordinates).
        min_quality: smallest mean ratio ``q_S = d·det(J)^(2/d)/‖J‖²`` at the samples (0 where
            det <= 0).
        mean_quality: mean of the element means of ``q_S`` at the samples.
        histogram: samples per quality bin ``[i/10, (i+1)/10)`` (the last bin includes 1), a
            tuple of 10 ints.
        element_bounds: lower bound of ``det J_S`` on every element, float64 array of shape (m,).
        element_quality: smallest sampled mean ratio on every element, float64 array of shape
            (m,).
    """

    certified_positive: bool
    uncertified: int
    det_lower_bound: float
    min_quality: float
    mean_quality: float
    histogram: Tuple[int, ...]
    element_bounds: np.ndarray = dataclasses.field(repr=False, compare=False)
    element_quality: np.ndarray = dataclasses.field(repr=False, compare=False)

    def as_dict(self):
        """The report as a dict (the arrays included)."""
        return {field.name: getattr(self, field.name) for field in dataclasses.fields(self)}


def _uint32(value, name):
    """``value`` as an int that fits a uint32 (the library checks its range)."""
    return c_int_value(value, name, ctypes.c_uint32, 0)


def _index(value, name):
    return c_int_value(value, name, ctypes.c_size_t, 0)


class Spline(_Refit, _Handle):
    """A cubic THB-spline map ``S: [0,1]^d → Ω``, d = 2 or 3 (an ``igaparam_spline`` handle).

    Parametric points are rows of d floats in [0,1]^d, physical points rows of d floats. Create
    it with :meth:`fit` (from a built :class:`Domain`) or :meth:`read_gismo`; :meth:`clone`
    gives an independent copy. Release the handle with :meth:`close` or a ``with`` block (it is
    also released when the object is collected); a closed spline raises ``ValueError``.

    Attributes:
        fit_report: the :class:`FitReport` of the fit that gave the current control points
            (:meth:`fit`, then the last :meth:`refine`); None for a spline read from a file.

    Example::

        with igaparam.Domain.from_file("tests/data/boundary/male_bdry.xml") as domain:
            domain.build()
            spline = igaparam.Spline.fit(domain)    # spline.fit_report.residual ~ 1e-15
        with spline:
            xy, jac = spline.evaluate([[0.5, 0.5]], jacobians=True)   # (1, 2), (1, 2, 2)
            assert spline.check_validity().certified_positive
    """

    _kind = "spline"
    _free = "igaparam_spline_free"

    _fit_report_type = FitReport

    def __init__(self, handle, fit_report=None):
        """Takes ownership of an ``igaparam_spline *`` (use :meth:`fit` or :meth:`read_gismo`)."""
        self._lib = _capi.library()
        self._handle = handle
        self.fit_report: Optional[FitReport] = fit_report
        #: What :meth:`fit_adaptive` did, for a spline it made.
        self.adapt_report: Optional[AdaptReport] = None

    @classmethod
    def fit(
        cls,
        domain: Domain,
        choice: Union[FitChoice, int] = FitChoice.BEST,
        untangle_rounds: Optional[int] = None,
        untangle_sweeps: Optional[int] = None,
        boundary_offset: Optional[float] = None,
        smoothing_sweeps: Optional[int] = None,
        smoothing_power: Optional[float] = None,
        max_depth: Optional[int] = None,
        samples: Optional[int] = None,
        threads: int = 0,
        progress: Optional[Callable[[Stage, int, int], Optional[bool]]] = None,
    ) -> "Spline":
        """Fits the cubic THB spline space of a built domain's T-mesh to its optimized map,
        certifies it, untangles it where it is not certified and smooths it
        (``igaparam_spline_fit_domain_with``; every option left out keeps its default). The
        spline does not refer to the domain afterwards.

        Args:
            domain: a :class:`Domain` on which :meth:`Domain.build` succeeded.
            choice: :class:`FitChoice` ``BEST`` (interpolation at the Greville points, least
                squares when singular, and the quasi-interpolant when that map is not certified;
                the better kept), ``INTERPOLATION`` or ``QUASI_INTERPOLATION``.
            untangle_rounds: untangling rounds per stage (default 4; 0: no untangling).
            untangle_sweeps: sweeps per untangling round (default 20).
            boundary_offset: largest move of a boundary control point by the untangling,
                relative to the bounding box (default: the domain's own; 0 keeps the boundary).
            smoothing_sweeps: smoothing sweeps of a certified map (default 8; 0: none).
            smoothing_power: exponent p of the smoothing's objective, the sum of the
                distortions to the power p (default 0: 4 for planar maps, 1 for solids; else
                in [1, 16]; 1: the mean distortion, larger ones lift the smallest quality most).
            max_depth, samples: the certification's subdivision depth (default 5, at most 12)
                and samples per direction and element (default 5, 2 to 64).
            threads: worker threads; 0 uses one per core (the result does not depend on it).
            progress: None, or a callable ``progress(stage, done, total)`` with ``Stage.FIT``,
                ``Stage.UNTANGLING`` and ``Stage.SMOOTHING``; return None or True to go on,
                False to cancel (``Status.CANCELLED``); any other answer (an int included)
                raises TypeError. An exception raised by it cancels and is re-raised.

        Returns:
            Spline, with the fit's :class:`FitReport` in ``fit_report``.

        Raises:
            IgaparamError: ``Status.INVALID_ARGUMENT`` if the domain is not built or an option
                is out of range; ``Status.CANCELLED``.
            ValueError: the domain is closed, a negative count.
        """
        lib = _capi.library()
        options = lib.igaparam_fit_options_default()
        options.choice = int(FitChoice(choice))
        _set_counts(
            options,
            untangle_rounds=untangle_rounds,
            untangle_sweeps=untangle_sweeps,
            smoothing_sweeps=smoothing_sweeps,
            threads=threads,
        )
        _set_counts(options.validity, max_depth=max_depth, samples=samples)
        if boundary_offset is not None:
            if not float(boundary_offset) >= 0.0:
                raise ValueError("boundary_offset must be a number >= 0")
            options.boundary_offset = float(boundary_offset)
        if smoothing_power is not None:
            options.smoothing_power = float(smoothing_power)
        raised, _callback = _attach_progress(options, progress)
        handle = ctypes.c_void_p()
        report = _capi.FitReport()
        status = lib.igaparam_spline_fit_domain_with(
            domain._h(), ctypes.byref(options), ctypes.byref(handle), ctypes.byref(report)
        )
        if raised:
            raise raised[0]
        _check(status)
        return cls(handle, FitReport._from_c(report))

    @classmethod
    def fit_adaptive(
        cls,
        domain: Domain,
        target_quality: Optional[float] = None,
        max_rounds: Optional[int] = None,
        max_level: Optional[int] = None,
        max_sweeps: Optional[int] = None,
        threads: int = 0,
        progress: Optional[Callable[[Stage, int, int], Optional[bool]]] = None,
    ) -> "Spline":
        """The method's adaptive loop: fits the spline map of a built domain, refines the T-mesh
        cells whose element is not certified valid or has a sampled mean ratio under
        ``target_quality``, optimizes the T-mesh again and refits, for at most ``max_rounds``
        rounds. The domain keeps its refined T-mesh; on an error or a cancellation it is
        unchanged.

        Args:
            domain: a :class:`Domain` on which :meth:`Domain.build` succeeded.
            target_quality: smallest sampled mean ratio wanted, in [0, 1) (default 0.1).
            max_rounds: largest number of refinement rounds (default 4).
            max_level: cells at this level are not refined further, at most 16 (default 10).
            max_sweeps: optimization sweeps after each refinement (default 200).
            threads: worker threads, capped to the cores; 0 uses one per core (the result does not
                depend on it).
            progress: None, or a callable ``progress(stage, done, total)`` called before each
                refinement; return None or True to go on, False to cancel
                (``Status.CANCELLED``); any other answer (an int included) raises TypeError. An
                exception raised by it cancels the loop and is re-raised.

        Returns:
            Spline, with the loop's :class:`AdaptReport` in ``adapt_report``.

        Raises:
            ValueError: a negative count.
            IgaparamError: the domain is not built, options rejected by the library, a failed
                or cancelled loop.
        """
        lib = _capi.library()
        options = lib.igaparam_adapt_options_default()
        if target_quality is not None:
            options.target_quality = float(target_quality)
        _set_counts(options, max_rounds=max_rounds, max_level=max_level, max_sweeps=max_sweeps, threads=threads)
        raised, _callback = _attach_progress(options, progress)
        handle = ctypes.c_void_p()
        report = _capi.AdaptReport()
        status = lib.igaparam_domain_fit_adaptive(
            domain._h(), ctypes.byref(options), ctypes.byref(handle), ctypes.byref(report)
        )
        if raised:
            raise raised[0]
        _check(status)
        spline = cls(handle)
        spline.adapt_report = AdaptReport._from_c(report)
        return spline

    @classmethod
    def read_gismo(cls, path: Union[str, "os.PathLike[str]"]) -> "Spline":
        """Reads a THB-spline map written by :meth:`write_gismo` (G+Smo XML, a ``THBSpline2`` or
        ``THBSpline3`` geometry).

        Raises:
            IgaparamError: ``Status.IO`` if the file cannot be read or holds no such map.
        """
        handle = ctypes.c_void_p()
        _check(_capi.library().igaparam_spline_read_gismo(os.fsencode(path), ctypes.byref(handle)))
        return cls(handle)

    def clone(self) -> "Spline":
        """A new, independent copy (to refine one while keeping the other); it has the same
        ``fit_report``."""
        handle = ctypes.c_void_p()
        _check(self._lib.igaparam_spline_clone(self._h(), ctypes.byref(handle)))
        return type(self)(handle, self.fit_report)

    def __repr__(self):
        if self._handle is None:
            return "<igaparam.Spline (closed)>"
        return (
            f"<igaparam.Spline d={self.dimension}, {self.basis_count} functions, "
            f"{self.element_count} elements>"
        )

    # Sizes and read-back.

    def _count(self, function):
        out = ctypes.c_size_t()
        _check(function(self._h(), ctypes.byref(out)))
        return out.value

    @property
    def dimension(self) -> int:
        """The dimension d (2 or 3) of the parametric and physical spaces."""
        return self._count(self._lib.igaparam_spline_dimension)

    @property
    def basis_count(self) -> int:
        """Basis functions (= control points)."""
        return self._count(self._lib.igaparam_spline_basis_count)

    @property
    def element_count(self) -> int:
        """Elements (boxes on which every basis function is a polynomial)."""
        return self._count(self._lib.igaparam_spline_element_count)

    def _points(self, function):
        out = np.empty((self.basis_count, self.dimension), dtype=np.float64)
        _check(function(self._h(), _ptr(out, ctypes.c_double), out.size))
        return out

    @property
    def control_points(self) -> npt.NDArray[np.float64]:
        """Control points, a new float64 array of shape (n, d), n = :attr:`basis_count`."""
        return self._points(self._lib.igaparam_spline_copy_control_points)

    @property
    def greville_points(self) -> npt.NDArray[np.float64]:
        """Greville points of the basis functions, a new float64 array of shape (n, d) in
        [0,1]^d. A function whose Greville point is inside (0,1)^d vanishes on the boundary of
        the parametric domain; those with a point on it (some coordinate 0 or 1) are the
        degrees of freedom a Dirichlet condition sets."""
        return self._points(self._lib.igaparam_spline_copy_greville_points)

    @property
    def element_levels(self) -> npt.NDArray[np.uint8]:
        """Refinement level of every element (side 2^-level), a new uint8 array of shape (m,),
        m = :attr:`element_count`."""
        out = np.empty(self.element_count, dtype=np.uint8)
        _check(self._lib.igaparam_spline_copy_elements(self._h(), _ptr(out, ctypes.c_uint8), None, out.size))
        return out

    @property
    def element_bounds(self) -> npt.NDArray[np.float64]:
        """Parametric box of every element, a new float64 array of shape (m, 2d): the lower
        corner then the upper corner (u0 v0 u1 v1 in 2D)."""
        m, d = self.element_count, self.dimension
        out = np.empty((m, 2 * d), dtype=np.float64)
        _check(self._lib.igaparam_spline_copy_elements(self._h(), None, _ptr(out, ctypes.c_double), m))
        return out

    def extraction(self, element: int) -> Tuple[npt.NDArray[np.uintp], npt.NDArray[np.float64]]:
        """The Bézier extraction of element ``element``.

        Returns:
            (functions, operator): ``functions``, int64 array of shape (k,), the increasing
            global indices of the k basis functions non-zero on the element; ``operator``,
            float64 array of shape (k, 4^d), the matrix C with ``N_functions[i] = Σ_j C[i, j] B_j``
            on the element, ``B_j`` the tensor Bernstein polynomials of degree 3 on the
            element's box mapped to [0,1]^d, ``j = j0 + 4 j1 (+ 16 j2)``.

        Raises:
            IgaparamError: ``Status.INVALID_ARGUMENT`` if ``element >= element_count``.
            ValueError: a negative ``element``.
        """
        element = _index(element, "element")
        h = self._h()
        k = ctypes.c_size_t()
        _check(self._lib.igaparam_spline_element_function_count(h, element, ctypes.byref(k)))
        k = k.value
        functions = np.empty(k, dtype=_SIZE_T)
        matrix = np.empty((k, 4 ** self.dimension), dtype=np.float64)
        _check(
            self._lib.igaparam_spline_copy_element_extraction(
                h, element, _ptr(functions, ctypes.c_size_t), k, _ptr(matrix, ctypes.c_double), matrix.size
            )
        )
        return functions.astype(np.int64), matrix

    # Evaluation.

    def _as_points(self, values, name):
        """``values`` as a C-contiguous float64 array of shape (n, d)."""
        d = self.dimension
        array = np.asarray(values)
        if array.dtype.kind not in "fiu":
            raise ValueError(f"{name} must be numeric, not {array.dtype}")
        if array.ndim != 2 or array.shape[1] != d:
            raise ValueError(f"{name} must have shape (n, {d}), not {array.shape}")
        return np.ascontiguousarray(array, dtype=np.float64)

    def evaluate(self, params: npt.ArrayLike, jacobians: bool = False):
        """The map at parametric points.

        Args:
            params: (n, d) points in [0,1]^d.
            jacobians: also return the Jacobian matrices.

        Returns:
            points, float64 (n, d): ``S(params)``; with ``jacobians=True``, ``(points, jac)``
            with ``jac`` float64 (n, d, d), ``jac[p, i, j] = ∂S_i/∂u_j``.

        Raises:
            IgaparamError: ``Status.INVALID_ARGUMENT`` for a point outside [0,1]^d,
                ``Status.NOT_FINITE`` for NaN or infinity.
            ValueError: not an array of shape (n, d).
        """
        params = self._as_points(params, "params")
        n, d = params.shape
        points = np.empty((n, d), dtype=np.float64)
        jac = np.empty((n, d, d), dtype=np.float64) if jacobians else None
        _check(
            self._lib.igaparam_spline_evaluate(
                self._h(),
                n,
                _ptr(params, ctypes.c_double),
                _ptr(points, ctypes.c_double),
                _ptr(jac, ctypes.c_double) if jacobians else None,
            )
        )
        return (points, jac) if jacobians else points

    def mean_ratio(self, params: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The mean ratio of the Jacobian, ``q_S = d·det(J)^(2/d)/‖J‖²_F`` in [0, 1] (1 for a
        conformal map, 0 where det J <= 0), at (n, d) parametric points: float64 array (n,).

        Raises:
            IgaparamError: as :meth:`evaluate`.
        """
        params = self._as_points(params, "params")
        quality = np.empty(params.shape[0], dtype=np.float64)
        _check(
            self._lib.igaparam_spline_mean_ratio(
                self._h(), params.shape[0], _ptr(params, ctypes.c_double), _ptr(quality, ctypes.c_double)
            )
        )
        return quality

    def invert(self, points: npt.ArrayLike, samples: int = 4) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.bool_]]:
        """The parametric points whose images are the physical ``points`` (n, d), by Newton's
        method started from the nearest of ``samples^d`` samples per element (2 to 32).

        Returns:
            (params, found): ``params`` float64 (n, d), NaN where not found; ``found`` bool
            (n,), False where the point is outside the domain (or Newton's method did not
            converge).

        Raises:
            IgaparamError: ``Status.NOT_FINITE`` for NaN or infinite points,
                ``Status.INVALID_ARGUMENT`` for ``samples`` out of range.
            ValueError: not an array of shape (n, d).
        """
        points = self._as_points(points, "points")
        samples = _uint32(samples, "samples")
        n, d = points.shape
        params = np.empty((n, d), dtype=np.float64)
        found = np.empty(n, dtype=np.int32)
        _check(
            self._lib.igaparam_spline_invert(
                self._h(),
                n,
                _ptr(points, ctypes.c_double),
                samples,
                _ptr(params, ctypes.c_double),
                _ptr(found, ctypes.c_int32),
            )
        )
        return params, found != 0

    def basis_at(self, param: npt.ArrayLike):
        """The basis functions non-zero on the element holding the parametric point ``param``
        (d floats in [0,1]^d; on an element boundary, the element on the upper side).

        Returns:
            (functions, values, gradients): int64 (k,) global indices, float64 (k,) values
            (summing to 1) and float64 (k, d) gradients with respect to the parametric
            coordinates; ``values @ control_points[functions]`` is ``S(param)``.

        Raises:
            IgaparamError: as :meth:`evaluate`.
            ValueError: not d numbers.
        """
        d = self.dimension
        array = np.asarray(param)
        if array.dtype.kind not in "fiu" or array.shape != (d,):
            raise ValueError(f"param must be {d} numbers, not an array of shape {array.shape} ({array.dtype})")
        param = np.ascontiguousarray(array, dtype=np.float64)
        h, p = self._h(), _ptr(param, ctypes.c_double)
        k = ctypes.c_size_t()
        _check(self._lib.igaparam_spline_basis_count_at(h, p, ctypes.byref(k)))
        size = k.value
        functions = np.empty(size, dtype=_SIZE_T)
        values = np.empty(size, dtype=np.float64)
        gradients = np.empty((size, d), dtype=np.float64)
        _check(
            self._lib.igaparam_spline_basis_at(
                h,
                p,
                ctypes.byref(k),
                _ptr(functions, ctypes.c_size_t),
                _ptr(values, ctypes.c_double),
                _ptr(gradients, ctypes.c_double),
                size,
            )
        )
        k = k.value
        return functions[:k].astype(np.int64), values[:k].copy(), gradients[:k].copy()

    # Refinement and validity.

    def refine(self, elements: Optional[npt.ArrayLike] = None) -> "FitReport":
        """h-refines the spline space, the map staying the same: the listed elements are split
        into 2^d (and more where the mesh's 2:1 balance requires it); ``None`` refines every
        element once. Element and function indices change. On failure the spline is unchanged.

        Args:
            elements: None, or a non-empty sequence of element indices (k,).

        Returns:
            FitReport of the refinement (``residual``: difference with the previous map at the
            fit points, round-off); it also becomes ``fit_report``.

        Raises:
            IgaparamError: ``Status.INVALID_ARGUMENT`` for an index >= ``element_count``.
            ValueError: an empty list, negative or non-integer indices.
        """
        h = self._h()
        report = _capi.FitReport()
        if elements is None:
            _check(self._lib.igaparam_spline_refine(h, 0, None, ctypes.byref(report)))
        else:
            array = np.asarray(elements)
            if array.size == 0:
                raise ValueError("elements is empty (pass None to refine every element)")
            if array.ndim != 1 or array.dtype.kind not in "iu":
                raise ValueError(f"elements must be a 1-D integer array, not {array.dtype} of shape {array.shape}")
            if array.dtype.kind == "i" and array.min() < 0:
                raise ValueError("elements must be >= 0")
            array = np.ascontiguousarray(array, dtype=_SIZE_T)
            _check(
                self._lib.igaparam_spline_refine(h, array.size, _ptr(array, ctypes.c_size_t), ctypes.byref(report))
            )
        self.fit_report = FitReport._from_c(report)
        return self.fit_report

    def check_validity(self, max_depth: int = 5, samples: int = 5) -> "ValidityReport":
        """Certifies the sign of the Jacobian determinant on every element (lower bounds from
        the Bernstein coefficients of det J_S, subdividing up to ``max_depth`` times, at most
        12, when inconclusive) and samples the mean ratio at ``samples^d`` points per element
        (``samples`` from 2 to 64).

        Returns:
            ValidityReport, with per-element arrays ``element_bounds`` and ``element_quality``
            of shape (m,).

        Raises:
            IgaparamError: ``Status.INVALID_ARGUMENT`` for options out of range.
        """
        options = self._lib.igaparam_validity_options_default()
        options.max_depth = _uint32(max_depth, "max_depth")
        options.samples = _uint32(samples, "samples")
        m = self.element_count
        bounds = np.empty(m, dtype=np.float64)
        quality = np.empty(m, dtype=np.float64)
        report = _capi.ValidityReport()
        _check(
            self._lib.igaparam_spline_check_validity(
                self._h(),
                ctypes.byref(options),
                ctypes.byref(report),
                _ptr(bounds, ctypes.c_double),
                _ptr(quality, ctypes.c_double),
                m,
            )
        )
        return ValidityReport(
            certified_positive=bool(report.certified_positive),
            uncertified=report.uncertified,
            det_lower_bound=report.det_lower_bound,
            min_quality=report.min_quality,
            mean_quality=report.mean_quality,
            histogram=tuple(int(count) for count in report.histogram),
            element_bounds=bounds,
            element_quality=quality,
        )

    def quality_bound(
        self, max_depth: Optional[int] = None, samples: Optional[int] = None, gap: Optional[float] = None
    ) -> "QualityBound":
        """A certified lower bound of the map's mean ratio, with the sampled minimum it is
        refined towards (``igaparam_spline_quality_bound``): on each element the Bernstein
        coefficients of det J and ‖J‖² bound the mean ratio from below; pieces are subdivided
        (up to ``max_depth`` times, default 6, at most 8; 3 for a solid) while their bound is more
        than ``gap`` (default 0.05) below the minimum at ``samples^d`` points per element
        (default 5).

        Raises:
            IgaparamError: ``Status.INVALID_ARGUMENT`` for options out of range.
        """
        options = self._lib.igaparam_quality_bound_options_default()
        if max_depth is not None:
            options.max_depth = _uint32(max_depth, "max_depth")
        if samples is not None:
            options.samples = _uint32(samples, "samples")
        if gap is not None:
            options.gap = float(gap)
        report = _capi.QualityBoundReport()
        _check(self._lib.igaparam_spline_quality_bound(self._h(), ctypes.byref(options), ctypes.byref(report)))
        return QualityBound(report.lower_bound, report.sampled_min, report.element)

    # Output.

    def write_vtu(self, path: Union[str, "os.PathLike[str]"], samples: int = 4) -> None:
        """Writes the map sampled on ``samples^d`` sub-cells per element (1 to 32) as a VTK
        .vtu file: quads (2D) or hexahedra (3D), point data ``quality`` (q_S) and ``det``
        (det J_S), cell data ``level`` and ``element``.

        Raises:
            IgaparamError: ``Status.IO`` when the file cannot be written,
                ``Status.INVALID_ARGUMENT`` for ``samples`` out of range.
        """
        samples = _uint32(samples, "samples")
        _check(self._lib.igaparam_spline_write_vtu(self._h(), os.fsencode(path), samples))

    def write_gismo(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the map as G+Smo XML (a ``THBSpline2``/``THBSpline3`` geometry), readable by
        G+Smo's ``gsReadFile`` and :meth:`read_gismo`.

        Raises:
            IgaparamError: ``Status.IO`` when the file cannot be written.
        """
        _check(self._lib.igaparam_spline_write_gismo(self._h(), os.fsencode(path)))
