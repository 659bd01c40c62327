"""The :class:`Domain` class: a planar domain bounded by four curves and its adapted, optimized
T-mesh parameterization."""

import ctypes
import dataclasses
import os

import numpy as np

from . import _capi
from ._handle import _Handle
from ._mesh import _check, _progress_callback, _ptr

__all__ = ["Domain", "DomainReport"]


@dataclasses.dataclass(frozen=True)
class DomainReport:
    """What :meth:`Domain.build` did (``igaparam_domain_report``). Quality is the inverse mean
    distortion of a cell against its parametric (square) cell: 1 is a square, 0 an inverted
    cell."""

    cells: int
    vertices: int
    max_level: int
    boundary_error: float
    #: Largest distance of a boundary vertex from its point on the boundary, in coordinates
    #: that map the bounding box onto the unit box: at most the ``boundary_offset`` option of
    #: :meth:`Domain.build`, 0 when no seam relief was needed.
    boundary_offset: float
    invalid_after_placement: int
    invalid_cells: int
    min_quality: float
    mean_quality: float
    sweeps: int
    seconds: float

    @classmethod
    def _from_c(cls, report):
        return cls(**{field.name: getattr(report, field.name) for field in dataclasses.fields(cls)})

    def as_dict(self):
        """The report as a dict."""
        return dataclasses.asdict(self)


def _as_polyline(values, index):
    array = np.asarray(values)
    if array.dtype.kind not in "fiu":
        raise ValueError(f"polyline {index} must be numeric, not {array.dtype}")
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(f"polyline {index} must have shape (k, 2), not {array.shape}")
    return np.ascontiguousarray(array, dtype=np.float64)


class Domain(_Handle):
    """A planar domain bounded by four curves (an ``igaparam_domain`` handle) and, once
    :meth:`build` succeeded, its T-mesh: a quadtree of the parameter square [0,1]² adapted to
    the boundary, with every vertex placed in the domain and optimized so that no cell folds.

    Create it with :meth:`from_file` or :meth:`from_polylines`. Release the handle with
    :meth:`close` or a ``with`` block (it is also released when the object is collected).

    Example::

        with igaparam.Domain.from_file("tests/data/boundary/puzzle3_bdry.xml") as domain:
            report = domain.build()                 # report.invalid_cells == 0
            xy = domain.physical_vertices           # (n, 2)
            quality = domain.cell_quality           # (m,)
    """

    _kind = "domain"
    _free = "igaparam_domain_free"

    def __init__(self, handle):
        """Takes ownership of an ``igaparam_domain *`` (use the ``from_*`` constructors)."""
        self._lib = _capi.library()
        self._handle = handle

    @classmethod
    def from_file(cls, path):
        """A domain from a boundary file, chosen by its extension: ``.xml``, a G+Smo XML B-rep of
        four B-spline curves; ``.txt``, a coastline (points with four marked corners).

        Raises:
            IgaparamError: ``Status.IO`` when the file cannot be read or parsed,
                ``Status.INVALID_ARGUMENT`` for another extension or a boundary that is not a
                closed loop of four curves with convex corners.
        """
        handle = ctypes.c_void_p()
        _check(_capi.library().igaparam_domain_new_from_file(os.fsencode(path), ctypes.byref(handle)))
        return cls(handle)

    @classmethod
    def from_polylines(cls, polylines):
        """A domain bounded by four polylines, each an array of shape (k, 2) with k >= 2, in any
        order and direction: they are chained end to end into a counter-clockwise loop, the
        first one becoming the side u = 0.

        Raises:
            ValueError: not four arrays of shape (k, 2).
            IgaparamError: rejected by the library (ends that do not meet, NaN, ...).
        """
        polylines = list(polylines)
        if len(polylines) != 4:
            raise ValueError(f"a domain needs 4 polylines, not {len(polylines)}")
        arrays = [_as_polyline(p, i) for i, p in enumerate(polylines)]
        counts = (ctypes.c_size_t * 4)(*[a.shape[0] for a in arrays])
        points = (ctypes.POINTER(ctypes.c_double) * 4)(*[_ptr(a, ctypes.c_double) for a in arrays])
        handle = ctypes.c_void_p()
        _check(_capi.library().igaparam_domain_new_from_polylines(counts, points, ctypes.byref(handle)))
        return cls(handle)

    # Building.

    def build(
        self,
        tolerance=None,
        min_level=None,
        max_level=None,
        max_sweeps=None,
        threads=0,
        progress=None,
        repair_rounds=None,
        boundary_offset=None,
    ):
        """Adapts a T-mesh to the boundary, places its vertices and optimizes them. Building
        again replaces the previous T-mesh; on any error the domain keeps its previous state.

        Args:
            tolerance: boundary tolerance, relative to the squared bounding-box diagonal
                (library default 1e-5).
            min_level: level of the initial uniform refinement (default 2).
            max_level: deepest level of the adaptation, at most 16 (default 9).
            max_sweeps: largest number of optimization sweeps (default 200).
            threads: worker threads; 0 uses one per core (the result does not depend on it).
            progress: None, or a callable ``progress(stage, done, total)`` called after
                optimization sweeps; return False to cancel (``Status.CANCELLED``). An exception
                raised by it cancels the build and is re-raised.
            repair_rounds: rounds of repair after the optimization (default 6): cells left
                invalid are refined (past ``max_level``, up to level 16) and the mesh optimized
                again; 0 disables it.
            boundary_offset: seam relief cap, finite and >= 0 (default 1e-2): the largest
                distance, in coordinates that map the bounding box onto the unit box, by which a
                boundary vertex may leave the boundary to open a cell that stays folded with
                every boundary vertex on it; 0 keeps every boundary vertex on the boundary.

        Returns:
            DomainReport; ``invalid_cells == 0`` for a usable parameterization.

        Raises:
            ValueError: a negative level, sweep, thread or round count.
            IgaparamError: options rejected by the library (``Status.NOT_FINITE`` for a NaN or
                infinite ``tolerance`` or ``boundary_offset``, ``Status.INVALID_ARGUMENT`` for a
                negative ``boundary_offset``, ...), a build that failed or was cancelled.
        """
        options = self._lib.igaparam_domain_options_default()
        if tolerance is not None:
            options.tolerance = float(tolerance)
        if boundary_offset is not None:
            options.boundary_offset = float(boundary_offset)
        for name, value in (("min_level", min_level), ("max_level", max_level), ("max_sweeps", max_sweeps),
                            ("threads", threads), ("repair_rounds", repair_rounds)):
            if value is not None:
                if int(value) < 0:
                    raise ValueError(f"{name} must be >= 0")
                setattr(options, name, int(value))
        raised = []
        callback = _progress_callback(progress, raised)  # kept alive during the call
        if callback is not None:
            options.progress = callback
        report = _capi.DomainReport()
        status = self._lib.igaparam_domain_build(self._h(), ctypes.byref(options), ctypes.byref(report))
        if raised:
            raise raised[0]
        _check(status)
        return DomainReport._from_c(report)

    @property
    def is_built(self):
        """True once :meth:`build` succeeded."""
        out = ctypes.c_int()
        _check(self._lib.igaparam_domain_is_built(self._h(), ctypes.byref(out)))
        return bool(out.value)

    # Read-back of the T-mesh (IgaparamError with Status.INVALID_ARGUMENT before a build).

    def _count(self, function):
        out = ctypes.c_size_t()
        _check(function(self._h(), ctypes.byref(out)))
        return out.value

    @property
    def vertex_count(self):
        """Vertices of the T-mesh, hanging ones included."""
        return self._count(self._lib.igaparam_domain_vertex_count)

    @property
    def cell_count(self):
        """Cells of the T-mesh."""
        return self._count(self._lib.igaparam_domain_cell_count)

    def _vertices(self, physical):
        out = np.empty((self.vertex_count, 2), dtype=np.float64)
        pointers = (None, _ptr(out, ctypes.c_double)) if physical else (_ptr(out, ctypes.c_double), None)
        _check(self._lib.igaparam_domain_copy_vertices(self._h(), *pointers, out.size))
        return out

    @property
    def parametric_vertices(self):
        """(u, v) of every vertex in [0,1]², a new float64 array of shape (n, 2)."""
        return self._vertices(physical=False)

    @property
    def physical_vertices(self):
        """(x, y) of every vertex in the domain, a new float64 array of shape (n, 2)."""
        return self._vertices(physical=True)

    @property
    def cell_quality(self):
        """Quality of every cell, a new float64 array of shape (m,), in (0, 1]; 0 for a cell
        with det J <= 0 somewhere."""
        out = np.empty(self.cell_count, dtype=np.float64)
        _check(self._lib.igaparam_domain_copy_cell_quality(self._h(), _ptr(out, ctypes.c_double), out.size))
        return out

    @property
    def cell_levels(self):
        """Refinement level of every cell, a new uint8 array of shape (m,)."""
        out = np.empty(self.cell_count, dtype=np.uint8)
        _check(self._lib.igaparam_domain_copy_cells(self._h(), _ptr(out, ctypes.c_uint8), None, out.size))
        return out

    @property
    def cell_bounds(self):
        """Parametric box of every cell, a new float64 array of shape (m, 4): u0, v0, u1, v1
        (lower then upper corner)."""
        m = self.cell_count
        out = np.empty((m, 4), dtype=np.float64)
        _check(self._lib.igaparam_domain_copy_cells(self._h(), None, _ptr(out, ctypes.c_double), m))
        return out

    def write_vtu(self, path):
        """Writes the T-mesh as a VTK .vtu file (polygons through corners and hanging vertices,
        cell arrays ``quality`` and ``level``).

        Raises:
            IgaparamError: ``Status.IO`` when the file cannot be written.
        """
        _check(self._lib.igaparam_domain_write_vtu(self._h(), os.fsencode(path)))
