//! NI TDMS files, read from NI's public description of the format ("TDMS File Format
//! Internal Structure").
//!
//! A file is a sequence of segments. Each starts with a 28-byte lead-in (`TDSm`, the
//! table-of-contents flags, the version 4712 or 4713, the offset of the next segment and of
//! the raw data), then optional metadata (the objects `/`, `/'group'`, `/'group'/'channel'`
//! with their raw-data index and properties), then raw data: chunks of each channel's values
//! in the order of the segment's object list, contiguous or interleaved. A segment without
//! metadata or without a new object list carries on the previous segment's list and indexes.
//!
//! Read: little-endian segments, channels of 8- to 64-bit integers and single or double
//! floats (with or without unit), contiguous or interleaved, any number of segments, and the
//! `wf_start_offset`/`wf_increment` waveform properties for the time; DAQmx raw data (NI's
//! DAQmx logging: format-changing scalers of any DAQmx integer or float type in interleaved
//! raw buffers, `daqmx`); `NI_Scaling` properties of the channel, its group or the file
//! (linear and polynomial scales, chained from the raw values or a DAQmx scaler, `scaling`),
//! applied as npTDMS applies them. Not read: big-endian segments, digital-line scalers,
//! other scale types (RTD, strain, table, …: a typed error), and a partial chunk at the end
//! of a segment whose writer stopped (next-segment offset all ones).

mod metadata;
mod raw;
mod segment;
mod walk;

use std::collections::HashMap;
use std::path::Path;

use super::channels::{BinaryChannels, ChannelInfo, Place, Series, assemble};
use super::scaling::Prop;
use super::source::{Source, with_source};
use crate::error::{BinaryFormat, RecordingError, Result};
use crate::lab::probe::Recording;
use walk::{Walk, series};

/// Reads the channels of a probe recording from a TDMS file (see [`parse_tdms`]): the
/// lead-ins and metadata, then only the samples of the channels asked for, through a
/// reused buffer.
pub fn load_tdms(path: &Path, channels: &BinaryChannels) -> Result<Recording> {
    with_source(path, |source| read(source, path, channels))
}

/// Parses the channels of a probe recording from a TDMS file held in memory; `path` names
/// it in errors. Never panics; an error names the file and the byte offset or channel.
pub fn parse_tdms(bytes: &[u8], path: &Path, channels: &BinaryChannels) -> Result<Recording> {
    read(&Source::Bytes(bytes), path, channels)
}

/// The channels of a TDMS file held in memory, each with its group, the unit it states
/// (`unit_string`, else `NI_UnitDescription`), whether it has waveform timing
/// (`wf_increment`) and its number of values (`None`: a data type the reader does not
/// convert), in the order the file names them; for `init`, which proposes a study
/// configuration from them. `path` names the file in errors.
///
/// # Errors
/// As [`parse_tdms`], for a file whose structure cannot be read.
pub fn list_tdms(bytes: &[u8], path: &Path) -> Result<Vec<ChannelInfo>> {
    let place = Place {
        path,
        format: BinaryFormat::Tdms,
    };
    let mut file = Walk {
        place,
        group: None,
        roles: &[],
        objects: Vec::new(),
        daqmx: Vec::new(),
        by_path: HashMap::new(),
        list: Vec::new(),
        claimed: [None; 3],
        all: true,
    };
    let mut buf = Vec::new();
    file.walk(&Source::Bytes(bytes), &mut buf)?;
    Ok(file
        .objects
        .iter()
        .filter_map(|o| {
            let (group, name) = o.name.clone()?;
            let text = |key: &str| {
                o.props.iter().rev().find_map(|(n, v)| match v {
                    Prop::Text(t) if n == key && !t.trim().is_empty() => Some(t.trim().to_owned()),
                    _ => None,
                })
            };
            let convertible = o.bad_type.is_none() && o.unsupported.is_none();
            let samples = if o.scalers.is_empty() {
                o.spans.iter().map(|s| s.count).sum()
            } else {
                o.scalers
                    .iter()
                    .map(|(_, spans)| spans.iter().map(|s| s.count).sum::<usize>())
                    .max()
                    .unwrap_or(0)
            };
            Some(ChannelInfo {
                group: Some(group),
                name,
                unit: text("unit_string").or_else(|| text("NI_UnitDescription")),
                waveform: o.wf_increment.is_some(),
                samples: convertible.then_some(samples),
            })
        })
        .collect())
}

/// The values of one channel of a TDMS file held in memory (in `group`, else the first
/// group that has it), scaled as [`parse_tdms`] scales them; for `init`.
///
/// # Errors
/// As [`parse_tdms`]; [`RecordingError::MissingChannel`] when the file has no such channel.
pub fn tdms_channel(
    bytes: &[u8],
    path: &Path,
    group: Option<&str>,
    name: &str,
) -> Result<Vec<f64>> {
    let place = Place {
        path,
        format: BinaryFormat::Tdms,
    };
    let roles = ["", name, ""];
    let mut file = Walk {
        place,
        group,
        roles: &roles,
        objects: Vec::new(),
        daqmx: Vec::new(),
        by_path: HashMap::new(),
        list: Vec::new(),
        claimed: [None; 3],
        all: false,
    };
    let source = Source::Bytes(bytes);
    let mut buf = Vec::new();
    file.walk(&source, &mut buf)?;
    match file.claimed[1] {
        Some(k) => Ok(file.values(&source, k, name, &mut buf)?.values),
        None => Err(place.missing(&file.qualified(name), file.available())),
    }
}

/// The channels of a probe recording from a TDMS file read from `source`.
pub(crate) fn read(
    source: &Source<'_>,
    path: &Path,
    channels: &BinaryChannels,
) -> Result<Recording> {
    let place = Place {
        path,
        format: BinaryFormat::Tdms,
    };
    let roles: Vec<&str> = [
        channels.time.as_deref(),
        Some(channels.gap.as_str()),
        channels.angle.as_deref(),
    ]
    .into_iter()
    .map(Option::unwrap_or_default)
    .collect();
    let mut file = Walk {
        place,
        group: channels.group.as_deref(),
        roles: &roles,
        objects: Vec::new(),
        daqmx: Vec::new(),
        by_path: HashMap::new(),
        list: Vec::new(),
        claimed: [None; 3],
        all: false,
    };
    let mut buf = Vec::new();
    file.walk(source, &mut buf)?;
    let mut take = |role: usize| -> Result<Option<Series>> {
        file.claimed[role]
            .map(|k| file.values(source, k, roles[role], &mut buf))
            .transpose()
    };
    let gap = take(1)?;
    let time = if channels.time.is_some() {
        take(0)?
    } else {
        None
    };
    let angle = if channels.angle.is_some() {
        take(2)?
    } else {
        None
    };
    let Some(gap) = gap else {
        return Err(place.missing(&file.qualified(&channels.gap), file.available()));
    };
    let time = match (&channels.time, time) {
        (_, Some(time)) => time,
        (Some(name), None) => return Err(place.missing(&file.qualified(name), file.available())),
        (None, None) => {
            let obj = file.claimed[1].map(|k| &file.objects[k]);
            let Some((start, step)) =
                obj.and_then(|o| Some((o.wf_start.unwrap_or(0.0), o.wf_increment?)))
            else {
                return Err(RecordingError::NoTimeBase {
                    path: place.path(),
                    channel: channels.gap.clone(),
                });
            };
            let values = (0..gap.values.len())
                .map(|i| start + i as f64 * step)
                .collect();
            series(&format!("{} (wf_increment)", channels.gap), values)
        }
    };
    assemble(path, BinaryFormat::Tdms, channels, time, gap, angle)
}
