"""centrifuge_cal: PIGA calibration on a precision centrifuge, from Python.

The Rust toolkit behind ``cargo xtask``, with numpy arrays in and typed results out:

- :func:`read_recording`: a probe recording (CSV with a format description, NI TDMS, MATLAB
  MAT) into numpy arrays, as the command line reads it;
- :func:`fit_harmonics`: the per-revolution Fourier fit of eq. 20 on arrays;
- :func:`fit_radius_error` and :func:`delta_k2`: C_r from the radius error (eq. 16) and the
  pseudo-second-order term Δk2 = k1·C_r·g/R² (eq. 19);
- :func:`calibrate`: k0…k3 from rates and PIGA outputs (eq. 18), compensated for Δk2, with
  a GUM budget and a Monte Carlo check (JCGM 100/101);
- :func:`advise_balance` and :func:`plan`: the balance advisor and the test planner;
- :func:`run_study`: a whole study from its configuration file or a dict of the same shape,
  returning what ``results.json`` holds;
- :func:`certificate`: the calibration certificate (PDF/A) of a study's results folder.

Units are in the names (``rate_deg_s``, ``radius_error_um``, ``c_r_m_s2``). Errors are
:class:`CentrifugeCalError` subclasses with the command line's message. Long computations
release the GIL. ``docs/PYTHON.md`` in the repository walks through a calibration.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from . import _native
from ._arrays import FloatArray, finite, samples
from .errors import (
    CentrifugeCalError,
    ComputationError,
    ConfigError,
    InputError,
    RecordingError,
)
from .results import (
    BalanceAdvice,
    Coefficients,
    DeltaK2,
    FirstHarmonic,
    HarmonicFit,
    IncompleteRevolution,
    PerRevolution,
    RadiusFit,
    StudyResults,
    Warning,
    _Result,
)

__version__: str = _native.VERSION

PathLike = str | os.PathLike[str]

#: Highest Fourier order fitted by default (the paper's).
DEFAULT_ORDER = 4


class Recording:
    """A probe recording read from a file: ``time_s`` (s), ``gap`` (in ``gap_unit``) and,
    when the spindle's angle was recorded, ``angle_rad`` (rad, an encoder's or interpolated
    index pulses'), as read-only numpy arrays."""

    path: str
    time_s: FloatArray
    gap: FloatArray
    angle_rad: FloatArray | None
    gap_unit: str
    angle_source: str

    def __init__(self, native: _native.NativeRecording) -> None:
        self._native = native
        d = native.arrays()
        self.path = d["path"]
        self.time_s = d["time_s"]
        self.gap = d["gap"]
        self.angle_rad = d["angle_rad"]
        for a in (self.time_s, self.gap, self.angle_rad):
            if a is not None:
                a.flags.writeable = False
        self.gap_unit = d["gap_unit"]
        self.angle_source = d["angle_source"]

    def __len__(self) -> int:
        return int(self.time_s.shape[0])

    def __repr__(self) -> str:
        return (
            f"Recording({self.path!r}, {len(self)} samples, gap in {self.gap_unit}, "
            f"angle from {self.angle_source})"
        )

    def fit_harmonics(
        self,
        *,
        rate_deg_s: float,
        order: int = DEFAULT_ORDER,
        drift: bool = False,
        revolutions: int | None = None,
        probe_along: bool = False,
    ) -> HarmonicFit:
        """Fits eq. 20 to every complete revolution as ``cargo xtask harmonics FILE
        --rate-deg-s W`` does, with its warnings (the format's gap and non-finite sample
        policies apply)."""
        return HarmonicFit._of(
            self._native.analyze(math.radians(rate_deg_s), order, drift, revolutions, probe_along)
        )


def read_recording(
    path: PathLike,
    format: PathLike | dict[str, Any] | None = None,
    *,
    group: str | None = None,
    waveform_time: bool = False,
) -> Recording:
    """Reads a probe recording, choosing the reader by the file's extension: ``.tdms`` (NI
    TDMS), ``.mat`` (MATLAB v5/v7), else delimited text with a header row.

    ``format`` describes the file as a study's ``format: (...)`` does
    (``docs/YOUR-DATA.md``): the path of a RON file, or a dict of the same shape, e.g.
    ``{"delimiter": ";", "decimal": "comma", "time": {"column": "t", "unit": "ms"},
    "angle": {"encoder": {"column": "enc", "unit": {"counts": {"per_rev": 4096}}}}}``.
    For TDMS and MAT files, the format's column names and units name the channels or
    variables; ``group`` is the TDMS group or MAT struct holding them, and
    ``waveform_time`` takes TDMS sample times from the gap channel's waveform properties.
    """
    ron = None
    fmt = None
    if isinstance(format, dict):
        fmt = format
    elif format is not None:
        ron = os.fspath(format)
    return Recording(_native.read_recording(os.fspath(path), ron, fmt, group, waveform_time))


def fit_harmonics(
    time_s: Any,
    gap: Any,
    *,
    rate_deg_s: float,
    angle_rad: Any = None,
    start_angle_deg: float = 0.0,
    order: int = DEFAULT_ORDER,
    drift: bool = False,
    revolutions: int | None = None,
    max_gap_intervals: float = 3.0,
    probe_along: bool = False,
) -> HarmonicFit:
    """Fits eq. 20, ``gap(θ) = l0 + Σ (c_k cos kθ + s_k sin kθ)``, to every complete
    revolution of a probe recording held in arrays, and averages the coefficients.

    ``time_s`` (s, strictly increasing) and ``gap`` (any length unit; the results are in
    it) are 1-D float64 arrays of one length. The angle θ is ``angle_rad`` (the spindle
    encoder, rad, zero at the O1X1 reference; it may wrap) when given, checked against
    ``rate_deg_s`` (within 2 %); else ``θ = ω·(t − t₀) + start_angle_deg`` from the declared
    rate, with the warning ``angle_from_rate``. ``probe_along``: the probe measures along
    O1X1 (sets the sign of β). The GIL is released during the fit; contiguous float64
    arrays are read in place.
    """
    t = samples("time_s", time_s)
    g = samples("gap", gap, length=t.shape[0])
    a = None if angle_rad is None else samples("angle_rad", angle_rad, length=t.shape[0])
    d = _native.fit_harmonics(
        t,
        g,
        a,
        math.radians(rate_deg_s),
        math.radians(start_angle_deg),
        order,
        drift,
        revolutions,
        max_gap_intervals,
        probe_along,
    )
    return HarmonicFit._of(d)


def fit_radius_error(
    rate_deg_s: Any,
    radius_error_um: Any,
    *,
    sigma_um: Any = None,
    model: Literal["two_term", "three_term"] = "two_term",
) -> RadiusFit:
    """Fits the radius error ``Δr(ω) = a + C_r·ω²`` (``three_term``: ``a + b·ω + C_r·ω²``)
    by QR least squares (eq. 16): C_r in m·s² with its standard error from the residuals;
    weighted by ``1/σ`` when ``sigma_um`` is given. Rates in deg/s, radius errors and σ in µm.
    """
    if model not in ("two_term", "three_term"):
        raise InputError(
            f"model: {model!r} is not a radius-error model (two_term or three_term)",
            field="model",
        )
    w = samples("rate_deg_s", rate_deg_s)
    r = samples("radius_error_um", radius_error_um, length=w.shape[0])
    s = None if sigma_um is None else samples("sigma_um", sigma_um, length=w.shape[0])
    for name, x in (("rate_deg_s", w), ("radius_error_um", r), ("sigma_um", s)):
        if x is not None:
            finite(name, x)
    d = _native.fit_radius_error(
        np.radians(w), r * 1e-6, None if s is None else s * 1e-6, model == "three_term"
    )
    return RadiusFit(
        model=d["model"],
        c_r_m_s2=d["c_r_m_s2"],
        c_r_sigma_m_s2=d["c_r_sigma_m_s2"],
        offset_m=d["offset_m"],
        linear_m_s=d["linear_m_s"],
        linear_sigma_m_s=d["linear_sigma_m_s"],
        residuals_m=d["residuals_m"],
        weighted=d["weighted"],
        dof=d["dof"],
        residual_sd=d["residual_sd"],
        condition_number=d["condition_number"],
        warnings=tuple(Warning(**x) for x in d["warnings"]),
        rate_deg_s=w.copy(),
        radius_error_um=r.copy(),
        sigma_um=None if s is None else s.copy(),
    )


def delta_k2(
    *,
    k1_rad_s_g: float,
    c_r_m_s2: float,
    c_r_sigma_m_s2: float,
    radius_m: float,
    g_m_s2: float,
) -> DeltaK2:
    """The pseudo-second-order error Δk2 = k1·C_r·g/R² (eq. 19) and its standard deviation
    |k1·g/R²|·σ(C_r), rad/(s·g²). Only σ(C_r) is propagated."""
    value, sigma = _native.delta_k2(k1_rad_s_g, c_r_m_s2, c_r_sigma_m_s2, radius_m, g_m_s2)
    return DeltaK2(value, sigma)


def run_study(
    config: PathLike | dict[str, Any],
    *,
    base_dir: PathLike | None = None,
) -> StudyResults:
    """Runs a study as ``cargo xtask study --config FILE`` does and returns what its
    ``results.json`` holds (the document; no files are written).

    ``config`` is the path of a study file (RON, ``docs/CONFIGURATION.md``; the result then
    carries ``provenance``: the files' SHA-256) or a dict of the same shape, RON's enum
    variants as one-key dicts (``{"radius_error": [...]}``) and unit variants as strings
    (``"inverse_variance"``). A dict's relative file names are found under ``base_dir``
    (default: the working directory).
    """
    if isinstance(config, dict):
        return _study_dict(config, base_dir, {})
    return StudyResults._of(json.loads(_native.run_study_file(os.fspath(config))))


def certificate(results_dir: PathLike, out: PathLike | None = None) -> str:
    """Writes the calibration certificate of a study's results folder as PDF/A-2b, as
    ``centrifuge-cal certificate RESULTS_DIR --out FILE.pdf`` does, and returns the path
    written.

    ``results_dir`` is the folder a study wrote (holding ``results.json``; the study's
    configuration needs a ``certificate`` section) or that ``results.json``; ``out`` defaults
    to ``certificate.pdf`` in that folder. Raises :class:`ComputationError` when the results
    have no certificate or cannot be read.
    """
    return _native.certificate(
        os.fspath(results_dir), None if out is None else os.fspath(out)
    )


def _study_dict(
    config: dict[str, Any], base_dir: PathLike | None, tables: dict[str, bytes]
) -> StudyResults:
    source = os.path.join(os.fspath(base_dir), "<dict>") if base_dir is not None else "<dict>"
    text = _native.run_study_dict(config, source, tables)
    return StudyResults._of(json.loads(text))


@dataclass(frozen=True)
class Calibration(_Result):
    """A calibration of k0…k3 (eq. 18) compensated for Δk2 (eq. 19): ``calibration`` is
    results.json's ``calibration`` object (coefficients with u and U95, the GUM budget, the
    Monte Carlo check, the uncompensated fit beside it), ``study`` the whole document."""

    calibration: dict[str, Any]
    study: StudyResults

    def to_dict(self) -> dict[str, Any]:
        return self.calibration


def calibrate(
    rate_deg_s: Any,
    output_rad_s: Any,
    *,
    compensate_with: RadiusFit,
    radius_m: float,
    g_m_s2: float,
    k1_rad_s_g: float,
    pivot_to_probe_mm: float,
    probe_to_piga_mm: float,
    output_sigma_rad_s: Any = None,
    labels: list[str] | None = None,
    k1: Literal["fitted"] | tuple[float, float] = "fitted",
    uncertainty: dict[str, Any] | None = None,
    seed: int = 1,
    trials: Literal["adaptive"] | int = "adaptive",
) -> Calibration:
    """Identifies k0…k3 from the PIGA's mean output at each rate (eq. 18), removes the
    Δk2 of ``compensate_with`` (the radius-error fit of the spindle, whose points become the
    study's compensating phase), and evaluates the uncertainty: a GUM budget and an adaptive
    (or fixed-``trials``) Monte Carlo with ``seed``.

    ``output_sigma_rad_s``: each point's standard uncertainty (the fit is then weighted);
    ``k1``: ``"fitted"`` or ``(k1_rad_s_g, u_rad_s_g)`` given; ``uncertainty``: the Type B
    inputs as a study's ``uncertainty`` section (``radius_u_m``, ``g_u_m_s2``, ``g_source``,
    ``rate_u_relative``, ``pivot_to_probe_u_mm``, ``probe_to_piga_u_mm``,
    ``probe_gain_u_relative``, each required, and ``zero_reasons`` with the reason for each
    zero: nothing is taken as exact without a word). ``radius_m``, ``g_m_s2`` and ``k1_rad_s_g`` are the
    centrifuge's radius, local gravity and the PIGA's nominal scale factor.
    """
    w = samples("rate_deg_s", rate_deg_s)
    y = samples("output_rad_s", output_rad_s, length=w.shape[0])
    s = None if output_sigma_rad_s is None else samples(
        "output_sigma_rad_s", output_sigma_rad_s, length=w.shape[0]
    )
    for name, x in (("rate_deg_s", w), ("output_rad_s", y), ("output_sigma_rad_s", s)):
        if x is not None:
            finite(name, x)
    if labels is not None and len(labels) != w.shape[0]:
        raise InputError(
            f"labels: {len(labels)} labels for {w.shape[0]} rates", field="labels"
        )
    if compensate_with.weighted:
        raise InputError(
            "compensate_with: a weighted radius-error fit; give the phase with its σ as "
            "first-harmonic points to run_study instead",
            field="compensate_with",
        )
    if compensate_with.model != "two_term":
        model = "three_term"
    else:
        model = "two_term"
    header = ["rate_deg_s", "output_rad_s"]
    if s is not None:
        header.append("sigma_rad_s")
    if labels is not None:
        header.append("label")
    rows = [",".join(header)]
    for i in range(w.shape[0]):
        row = [repr(float(w[i])), repr(float(y[i]))]
        if s is not None:
            row.append(repr(float(s[i])))
        if labels is not None:
            label = str(labels[i])
            if any(c in label for c in ',"\n\r#'):
                raise InputError(
                    f"labels[{i}]: {label!r} holds a comma, quote, '#' or line end",
                    field="labels",
                )
            row.append(label)
        rows.append(",".join(row))
    table_path = "<arrays>/piga.csv"
    table: dict[str, Any] = {"file": table_path}
    if s is not None:
        table["sigma_column"] = "sigma_rad_s"
    if labels is not None:
        table["label_column"] = "label"
    k1_config: Any
    if k1 == "fitted":
        k1_config = "fitted"
    else:
        k1_config = {"given": {"k1_rad_s_g": float(k1[0]), "u_rad_s_g": float(k1[1])}}
    config: dict[str, Any] = {
        "name": "calibration",
        "radius_m": radius_m,
        "g_m_s2": g_m_s2,
        "k1_rad_s_g": k1_rad_s_g,
        "lever": {"pivot_to_probe_mm": pivot_to_probe_mm, "probe_to_piga_mm": probe_to_piga_mm},
        "radius_model": model,
        "phases": [
            {
                "name": "spindle",
                "points": {
                    "radius_error": [
                        {"rate_deg_s": float(r), "radius_error_um": float(e)}
                        for r, e in zip(compensate_with.rate_deg_s, compensate_with.radius_error_um)
                    ]
                },
            }
        ],
        "calibration": {
            "table": table,
            "compensate_with": "spindle",
            "k1": k1_config,
            "seed": seed,
            "trials": trials if trials == "adaptive" else {"fixed": int(trials)},
        },
    }
    if uncertainty is not None:
        config["uncertainty"] = uncertainty
    study = _study_dict(config, None, {table_path: ("\n".join(rows) + "\n").encode()})
    if study.calibration is None:
        raise ComputationError("the study gave no calibration")
    return Calibration(study.calibration, study)


def advise_balance(
    phases: dict[str, dict[str, Any]],
    balance: dict[str, Any],
    *,
    radius_m: float,
    g_m_s2: float,
    k1_rad_s_g: float,
    pivot_to_probe_mm: float,
    probe_to_piga_mm: float,
    probe_along: bool = False,
    base_dir: PathLike | None = None,
) -> BalanceAdvice:
    """The balance advisor (``docs/BALANCING.md``): the static/dynamic phasors of each
    phase, the correction mass and azimuth, the residual C_r and Δk2 it leaves.

    ``phases`` maps a phase's name to its points as in a study (e.g. ``{"before":
    {"first_harmonic": [{"rate_deg_s": 10.0, "dc1_um": -3.29, "ds1_um": -1.19}, ...]}}``);
    ``balance`` is a study's ``balance`` section naming them (``initial``, ``trial``,
    ``trial_mass``, ``correction_radius_m``, …). Returns a :class:`BalanceAdvice`, whose
    ``to_dict()`` is results.json's ``balance`` object.
    """
    config = {
        "name": "balance",
        "radius_m": radius_m,
        "g_m_s2": g_m_s2,
        "k1_rad_s_g": k1_rad_s_g,
        "lever": {
            "pivot_to_probe_mm": pivot_to_probe_mm,
            "probe_to_piga_mm": probe_to_piga_mm,
            "probe_direction": "along_o1_x1" if probe_along else "against_o1_x1",
        },
        "phases": [{"name": name, "points": points} for name, points in phases.items()],
        "balance": balance,
    }
    study = _study_dict(config, base_dir, {})
    if study.balance is None:
        raise ComputationError("the study gave no balance advice")
    return BalanceAdvice._of(study.balance)


@dataclass(frozen=True)
class Plan(_Result):
    """A calibration campaign planned for a U95(k2) target (``docs/PLANNING.md``): the
    rate points, revolutions per rate and the predicted U95(k2); ``data`` is the plan as
    ``plan.json`` holds it."""

    rates_deg_s: tuple[float, ...]
    revolutions: tuple[int, ...]
    u95_k2_rad_s_g2: float | None
    data: dict[str, Any]
    #: For a two-orientation plan (a ``two_orientation`` section): the mounting of each
    #: point (``"ia_in"`` or ``"ia_out"``), aligned with ``rates_deg_s``; empty otherwise.
    orientations: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        return self.data


def plan(config: PathLike | dict[str, Any]) -> Plan:
    """Plans a calibration campaign as ``cargo xtask plan --config FILE`` does, from a plan
    file (RON) or a dict of the same shape."""
    if isinstance(config, dict):
        text = _native.plan(None, config)
    else:
        text = _native.plan(os.fspath(config), None)
    data = json.loads(text)
    two = data.get("two_orientation")
    if two is not None:
        mounted = [(m["orientation"], p) for m in two["mountings"] for p in m["points"]]
        return Plan(
            rates_deg_s=tuple(p["rate_deg_s"] for _, p in mounted),
            revolutions=tuple(p["revolutions"] for _, p in mounted),
            u95_k2_rad_s_g2=two.get("u95_k2_rad_s_g2"),
            data=data,
            orientations=tuple(o for o, _ in mounted),
        )
    points = data.get("points", [])
    return Plan(
        rates_deg_s=tuple(p.get("rate_deg_s") for p in points),
        revolutions=tuple(p.get("revolutions") for p in points),
        u95_k2_rad_s_g2=data.get("u95_k2_rad_s_g2"),
        data=data,
    )


__all__ = [
    "DEFAULT_ORDER",
    "BalanceAdvice",
    "Calibration",
    "CentrifugeCalError",
    "Coefficients",
    "ComputationError",
    "ConfigError",
    "DeltaK2",
    "FirstHarmonic",
    "HarmonicFit",
    "IncompleteRevolution",
    "InputError",
    "PerRevolution",
    "Plan",
    "RadiusFit",
    "Recording",
    "RecordingError",
    "StudyResults",
    "Warning",
    "advise_balance",
    "calibrate",
    "certificate",
    "delta_k2",
    "fit_harmonics",
    "fit_radius_error",
    "plan",
    "read_recording",
    "run_study",
]
