"""The one check of Python integers bound for C: ctypes wraps an int that does not fit its C
type silently (2**32 becomes 0 in a uint32), so every integer option, field and scalar argument
goes through :func:`c_int_value` first."""

import ctypes
import operator


class IntegerRangeError(OverflowError, ValueError):
    """An integer that does not fit the C type it is bound for (both an OverflowError and a
    ValueError, as callers catch either)."""


def _range(ctype):
    """The smallest and largest values of the ctypes integer type ``ctype``."""
    bits = 8 * ctypes.sizeof(ctype)
    if ctype(-1).value < 0:
        return -(2 ** (bits - 1)), 2 ** (bits - 1) - 1
    return 0, 2**bits - 1


def c_int_value(value, name, ctype, minimum=None):
    """``value`` as an int that fits the ctypes integer type ``ctype`` (and is at least
    ``minimum`` when given).

    Raises:
        TypeError: ``value`` is not an integer (a bool is refused too).
        IntegerRangeError: ``value`` does not fit ``ctype`` (an OverflowError and a
            ValueError).
        ValueError: ``value`` is below ``minimum``.
    """
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        raise TypeError(f"{name} must be an integer, not {type(value).__name__}")
    try:
        value = operator.index(value)
    except TypeError:
        raise TypeError(f"{name} must be an integer, not {type(value).__name__}") from None
    low, high = _range(ctype)
    if minimum is not None and value < minimum:
        raise ValueError(f"{name} must be >= {minimum}, not {value}")
    if not low <= value <= high:
        raise IntegerRangeError(f"{name} = {value} does not fit the C type {ctype.__name__} ({low} to {high})")
    return value


def set_int_fields(struct, minimum=0, **values):
    """Sets the integer fields of the ctypes structure ``struct`` given (not None), each checked
    against its own C type by :func:`c_int_value` (and ``minimum``)."""
    types = dict(type(struct)._fields_)
    for name, value in values.items():
        if value is not None:
            setattr(struct, name, c_int_value(value, name, types[name], minimum))
