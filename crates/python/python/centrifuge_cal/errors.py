"""The package's exceptions and warning class, created by the native module (Rust).

Every error is a :class:`CentrifugeCalError`: its ``message`` is the command line's (what
``cargo xtask`` prints after ``error:``); ``file``, ``line`` (1-based), ``field`` (a field
of a configuration, or an argument's name) and ``hint`` (what to change) are what the error
locates, set from the Rust error's own fields, ``None`` where it names none.

:class:`CentrifugeCalWarning` (a ``UserWarning``) is issued through :mod:`warnings` for
each warning a result carries (a gap implausible for its unit, a drift not fitted, a fit
worse than its noise), with results.json's ``code`` at the start of its text.
"""

from __future__ import annotations

from ._native import (
    CentrifugeCalError,
    CentrifugeCalWarning,
    ComputationError,
    ConfigError,
    InputError,
    RecordingError,
)


def _error(
    cls: type[CentrifugeCalError],
    message: str,
    *,
    field: str | None = None,
    file: str | None = None,
    line: int | None = None,
    hint: str | None = None,
) -> CentrifugeCalError:
    """An error of ``cls`` with what it locates (the classes take one argument, the
    message; the package sets the rest)."""
    e = cls(message)
    e.field = field
    e.file = file
    e.line = line
    e.hint = hint
    return e


__all__ = [
    "CentrifugeCalError",
    "CentrifugeCalWarning",
    "InputError",
    "RecordingError",
    "ConfigError",
    "ComputationError",
]
