//! Probe recordings in the binary formats labs store beside CSV: NI TDMS (`tdms`) and
//! MATLAB MAT v5/v7 (`mat`). This module holds what both share: the channel selection,
//! the typed error parts, the sample conversion, and the assembly of a [`Recording`].
//!
//! # Samples have no line
//!
//! A CSV recording keeps the line of each sample; a binary one has none, so
//! [`Recording::line_of_sample`] is 0 for it and its errors name the channel (or variable)
//! and the 0-based sample index ([`RecordingError::NonFiniteSample`],
//! [`RecordingError::TimeAxis`], [`RecordingError::Samples`] with `line: None`).
//!
//! # Bounded reading
//!
//! Only a regular file is read (a FIFO, a device or a folder is
//! [`RecordingError::NotAFile`], refused without blocking). The file is read with positioned
//! reads, only the structures and the samples asked for (a file without the format's
//! signature is refused after its first bytes, whatever its size), and every length field is
//! checked against the file's real size before anything is sliced or allocated from it:
//! a sample vector is allocated only for samples whose bytes are in the file. A compressed
//! MAT variable grows only with its inflated output, at most 1032 times its compressed size
//! (DEFLATE's largest ratio).

mod channels;
mod daqmx;
mod decode;
pub(crate) mod mat;
mod scaling;
mod source;
pub(crate) mod tdms;

pub(crate) use source::{Source, with_source};

pub use channels::{BinaryChannels, ChannelInfo, MatVariables};

use std::path::Path;

use crate::error::{BinaryFormat, RecordingError, Result};
use crate::lab::format::{AngleSource, AngleUnit, RecordingFormat};
use crate::lab::probe::{AngleSourceKind, Recording, pulse_angle};

/// The binary format a file's extension names (`.tdms`, `.mat`, any case), if any.
pub(crate) fn format_of(path: &Path) -> Option<BinaryFormat> {
    let extension = path.extension()?.to_string_lossy().to_ascii_lowercase();
    match extension.as_str() {
        "tdms" => Some(BinaryFormat::Tdms),
        "mat" => Some(BinaryFormat::Mat),
        _ => None,
    }
}

/// A probe recording from a TDMS or MAT file (read from `source`; `path` names it) with a
/// [`RecordingFormat`]'s names and units: the time channel (or the waveform timing), the
/// gap channel and its unit, the angle from an encoder channel, an index-pulse channel or
/// the declared rate.
pub(crate) fn read_with_format(
    path: &Path,
    source: &Source<'_>,
    kind: BinaryFormat,
    format: &RecordingFormat,
) -> Result<Recording> {
    if format.waveform_time && kind == BinaryFormat::Mat {
        return Err(RecordingError::SettingNotForFile {
            path: path.to_path_buf(),
            setting: "waveform_time",
            applies_to: "TDMS files",
        });
    }
    format.gap.unit.sensitivity()?;
    let (angle, angle_unit) = match &format.angle {
        AngleSource::Encoder { column, unit, .. } => {
            if let AngleUnit::Counts { per_rev: 0 } = unit {
                return Err(RecordingError::InvalidCountsPerRev);
            }
            (Some(column.trim().to_owned()), *unit)
        }
        // The marker's 0/1 values as they are.
        AngleSource::IndexPulse { column } => (Some(column.trim().to_owned()), AngleUnit::Rad),
        AngleSource::Rate { start_angle_deg } => {
            if !start_angle_deg.is_finite() {
                return Err(RecordingError::InvalidStartAngle {
                    value: *start_angle_deg,
                });
            }
            (None, AngleUnit::Deg)
        }
    };
    let channels = BinaryChannels {
        group: format.group.clone(),
        time: (!format.waveform_time).then(|| format.time.column.trim().to_owned()),
        gap: format.gap.column.trim().to_owned(),
        gap_unit: format.gap.unit,
        angle,
        angle_unit,
        max_gap_intervals: format.max_gap_intervals,
        on_gap: format.on_gap,
        on_non_finite: format.on_non_finite,
    };
    let read = |channels: &BinaryChannels| match kind {
        BinaryFormat::Tdms => tdms::read(source, path, channels),
        BinaryFormat::Mat => mat::read(source, path, channels),
    };
    let mut rec = read(&channels)?;
    rec.on_outlier = format.on_outlier;
    // Times in another unit than seconds (a MAT time variable in ms, say).
    let scale = format.time.unit.s_per_unit();
    if !format.waveform_time && scale != 1.0 {
        rec.time_s.iter_mut().for_each(|t| *t *= scale);
    }
    match &format.angle {
        AngleSource::Encoder {
            column, optional, ..
        } if rec.angle_rad.is_none() && !optional => {
            // A required encoder channel the file lacks: the reader's error for a missing
            // channel, which lists those the file has.
            let lookup = BinaryChannels {
                gap: column.trim().to_owned(),
                angle: None,
                ..channels.clone()
            };
            read(&lookup)?;
        }
        AngleSource::IndexPulse { column } => {
            let pulses = rec.angle_rad.take().unwrap_or_default();
            if pulses.is_empty() {
                read(&BinaryChannels {
                    gap: column.trim().to_owned(),
                    angle: None,
                    ..channels.clone()
                })?;
            }
            rec.angle_rad = Some(pulse_angle(path, column, &rec.time_s, &pulses)?);
            rec.angle_source = AngleSourceKind::IndexPulse;
        }
        AngleSource::Rate { start_angle_deg } => {
            rec.angle_rad = None;
            rec.angle_source = AngleSourceKind::DeclaredRate;
            rec.start_angle_rad = start_angle_deg.to_radians();
        }
        AngleSource::Encoder { .. } => {}
    }
    Ok(rec)
}
