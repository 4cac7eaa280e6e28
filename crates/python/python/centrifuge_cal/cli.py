"""The ``centrifuge-cal`` console script: the command line of ``cargo xtask`` (the ``cli``
crate), run inside the Python process."""

from __future__ import annotations

import sys


def main() -> int:
    """Runs the command line with ``sys.argv``; returns its exit status (0 success, 1 an
    error, 2 a usage error, 141 standard output closed by its reader)."""
    from . import _native

    sys.stdout.flush()
    sys.stderr.flush()
    return _native.cli_main(sys.argv)


if __name__ == "__main__":
    raise SystemExit(main())
