"""Typed result objects. Each is a frozen dataclass with ``to_dict()`` giving plain Python
values (lists for arrays) that ``json.dumps`` accepts."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Self

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]


def _plain(value: Any) -> Any:
    if isinstance(value, np.ndarray) and value.dtype.kind == "M":
        return [str(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.datetime64):
        return str(value)
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: _plain(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


class _Result:
    def to_dict(self) -> dict[str, Any]:
        """The result as plain Python values (arrays as lists)."""
        out: dict[str, Any] = _plain(self)
        return out

    @classmethod
    def _from(cls, d: dict[str, Any], **given: Any) -> Self:
        """The result (a dataclass) with the fields ``given``, and ``d``'s values of the same
        names for the others: the one reading of a dictionary of the native module."""
        names = (f.name for f in dataclasses.fields(cls))  # type: ignore[arg-type]
        return cls(**{n: given[n] if n in given else d[n] for n in names})


@dataclass(frozen=True)
class Warning(_Result):
    """Something that may make the numbers wrong: a stable ``code`` and a ``message`` in
    the command line's words."""

    code: str
    message: str


@dataclass(frozen=True)
class Coefficients(_Result):
    """Eq. 20's coefficients, in µm: ``l0`` and, for order k = 1…N, ``c[k-1]`` (cos kθ) and
    ``s[k-1]`` (sin kθ); ``drift_per_s`` (µm per second) when fitted."""

    l0: float
    c: tuple[float, ...]
    s: tuple[float, ...]
    drift_per_s: float | None

    @staticmethod
    def _of(d: dict[str, Any] | None) -> Coefficients | None:
        if d is None:
            return None
        return Coefficients(float(d["l0"]), tuple(d["c"]), tuple(d["s"]), d["drift_per_s"])


@dataclass(frozen=True)
class FirstHarmonic(_Result):
    """The first harmonic of the mean coefficients (eq. 21): ``c1``, ``s1`` and
    ``amplitude`` ΔR1 in µm, ``beta_deg`` β for the probe's direction."""

    c1: float
    s1: float
    amplitude: float
    beta_deg: float
    probe_direction: str


@dataclass(frozen=True)
class PerRevolution(_Result):
    """One row per revolution fitted: its first sample and sample count, its coefficients
    (``c`` and ``s`` are K×N arrays), the RMS of its residuals and the condition number of
    its normal matrix."""

    first_sample: npt.NDArray[np.uint64]
    samples: npt.NDArray[np.uint64]
    l0: FloatArray
    c: FloatArray
    s: FloatArray
    drift_per_s: FloatArray | None
    residual_rms: FloatArray
    condition: FloatArray


@dataclass(frozen=True)
class IncompleteRevolution(_Result):
    """The trailing revolution left out: its first sample, sample count and turns."""

    first_sample: int
    samples: int
    turns: float


@dataclass(frozen=True)
class HarmonicFit(_Result):
    """The per-revolution Fourier fit of eq. 20 and its average across revolutions.

    ``mean``, ``std`` (sample standard deviation across revolutions) and ``std_error``
    (``std/√K``) are in µm (``gap_unit``), converted from the gap's declared unit
    (``declared_gap_unit``) as the study converts them; ``std`` and ``std_error`` are
    ``None`` with one revolution. ``measured_rate_deg_s`` is the encoder's mean rate over the revolutions
    fitted (``None`` with the angle from the declared rate)."""

    samples: int
    angle_source: str
    rate_deg_s: float
    measured_rate_deg_s: float | None
    order: int
    drift: bool
    revolutions_used: int
    revolutions_available: int
    nominal_interval_s: float
    mean: Coefficients
    std: Coefficients | None
    std_error: Coefficients | None
    first_harmonic: FirstHarmonic
    per_revolution: PerRevolution
    incomplete_revolution: IncompleteRevolution | None
    dropped_revolutions: int
    warnings: tuple[Warning, ...]
    #: Seconds the Rust computation took, the GIL released (checks, fit, statistics); the
    #: rest of the call is the binding's overhead (``bench/python_binding.py``).
    rust_seconds: float | None = dataclasses.field(default=None, compare=False, repr=False)
    #: The unit of every length of the fit (``mean``, ``std``, ``first_harmonic``,
    #: ``per_revolution``): µm, the study's, whatever the gap's declared unit.
    gap_unit: str = "um"
    #: The gap's declared unit (the format's, or ``fit_harmonics``' ``gap_unit``), which
    #: the lengths were converted from.
    declared_gap_unit: str = "um"

    @property
    def rate_rad_s(self) -> float:
        """The rate the radius-error fit uses: the measured one when measured, else the
        declared one, rad/s."""
        rate = self.measured_rate_deg_s if self.measured_rate_deg_s is not None else self.rate_deg_s
        return math.radians(rate)

    @staticmethod
    def _of(d: dict[str, Any]) -> HarmonicFit:
        mean = Coefficients._of(d["mean"])
        assert mean is not None
        inc = d["incomplete_revolution"]
        return HarmonicFit(
            samples=int(d["samples"]),
            angle_source=d["angle_source"],
            rate_deg_s=float(d["rate_deg_s"]),
            measured_rate_deg_s=d["measured_rate_deg_s"],
            order=int(d["order"]),
            drift=bool(d["drift"]),
            revolutions_used=int(d["revolutions_used"]),
            revolutions_available=int(d["revolutions_available"]),
            nominal_interval_s=float(d["nominal_interval_s"]),
            mean=mean,
            std=Coefficients._of(d["std"]),
            std_error=Coefficients._of(d["std_error"]),
            first_harmonic=FirstHarmonic(**d["first_harmonic"]),
            per_revolution=PerRevolution(**d["per_revolution"]),
            incomplete_revolution=None if inc is None else IncompleteRevolution(**inc),
            dropped_revolutions=int(d["dropped_revolutions"]),
            warnings=tuple(Warning(**w) for w in d["warnings"]),
            rust_seconds=d.get("rust_seconds"),
            declared_gap_unit=d.get("declared_gap_unit", "um"),
        )


@dataclass(frozen=True)
class DeltaK2(_Result):
    """The pseudo-second-order error of eq. 19, Δk2 = k1·C_r·g/R², and its standard
    deviation from σ(C_r), rad/(s·g²)."""

    delta_k2_rad_s_g2: float
    sigma_rad_s_g2: float


@dataclass(frozen=True)
class RadiusFit(_Result):
    """The radius-error fit of eq. 16, ``Δr = a (+ b·ω) + C_r·ω²``, with the points it was
    fitted to (kept so that a calibration can be compensated with it)."""

    model: str
    c_r_m_s2: float
    c_r_sigma_m_s2: float
    offset_m: float
    linear_m_s: float | None
    linear_sigma_m_s: float | None
    residuals_m: FloatArray
    weighted: bool
    dof: int
    residual_sd: float
    condition_number: float
    warnings: tuple[Warning, ...]
    rate_deg_s: FloatArray
    radius_error_um: FloatArray
    sigma_um: FloatArray | None

    def delta_k2(self, *, k1_rad_s_g: float, radius_m: float, g_m_s2: float) -> DeltaK2:
        """Δk2 = k1·C_r·g/R² and its σ from this fit's σ(C_r) (eq. 19)."""
        from . import delta_k2

        return delta_k2(
            k1_rad_s_g=k1_rad_s_g,
            c_r_m_s2=self.c_r_m_s2,
            c_r_sigma_m_s2=self.c_r_sigma_m_s2,
            radius_m=radius_m,
            g_m_s2=g_m_s2,
        )


@dataclass(frozen=True)
class BalanceAdvice(_Result):
    """The balance advisor's answer (``docs/BALANCING.md``): the correction mass, its radius
    and azimuth with their standard uncertainties, and the C_r and Δk2 it is predicted to
    leave. ``assumption`` says in words what the advice rests on (one probe plane or two);
    ``data`` is results.json's ``balance`` object, phasors of each phase included
    (``to_dict()`` returns it)."""

    correction_method: str
    correction_mass_kg: float
    correction_mass_u_kg: float
    correction_radius_m: float
    correction_azimuth_deg: float
    correction_azimuth_u_deg: float
    predicted_c_r_m_s2: float
    predicted_c_r_u_m_s2: float
    predicted_delta_k2_rad_s_g2: float
    predicted_delta_k2_u_rad_s_g2: float
    assumption: str
    data: dict[str, Any]

    def to_dict(self) -> dict[str, Any]:
        """results.json's ``balance`` object."""
        return self.data

    @staticmethod
    def _of(d: dict[str, Any]) -> BalanceAdvice:
        c, p = d["correction"], d["predicted"]
        return BalanceAdvice._from(
            {f"correction_{k}": v for k, v in c.items()}
            | {f"predicted_{k}": v for k, v in p.items()},
            assumption=d["assumption"],
            data=d,
        )


@dataclass(frozen=True)
class StudyResults(_Result):
    """What ``results.json`` holds. ``data`` is the whole document (``to_dict()`` returns
    it); the attributes are its main parts."""

    study: str
    phases: tuple[dict[str, Any], ...]
    warnings: tuple[dict[str, Any], ...]
    calibration: dict[str, Any] | None
    balance: dict[str, Any] | None
    mechanism: dict[str, Any] | None
    data: dict[str, Any]
    #: results.json's ``two_orientation`` object (the IA-in/IA-out fit of eq. 23: k2, C,
    #: C − C_r against the probe, their budgets), ``None`` without that section.
    two_orientation: dict[str, Any] | None = None

    def phase(self, name: str) -> dict[str, Any]:
        """The phase named ``name``; ``KeyError`` naming the study's phases otherwise."""
        for p in self.phases:
            if p["name"] == name:
                return p
        raise KeyError(f"no phase {name!r}; the study's phases: {[p['name'] for p in self.phases]}")

    def to_dict(self) -> dict[str, Any]:
        """The document of ``results.json``."""
        return self.data

    @staticmethod
    def _of(d: dict[str, Any]) -> StudyResults:
        return StudyResults(
            study=d.get("study", ""),
            phases=tuple(d.get("phases", [])),
            warnings=tuple(d.get("warnings", [])),
            calibration=d.get("calibration"),
            balance=d.get("balance"),
            mechanism=d.get("mechanism"),
            data=d,
            two_orientation=d.get("two_orientation"),
        )
