"""Checks of what a caller hands over: arrays (1-D float64, contiguous, in native byte
order) and scalars, each refused with :class:`InputError` naming the argument."""

from __future__ import annotations

import math
import operator
import reprlib
from typing import Any

import numpy as np
import numpy.typing as npt

from .errors import InputError, _error

FloatArray = npt.NDArray[np.float64]

#: The largest integer a float64 holds exactly: integer arrays beyond it are refused
#: rather than rounded.
_EXACT_INTEGER = 2**53


_SHOW = reprlib.Repr()
_SHOW.maxlevel, _SHOW.maxstring, _SHOW.maxother, _SHOW.maxlist, _SHOW.maxdict = 2, 40, 40, 4, 4


def show(value: Any) -> str:
    """A short, safe repr of what a caller gave (a deep or self-holding structure too)."""
    try:
        return _SHOW.repr(value)
    except Exception:  # noqa: BLE001 - an object whose repr raises is still named
        return f"a {type(value).__name__}"


def _refuse(name: str, message: str) -> InputError:
    e = _error(InputError, f"{name}: {message}", field=name)
    assert isinstance(e, InputError)
    return e


def samples(name: str, values: Any, *, length: int | None = None) -> FloatArray:
    """``values`` as a contiguous 1-D float64 array in native byte order, without a copy
    when it already is one.

    Accepted: float64 arrays in either byte order (big-endian ones are converted), lists
    and tuples of numbers, and integer arrays or lists whose values a float64 holds
    exactly. Refused with :class:`InputError` naming ``name``: a masked array (its masked
    values would be read as numbers), ``None``, text, a dict, a boolean, complex, object
    or lower-precision float dtype, anything but one dimension, and a length other than
    ``length``.
    """
    if isinstance(values, np.ma.MaskedArray):
        raise _refuse(
            name,
            "a masked array: its masked values would be read as numbers; give the samples "
            f"to use ({name}.compressed(), with the other arrays cut alike) or fill them",
        )
    if values is None or isinstance(values, (str, bytes, dict, set)):
        raise _refuse(
            name, f"a {type(values).__name__} is not an array of numbers; give a 1-D float64 array"
        )
    try:
        array = np.asarray(values)
    except (ValueError, TypeError, OverflowError, RecursionError) as e:
        raise _refuse(name, f"not an array of numbers ({show(str(e))})") from e
    kind = array.dtype.kind
    if kind in "iu":
        if array.size and int(np.max(np.abs(array.astype(np.float64)))) > _EXACT_INTEGER:
            raise _refuse(name, "integers beyond 2⁵³, which a float64 does not hold exactly")
        array = array.astype(np.float64)
    elif kind == "f" and array.dtype.itemsize == 8:
        if not array.dtype.isnative:
            array = array.astype(np.float64)
    else:
        what = {
            "b": "a boolean",
            "c": "a complex",
            "O": "an object",
            "U": "a string",
            "S": "a bytes",
            "f": "a lower-precision float",
        }.get(kind, "a")
        raise _refuse(
            name,
            f"{what} array (dtype {array.dtype}); float64 is needed "
            f"(convert with {name}.astype(numpy.float64) if the values are right)",
        )
    if array.ndim != 1:
        raise _refuse(name, f"a 1-D array is needed, this one has shape {array.shape}")
    if length is not None and array.shape[0] != length:
        raise _refuse(name, f"{array.shape[0]} values, {length} expected (one per rate or sample)")
    return np.ascontiguousarray(array)


def finite(name: str, array: FloatArray) -> None:
    """Raises :class:`InputError` naming the first NaN or infinite value of ``array``."""
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        i = int(bad[0])
        raise _error(
            InputError,
            f"{name}[{i}] is not finite ({array[i]}); {bad.size} such value(s)",
            field=name,
        )


def number(name: str, value: Any) -> float:
    """A finite real number (an int, a float or a numpy number; not a bool)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(
        value, (int, float, np.integer, np.floating)
    ):
        raise _refuse(name, f"{show(value)} is not a number")
    try:
        x = float(value)
    except OverflowError as e:
        raise _refuse(name, "too large for a float64") from e
    if not math.isfinite(x):
        raise _refuse(name, f"{x} is not finite")
    return x


def count(name: str, value: Any, *, minimum: int = 0, maximum: int = 2**64 - 1) -> int:
    """A whole number within ``minimum``…``maximum`` (an int or numpy integer; not a bool)."""
    if isinstance(value, (bool, np.bool_)):
        raise _refuse(name, f"{show(value)} is not a whole number")
    try:
        n = operator.index(value)
    except TypeError as e:
        raise _refuse(name, f"{show(value)} is not a whole number") from e
    if not minimum <= n <= maximum:
        raise _refuse(name, f"{n:.6g} is outside {minimum}…{maximum}")
    return n


def optional_count(name: str, value: Any, *, minimum: int = 0) -> int | None:
    """``None``, or a whole number of at least ``minimum``."""
    return None if value is None else count(name, value, minimum=minimum)


def flag(name: str, value: Any) -> bool:
    """A bool (or numpy bool)."""
    if not isinstance(value, (bool, np.bool_)):
        raise _refuse(name, f"{show(value)} is not True or False")
    return bool(value)


def text(name: str, value: Any) -> str:
    """A str."""
    if not isinstance(value, str):
        raise _refuse(name, f"{show(value)} is not a string")
    return value
