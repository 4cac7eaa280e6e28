"""The calibration certificate from Python: the same Rust function as ``centrifuge-cal
certificate`` writes a PDF/A-2b of a study's results folder; a folder without a certificate
is a ComputationError naming what is missing."""

from __future__ import annotations

from pathlib import Path

import pytest

import centrifuge_cal as cc
from centrifuge_cal import _native
from conftest import ROOT


def study(config: str, out: Path) -> None:
    """Runs a study with the package's own command line (no cargo)."""
    status = _native.cli_main(
        ["centrifuge-cal", "study", "--config", str(ROOT / config), "--out", str(out), "--no-compare"]
    )
    assert status == 0


def test_certificate_of_a_results_folder_is_a_pdf_a(tmp_path: Path) -> None:
    out = tmp_path / "study"
    study("fixtures/studies/campaign.ron", out)
    # the study wrote its own certificate.pdf
    assert (out / "certificate.pdf").read_bytes().startswith(b"%PDF-")
    written = cc.certificate(out, out=tmp_path / "again.pdf")
    assert Path(written) == tmp_path / "again.pdf"
    pdf = Path(written).read_bytes()
    assert pdf.startswith(b"%PDF-1.7")
    # PDF/A-2b declared in the XMP metadata, the certificate's id in its title
    assert b"<pdfaid:part>2</pdfaid:part>" in pdf
    assert b"<pdfaid:conformance>B</pdfaid:conformance>" in pdf
    assert b"CC-2026-0042" in pdf
    # the default: certificate.pdf in the folder, the same document as the study's
    assert cc.certificate(out) == str(out / "certificate.pdf")
    assert (out / "certificate.pdf").read_bytes() == pdf


def test_a_study_without_certificate_section_has_none(tmp_path: Path) -> None:
    out = tmp_path / "study"
    study("fixtures/studies/paper-2025.ron", out)
    with pytest.raises(cc.ComputationError, match="certificate"):
        cc.certificate(out)
    assert not (out / "certificate.pdf").exists()


def test_a_folder_without_results_is_named(tmp_path: Path) -> None:
    with pytest.raises(cc.CentrifugeCalError, match="results.json"):
        cc.certificate(tmp_path)
