"""Hostile and careless input (issue 32): every public function fed every bad type raises
only the package's classes; deep and self-holding structures, masked arrays and a billion
trials give a clear error, not a crash; big-endian float64 and integer lists are taken; and
Ctrl-C stops a long call within 0.1 s."""

from __future__ import annotations

import os
import signal
import threading
import time
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import centrifuge_cal as cc
from conftest import ROOT, synthetic

CSV = ROOT / "fixtures" / "recordings" / "probe_120deg_s.csv"
PLAN = ROOT / "fixtures" / "plans" / "paper-centrifuge.ron"
R_M, G, K1 = 2.5, 9.8, 0.56


@pytest.fixture(autouse=True)
def quiet() -> Iterator[None]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cc.CentrifugeCalWarning)
        yield


def _deep(levels: int) -> dict[str, Any]:
    root: dict[str, Any] = {}
    node = root
    for _ in range(levels):
        node["a"] = {}
        node = node["a"]
    return root


def _recursive() -> dict[str, Any]:
    d: dict[str, Any] = {"name": "loop"}
    d["phases"] = [d]
    return d


def _table() -> tuple[np.ndarray[Any, Any], ...]:
    """Eq. 18 outputs at 12 rates with a spindle's C_r folded in, and its radius errors."""
    rates = np.linspace(20.0, 200.0, 12)
    w = np.radians(rates)
    a_g = w**2 * R_M / G
    c_r = -4.05e-8
    rng = np.random.default_rng(11)
    y = 1e-5 + K1 * a_g + (5e-7 + K1 * c_r * G / R_M**2) * a_g**2 + 2e-8 * a_g**3
    y = y + rng.normal(0, 2e-8, 12)
    err_um = (1.0e-6 + c_r * w**2) * 1e6 + rng.normal(0, 0.005, 12)
    return rates, y, np.full(12, 2e-8), err_um


MASKED = np.ma.masked_array([1.0, 2.0, 3.0], mask=[False, True, False])
#: Every bad value a careless caller hands over.
BAD: dict[str, Any] = {
    "None": None,
    "str": "1.5",
    "dict": {"a": 1.0},
    "nested lists": [[1.0, 2.0], [3.0, 4.0]],
    "ragged lists": [[1.0], [2.0, 3.0]],
    "list with None": [1.0, None, 3.0],
    "complex dtype": np.array([1.0 + 1j, 2.0]),
    "object dtype": np.array([object(), object()]),
    "float32": np.array([1.0, 2.0], dtype=np.float32),
    "bool": True,
    "2-D array": np.ones((3, 2)),
    "NaN": float("nan"),
    "NaN array": np.array([1.0, np.nan, 3.0]),
    "masked": MASKED,
    "minus one": -1,
    "huge int": 10**30,
    "huge int list": [10**30, 1],
    "one-tuple": (0.56,),
    "recursive dict": _recursive(),
    "20,000-deep dict": _deep(20_000),
    "empty list": [],
}


def _calls() -> list[tuple[str, Callable[..., Any], dict[str, Any]]]:
    """Every public function with good arguments (each bad value replaces one of them)."""
    d = synthetic(turns=3.5)
    rates, y, sigma, err_um = _table()
    spindle = cc.fit_radius_error(rates, err_um)
    recording = cc.read_recording(CSV)
    phases = {
        "before": {
            "first_harmonic": [
                {"rate_deg_s": r, "dc1_um": -3.0 - 0.01 * r, "ds1_um": -1.0} for r in rates
            ]
        }
    }
    common = dict(
        radius_m=R_M, g_m_s2=G, k1_rad_s_g=K1, pivot_to_probe_mm=700.0, probe_to_piga_mm=510.0
    )
    study = {
        "name": "s",
        "radius_m": R_M,
        "g_m_s2": G,
        "k1_rad_s_g": K1,
        "lever": {"pivot_to_probe_mm": 700.0, "probe_to_piga_mm": 510.0},
        "phases": [
            {
                "name": "p",
                "points": {
                    "radius_error": [
                        {"rate_deg_s": 10.0, "radius_error_um": 1.0},
                        {"rate_deg_s": 100.0, "radius_error_um": 0.9},
                        {"rate_deg_s": 200.0, "radius_error_um": 0.6},
                    ]
                },
            }
        ],
    }
    return [
        ("read_recording", cc.read_recording, dict(path=CSV, format=None, group=None)),
        (
            "Recording.fit_harmonics",
            recording.fit_harmonics,
            dict(rate_deg_s=120.0, order=4, drift=True, revolutions=None, probe_along=False),
        ),
        (
            "fit_harmonics",
            cc.fit_harmonics,
            dict(
                time_s=d.time_s,
                gap=d.gap,
                rate_deg_s=120.0,
                angle_rad=None,
                start_angle_deg=0.0,
                order=4,
                drift=True,
                revolutions=None,
                max_gap_intervals=3.0,
                probe_along=False,
                gap_unit="um",
            ),
        ),
        (
            "fit_radius_error",
            cc.fit_radius_error,
            dict(rate_deg_s=rates, radius_error_um=err_um, sigma_um=None, model="two_term"),
        ),
        (
            "delta_k2",
            cc.delta_k2,
            dict(k1_rad_s_g=K1, c_r_m_s2=-4e-8, c_r_sigma_m_s2=1e-9, radius_m=R_M, g_m_s2=G),
        ),
        (
            "RadiusFit.delta_k2",
            spindle.delta_k2,
            dict(k1_rad_s_g=K1, radius_m=R_M, g_m_s2=G),
        ),
        (
            "calibrate",
            cc.calibrate,
            dict(
                rate_deg_s=rates,
                output_rad_s=y,
                compensate_with=spindle,
                output_sigma_rad_s=sigma,
                labels=None,
                k1="fitted",
                uncertainty=None,
                seed=1,
                trials=2000,
                **common,
            ),
        ),
        (
            "calibrate_two_orientation",
            cc.calibrate_two_orientation,
            dict(
                rate_in_deg_s=rates,
                output_in_rad_s=y,
                rate_out_deg_s=rates,
                output_out_rad_s=y * 1.001,
                radius_in_m=R_M,
                radius_out_m=R_M + 0.04,
                compare_with=spindle,
                g_m_s2=G,
                k1_rad_s_g=K1,
                pivot_to_probe_mm=700.0,
                probe_to_piga_mm=510.0,
                trials=2000,
            ),
        ),
        (
            "advise_balance",
            cc.advise_balance,
            dict(
                phases=phases,
                balance={"initial": "before", "radial_stiffness_n_m": 5e7, "correction_radius_m": 2.5},
                **common,
            ),
        ),
        ("plan", cc.plan, dict(config=PLAN)),
        ("run_study", cc.run_study, dict(config=study, base_dir=None)),
    ]


CALLS = _calls()


@pytest.mark.parametrize("bad", list(BAD), ids=list(BAD))
@pytest.mark.parametrize("call", CALLS, ids=[c[0] for c in CALLS])
def test_every_bad_type_raises_only_the_packages_classes(
    call: tuple[str, Callable[..., Any], dict[str, Any]], bad: str
) -> None:
    name, function, good = call
    refused = 0
    for argument in good:
        kwargs = dict(good, **{argument: BAD[bad]})
        try:
            function(**kwargs)
        except cc.CentrifugeCalError as e:
            refused += 1
            assert str(e), (name, argument, bad)
            assert e.message == str(e)
        except Exception as e:  # noqa: BLE001 - the point of the test
            pytest.fail(f"{name}({argument}={bad}) raised {type(e).__name__}: {e}")
    # a bad value is refused somewhere (None is a valid value of optional arguments only;
    # 1e30 is a finite number for Δk2, which it computes)
    assert refused > 0 or (name.endswith("delta_k2") and bad == "huge int"), (name, bad)


@pytest.mark.parametrize(
    "call,argument,value,kind,field",
    [
        ("fit_harmonics", "order", -1, cc.InputError, "order"),
        ("fit_harmonics", "order", 10**30, cc.InputError, "order"),
        ("calibrate", "k1", (0.56,), cc.InputError, "k1"),
        ("calibrate", "trials", 10**9, cc.InputError, "trials"),
        ("calibrate", "trials", 10**30, cc.InputError, "trials"),
        ("fit_harmonics", "gap", MASKED, cc.InputError, "gap"),
        ("run_study", "config", _deep(20_000), cc.ConfigError, None),
        ("run_study", "config", _recursive(), cc.ConfigError, None),
        ("plan", "config", _deep(20_000), cc.ConfigError, None),
        ("read_recording", "format", _deep(20_000), cc.ConfigError, None),
    ],
)
def test_named_cases_give_their_class(
    call: str, argument: str, value: Any, kind: type[cc.CentrifugeCalError], field: str | None
) -> None:
    _, function, good = next(c for c in CALLS if c[0] == call)
    with pytest.raises(kind) as e:
        function(**dict(good, **{argument: value}))
    if field is not None:
        assert e.value.field == field
    if "deep" in str(e.value) or "nested" in str(e.value):
        assert "64 levels" in str(e.value)


def test_a_billion_trials_in_a_study_file_is_refused_not_allocated(tmp_path: Any) -> None:
    # Python refuses it up front; a study file's reaches the Monte Carlo method, which
    # refuses it before it allocates (the study's own cap: `check` refuses it too once it
    # has one)
    rates, y, _, err_um = _table()
    (tmp_path / "piga.csv").write_text(
        "rate_deg_s,output_rad_s\n" + "".join(f"{r!r},{o!r}\n" for r, o in zip(rates, y))
    )
    points = ", ".join(
        f"(rate_deg_s: {r!r}, radius_error_um: {e!r})" for r, e in zip(rates, err_um)
    )
    study = tmp_path / "cal.ron"
    study.write_text(
        f"""(name: "c", radius_m: 2.5, g_m_s2: 9.8, k1_rad_s_g: 0.56,
        lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0),
        phases: [(name: "spindle", points: radius_error([{points}]))],
        calibration: (table: (file: "piga.csv"), compensate_with: "spindle",
                      trials: fixed(1000000000)))"""
    )
    with pytest.raises(cc.CentrifugeCalError) as e:
        cc.run_study(study)
    assert "trials" in str(e.value)


def test_a_masked_glitch_is_refused_not_read_through_its_mask() -> None:
    d = synthetic(turns=4.5)
    glitched = d.gap.copy()
    glitched[200] = 1e4
    masked = np.ma.masked_array(glitched, mask=np.arange(glitched.size) == 200)
    with pytest.raises(cc.InputError, match="masked array") as e:
        cc.fit_harmonics(d.time_s, masked, rate_deg_s=d.rate_deg_s)
    assert e.value.field == "gap"
    with pytest.raises(cc.ConfigError, match="masked array"):
        cc.plan({"centrifuge": {"rates": masked}})


def test_big_endian_float64_gives_the_native_result() -> None:
    d = synthetic(turns=4.5)
    native = cc.fit_harmonics(d.time_s, d.gap, rate_deg_s=d.rate_deg_s)
    big = cc.fit_harmonics(
        d.time_s.astype(">f8"), d.gap.astype(">f8"), rate_deg_s=d.rate_deg_s
    )
    assert big.mean == native.mean
    rates, _, _, err_um = _table()
    assert (
        cc.fit_radius_error(rates.astype(">f8"), err_um.astype(">f8")).c_r_m_s2
        == cc.fit_radius_error(rates, err_um).c_r_m_s2
    )


def test_integer_lists_are_numbers() -> None:
    rates = [20, 40, 60, 80, 100, 120]
    err_um = [1, 1, 0, 0, -1, -2]
    as_int = cc.fit_radius_error(rates, err_um)
    as_float = cc.fit_radius_error([float(r) for r in rates], [float(e) for e in err_um])
    assert as_int.c_r_m_s2 == as_float.c_r_m_s2
    assert cc.fit_radius_error(np.array(rates, dtype=np.int32), err_um).c_r_m_s2 == as_float.c_r_m_s2
    fit = cc.delta_k2(k1_rad_s_g=1, c_r_m_s2=-4e-8, c_r_sigma_m_s2=0, radius_m=2, g_m_s2=10)
    assert fit.delta_k2_rad_s_g2 == pytest.approx(-4e-8 * 10 / 4)
    with pytest.raises(cc.InputError, match="2⁵³"):
        cc.fit_radius_error([2**60, 2, 3], [1.0, 2.0, 3.0])


# -- Ctrl-C ---------------------------------------------------------------------------

#: How long after the signal the call must have raised.
BOUND_S = 0.1


def _long_calibration() -> None:
    rates, y, sigma, err_um = _table()
    cc.calibrate(
        rates,
        y,
        output_sigma_rad_s=sigma,
        compensate_with=cc.fit_radius_error(rates, err_um),
        radius_m=R_M,
        g_m_s2=G,
        k1_rad_s_g=K1,
        pivot_to_probe_mm=700.0,
        probe_to_piga_mm=510.0,
        trials=cc.STUDY_DEFAULTS["max_trials"],
    )


def _long_study() -> None:
    rates, y, _, err_um = _table()
    cc.run_study(
        {
            "name": "long",
            "radius_m": R_M,
            "g_m_s2": G,
            "k1_rad_s_g": K1,
            "lever": {"pivot_to_probe_mm": 700.0, "probe_to_piga_mm": 510.0},
            "phases": [
                {
                    "name": "spindle",
                    "points": {
                        "radius_error": [
                            {"rate_deg_s": float(r), "radius_error_um": float(e)}
                            for r, e in zip(rates, err_um)
                        ]
                    },
                }
            ],
            "calibration": {
                "table": {"file": str(ROOT / "fixtures" / "campaign" / "piga.csv")},
                "compensate_with": "spindle",
                "trials": {"fixed": cc.STUDY_DEFAULTS["max_trials"]},
            },
        }
    )


@pytest.mark.parametrize("long_call", [_long_calibration, _long_study], ids=["calibrate", "run_study"])
def test_ctrl_c_stops_a_long_call_within_a_tenth_of_a_second(long_call: Callable[[], None]) -> None:
    sent: list[float] = []

    def interrupt() -> None:
        sent.append(time.perf_counter())
        os.kill(os.getpid(), signal.SIGINT)

    # Python raises KeyboardInterrupt only when SIGINT has its default handler; a process
    # started in the background by a non-interactive shell inherits SIGINT ignored, and
    # Python then leaves it ignored. Install the handler a terminal's Python has.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.3, interrupt)
    start = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt) as e:
            long_call()
        raised = time.perf_counter()
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert sent, "the call ended before the signal: it is not long enough to test"
    latency = raised - sent[0]
    print(f"Ctrl-C latency {latency * 1e3:.1f} ms (signal sent {sent[0] - start:.2f} s in)")
    assert latency < BOUND_S, f"KeyboardInterrupt {latency:.3f} s after SIGINT"
    # raised from inside the native call, not before or after it
    frames = [f.name for f in e.traceback]
    assert frames[-1] in ("_study_dict", "run_study"), frames
    # the package works on after it
    rates, _, _, err_um = _table()
    assert cc.fit_radius_error(rates, err_um).c_r_m_s2 < 0


def test_one_glitch_in_arrays_is_warned_and_dropped_as_the_study_does(tmp_path: Path) -> None:
    # Issue 32: one glitch sample moved a rate's first harmonic with no warning. The arrays
    # get the study's outlier check: the same warning, the same revolution left out, the
    # same numbers as the recording read from a file.
    d = synthetic(turns=8.3, noise=0.01, seed=3)
    glitched = d.gap.copy()
    n_rev = d.time_s.shape[0] / 8.3
    at = int(3.02 * n_rev)  # near the angle 0: the glitch moves c1 the most
    glitched[at] += 900.0
    fit = cc.fit_harmonics(d.time_s, glitched, rate_deg_s=d.rate_deg_s)
    codes = [w.code for w in fit.warnings]
    assert "residual_outlier" in codes, codes
    assert fit.revolutions_used == 7
    assert fit.mean.c[0] == pytest.approx(d.c[0], abs=0.01)
    kept = cc.fit_harmonics(d.time_s, glitched, rate_deg_s=d.rate_deg_s, on_outlier="keep")
    assert "residual_outlier" in [w.code for w in kept.warnings]
    assert kept.revolutions_used == 8
    assert abs(kept.mean.c[0] - d.c[0]) > 0.05
    with pytest.raises(cc.InputError, match="on_outlier") as e:
        cc.fit_harmonics(
            d.time_s, glitched, rate_deg_s=d.rate_deg_s, on_outlier="drop"  # type: ignore[arg-type]
        )
    assert e.value.field == "on_outlier"
    # The same samples in a file, read as the study reads them.
    path = tmp_path / "glitch.csv"
    np.savetxt(path, np.column_stack([d.time_s, glitched]), delimiter=",", header="time_s,gap_um",
               comments="", fmt="%.17g")
    from_file = cc.read_recording(path).fit_harmonics(rate_deg_s=d.rate_deg_s)
    assert [w.code for w in from_file.warnings] == codes
    np.testing.assert_allclose(from_file.mean.c, fit.mean.c, rtol=1e-12)
