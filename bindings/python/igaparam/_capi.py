"""The loaded C library and the names the package uses from its declarations.

The declarations (enums, structs, callback types, constants and prototypes) are generated from
``include/igaparam.h`` into :mod:`igaparam._ffi`; this module loads the library, gives every
function its ``argtypes``/``restype``/docstring from there, and refuses a library built from
other declarations. Use :mod:`igaparam` rather than this module.
"""

import ctypes
import ctypes.util
import enum
import os
import sys

from . import _ffi
from ._ffi import *  # noqa: F401,F403  (the generated declarations, re-exported)

__all__ = [name for name in dir(_ffi) if not name.startswith("_") and name not in ("ctypes", "enum")]
__all__ += ["CellType", "FitChoice", "load_library", "library"]


class CellType(enum.IntEnum):
    """``IGAPARAM_CELL_*``: the supported cell types (VTK cell type codes)."""

    Q4 = _ffi.CELL_QUAD4
    Q8 = _ffi.CELL_QUAD8
    Q9 = _ffi.CELL_QUAD9
    H8 = _ffi.CELL_HEX8
    H20 = _ffi.CELL_HEX20
    H27 = _ffi.CELL_HEX27


class FitChoice(enum.IntEnum):
    """``IGAPARAM_FIT_CHOICE_*``: which fit rule :meth:`Spline.fit` uses."""

    BEST = _ffi.FIT_CHOICE_BEST
    INTERPOLATION = _ffi.FIT_CHOICE_INTERPOLATION
    QUASI_INTERPOLATION = _ffi.FIT_CHOICE_QUASI_INTERPOLATION


# name: (restype, argtypes) of every function of the header.
_PROTOTYPES = {name: (restype, argtypes) for name, (restype, argtypes, _) in _ffi.PROTOTYPES.items()}


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
        problem = _fingerprint_problem(lib, candidate)
        if problem:
            errors.append(problem)
            continue
        for name, (restype, argtypes, doc) in _ffi.PROTOTYPES.items():
            function = getattr(lib, name)
            function.restype = restype
            function.argtypes = argtypes
            function.__doc__ = doc
        return lib
    if explicit:
        raise OSError(f"igaparam: cannot load IGAPARAM_LIBRARY: {'; '.join(errors)}")
    tried = "; ".join(errors) if errors else "no candidate found"
    raise OSError(
        "igaparam: the shared library libigaparam was not found (set IGAPARAM_LIBRARY to its path, "
        f"or put it next to the igaparam package or on the loader's path): {tried}"
    )


def _fingerprint_problem(lib, path):
    """Why ``lib`` cannot be used with this package's declarations, or ``None`` if it can."""
    try:
        function = lib.igaparam_abi_fingerprint
    except AttributeError:
        found = None
    else:
        function.restype = ctypes.c_uint64
        function.argtypes = []
        found = function()
    if found == _ffi.ABI_FINGERPRINT:
        return None
    reported = "none" if found is None else f"{found:#018x}"
    return (
        f"{path} was built from other C declarations than this package (its ABI fingerprint is "
        f"{reported}, the package's {_ffi.ABI_FINGERPRINT:#018x}): install the package and the "
        "library from the same build, or point IGAPARAM_LIBRARY at the matching library"
    )


_library = None


def library():
    """The loaded library (loaded on first use)."""
    global _library
    if _library is None:
        _library = load_library()
    return _library
