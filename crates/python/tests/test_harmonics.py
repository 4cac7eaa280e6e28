"""The per-revolution harmonic fit on arrays: known coefficients, the NumPy reference,
warnings, bad arrays, and two threads at once."""

from __future__ import annotations

import threading
from typing import Any

import numpy as np
import pytest

import centrifuge_cal as cc
from conftest import synthetic


def test_known_coefficients_are_recovered() -> None:
    d = synthetic()
    fit = cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=d.rate_deg_s)
    assert fit.revolutions_used == 8
    assert fit.revolutions_available == 8
    assert fit.incomplete_revolution is not None
    assert fit.samples == d.time_s.shape[0]
    assert fit.mean.l0 == pytest.approx(d.l0, abs=1e-9)
    np.testing.assert_allclose(fit.mean.c, d.c, atol=1e-9)
    np.testing.assert_allclose(fit.mean.s, d.s, atol=1e-9)
    assert fit.first_harmonic.amplitude == pytest.approx(np.hypot(d.c[0], d.s[0]), rel=1e-9)
    assert fit.per_revolution.c.shape == (8, 4)
    assert fit.per_revolution.l0.shape == (8,)
    assert fit.angle_source == "declared_rate"
    assert [w.code for w in fit.warnings] == ["angle_from_rate"]
    assert fit.measured_rate_deg_s is None
    assert fit.rate_rad_s == pytest.approx(np.radians(120.0))


def test_the_numpy_lstsq_of_each_revolution_agrees() -> None:
    d = synthetic(noise=0.05, seed=7)
    fit = cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=d.rate_deg_s, drift=False)
    w = np.radians(d.rate_deg_s)
    theta = w * (d.time_s - d.time_s[0])
    k = np.arange(1, 5)
    for r in range(fit.revolutions_used):
        first = int(fit.per_revolution.first_sample[r])
        n = int(fit.per_revolution.samples[r])
        th = theta[first : first + n]
        a = np.column_stack([np.ones_like(th), np.cos(np.outer(th, k)), np.sin(np.outer(th, k))])
        x, *_ = np.linalg.lstsq(a, d.gap[first : first + n], rcond=None)
        assert fit.per_revolution.l0[r] == pytest.approx(x[0], abs=1e-10)
        np.testing.assert_allclose(fit.per_revolution.c[r], x[1:5], atol=1e-10)
        np.testing.assert_allclose(fit.per_revolution.s[r], x[5:], atol=1e-10)
    # the standard error is the spread of the revolutions over √K
    std = np.std(fit.per_revolution.c[:, 0], ddof=1)
    assert fit.std is not None and fit.std_error is not None
    assert fit.std.c[0] == pytest.approx(std, rel=1e-9)
    assert fit.std_error.c[0] == pytest.approx(std / np.sqrt(8), rel=1e-9)


def test_an_encoder_angle_gives_the_measured_rate() -> None:
    d = synthetic()
    fit = cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=120.0, angle_rad=d.angle_rad)
    assert fit.angle_source == "encoder"
    assert fit.measured_rate_deg_s == pytest.approx(120.0, rel=1e-12)
    assert fit.warnings == ()
    np.testing.assert_allclose(fit.mean.c, d.c, atol=1e-9)
    # a declared rate 0.5 % off: the measured one is used, and a warning says so
    off = cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=120.6, angle_rad=d.angle_rad)
    assert [w.code for w in off.warnings] == ["rate_differs"]
    assert "differs from the declared 120.600000 deg/s" in off.warnings[0].message
    assert off.rate_rad_s == pytest.approx(np.radians(120.0), rel=1e-12)


def test_drift_and_the_probe_direction() -> None:
    d = synthetic()
    gap = d.gap + 0.01 * d.time_s
    fit = cc.fit_harmonics(d.time_s, gap, rate_deg_s=d.rate_deg_s, drift=True)
    assert fit.mean.drift_per_s == pytest.approx(0.01, rel=1e-6)
    assert fit.per_revolution.drift_per_s is not None
    along = cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=d.rate_deg_s, probe_along=True)
    against = cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=d.rate_deg_s)
    assert along.first_harmonic.probe_direction == "along_o1x1"
    beta_diff = (along.first_harmonic.beta_deg - against.first_harmonic.beta_deg) % 360.0
    assert beta_diff == pytest.approx(180.0, abs=1e-9)


def test_to_dict_is_plain_json() -> None:
    import json

    d = synthetic(turns=3.2)
    fit = cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=d.rate_deg_s, revolutions=2)
    out = fit.to_dict()
    assert out["revolutions_used"] == 2
    assert json.loads(json.dumps(out))["per_revolution"]["c"] == fit.per_revolution.c.tolist()


def test_contiguous_float64_input_is_not_copied_and_a_strided_one_is_accepted() -> None:
    d = synthetic()
    before = d.gap.copy()
    cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=d.rate_deg_s)
    np.testing.assert_array_equal(d.gap, before)
    both = np.column_stack([d.time_s, d.gap])  # columns are strided views
    a = cc.fit_harmonics(both[:, 0], both[:, 1], rate_deg_s=d.rate_deg_s)
    b = cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=d.rate_deg_s)
    assert a.mean == b.mean
    # lists of floats are arrays too
    c = cc.fit_harmonics(list(d.time_s), list(d.gap), rate_deg_s=d.rate_deg_s)
    assert c.mean == b.mean




def _bad_cases() -> list[tuple[str, Any, Any, dict[str, Any], str, str]]:
    d = synthetic(turns=3.5)
    t, g = d.time_s, d.gap
    nan = g.copy()
    nan[17] = np.nan
    back = t.copy()
    back[40] = back[39]
    return [
        ("nan in gap", t, nan, {}, "gap", "sample 17: `gap` is not finite (NaN)"),
        ("masked", t, np.ma.masked_array(g, mask=g > g.mean()), {}, "gap", "a masked array"),
        ("length", t, g[:-1], {}, "gap", f"gap: {t.shape[0] - 1} values, {t.shape[0]} expected"),
        ("time not increasing", back, g, {}, "time_s", "sample 40: time"),
        ("2-D", np.column_stack([t, t]), g, {}, "time_s", "a 1-D array is needed"),
        ("boolean dtype", t, np.ones(t.shape[0], dtype=bool), {}, "gap", "a boolean array (dtype bool)"),
        ("float32", t.astype(np.float32), g, {}, "time_s", "a lower-precision float array"),
        ("angle length", t, g, {"angle_rad": d.angle_rad[:5]}, "angle_rad", "angle_rad: 5 values"),
        ("order 0", t, g, {"order": 0}, "", "order"),
        ("empty", t[:0], g[:0], {}, "", ""),
        ("too short", t[:100], g[:100], {}, "", "revolution"),
    ]


@pytest.mark.parametrize("case", _bad_cases(), ids=lambda c: c[0])
def test_bad_arrays_raise_input_error(case: tuple[str, Any, Any, dict[str, Any], str, str]) -> None:
    _, t, g, extra, field, words = case
    with pytest.raises(cc.InputError) as e:
        cc.fit_harmonics(t, g, rate_deg_s=120.0, **extra)
    assert isinstance(e.value, ValueError)
    assert isinstance(e.value, cc.CentrifugeCalError)
    assert words in str(e.value)
    if field:
        assert e.value.field == field


def test_two_threads_fit_at_once_as_one_does_alone() -> None:
    a = synthetic(noise=0.05, seed=1, turns=40)
    b = synthetic(noise=0.05, seed=2, turns=40, rate_deg_s=90.0)
    alone = [cc.fit_harmonics(x.time_s, x.gap, rate_deg_s=x.rate_deg_s) for x in (a, b)]
    results: dict[int, list[cc.HarmonicFit]] = {0: [], 1: []}
    errors: list[BaseException] = []
    barrier = threading.Barrier(2)

    def work(i: int, x: Any) -> None:
        try:
            barrier.wait()
            for _ in range(5):
                results[i].append(cc.fit_harmonics(x.time_s, x.gap, rate_deg_s=x.rate_deg_s))
        except BaseException as e:  # noqa: BLE001 - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(i, x)) for i, x in enumerate((a, b))]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert not errors
    for i in (0, 1):
        assert len(results[i]) == 5
        for r in results[i]:
            assert r.mean == alone[i].mean
            np.testing.assert_array_equal(r.per_revolution.c, alone[i].per_revolution.c)


def test_a_drifting_gap_fitted_without_drift_is_warned_about() -> None:
    d = synthetic(noise=0.01, seed=3)
    drifting = d.gap + 0.5 * d.time_s  # 0.5 µm/s: a probe warming up
    fit = cc.fit_harmonics(
        d.time_s, drifting, rate_deg_s=d.rate_deg_s, angle_rad=d.angle_rad, drift=False
    )
    codes = [w.code for w in fit.warnings]
    assert "drift_not_fitted" in codes, codes
    message = fit.warnings[codes.index("drift_not_fitted")].message
    assert "drift: true" in message and "per second" in message
    # fitted with the drift term (the study's default, and so Python's), the same samples
    # give no such warning
    with_drift = cc.fit_harmonics(d.time_s, drifting, rate_deg_s=d.rate_deg_s, angle_rad=d.angle_rad)
    assert with_drift.drift
    assert "drift_not_fitted" not in [w.code for w in with_drift.warnings]


def test_a_first_harmonic_that_changes_between_revolutions_is_warned_about() -> None:
    d = synthetic(noise=0.01, seed=4)
    w = np.radians(d.rate_deg_s)
    theta = w * d.time_s
    revolution = np.floor(theta / (2 * np.pi))
    # the first harmonic's amplitude steps by 2 % from one revolution to the next
    wobbling = d.gap + 0.02 * (revolution % 2) * (d.c[0] * np.cos(theta) + d.s[0] * np.sin(theta))
    fit = cc.fit_harmonics(d.time_s, wobbling, rate_deg_s=d.rate_deg_s, angle_rad=d.angle_rad)
    codes = [w.code for w in fit.warnings]
    assert "revolution_spread" in codes, codes
    assert "more than white noise explains" in fit.warnings[codes.index("revolution_spread")].message
    # the same recording without the step: no warning
    steady = cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=d.rate_deg_s, angle_rad=d.angle_rad)
    assert steady.warnings == ()
