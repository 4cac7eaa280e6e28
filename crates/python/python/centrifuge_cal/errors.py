"""The package's exceptions: one base class, :class:`CentrifugeCalError`.

Each carries the command line's message (what ``cargo xtask`` prints after ``error:``) and,
as attributes, what the error locates: ``file``, ``line`` (1-based), ``field`` (a field of
a configuration, or an argument's name) and ``hint`` (what to change), ``None`` where the
error does not name one.
"""

from __future__ import annotations


class CentrifugeCalError(Exception):
    """Base class of every error this package raises."""

    message: str
    file: str | None
    line: int | None
    field: str | None
    hint: str | None

    def __init__(
        self,
        message: str,
        *,
        file: str | None = None,
        line: int | None = None,
        field: str | None = None,
        hint: str | None = None,
    ) -> None:
        super().__init__(message)
        self.message = message
        self.file = file
        self.line = line
        self.field = field
        self.hint = hint

    def __str__(self) -> str:
        return self.message


class InputError(CentrifugeCalError, ValueError):
    """A bad argument: an array of the wrong length, shape or dtype, a NaN, time that does
    not increase, a value out of range."""


class RecordingError(CentrifugeCalError):
    """A recording that cannot be read, or whose samples cannot be analysed."""


class ConfigError(CentrifugeCalError):
    """A study, plan or format description refused (an unknown key, a missing field, a
    value out of range, a file named that cannot be read)."""


class ComputationError(CentrifugeCalError):
    """A computation that cannot give a trustworthy number (an ill-conditioned fit, a
    non-finite result)."""


__all__ = [
    "CentrifugeCalError",
    "InputError",
    "RecordingError",
    "ConfigError",
    "ComputationError",
]
