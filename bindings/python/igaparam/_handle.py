"""The base of the classes that own a C handle: release, context manager, closed state."""

from typing import Any


class _Handle:
    """Owns a C handle ``self._handle`` of library ``self._lib``, released by the C function named
    ``_free``; ``_kind`` names the object in messages."""

    _kind = "handle"
    _free = ""
    _lib: Any
    _handle: Any

    def close(self) -> None:
        """Releases the handle; the object is unusable afterwards. Calling it again does nothing."""
        handle, self._handle = getattr(self, "_handle", None), None
        if handle is not None:
            getattr(self._lib, self._free)(handle)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    @property
    def closed(self) -> bool:
        """True once :meth:`close` was called."""
        return self._handle is None

    def _h(self):
        if self._handle is None:
            raise ValueError(f"the {self._kind} is closed")
        return self._handle
