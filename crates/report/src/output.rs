//! Writing a study's outputs into a directory, all at once.

use std::path::{Path, PathBuf};

use edge_io::OutputSet;
use serde::Serialize;

use crate::error::{ReportError, Result};
use crate::expected::{CheckOutcome, Expected};
use crate::markdown::render;
use crate::plot::{probe_signals_svg as probe_signals_svg_text, radius_error_svg};
use crate::provenance::{Provenance, Software};
use pipeline::StudyResults;

/// The names a study's output directory may hold: what [`write_outputs`] writes.
const STUDY_FILES: &[&str] = &[
    "results.json",
    "report.md",
    "radius_error.svg",
    "probe_signals_*.svg",
    "calibration_residuals.svg",
    "balance_polar.svg",
    "certificate.pdf",
    // written by earlier versions: removed when a study writes into the folder again
    "certificate.html",
    dcc::FILE_NAME,
];

/// The files a study wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WrittenFiles {
    /// `results.json`.
    pub results_json: PathBuf,
    /// `report.md`.
    pub report_md: PathBuf,
    /// `radius_error.svg` (the paper's Fig. 5): the last phase whose fit has residual degrees
    /// of freedom.
    pub radius_error_svg: PathBuf,
    /// `calibration_residuals.svg`, when the study has a calibration section.
    pub calibration_residuals_svg: Option<PathBuf>,
    /// `probe_signals_<phase>.svg` (the paper's Fig. 4), for each phase given as recordings.
    pub probe_signals_svg: Vec<PathBuf>,
    /// `balance_polar.svg`, when the study has a balance section.
    pub balance_polar_svg: Option<PathBuf>,
    /// `certificate.pdf` (PDF/A-2b), when the study has a certificate section.
    pub certificate_pdf: Option<PathBuf>,
    /// `certificate.dcc.xml`, the certificate as a DCC, when the study has a certificate
    /// section.
    pub certificate_dcc: Option<PathBuf>,
}

/// What a study's `results.json` holds: the results and, when recorded, their provenance.
#[derive(Debug, Clone, PartialEq)]
pub struct SavedResults {
    /// The results.
    pub results: StudyResults,
    /// The provenance record (absent from a `results.json` written without one).
    pub provenance: Option<Provenance>,
}

/// The largest `results.json` [`read_results`] reads.
const RESULTS_MAX_BYTES: u64 = 256 * 1024 * 1024;

/// Reads a study's `results.json`: `path` is the file or the folder holding it.
///
/// # Errors
/// [`ReportError::File`] when it cannot be read (or is larger than 256 MiB, or not UTF-8);
/// [`ReportError::Results`] naming the file when it is not a study's results.
pub fn read_results(path: &Path) -> Result<SavedResults> {
    let file = if path.is_dir() {
        path.join("results.json")
    } else {
        path.to_owned()
    };
    let text = edge_io::read_text_capped(&file, RESULTS_MAX_BYTES)?;
    let bad = |e: serde_json::Error| ReportError::Results {
        path: file.clone(),
        message: format!("not a study's results ({e})"),
    };
    let mut value: serde_json::Value = serde_json::from_str(&text).map_err(bad)?;
    let provenance = match value.as_object_mut().and_then(|o| o.remove("provenance")) {
        Some(p) => Some(serde_json::from_value(p).map_err(bad)?),
        None => None,
    };
    let results = serde_json::from_value(value).map_err(bad)?;
    Ok(SavedResults {
        results,
        provenance,
    })
}

/// Serialises results as pretty JSON, without provenance.
///
/// # Errors
/// [`ReportError::NonFiniteOutput`] naming a number that is not finite (never a `null` for
/// one); [`ReportError::Serialize`] if the results cannot be serialised.
pub fn results_json(results: &StudyResults) -> Result<String> {
    edge_io::to_json_pretty(results).map_err(|e| ReportError::json("results.json", e))
}

/// Serialises results as pretty JSON with a leading `provenance` object: the text of
/// `results.json` as [`write_outputs`] writes it.
///
/// # Errors
/// [`ReportError::NonFiniteOutput`] naming a number that is not finite (never a `null` for
/// one); [`ReportError::Serialize`] if the results cannot be serialised.
pub fn results_json_with_provenance(
    results: &StudyResults,
    provenance: &Provenance,
) -> Result<String> {
    #[derive(Serialize)]
    struct WithProvenance<'a> {
        provenance: &'a Provenance,
        #[serde(flatten)]
        results: &'a StudyResults,
    }
    edge_io::to_json_pretty(&WithProvenance {
        provenance,
        results,
    })
    .map_err(|e| ReportError::json("results.json", e))
}

/// Writes `results.json` (with `provenance` when given), `report.md`, `radius_error.svg`,
/// for phases given as recordings `probe_signals_<phase>.svg`, and for a study with a
/// certificate section `certificate.pdf` (PDF/A-2b) and `certificate.dcc.xml` (the same
/// certificate as a DCC; their input files from `provenance`) into `dir`, atomically: every
/// file is rendered first, then written through an [`OutputSet`], so `dir` ends up holding
/// exactly these files, or, on any error, what it held before, byte for byte. Files of an
/// earlier study that this one does not write (a probe figure) are removed.
///
/// # Errors
/// [`ReportError::Plot`] or [`ReportError::Serialize`] when an output cannot be rendered
/// (nothing is written); [`ReportError::File`] when `dir` holds files a study does not write,
/// or a file cannot be written or moved into place.
pub fn write_outputs(
    dir: &Path,
    results: &StudyResults,
    expected: Option<&Expected>,
    outcomes: Option<&[CheckOutcome]>,
    provenance: Option<&Provenance>,
) -> Result<WrittenFiles> {
    let json = match provenance {
        Some(p) => results_json_with_provenance(results, p)?,
        None => results_json(results)?,
    };
    let report = render(results, expected, outcomes);
    let mut probe_figures = Vec::new();
    for phase in &results.phases {
        let key = &phase.name;
        let title = format!("{}: probe signal over one revolution, {key}", results.study);
        if let Some(svg) = probe_signals_svg_text(phase, &title)? {
            probe_figures.push((format!("probe_signals_{key}.svg"), svg));
        }
    }
    // Fig. 5: the last phase whose fit has residual degrees of freedom (the paper's: after
    // balancing), else the last phase.
    let figure = results
        .phases
        .iter()
        .rev()
        .find(|p| p.fit.dof > 0)
        .or(results.phases.last())
        .ok_or(ReportError::NoPhase)?;
    let title = format!("{}: radius error, phase {}", results.study, figure.name);
    let radius_figure = radius_error_svg(figure, &title)?;

    let balance_figure = results
        .balance
        .as_ref()
        .map(|b| {
            let title = format!("{}: balance phasors and correction", results.study);
            crate::balance::balance_polar_svg(b, &title)
        })
        .transpose()?;

    // The certificate lists the input files with their digests: without a provenance
    // record, the files' table says so.
    let certificate = results
        .certificate
        .as_ref()
        .map(|_| crate::certificate::certificate_pdf(results, provenance, &Software::this_build()))
        .transpose()?;

    let certificate_dcc = results
        .certificate
        .as_ref()
        .map(|_| certificate_dcc(results, provenance))
        .transpose()?;

    let mut set = OutputSet::create(dir, STUDY_FILES)?;
    let results_json = set.write("results.json", json.as_bytes())?;
    let report_md = set.write("report.md", report.as_bytes())?;
    let probe_signals_svg = probe_figures
        .iter()
        .map(|(name, svg)| set.write(name, svg.as_bytes()))
        .collect::<edge_io::Result<Vec<_>>>()?;
    let calibration_residuals_svg = match &results.calibration {
        Some(c) => {
            let title = format!("{}: calibration residuals (eq. 18)", results.study);
            let svg = crate::plot::calibration_residuals_svg(c, &title)?;
            Some(set.write("calibration_residuals.svg", svg.as_bytes())?)
        }
        None => None,
    };
    let radius_error_svg = set.write("radius_error.svg", radius_figure.as_bytes())?;
    let balance_polar_svg = balance_figure
        .map(|svg| set.write("balance_polar.svg", svg.as_bytes()))
        .transpose()?;
    let certificate_pdf = certificate
        .map(|pdf| set.write("certificate.pdf", &pdf))
        .transpose()?;
    let certificate_dcc = certificate_dcc
        .map(|xml| set.write(dcc::FILE_NAME, xml.as_bytes()))
        .transpose()?;
    set.commit()?;
    Ok(WrittenFiles {
        results_json,
        report_md,
        radius_error_svg,
        probe_signals_svg,
        calibration_residuals_svg,
        balance_polar_svg,
        certificate_pdf,
        certificate_dcc,
    })
}

/// The certificate as a DCC (`crates/dcc`): its software this build, its input files the
/// configuration and every data file of `provenance` (none stated without one).
fn certificate_dcc(results: &StudyResults, provenance: Option<&Provenance>) -> Result<String> {
    let build = Software::this_build();
    let software = dcc::Software {
        name: crate::TOOL.to_owned(),
        release: env!("CARGO_PKG_VERSION").to_owned(),
        commit: build.commit,
    };
    let files: Option<Vec<dcc::InputFile>> = provenance.map(|p| {
        let record = |f: &crate::provenance::FileRecord, role: &str| dcc::InputFile {
            path: f.path.clone(),
            bytes: f.bytes,
            sha256: f.sha256.clone(),
            role: f.role.clone().unwrap_or_else(|| role.to_owned()),
            field: f.field.clone(),
        };
        std::iter::once(record(&p.config, "configuration"))
            .chain(p.inputs.iter().map(|f| record(f, "data")))
            .collect()
    });
    Ok(dcc::write_dcc(&dcc::DccInput {
        results,
        software: &software,
        files: files.as_deref(),
    })?)
}

/// Re-renders the certificate of a study's results: reads `results` (a study's output folder
/// or its `results.json`, [`read_results`]) and writes the certificate as PDF/A-2b to `out`
/// (default: `certificate.pdf` beside `results.json`), through a temporary file in the same
/// folder renamed into place, so that `out` is never half-written. Returns the path written.
///
/// # Errors
/// As [`read_results`]; [`ReportError::NoCertificate`] when the study had no certificate
/// section; [`ReportError::Typeset`] when it cannot be typeset; [`ReportError::File`] when
/// the PDF cannot be written.
pub fn write_certificate(results: &Path, out: Option<&Path>) -> Result<PathBuf> {
    let saved = read_results(results)?;
    let pdf = crate::certificate::certificate_pdf(
        &saved.results,
        saved.provenance.as_ref(),
        &Software::this_build(),
    )?;
    let out = match out {
        // an existing folder: the certificate goes into it under its usual name
        Some(o) if o.is_dir() => o.join("certificate.pdf"),
        Some(o) => o.to_owned(),
        None if results.is_dir() => results.join("certificate.pdf"),
        None => results
            .parent()
            .unwrap_or_else(|| Path::new("."))
            .join("certificate.pdf"),
    };
    // a folder named in --out that does not exist yet is created, as `study --out` does
    if let Some(parent) = out.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent).map_err(|source| edge_io::EdgeIoError::Write {
            path: parent.to_owned(),
            source,
        })?;
    }
    write_file_atomically(&out, &pdf)?;
    Ok(out)
}

/// Writes `bytes` to `path` through `<path>.tmp-<pid>` in the same folder, synced, then
/// renamed over `path`.
fn write_file_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    use std::io::Write as _;
    let file_name = path
        .file_name()
        .map_or_else(|| "certificate.pdf".into(), std::ffi::OsStr::to_os_string);
    let mut tmp_name = file_name;
    tmp_name.push(format!(".tmp-{}", std::process::id()));
    let tmp = path.with_file_name(tmp_name);
    let write_error = |source| edge_io::EdgeIoError::Write {
        path: path.to_owned(),
        source,
    };
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(write_error(e).into());
    }
    Ok(())
}
