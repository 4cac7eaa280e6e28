"""The records' history from Python: ``centrifuge_cal.history`` and
``centrifuge_history`` give the numbers of ``centrifuge-cal history --json`` (the same Rust
functions on the same database), as numpy arrays; the several-unit fixture recorded twice,
a year apart, gives each unit two certificates and the centrifuge two campaigns."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import centrifuge_cal as cc
from centrifuge_cal import _native
from conftest import ROOT


def _script() -> str:
    script = shutil.which("centrifuge-cal", path=str(Path(sys.executable).parent))
    assert script is not None, "the console script is installed beside the interpreter"
    return script


def _json(*args: str) -> Any:
    p = subprocess.run([_script(), *args], capture_output=True, text=True, check=False)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


@pytest.fixture(scope="module")
def records(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The two-unit fixture's study run twice, a year apart (new certificate
    identifications and dates), each recorded with ``study --records``."""
    tmp = tmp_path_factory.mktemp("history")
    db = tmp / "lab.sqlite"
    study = (ROOT / "fixtures/studies/units.ron").read_text(encoding="utf-8")
    study = study.replace('"../units/', f'"{ROOT / "fixtures/units"}/')
    for year, (date, suffix) in enumerate([("2026-11-19", "0"), ("2027-11-18", "1")]):
        text = (
            study.replace("CC-2026-0051", f"CC-A-{suffix}")
            .replace("CC-2026-0052", f"CC-B-{suffix}")
            .replace("2026-11-16", date)
            .replace("2026-11-19 to 2026-11-20", date)
            .replace("2026-11-24", date)
        )
        config = tmp / f"units-{year}.ron"
        config.write_text(text, encoding="utf-8")
        status = _native.cli_main(
            ["centrifuge-cal", "study", "--config", str(config), "--out", str(tmp / f"out-{year}"),
             "--no-compare", "--records", str(db)]
        )
        assert status == 0
    return db


def test_a_units_history_is_the_command_lines_as_arrays(records: Path) -> None:
    h = cc.history("SN 2210-0033", records=records)
    cli = _json("history", "SN 2210-0033", "--json", "--records", str(records))
    assert h.to_dict() == cli
    assert h.unit["serial"] == "SN 2210-0033" and h.unit["model"] == "PIGA-22"
    k2 = h.term("k2")
    assert k2.certificates == ("CC-B-0", "CC-B-1")
    assert k2.dates.dtype == np.dtype("datetime64[D]")
    assert list(k2.dates.astype(str)) == ["2026-11-19", "2027-11-18"]
    cli_k2 = next(t for t in cli["terms"] if t["label"] == "k2")
    assert isinstance(k2.values, np.ndarray) and k2.values.dtype == np.float64
    np.testing.assert_array_equal(k2.values, [p["value"] for p in cli_k2["points"]])
    np.testing.assert_array_equal(k2.u, [p["u"] for p in cli_k2["points"]])
    np.testing.assert_array_equal(k2.expanded, [p["expanded"] for p in cli_k2["points"]])
    # the same data twice: no drift, and the prediction is the value certified
    assert k2.drift is not None and k2.drift.points == 2
    assert k2.drift.rate_per_year == cli_k2["drift"]["rate_per_year"]
    assert k2.drift.covariance.shape == (2, 2)
    assert not k2.drift.significant
    assert k2.prediction is not None
    assert k2.prediction.value == cli_k2["prediction"]["value"]
    assert h.at_source == "one_year_after_latest"


def test_an_interval_asked_for_from_python_is_the_command_lines(records: Path) -> None:
    h = cc.history("PIGA-16/SN 1604-0201", records, term="k2", tolerance=2e-7, at="2028-06-01")
    cli = _json(
        "history", "PIGA-16/SN 1604-0201", "--term", "k2", "--tolerance", "2e-7",
        "--at", "2028-06-01", "--json", "--records", str(records),
    )
    assert h.to_dict() == cli
    assert h.interval is not None and h.interval["term"] == "k2"
    assert h.at == np.datetime64("2028-06-01")


def test_a_centrifuges_health_counts_a_run_of_two_units_once(records: Path) -> None:
    h = cc.centrifuge_history("CF-2 (asset 1021)", records, target_u95=4e-7)
    cli = _json(
        "history", "--centrifuge", "CF-2 (asset 1021)", "--target-u95", "4e-7", "--json",
        "--records", str(records),
    )
    assert h.to_dict() == cli
    # two runs, each of two units from one probe phase: two campaigns, not four
    assert list(h.dates.astype(str)) == ["2026-11-19", "2027-11-18"]
    np.testing.assert_array_equal(
        h.c_r_m_s2, [c["c_r_m_s2"] for c in cli["campaigns"]]
    )
    assert h.c_r_m_s2[0] == h.c_r_m_s2[1]


def test_history_errors_are_the_packages(records: Path, tmp_path: Path) -> None:
    with pytest.raises(cc.ConfigError, match="SN 0000"):
        cc.history("SN 0000", records)
    with pytest.raises(cc.ConfigError):
        cc.history("SN 2210-0033", tmp_path / "none.sqlite")
    with pytest.raises(cc.InputError) as e:
        cc.history("SN 2210-0033", records, term="k2")
    assert e.value.field == "tolerance"
