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
    // a several-unit study: each unit's own outputs in units/<label>/
    "units/*/results.json",
    "units/*/report.md",
    "units/*/radius_error.svg",
    "units/*/probe_signals_*.svg",
    "units/*/calibration_residuals.svg",
    "units/*/balance_polar.svg",
    "units/*/certificate.pdf",
    "units/*/certificate.dcc.xml",
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
    /// A several-unit study: each unit's label and its files, in `units/<label>/`.
    pub units: Vec<(String, WrittenFiles)>,
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
/// A several-unit study's units (`results.unit_studies`) are written too, each into
/// `units/<label>/` as a single-unit study, in the same set; without their provenance
/// ([`write_outputs_with_units`] takes it).
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
    write_outputs_with_units(dir, results, expected, outcomes, provenance, &[])
}

/// [`write_outputs`], with the provenance of each unit of a several-unit study
/// (`unit_provenance[i]` for `results.unit_studies[i]`; a unit without one is written
/// without provenance): each unit's results.json and certificate list the configuration and
/// the files that unit's numbers come from (the probe recordings and its own data).
///
/// # Errors
/// As [`write_outputs`].
pub fn write_outputs_with_units(
    dir: &Path,
    results: &StudyResults,
    expected: Option<&Expected>,
    outcomes: Option<&[CheckOutcome]>,
    provenance: Option<&Provenance>,
    unit_provenance: &[Provenance],
) -> Result<WrittenFiles> {
    let top = render_study(results, expected, outcomes, provenance)?;
    let labels: Vec<&str> = results
        .units
        .iter()
        .flatten()
        .map(|u| u.label.as_str())
        .collect();
    let mut units = Vec::with_capacity(results.unit_studies.len());
    for (i, unit) in results.unit_studies.iter().enumerate() {
        let label = labels.get(i).copied().ok_or(ReportError::Results {
            path: dir.join("results.json"),
            message: format!("unit {i} of the study has no label in its `units` list"),
        })?;
        units.push((
            label,
            render_study(unit, None, None, unit_provenance.get(i))?,
        ));
    }
    let mut set = OutputSet::create(dir, STUDY_FILES)?;
    let mut written = write_rendered(&mut set, "", top)?;
    for (label, files) in units {
        let files = write_rendered(&mut set, &format!("units/{label}/"), files)?;
        written.units.push((label.to_owned(), files));
    }
    set.commit()?;
    Ok(written)
}

/// A study's files, rendered in memory, in the order they are written.
struct Rendered(Vec<(String, Vec<u8>)>);

/// Renders a study's files (nothing is written).
fn render_study(
    results: &StudyResults,
    expected: Option<&Expected>,
    outcomes: Option<&[CheckOutcome]>,
    provenance: Option<&Provenance>,
) -> Result<Rendered> {
    let json = match provenance {
        Some(p) => results_json_with_provenance(results, p)?,
        None => results_json(results)?,
    };
    let report = render(results, expected, outcomes);
    let mut files: Vec<(String, Vec<u8>)> = vec![
        ("results.json".to_owned(), json.into_bytes()),
        ("report.md".to_owned(), report.into_bytes()),
    ];
    for phase in &results.phases {
        let key = &phase.name;
        let title = format!("{}: probe signal over one revolution, {key}", results.study);
        if let Some(svg) = probe_signals_svg_text(phase, &title)? {
            files.push((format!("probe_signals_{key}.svg"), svg.into_bytes()));
        }
    }
    if let Some(c) = &results.calibration {
        let title = format!("{}: calibration residuals (eq. 18)", results.study);
        let svg = crate::plot::calibration_residuals_svg(c, &title)?;
        files.push(("calibration_residuals.svg".to_owned(), svg.into_bytes()));
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
    files.push((
        "radius_error.svg".to_owned(),
        radius_error_svg(figure, &title)?.into_bytes(),
    ));
    if let Some(b) = &results.balance {
        let title = format!("{}: balance phasors and correction", results.study);
        let svg = crate::balance::balance_polar_svg(b, &title)?;
        files.push(("balance_polar.svg".to_owned(), svg.into_bytes()));
    }
    // The certificate lists the input files with their digests: without a provenance
    // record, the files' table says so.
    if results.certificate.is_some() {
        let pdf =
            crate::certificate::certificate_pdf(results, provenance, &Software::this_build())?;
        files.push(("certificate.pdf".to_owned(), pdf));
        let xml = certificate_dcc(results, provenance)?;
        files.push((dcc::FILE_NAME.to_owned(), xml.into_bytes()));
    }
    Ok(Rendered(files))
}

/// Writes rendered files into `set` under `prefix` (`""` or `units/<label>/`).
fn write_rendered(set: &mut OutputSet, prefix: &str, rendered: Rendered) -> Result<WrittenFiles> {
    let mut written = WrittenFiles {
        results_json: PathBuf::new(),
        report_md: PathBuf::new(),
        radius_error_svg: PathBuf::new(),
        calibration_residuals_svg: None,
        probe_signals_svg: Vec::new(),
        balance_polar_svg: None,
        certificate_pdf: None,
        certificate_dcc: None,
        units: Vec::new(),
    };
    for (name, bytes) in rendered.0 {
        let path = set.write(&format!("{prefix}{name}"), &bytes)?;
        match name.as_str() {
            "results.json" => written.results_json = path,
            "report.md" => written.report_md = path,
            "radius_error.svg" => written.radius_error_svg = path,
            "calibration_residuals.svg" => written.calibration_residuals_svg = Some(path),
            "balance_polar.svg" => written.balance_polar_svg = Some(path),
            "certificate.pdf" => written.certificate_pdf = Some(path),
            n if n == dcc::FILE_NAME => written.certificate_dcc = Some(path),
            _ => written.probe_signals_svg.push(path),
        }
    }
    Ok(written)
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
