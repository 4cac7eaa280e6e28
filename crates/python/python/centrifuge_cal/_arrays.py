"""Checks of the arrays handed to the native code: 1-D, float64, contiguous."""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from .errors import InputError

FloatArray = npt.NDArray[np.float64]


def samples(name: str, values: Any, *, length: int | None = None) -> FloatArray:
    """``values`` as a contiguous 1-D float64 array, without a copy when it already is one.

    Raises :class:`InputError` naming ``name`` for an integer, boolean, complex or object
    dtype, for a float dtype other than float64, for anything but one dimension, and for a
    length other than ``length``.
    """
    array = np.asarray(values)
    if array.dtype != np.float64:
        kind = {
            "i": "an integer",
            "u": "an unsigned integer",
            "b": "a boolean",
            "c": "a complex",
            "O": "an object",
            "U": "a string",
            "S": "a bytes",
            "f": "a lower-precision float",
        }.get(array.dtype.kind, "a")
        raise InputError(
            f"{name}: {kind} array (dtype {array.dtype}); float64 is needed "
            f"(convert with {name}.astype(numpy.float64) if the values are right)",
            field=name,
        )
    if array.ndim != 1:
        raise InputError(
            f"{name}: a 1-D array is needed, this one has shape {array.shape}",
            field=name,
        )
    if length is not None and array.shape[0] != length:
        raise InputError(
            f"{name}: {array.shape[0]} values, {length} expected (one per rate or sample)",
            field=name,
        )
    return np.ascontiguousarray(array)


def finite(name: str, array: FloatArray) -> None:
    """Raises :class:`InputError` naming the first NaN or infinite value of ``array``."""
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        i = int(bad[0])
        raise InputError(
            f"{name}[{i}] is not finite ({array[i]}); {bad.size} such value(s)",
            field=name,
        )
