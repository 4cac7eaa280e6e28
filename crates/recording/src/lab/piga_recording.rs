//! Raw PIGA output recordings: time, the PIGA's output angle (its precession angle in
//! degrees or radians, or pick-off counts) and the spindle's angle reference, one file per
//! centrifuge rate; reduced to the mean output rate over whole spindle revolutions, where
//! once-per-revolution terms cancel, with its standard error across revolutions — one row
//! of the eq. 18 calibration.

use std::f64::consts::{FRAC_PI_2, TAU};
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::format::{
    AngleSource, AngleUnit, Column, DecimalMark, Delimiter, OnBadSamples, RecordingFormat, TimeUnit,
};
use super::probe::{AngleSourceKind, Recording};
use super::volts::GapUnit;
use crate::digest::FileDigest;
use crate::error::{RecordingError, Result};
use crate::read::{load_recording, parse_recording};

/// Default name of the output-angle column.
pub const PIGA_OUTPUT_ANGLE_COLUMN: &str = "output_rad";

/// Layout of a raw PIGA output recording: as a probe recording's ([`RecordingFormat`]), with
/// the PIGA's output angle in place of the gap.
///
/// ```
/// let ron_text = r#"(
///     delimiter: ';',
///     output: (column: "pickoff", unit: counts(per_rev: 4096)),
///     angle: encoder(column: "spindle_deg", unit: deg),
/// )"#;
/// let format: recording::PigaRecordingFormat = ron::from_str(ron_text).unwrap();
/// assert_eq!(format.output.column, "pickoff");
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PigaRecordingFormat {
    /// Field delimiter (default `,`).
    pub delimiter: Delimiter,
    /// Decimal mark (default point).
    pub decimal: DecimalMark,
    /// Lines before the header, blank ones included.
    pub skip_lines: usize,
    /// The time column (default `time_s`, seconds).
    pub time: Column<TimeUnit>,
    /// The PIGA's output angle (default `output_rad`, radians): degrees, radians or
    /// pick-off counts per output revolution. Whole turns are unwrapped (an angle that wraps
    /// at 360° or a counter that wraps is followed), so the output must move less than a
    /// quarter turn between two samples.
    pub output: Column<AngleUnit>,
    /// Where the spindle angle comes from (default: the encoder column `angle_deg` when the
    /// header has it, else the declared rate, with the warning `angle_from_rate`).
    pub angle: AngleSource,
    /// Largest interval between samples, in nominal (median) sample intervals, before it
    /// counts as a gap (default 3).
    pub max_gap_intervals: f64,
    /// A gap: refuse the file (default) or drop the revolutions it touches.
    pub on_gap: OnBadSamples,
    /// A NaN or infinite value: refuse the file (default) or drop the revolutions it
    /// touches.
    pub on_non_finite: OnBadSamples,
}

impl Default for PigaRecordingFormat {
    fn default() -> Self {
        let probe = RecordingFormat::default();
        Self {
            delimiter: probe.delimiter,
            decimal: probe.decimal,
            skip_lines: probe.skip_lines,
            time: probe.time,
            output: Column {
                column: PIGA_OUTPUT_ANGLE_COLUMN.into(),
                unit: AngleUnit::Rad,
            },
            angle: probe.angle,
            max_gap_intervals: probe.max_gap_intervals,
            on_gap: probe.on_gap,
            on_non_finite: probe.on_non_finite,
        }
    }
}

impl PigaRecordingFormat {
    /// The same layout as a probe recording's, the output angle in the gap's place (read
    /// it with [`crate::load_recording`], then [`PigaRecording::from_recording`]).
    ///
    /// # Errors
    /// [`RecordingError::InvalidCountsPerRev`] for `counts` with 0 counts per revolution.
    pub fn probe_format(&self) -> Result<RecordingFormat> {
        if let AngleUnit::Counts { per_rev: 0 } = self.output.unit {
            return Err(RecordingError::InvalidCountsPerRev);
        }
        Ok(RecordingFormat {
            delimiter: self.delimiter,
            decimal: self.decimal,
            skip_lines: self.skip_lines,
            time: self.time.clone(),
            gap: Column {
                column: self.output.column.clone(),
                // Unused: the values are converted with the output's angle unit.
                unit: GapUnit::Um,
            },
            angle: self.angle.clone(),
            max_gap_intervals: self.max_gap_intervals,
            on_gap: self.on_gap,
            on_non_finite: self.on_non_finite,
            on_outlier: crate::lab::format::OnOutlier::default(),
            group: None,
            waveform_time: false,
        })
    }
}

/// A raw PIGA output recording in memory: time (s), the output angle (rad, whole turns
/// unwrapped) and the spindle angle.
#[derive(Debug, Clone, PartialEq)]
pub struct PigaRecording {
    /// The samples, the output angle in radians in the gap's place.
    samples: Recording,
}

impl PigaRecording {
    /// The file it was read from.
    pub fn path(&self) -> &Path {
        &self.samples.path
    }

    /// Sample times, s.
    pub fn time_s(&self) -> &[f64] {
        &self.samples.time_s
    }

    /// The output angle of each sample, rad, whole turns unwrapped.
    pub fn output_rad(&self) -> &[f64] {
        &self.samples.gap
    }

    /// Where the spindle angle comes from.
    pub fn angle_source(&self) -> AngleSourceKind {
        self.samples.angle_source
    }

    /// The samples as read: the output angle (rad, whole turns unwrapped) in the gap's
    /// place, with the spindle angle and the format's choices for bad samples.
    pub(crate) fn samples(&self) -> &Recording {
        &self.samples
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.samples.len()
    }

    /// Whether there are no samples (never true for a recording read from a file).
    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }

    /// The 1-based line of sample `index` in the file.
    pub fn line_of_sample(&self, index: usize) -> usize {
        self.samples.line_of_sample(index)
    }

    /// A recording read as a probe recording in [`PigaRecordingFormat::probe_format`], its
    /// output (in the gap's place) converted from `unit` to radians and unwrapped.
    ///
    /// # Errors
    /// [`RecordingError::OutputStep`] for an output that moves by more than a quarter turn
    /// between two samples.
    pub fn from_recording(mut samples: Recording, unit: AngleUnit) -> Result<Self> {
        let scale = unit.rad_per_unit();
        let mut turns = 0.0;
        let mut previous: Option<f64> = None;
        for i in 0..samples.gap.len() {
            let raw = samples.gap[i] * scale;
            if !raw.is_finite() {
                // Kept only with `on_non_finite: drop_revolution`: the analysis drops it.
                samples.gap[i] = raw;
                continue;
            }
            if let Some(before) = previous {
                let step = raw - before;
                turns -= (step / TAU).round() * TAU;
                let unwrapped = step - (step / TAU).round() * TAU;
                if unwrapped.abs() > FRAC_PI_2 {
                    return Err(RecordingError::OutputStep {
                        path: samples.path.clone(),
                        line: samples.line_of_sample(i),
                        step_rad: unwrapped,
                    });
                }
            }
            previous = Some(raw);
            samples.gap[i] = raw + turns;
        }
        Ok(Self { samples })
    }
}

/// Reads a raw PIGA output recording from a file (see [`load_recording`] for the text
/// format and its errors).
///
/// # Errors
/// Those of [`load_recording`]; [`RecordingError::InvalidCountsPerRev`] for `counts` with 0
/// counts per revolution; [`RecordingError::OutputStep`] for an output that moves by more
/// than a quarter turn between two samples.
pub fn load_piga_recording(path: &Path, format: &PigaRecordingFormat) -> Result<PigaRecording> {
    let samples = load_recording(path, &format.probe_format()?)?;
    PigaRecording::from_recording(samples, format.output.unit)
}

/// [`load_piga_recording`], with the size and SHA-256 of the bytes it read, taken as it read
/// them (the file is read once).
///
/// # Errors
/// Those of [`load_piga_recording`].
pub fn load_piga_recording_digested(
    path: &Path,
    format: &PigaRecordingFormat,
) -> Result<(PigaRecording, FileDigest)> {
    let (samples, digest) = crate::read::load_recording_digested(path, &format.probe_format()?)?;
    Ok((
        PigaRecording::from_recording(samples, format.output.unit)?,
        digest,
    ))
}

/// Parses a raw PIGA output recording held in memory; `path` names it in errors.
///
/// ```
/// use recording::{PigaRecordingFormat, parse_piga_recording};
/// // An output angle that wraps at 360°.
/// let text = "time_s,output_deg,angle_deg\n0,359.0,0\n0.01,1.0,3.6\n";
/// let format: PigaRecordingFormat =
///     ron::from_str(r#"(output: (column: "output_deg", unit: deg))"#).unwrap();
/// let rec = parse_piga_recording(text.as_bytes(), "piga.csv".as_ref(), &format)?;
/// approx::assert_relative_eq!(rec.output_rad()[1] - rec.output_rad()[0], 2f64.to_radians(),
///                             max_relative = 1e-12);
/// # Ok::<(), recording::RecordingError>(())
/// ```
///
/// # Errors
/// As [`load_piga_recording`].
pub fn parse_piga_recording(
    text: &[u8],
    path: &Path,
    format: &PigaRecordingFormat,
) -> Result<PigaRecording> {
    let samples = parse_recording(text, path, &format.probe_format()?)?;
    PigaRecording::from_recording(samples, format.output.unit)
}
