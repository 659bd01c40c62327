"""Low-level ctypes declarations of the C API in ``include/igaparam.h``.

The structures mirror the C structs field by field (same order and types); the functions get
their ``argtypes``/``restype`` from the header's prototypes. Use :mod:`igaparam` rather than
this module.
"""

import ctypes
import ctypes.util
import enum
import os
import sys

__all__ = [
    "Status",
    "Stage",
    "CellType",
    "RelocateOptions",
    "RelocateReport",
    "DomainOptions",
    "DomainReport",
    "Curve",
    "Surface",
    "DomainUpdateOptions",
    "DomainUpdateReport",
    "FitRule",
    "RefitReport",
    "ValidityOptions",
    "FitReport",
    "FitChoice",
    "FitOptions",
    "ValidityReport",
    "HISTOGRAM_BINS",
    "PROGRESS_FN",
    "load_library",
    "library",
]


class Status(enum.IntEnum):
    """``igaparam_status``: 0 is success, every other value comes with a message."""

    OK = 0
    NULL_ARGUMENT = 1
    INVALID_ARGUMENT = 2
    NOT_FINITE = 3
    INVALID_MESH = 4
    BUFFER_TOO_SMALL = 5
    CANCELLED = 6
    IO = 7
    INTERNAL = 8
    BUSY = 9
    LIMIT_EXCEEDED = 10


class Stage(enum.IntEnum):
    """``igaparam_stage``: a stage of long work, passed to the progress callback."""

    PLACEMENT = 0
    OPTIMIZATION = 1
    ADAPTATION = 2
    STATIONARITY = 3
    FIT = 4
    UNTANGLING = 5
    SMOOTHING = 6


class CellType(enum.IntEnum):
    """``IGAPARAM_CELL_*``: the supported cell types (VTK cell type codes)."""

    Q4 = 9
    Q8 = 23
    Q9 = 28
    H8 = 12
    H20 = 25
    H27 = 29


TARGET_INITIAL = 0
TARGET_MASTER = 1
PLACEMENT_LAPLACIAN = 0
PLACEMENT_CURRENT = 1
PLACEMENT_INCREMENTAL = 2
# IGAPARAM_METHOD_*: how relocation reaches the optimum.
METHOD_AUTO = 0
METHOD_SWEEPS = 1
METHOD_NEWTON = 2
# IGAPARAM_VTU_*: storages of written .vtu files; ZLIB is a flag for the binary ones.
VTU_ASCII = 0
VTU_BINARY = 1
VTU_APPENDED = 2
VTU_APPENDED_BASE64 = 3
VTU_ZLIB = 16
# IGAPARAM_ORDER_*: local node orders of connectivity arrays.
ORDER_VTK = 0
ORDER_GMSH = 1

# int (*igaparam_progress_fn)(void *user, igaparam_stage stage, size_t done, size_t total)
PROGRESS_FN = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_int, ctypes.c_size_t, ctypes.c_size_t)


class RelocateOptions(ctypes.Structure):
    """``igaparam_relocate_options``."""

    _fields_ = [
        ("target", ctypes.c_int),  # igaparam_target
        ("placement", ctypes.c_int),  # igaparam_placement
        ("optimize", ctypes.c_int),
        ("max_sweeps", ctypes.c_uint32),
        ("move_tolerance", ctypes.c_double),
        ("gradient_tolerance", ctypes.c_double),
        ("max_newton_iterations", ctypes.c_uint32),
        ("relaxation", ctypes.c_double),
        ("threads", ctypes.c_uint32),
        ("stationarity_tolerance", ctypes.c_double),
        ("method", ctypes.c_int),  # igaparam_method
        ("progress", PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
    ]


class RelocateReport(ctypes.Structure):
    """``igaparam_relocate_report``."""

    _fields_ = [
        ("cells", ctypes.c_size_t),
        ("nodes", ctypes.c_size_t),
        ("free_nodes", ctypes.c_size_t),
        ("invalid_before", ctypes.c_size_t),
        ("invalid_after_placement", ctypes.c_size_t),
        ("invalid_after", ctypes.c_size_t),
        ("min_quality", ctypes.c_double),
        ("mean_quality", ctypes.c_double),
        ("sweeps", ctypes.c_uint32),
        ("steps", ctypes.c_uint32),
        ("converged", ctypes.c_int),
        ("gradient_norm", ctypes.c_double),
        ("newton_iterations", ctypes.c_uint32),
        ("seconds", ctypes.c_double),
    ]


class DomainOptions(ctypes.Structure):
    """``igaparam_domain_options``."""

    _fields_ = [
        ("tolerance", ctypes.c_double),
        ("min_level", ctypes.c_uint32),
        ("max_level", ctypes.c_uint32),
        ("max_sweeps", ctypes.c_uint32),
        ("max_total_sweeps", ctypes.c_uint32),
        ("threads", ctypes.c_uint32),
        ("repair_rounds", ctypes.c_uint32),
        ("boundary_offset", ctypes.c_double),
        ("max_cells", ctypes.c_size_t),
        ("stationarity_tolerance", ctypes.c_double),
        ("progress", PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
    ]


class DomainReport(ctypes.Structure):
    """``igaparam_domain_report``."""

    _fields_ = [
        ("cells", ctypes.c_size_t),
        ("vertices", ctypes.c_size_t),
        ("max_level", ctypes.c_uint32),
        ("boundary_error", ctypes.c_double),
        ("boundary_offset", ctypes.c_double),
        ("invalid_after_placement", ctypes.c_size_t),
        ("invalid_cells", ctypes.c_size_t),
        ("min_quality", ctypes.c_double),
        ("mean_quality", ctypes.c_double),
        ("sweeps", ctypes.c_uint32),
        ("sweep_budget_exhausted", ctypes.c_int),
        ("seconds", ctypes.c_double),
    ]


class Curve(ctypes.Structure):
    """``igaparam_curve``: a B-spline or NURBS curve of the plane by its arrays."""

    _fields_ = [
        ("degree", ctypes.c_uint32),
        ("knot_count", ctypes.c_size_t),
        ("knots", ctypes.POINTER(ctypes.c_double)),
        ("control_point_count", ctypes.c_size_t),
        ("control_points", ctypes.POINTER(ctypes.c_double)),
        ("weights", ctypes.POINTER(ctypes.c_double)),
    ]


class Surface(ctypes.Structure):
    """``igaparam_surface``: a tensor-product B-spline or NURBS surface in 3D by its arrays."""

    _fields_ = [
        ("degree_u", ctypes.c_uint32),
        ("degree_v", ctypes.c_uint32),
        ("knot_count_u", ctypes.c_size_t),
        ("knots_u", ctypes.POINTER(ctypes.c_double)),
        ("knot_count_v", ctypes.c_size_t),
        ("knots_v", ctypes.POINTER(ctypes.c_double)),
        ("control_point_count_u", ctypes.c_size_t),
        ("control_point_count_v", ctypes.c_size_t),
        ("control_points", ctypes.POINTER(ctypes.c_double)),
        ("weights", ctypes.POINTER(ctypes.c_double)),
    ]


class DomainUpdateOptions(ctypes.Structure):
    """``igaparam_domain_update_options``."""

    _fields_ = [
        ("max_sweeps", ctypes.c_uint32),
        ("threads", ctypes.c_uint32),
        ("refine", ctypes.c_int32),
        ("progress", PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
    ]


class DomainUpdateReport(ctypes.Structure):
    """``igaparam_domain_update_report``."""

    _fields_ = [
        ("domain", DomainReport),
        ("tolerance_met", ctypes.c_int32),
        ("cells_over_tolerance", ctypes.c_size_t),
        ("refined_cells", ctypes.c_size_t),
        ("boundary_motion", ctypes.c_double),
        ("steps", ctypes.c_uint32),
    ]


# IGAPARAM_HISTOGRAM_BINS: bins of the quality histogram of igaparam_validity_report.
HISTOGRAM_BINS = 10


class ValidityOptions(ctypes.Structure):
    """``igaparam_validity_options``."""

    _fields_ = [
        ("max_depth", ctypes.c_uint32),
        ("samples", ctypes.c_uint32),
    ]


class FitReport(ctypes.Structure):
    """``igaparam_fit_report``."""

    _fields_ = [
        ("basis_count", ctypes.c_size_t),
        ("element_count", ctypes.c_size_t),
        ("residual", ctypes.c_double),
        ("least_squares", ctypes.c_int32),
        ("quasi_interpolation", ctypes.c_int32),
        ("untangled", ctypes.c_size_t),
        ("boundary_offset", ctypes.c_double),
        ("seconds", ctypes.c_double),
        ("smoothed", ctypes.c_size_t),
    ]


class FitChoice(enum.IntEnum):
    """``IGAPARAM_FIT_CHOICE_*``: which fit rule :meth:`Spline.fit` uses."""

    BEST = 0
    INTERPOLATION = 1
    QUASI_INTERPOLATION = 2


class FitOptions(ctypes.Structure):
    """``igaparam_fit_options``."""

    _fields_ = [
        ("choice", ctypes.c_int),  # igaparam_fit_choice
        ("validity", ValidityOptions),
        ("untangle_rounds", ctypes.c_uint32),
        ("untangle_sweeps", ctypes.c_uint32),
        ("boundary_offset", ctypes.c_double),
        ("smoothing_sweeps", ctypes.c_uint32),
        ("threads", ctypes.c_uint32),
        ("progress", PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
    ]


class FitRule(enum.IntEnum):
    """``igaparam_fit_rule``: how the control points of a spline come from the T-mesh's map."""

    INTERPOLATION = 0
    LEAST_SQUARES = 1
    QUASI_INTERPOLATION = 2


class RefitReport(ctypes.Structure):
    """``igaparam_refit_report``."""

    _fields_ = [
        ("fit", FitReport),
        ("rule", ctypes.c_int),  # igaparam_fit_rule
        ("corrected", ctypes.c_size_t),
        ("certified_positive", ctypes.c_int32),
        ("uncertified", ctypes.c_size_t),
        ("min_quality", ctypes.c_double),
        ("mean_quality", ctypes.c_double),
    ]


class AdaptOptions(ctypes.Structure):
    """``igaparam_adapt_options``."""

    _fields_ = [
        ("target_quality", ctypes.c_double),
        ("max_rounds", ctypes.c_uint32),
        ("max_level", ctypes.c_uint32),
        ("max_sweeps", ctypes.c_uint32),
        ("threads", ctypes.c_uint32),
        ("progress", PROGRESS_FN),
        ("progress_user", ctypes.c_void_p),
    ]


class AdaptReport(ctypes.Structure):
    """``igaparam_adapt_report``."""

    _fields_ = [
        ("rounds", ctypes.c_uint32),
        ("reached", ctypes.c_int32),
        ("refined_cells", ctypes.c_size_t),
        ("elements", ctypes.c_size_t),
        ("basis", ctypes.c_size_t),
        ("certified_positive", ctypes.c_int32),
        ("min_quality", ctypes.c_double),
        ("mean_quality", ctypes.c_double),
        ("seconds", ctypes.c_double),
        ("untangled", ctypes.c_size_t),
        ("boundary_offset", ctypes.c_double),
    ]


class QualityBoundOptions(ctypes.Structure):
    """``igaparam_quality_bound_options``."""

    _fields_ = [
        ("max_depth", ctypes.c_uint32),
        ("samples", ctypes.c_uint32),
        ("gap", ctypes.c_double),
    ]


class QualityBoundReport(ctypes.Structure):
    """``igaparam_quality_bound_report``."""

    _fields_ = [
        ("lower_bound", ctypes.c_double),
        ("sampled_min", ctypes.c_double),
        ("element", ctypes.c_size_t),
    ]


class ValidityReport(ctypes.Structure):
    """``igaparam_validity_report``."""

    _fields_ = [
        ("certified_positive", ctypes.c_int32),
        ("uncertified", ctypes.c_size_t),
        ("det_lower_bound", ctypes.c_double),
        ("min_quality", ctypes.c_double),
        ("mean_quality", ctypes.c_double),
        ("histogram", ctypes.c_size_t * HISTOGRAM_BINS),
    ]


_mesh_p = ctypes.c_void_p  # igaparam_mesh * (opaque)
_domain_p = ctypes.c_void_p  # igaparam_domain * (opaque)
_spline_p = ctypes.c_void_p  # igaparam_spline * (opaque)
_status = ctypes.c_int
_size_p = ctypes.POINTER(ctypes.c_size_t)
_double_p = ctypes.POINTER(ctypes.c_double)
_int64_p = ctypes.POINTER(ctypes.c_int64)
_uint8_p = ctypes.POINTER(ctypes.c_uint8)
_int32_p = ctypes.POINTER(ctypes.c_int32)
_uint32_p = ctypes.POINTER(ctypes.c_uint32)

# name: (restype, argtypes)
_PROTOTYPES = {
    "igaparam_last_error_message": (ctypes.c_size_t, [ctypes.c_char_p, ctypes.c_size_t]),
    "igaparam_version": (ctypes.c_char_p, []),
    "igaparam_relocate_options_default": (RelocateOptions, []),
    "igaparam_mesh_new": (
        _status,
        [ctypes.c_int, ctypes.c_size_t, _double_p, ctypes.c_size_t, _int64_p, ctypes.POINTER(_mesh_p)],
    ),
    "igaparam_mesh_free": (None, [_mesh_p]),
    "igaparam_mesh_node_count": (_status, [_mesh_p, _size_p]),
    "igaparam_mesh_cell_count": (_status, [_mesh_p, _size_p]),
    "igaparam_mesh_dimension": (_status, [_mesh_p, ctypes.POINTER(ctypes.c_int)]),
    "igaparam_mesh_set_fixed": (_status, [_mesh_p, ctypes.c_size_t, _uint8_p]),
    "igaparam_mesh_move_nodes": (_status, [_mesh_p, ctypes.c_size_t, _int64_p, _double_p]),
    "igaparam_mesh_reset_reference": (_status, [_mesh_p]),
    "igaparam_mesh_relocate": (
        _status,
        [_mesh_p, ctypes.POINTER(RelocateOptions), ctypes.POINTER(RelocateReport)],
    ),
    "igaparam_mesh_copy_positions": (_status, [_mesh_p, _double_p, ctypes.c_size_t]),
    "igaparam_mesh_copy_cell_quality": (_status, [_mesh_p, ctypes.c_int, _double_p, ctypes.c_size_t]),
    "igaparam_mesh_copy_reference": (_status, [_mesh_p, _double_p, ctypes.c_size_t]),
    "igaparam_mesh_copy_fixed": (_status, [_mesh_p, _uint8_p, ctypes.c_size_t]),
    "igaparam_cell_type_node_count": (_status, [ctypes.c_int, _size_p]),
    "igaparam_mesh_invalid_cell_count": (_status, [_mesh_p, _size_p]),
    "igaparam_mesh_adjoint": (_status, [_mesh_p, ctypes.c_size_t, _double_p, _double_p]),
    "igaparam_mesh_tangent": (_status, [_mesh_p, ctypes.c_size_t, _double_p, _double_p]),
    "igaparam_mesh_read_vtu": (_status, [ctypes.c_char_p, ctypes.POINTER(_mesh_p)]),
    "igaparam_mesh_write_vtu": (_status, [_mesh_p, ctypes.c_char_p]),
    "igaparam_mesh_write_vtu_format": (_status, [_mesh_p, ctypes.c_char_p, ctypes.c_int]),
    "igaparam_mesh_cell_type": (_status, [_mesh_p, ctypes.POINTER(ctypes.c_int)]),
    "igaparam_mesh_new_ordered": (
        _status,
        [ctypes.c_int, ctypes.c_int, ctypes.c_size_t, _double_p, ctypes.c_size_t, _int64_p, ctypes.POINTER(_mesh_p)],
    ),
    "igaparam_mesh_order": (_status, [_mesh_p, ctypes.POINTER(ctypes.c_int)]),
    "igaparam_mesh_copy_connectivity": (_status, [_mesh_p, ctypes.c_int, _int64_p, ctypes.c_size_t]),
    "igaparam_cell_type_copy_node_coordinates": (_status, [ctypes.c_int, ctypes.c_int, _double_p, ctypes.c_size_t]),
    "igaparam_domain_options_default": (DomainOptions, []),
    "igaparam_domain_options_default_solid": (DomainOptions, []),
    "igaparam_domain_new_from_file": (_status, [ctypes.c_char_p, ctypes.POINTER(_domain_p)]),
    "igaparam_domain_new_from_polylines": (
        _status,
        [_size_p, ctypes.POINTER(_double_p), ctypes.POINTER(_domain_p)],
    ),
    "igaparam_domain_new_solid_from_file": (_status, [ctypes.c_char_p, ctypes.POINTER(_domain_p)]),
    "igaparam_domain_new_solid_from_file_scaled": (
        _status,
        [ctypes.c_char_p, _double_p, ctypes.POINTER(_domain_p)],
    ),
    "igaparam_domain_new_solid_from_triangulations": (
        _status,
        [_size_p, ctypes.POINTER(_double_p), _size_p, ctypes.POINTER(_uint32_p), ctypes.POINTER(_domain_p)],
    ),
    "igaparam_domain_new_from_curves": (
        _status,
        [ctypes.c_size_t, ctypes.POINTER(Curve), ctypes.POINTER(_domain_p)],
    ),
    "igaparam_domain_new_solid_from_surfaces": (
        _status,
        [ctypes.c_size_t, ctypes.POINTER(Surface), ctypes.POINTER(_domain_p)],
    ),
    "igaparam_domain_set_boundary_curves": (_status, [_domain_p, ctypes.c_size_t, ctypes.POINTER(Curve)]),
    "igaparam_domain_set_boundary_polylines": (_status, [_domain_p, _size_p, ctypes.POINTER(_double_p)]),
    "igaparam_domain_set_boundary_surfaces": (_status, [_domain_p, ctypes.c_size_t, ctypes.POINTER(Surface)]),
    "igaparam_domain_set_boundary_triangulations": (
        _status,
        [_domain_p, _size_p, ctypes.POINTER(_double_p), _size_p, ctypes.POINTER(_uint32_p)],
    ),
    "igaparam_domain_set_boundary_from_file": (_status, [_domain_p, ctypes.c_char_p]),
    "igaparam_domain_set_boundary_from_file_scaled": (_status, [_domain_p, ctypes.c_char_p, _double_p]),
    "igaparam_domain_update_options_default": (DomainUpdateOptions, []),
    "igaparam_domain_update": (
        _status,
        [_domain_p, ctypes.POINTER(DomainUpdateOptions), ctypes.POINTER(DomainUpdateReport)],
    ),
    "igaparam_domain_dimension": (_status, [_domain_p, _size_p]),
    "igaparam_domain_free": (None, [_domain_p]),
    "igaparam_domain_build": (
        _status,
        [_domain_p, ctypes.POINTER(DomainOptions), ctypes.POINTER(DomainReport)],
    ),
    "igaparam_domain_vertex_count": (_status, [_domain_p, _size_p]),
    "igaparam_domain_cell_count": (_status, [_domain_p, _size_p]),
    "igaparam_domain_copy_vertices": (_status, [_domain_p, _double_p, _double_p, ctypes.c_size_t]),
    "igaparam_domain_copy_cell_quality": (_status, [_domain_p, _double_p, ctypes.c_size_t]),
    "igaparam_domain_copy_cells": (_status, [_domain_p, _uint8_p, _double_p, ctypes.c_size_t]),
    "igaparam_domain_copy_cell_corners": (_status, [_domain_p, _size_p, ctypes.c_size_t]),
    "igaparam_domain_write_vtu": (_status, [_domain_p, ctypes.c_char_p]),
    "igaparam_domain_is_built": (_status, [_domain_p, ctypes.POINTER(ctypes.c_int)]),
    "igaparam_validity_options_default": (ValidityOptions, []),
    "igaparam_quality_bound_options_default": (QualityBoundOptions, []),
    "igaparam_spline_quality_bound": (
        _status,
        [_spline_p, ctypes.POINTER(QualityBoundOptions), ctypes.POINTER(QualityBoundReport)],
    ),
    "igaparam_spline_fit_domain": (
        _status,
        [_domain_p, ctypes.POINTER(_spline_p), ctypes.POINTER(FitReport)],
    ),
    "igaparam_fit_options_default": (FitOptions, []),
    "igaparam_spline_fit_domain_with": (
        _status,
        [_domain_p, ctypes.POINTER(FitOptions), ctypes.POINTER(_spline_p), ctypes.POINTER(FitReport)],
    ),
    "igaparam_adapt_options_default": (AdaptOptions, []),
    "igaparam_domain_fit_adaptive": (
        _status,
        [_domain_p, ctypes.POINTER(AdaptOptions), ctypes.POINTER(_spline_p), ctypes.POINTER(AdaptReport)],
    ),
    "igaparam_spline_read_gismo": (_status, [ctypes.c_char_p, ctypes.POINTER(_spline_p)]),
    "igaparam_spline_free": (None, [_spline_p]),
    "igaparam_spline_clone": (_status, [_spline_p, ctypes.POINTER(_spline_p)]),
    "igaparam_spline_dimension": (_status, [_spline_p, _size_p]),
    "igaparam_spline_basis_count": (_status, [_spline_p, _size_p]),
    "igaparam_spline_element_count": (_status, [_spline_p, _size_p]),
    "igaparam_spline_copy_control_points": (_status, [_spline_p, _double_p, ctypes.c_size_t]),
    "igaparam_spline_copy_greville_points": (_status, [_spline_p, _double_p, ctypes.c_size_t]),
    "igaparam_spline_copy_elements": (_status, [_spline_p, _uint8_p, _double_p, ctypes.c_size_t]),
    "igaparam_spline_element_function_count": (_status, [_spline_p, ctypes.c_size_t, _size_p]),
    "igaparam_spline_copy_element_extraction": (
        _status,
        [_spline_p, ctypes.c_size_t, _size_p, ctypes.c_size_t, _double_p, ctypes.c_size_t],
    ),
    "igaparam_spline_evaluate": (_status, [_spline_p, ctypes.c_size_t, _double_p, _double_p, _double_p]),
    "igaparam_spline_mean_ratio": (_status, [_spline_p, ctypes.c_size_t, _double_p, _double_p]),
    "igaparam_spline_invert": (
        _status,
        [_spline_p, ctypes.c_size_t, _double_p, ctypes.c_uint32, _double_p, _int32_p],
    ),
    "igaparam_spline_basis_count_at": (_status, [_spline_p, _double_p, _size_p]),
    "igaparam_spline_basis_at": (
        _status,
        [_spline_p, _double_p, _size_p, _size_p, _double_p, _double_p, ctypes.c_size_t],
    ),
    "igaparam_spline_refine": (_status, [_spline_p, ctypes.c_size_t, _size_p, ctypes.POINTER(FitReport)]),
    "igaparam_spline_check_validity": (
        _status,
        [
            _spline_p,
            ctypes.POINTER(ValidityOptions),
            ctypes.POINTER(ValidityReport),
            _double_p,
            _double_p,
            ctypes.c_size_t,
        ],
    ),
    "igaparam_spline_write_vtu": (_status, [_spline_p, ctypes.c_char_p, ctypes.c_uint32]),
    "igaparam_spline_write_gismo": (_status, [_spline_p, ctypes.c_char_p]),
    "igaparam_spline_refit": (_status, [_spline_p, _domain_p, ctypes.POINTER(RefitReport)]),
    "igaparam_spline_fit_rule": (_status, [_spline_p, ctypes.POINTER(ctypes.c_int)]),
}


def _library_file_names():
    if sys.platform == "win32":
        return ["igaparam.dll"]
    if sys.platform == "darwin":
        return ["libigaparam.dylib"]
    return ["libigaparam.so", "libigaparam.so.0"]


def _candidates():
    """Paths or names to try, in order."""
    env = os.environ.get("IGAPARAM_LIBRARY")
    if env:
        # An explicit choice: no fallback, so that a wrong path is reported, not papered over.
        return [env], True
    here = os.path.dirname(os.path.abspath(__file__))
    candidates = [os.path.join(here, name) for name in _library_file_names()]
    candidates = [path for path in candidates if os.path.exists(path)]
    found = ctypes.util.find_library("igaparam")
    if found:
        candidates.append(found)
    return candidates, False


def load_library():
    """Loads the shared library and declares its functions.

    Looks up, in order: the path in the environment variable ``IGAPARAM_LIBRARY``; a library
    file next to this package; ``ctypes.util.find_library("igaparam")``. Raises ``OSError`` if
    none loads.
    """
    candidates, explicit = _candidates()
    errors = []
    for candidate in candidates:
        try:
            lib = ctypes.CDLL(candidate)
        except OSError as error:
            errors.append(f"{candidate}: {error}")
            continue
        for name, (restype, argtypes) in _PROTOTYPES.items():
            function = getattr(lib, name)
            function.restype = restype
            function.argtypes = argtypes
        return lib
    if explicit:
        raise OSError(f"igaparam: cannot load IGAPARAM_LIBRARY: {'; '.join(errors)}")
    tried = "; ".join(errors) if errors else "no candidate found"
    raise OSError(
        "igaparam: the shared library libigaparam was not found (set IGAPARAM_LIBRARY to its path, "
        f"or put it next to the igaparam package or on the loader's path): {tried}"
    )


_library = None


def library():
    """The loaded library (loaded on first use)."""
    global _library
    if _library is None:
        _library = load_library()
    return _library
