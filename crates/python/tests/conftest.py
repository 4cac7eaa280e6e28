"""Shared helpers: the repository root, the command line, and a synthetic recording."""

from __future__ import annotations

import os
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

ROOT = Path(__file__).resolve().parents[3]


@dataclass
class Cli:
    status: int
    stdout: str
    stderr: str


def xtask(*args: str) -> Cli:
    """Runs ``cargo xtask ARGS`` in the repository (the command line the package must
    agree with). Without cargo the test fails, unless CENTRIFUGE_CAL_NO_CARGO is set, when
    it is skipped (a wheel tested away from the sources)."""
    if shutil.which("cargo") is None:
        if os.environ.get("CENTRIFUGE_CAL_NO_CARGO"):
            pytest.skip("no cargo: the command line cannot be compared")
        pytest.fail("cargo is needed to compare with the command line")
    p = subprocess.run(
        ["cargo", "xtask", *args], cwd=ROOT, capture_output=True, text=True, check=False
    )
    return Cli(p.returncode, p.stdout, p.stderr)


def cli_error(cli: Cli) -> str:
    """The command line's error message: its last line of standard error after
    ``error: ``."""
    assert cli.status == 1, cli.stderr
    line = [ln for ln in cli.stderr.splitlines() if ln.startswith("error: ")][-1]
    return line[len("error: ") :]


@dataclass
class Synthetic:
    time_s: npt.NDArray[np.float64]
    gap: npt.NDArray[np.float64]
    angle_rad: npt.NDArray[np.float64]
    rate_deg_s: float
    l0: float
    c: tuple[float, ...]
    s: tuple[float, ...]


def synthetic(
    *, rate_deg_s: float = 120.0, rate_hz: float = 1000.0, turns: float = 8.3, noise: float = 0.0, seed: int = 1
) -> Synthetic:
    """Eq. 20 with known coefficients (µm), sampled at ``rate_hz`` for ``turns`` turns;
    the angle starts at 0 and is returned wrapped to [0, 2π) as an encoder gives it."""
    w = np.radians(rate_deg_s)
    n = int(turns * 2 * np.pi / w * rate_hz)
    t = np.arange(n) / rate_hz
    theta = w * t
    l0, c, s = 47.3, (-3.2385, 0.21, -0.05, 0.012), (-1.1406, 0.33, 0.02, -0.007)
    gap = np.full(n, l0)
    for k in range(4):
        gap += c[k] * np.cos((k + 1) * theta) + s[k] * np.sin((k + 1) * theta)
    if noise:
        gap += np.random.default_rng(seed).normal(0.0, noise, n)
    return Synthetic(t, gap, np.mod(theta, 2 * np.pi), rate_deg_s, l0, c, s)
