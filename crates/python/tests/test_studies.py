"""Whole studies through Python equal the command line's results.json (1e-12 relative);
a study given as a dict equals the same study given as a file."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pytest

import centrifuge_cal as cc
from conftest import ROOT, xtask

STUDIES = sorted(p.name for p in (ROOT / "fixtures" / "studies").glob("*.ron"))


def assert_close(a: Any, b: Any, where: str = "") -> None:
    """Equal structure; numbers within 1e-12 relative (exact for integers and strings)."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and a.keys() == b.keys(), f"{where}: {sorted(a)} != {sorted(b)}"
        for k in a:
            assert_close(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            assert_close(x, y, f"{where}[{i}]")
    elif isinstance(a, float) and not isinstance(b, bool) and isinstance(b, (int, float)):
        assert math.isclose(a, b, rel_tol=1e-12, abs_tol=0.0) or a == b, f"{where}: {a} != {b}"
    else:
        assert a == b, f"{where}: {a!r} != {b!r}"


def test_every_fixture_study_is_found() -> None:
    assert "campaign.ron" in STUDIES and len(STUDIES) >= 5


@pytest.mark.parametrize("name", STUDIES)
def test_fixture_study_equals_the_command_line(name: str, tmp_path: Path) -> None:
    config = f"fixtures/studies/{name}"
    cli = xtask("study", "--config", config, "--out", str(tmp_path / "out"), "--no-compare")
    assert cli.status == 0, cli.stderr
    expected = json.loads((tmp_path / "out" / "results.json").read_text())
    import os

    here = os.getcwd()
    os.chdir(ROOT)
    try:
        got = cc.run_study(config)
    finally:
        os.chdir(here)
    assert_close(got.to_dict(), expected)
    assert got.study == expected["study"]
    assert got.phases[0]["name"] == expected["phases"][0]["name"]
    # each section an attribute, the two-orientation one included
    assert got.two_orientation == expected.get("two_orientation")
    assert got.calibration == expected.get("calibration")
    if name.startswith("two_orientation"):
        assert got.two_orientation is not None and "k2" in str(got.two_orientation)


PAPER_LIKE: dict[str, Any] = {
    "name": "example",
    "radius_m": 2.5,
    "g_m_s2": 9.8,
    "k1_rad_s_g": 0.56,
    "lever": {"pivot_to_probe_mm": 700.0, "probe_to_piga_mm": 510.0},
    "phases": [
        {
            "name": "before",
            "points": {
                "radius_change": {"from_rate_deg_s": 10.0, "to_rate_deg_s": 200.0, "change_um": 20.0}
            },
        },
        {
            "name": "after",
            "weighting": "unweighted",
            "points": {
                "radius_error": [
                    {"rate_deg_s": 10.0, "radius_error_um": 1.0},
                    {"rate_deg_s": 100.0, "radius_error_um": 0.9},
                    {"rate_deg_s": 200.0, "radius_error_um": 0.6},
                ]
            },
        },
    ],
}

PAPER_LIKE_RON = """(
    name: "example", radius_m: 2.5, g_m_s2: 9.8, k1_rad_s_g: 0.56,
    lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0),
    phases: [
        (name: "before", points: radius_change(from_rate_deg_s: 10.0, to_rate_deg_s: 200.0,
                                               change_um: 20.0)),
        (name: "after", weighting: unweighted, points: radius_error([
            (rate_deg_s: 10.0, radius_error_um: 1.0),
            (rate_deg_s: 100.0, radius_error_um: 0.9),
            (rate_deg_s: 200.0, radius_error_um: 0.6),
        ])),
    ],
)"""


def test_a_dict_equals_the_same_study_as_a_file(tmp_path: Path) -> None:
    path = tmp_path / "example.ron"
    path.write_text(PAPER_LIKE_RON)
    from_file = cc.run_study(path).to_dict()
    from_file.pop("provenance")
    assert cc.run_study(PAPER_LIKE).to_dict() == from_file
    after = cc.run_study(PAPER_LIKE).phase("after")
    assert after["c_r_m_s2"] < 0.0
    with pytest.raises(KeyError, match="before"):
        cc.run_study(PAPER_LIKE).phase("nope")


def test_a_dict_with_an_unknown_key_names_it() -> None:
    bad = dict(PAPER_LIKE, radius_mm=2500.0)
    with pytest.raises(cc.ConfigError) as e:
        cc.run_study(bad)
    assert "unknown field `radius_mm`" in str(e.value)
    assert e.value.field == "radius_mm"


def test_a_dict_with_a_bad_value_names_the_field() -> None:
    bad = dict(PAPER_LIKE, radius_m=-2.5)
    with pytest.raises(cc.ConfigError) as e:
        cc.run_study(bad)
    assert e.value.field == "radius_m"
    assert "<dict>" in str(e.value)


def test_a_study_file_error_has_the_command_line_words(tmp_path: Path) -> None:
    path = tmp_path / "bad.ron"
    path.write_text(PAPER_LIKE_RON.replace("radius_m: 2.5", "radius_m: -2.5"))
    with pytest.raises(cc.ConfigError) as e:
        cc.run_study(path)
    cli = xtask("study", "--config", str(path), "--out", str(tmp_path / "out"))
    from conftest import cli_error

    assert str(e.value) == cli_error(cli)
    assert e.value.file == str(path)
    assert e.value.field == "radius_m"


def test_a_missing_study_file() -> None:
    with pytest.raises(cc.CentrifugeCalError) as e:
        cc.run_study("no/such/study.ron")
    assert "no/such/study.ron" in str(e.value)
    assert e.value.file == "no/such/study.ron"
