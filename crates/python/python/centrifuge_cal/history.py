"""The records' history as typed objects with numpy arrays: a unit's certified coefficients
against date (:class:`UnitHistory`) and a centrifuge's health (:class:`CentrifugeHealth`),
the numbers of ``centrifuge-cal history --json`` (``docs/RECORDS.md``)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from .results import FloatArray, _Result

#: Dates as numpy calendar days.
DateArray = npt.NDArray[np.datetime64]


def _day(text: str) -> np.datetime64:
    return np.datetime64(text, "D")


def _days(items: list[dict[str, Any]], key: str) -> DateArray:
    return np.array([i[key] for i in items], dtype="datetime64[D]")


def _floats(items: list[dict[str, Any]], key: str) -> FloatArray:
    """A column of numbers; ``None`` (not stated) is NaN in the array."""
    return np.array(
        [np.nan if i[key] is None else float(i[key]) for i in items], dtype=np.float64
    )


@dataclass(frozen=True)
class Drift(_Result):
    """A straight line ``a + b·t`` fitted through a quantity's records (``t`` in years of
    365.2425 days from ``origin``): ``rate_per_year`` b with its standard uncertainty, the
    covariance of (a, b) (2×2), the Birge ratio (``None`` with two records), the coverage
    factor of the 95 % intervals and whether the drift is significant."""

    origin: np.datetime64
    intercept: float
    rate_per_year: float
    u_rate_per_year: float
    covariance: FloatArray
    birge_ratio: float | None
    scaled_by_scatter: bool
    k95: float
    expanded_rate_per_year: float
    significant: bool
    points: int

    @staticmethod
    def _of(d: dict[str, Any] | None) -> Drift | None:
        if d is None:
            return None
        return Drift._from(
            d,
            origin=_day(d["origin"]),
            covariance=np.array(d["covariance"], dtype=np.float64),
        )


@dataclass(frozen=True)
class Prediction(_Result):
    """The value predicted at ``date`` with its standard uncertainty from the fit, the
    standard uncertainty of what a calibration on that date would read, and the coverage
    factor."""

    date: np.datetime64
    value: float
    u: float
    u_reading: float
    k95: float

    @staticmethod
    def _of(d: dict[str, Any] | None) -> Prediction | None:
        if d is None:
            return None
        return Prediction._from(d, date=_day(d["date"]))


@dataclass(frozen=True)
class TermHistory(_Result):
    """One certified term (``k2``, ``k0 (ia_out)``) across the unit's current certificates,
    by date: the certificates, their dates, values, standard and expanded (95 %)
    uncertainties as arrays, the drift fitted through them and the value predicted."""

    label: str
    unit: str
    certificates: tuple[str, ...]
    dates: DateArray
    values: FloatArray
    u: FloatArray
    expanded: FloatArray
    drift: Drift | None
    prediction: Prediction | None

    @staticmethod
    def _of(d: dict[str, Any]) -> TermHistory:
        points: list[dict[str, Any]] = d["points"]
        return TermHistory(
            label=d["label"],
            unit=d["unit"],
            certificates=tuple(p["certificate"] for p in points),
            dates=_days(points, "date"),
            values=_floats(points, "value"),
            u=_floats(points, "u"),
            expanded=_floats(points, "expanded"),
            drift=Drift._of(d["drift"]),
            prediction=Prediction._of(d["prediction"]),
        )


@dataclass(frozen=True)
class UnitHistory(_Result):
    """A unit's history: its identity (``kind``, ``manufacturer``, ``model``, ``serial``),
    each certified term (:class:`TermHistory`, by ``label`` through :meth:`term`), the date
    of the predictions and where it comes from (``given``, ``interval_end``,
    ``one_year_after_latest``), and the recommended interval when asked for (``None``
    otherwise). ``data`` is the whole document of ``history --json``."""

    unit: dict[str, str]
    terms: tuple[TermHistory, ...]
    at: np.datetime64
    at_source: str
    interval: dict[str, Any] | None
    certificates: tuple[dict[str, Any], ...]
    data: dict[str, Any]

    def term(self, label: str) -> TermHistory:
        """The term ``label`` (``k2``); ``KeyError`` naming the unit's terms otherwise."""
        for t in self.terms:
            if t.label == label:
                return t
        raise KeyError(f"no term {label!r}; the unit's terms: {[t.label for t in self.terms]}")

    def to_dict(self) -> dict[str, Any]:
        """The document of ``centrifuge-cal history --json``."""
        return self.data

    @staticmethod
    def _of(d: dict[str, Any]) -> UnitHistory:
        return UnitHistory(
            unit=dict(d["unit"]),
            terms=tuple(TermHistory._of(t) for t in d["terms"]),
            at=_day(d["at"]),
            at_source=d["at_source"],
            interval=d["interval"],
            certificates=tuple(d["certificates"]),
            data=d,
        )


@dataclass(frozen=True)
class CentrifugeHealth(_Result):
    """A centrifuge's health: its campaigns by date as arrays (``dates``, ``c_r_m_s2`` with
    ``c_r_u_m_s2``, ``offset_um``, ``delta_k2_rad_s_g2`` with ``delta_k2_u_rad_s_g2``; NaN
    where a study states no uncertainty), its balance dates, the drifts of C_r and Δk2 since
    the latest balance, the Δk2 predicted at the next campaign, and the advice
    (``rebalance``, ``may_exceed``, ``fine``, ``too_few_campaigns``, ``no_target``).
    ``data`` is the whole document of ``history --centrifuge … --json``."""

    name: str
    studies: tuple[str, ...]
    phases: tuple[str, ...]
    dates: DateArray
    c_r_m_s2: FloatArray
    c_r_u_m_s2: FloatArray
    offset_um: FloatArray
    delta_k2_rad_s_g2: FloatArray
    delta_k2_u_rad_s_g2: FloatArray
    balance_dates: DateArray
    balance_notes: tuple[str, ...]
    c_r_drift: Drift | None
    delta_k2_drift: Drift | None
    next: np.datetime64 | None
    predicted_delta_k2: Prediction | None
    limit_rad_s_g2: float | None
    advice: str
    data: dict[str, Any]

    def to_dict(self) -> dict[str, Any]:
        """The document of ``centrifuge-cal history --centrifuge NAME --json``."""
        return self.data

    @staticmethod
    def _of(d: dict[str, Any]) -> CentrifugeHealth:
        campaigns: list[dict[str, Any]] = d["campaigns"]
        balances: list[dict[str, Any]] = d["balances"]
        return CentrifugeHealth(
            name=d["name"],
            studies=tuple(c["study"] for c in campaigns),
            phases=tuple(c["phase"] for c in campaigns),
            dates=_days(campaigns, "date"),
            c_r_m_s2=_floats(campaigns, "c_r_m_s2"),
            c_r_u_m_s2=_floats(campaigns, "c_r_u_m_s2"),
            offset_um=_floats(campaigns, "offset_um"),
            delta_k2_rad_s_g2=_floats(campaigns, "delta_k2_rad_s_g2"),
            delta_k2_u_rad_s_g2=_floats(campaigns, "delta_k2_u_rad_s_g2"),
            balance_dates=_days(balances, "date"),
            balance_notes=tuple(b["note"] for b in balances),
            c_r_drift=Drift._of(d["c_r_drift"]),
            delta_k2_drift=Drift._of(d["delta_k2_drift"]),
            next=None if d["next"] is None else _day(d["next"]),
            predicted_delta_k2=Prediction._of(d["predicted_delta_k2"]),
            limit_rad_s_g2=d["limit_rad_s_g2"],
            advice=d["advice"],
            data=d,
        )
