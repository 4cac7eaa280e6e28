"""Recordings read from files (CSV with a format description, TDMS, MAT) and their fit,
equal to the command line's; errors with the command line's words."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import centrifuge_cal as cc
from conftest import ROOT, cli_error, xtask

CSV = ROOT / "fixtures" / "recordings" / "probe_120deg_s.csv"
BINARY = ROOT / "fixtures" / "recordings" / "binary"


def test_a_csv_recording_reads_into_arrays() -> None:
    rec = cc.read_recording(CSV)
    assert len(rec) == rec.time_s.shape[0] == rec.gap.shape[0] > 1000
    assert rec.time_s.dtype == np.float64
    assert rec.angle_rad is not None and rec.angle_source == "encoder"
    assert rec.angle_rad[0] == pytest.approx(np.radians(30.0))
    assert rec.gap_unit == "µm" or rec.gap_unit == "um"
    with pytest.raises(ValueError):
        rec.gap[0] = 1.0  # read-only: the recording is what the file holds


def test_the_fit_of_a_file_equals_the_command_line() -> None:
    # the command's `harmonics` fits without the drift term unless asked; the study (and
    # Python, with the study's defaults) fit it
    cli = xtask("harmonics", str(CSV), "--rate-deg-s", "120", "--json", "--drift")
    assert cli.status == 0, cli.stderr
    expected = json.loads(cli.stdout)
    fit = cc.read_recording(CSV).fit_harmonics(rate_deg_s=120.0)
    assert fit.drift is cc.STUDY_DEFAULTS["drift"] is True
    assert fit.revolutions_used == expected["revolutions_used"]
    assert fit.measured_rate_deg_s == expected["measured_rate_deg_s"]
    for key in ("l0",):
        assert fit.mean.l0 == expected["mean"][key]
    assert list(fit.mean.c) == expected["mean"]["c"]
    assert list(fit.mean.s) == expected["mean"]["s"]
    assert fit.first_harmonic.beta_deg == expected["first_harmonic"]["beta_deg"]
    assert [w.to_dict() for w in fit.warnings] == [
        {"code": w["code"], "message": w["message"]} for w in expected["warnings"]
    ]
    assert fit.per_revolution.residual_rms.tolist() == [r["residual_rms"] for r in expected["revolutions"]]


def test_arrays_and_file_give_the_same_fit() -> None:
    rec = cc.read_recording(CSV)
    from_file = rec.fit_harmonics(rate_deg_s=120.0)
    from_arrays = cc.fit_harmonics(rec.time_s, rec.gap, rate_deg_s=120.0, angle_rad=rec.angle_rad)
    np.testing.assert_allclose(from_arrays.mean.c, from_file.mean.c, rtol=1e-12)
    assert from_arrays.measured_rate_deg_s == pytest.approx(from_file.measured_rate_deg_s, rel=1e-12)


@pytest.mark.parametrize(
    "name,group",
    [("probe_120deg_s.tdms", None), ("probe_120deg_s.mat", None), ("probe_120deg_s_v7.mat", "rec")],
)
def test_binary_recordings_read_as_the_csv(name: str, group: str | None) -> None:
    rec = cc.read_recording(BINARY / name, group=group)
    csv = cc.read_recording(CSV)
    np.testing.assert_allclose(rec.gap, csv.gap, rtol=1e-12)
    np.testing.assert_allclose(rec.time_s, csv.time_s, rtol=1e-12)


def test_a_format_dict_reads_a_lab_file(tmp_path: Path) -> None:
    path = tmp_path / "lab.txt"
    lines = ["instrument: probe rig 2", "t;spalt;enc"]
    csv = cc.read_recording(CSV)
    assert csv.angle_rad is not None
    for t, g, a in zip(csv.time_s, csv.gap, csv.angle_rad):
        lines.append(f"{t * 1e3:.6f};{g / 1e3:.9f};{np.degrees(a):.6f}".replace(".", ","))
    path.write_text("\n".join(lines) + "\n")
    fmt = {
        "delimiter": ";",
        "decimal": "comma",
        "skip_lines": 1,
        "time": {"column": "t", "unit": "ms"},
        "gap": {"column": "spalt", "unit": "mm"},
        "angle": {"encoder": {"column": "enc", "unit": "deg"}},
    }
    rec = cc.read_recording(path, fmt)
    # the gap in µm, as the study converts it, with the declared unit and the factor stated
    assert rec.gap_unit == "um" and rec.declared_gap_unit == "mm"
    assert rec.um_per_declared_unit == 1000.0
    np.testing.assert_allclose(rec.gap_um, csv.gap, rtol=1e-9)
    assert rec.gap is rec.gap_um
    np.testing.assert_allclose(rec.time_s, csv.time_s, rtol=1e-9, atol=1e-12)
    # the same description as a RON file
    ron = tmp_path / "lab.ron"
    ron.write_text(
        '(delimiter: ";", decimal: comma, skip_lines: 1, time: (column: "t", unit: ms), '
        'gap: (column: "spalt", unit: mm), angle: encoder(column: "enc", unit: deg))'
    )
    np.testing.assert_array_equal(cc.read_recording(path, ron).gap, rec.gap)


def test_a_missing_file_has_the_command_line_words() -> None:
    with pytest.raises(cc.RecordingError) as e:
        cc.read_recording("no/such/probe.csv")
    cli = xtask("harmonics", "no/such/probe.csv", "--rate-deg-s", "120")
    assert str(e.value) == cli_error(cli)
    assert e.value.file == "no/such/probe.csv"


def test_a_nan_in_the_gap_file_has_the_command_line_words(tmp_path: Path) -> None:
    text = CSV.read_text().splitlines()
    text[10] = text[10].split(",")[0] + ",nan," + text[10].split(",")[2]
    path = tmp_path / "nan.csv"
    path.write_text("\n".join(text) + "\n")
    with pytest.raises(cc.RecordingError) as e:
        cc.read_recording(path).fit_harmonics(rate_deg_s=120.0)
    cli = xtask("harmonics", str(path), "--rate-deg-s", "120")
    assert str(e.value) == cli_error(cli)
    assert e.value.file == str(path)
    assert e.value.line == 11
    assert e.value.hint is not None and "on_non_finite" in e.value.hint


def test_an_unknown_format_key_has_the_command_line_words(tmp_path: Path) -> None:
    ron = tmp_path / "format.ron"
    ron.write_text("(delimter: \";\")")
    with pytest.raises(cc.ConfigError) as e:
        cc.read_recording(CSV, ron)
    cli = xtask("harmonics", str(CSV), "--rate-deg-s", "120", "--format", str(ron))
    assert str(e.value) == cli_error(cli)
    assert e.value.field == "delimter"
    with pytest.raises(cc.ConfigError) as d:
        cc.read_recording(CSV, {"delimter": ";"})
    assert "unknown field `delimter`" in str(d.value)
    assert d.value.field == "delimter"


def test_a_decimal_comma_gets_its_hint(tmp_path: Path) -> None:
    path = tmp_path / "comma.csv"
    path.write_text("time_s,gap_um\n0,1\n0,001;1,5\n")
    with pytest.raises(cc.RecordingError) as e:
        cc.read_recording(path)
    cli = xtask("harmonics", str(path), "--rate-deg-s", "120")
    assert str(e.value) == cli_error(cli)
    assert e.value.line is not None


def test_the_console_script_is_the_command_line(tmp_path: Path) -> None:
    import shutil
    import subprocess
    import sys

    script = shutil.which("centrifuge-cal", path=str(Path(sys.executable).parent))
    assert script is not None, "the console script is installed beside the interpreter"
    ok = subprocess.run(
        [script, "harmonics", str(CSV), "--rate-deg-s", "120", "--json"],
        capture_output=True, text=True, check=False,
    )
    assert ok.returncode == 0, ok.stderr
    cli = xtask("harmonics", str(CSV), "--rate-deg-s", "120", "--json")
    assert json.loads(ok.stdout)["mean"] == json.loads(cli.stdout)["mean"]
    bad = subprocess.run(
        [script, "harmonics", "no/such/probe.csv", "--rate-deg-s", "120"],
        capture_output=True, text=True, check=False,
    )
    assert bad.returncode == 1
    missing = xtask("harmonics", "no/such/probe.csv", "--rate-deg-s", "120")
    assert bad.stderr.strip().splitlines()[-1] == "error: " + cli_error(missing)
    usage = subprocess.run([script, "--bogus"], capture_output=True, text=True, check=False)
    assert usage.returncode == 2
