"""The radius-error fit and Δk2, the calibration with its uncertainty budget, the balance
advisor and the planner: on known synthetic data, and equal to the command line."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import centrifuge_cal as cc
from conftest import ROOT, xtask

R_M, G, K1 = 2.5, 9.8, 0.56


def test_radius_fit_recovers_c_r() -> None:
    rates = np.array([10.0, 40.0, 80.0, 120.0, 160.0, 200.0])
    w = np.radians(rates)
    c_r = -4.05e-8
    err_um = (1.5e-6 + c_r * w**2) * 1e6
    fit = cc.fit_radius_error(rates, err_um)
    assert fit.c_r_m_s2 == pytest.approx(c_r, rel=1e-9)
    assert fit.offset_m == pytest.approx(1.5e-6, rel=1e-9)
    assert fit.dof == 4
    assert fit.linear_m_s is None
    assert fit.warnings == ()
    three = cc.fit_radius_error(rates, err_um, model="three_term")
    assert three.linear_m_s == pytest.approx(0.0, abs=1e-12)
    weighted = cc.fit_radius_error(rates, err_um, sigma_um=np.full(6, 0.01))
    assert weighted.weighted and weighted.c_r_m_s2 == pytest.approx(c_r, rel=1e-9)


def test_radius_fit_sigma_is_the_least_squares_one() -> None:
    rng = np.random.default_rng(3)
    rates = np.linspace(10.0, 200.0, 12)
    w = np.radians(rates)
    y = 1.0 + (-4e-8 * w**2) * 1e6 + rng.normal(0, 0.02, 12)
    fit = cc.fit_radius_error(rates, y)
    x = np.column_stack([np.ones(12), w**2])
    beta, res, *_ = np.linalg.lstsq(x, y * 1e-6, rcond=None)
    s2 = res[0] / (12 - 2)
    cov = s2 * np.linalg.inv(x.T @ x)
    assert fit.c_r_m_s2 == pytest.approx(beta[1], rel=1e-9)
    assert fit.c_r_sigma_m_s2 == pytest.approx(np.sqrt(cov[1, 1]), rel=1e-6)


def test_delta_k2_is_eq_19() -> None:
    d = cc.delta_k2(k1_rad_s_g=K1, c_r_m_s2=-4.05e-8, c_r_sigma_m_s2=1e-9, radius_m=R_M, g_m_s2=G)
    assert d.delta_k2_rad_s_g2 == pytest.approx(K1 * -4.05e-8 * G / R_M**2, rel=1e-15)
    assert d.sigma_rad_s_g2 == pytest.approx(K1 * 1e-9 * G / R_M**2, rel=1e-15)
    with pytest.raises(cc.InputError) as e:
        cc.delta_k2(k1_rad_s_g=K1, c_r_m_s2=1e-8, c_r_sigma_m_s2=1e-9, radius_m=0.0, g_m_s2=G)
    assert "radius" in str(e.value)


def test_bad_radius_fit_inputs() -> None:
    with pytest.raises(cc.InputError, match="rate_deg_s"):
        cc.fit_radius_error([10.0, np.nan, 30.0], [1.0, 2.0, 3.0])
    with pytest.raises(cc.InputError, match="radius_error_um: 2 values, 3 expected"):
        cc.fit_radius_error([10.0, 20.0, 30.0], [1.0, 2.0])
    with pytest.raises(cc.InputError, match="model"):
        cc.fit_radius_error([10.0, 20.0, 30.0], [1.0, 2.0, 3.0], model="cubic")  # type: ignore[arg-type]
    with pytest.raises(cc.ComputationError):
        cc.fit_radius_error([10.0, 10.0, 10.0], [1.0, 2.0, 3.0])


def _campaign_table() -> tuple[np.ndarray[Any, Any], ...]:
    """PIGA outputs of eq. 18 at 12 rates with the C_r of a spindle fit folded in."""
    rates = np.linspace(20.0, 200.0, 12)
    w = np.radians(rates)
    a_g = w**2 * R_M / G
    k0, k1, k2, k3 = 1e-5, 0.56, 5e-7, 2e-8
    c_r = -4.05e-8
    dk2 = k1 * c_r * G / R_M**2
    rng = np.random.default_rng(11)
    y = k0 + k1 * a_g + (k2 + dk2) * a_g**2 + k3 * a_g**3 + rng.normal(0, 2e-8, 12)
    err_um = (1.0e-6 + c_r * w**2) * 1e6 + rng.normal(0, 0.005, 12)
    return rates, y, np.full(12, 2e-8), err_um


def test_calibrate_recovers_k2_with_its_budget() -> None:
    rates, y, sigma, err_um = _campaign_table()
    spindle = cc.fit_radius_error(rates, err_um)
    cal = cc.calibrate(
        rates,
        y,
        output_sigma_rad_s=sigma,
        compensate_with=spindle,
        radius_m=R_M,
        g_m_s2=G,
        k1_rad_s_g=K1,
        pivot_to_probe_mm=700.0,
        probe_to_piga_mm=510.0,
        uncertainty={
            "radius_u_m": 5e-5,
            "g_u_m_s2": 1e-5,
            "g_source": "gravimeter",
            "rate_u_relative": 0.0,
            "pivot_to_probe_u_mm": 0.5,
            "probe_to_piga_u_mm": 0.5,
            "probe_gain_u_relative": 2e-3,
            # every Type B input is stated; a zero with its reason
            "zero_reasons": {"rate_u_relative": "encoder against the frequency standard"},
        },
        trials=20000,
    )
    d = cal.to_dict()
    assert json.loads(json.dumps(d)) == d
    text = json.dumps(d)
    for word in ("k2", "monte_carlo", "budget"):
        assert word in text
    assert cal.study.calibration is d


def test_calibrate_equals_the_same_study_from_files(tmp_path: Path) -> None:
    rates, y, sigma, err_um = _campaign_table()
    spindle = cc.fit_radius_error(rates, err_um)
    kwargs: dict[str, Any] = dict(
        compensate_with=spindle,
        radius_m=R_M,
        g_m_s2=G,
        k1_rad_s_g=K1,
        pivot_to_probe_mm=700.0,
        probe_to_piga_mm=510.0,
        output_sigma_rad_s=sigma,
        trials=5000,
    )
    cal = cc.calibrate(rates, y, **kwargs)
    table = tmp_path / "piga.csv"
    table.write_text(
        "rate_deg_s,output_rad_s,sigma_rad_s\n"
        + "".join(f"{r!r},{o!r},{s!r}\n" for r, o, s in zip(rates.tolist(), y.tolist(), sigma.tolist()))
    )
    points = ",\n".join(
        f"(rate_deg_s: {r!r}, radius_error_um: {e!r})" for r, e in zip(rates.tolist(), err_um.tolist())
    )
    study = tmp_path / "cal.ron"
    study.write_text(
        f"""(name: "calibration", radius_m: 2.5, g_m_s2: 9.8, k1_rad_s_g: 0.56,
        lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0),
        phases: [(name: "spindle", points: radius_error([{points}]))],
        calibration: (table: (file: "piga.csv", sigma_column: "sigma_rad_s"),
                      compensate_with: "spindle", trials: fixed(5000)))"""
    )
    cli = xtask("study", "--config", str(study), "--out", str(tmp_path / "out"), "--no-compare")
    assert cli.status == 0, cli.stderr
    expected = json.loads((tmp_path / "out" / "results.json").read_text())["calibration"]
    from test_studies import assert_close

    # the arrays are the study's table, named `<arrays piga>` where a file would be
    assert cal.to_dict()["table"] == "<arrays piga>"
    got = json.loads(json.dumps(cal.to_dict()).replace("<arrays piga>", str(table)))
    # an array's rows are numbered from 1 where a file's lines count its header too
    for residual in got["residuals"]:
        residual["line"] += 1
    assert_close(got, json.loads(json.dumps(expected)))


def test_calibrate_is_identify_on_a_table_scattering_3_sigma(tmp_path: Path) -> None:
    """One calibration, one voice (issue 31): a weighted table whose points scatter three
    times their stated σ gives the same k0…k3, u, Birge ratio, τ and warnings from
    :func:`calibrate` as from ``centrifuge-cal identify`` (1e-12 relative)."""
    rates = np.array([20.0, 35.0, 50.0, 65.0, 80.0, 95.0, 110.0, 125.0, 140.0, 155.0, 170.0, 185.0])
    w = np.radians(rates)
    a = R_M * w**2 / G
    sigma = np.full(12, 1e-9)
    pattern = np.array([3.0, -2.5, 4.5, -3.5, 1.0, -4.0, 2.5, -1.5, 3.5, -3.0, 2.0, -4.0])
    y = 1e-5 + K1 * a + 5e-7 * a**2 + 2e-8 * a**3 + pattern * sigma
    err_um = (1.5e-6 - 4e-8 * w**2) * 1e6 + 0.002 * np.sin(np.arange(12.0))
    spindle = cc.fit_radius_error(rates, err_um)
    with pytest.warns(cc.CentrifugeCalWarning):
        cal = cc.calibrate(
            rates, y, compensate_with=spindle, radius_m=R_M, g_m_s2=G, k1_rad_s_g=K1,
            pivot_to_probe_mm=700.0, probe_to_piga_mm=510.0, output_sigma_rad_s=sigma,
            trials=2000,
        )
    table = tmp_path / "piga.csv"
    table.write_text(
        "rate_deg_s,output_rad_s,sigma_rad_s\n"
        + "".join(f"{r!r},{o!r},{s!r}\n" for r, o, s in zip(rates.tolist(), y.tolist(), sigma.tolist()))
    )
    cli = xtask(
        "identify", str(table), "--sigma-column", "sigma_rad_s", "--radius-m", "2.5",
        "--g", "9.8", "--c-r-m-s2", repr(spindle.c_r_m_s2),
        "--c-r-sigma-m-s2", repr(spindle.c_r_sigma_m_s2), "--json",
    )
    assert cli.status == 0, cli.stderr
    i = json.loads(cli.stdout)
    c = cal.to_dict()

    def same(what: str, a: float, b: float) -> None:
        assert a == pytest.approx(b, rel=1e-12), what

    assert 2.0 < i["birge_ratio"] < 4.5
    same("Birge ratio", i["birge_ratio"], c["birge_ratio"])
    same("τ", i["excess_u_rad_s"], c["excess_u_rad_s"])
    for name, v in (
        ("k0", i["coefficients"]["bias_rad_s"]),
        ("k1", i["k1_implied_rad_s_g"]),
        ("k2", i["coefficients"]["k2_apparent_rad_s_g2"]),
        ("k3", i["coefficients"]["k3_rad_s_g3"]),
    ):
        same(name, v["value"], c["uncompensated"][name]["value"])
        same(f"u({name})", v["sigma"], c["uncompensated"][name]["u"])
    same("k2", i["compensated"]["k2_rad_s_g2"], c["coefficients"]["k2"]["value"])
    same("u(k2)", i["compensated"]["k2_sigma_rad_s_g2"], c["coefficients"]["k2"]["u"])
    same("residual SD", i["residual_sd_rad_s"], c["residual_sd_rad_s"])
    study_warnings = {(x["code"], x["message"]) for x in cal.study.warnings}
    assert [x["code"] for x in i["warnings"]] == ["calibration_lack_of_fit"]
    for x in i["warnings"]:
        assert (x["code"], x["message"]) in study_warnings


def test_calibrate_refuses_bad_arrays() -> None:
    rates, y, sigma, err_um = _campaign_table()
    spindle = cc.fit_radius_error(rates, err_um)
    common: dict[str, Any] = dict(
        compensate_with=spindle, radius_m=R_M, g_m_s2=G, k1_rad_s_g=K1,
        pivot_to_probe_mm=700.0, probe_to_piga_mm=510.0,
    )
    with pytest.raises(cc.InputError, match="output_rad_s: 11 values, 12 expected"):
        cc.calibrate(rates, y[:-1], **common)
    bad = y.copy()
    bad[3] = np.inf
    with pytest.raises(cc.InputError, match=r"output_rad_s\[3\] is not finite"):
        cc.calibrate(rates, bad, **common)


def _balance_fixture() -> tuple[dict[str, Any], dict[str, Any]]:
    """The phases and balance section of fixtures/studies/balance-simulated.ron, as dicts
    (read from the file's RON by its simple structure)."""
    import re

    text = (ROOT / "fixtures" / "studies" / "balance-simulated.ron").read_text()
    phases: dict[str, Any] = {}
    for name, body in re.findall(r'\(name: "(\w+)", points: first_harmonic\(\[(.*?)\]\)\)', text, re.S):
        phases[name] = {
            "first_harmonic": [
                {"rate_deg_s": float(r), "dc1_um": float(c), "ds1_um": float(s)}
                for r, c, s in re.findall(
                    r"rate_deg_s: ([-\d.]+), dc1_um: ([-\d.]+), ds1_um: ([-\d.]+)", body
                )
            ]
        }
    balance = {
        "initial": "before",
        "trial": "trial",
        "trial_mass": {"mass_kg": 8.0, "radius_m": 2.5, "azimuth_deg": 90.0},
        "radial_stiffness_n_m": 5.0e7,
        "correction_radius_m": 2.5,
        "fixed_azimuths_deg": [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0],
        "rotor_mass_kg": 2000.0,
        "check": "check",
    }
    return phases, balance


def test_advise_balance_equals_the_balance_study() -> None:
    phases, balance = _balance_fixture()
    assert len(phases) == 3 and all(len(p["first_harmonic"]) == 8 for p in phases.values())
    advice = cc.advise_balance(
        phases, balance, radius_m=2.5, g_m_s2=9.8, k1_rad_s_g=0.56,
        pivot_to_probe_mm=700.0, probe_to_piga_mm=510.0,
    )
    expected = cc.run_study(ROOT / "fixtures" / "studies" / "balance-simulated.ron").balance
    assert isinstance(advice, cc.BalanceAdvice)
    assert advice.to_dict() == expected
    assert advice.correction_mass_kg == expected["correction"]["mass_kg"]
    assert advice.correction_azimuth_u_deg == expected["correction"]["azimuth_u_deg"]
    assert advice.predicted_delta_k2_u_rad_s_g2 == expected["predicted"]["delta_k2_u_rad_s_g2"]
    assert advice.correction_method == "influence_coefficient"
    assert "probe plane" in advice.assumption


def test_advise_balance_names_an_unknown_phase() -> None:
    phases, balance = _balance_fixture()
    with pytest.raises(cc.ConfigError) as e:
        cc.advise_balance(
            phases, dict(balance, check="after"), radius_m=2.5, g_m_s2=9.8, k1_rad_s_g=0.56,
            pivot_to_probe_mm=700.0, probe_to_piga_mm=510.0,
        )
    assert "no phase is named `after`" in str(e.value)
    assert e.value.field is not None and "check" in e.value.field


def test_plan_equals_the_command_line(tmp_path: Path) -> None:
    config = ROOT / "fixtures" / "plans" / "paper-centrifuge.ron"
    cli = xtask("plan", "--config", str(config), "--json", "--out", str(tmp_path / "plan"))
    assert cli.status == 0, cli.stderr
    expected = json.loads(cli.stdout)["plan"]
    p = cc.plan(config)
    from test_studies import assert_close

    assert_close(p.to_dict(), expected)
    assert len(p.rates_deg_s) == len(p.revolutions) > 0


def test_two_orientation_plan_equals_the_command_line(tmp_path: Path) -> None:
    # A plan file with `two_orientation` is planned for both mountings, not silently as
    # a single-orientation plan.
    config = ROOT / "fixtures" / "plans" / "two_orientation.ron"
    cli = xtask("plan", "--config", str(config), "--json", "--out", str(tmp_path / "plan"))
    assert cli.status == 0, cli.stderr
    expected = json.loads(cli.stdout)["two_orientation"]
    p = cc.plan(config)
    from test_studies import assert_close

    assert_close(p.to_dict()["two_orientation"], expected)
    assert p.u95_k2_rad_s_g2 == expected["u95_k2_rad_s_g2"]
    assert set(p.orientations) == {"ia_in", "ia_out"}
    assert len(p.orientations) == len(p.rates_deg_s) == len(p.revolutions)


def test_plan_with_an_unknown_key() -> None:
    with pytest.raises(cc.ConfigError) as e:
        cc.plan({"centrifuge": {}, "pigga": {}})
    assert e.value.field is not None
