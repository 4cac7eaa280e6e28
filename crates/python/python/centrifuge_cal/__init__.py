"""centrifuge_cal: PIGA calibration on a precision centrifuge, from Python.

The Rust toolkit behind ``cargo xtask``, with numpy arrays in and typed results out:

- :func:`read_recording`: a probe recording (CSV with a format description, NI TDMS, MATLAB
  MAT) into numpy arrays, as the study reads it (the gap in µm);
- :func:`fit_harmonics`: the per-revolution Fourier fit of eq. 20 on arrays;
- :func:`fit_radius_error` and :func:`delta_k2`: C_r from the radius error (eq. 16) and the
  pseudo-second-order term Δk2 = k1·C_r·g/R² (eq. 19);
- :func:`calibrate`: k0…k3 from rates and PIGA outputs (eq. 18), compensated for Δk2, with
  a GUM budget and a Monte Carlo check (JCGM 100/101);
- :func:`calibrate_two_orientation`: k2 and the total radius growth C from the PIGA
  calibrated with its input axis in and out (eq. 23), C compared with a probe's C_r;
- :func:`advise_balance` and :func:`plan`: the balance advisor and the test planner;
- :func:`run_study`: a whole study from its configuration file or a dict of the same shape,
  returning what ``results.json`` holds;
- :func:`certificate`: the calibration certificate (PDF/A) of a study's results folder;
- :func:`history` and :func:`centrifuge_history`: a unit's certified coefficients against
  date (drift, prediction, recommended interval) and a centrifuge's health, from the records
  database, as numpy arrays (the numbers of ``centrifuge-cal history --json``).

Units are in the names (``rate_deg_s``, ``radius_error_um``, ``c_r_m_s2``); lengths of a
probe recording and of its fit are in µm, the study's unit, whatever the file declares (the
declared unit is kept on the object). Defaults are the study's (:data:`STUDY_DEFAULTS`,
read from the Rust study). Errors are :class:`CentrifugeCalError` subclasses with the
command line's message; the warnings a result carries are also issued as
:class:`CentrifugeCalWarning`. Long computations release the GIL and stop on Ctrl-C.
``docs/PYTHON.md`` in the repository walks through a calibration.
"""

from __future__ import annotations

import math
import os
import warnings as _warnings
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from . import _native
from ._arrays import (
    FloatArray,
    count,
    finite,
    flag,
    number,
    optional_count,
    samples,
    show,
    text,
)
from .errors import (
    CentrifugeCalError,
    CentrifugeCalWarning,
    ComputationError,
    ConfigError,
    InputError,
    RecordingError,
    _error,
)
from .history import (
    CentrifugeHealth,
    Drift,
    Prediction,
    TermHistory,
    UnitHistory,
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

#: The study's defaults, from the Rust study itself (``pipeline::FitSettings``, a recording
#: format's, a calibration section's): the harmonic fit's ``order``, ``drift`` and
#: ``revolutions``, a recording's ``max_gap_intervals``, the Monte Carlo ``seed`` and
#: ``trials``, and ``k1``. Every function here that takes one defaults to it.
STUDY_DEFAULTS: Mapping[str, Any] = _native.defaults()

#: Highest Fourier order fitted by default (the study's; the paper's 4).
DEFAULT_ORDER: int = STUDY_DEFAULTS["order"]
#: Whether the harmonic fit has a drift term by default (the study's: it has).
DEFAULT_DRIFT: bool = STUDY_DEFAULTS["drift"]
_DEFAULT_REVOLUTIONS: int | None = STUDY_DEFAULTS["revolutions"]
_DEFAULT_GAP_INTERVALS: float = STUDY_DEFAULTS["max_gap_intervals"]
_DEFAULT_SEED: int = STUDY_DEFAULTS["seed"]
_DEFAULT_TRIALS: Any = STUDY_DEFAULTS["trials"]


def _issue(items: Iterable[tuple[str, str]], stacklevel: int) -> None:
    """Issues each ``(code, message)`` as a :class:`CentrifugeCalWarning`; ``stacklevel``
    as :func:`warnings.warn` counts it from this function."""
    for code, message in items:
        _warnings.warn(f"[{code}] {message}", CentrifugeCalWarning, stacklevel=stacklevel + 1)


def _fit_warnings(fit: HarmonicFit) -> HarmonicFit:
    # caller's caller: the line that called the public function
    _issue(((w.code, w.message) for w in fit.warnings), stacklevel=3)
    return fit


def _study_warnings(study: StudyResults) -> StudyResults:
    _issue(
        (
            (str(w.get("code", "")), f"{w.get('where', '')}: {w.get('message', '')}")
            for w in study.warnings
        ),
        stacklevel=3,
    )
    return study


def _path(name: str, value: Any) -> str:
    """A path given as text or an ``os.PathLike``."""
    try:
        p = os.fspath(value)
    except TypeError as e:
        raise _error(InputError, f"{name}: {show(value)} is not a path", field=name) from e
    if not isinstance(p, str):
        raise _error(InputError, f"{name}: give the path as text, not bytes", field=name)
    return p


def _dict(name: str, value: Any) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise _error(InputError, f"{name}: {show(value)} is not a dict", field=name)
    return value


class Recording:
    """A probe recording read from a file: ``time_s`` (s), ``gap_um`` (µm, the study's
    unit, converted from the file's ``declared_gap_unit`` by ``um_per_declared_unit`` as
    the study converts it; ``gap`` is the same array) and, when the spindle's angle was
    recorded, ``angle_rad`` (rad, an encoder's or interpolated index pulses'), as read-only
    numpy arrays."""

    path: str
    time_s: FloatArray
    gap_um: FloatArray
    angle_rad: FloatArray | None
    #: The unit of ``gap_um`` and ``gap``: ``"um"``, always.
    gap_unit: str
    #: The gap column's unit as the format declares it (``"mm"``, ``"um"``, …; ``"um"``
    #: for a gap recorded in volts and converted with the probe's sensitivity).
    declared_gap_unit: str
    #: µm per declared unit: ``gap_um`` is the file's gap times this.
    um_per_declared_unit: float
    angle_source: str

    def __init__(self, native: _native.NativeRecording) -> None:
        self._native = native
        d = native.arrays()
        self.path = d["path"]
        self.time_s = d["time_s"]
        self.gap_um = d["gap_um"]
        self.angle_rad = d["angle_rad"]
        for a in (self.time_s, self.gap_um, self.angle_rad):
            if a is not None:
                a.flags.writeable = False
        self.gap_unit = "um"
        self.declared_gap_unit = d["declared_gap_unit"]
        self.um_per_declared_unit = float(d["um_per_declared_unit"])
        self.angle_source = d["angle_source"]

    @property
    def gap(self) -> FloatArray:
        """The gap, µm (the same array as ``gap_um``)."""
        return self.gap_um

    def __len__(self) -> int:
        return int(self.time_s.shape[0])

    def __repr__(self) -> str:
        converted = (
            ""
            if self.declared_gap_unit == "um"
            else f" (declared in {self.declared_gap_unit}, × {self.um_per_declared_unit:g})"
        )
        return (
            f"Recording({self.path!r}, {len(self)} samples, gap in µm{converted}, "
            f"angle from {self.angle_source})"
        )

    def fit_harmonics(
        self,
        *,
        rate_deg_s: float,
        order: int = DEFAULT_ORDER,
        drift: bool = DEFAULT_DRIFT,
        revolutions: int | None = _DEFAULT_REVOLUTIONS,
        probe_along: bool = False,
    ) -> HarmonicFit:
        """Fits eq. 20 to every complete revolution as the study fits a recording (with
        the study's defaults, drift included; the format's gap and non-finite sample
        policies apply), with the study's warnings for it, also issued as
        :class:`CentrifugeCalWarning`. Lengths in µm."""
        d = self._native.analyze(
            math.radians(number("rate_deg_s", rate_deg_s)),
            count("order", order, minimum=1, maximum=64),
            flag("drift", drift),
            optional_count("revolutions", revolutions, minimum=1),
            flag("probe_along", probe_along),
        )
        return _fit_warnings(HarmonicFit._of(d))


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
    "gap": {"column": "spalt", "unit": "mm"},
    "angle": {"encoder": {"column": "enc", "unit": {"counts": {"per_rev": 4096}}}}}``.
    For TDMS and MAT files, the format's column names and units name the channels or
    variables; ``group`` is the TDMS group or MAT struct holding them, and
    ``waveform_time`` takes TDMS sample times from the gap channel's waveform properties.

    The gap comes back in µm, the study's unit (``gap_um``), converted from the unit the
    format declares (``declared_gap_unit``, e.g. ``mm``) as the study converts it.
    """
    ron = None
    fmt = None
    if isinstance(format, dict):
        fmt = format
    elif format is not None:
        ron = _path("format", format)
    return Recording(
        _native.read_recording(
            _path("path", path),
            ron,
            fmt,
            None if group is None else text("group", group),
            flag("waveform_time", waveform_time),
        )
    )


def fit_harmonics(
    time_s: Any,
    gap: Any,
    *,
    rate_deg_s: float,
    angle_rad: Any = None,
    start_angle_deg: float = 0.0,
    order: int = DEFAULT_ORDER,
    drift: bool = DEFAULT_DRIFT,
    revolutions: int | None = _DEFAULT_REVOLUTIONS,
    max_gap_intervals: float = _DEFAULT_GAP_INTERVALS,
    probe_along: bool = False,
    gap_unit: Literal["nm", "um", "mm", "m"] = "um",
    on_outlier: Literal["drop_revolution", "keep"] = "drop_revolution",
) -> HarmonicFit:
    """Fits eq. 20, ``gap(θ) = l0 + Σ (c_k cos kθ + s_k sin kθ)``, to every complete
    revolution of a probe recording held in arrays, and averages the coefficients.

    ``time_s`` (s, strictly increasing) and ``gap`` (in ``gap_unit``, default µm) are 1-D
    float64 arrays of one length (integer arrays and lists of numbers are taken too); the
    results are in µm whatever ``gap_unit`` is, and a gap implausible in its unit (a mean
    below a micrometre: millimetres given as µm) is warned about as the study warns. The
    angle θ is ``angle_rad`` (the spindle encoder, rad, zero at the O1X1 reference; it may
    wrap) when given, checked against ``rate_deg_s`` (within 2 %); else
    ``θ = ω·(t − t₀) + start_angle_deg`` from the declared rate, with the warning
    ``angle_from_rate``. ``probe_along``: the probe measures along O1X1 (sets the sign of
    β). The defaults (``order``, ``drift``, ``revolutions``, ``max_gap_intervals``) are the
    study's (:data:`STUDY_DEFAULTS`). A revolution that fits far worse than the others (a
    glitch: residual RMS above 5 times the median) is warned (``residual_outlier``) and, with
    ``on_outlier="drop_revolution"`` (the study's default), left out of the mean;
    ``"keep"`` keeps it; residuals alternating in sign are warned
    (``alternating_residuals``), as the study warns. Warnings are also issued as
    :class:`CentrifugeCalWarning`. The GIL is released during the fit; contiguous float64
    arrays are read in place.
    """
    t = samples("time_s", time_s)
    g = samples("gap", gap, length=t.shape[0])
    a = None if angle_rad is None else samples("angle_rad", angle_rad, length=t.shape[0])
    d = _native.fit_harmonics(
        t,
        g,
        a,
        math.radians(number("rate_deg_s", rate_deg_s)),
        math.radians(number("start_angle_deg", start_angle_deg)),
        count("order", order, minimum=1, maximum=64),
        flag("drift", drift),
        optional_count("revolutions", revolutions, minimum=1),
        number("max_gap_intervals", max_gap_intervals),
        flag("probe_along", probe_along),
        text("gap_unit", gap_unit),
        text("on_outlier", on_outlier),
    )
    return _fit_warnings(HarmonicFit._of(d))


def fit_radius_error(
    rate_deg_s: Any,
    radius_error_um: Any,
    *,
    sigma_um: Any = None,
    model: Literal["two_term", "three_term"] = "two_term",
) -> RadiusFit:
    """Fits the radius error ``Δr(ω) = a + C_r·ω²`` (``three_term``: ``a + b·ω + C_r·ω²``)
    by QR least squares (eq. 16): C_r in m·s² with its standard error from the residuals;
    weighted by ``1/σ`` when ``sigma_um`` is given. Rates in deg/s, radius errors and σ in
    µm (as :class:`HarmonicFit` gives them)."""
    if not isinstance(model, str) or model not in ("two_term", "three_term"):
        raise _error(
            InputError,
            f"model: {show(model)} is not a radius-error model (two_term or three_term)",
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
    _issue(((x["code"], x["message"]) for x in d["warnings"]), stacklevel=2)
    return RadiusFit._from(
        d,
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
    value, sigma = _native.delta_k2(
        number("k1_rad_s_g", k1_rad_s_g),
        number("c_r_m_s2", c_r_m_s2),
        number("c_r_sigma_m_s2", c_r_sigma_m_s2),
        number("radius_m", radius_m),
        number("g_m_s2", g_m_s2),
    )
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
    (default: the working directory). The study's warnings are also issued as
    :class:`CentrifugeCalWarning`. The GIL is released while it runs; Ctrl-C stops it.
    """
    if isinstance(config, dict):
        return _study_warnings(_study_dict(config, base_dir, {}))
    return _study_warnings(StudyResults._of(_native.run_study_file(_path("config", config))))


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
        _path("results_dir", results_dir), None if out is None else _path("out", out)
    )


def history(
    unit: str,
    records: PathLike | None = None,
    *,
    at: str | None = None,
    term: str | None = None,
    tolerance: float | None = None,
    reliability: float = 0.95,
) -> UnitHistory:
    """A unit's history from the records database, as ``centrifuge-cal history UNIT --json``
    computes it (``docs/RECORDS.md``): each certified term across the unit's current
    certificates as numpy arrays (dates as ``datetime64[D]``), its drift per year with its
    uncertainty and significance, and the value predicted at ``at`` (YYYY-MM-DD; default the
    end of the recommended interval, else one year after the latest certificate).

    ``unit`` is its serial number or ``MODEL/SERIAL``; ``records`` the database (default: as
    the command line finds it, ``$CENTRIFUGE_CAL_RECORDS``, else
    ``~/.local/share/centrifuge-cal/records.sqlite``). With ``term`` (``"k2"``) and
    ``tolerance`` (in the term's unit), the recommended interval for ``reliability`` by the
    variables method. Raises :class:`ConfigError` for a database or unit that cannot be found
    and :class:`InputError` for a term without a tolerance.
    """
    return UnitHistory._of(
        _native.unit_history(
            text("unit", unit),
            None if records is None else _path("records", records),
            None if at is None else text("at", at),
            None if term is None else text("term", term),
            None if tolerance is None else number("tolerance", tolerance),
            number("reliability", reliability),
        )
    )


def centrifuge_history(
    name: str,
    records: PathLike | None = None,
    *,
    target_u95: float | None = None,
    share: float | None = None,
    next: str | None = None,
) -> CentrifugeHealth:
    """A centrifuge's health from the records database, as ``centrifuge-cal history
    --centrifuge NAME --json`` computes it: C_r, the static offset and Δk2 of each campaign as
    numpy arrays, the balance events, the drifts since the latest balance and, with
    ``target_u95`` (the U95 of k2 to meet, rad/(s·g²)), whether to rebalance before the next
    campaign (``next``, YYYY-MM-DD; ``share`` of the target Δk2 may reach, default 0.2 as the
    command line's). ``records`` as for :func:`history`.
    """
    return CentrifugeHealth._of(
        _native.centrifuge_health(
            text("name", name),
            None if records is None else _path("records", records),
            None if target_u95 is None else number("target_u95", target_u95),
            None if share is None else number("share", share),
            None if next is None else text("next", next),
        )
    )


def _study_dict(
    config: dict[str, Any], base_dir: PathLike | None, tables: dict[str, Any]
) -> StudyResults:
    source = "<dict>" if base_dir is None else os.path.join(_path("base_dir", base_dir), "<dict>")
    return StudyResults._of(_native.run_study_dict(config, source, tables))


@dataclass(frozen=True)
class Calibration(_Result):
    """A calibration of k0…k3 (eq. 18) compensated for Δk2 (eq. 19): ``calibration`` is
    results.json's ``calibration`` object (coefficients with u and U95, the GUM budget, the
    Monte Carlo check, the uncompensated fit beside it), ``study`` the whole document."""

    calibration: dict[str, Any]
    study: StudyResults

    def to_dict(self) -> dict[str, Any]:
        return self.calibration


def _trials(trials: Any) -> Any:
    """The study's `trials`: ``"adaptive"`` or a whole number (fixed), at most the Monte
    Carlo method's cap (``STUDY_DEFAULTS["max_trials"]``, which the method itself refuses
    beyond); the study checks the least."""
    if isinstance(trials, str) and trials in ("adaptive", _DEFAULT_TRIALS):
        return "adaptive"
    n = count("trials", trials, minimum=0)
    cap = int(STUDY_DEFAULTS["max_trials"])
    if n > cap:
        raise _error(
            InputError,
            f"trials: {n:.3g} is more than the Monte Carlo method runs ({cap:.0e}: it keeps "
            "every trial's values, 8 bytes per output and trial)",
            field="trials",
        )
    return {"fixed": n}


def _piga_table(
    prefix: str, rates: Any, outputs: Any, sigma: Any, labels: Any
) -> tuple[dict[str, Any], dict[str, Any], FloatArray]:
    """A PIGA table given as arrays: the study's `table` block and the arrays for the
    native side (columns by name, labels), checked; and the rates."""
    w = samples(f"{prefix}rate_deg_s", rates)
    y = samples(f"{prefix}output_rad_s", outputs, length=w.shape[0])
    s = (
        None
        if sigma is None
        else samples(f"{prefix}output_sigma_rad_s", sigma, length=w.shape[0])
    )
    for name, x in (
        (f"{prefix}rate_deg_s", w),
        (f"{prefix}output_rad_s", y),
        (f"{prefix}output_sigma_rad_s", s),
    ):
        if x is not None:
            finite(name, x)
    table: dict[str, Any] = {"file": f"<arrays {prefix or 'piga'}>"}
    columns: dict[str, FloatArray] = {"rate_deg_s": w, "output_rad_s": y}
    if s is not None:
        table["sigma_column"] = "sigma_rad_s"
        columns["sigma_rad_s"] = s
    names: list[str] | None = None
    if labels is not None:
        if isinstance(labels, (str, bytes)) or not isinstance(labels, (list, tuple)):
            raise _error(InputError, f"{prefix}labels: a list of str is needed", field="labels")
        names = [text(f"{prefix}labels[{i}]", label) for i, label in enumerate(labels)]
        if len(names) != w.shape[0]:
            raise _error(
                InputError,
                f"{prefix}labels: {len(names)} labels for {w.shape[0]} rates",
                field=f"{prefix}labels",
            )
        table["label_column"] = "label"
    return table, {"columns": columns, "labels": names}, w


def _compensating_phase(compensate_with: Any, name: str) -> tuple[dict[str, Any], str]:
    """A radius-error fit as the study's phase of radius-error points, and its model."""
    if not isinstance(compensate_with, RadiusFit):
        raise _error(
            InputError,
            f"{name}: a RadiusFit (from fit_radius_error) is needed, not "
            f"{type(compensate_with).__name__}",
            field=name,
        )
    if compensate_with.weighted:
        raise _error(
            InputError,
            f"{name}: a weighted radius-error fit; give the phase with its σ as "
            "first-harmonic points to run_study instead",
            field=name,
        )
    phase = {
        "name": "spindle",
        "points": {
            "radius_error": [
                {"rate_deg_s": float(r), "radius_error_um": float(e)}
                for r, e in zip(compensate_with.rate_deg_s, compensate_with.radius_error_um)
            ]
        },
    }
    return phase, compensate_with.model


def _core(
    name: str,
    radius_m: Any,
    g_m_s2: Any,
    k1_rad_s_g: Any,
    pivot_to_probe_mm: Any,
    probe_to_piga_mm: Any,
    probe_along: bool,
) -> dict[str, Any]:
    return {
        "name": name,
        "radius_m": number("radius_m", radius_m),
        "g_m_s2": number("g_m_s2", g_m_s2),
        "k1_rad_s_g": number("k1_rad_s_g", k1_rad_s_g),
        "lever": {
            "pivot_to_probe_mm": number("pivot_to_probe_mm", pivot_to_probe_mm),
            "probe_to_piga_mm": number("probe_to_piga_mm", probe_to_piga_mm),
            "probe_direction": "along_o1_x1"
            if flag("probe_along", probe_along)
            else "against_o1_x1",
        },
    }


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
    seed: int = _DEFAULT_SEED,
    trials: Literal["adaptive"] | int = "adaptive",
    probe_along: bool = False,
) -> Calibration:
    """Identifies k0…k3 from the PIGA's mean output at each rate (eq. 18), removes the
    Δk2 of ``compensate_with`` (the radius-error fit of the spindle, whose points become the
    study's compensating phase), and evaluates the uncertainty: a GUM budget and an adaptive
    (or fixed-``trials``) Monte Carlo with ``seed`` — the study's calibration section, run
    on the arrays (they cross as arrays, read as the study's table).

    ``output_sigma_rad_s``: each point's standard uncertainty (the fit is then weighted);
    ``k1``: ``"fitted"`` or ``(k1_rad_s_g, u_rad_s_g)`` given; ``uncertainty``: the Type B
    inputs as a study's ``uncertainty`` section (``radius_u_m``, ``g_u_m_s2``, ``g_source``,
    ``rate_u_relative``, ``pivot_to_probe_u_mm``, ``probe_to_piga_u_mm``,
    ``probe_gain_u_relative``, each required, and ``zero_reasons`` with the reason for each
    zero: nothing is taken as exact without a word). ``radius_m``, ``g_m_s2`` and
    ``k1_rad_s_g`` are the centrifuge's radius, local gravity and the PIGA's nominal scale
    factor. The study's warnings are also issued as :class:`CentrifugeCalWarning`; the GIL
    is released while it runs, and Ctrl-C stops it (the Monte Carlo method between two
    batches of 10⁴ trials).
    """
    table, arrays, _ = _piga_table("", rate_deg_s, output_rad_s, output_sigma_rad_s, labels)
    phase, model = _compensating_phase(compensate_with, "compensate_with")
    k1_config: Any
    if isinstance(k1, str) and k1 == "fitted":
        k1_config = "fitted"
    elif isinstance(k1, (tuple, list)) and len(k1) == 2:
        k1_config = {
            "given": {"k1_rad_s_g": number("k1[0]", k1[0]), "u_rad_s_g": number("k1[1]", k1[1])}
        }
    else:
        raise _error(
            InputError,
            f'k1: {show(k1)} is neither "fitted" nor (k1_rad_s_g, u_rad_s_g)',
            field="k1",
        )
    config: dict[str, Any] = {
        **_core(
            "calibration",
            radius_m,
            g_m_s2,
            k1_rad_s_g,
            pivot_to_probe_mm,
            probe_to_piga_mm,
            probe_along,
        ),
        "radius_model": model,
        "phases": [phase],
        "calibration": {
            "table": table,
            "compensate_with": "spindle",
            "k1": k1_config,
            "seed": count("seed", seed),
            "trials": _trials(trials),
        },
    }
    if uncertainty is not None:
        config["uncertainty"] = _dict("uncertainty", uncertainty)
    study = _study_dict(config, None, {table["file"]: arrays})
    if study.calibration is None:
        raise _error(ComputationError, "the study gave no calibration")
    return Calibration(study.calibration, _study_warnings(study))


@dataclass(frozen=True)
class TwoOrientation(_Result):
    """A two-orientation calibration (eq. 23, ``docs/TWO_ORIENTATION.md``):
    ``two_orientation`` is results.json's ``two_orientation`` object (k2 and the total
    radius growth C with their budgets, C − C_r against the probe, the warnings' codes),
    ``study`` the whole document."""

    two_orientation: dict[str, Any]
    study: StudyResults

    def to_dict(self) -> dict[str, Any]:
        return self.two_orientation


def calibrate_two_orientation(
    rate_in_deg_s: Any,
    output_in_rad_s: Any,
    rate_out_deg_s: Any,
    output_out_rad_s: Any,
    *,
    radius_in_m: float,
    radius_out_m: float,
    compare_with: RadiusFit,
    g_m_s2: float,
    k1_rad_s_g: float,
    pivot_to_probe_mm: float,
    probe_to_piga_mm: float,
    output_sigma_in_rad_s: Any = None,
    output_sigma_out_rad_s: Any = None,
    uncertainty: dict[str, Any] | None = None,
    seed: int = _DEFAULT_SEED,
    trials: Literal["adaptive"] | int = "adaptive",
    probe_along: bool = False,
    latitude_deg: float | None = None,
    spin_seen_from_above: Literal["counterclockwise", "clockwise"] | None = None,
) -> TwoOrientation:
    """The two-orientation calibration of eq. 23 on arrays: the PIGA's mean outputs with
    its input axis in (towards the spindle axis, at ``radius_in_m``) and out (at
    ``radius_out_m``) fitted together give k2 and the total radius growth C from the PIGA
    alone, with a GUM budget and a Monte Carlo check; C is compared with the C_r of
    ``compare_with`` (the probe's radius-error fit; a disagreement names the angle
    reference, probe direction and gap unit to check). It is the study's
    ``two_orientation`` section, run on the arrays; the study's core radius is
    ``radius_in_m``.

    ``output_sigma_*_rad_s``: each point's standard uncertainty (weighted fit);
    ``uncertainty``: the Type B inputs as in :func:`calibrate`; ``latitude_deg`` and
    ``spin_seen_from_above``: the Earth rate about the spindle axis, whose term with k2 the
    fit removes when both are given and otherwise takes as an uncertainty (the study's
    fields of the same names, docs/TWO_ORIENTATION.md). Warnings are also issued as
    :class:`CentrifugeCalWarning`; the GIL is released, and Ctrl-C stops it.
    """
    table_in, arrays_in, _ = _piga_table(
        "ia_in_", rate_in_deg_s, output_in_rad_s, output_sigma_in_rad_s, None
    )
    table_out, arrays_out, _ = _piga_table(
        "ia_out_", rate_out_deg_s, output_out_rad_s, output_sigma_out_rad_s, None
    )
    phase, model = _compensating_phase(compare_with, "compare_with")
    config: dict[str, Any] = {
        **_core(
            "two_orientation",
            radius_in_m,
            g_m_s2,
            k1_rad_s_g,
            pivot_to_probe_mm,
            probe_to_piga_mm,
            probe_along,
        ),
        "radius_model": model,
        "phases": [phase],
        "two_orientation": {
            "orientations": [
                {
                    "orientation": "ia_in",
                    "radius_m": number("radius_in_m", radius_in_m),
                    "table": table_in,
                },
                {
                    "orientation": "ia_out",
                    "radius_m": number("radius_out_m", radius_out_m),
                    "table": table_out,
                },
            ],
            "compare_with": "spindle",
            "seed": count("seed", seed),
            "trials": _trials(trials),
        },
    }
    if latitude_deg is not None:
        config["two_orientation"]["latitude_deg"] = number("latitude_deg", latitude_deg)
    if spin_seen_from_above is not None:
        config["two_orientation"]["spin_seen_from_above"] = spin_seen_from_above
    if uncertainty is not None:
        config["uncertainty"] = _dict("uncertainty", uncertainty)
    study = _study_dict(
        config, None, {table_in["file"]: arrays_in, table_out["file"]: arrays_out}
    )
    if study.two_orientation is None:
        raise _error(ComputationError, "the study gave no two-orientation results")
    return TwoOrientation(study.two_orientation, _study_warnings(study))


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
        **_core(
            "balance",
            radius_m,
            g_m_s2,
            k1_rad_s_g,
            pivot_to_probe_mm,
            probe_to_piga_mm,
            probe_along,
        ),
        "phases": [
            {"name": name, "points": points} for name, points in _dict("phases", phases).items()
        ],
        "balance": _dict("balance", balance),
    }
    study = _study_warnings(_study_dict(config, base_dir, {}))
    if study.balance is None:
        raise _error(ComputationError, "the study gave no balance advice")
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
    file (RON) or a dict of the same shape. The GIL is released; Ctrl-C stops it."""
    if isinstance(config, dict):
        data = _native.plan(None, config)
    else:
        data = _native.plan(_path("config", config), None)
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
    "DEFAULT_DRIFT",
    "DEFAULT_ORDER",
    "STUDY_DEFAULTS",
    "BalanceAdvice",
    "Calibration",
    "CentrifugeCalError",
    "CentrifugeHealth",
    "CentrifugeCalWarning",
    "Coefficients",
    "ComputationError",
    "ConfigError",
    "DeltaK2",
    "Drift",
    "FirstHarmonic",
    "HarmonicFit",
    "IncompleteRevolution",
    "InputError",
    "PerRevolution",
    "Plan",
    "Prediction",
    "RadiusFit",
    "Recording",
    "RecordingError",
    "StudyResults",
    "TermHistory",
    "TwoOrientation",
    "UnitHistory",
    "Warning",
    "advise_balance",
    "calibrate",
    "calibrate_two_orientation",
    "centrifuge_history",
    "certificate",
    "delta_k2",
    "fit_harmonics",
    "fit_radius_error",
    "history",
    "plan",
    "read_recording",
    "run_study",
]
