//! Probe recordings: time, probe gap and, optionally, the spindle encoder's angle, one
//! sample per row (the raw data behind eq. 20).

use std::path::{Path, PathBuf};

use harmonics::{HarmonicsError, ProbeSignal, SpindleAngle};

use crate::error::{RecordingError, Result};
use crate::format::{LengthUnit, RecordingFormat};
use crate::line_table::LineTable;
use crate::table::{Table, load_table, parse_table};

/// A probe recording in memory.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// The file it was read from.
    pub path: PathBuf,
    /// Sample times, s (strictly increasing, no gap above the format's limit).
    pub time_s: Vec<f64>,
    /// Probe gap of each sample, in [`Recording::gap_unit`].
    pub gap: Vec<f64>,
    /// Unit of [`Recording::gap`].
    pub gap_unit: LengthUnit,
    /// Encoder angle of each sample, rad, when the file has the angle column.
    pub angle_rad: Option<Vec<f64>>,
    /// The line of each sample in the file.
    lines: LineTable,
}

impl Recording {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }

    /// Whether there are no samples (never true for a loaded recording).
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }

    /// The 1-based line of sample `index` (0-based) in the file, from the row → line table
    /// kept when the file was read (the file is not read again). An index past the last
    /// sample is counted on from it. 0 for a recording read from a binary file (TDMS,
    /// MAT), whose samples have no line: its errors name the channel and sample index.
    pub fn line_of_sample(&self, index: usize) -> usize {
        self.lines.line_of(index)
    }

    /// A recording of checked samples read from a binary file: no row → line table
    /// ([`Recording::line_of_sample`] is 0).
    pub(crate) fn from_samples(
        path: PathBuf,
        time_s: Vec<f64>,
        gap: Vec<f64>,
        gap_unit: LengthUnit,
        angle_rad: Option<Vec<f64>>,
    ) -> Self {
        Self {
            path,
            time_s,
            gap,
            gap_unit,
            angle_rad,
            lines: LineTable::default(),
        }
    }

    /// The samples as a [`ProbeSignal`]: angles from the encoder column when present, else
    /// `θ = ω·(t − t₀) + θ₀` from the given rate and first-sample angle.
    pub fn signal(&self, rate_rad_s: f64, start_angle_rad: f64) -> ProbeSignal<'_> {
        let angle = match &self.angle_rad {
            Some(a) => SpindleAngle::Encoder(a),
            None => SpindleAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            },
        };
        ProbeSignal {
            time_s: &self.time_s,
            gap: &self.gap,
            angle,
        }
    }

    /// The recording in a table read with [`RecordingFormat::table_format`]: the angle in
    /// radians, the time axis checked.
    fn from_table(table: Table, format: &RecordingFormat) -> Result<Self> {
        let Table {
            path,
            mut columns,
            lines,
            ..
        } = table;
        let mut take = |k: usize| columns.get_mut(k).and_then(Option::take);
        // Time and gap are required columns: the table has them.
        let time_s = take(0).unwrap_or_default();
        let gap = take(1).unwrap_or_default();
        let mut angle_rad = take(2);
        let scale = format.angle_unit.rad_per_unit();
        if let Some(angle) = angle_rad.as_mut().filter(|_| scale != 1.0) {
            for a in angle {
                *a *= scale;
            }
        }
        // The values are finite; what is left is their order, gaps, and intervals that
        // overflow (a single row has no interval to check).
        if time_s.len() > 1 {
            harmonics::check_time_axis(&time_s, format.max_gap_intervals).map_err(|e| {
                let line = |index| lines.line_of(index);
                match e {
                    HarmonicsError::TimeNotIncreasing {
                        index,
                        previous_s,
                        time_s,
                        ..
                    } => RecordingError::TimeNotIncreasing {
                        path: path.clone(),
                        line: line(index),
                        previous_s,
                        time_s,
                    },
                    HarmonicsError::SampleGap {
                        index,
                        interval_s,
                        nominal_interval_s,
                        max_intervals,
                        ..
                    } => RecordingError::SampleGap {
                        path: path.clone(),
                        line: line(index),
                        interval_s,
                        nominal_interval_s,
                        max_intervals,
                    },
                    source => RecordingError::Samples {
                        path: path.clone(),
                        line: sample_index(&source).map(line),
                        source,
                    },
                }
            })?;
        }
        Ok(Self {
            path,
            time_s,
            gap,
            gap_unit: format.gap_unit,
            angle_rad,
            lines,
        })
    }
}

/// Reads a probe recording from a file, streaming it through one reused buffer of about a
/// megabyte (see [`load_table`](crate::load_table); a line longer than 16 MiB is
/// [`RecordingError::LineTooLong`]). The samples' lines are kept in a compact row → line
/// table ([`Recording::line_of_sample`]).
pub fn load_recording(path: &Path, format: &RecordingFormat) -> Result<Recording> {
    let table = load_table(path, &format.table_format()?)?;
    Recording::from_table(table, format)
}

/// Parses a probe recording held in memory; `path` names it in errors.
pub fn parse_recording(text: &[u8], path: &Path, format: &RecordingFormat) -> Result<Recording> {
    let table = parse_table(text, path, &format.table_format()?)?;
    Recording::from_table(table, format)
}

/// [`parse_recording`] through the reference path of the table parser (every row field by
/// field, [`crate::parse_table_reference`]): the fast path must give the same recording or
/// the same error. For the tests and the fuzz targets; not part of the crate's interface.
#[doc(hidden)]
pub fn parse_recording_reference(
    text: &[u8],
    path: &Path,
    format: &RecordingFormat,
) -> Result<Recording> {
    let table = crate::parse_table_reference(text, path, &format.table_format()?)?;
    Recording::from_table(table, format)
}

/// Fits eq. 20 per revolution to a loaded recording ([`harmonics::analyze`]), with the angle
/// from the encoder column when present, else from the rate; an error naming a sample is
/// given the sample's line in the file ([`Recording::line_of_sample`]).
///
/// With an encoder column, the encoder's mean rate must match `rate_rad_s` within
/// [`harmonics::ENCODER_RATE_TOLERANCE`] (2 %), else [`HarmonicsError::RateMismatch`]: a
/// study fits with the declared rate, so a file attached to the wrong rate point is refused.
pub fn analyze_recording(
    recording: &Recording,
    rate_rad_s: f64,
    start_angle_rad: f64,
    config: &harmonics::FitConfig,
) -> Result<harmonics::HarmonicAnalysis> {
    let located = |source: HarmonicsError| RecordingError::Samples {
        path: recording.path.clone(),
        // A binary recording has no lines (0): its error names the sample index only.
        line: sample_index(&source)
            .map(|row| recording.line_of_sample(row))
            .filter(|&line| line != 0),
        source,
    };
    let signal = recording.signal(rate_rad_s, start_angle_rad);
    let analysis = harmonics::analyze(&signal, config).map_err(located)?;
    // The encoder gives the angle, but the declared rate is the ω a study fits with.
    harmonics::check_encoder_rate(&signal, harmonics::DeclaredRate::new(rate_rad_s))
        .map_err(located)?;
    Ok(analysis)
}

/// The sample an analysis error names, if any.
fn sample_index(error: &HarmonicsError) -> Option<usize> {
    match error {
        HarmonicsError::NonFinite { index, .. }
        | HarmonicsError::NonFiniteInterval { index, .. }
        | HarmonicsError::TimeNotIncreasing { index, .. }
        | HarmonicsError::SampleGap { index, .. }
        | HarmonicsError::AngleNotIncreasing { index, .. } => Some(*index),
        HarmonicsError::TooFewSamples { first_sample, .. } => Some(*first_sample),
        HarmonicsError::Aliasing { after_sample, .. } => Some(*after_sample),
        _ => None,
    }
}
