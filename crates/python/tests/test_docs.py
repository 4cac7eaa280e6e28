"""docs/PYTHON.md's examples run as written, in order, on a laboratory's export
(fixtures/lab-mm-comma: `;`, decimal comma, time in ms, the gap in mm), and their numbers are
the study's: the same C_r and k0…k3 as `study.ron` of that folder through Python and through
the command line (1e-12 relative). One source of defaults, one estimator."""

from __future__ import annotations

import json
import math
import os
import re
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import centrifuge_cal as cc
from conftest import ROOT, xtask

DOC = ROOT / "docs" / "PYTHON.md"
LAB = ROOT / "fixtures" / "lab-mm-comma"
MARKER = "<!-- test: the examples below run in this order in fixtures/lab-mm-comma -->"
TERMS = ("k0", "k1", "k2", "k3")


def examples() -> list[str]:
    """The ```python blocks after the marker, in order."""
    text = DOC.read_text(encoding="utf-8")
    assert MARKER in text, "docs/PYTHON.md lost the marker the examples' test looks for"
    return re.findall(r"```python\n(.*?)```", text.split(MARKER, 1)[1], re.S)


def close(a: float, b: float) -> bool:
    return math.isclose(a, b, rel_tol=1e-12, abs_tol=0.0)


def coefficient(calibration: dict[str, Any], term: str) -> float:
    """A coefficient's estimate from results.json's `calibration.coefficients`."""
    coefficients = calibration["coefficients"]
    entry = coefficients[term] if isinstance(coefficients, dict) else next(
        c for c in coefficients if c.get("name") == term
    )
    value = entry["value"] if isinstance(entry, dict) and "value" in entry else entry
    if isinstance(value, dict):
        value = value.get("estimate", value.get("value"))
    return float(value)


@pytest.fixture(scope="module")
def ran() -> Iterator[dict[str, Any]]:
    """The examples' namespace after running them all in fixtures/lab-mm-comma, with the
    warnings they issued."""
    namespace: dict[str, Any] = {"__name__": "docs_example"}
    here = os.getcwd()
    os.chdir(LAB)
    try:
        with warnings.catch_warnings(record=True) as issued:
            warnings.simplefilter("always")
            for i, block in enumerate(examples()):
                try:
                    exec(compile(block, f"docs/PYTHON.md example {i + 1}", "exec"), namespace)
                except Exception as e:  # noqa: BLE001 - named with its block
                    pytest.fail(f"docs/PYTHON.md example {i + 1} failed: {e!r}\n{block}")
        namespace["__issued__"] = list(issued)
        yield namespace
    finally:
        os.chdir(here)


@pytest.fixture(scope="module")
def study() -> cc.StudyResults:
    here = os.getcwd()
    os.chdir(LAB)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return cc.run_study("study.ron")
    finally:
        os.chdir(here)


def test_every_example_ran(ran: dict[str, Any]) -> None:
    assert len(examples()) >= 5
    for name in ("spindle", "cal", "results", "two", "fit"):
        assert name in ran, name


def test_the_recordings_are_in_um_as_the_study_reads_them(ran: dict[str, Any]) -> None:
    rec = ran["recordings"][0]
    assert rec.declared_gap_unit == "mm" and rec.gap_unit == "um"
    assert rec.um_per_declared_unit == 1000.0
    # the file holds 0,046957127329 mm: 46.957127329 µm
    assert rec.gap_um[0] == pytest.approx(46.957127329, rel=1e-12)
    assert "declared in mm" in repr(rec)
    assert all(f.drift == cc.STUDY_DEFAULTS["drift"] is True for f in ran["fits"])


def test_the_example_gives_the_studys_c_r(ran: dict[str, Any], study: cc.StudyResults) -> None:
    expected = study.phase("spindle")["c_r_m_s2"]
    got = ran["spindle"].c_r_m_s2
    assert close(got, expected), (got, expected)
    # and not the millimetre slip of before (1000x too small)
    assert 1e-7 < abs(got) < 1e-5


def test_the_example_gives_the_studys_k0_to_k3(ran: dict[str, Any], study: cc.StudyResults) -> None:
    assert study.calibration is not None
    for term in TERMS:
        got = coefficient(ran["cal"].to_dict(), term)
        expected = coefficient(study.calibration, term)
        assert close(got, expected), (term, got, expected)


def test_the_command_line_gives_the_same_numbers(
    ran: dict[str, Any], study: cc.StudyResults, tmp_path: Path
) -> None:
    cli = xtask(
        "study", "--config", str(LAB / "study.ron"), "--out", str(tmp_path / "out"), "--no-compare"
    )
    assert cli.status == 0, cli.stderr
    document = json.loads((tmp_path / "out" / "results.json").read_text())
    phase = next(p for p in document["phases"] if p["name"] == "spindle")
    assert close(phase["c_r_m_s2"], ran["spindle"].c_r_m_s2)
    assert phase["c_r_m_s2"] == study.phase("spindle")["c_r_m_s2"]
    for term in TERMS:
        cli_value = coefficient(document["calibration"], term)
        assert cli_value == coefficient(study.to_dict()["calibration"], term), term
        assert close(cli_value, coefficient(ran["cal"].to_dict(), term)), term


def test_the_whole_study_example_is_the_study(ran: dict[str, Any], study: cc.StudyResults) -> None:
    results = ran["results"]
    assert results.phase("spindle")["c_r_m_s2"] == study.phase("spindle")["c_r_m_s2"]


def test_the_two_orientation_example_is_an_attribute_of_its_study(ran: dict[str, Any]) -> None:
    two = ran["two"]
    assert isinstance(two, cc.TwoOrientation)
    assert two.study.two_orientation is two.two_orientation
    assert two.to_dict() is two.two_orientation


def test_a_gap_in_mm_given_as_um_is_warned_about(ran: dict[str, Any]) -> None:
    rec = ran["recordings"][5]
    slipped = rec.gap_um / 1000.0  # the file's millimetres, declared as the default µm
    with pytest.warns(cc.CentrifugeCalWarning, match="implausible_gap_unit"):
        fit = cc.fit_harmonics(rec.time_s, slipped, rate_deg_s=120.0, angle_rad=rec.angle_rad)
    assert "implausible_gap_unit" in [w.code for w in fit.warnings]
    # declared as what they are, the same numbers give the study's µm and no such warning
    with warnings.catch_warnings(record=True) as issued:
        warnings.simplefilter("always")
        declared = cc.fit_harmonics(
            rec.time_s, slipped, rate_deg_s=120.0, angle_rad=rec.angle_rad, gap_unit="mm"
        )
    assert "implausible_gap_unit" not in [w.code for w in declared.warnings]
    assert not [w for w in issued if "implausible_gap_unit" in str(w.message)]
    assert declared.mean.c[0] == pytest.approx(ran["fits"][5].mean.c[0], rel=1e-12)
    assert declared.gap_unit == "um" and declared.declared_gap_unit == "mm"
