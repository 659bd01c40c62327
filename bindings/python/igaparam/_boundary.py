"""Boundaries given by their arrays: :class:`Curve` (a B-spline or NURBS curve of the plane) and
:class:`Surface` (a tensor-product B-spline or NURBS surface in 3D), and the C arrays of the
boundaries a :class:`~igaparam.Domain` is made from (curves, surfaces, polylines, triangulated
faces)."""

from __future__ import annotations

import ctypes
import dataclasses
from typing import Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

from . import _capi
from ._ints import c_int_value
from ._mesh import _ptr

__all__ = ["Curve", "Surface"]


def _floats(values, name, ndim):
    array = np.asarray(values)
    if array.dtype.kind not in "fiu":
        raise ValueError(f"{name} must be numeric, not {array.dtype}")
    if array.ndim != ndim:
        raise ValueError(f"{name} must have {ndim} dimension(s), not shape {array.shape}")
    return np.ascontiguousarray(array, dtype=np.float64)


def _degree(value, name):
    return c_int_value(int(value), name, ctypes.c_uint32, 0)


@dataclasses.dataclass(frozen=True)
class Curve:
    """A B-spline or NURBS curve of the plane, ``C(t) = Σ w_i N_i(t) P_i / Σ w_i N_i(t)`` over
    its knot domain (the arrays of ``igaparam_curve``).

    Attributes:
        degree: the polynomial degree p, at least 1.
        knots: ``n + p + 1`` knots, finite and non-decreasing.
        control_points: the n control points, shape (n, 2).
        weights: None (a B-spline curve) or n positive weights (a NURBS curve).
    """

    degree: int
    knots: npt.ArrayLike
    control_points: npt.ArrayLike
    weights: Optional[npt.ArrayLike] = None


@dataclasses.dataclass(frozen=True)
class Surface:
    """A tensor-product B-spline or NURBS surface in 3D (the arrays of ``igaparam_surface``).

    Attributes:
        degree: the degrees ``(p_u, p_v)``, each at least 1.
        knots: the knot vectors ``(knots_u, knots_v)``, of ``n_u + p_u + 1`` and
            ``n_v + p_v + 1`` knots.
        control_points: shape (n_v, n_u, 3): ``control_points[j, i]`` is the control point of
            the i-th function in u and the j-th in v (u runs fastest in memory, as in G+Smo).
        weights: None (a B-spline surface) or positive weights of shape (n_v, n_u).
    """

    degree: Tuple[int, int]
    knots: Tuple[npt.ArrayLike, npt.ArrayLike]
    control_points: npt.ArrayLike
    weights: Optional[npt.ArrayLike] = None


def _coerce(cls, value, name):
    """``value`` as a ``cls`` (a :class:`Curve` or :class:`Surface`), made from a tuple of its
    fields if need be."""
    if isinstance(value, cls):
        return value
    try:
        return cls(*value)
    except TypeError:
        raise ValueError(f"{name} must be a {cls.__name__} or (degree, knots, control_points[, weights])") from None


def _as_curve(curve, index):
    name = f"curve {index}"
    curve = _coerce(Curve, curve, name)
    knots = _floats(curve.knots, f"knots of {name}", 1)
    points = _floats(curve.control_points, f"control points of {name}", 2)
    if points.shape[1] != 2:
        raise ValueError(f"control points of {name} must have shape (n, 2), not {points.shape}")
    weights = None if curve.weights is None else _floats(curve.weights, f"weights of {name}", 1)
    if weights is not None and weights.shape[0] != points.shape[0]:
        raise ValueError(f"{name} has {weights.shape[0]} weights for {points.shape[0]} control points")
    return _degree(curve.degree, f"degree of {name}"), knots, points, weights


def _as_surface(surface, index):
    name = f"surface {index}"
    surface = _coerce(Surface, surface, name)
    try:
        (pu, pv), (ku, kv) = surface.degree, surface.knots
    except (TypeError, ValueError):
        raise ValueError(f"{name}: degree and knots must be pairs (u, v)") from None
    knots = (_floats(ku, f"knots_u of {name}", 1), _floats(kv, f"knots_v of {name}", 1))
    points = _floats(surface.control_points, f"control points of {name}", 3)
    if points.shape[2] != 3:
        raise ValueError(f"control points of {name} must have shape (n_v, n_u, 3), not {points.shape}")
    weights = None if surface.weights is None else _floats(surface.weights, f"weights of {name}", 2)
    if weights is not None and weights.shape != points.shape[:2]:
        raise ValueError(f"weights of {name} must have shape {points.shape[:2]}, not {weights.shape}")
    degrees = (_degree(pu, f"degree_u of {name}"), _degree(pv, f"degree_v of {name}"))
    return degrees, knots, points, weights


def _nullable(array):
    return _ptr(array, ctypes.c_double) if array is not None else None


def curve_arrays(curves: Sequence) -> Tuple[ctypes.Array, list]:
    """The ``igaparam_curve`` array of ``curves`` and the numpy arrays it points into (keep them
    alive during the call)."""
    curves = list(curves)
    converted = [_as_curve(c, i) for i, c in enumerate(curves)]
    out = (_capi.Curve * max(len(curves), 1))()
    for slot, (degree, knots, points, weights) in zip(out, converted):
        slot.degree = degree
        slot.knot_count = knots.shape[0]
        slot.knots = _ptr(knots, ctypes.c_double)
        slot.control_point_count = points.shape[0]
        slot.control_points = _ptr(points, ctypes.c_double)
        slot.weights = _nullable(weights)
    return out, converted


def surface_arrays(surfaces: Sequence) -> Tuple[ctypes.Array, list]:
    """The ``igaparam_surface`` array of ``surfaces`` and the numpy arrays it points into."""
    surfaces = list(surfaces)
    converted = [_as_surface(s, i) for i, s in enumerate(surfaces)]
    out = (_capi.Surface * max(len(surfaces), 1))()
    for slot, ((pu, pv), (ku, kv), points, weights) in zip(out, converted):
        slot.degree_u, slot.degree_v = pu, pv
        slot.knot_count_u, slot.knots_u = ku.shape[0], _ptr(ku, ctypes.c_double)
        slot.knot_count_v, slot.knots_v = kv.shape[0], _ptr(kv, ctypes.c_double)
        slot.control_point_count_v, slot.control_point_count_u = points.shape[:2]
        slot.control_points = _ptr(points, ctypes.c_double)
        slot.weights = _nullable(weights)
    return out, converted


def _as_polyline(values, index):
    array = np.asarray(values)
    if array.dtype.kind not in "fiu":
        raise ValueError(f"polyline {index} must be numeric, not {array.dtype}")
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(f"polyline {index} must have shape (k, 2), not {array.shape}")
    return np.ascontiguousarray(array, dtype=np.float64)


def polyline_arrays(polylines: Sequence[npt.ArrayLike]):
    """The C arrays ``(counts, points)`` of four polylines and the numpy arrays they point into."""
    polylines = list(polylines)
    if len(polylines) != 4:
        raise ValueError(f"a domain needs 4 polylines, not {len(polylines)}")
    arrays = [_as_polyline(p, i) for i, p in enumerate(polylines)]
    counts = (ctypes.c_size_t * 4)(*[a.shape[0] for a in arrays])
    points = (ctypes.POINTER(ctypes.c_double) * 4)(*[_ptr(a, ctypes.c_double) for a in arrays])
    return counts, points, arrays


# The faces of a solid, in the order of the C API (the unit cube's faces x = 0, x = 1, ...).
CUBE_FACES = ("xmin", "xmax", "ymin", "ymax", "zmin", "zmax")


def _as_face(face, index):
    """``(vertices, triangles)`` of face ``index`` as C-contiguous float64 (n, 3) and uint32
    (m, 3) arrays."""
    name = CUBE_FACES[index]
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


def face_arrays(faces: Sequence):
    """The C arrays ``(vertex_counts, points, triangle_counts, triangles)`` of six triangulated
    faces and the numpy arrays they point into."""
    faces = list(faces)
    if len(faces) != 6:
        raise ValueError(f"a solid needs 6 faces (xmin, xmax, ymin, ymax, zmin, zmax), not {len(faces)}")
    arrays = [_as_face(face, i) for i, face in enumerate(faces)]
    vertex_counts = (ctypes.c_size_t * 6)(*[v.shape[0] for v, _ in arrays])
    triangle_counts = (ctypes.c_size_t * 6)(*[t.shape[0] for _, t in arrays])
    points = (ctypes.POINTER(ctypes.c_double) * 6)(*[_ptr(v, ctypes.c_double) for v, _ in arrays])
    triangles = (ctypes.POINTER(ctypes.c_uint32) * 6)(*[_ptr(t, ctypes.c_uint32) for _, t in arrays])
    return (vertex_counts, points, triangle_counts, triangles), arrays
