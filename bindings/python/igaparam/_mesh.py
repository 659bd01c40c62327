"""The :class:`Mesh` class, its relocation report and errors."""

from __future__ import annotations

import ctypes
import dataclasses
import os
from typing import Callable, Optional, Union

import numpy as np
import numpy.typing as npt

from . import _capi
from ._handle import _Handle
from ._ints import c_int_value, set_int_fields
from ._capi import CellType, Stage, Status

__all__ = [
    "IgaparamError",
    "Mesh",
    "RelocateReport",
    "version",
    "nodes_per_cell",
    "cell_type_code",
    "node_coordinates",
]


class IgaparamError(Exception):
    """A failed call of the library.

    Attributes:
        status: the :class:`Status` the C function returned.
        message: the library's message.
    """

    def __init__(self, status, message):
        try:
            status = Status(status)
        except ValueError:
            pass
        self.status = status
        self.message = message
        name = status.name if isinstance(status, Status) else str(status)
        super().__init__(f"{message} (status {int(status)}, {name})")


def _last_error_message() -> str:
    lib = _capi.library()
    size = lib.igaparam_last_error_message(None, 0)
    buf = ctypes.create_string_buffer(size)
    lib.igaparam_last_error_message(buf, size)
    return buf.value.decode("utf-8", errors="replace")


def _check(status: int) -> None:
    if status != Status.OK:
        raise IgaparamError(status, _last_error_message())


def version() -> str:
    """The library version, e.g. ``"0.1.0"``."""
    return _capi.library().igaparam_version().decode()


_CELL_NAMES = {name: int(code) for name, code in CellType.__members__.items()}
# meshio's names of the supported cell types (VTK's node order, as meshio keeps it).
MESHIO_NAMES = {"QUAD": 9, "QUAD8": 23, "QUAD9": 28, "HEXAHEDRON": 12, "HEXAHEDRON20": 25, "HEXAHEDRON27": 29}
_MESHIO_BY_CODE = {code: name.lower() for name, code in MESHIO_NAMES.items()}
_ORDERS = {"vtk": _capi.ORDER_VTK, "gmsh": _capi.ORDER_GMSH}
_ORDER_NAMES = {code: name for name, code in _ORDERS.items()}
_TARGETS = {"initial": _capi.TARGET_INITIAL, "master": _capi.TARGET_MASTER}
_PLACEMENTS = {
    "laplacian": _capi.PLACEMENT_LAPLACIAN,
    "current": _capi.PLACEMENT_CURRENT,
    "incremental": _capi.PLACEMENT_INCREMENTAL,
}
_METHODS = {"auto": _capi.METHOD_AUTO, "sweeps": _capi.METHOD_SWEEPS, "newton": _capi.METHOD_NEWTON}


def cell_type_code(cell_type: Union[int, str]) -> int:
    """The VTK code of a cell type given as a code (e.g. 28), a name ('Q4', 'Q8', 'Q9', 'H8',
    'H20', 'H27') or a meshio name ('quad', 'quad8', 'quad9', 'hexahedron', 'hexahedron20',
    'hexahedron27')."""
    if isinstance(cell_type, str):
        key = cell_type.upper()
        if key in _CELL_NAMES:
            return _CELL_NAMES[key]
        if key in MESHIO_NAMES:
            return MESHIO_NAMES[key]
        names = sorted(_CELL_NAMES) + sorted(name.lower() for name in MESHIO_NAMES)
        raise ValueError(f"unknown cell type {cell_type!r}: expected one of {names}")
    if isinstance(cell_type, (bool, np.bool_)) or not isinstance(cell_type, (int, np.integer)):
        raise TypeError(f"cell_type must be an int (VTK code) or a name, not {type(cell_type).__name__}")
    return c_int_value(cell_type, "cell_type", ctypes.c_int)


def nodes_per_cell(cell_type: Union[int, str]) -> int:
    """Nodes of one cell of ``cell_type`` (a VTK code or a name), e.g. 9 for 'Q9'."""
    out = ctypes.c_size_t()
    _check(_capi.library().igaparam_cell_type_node_count(cell_type_code(cell_type), ctypes.byref(out)))
    return out.value


def node_coordinates(cell_type: Union[int, str], order: str = "vtk") -> npt.NDArray[np.float64]:
    """Reference coordinates in [-1, 1]^d of the local nodes of ``cell_type`` in ``order``
    ('vtk' or 'gmsh'): a float64 array of shape (nodes per cell, d), row i for local node i."""
    code = cell_type_code(cell_type)
    k = nodes_per_cell(code)
    d = 2 if code in (9, 23, 28) else 3
    out = np.empty((k, d), dtype=np.float64)
    _check(
        _capi.library().igaparam_cell_type_copy_node_coordinates(
            code, _option_code(order, _ORDERS, "order"), _ptr(out, ctypes.c_double), out.size
        )
    )
    return out


def _option_code(value, codes, what):
    if isinstance(value, str):
        try:
            return codes[value.lower()]
        except KeyError:
            raise ValueError(f"unknown {what} {value!r}: expected one of {sorted(codes)}") from None
    if isinstance(value, (int, np.integer)) and int(value) in codes.values():
        return int(value)
    raise ValueError(f"unknown {what} {value!r}: expected one of {sorted(codes)}")


def _ptr(array, ctype):
    return array.ctypes.data_as(ctypes.POINTER(ctype))


def _as_xyz(values, name):
    """``values`` as a C-contiguous float64 array of shape (n, 3); (n, 2) gets z = 0."""
    array = np.asarray(values)
    if array.dtype.kind not in "fiub":
        raise ValueError(f"{name} must be numeric, not {array.dtype}")
    if array.ndim != 2 or array.shape[1] not in (2, 3):
        raise ValueError(f"{name} must have shape (n, 3) (or (n, 2)), not {array.shape}")
    array = np.asarray(array, dtype=np.float64)
    if array.shape[1] == 2:
        array = np.hstack([array, np.zeros((array.shape[0], 1))])
    return np.ascontiguousarray(array)


def _as_int64(values, name, ndim):
    array = np.asarray(values)
    if array.size == 0 and array.dtype.kind == "f":
        array = array.astype(np.int64)
    if array.dtype.kind not in "iu":
        raise ValueError(f"{name} must be an integer array, not {array.dtype}")
    if array.ndim != ndim:
        raise ValueError(f"{name} must have {ndim} dimension(s), not shape {array.shape}")
    if array.dtype.kind == "u" and array.size and array.max() > np.iinfo(np.int64).max:
        raise ValueError(f"{name} has values out of the int64 range")
    return np.ascontiguousarray(array, dtype=np.int64)


def _set_counts(options, **counts):
    """Sets the integer fields of a C options struct given (not None), refusing negative ones
    and ones that do not fit their C type."""
    set_int_fields(options, **counts)


def _attach_progress(options, progress):
    """Sets ``options.progress`` from a Python ``progress`` (see :func:`_progress_callback`).
    Returns the list that collects the exceptions it raised and the C callback, which the
    caller keeps alive during the call."""
    raised = []
    callback = _progress_callback(progress, raised)
    if callback is not None:
        options.progress = callback
    return raised, callback


PROGRESS_RULE = "return None or True to go on, False to cancel"


def _cancels(answer) -> bool:
    """The progress rule of every entry point taking ``progress``: None or True go on, False
    cancels (numpy's booleans alike). Any other value raises TypeError, which cancels the call
    and is re-raised after it: an int would be ambiguous, C's callback cancelling on non-zero
    where Python's truth would go on at 0 and cancel at 1 only by accident."""
    if answer is None:
        return False
    if isinstance(answer, (bool, np.bool_)):
        return not answer
    raise TypeError(f"progress returned {answer!r}: {PROGRESS_RULE}")


def _progress_callback(progress, raised):
    """A C progress callback calling ``progress(stage, done, total)`` (None if ``progress`` is
    None) under :func:`_cancels`' rule: False cancels; an exception (TypeError for an answer
    other than None, True or False) cancels and is appended to ``raised`` (re-raise it after
    the call)."""
    if progress is None:
        return None

    def trampoline(_user, stage, done, total):
        try:
            try:
                stage = Stage(stage)
            except ValueError:
                pass
            return 1 if _cancels(progress(stage, done, total)) else 0
        except BaseException as error:  # cancel, re-raise after the call
            raised.append(error)
            return 1

    return _capi.PROGRESS_FN(trampoline)


@dataclasses.dataclass(frozen=True)
class RelocateReport:
    """What :meth:`Mesh.relocate` did (``igaparam_relocate_report``). Quality is the inverse mean
    distortion of a cell against its target: 1 is the target shape, 0 an inverted cell."""

    cells: int
    nodes: int
    free_nodes: int
    invalid_before: int
    invalid_after_placement: int
    invalid_after: int
    min_quality: float
    mean_quality: float
    sweeps: int
    steps: int
    converged: bool
    gradient_norm: float
    newton_iterations: int
    seconds: float

    @classmethod
    def _from_c(cls, report):
        values = {field.name: getattr(report, field.name) for field in dataclasses.fields(cls)}
        values["converged"] = bool(values["converged"])
        return cls(**values)

    def as_dict(self) -> dict:
        """The report as a dict."""
        return dataclasses.asdict(self)


class Mesh(_Handle):
    """A quadrilateral or hexahedral finite-element mesh of one cell type, owning an
    ``igaparam_mesh`` handle.

    Args:
        cell_type: VTK cell type code (9, 23, 28, 12, 25, 29) or name ('Q4', 'Q8', 'Q9', 'H8',
            'H20', 'H27').
        points: node coordinates, shape (n, 3) (or (n, 2): z = 0), converted to float64. They
            are the reference shape of the targets. For quadrilaterals z is carried unchanged.
        cells: connectivity, shape (m, k) with k the nodes per cell of ``cell_type``, in
            ``order``, converted to int64.
        order: the local node order of ``cells``: 'vtk' (VTK's and meshio's, the default) or
            'gmsh' (Gmsh's); see ``igaparam_node_order`` in igaparam.h for the tables and
            :func:`node_coordinates`. :attr:`cells` gives them back in this order.

    ``cell_type`` may also be a meshio name ('quad9', 'hexahedron27', ...). A mesh every cell
    of which is inverted or folded is refused (``Status.INVALID_MESH``; likely a wrong node
    order or cells oriented the wrong way).

    All nodes start free (see :meth:`set_fixed`). The arrays are copied. Release the handle
    with :meth:`close` or a ``with`` block (it is also released when the object is collected).

    Raises:
        ValueError: arrays of the wrong shape or type, or an unknown cell type name.
        IgaparamError: rejected by the library, e.g. ``Status.NOT_FINITE`` for NaN coordinates,
            ``Status.INVALID_MESH`` for a node index out of range.
    """

    _kind = "mesh"
    _free = "igaparam_mesh_free"

    def __init__(self, cell_type: Union[int, str], points: npt.ArrayLike, cells: npt.ArrayLike, order: str = "vtk"):
        self._handle = None
        self._lib = _capi.library()
        code = cell_type_code(cell_type)
        k = nodes_per_cell(code)
        xyz = _as_xyz(points, "points")
        connectivity = _as_int64(cells, "cells", 2)
        if connectivity.shape[1] != k and connectivity.size > 0:
            raise ValueError(
                f"cells must have shape (m, {k}) for cell type {code} ({k} nodes per cell), "
                f"not {connectivity.shape}"
            )
        handle = _capi.ctypes.c_void_p()
        _check(
            self._lib.igaparam_mesh_new_ordered(
                code,
                _option_code(order, _ORDERS, "order"),
                xyz.shape[0],
                _ptr(xyz, ctypes.c_double),
                connectivity.shape[0],
                _ptr(connectivity, ctypes.c_int64),
                ctypes.byref(handle),
            )
        )
        self._handle = handle
        self._cell_type = code

    @classmethod
    def from_meshio(cls, mesh) -> "Mesh":
        """A Mesh from a ``meshio.Mesh`` (VTK node order, as meshio keeps it): its one block
        type of supported cells ('quad', 'quad8', 'quad9', 'hexahedron', 'hexahedron20',
        'hexahedron27'; blocks of lower dimension, such as boundary lines or faces, are left
        out). The point data ``fixed_components`` and ``moved``, when present, constrain and
        move the nodes as in :meth:`read_vtu`.

        Raises:
            ValueError: no supported cells, or several types of them.
        """
        blocks = [b for b in mesh.cells if b.type.upper() in MESHIO_NAMES]
        dims = {MESHIO_NAMES[b.type.upper()] in (12, 25, 29) for b in blocks}
        if True in dims:
            blocks = [b for b in blocks if b.type.upper().startswith("HEX")]
        types = sorted({b.type for b in blocks})
        if len(types) != 1:
            raise ValueError(
                f"the meshio mesh must hold one supported cell type, it holds {types or 'none'} "
                f"(of {[b.type for b in mesh.cells]})"
            )
        cells = np.concatenate([np.asarray(b.data) for b in blocks])
        out = cls(types[0], mesh.points, cells)
        data = mesh.point_data
        if "fixed_components" in data:
            mask = np.asarray(data["fixed_components"]).reshape(-1)
            if not np.all((mask == np.round(mask)) & (mask >= 0) & (mask <= 7)):
                out.close()
                raise ValueError("point data fixed_components must hold masks in 0..7")
            mask = mask.astype(np.uint8)
            if "moved" in data:
                moved = np.asarray(data["moved"], dtype=np.float64).reshape(-1, 3)
                bits = ((mask[:, None] >> np.arange(3)) & 1) == 1
                out.move_nodes(np.where(bits, moved, out.reference))
            out.set_fixed(mask)
        return out

    def to_meshio(self):
        """The mesh as a ``meshio.Mesh``: current positions, cells (VTK order), point data
        ``fixed_components`` and ``displacement``, cell data ``quality``."""
        import meshio

        positions = self.positions
        cells = self.cells_in("vtk")
        return meshio.Mesh(
            positions,
            [(_MESHIO_BY_CODE[self._cell_type], cells)],
            point_data={"fixed_components": self.fixed, "displacement": positions - self.reference},
            cell_data={"quality": [self.cell_quality()]},
        )

    @classmethod
    def _from_handle(cls, handle):
        """A Mesh owning ``handle`` (an ``igaparam_mesh *`` of the library)."""
        mesh = cls.__new__(cls)
        mesh._lib = _capi.library()
        mesh._handle = handle
        code = ctypes.c_int()
        _check(mesh._lib.igaparam_mesh_cell_type(handle, ctypes.byref(code)))
        mesh._cell_type = code.value
        return mesh

    @classmethod
    def read_vtu(cls, path: Union[str, "os.PathLike[str]"]) -> "Mesh":
        """Reads a mesh from a ``.vtu`` file in any storage VTK and meshio write (ASCII, binary,
        appended raw or base64, zlib-compressed): one supported cell type in VTK's node order;
        its point arrays ``fixed_components`` (masks) and ``moved`` (new positions), when
        present, constrain and move the nodes (see ``igaparam_mesh_read_vtu`` in igaparam.h).

        Raises:
            IgaparamError: ``Status.IO`` for a file that cannot be read or understood,
                ``Status.INVALID_MESH`` for unsupported or mixed cells or bad masks.
        """
        handle = ctypes.c_void_p()
        _check(_capi.library().igaparam_mesh_read_vtu(os.fsencode(path), ctypes.byref(handle)))
        return cls._from_handle(handle)

    def write_vtu(self, path: Union[str, "os.PathLike[str]"], encoding: str = "binary", compress: bool = True) -> None:
        """Writes the mesh to a ``.vtu`` file: current positions, cells (VTK order), point data
        ``displacement`` and ``fixed_components``, cell data ``quality``.

        Args:
            path: the file.
            encoding: 'binary' (base64 in each array, valid XML), 'appended' (raw bytes in an
                appended section, VTK's default, the smallest), 'appended-base64' or 'ascii'.
            compress: zlib-compress the binary data (not with 'ascii').
        """
        codes = {
            "ascii": _capi.VTU_ASCII,
            "binary": _capi.VTU_BINARY,
            "appended": _capi.VTU_APPENDED,
            "appended-base64": _capi.VTU_APPENDED_BASE64,
        }
        code = _option_code(encoding, codes, "encoding")
        if compress and code == _capi.VTU_ASCII:
            raise ValueError("ASCII .vtu files cannot be compressed: pass compress=False")
        code |= _capi.VTU_ZLIB if compress else 0
        _check(self._lib.igaparam_mesh_write_vtu_format(self._h(), os.fsencode(path), code))

    def __repr__(self):
        if self.closed:
            return "<igaparam.Mesh (closed)>"
        return f"<igaparam.Mesh {self.cell_count} cells of type {self._cell_type}, {self.node_count} nodes>"

    # Sizes.

    def _size(self, function):
        out = ctypes.c_size_t()
        _check(function(self._h(), ctypes.byref(out)))
        return out.value

    @property
    def node_count(self) -> int:
        """Number of nodes n."""
        return self._size(self._lib.igaparam_mesh_node_count)

    @property
    def cell_count(self) -> int:
        """Number of cells m."""
        return self._size(self._lib.igaparam_mesh_cell_count)

    @property
    def dimension(self) -> int:
        """Spatial dimension of the cells: 2 (quadrilaterals) or 3 (hexahedra)."""
        out = ctypes.c_int()
        _check(self._lib.igaparam_mesh_dimension(self._h(), ctypes.byref(out)))
        return out.value

    @property
    def cell_type(self) -> int:
        """The VTK code of the cell type."""
        return self._cell_type

    @property
    def order(self) -> str:
        """The node order :attr:`cells` is given in: 'vtk' or 'gmsh' (as at creation)."""
        out = ctypes.c_int()
        _check(self._lib.igaparam_mesh_order(self._h(), ctypes.byref(out)))
        return _ORDER_NAMES[out.value]

    @property
    def cells(self) -> npt.NDArray[np.int64]:
        """The connectivity, a new int64 array of shape (m, k), in the mesh's :attr:`order`."""
        return self.cells_in(self.order)

    def cells_in(self, order: str) -> npt.NDArray[np.int64]:
        """The connectivity, shape (m, k), with each cell's nodes in ``order`` ('vtk' or 'gmsh')."""
        k = nodes_per_cell(self._cell_type)
        out = np.empty((self.cell_count, k), dtype=np.int64)
        code = _option_code(order, _ORDERS, "order")
        _check(self._lib.igaparam_mesh_copy_connectivity(self._h(), code, _ptr(out, ctypes.c_int64), out.size))
        return out

    @property
    def invalid_cell_count(self) -> int:
        """Number of cells with det J <= 0 at some Gauss–Lobatto point."""
        return self._size(self._lib.igaparam_mesh_invalid_cell_count)

    # Constraints and motion.

    def set_fixed(self, mask: npt.ArrayLike) -> None:
        """Sets the constraint of every node.

        Args:
            mask: shape (n,), integers in 0..7 (or booleans: True fixes every coordinate of
                the mesh's dimension): bit 0 keeps x, bit 1 y, bit 2 z (0 free, 3 fixed in 2D,
                7 fixed in 3D, 4 sliding in its plane z = const).
        """
        array = np.asarray(mask)
        if array.dtype.kind == "b":
            array = np.where(array, 3 if self.dimension == 2 else 7, 0)
        if array.dtype.kind not in "iu":
            raise ValueError(f"mask must be an integer (or boolean) array, not {array.dtype}")
        if array.ndim != 1:
            raise ValueError(f"mask must have shape (n,), not {array.shape}")
        if array.size and (array.min() < 0 or array.max() > 255):
            raise ValueError("mask values must be in 0..7")
        array = np.ascontiguousarray(array, dtype=np.uint8)
        _check(self._lib.igaparam_mesh_set_fixed(self._h(), array.shape[0], _ptr(array, ctypes.c_uint8)))

    def move_nodes(self, xyz: npt.ArrayLike, indices: Optional[npt.ArrayLike] = None) -> None:
        """Sets the positions of some nodes (typically the boundary's, before :meth:`relocate`);
        the reference shape is not changed.

        Args:
            xyz: new positions, shape (k, 3) (or (k, 2): z = 0).
            indices: the nodes moved, shape (k,); None means nodes 0..k-1.
        """
        positions = _as_xyz(xyz, "xyz")
        if indices is None:
            index_ptr = None
        else:
            index_array = _as_int64(indices, "indices", 1)
            if index_array.shape[0] != positions.shape[0]:
                raise ValueError(
                    f"indices has {index_array.shape[0]} entries but xyz has {positions.shape[0]} rows"
                )
            index_ptr = _ptr(index_array, ctypes.c_int64)
        _check(
            self._lib.igaparam_mesh_move_nodes(
                self._h(), positions.shape[0], index_ptr, _ptr(positions, ctypes.c_double)
            )
        )

    def reset_reference(self) -> None:
        """Makes the current positions the reference shape of the targets."""
        _check(self._lib.igaparam_mesh_reset_reference(self._h()))

    # Relocation.

    def relocate(
        self,
        threads: int = 0,
        target: str = "initial",
        laplacian_only: bool = False,
        max_sweeps: Optional[int] = None,
        progress: Optional[Callable[[Stage, int, int], Optional[bool]]] = None,
        placement: str = "laplacian",
        move_tolerance: Optional[float] = None,
        gradient_tolerance: Optional[float] = None,
        max_newton_iterations: Optional[int] = None,
        relaxation: Optional[float] = None,
        stationarity_tolerance: Optional[float] = None,
        method: str = "auto",
    ) -> "RelocateReport":
        """Relocates the free coordinates of the nodes so that every cell is valid and close to
        its target shape. On any error the mesh is unchanged.

        Args:
            threads: worker threads, capped to the cores; 0 uses one per core (the result does not
                depend on it).
            target: 'initial' (the cells' reference shapes) or 'master' (square/cube).
            laplacian_only: stop after the first placement (no optimization).
            max_sweeps: largest number of Gauss–Seidel sweeps (library default: 100 per step).
            progress: None, or a callable ``progress(stage, done, total)`` (stage a
                :class:`Stage`) called on this thread; return None or True to go on, False to
                cancel (the call then raises IgaparamError with ``Status.CANCELLED``); any other
                answer (an int included) raises TypeError. An exception raised by it cancels the
                call and is re-raised.
            placement: 'laplacian' (from the reference shape), 'current' (the positions as they
                are) or 'incremental' (from the last relocation: the placement of a loop that
                moves the boundary a little at every step).
            stationarity_tolerance: when positive, the result is a stationary point of the global
                objective to this scaled gradient norm (e.g. 1e-10), which :meth:`adjoint` and
                :meth:`tangent` differentiate; None or 0: no such guarantee.
            method: 'auto', 'sweeps' or 'newton' (``IGAPARAM_METHOD_*`` in igaparam.h).
            move_tolerance, gradient_tolerance, max_newton_iterations, relaxation: see
                ``igaparam_relocate_options`` in igaparam.h; None keeps the library's default.

        Returns:
            RelocateReport.
        """
        options = self._lib.igaparam_relocate_options_default()
        options.target = _option_code(target, _TARGETS, "target")
        options.placement = _option_code(placement, _PLACEMENTS, "placement")
        options.method = _option_code(method, _METHODS, "method")
        options.optimize = 0 if laplacian_only else 1
        _set_counts(options, threads=threads, max_sweeps=max_sweeps, max_newton_iterations=max_newton_iterations)
        for name, value in (
            ("move_tolerance", move_tolerance),
            ("gradient_tolerance", gradient_tolerance),
            ("relaxation", relaxation),
            ("stationarity_tolerance", stationarity_tolerance),
        ):
            if value is not None:
                setattr(options, name, float(value))

        raised, _callback = _attach_progress(options, progress)
        report = _capi.RelocateReport()
        status = self._lib.igaparam_mesh_relocate(self._h(), ctypes.byref(options), ctypes.byref(report))
        if raised:
            raise raised[0]
        _check(status)
        return RelocateReport._from_c(report)

    def _product(self, function, values, name):
        xyz = _as_xyz(values, name)
        if xyz.shape[0] != self.node_count:
            raise ValueError(f"{name} has {xyz.shape[0]} rows, expected one per node ({self.node_count})")
        out = np.empty((self.node_count, 3), dtype=np.float64)
        _check(function(self._h(), xyz.size, _ptr(xyz, ctypes.c_double), _ptr(out, ctypes.c_double)))
        return out

    def adjoint(self, dj_dx: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The total derivative of a scalar J of the node positions with respect to the prescribed
        coordinates, through the last relocation (``igaparam_mesh_adjoint``).

        Args:
            dj_dx: (n, 3) partial derivatives of J with respect to every node coordinate.

        Returns:
            (n, 3) float64: dJ/dx_p at the prescribed coordinates, 0 at the free ones.

        Needs a last relocation with ``stationarity_tolerance > 0`` that reached it, and no move,
        constraint or reference change since; else IgaparamError says why.
        """
        return self._product(self._lib.igaparam_mesh_adjoint, dj_dx, "dj_dx")

    def tangent(self, dx_prescribed: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The first-order motion of every node for a motion of the prescribed coordinates, through
        the last relocation (``igaparam_mesh_tangent``, the transpose of :meth:`adjoint`).

        Args:
            dx_prescribed: (n, 3) motion; entries at free coordinates are ignored.

        Returns:
            (n, 3) float64 motion of every node.
        """
        return self._product(self._lib.igaparam_mesh_tangent, dx_prescribed, "dx_prescribed")

    # Arrays copied out.

    def _copy_xyz(self, function):
        out = np.empty((self.node_count, 3), dtype=np.float64)
        _check(function(self._h(), _ptr(out, ctypes.c_double), out.size))
        return out

    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """Current node positions, a new float64 array of shape (n, 3)."""
        return self._copy_xyz(self._lib.igaparam_mesh_copy_positions)

    @property
    def reference(self) -> npt.NDArray[np.float64]:
        """Reference positions (the shape the targets are taken from), shape (n, 3)."""
        return self._copy_xyz(self._lib.igaparam_mesh_copy_reference)

    @property
    def fixed(self) -> npt.NDArray[np.uint8]:
        """Constraint mask of every node (see :meth:`set_fixed`), a new uint8 array of shape (n,)."""
        out = np.empty(self.node_count, dtype=np.uint8)
        _check(self._lib.igaparam_mesh_copy_fixed(self._h(), _ptr(out, ctypes.c_uint8), out.size))
        return out

    def cell_quality(self, target: str = "initial") -> npt.NDArray[np.float64]:
        """Quality of every cell against ``target`` ('initial' or 'master'): float64 array of
        shape (m,), in (0, 1], 0 for a cell with det J <= 0 somewhere."""
        code = _option_code(target, _TARGETS, "target")
        out = np.empty(self.cell_count, dtype=np.float64)
        _check(self._lib.igaparam_mesh_copy_cell_quality(self._h(), code, _ptr(out, ctypes.c_double), out.size))
        return out
