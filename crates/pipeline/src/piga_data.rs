//! The PIGA's data of a calibration (the `calibration` section, or one orientation of the
//! `two_orientation` one): a PIGA table read as it is, or raw PIGA output recordings each reduced to
//! its mean output over whole spindle revolutions; both become points. Every error and
//! warning names the configuration field the data set comes from (`calibration.table`,
//! `two_orientation.orientations[1].recordings.files[3]`).

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use recording::FileDigest;

use crate::config::{
    OutputSigma, PigaRecordingSet, PigaTableConfig, SIGMA_RATE_TOLERANCE, TableLayoutError,
};
use crate::error::{InvalidReason, PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, DataSource, InputFile, InputRole};
use crate::results::{PigaRecordingResult, Warning};

/// The PIGA's data: a table, or raw output recordings to reduce.
#[derive(Debug, Clone)]
pub(crate) enum PigaData {
    Table(PigaTableRows),
    Recordings {
        /// The configuration field of the set (`calibration.recordings`).
        field: String,
        /// Harmonics of the spindle angle removed per revolution.
        order: usize,
        files: Vec<LoadedPigaRecording>,
    },
}

impl PigaData {
    /// The declared rate of each point, deg/s (a table's rows, or each recording's rate as
    /// the study file declares it).
    pub(crate) fn declared_rates_deg_s(&self) -> Vec<f64> {
        match self {
            Self::Table(t) => t.rates_deg_s.clone(),
            Self::Recordings { files, .. } => files.iter().map(|f| f.rate_deg_s).collect(),
        }
    }

    /// Every data file, with its digest and configuration field: the table, or each
    /// recording in the configuration's order.
    pub(crate) fn input_files(&self) -> Vec<InputFile<'_>> {
        match self {
            Self::Table(t) => vec![InputFile {
                path: &t.file,
                role: InputRole::PigaTable,
                field: t.field.clone(),
                digest: t.digest.as_ref(),
            }],
            Self::Recordings { field, files, .. } => files
                .iter()
                .enumerate()
                .map(|(i, f)| InputFile {
                    path: &f.file,
                    role: InputRole::PigaRecording,
                    field: format!("{field}.files[{i}]"),
                    digest: f.digest.as_ref(),
                })
                .collect(),
        }
    }

    /// The field and file a "too few rates" error names: the table, or the recordings.
    pub(crate) fn named(&self) -> (String, PathBuf) {
        match self {
            Self::Table(t) => (t.field.clone(), t.file.clone()),
            Self::Recordings { field, .. } => {
                (format!("{field}.files"), PathBuf::from("the recordings"))
            }
        }
    }
}

/// A PIGA table's rows, checked (rates > 0, σ > 0).
#[derive(Debug, Clone)]
pub(crate) struct PigaTableRows {
    /// The configuration field of the table (`calibration.table`).
    pub(crate) field: String,
    pub(crate) file: PathBuf,
    pub(crate) rates_deg_s: Vec<f64>,
    pub(crate) outputs_rad_s: Vec<f64>,
    pub(crate) sigma_rad_s: Option<Vec<f64>>,
    pub(crate) labels: Option<Vec<String>>,
    /// The line of each row in the table file.
    pub(crate) lines: Vec<usize>,
    /// The file's size and SHA-256 as read, when the data source keeps them.
    pub(crate) digest: Option<FileDigest>,
}

/// A raw PIGA output recording and the rate the study declares for it.
#[derive(Debug, Clone)]
pub(crate) struct LoadedPigaRecording {
    pub(crate) rate_deg_s: f64,
    pub(crate) file: PathBuf,
    pub(crate) recording: recording::PigaRecording,
    /// The file's size and SHA-256 as read, when the data source keeps them.
    pub(crate) digest: Option<FileDigest>,
}

/// The calibration's points, whatever they came from: one per table row or recording.
#[derive(Debug, Clone)]
pub(crate) struct PigaPoints {
    /// The rate of each point, deg/s (a recording's measured rate when it has an encoder).
    pub(crate) rates_deg_s: Vec<f64>,
    pub(crate) outputs_rad_s: Vec<f64>,
    /// Each output's standard uncertainty, rad/s (a table's σ column, or a recording's
    /// standard error across revolutions); `None`: unweighted.
    pub(crate) sigma_rad_s: Option<Vec<f64>>,
    pub(crate) labels: Option<Vec<String>>,
    /// Where each point comes from.
    pub(crate) origins: Vec<Origin>,
    /// The table file, or `None` for recordings.
    pub(crate) table: Option<PathBuf>,
    /// Each recording's reduction (empty for a table).
    pub(crate) recordings: Vec<PigaRecordingResult>,
}

/// Where a calibration point comes from.
#[derive(Debug, Clone)]
pub(crate) enum Origin {
    /// A table row's line.
    Line(usize),
    /// A recording file.
    File(PathBuf),
}

/// The calibration's points: a table's rows as they are, or each raw recording reduced
/// to its mean output over whole spindle revolutions (in parallel), with the
/// recordings' diagnostics as warnings naming the field and the file.
pub(crate) fn points(
    data: &PigaData,
    source: &Path,
) -> std::result::Result<(PigaPoints, Vec<Warning>), PipelineError> {
    let (set_field, order, files) = match data {
        PigaData::Table(t) => {
            return Ok((
                PigaPoints {
                    rates_deg_s: t.rates_deg_s.clone(),
                    outputs_rad_s: t.outputs_rad_s.clone(),
                    sigma_rad_s: t.sigma_rad_s.clone(),
                    labels: t.labels.clone(),
                    origins: t.lines.iter().map(|&l| Origin::Line(l)).collect(),
                    table: Some(t.file.clone()),
                    recordings: Vec::new(),
                },
                Vec::new(),
            ));
        }
        PigaData::Recordings {
            field,
            order,
            files,
        } => (field, *order, files),
    };
    let reduced: Vec<_> = files
        .par_iter()
        .map(|f| {
            let _span = tracing::info_span!("reduce", file = %f.file.display()).entered();
            recording::reduce_piga_recording(
                &f.recording,
                units::deg_s_to_rad_s(f.rate_deg_s),
                order,
            )
        })
        .collect();
    let mut errors = Vec::new();
    let mut warnings = Vec::new();
    let mut points = PigaPoints {
        rates_deg_s: Vec::with_capacity(files.len()),
        outputs_rad_s: Vec::with_capacity(files.len()),
        sigma_rad_s: Some(Vec::with_capacity(files.len())),
        labels: None,
        origins: Vec::with_capacity(files.len()),
        table: None,
        recordings: Vec::with_capacity(files.len()),
    };
    for (i, (f, result)) in files.iter().zip(reduced).enumerate() {
        let field = format!("{set_field}.files[{i}]");
        let r = match result {
            Ok(r) => r,
            Err(e) => {
                errors.push(PipelineError::Recording {
                    path: source.to_owned(),
                    field,
                    source: Box::new(e),
                });
                continue;
            }
        };
        let location = format!("{field} ({})", f.file.display());
        warnings.extend(
            r.diagnostics
                .iter()
                .map(|d| Warning::recording(d, location.clone())),
        );
        let rate_deg_s = r.rate_rad_s().to_degrees();
        points.rates_deg_s.push(rate_deg_s);
        points.outputs_rad_s.push(r.output_rad_s);
        if let Some(s) = points.sigma_rad_s.as_mut() {
            s.push(r.output_u_rad_s);
        }
        points.origins.push(Origin::File(f.file.clone()));
        points.recordings.push(PigaRecordingResult {
            file: f.file.display().to_string(),
            declared_rate_deg_s: f.rate_deg_s,
            rate_deg_s,
            angle_source: r.angle_source.name().to_owned(),
            output_rad_s: r.output_rad_s,
            u_rad_s: r.output_u_rad_s,
            across_revolutions_u_rad_s: r.across_revolutions_u_rad_s,
            white_noise_u_rad_s: r.white_noise_u_rad_s,
            revolution_sd_rad_s: r.revolution_sd_rad_s,
            revolutions: r.revolutions,
            dropped_revolutions: r.dropped_revolutions,
        });
    }
    PipelineError::from_list(errors)?;
    // A recording whose output has no scatter (noise-free data) cannot be weighted:
    // the fit is then unweighted.
    if points
        .sigma_rad_s
        .as_ref()
        .is_some_and(|s| s.iter().any(|v| !v.is_finite() || *v <= 0.0))
    {
        points.sigma_rad_s = None;
        warnings.push(Warning::calibration_unweighted(set_field));
    }
    Ok((points, warnings))
}

/// Reads a PIGA table (the configuration field `field`, `calibration.table`): rate and
/// output columns, the σ and label columns when named; as the laboratory exported it when the
/// configuration gives its `format` (units converted, the headers' stated units checked).
/// Rates must be finite and > 0, outputs finite, σ finite and > 0.
pub(crate) fn load_piga_table(
    config: &PigaTableConfig,
    field: &str,
    base: &Path,
    source: &Path,
    load: &dyn DataSource,
) -> Result<PigaTableRows> {
    let file = base.join(&config.file);
    let recording_error = |e: recording::RecordingError| PipelineError::Recording {
        path: source.to_owned(),
        field: field.to_owned(),
        source: Box::new(e),
    };
    let layout_error = |e| match e {
        TableLayoutError::FormatAndColumns => PipelineError::Unsupported {
            path: source.to_owned(),
            field: field.to_owned(),
            reason: UnsupportedReason::TableFormatAndColumns,
        },
        TableLayoutError::Recording(e) => recording_error(e),
    };
    let layout = config.piga_format().map_err(layout_error)?;
    let format = config.reader_format().map_err(layout_error)?;
    if let Some(declared) = &config.output_sigma_rad_s {
        check_declared_sigma(declared, config, field, source)?;
    }
    let read = load.read_table(&file, &format).map_err(recording_error)?;
    let t = recording::PigaTable::from_table(read.value, &layout).map_err(recording_error)?;
    let lines: Vec<usize> = (0..t.len()).map(|i| t.line_of_row(i)).collect();
    let (rates, outputs, sigma, labels) = (t.rate_deg_s, t.output_rad_s, t.sigma_rad_s, t.labels);
    let rate_name = layout.rate.column.trim().to_owned();
    let output_name = layout.output.column.trim().to_owned();
    let sigma_name = layout.sigma.as_ref().map(|c| c.column.trim().to_owned());
    let bad =
        |i: usize, column: &str, value: f64, reason: InvalidReason| PipelineError::TableValue {
            path: source.to_owned(),
            field: field.to_owned(),
            file: file.clone(),
            line: lines[i],
            column: column.to_owned(),
            value,
            reason,
        };
    // the calibration's own check of its points (`centrifuge-cal identify` makes the same),
    // every refused value at once, each at its line and column
    let rates_rad_s: Vec<f64> = rates.iter().map(|&r| units::deg_s_to_rad_s(r)).collect();
    let checked = ::calibration::check_points(&::calibration::Points {
        rates_rad_s: &rates_rad_s,
        outputs_rad_s: &outputs,
        sigma_rad_s: sigma.as_deref(),
    });
    if let Err(::calibration::CalibrationError::Points { bad: refused }) = checked {
        use ::calibration::PointValue;
        let sigma_name = sigma_name.as_deref().unwrap_or("sigma_rad_s");
        PipelineError::from_list(
            refused
                .iter()
                .map(|b| {
                    let reason = InvalidReason::of_point(b);
                    match b.what {
                        PointValue::Rate => bad(b.row, &rate_name, rates[b.row], reason),
                        PointValue::Output => bad(b.row, &output_name, b.value, reason),
                        PointValue::Sigma => bad(b.row, sigma_name, b.value, reason),
                    }
                })
                .collect(),
        )?;
    }
    let sigma = match &config.output_sigma_rad_s {
        Some(declared) => Some(declared_sigma(
            declared, &rates, &lines, field, &file, source,
        )?),
        None => sigma,
    };
    Ok(PigaTableRows {
        field: field.to_owned(),
        file: file.clone(),
        rates_deg_s: rates,
        outputs_rad_s: outputs,
        sigma_rad_s: sigma,
        labels,
        lines,
        digest: read.digest,
    })
}

/// Reads raw PIGA output recordings (the configuration field `field`,
/// `calibration.recordings`) in parallel, after checking their rates and the harmonic order.
pub(crate) fn load_piga_recordings(
    set: &PigaRecordingSet,
    field: &str,
    base: &Path,
    source: &Path,
    load: &dyn DataSource,
) -> Result<PigaData> {
    let check = Check { path: source };
    if !(1..=harmonics::MAX_ORDER).contains(&set.order) {
        return Err(check.invalid(
            format!("{field}.order"),
            set.order as f64,
            InvalidReason::HarmonicOrder,
        ));
    }
    for (i, point) in set.files.iter().enumerate() {
        if !(point.rate_deg_s.is_finite() && point.rate_deg_s > 0.0) {
            return Err(check.invalid(
                format!("{field}.files[{i}].rate_deg_s"),
                point.rate_deg_s,
                InvalidReason::RateNotPositive,
            ));
        }
    }
    let loaded: Vec<_> = set
        .files
        .par_iter()
        .map(|point| {
            let file = base.join(&point.file);
            let _span = tracing::info_span!("load", file = %file.display()).entered();
            let result = load.read_piga_recording(&file, &set.format);
            (point.rate_deg_s, file, result)
        })
        .collect();
    let mut errors = Vec::new();
    let mut files = Vec::with_capacity(loaded.len());
    for (i, (rate_deg_s, file, result)) in loaded.into_iter().enumerate() {
        match result {
            Ok(read) => files.push(LoadedPigaRecording {
                rate_deg_s,
                file,
                recording: read.value,
                digest: read.digest,
            }),
            Err(error) => errors.push(PipelineError::Recording {
                path: source.to_owned(),
                field: format!("{field}.files[{i}]"),
                source: Box::new(error),
            }),
        }
    }
    PipelineError::from_list(errors)?;
    Ok(PigaData::Recordings {
        field: field.to_owned(),
        order: set.order,
        files,
    })
}

/// Checks a table's stated output noise (`output_sigma_rad_s`) before the table is read: no
/// σ column beside it, every σ finite and > 0, every rate finite, > 0 and listed once.
fn check_declared_sigma(
    declared: &OutputSigma,
    config: &PigaTableConfig,
    field: &str,
    source: &Path,
) -> Result<()> {
    let check = Check { path: source };
    let key = format!("{field}.output_sigma_rad_s");
    let column = match &config.format {
        Some(f) if f.sigma.is_some() => Some(format!("{field}.format.sigma")),
        _ => config
            .sigma_column
            .as_ref()
            .map(|_| format!("{field}.sigma_column")),
    };
    if let Some(other) = column {
        return Err(PipelineError::StatedTwice {
            path: source.to_owned(),
            field: key,
            other,
            what: "each output's standard uncertainty",
        });
    }
    let sigma_ok = |s: f64| s.is_finite() && s > 0.0;
    match declared {
        OutputSigma::Constant(s) => {
            if !sigma_ok(*s) {
                return Err(check.invalid(
                    format!("{key}.constant"),
                    *s,
                    InvalidReason::SigmaNotPositive,
                ));
            }
        }
        OutputSigma::PerRate(list) => {
            if list.is_empty() {
                return Err(PipelineError::EmptyList {
                    path: source.to_owned(),
                    field: format!("{key}.per_rate"),
                });
            }
            for (i, &(rate, s)) in list.iter().enumerate() {
                let entry = format!("{key}.per_rate[{i}]");
                check.rate(format!("{entry} (rate_deg_s)"), rate)?;
                if !sigma_ok(s) {
                    return Err(check.invalid(
                        format!("{entry} (sigma_rad_s)"),
                        s,
                        InvalidReason::SigmaNotPositive,
                    ));
                }
                if let Some(j) = list[..i].iter().position(|&(r, _)| same_rate(r, rate)) {
                    return Err(PipelineError::DuplicateRate {
                        path: source.to_owned(),
                        field: entry,
                        first: format!("{key}.per_rate[{j}]"),
                        rate_deg_s: rate,
                    });
                }
            }
        }
    }
    Ok(())
}

/// Two rates, deg/s, equal to [`SIGMA_RATE_TOLERANCE`].
fn same_rate(a: f64, b: f64) -> bool {
    (a - b).abs() <= SIGMA_RATE_TOLERANCE * a.abs().max(b.abs())
}

/// Each row's standard uncertainty from the stated output noise (checked by
/// [`check_declared_sigma`]): the constant, or its rate's entry; every row whose rate is not
/// listed is an error, all at once.
fn declared_sigma(
    declared: &OutputSigma,
    rates_deg_s: &[f64],
    lines: &[usize],
    field: &str,
    file: &Path,
    source: &Path,
) -> Result<Vec<f64>> {
    let list = match declared {
        OutputSigma::Constant(s) => return Ok(vec![*s; rates_deg_s.len()]),
        OutputSigma::PerRate(list) => list,
    };
    let mut sigma = Vec::with_capacity(rates_deg_s.len());
    let mut errors = Vec::new();
    for (i, &rate) in rates_deg_s.iter().enumerate() {
        match list.iter().find(|&&(r, _)| same_rate(r, rate)) {
            Some(&(_, s)) => sigma.push(s),
            None => errors.push(PipelineError::RateWithoutSigma {
                path: source.to_owned(),
                field: format!("{field}.output_sigma_rad_s"),
                file: file.to_owned(),
                line: lines[i],
                rate_deg_s: rate,
                listed: list.iter().map(|&(r, _)| r).collect(),
            }),
        }
    }
    PipelineError::from_list(errors)?;
    Ok(sigma)
}
