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
from ._mesh import _attach_progress, _check, _ptr, _set_counts

__all__ = ["Domain", "DomainReport"]

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
    seconds: float

    @classmethod
    def _from_c(cls, report):
        return cls(**{field.name: getattr(report, field.name) for field in dataclasses.fields(cls)})

    def as_dict(self) -> dict:
        """The report as a dict."""
        return dataclasses.asdict(self)


def _as_polyline(values, index):
    array = np.asarray(values)
    if array.dtype.kind not in "fiu":
        raise ValueError(f"polyline {index} must be numeric, not {array.dtype}")
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(f"polyline {index} must have shape (k, 2), not {array.shape}")
    return np.ascontiguousarray(array, dtype=np.float64)


# The faces of a solid, in the order of the C API (the unit cube's faces x = 0, x = 1, ...).
_CUBE_FACES = ("xmin", "xmax", "ymin", "ymax", "zmin", "zmax")


def _as_face(face, index):
    """``(vertices, triangles)`` of face ``index`` as C-contiguous float64 (n, 3) and uint32
    (m, 3) arrays."""
    name = _CUBE_FACES[index]
    try:
        vertices, triangles = face
    except (TypeError, ValueError):
        raise ValueError(f"face {index} ({name}) must be a pair (vertices, triangles)") from None
    vertices, triangles = np.asarray(vertices), np.asarray(triangles)
    if vertices.dtype.kind not in "fiu":
        raise ValueError(f"vertices of face {index} ({name}) must be numeric, not {vertices.dtype}")
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise ValueError(f"vertices of face {index} ({name}) must have shape (n, 3), not {vertices.shape}")
    if triangles.dtype.kind not in "iu":
        raise ValueError(f"triangles of face {index} ({name}) must be an integer array, not {triangles.dtype}")
    if triangles.ndim != 2 or triangles.shape[1] != 3:
        raise ValueError(f"triangles of face {index} ({name}) must have shape (m, 3), not {triangles.shape}")
    if triangles.size and (triangles.min() < 0 or triangles.max() > np.iinfo(np.uint32).max):
        raise ValueError(f"triangles of face {index} ({name}) hold indices out of the uint32 range")
    return (
        np.ascontiguousarray(vertices, dtype=np.float64),
        np.ascontiguousarray(triangles, dtype=np.uint32),
    )


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
        polylines = list(polylines)
        if len(polylines) != 4:
            raise ValueError(f"a domain needs 4 polylines, not {len(polylines)}")
        arrays = [_as_polyline(p, i) for i, p in enumerate(polylines)]
        counts = (ctypes.c_size_t * 4)(*[a.shape[0] for a in arrays])
        points = (ctypes.POINTER(ctypes.c_double) * 4)(*[_ptr(a, ctypes.c_double) for a in arrays])
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
        faces = list(faces)
        if len(faces) != 6:
            raise ValueError(f"a solid needs 6 faces (xmin, xmax, ymin, ymax, zmin, zmax), not {len(faces)}")
        arrays = [_as_face(face, i) for i, face in enumerate(faces)]
        vertex_counts = (ctypes.c_size_t * 6)(*[v.shape[0] for v, _ in arrays])
        triangle_counts = (ctypes.c_size_t * 6)(*[t.shape[0] for _, t in arrays])
        points = (ctypes.POINTER(ctypes.c_double) * 6)(*[_ptr(v, ctypes.c_double) for v, _ in arrays])
        triangles = (ctypes.POINTER(ctypes.c_uint32) * 6)(*[_ptr(t, ctypes.c_uint32) for _, t in arrays])
        handle = ctypes.c_void_p()
        _check(
            _capi.library().igaparam_domain_new_solid_from_triangulations(
                vertex_counts, points, triangle_counts, triangles, ctypes.byref(handle)
            )
        )
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
        if self.dimension == 3:
            options = self._lib.igaparam_domain_options_default_solid()
        else:
            options = self._lib.igaparam_domain_options_default()
        if tolerance is not None:
            options.tolerance = float(tolerance)
        if boundary_offset is not None:
            options.boundary_offset = float(boundary_offset)
        _set_counts(options, min_level=min_level, max_level=max_level, max_sweeps=max_sweeps, threads=threads,
                    repair_rounds=repair_rounds)
        raised, _callback = _attach_progress(options, progress)
        report = _capi.DomainReport()
        status = self._lib.igaparam_domain_build(self._h(), ctypes.byref(options), ctypes.byref(report))
        if raised:
            raise raised[0]
        _check(status)
        return DomainReport._from_c(report)

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
