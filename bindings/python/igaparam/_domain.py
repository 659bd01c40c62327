"""The :class:`Domain` class: a planar domain bounded by four curves or a solid bounded by six
surfaces, and its adapted, optimized T-mesh parameterization."""

from __future__ import annotations

import ctypes
import dataclasses
import os
from typing import Callable, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _capi
from ._handle import _Handle
from ._capi import Stage
from ._boundary import Curve, Surface, curve_arrays, face_arrays, polyline_arrays, surface_arrays
from ._mesh import _attach_progress, _check, _ptr, _set_counts

__all__ = ["Domain", "DomainReport", "UpdateReport"]

# size_t as a numpy dtype, for the buffer of cell corners.
_SIZE_T = np.dtype(f"u{ctypes.sizeof(ctypes.c_size_t)}")


@dataclasses.dataclass(frozen=True)
class DomainReport:
    """What :meth:`Domain.build` did (``igaparam_domain_report``). Quality is the inverse mean
    distortion of a cell against its parametric (square or cube) cell: 1 is a square or cube, 0
    an inverted cell."""

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
    #: Whether the optimization stopped because it spent ``max_total_sweeps`` (the T-mesh is
    #: the state its sweeps reached: check ``invalid_cells``).
    sweep_budget_exhausted: bool
    #: Newton iterations of the polish (``stationarity_tolerance > 0``; 0 when it is off or a
    #: cell stays invalid).
    newton_iterations: int
    #: Scaled max-norm of the global objective's gradient after the polish: at most
    #: ``stationarity_tolerance`` when it converged (the state :meth:`Spline.tangent` and
    #: :meth:`Spline.adjoint` differentiate), ``inf`` when a cell stays invalid, 0 when off.
    gradient_norm: float
    seconds: float

    @classmethod
    def _from_c(cls, report):
        values = {field.name: getattr(report, field.name) for field in dataclasses.fields(cls)}
        values["sweep_budget_exhausted"] = bool(values["sweep_budget_exhausted"])
        return cls(**values)

    def as_dict(self) -> dict:
        """The report as a dict."""
        return dataclasses.asdict(self)


@dataclasses.dataclass(frozen=True)
class UpdateReport:
    """What :meth:`Domain.update` did (``igaparam_domain_update_report``).

    Attributes:
        domain: the T-mesh as :meth:`Domain.build` reports it (``invalid_after_placement``:
            cells the harmonic placement left invalid; ``boundary_error`` measured in the new
            boundary's own bounding box; ``sweeps`` and ``seconds`` those of the update).
        tolerance_met: True when the tree still meets the build's tolerance (a build's
            adaptation would refine no cell).
        cells_over_tolerance: boundary cells below the build's ``max_level`` whose error
            exceeds its tolerance.
        refined_cells: cells added by refinement (0 unless ``refine=True``).
        boundary_motion: largest move of a boundary vertex, in coordinates that map the
            build's bounding box onto the unit box.
        steps: steps the motion was applied in.
    """

    domain: DomainReport
    tolerance_met: bool
    cells_over_tolerance: int
    refined_cells: int
    boundary_motion: float
    steps: int

    @classmethod
    def _from_c(cls, report):
        return cls(
            domain=DomainReport._from_c(report.domain),
            tolerance_met=bool(report.tolerance_met),
            cells_over_tolerance=report.cells_over_tolerance,
            refined_cells=report.refined_cells,
            boundary_motion=report.boundary_motion,
            steps=report.steps,
        )

    def as_dict(self) -> dict:
        """The report as a dict (the T-mesh's report nested)."""
        return dataclasses.asdict(self)


def _call(function, handle, options, progress, report):
    """``function(handle, &options, &report)`` with the Python ``progress`` attached to the
    options; re-raises what ``progress`` raised, then raises on a failed status. Returns the
    report."""
    raised, _callback = _attach_progress(options, progress)
    status = function(handle, ctypes.byref(options), ctypes.byref(report))
    if raised:
        raise raised[0]
    _check(status)
    return report


def _as_scale(scale):
    """None, or ``scale`` as a C array of three doubles (the library checks the values)."""
    if scale is None:
        return None
    array = np.asarray(scale)
    if array.dtype.kind not in "fiu":
        raise ValueError(f"scale must be numeric, not {array.dtype}")
    if array.shape != (3,):
        raise ValueError(f"scale must hold 3 factors (x, y, z), not shape {array.shape}")
    return (ctypes.c_double * 3)(*array.astype(np.float64).tolist())


class Domain(_Handle):
    """A planar domain bounded by four curves or a solid bounded by six surfaces (an
    ``igaparam_domain`` handle) and, once :meth:`build` succeeded, its T-mesh: a quadtree
    (octree for a solid) of the parameter square [0,1]² (cube [0,1]³) adapted to the boundary,
    with every vertex placed in the domain and optimized so that no cell folds. Arrays of points
    have :attr:`dimension` (d = 2 or 3) columns.

    Create a planar domain with :meth:`from_file` or :meth:`from_polylines`, a solid with
    :meth:`solid_from_file` or :meth:`solid_from_triangulations`. Release the handle with
    :meth:`close` or a ``with`` block (it is also released when the object is collected).

    Example::

        with igaparam.Domain.from_file("tests/data/boundary/puzzle3_bdry.xml") as domain:
            report = domain.build()                 # report.invalid_cells == 0
            xy = domain.physical_vertices           # (n, 2)
            quality = domain.cell_quality           # (m,)

        km = [89273.3, 111200.0, 1.0]               # x, y in degrees/1000 -> km
        with igaparam.Domain.solid_from_file("tests/data/boundary/jacksboro_faces", scale=km) as block:
            report = block.build(tolerance=1e-3, max_level=3)
            xyz = block.physical_vertices           # (n, 3), in km
    """

    _kind = "domain"
    _free = "igaparam_domain_free"

    def __init__(self, handle):
        """Takes ownership of an ``igaparam_domain *`` (use the ``from_*`` constructors)."""
        self._lib = _capi.library()
        self._handle = handle

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"]) -> "Domain":
        """A planar domain from a boundary file, chosen by its extension: ``.xml``, a G+Smo XML B-rep of
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
    def from_polylines(cls, polylines: Sequence[npt.ArrayLike]) -> "Domain":
        """A planar domain bounded by four polylines, each an array of shape (k, 2) with k >= 2, in any
        order and direction: they are chained end to end into a counter-clockwise loop, the
        first one becoming the side u = 0.

        Raises:
            ValueError: not four arrays of shape (k, 2).
            IgaparamError: rejected by the library (ends that do not meet, NaN, ...).
        """
        counts, points, _arrays = polyline_arrays(polylines)
        handle = ctypes.c_void_p()
        _check(_capi.library().igaparam_domain_new_from_polylines(counts, points, ctypes.byref(handle)))
        return cls(handle)

    @classmethod
    def solid_from_file(cls, path: Union[str, "os.PathLike[str]"], scale: Optional[Sequence[float]] = None) -> "Domain":
        """A solid from a G+Smo XML B-rep of six B-spline surfaces (a ``.xml`` file) or a folder
        of six triangulated faces ``xmin.obj``, ``xmax.obj``, ..., ``zmax.obj`` (each mapped
        onto its face of the unit cube by Floater's mean-value parameterization).

        Args:
            path: the file or folder.
            scale: None, or three factors ``(fx, fy, fz)``, each finite and positive, that
                multiply the input's coordinates axis by axis before anything else (the faces'
                vertices, or the surfaces' control points: exact for B-splines and NURBS). For
                data whose axes are in different units: Floater's map measures angles in the
                coordinates given, so the T-mesh depends on them. The T-mesh and a fitted
                :class:`Spline` are in the scaled coordinates.

        Raises:
            ValueError: ``scale`` is not three numbers.
            IgaparamError: ``Status.INVALID_ARGUMENT`` for a factor that is NaN, infinite,
                zero or negative (before any file is read), or a path that is neither a folder
                nor a ``.xml`` file; ``Status.IO`` when a file cannot be read or parsed;
                ``Status.INVALID_MESH`` for faces that do not share their edges and corners.
        """
        factors = _as_scale(scale)
        handle = ctypes.c_void_p()
        lib = _capi.library()
        if factors is None:
            status = lib.igaparam_domain_new_solid_from_file(os.fsencode(path), ctypes.byref(handle))
        else:
            status = lib.igaparam_domain_new_solid_from_file_scaled(os.fsencode(path), factors, ctypes.byref(handle))
        _check(status)
        return cls(handle)

    @classmethod
    def solid_from_triangulations(cls, faces: Sequence[Tuple[npt.ArrayLike, npt.ArrayLike]]) -> "Domain":
        """A solid bounded by six triangulated faces, each mapped onto its face of the unit cube
        by Floater's mean-value parameterization.

        Args:
            faces: six pairs ``(vertices, triangles)`` in the order xmin, xmax, ymin, ymax,
                zmin, zmax (the solid's sides on the cube's faces x = 0, x = 1, y = 0, ...):
                ``vertices`` a numeric array of shape (n, 3), ``triangles`` an integer array of
                shape (m, 3) of vertex indices counting from 0. Each face is a disk; faces that
                touch share their edge vertices with identical coordinates, and the vertex
                shared by three faces is a corner of the solid. The arrays are copied.

        Raises:
            ValueError: not six pairs, or arrays of the wrong shape or type, or negative
                indices.
            IgaparamError: rejected by the library: ``Status.NOT_FINITE`` for a NaN or infinite
                coordinate, ``Status.INVALID_MESH`` for a triangle with an index out of range or
                a repeated vertex, and for faces that do not match on their edges or corners.
        """
        c_arrays, _arrays = face_arrays(faces)
        handle = ctypes.c_void_p()
        _check(_capi.library().igaparam_domain_new_solid_from_triangulations(*c_arrays, ctypes.byref(handle)))
        return cls(handle)

    @classmethod
    def from_curves(cls, curves: Sequence[Union[Curve, tuple]]) -> "Domain":
        """A planar domain bounded by four B-spline or NURBS curves given by their arrays, each a
        :class:`Curve` or a tuple ``(degree, knots, control_points[, weights])``. They are read
        as :meth:`from_file` reads the curves of a G+Smo file (the same curves give the same
        domain, bit for bit): in any order and direction, chained end to end into a
        counter-clockwise loop, the first one becoming the side u = 0.

        Raises:
            ValueError: arrays of the wrong shape or type.
            IgaparamError: ``Status.INVALID_ARGUMENT`` for not four curves, a degree of 0, a
                knot count other than control points + degree + 1, decreasing knots, weights
                that are not positive, ends that do not meet or a corner whose interior angle
                reaches 180 degrees; ``Status.NOT_FINITE`` for NaN or infinite values.
        """
        array, _arrays = curve_arrays(curves)
        handle = ctypes.c_void_p()
        _check(_capi.library().igaparam_domain_new_from_curves(len(_arrays), array, ctypes.byref(handle)))
        return cls(handle)

    @classmethod
    def solid_from_surfaces(cls, surfaces: Sequence[Union[Surface, tuple]]) -> "Domain":
        """A solid bounded by six tensor-product B-spline or NURBS surfaces given by their
        arrays, each a :class:`Surface` or a tuple ``(degree, knots, control_points[,
        weights])``, read as :meth:`solid_from_file` reads a G+Smo B-rep (corners matched into
        a cube, each surface oriented onto its face).

        Raises:
            ValueError: arrays of the wrong shape or type.
            IgaparamError: ``Status.INVALID_ARGUMENT`` for not six surfaces or invalid knots
                or weights, ``Status.NOT_FINITE`` for NaN or infinite values,
                ``Status.INVALID_MESH`` for surfaces that do not share their edges and corners.
        """
        array, _arrays = surface_arrays(surfaces)
        handle = ctypes.c_void_p()
        _check(_capi.library().igaparam_domain_new_solid_from_surfaces(len(_arrays), array, ctypes.byref(handle)))
        return cls(handle)

    def __repr__(self):
        if self._handle is None:
            return "<igaparam.Domain (closed)>"
        kind = "planar domain" if self.dimension == 2 else "solid"
        if not self.is_built:
            return f"<igaparam.Domain {kind}, not built>"
        return f"<igaparam.Domain {kind}, {self.cell_count} cells, {self.vertex_count} vertices>"

    @property
    def dimension(self) -> int:
        """2 for a planar domain, 3 for a solid."""
        out = ctypes.c_size_t()
        _check(self._lib.igaparam_domain_dimension(self._h(), ctypes.byref(out)))
        return out.value

    # Building.

    def build(
        self,
        tolerance: Optional[float] = None,
        min_level: Optional[int] = None,
        max_level: Optional[int] = None,
        max_sweeps: Optional[int] = None,
        threads: int = 0,
        progress: Optional[Callable[[Stage, int, int], Optional[bool]]] = None,
        repair_rounds: Optional[int] = None,
        boundary_offset: Optional[float] = None,
        max_cells: Optional[int] = None,
        max_total_sweeps: Optional[int] = None,
        stationarity_tolerance: Optional[float] = None,
    ) -> "DomainReport":
        """Adapts a T-mesh to the boundary, places its vertices and optimizes them. Building
        again replaces the previous T-mesh; on any error the domain keeps its previous state.

        Args:
            tolerance: boundary tolerance (default 1e-5 for a planar domain, 1e-3 for a solid):
                a boundary cell edge (planar domain) or face (solid) is refined while the
                triangle of its end images and the image of its midpoint (the four tetrahedra of
                consecutive corner images and the image of its centre), measured in coordinates
                that map the bounding box onto the unit box, exceed ``tolerance × √d^d``.
            min_level: level of the initial uniform refinement (default 2).
            max_level: deepest level of the adaptation, at most 16 (default 9).
            max_sweeps: largest number of optimization sweeps of one stage (default 200).
            threads: worker threads, capped to the cores; 0 uses one per core (the result does not
                depend on it).
            progress: None, or a callable ``progress(stage, done, total)`` called after
                optimization sweeps and between the rounds of the adaptation; return None or
                True to go on, False to cancel (``Status.CANCELLED``); any other answer (an int
                included) raises TypeError. An exception raised by it cancels the build and is
                re-raised.
            repair_rounds: rounds of repair after the optimization (default 6): cells left
                invalid are refined (past ``max_level``, up to level 16) and the mesh optimized
                again; 0 disables it.
            boundary_offset: seam relief cap, finite and >= 0 (default 1e-2): the largest
                distance, in coordinates that map the bounding box onto the unit box, by which a
                boundary vertex may leave the boundary to open a cell that stays folded with
                every boundary vertex on it; 0 keeps every boundary vertex on the boundary.
            max_cells: largest number of cells of the T-mesh (default 1,000,000): a build
                beyond it is refused (``Status.LIMIT_EXCEEDED``), before any work when the
                uniform refinement to ``min_level`` alone exceeds it.
            max_total_sweeps: largest number of sweeps of all stages together, at least 1
                (default 5,000): once spent the build stops optimizing and succeeds with the
                T-mesh reached so far, ``sweep_budget_exhausted`` set in the report.
            stationarity_tolerance: the Newton polish after the sweeps, finite and >= 0
                (default 0: off): on a valid T-mesh the inner vertices go to a stationary point
                of the global objective (the sum of the cells' mean distortions) to this scaled
                gradient norm (1e-8 is typical); it raises the mean cell quality and may lower
                the smallest.

        Returns:
            DomainReport; ``invalid_cells == 0`` for a usable parameterization.

        Raises:
            ValueError: a negative level, sweep, thread or round count.
            IgaparamError: options rejected by the library (``Status.NOT_FINITE`` for a NaN or
                infinite ``tolerance``, ``boundary_offset`` or ``stationarity_tolerance``,
                ``Status.INVALID_ARGUMENT`` for a negative one, ...), a build that failed or was cancelled.
        """
        if self.dimension == 3:
            options = self._lib.igaparam_domain_options_default_solid()
        else:
            options = self._lib.igaparam_domain_options_default()
        if tolerance is not None:
            options.tolerance = float(tolerance)
        if boundary_offset is not None:
            options.boundary_offset = float(boundary_offset)
        if stationarity_tolerance is not None:
            options.stationarity_tolerance = float(stationarity_tolerance)
        _set_counts(options, min_level=min_level, max_level=max_level, max_sweeps=max_sweeps, threads=threads,
                    repair_rounds=repair_rounds, max_cells=max_cells, max_total_sweeps=max_total_sweeps)
        report = _call(self._lib.igaparam_domain_build, self._h(), options, progress, _capi.DomainReport())
        return DomainReport._from_c(report)

    # Moving the boundary.

    def set_boundary(
        self,
        *,
        curves: Optional[Sequence] = None,
        polylines: Optional[Sequence[npt.ArrayLike]] = None,
        surfaces: Optional[Sequence] = None,
        faces: Optional[Sequence] = None,
    ) -> None:
        """Replaces the boundary by one of the same kind, given as to the constructors: four
        ``curves`` or ``polylines`` for a planar domain (:meth:`from_curves`,
        :meth:`from_polylines`), six ``surfaces`` or triangulated ``faces`` for a solid
        (:meth:`solid_from_surfaces`, :meth:`solid_from_triangulations`); exactly one of them.
        Give the curves or surfaces in the order and direction of the first ones, so that each
        lands on the same side. The T-mesh stays where it is until :meth:`update` moves it onto
        the new boundary (or :meth:`build` builds anew); fits need that first. On any error
        the domain is unchanged.

        Raises:
            ValueError: not exactly one boundary, or arrays of the wrong shape or type.
            IgaparamError: the errors of the constructors; ``Status.INVALID_ARGUMENT`` for a
                boundary of the other kind or one oriented the other way round.
        """
        given = {name: value for name, value in
                 [("curves", curves), ("polylines", polylines), ("surfaces", surfaces), ("faces", faces)]
                 if value is not None}
        if len(given) != 1:
            raise ValueError(f"give exactly one of curves, polylines, surfaces and faces, not {sorted(given)}")
        (kind, value), = given.items()
        lib, h = self._lib, self._h()
        if kind == "curves":
            array, arrays = curve_arrays(value)
            status = lib.igaparam_domain_set_boundary_curves(h, len(arrays), array)
        elif kind == "surfaces":
            array, arrays = surface_arrays(value)
            status = lib.igaparam_domain_set_boundary_surfaces(h, len(arrays), array)
        elif kind == "polylines":
            counts, points, _arrays = polyline_arrays(value)
            status = lib.igaparam_domain_set_boundary_polylines(h, counts, points)
        else:
            c_arrays, _arrays = face_arrays(value)
            status = lib.igaparam_domain_set_boundary_triangulations(h, *c_arrays)
        _check(status)

    def set_boundary_from_file(self, path: Union[str, "os.PathLike[str]"], scale: Optional[Sequence[float]] = None) -> None:
        """Replaces the boundary by the one of a file, read as :meth:`from_file` (planar) or
        :meth:`solid_from_file` (a solid, with optional per-axis ``scale``) read theirs;
        otherwise as :meth:`set_boundary`."""
        factors = _as_scale(scale)
        if factors is None:
            status = self._lib.igaparam_domain_set_boundary_from_file(self._h(), os.fsencode(path))
        else:
            status = self._lib.igaparam_domain_set_boundary_from_file_scaled(self._h(), os.fsencode(path), factors)
        _check(status)

    def update(
        self,
        threads: int = 0,
        max_sweeps: Optional[int] = None,
        refine: bool = False,
        progress: Optional[Callable[[Stage, int, int], Optional[bool]]] = None,
    ) -> "UpdateReport":
        """Moves the built T-mesh onto the boundary given by :meth:`set_boundary`, keeping its
        tree: boundary vertices to the points of their parameters on the new boundary, inner
        ones by their current positions plus the harmonic extension of that motion (in steps
        for large motions), all optimized again with the build's targets. Then
        :meth:`Spline.refit` gives the spline map in the same space. On any error the domain
        is unchanged.

        Args:
            threads: worker threads, capped to the cores; 0 uses one per core (the result does not
                depend on it).
            max_sweeps: largest number of optimization sweeps per step (default 200).
            refine: refine the boundary cells whose error exceeds the build's tolerance and
                repair folded cells as the build does (the tree, and the spline space, change);
                by default the tree is kept and the report says whether its tolerance holds.
            progress: as for :meth:`build`.

        Raises:
            IgaparamError: ``Status.INVALID_ARGUMENT`` before a build, ``Status.CANCELLED``.
        """
        options = self._lib.igaparam_domain_update_options_default()
        _set_counts(options, max_sweeps=max_sweeps, threads=threads)
        options.refine = 1 if refine else 0
        report = _call(self._lib.igaparam_domain_update, self._h(), options, progress, _capi.DomainUpdateReport())
        return UpdateReport._from_c(report)

    @property
    def is_built(self) -> bool:
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
    def vertex_count(self) -> int:
        """Vertices of the T-mesh, hanging ones included."""
        return self._count(self._lib.igaparam_domain_vertex_count)

    @property
    def control_count(self) -> int:
        """Control points of the boundary's curves (planar) or surfaces (solid) together, in
        the order of :meth:`Spline.tangent_controls`; IgaparamError for polylines or
        triangulated faces."""
        return self._count(self._lib.igaparam_domain_control_count)

    @property
    def cell_count(self) -> int:
        """Cells of the T-mesh."""
        return self._count(self._lib.igaparam_domain_cell_count)

    def _vertices(self, physical):
        out = np.empty((self.vertex_count, self.dimension), dtype=np.float64)
        pointers = (None, _ptr(out, ctypes.c_double)) if physical else (_ptr(out, ctypes.c_double), None)
        _check(self._lib.igaparam_domain_copy_vertices(self._h(), *pointers, out.size))
        return out

    @property
    def parametric_vertices(self) -> npt.NDArray[np.float64]:
        """(u, v) (planar) or (u, v, w) (solid) of every vertex in [0,1]^d, a new float64 array
        of shape (n, d)."""
        return self._vertices(physical=False)

    @property
    def physical_vertices(self) -> npt.NDArray[np.float64]:
        """(x, y) (planar) or (x, y, z) (solid) of every vertex in the domain, a new float64
        array of shape (n, d)."""
        return self._vertices(physical=True)

    @property
    def cell_quality(self) -> npt.NDArray[np.float64]:
        """Quality of every cell, a new float64 array of shape (m,), in (0, 1]; 0 for a cell
        with det J <= 0 somewhere."""
        out = np.empty(self.cell_count, dtype=np.float64)
        _check(self._lib.igaparam_domain_copy_cell_quality(self._h(), _ptr(out, ctypes.c_double), out.size))
        return out

    @property
    def cell_levels(self) -> npt.NDArray[np.uint8]:
        """Refinement level of every cell, a new uint8 array of shape (m,)."""
        out = np.empty(self.cell_count, dtype=np.uint8)
        _check(self._lib.igaparam_domain_copy_cells(self._h(), _ptr(out, ctypes.c_uint8), None, out.size))
        return out

    @property
    def cell_bounds(self) -> npt.NDArray[np.float64]:
        """Parametric box of every cell, a new float64 array of shape (m, 2d): the lower then
        the upper corner (u0, v0, u1, v1 for a planar domain, u0, v0, w0, u1, v1, w1 for a
        solid)."""
        m = self.cell_count
        out = np.empty((m, 2 * self.dimension), dtype=np.float64)
        _check(self._lib.igaparam_domain_copy_cells(self._h(), None, _ptr(out, ctypes.c_double), m))
        return out

    @property
    def cell_corners(self) -> npt.NDArray[np.uintp]:
        """Corner vertices of every cell, a new int64 array of shape (m, 2^d) of indices into
        the vertex arrays: counter-clockwise from the lower-left corner for a planar domain, in
        VTK's hexahedron order for a solid. Hanging vertices are not listed."""
        m = self.cell_count
        out = np.empty((m, 2**self.dimension), dtype=_SIZE_T)
        _check(self._lib.igaparam_domain_copy_cell_corners(self._h(), _ptr(out, ctypes.c_size_t), out.size))
        return out.astype(np.int64)

    def write_vtu(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the T-mesh as a VTK .vtu file (polygons through corners and hanging vertices
        for a planar domain, hexahedra through their corners for a solid; point array
        ``parametric``, cell arrays ``quality`` and ``level``).

        Raises:
            IgaparamError: ``Status.IO`` when the file cannot be written.
        """
        _check(self._lib.igaparam_domain_write_vtu(self._h(), os.fsencode(path)))
