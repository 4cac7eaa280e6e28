//! What both binary readers share: the channel selection, the named series read, their
//! assembly into a [`Recording`], and the bounded little-endian cursor with its error place.

use std::path::{Path, PathBuf};

use super::decode::{BLOCK, first_non_finite};
use crate::error::{BinaryDefect, BinaryFormat, BinaryPart, RecordingError, Result, Unsupported};
use crate::lab::format::{ANGLE_COLUMN, AngleUnit, GAP_COLUMN, OnBadSamples, TIME_COLUMN};
use crate::lab::probe::Recording;
use crate::lab::volts::{GapUnit, volts_to_um};

/// The channels (TDMS) or variables (MAT) of a probe recording in a binary file, and their
/// units; [`load_tdms`](crate::load_tdms), [`load_mat`](crate::load_mat).
///
/// The default reads `time_s`, `gap_um` (µm) and, when present, `angle_deg` (deg), as the
/// CSV reader does.
#[derive(Debug, Clone, PartialEq)]
pub struct BinaryChannels {
    /// TDMS: the group holding the channels (`None`: the first group, in file order, that
    /// has a channel of that name). MAT: a struct variable whose fields are the variables
    /// (`None`: top-level variables; a name may also be a dotted path such as `rec.gap_um`).
    pub group: Option<String>,
    /// The time channel, s. `None` for TDMS: the times are `wf_start_offset + i ·
    /// wf_increment` from the gap channel's waveform properties. A MAT file needs one.
    pub time: Option<String>,
    /// The probe-gap channel, in [`BinaryChannels::gap_unit`].
    pub gap: String,
    /// Unit of the gap channel.
    pub gap_unit: GapUnit,
    /// The encoder-angle channel, in [`BinaryChannels::angle_unit`], used when the file has
    /// it (as the CSV reader's angle column); zero at the O1X1 reference, may wrap.
    pub angle: Option<String>,
    /// Unit of the angle channel.
    pub angle_unit: AngleUnit,
    /// Largest interval between samples, in nominal (median) sample intervals, before the
    /// recording is refused as having a gap (default 3, as for CSV).
    pub max_gap_intervals: f64,
    /// What a gap does: refuse the recording (default), or leave it for the analysis to
    /// drop the revolutions it touches, as for CSV (`on_gap`).
    pub on_gap: OnBadSamples,
    /// What a NaN or infinite sample does: refuse the recording naming the channel and
    /// sample index (default), or keep it for the analysis to drop its revolution, as for
    /// CSV (`on_non_finite`).
    pub on_non_finite: OnBadSamples,
}

impl Default for BinaryChannels {
    fn default() -> Self {
        Self {
            group: None,
            time: Some(TIME_COLUMN.into()),
            gap: GAP_COLUMN.into(),
            gap_unit: GapUnit::Um,
            angle: Some(ANGLE_COLUMN.into()),
            angle_unit: AngleUnit::Deg,
            max_gap_intervals: 3.0,
            on_gap: OnBadSamples::Error,
            on_non_finite: OnBadSamples::Error,
        }
    }
}

/// A channel of a TDMS file or a numeric variable of a MAT-file, as [`list_tdms`](crate::list_tdms)
/// and [`list_mat`](crate::list_mat) list them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChannelInfo {
    /// TDMS: its group. MAT: the struct variable holding it (`None`: a top-level variable).
    pub group: Option<String>,
    /// Its name (what [`BinaryChannels`] names).
    pub name: String,
    /// The unit the file states for it (TDMS `unit_string`, else `NI_UnitDescription`; a
    /// MAT-file states none).
    pub unit: Option<String>,
    /// TDMS: it carries waveform timing (`wf_increment`), so its sample times need no time
    /// channel.
    pub waveform: bool,
    /// Its number of values; `None` for a data type or shape the readers do not convert.
    pub samples: Option<usize>,
}

/// The MAT reader's name for [`BinaryChannels`]: variables instead of channels, `group` a
/// struct variable.
pub type MatVariables = BinaryChannels;

/// A named series read from a binary file.
#[derive(Debug)]
pub(crate) struct Series {
    /// Its name as given.
    pub(crate) name: String,
    /// Its values.
    pub(crate) values: Vec<f64>,
    /// Whether all values are known to be finite (checked while decoding); when false, the
    /// values are scanned to find the culprit.
    pub(crate) finite: bool,
}

/// Checks the series of a binary recording (finite, equal lengths, the time axis) and
/// builds the [`Recording`]; `time` is `Err(gap name)` when the times were computed from
/// the gap channel's waveform properties.
pub(crate) fn assemble(
    path: &Path,
    format: BinaryFormat,
    channels: &BinaryChannels,
    time: Series,
    gap: Series,
    angle: Option<Series>,
) -> Result<Recording> {
    if !channels.max_gap_intervals.is_finite() || channels.max_gap_intervals < 1.0 {
        return Err(RecordingError::InvalidGapLimit {
            value: channels.max_gap_intervals,
        });
    }
    let all = [Some(&time), Some(&gap), angle.as_ref()];
    for s in all.into_iter().flatten() {
        if s.values.is_empty() {
            return Err(RecordingError::Unsupported {
                path: path.to_path_buf(),
                format,
                channel: s.name.clone(),
                what: Unsupported::NoSamples,
            });
        }
        if s.values.len() != time.values.len() {
            return Err(RecordingError::ChannelLength {
                path: path.to_path_buf(),
                format,
                channel: s.name.clone(),
                reference: time.name.clone(),
                expected: time.values.len(),
                found: s.values.len(),
            });
        }
        // A non-finite sample is refused, or kept for the analysis to drop its revolution.
        let check = !s.finite && channels.on_non_finite == OnBadSamples::Error;
        if let Some(index) = check.then(|| first_non_finite(&s.values)).flatten() {
            return Err(RecordingError::NonFiniteSample {
                path: path.to_path_buf(),
                format,
                channel: s.name.clone(),
                index,
                value: s.values[index],
            });
        }
    }
    // As for CSV: with both policies strict, the time axis is checked whole (order and
    // gaps); a format that drops revolutions leaves gaps and non-finite samples to the
    // analysis, and only the order of finite times is checked here.
    let strict =
        channels.on_gap == OnBadSamples::Error && channels.on_non_finite == OnBadSamples::Error;
    let limit = if strict {
        channels.max_gap_intervals
    } else {
        f64::MAX
    };
    let finite_times = strict || time.values.iter().all(|t| t.is_finite());
    if time.values.len() > 1 && finite_times {
        harmonics::check_time_axis(&time.values, limit).map_err(|source| {
            RecordingError::TimeAxis {
                path: path.to_path_buf(),
                format,
                channel: time.name.clone(),
                source,
            }
        })?;
    }
    let angle_rad = angle.map(|a| {
        let mut v = a.values;
        let scale = channels.angle_unit.rad_per_unit();
        if scale != 1.0 {
            use rayon::prelude::*;
            v.par_chunks_mut(BLOCK)
                .for_each(|block| block.iter_mut().for_each(|x| *x *= scale));
        }
        v
    });
    let sensitivity = channels.gap_unit.sensitivity()?;
    let mut gap_values = gap.values;
    if let Some(s) = &sensitivity {
        volts_to_um(&mut gap_values, s);
    }
    Ok(Recording::from_samples(
        path.to_path_buf(),
        time.values,
        gap_values,
        channels.gap_unit.length_unit(),
        sensitivity,
        angle_rad,
        (
            channels.max_gap_intervals,
            channels.on_gap,
            channels.on_non_finite,
        ),
    ))
}

/// The place of an error: file and format, for the readers' cursor.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Place<'a> {
    pub(crate) path: &'a Path,
    pub(crate) format: BinaryFormat,
}

impl Place<'_> {
    pub(crate) fn path(&self) -> PathBuf {
        self.path.to_path_buf()
    }

    pub(crate) fn truncated(&self, offset: usize, what: BinaryPart, needed: u64) -> RecordingError {
        RecordingError::Truncated {
            path: self.path(),
            format: self.format,
            offset: offset as u64,
            what,
            needed,
        }
    }

    pub(crate) fn malformed(&self, offset: usize, defect: BinaryDefect) -> RecordingError {
        RecordingError::Malformed {
            path: self.path(),
            format: self.format,
            offset: offset as u64,
            defect,
        }
    }

    pub(crate) fn unsupported(&self, channel: &str, what: Unsupported) -> RecordingError {
        RecordingError::Unsupported {
            path: self.path(),
            format: self.format,
            channel: channel.to_string(),
            what,
        }
    }

    pub(crate) fn missing(&self, channel: &str, available: Vec<String>) -> RecordingError {
        RecordingError::MissingChannel {
            path: self.path(),
            format: self.format,
            channel: channel.to_string(),
            available,
        }
    }
}

/// A little-endian reader over bytes that never reads past them: every read names the
/// structure it is in, for [`RecordingError::Truncated`].
#[derive(Debug, Clone)]
pub(crate) struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// Offset of `bytes[0]` in the file, for errors.
    base: usize,
    what: BinaryPart,
    place: Place<'a>,
}

impl<'a> Cursor<'a> {
    pub(crate) fn new(bytes: &'a [u8], pos: usize, what: BinaryPart, place: Place<'a>) -> Self {
        Self {
            bytes,
            pos,
            base: 0,
            what,
            place,
        }
    }

    /// A cursor at the start of `bytes`, which are at `base` in the file.
    pub(crate) fn based(bytes: &'a [u8], base: usize, what: BinaryPart, place: Place<'a>) -> Self {
        Self {
            base,
            ..Self::new(bytes, 0, what, place)
        }
    }

    /// Position in the file.
    pub(crate) fn pos(&self) -> usize {
        self.base + self.pos
    }

    pub(crate) fn take(&mut self, n: u64) -> Result<&'a [u8]> {
        let start = self.pos;
        let end = usize::try_from(n)
            .ok()
            .and_then(|n| start.checked_add(n))
            .filter(|&e| e <= self.bytes.len())
            .ok_or_else(|| self.place.truncated(self.base + start, self.what, n))?;
        self.pos = end;
        Ok(&self.bytes[start..end])
    }

    pub(crate) fn array<const N: usize>(&mut self) -> Result<[u8; N]> {
        let b = self.take(N as u64)?;
        <[u8; N]>::try_from(b).map_err(|_| self.place.truncated(self.pos(), self.what, N as u64))
    }

    pub(crate) fn u32(&mut self) -> Result<u32> {
        self.array().map(u32::from_le_bytes)
    }

    pub(crate) fn u64(&mut self) -> Result<u64> {
        self.array().map(u64::from_le_bytes)
    }
}
