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

use std::collections::HashMap;
use std::path::Path;

use super::channels::{BinaryChannels, ChannelInfo, Cursor, Place, Series, assemble};
use super::daqmx::{self, DaqmxIndex};
use super::decode::{NumType, decode};
use super::scaling::{Leaf, Prop, Scaling};
use super::source::{Source, with_source};
use crate::error::{BinaryDefect, BinaryFormat, BinaryPart, RecordingError, Result, Unsupported};
use crate::lab::probe::Recording;

const LEAD_IN: usize = 28;
const TOC_META_DATA: u32 = 1 << 1;
const TOC_NEW_OBJ_LIST: u32 = 1 << 2;
const TOC_RAW_DATA: u32 = 1 << 3;
const TOC_INTERLEAVED: u32 = 1 << 5;
const TOC_BIG_ENDIAN: u32 = 1 << 6;
const TYPE_STRING: u32 = 0x20;
const NO_RAW_DATA: u32 = 0xFFFF_FFFF;
const SAME_RAW_INDEX: u32 = 0;

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

fn read(source: &Source<'_>, path: &Path, channels: &BinaryChannels) -> Result<Recording> {
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

fn series(name: &str, values: Vec<f64>) -> Series {
    Series {
        name: name.to_string(),
        values,
        finite: false,
    }
}

/// Values of one channel in the file: `count` values from `offset`, `stride` bytes apart.
#[derive(Debug, Clone, Copy)]
struct Span {
    ty: NumType,
    offset: usize,
    count: usize,
    stride: usize,
}

/// A channel's raw-data index: its data type and values per chunk.
#[derive(Debug, Clone, Copy)]
struct Index {
    code: u32,
    count: u64,
    /// Bytes per chunk (for strings, from the index; else count × size), `None` when the
    /// type's size is unknown.
    bytes: Option<u64>,
    /// The DAQmx part of the index, by its place in [`Walk::daqmx`].
    daqmx: Option<usize>,
}

#[derive(Debug)]
struct Object {
    /// `(group, channel)` of a channel object.
    name: Option<(String, String)>,
    /// Index of the current segment (`None`: no data in it).
    index: Option<Index>,
    /// Index last given, for a later segment's "same as before".
    last: Option<Index>,
    /// A data type of a channel to read that is not converted.
    bad_type: Option<u32>,
    wf_increment: Option<f64>,
    wf_start: Option<f64>,
    /// The channel's values, for channels to read.
    spans: Vec<Span>,
    /// A DAQmx channel's values, by scaler: `(scale id, spans)`.
    scalers: Vec<(u32, Vec<Span>)>,
    /// A DAQmx channel's TDMS data type.
    daqmx_type: Option<u32>,
    /// What a DAQmx channel to read has that is not converted.
    unsupported: Option<Unsupported>,
    /// Its `NI_` properties (scaling, unit description) and `unit_string`.
    props: Vec<(String, Prop)>,
    wanted: bool,
}

struct Walk<'a> {
    place: Place<'a>,
    group: Option<&'a str>,
    /// Names of time, gap and angle ("" for none).
    roles: &'a [&'a str],
    objects: Vec<Object>,
    /// The DAQmx raw-data indexes read.
    daqmx: Vec<DaqmxIndex>,
    by_path: HashMap<String, usize>,
    /// The current segment's object list.
    list: Vec<usize>,
    /// The object read for each role.
    claimed: [Option<usize>; 3],
    /// Every channel is read (to list them).
    all: bool,
}

impl Walk<'_> {
    fn walk(&mut self, source: &Source<'_>, buf: &mut Vec<u8>) -> Result<()> {
        if source.len() == 0 {
            return Err(self.place.truncated(0, BinaryPart::LeadIn, LEAD_IN as u64));
        }
        let mut pos = 0;
        while pos < source.len() {
            pos = self.segment(source, pos, buf)?;
        }
        Ok(())
    }

    /// Reads the segment at `pos`; returns the position of the next.
    fn segment(&mut self, source: &Source<'_>, pos: usize, buf: &mut Vec<u8>) -> Result<usize> {
        let place = self.place;
        let file_len = source.len();
        let lead_in = source.read(pos, LEAD_IN, buf)?;
        let mut lead = Cursor::based(lead_in, pos, BinaryPart::LeadIn, place);
        if lead.array::<4>().ok() != Some(*b"TDSm") {
            if lead_in.len() < 4 && b"TDSm".starts_with(lead_in) {
                return Err(place.truncated(pos, BinaryPart::LeadIn, LEAD_IN as u64));
            }
            return Err(RecordingError::BadMagic {
                path: place.path(),
                format: BinaryFormat::Tdms,
                offset: pos as u64,
            });
        }
        let toc = lead.u32()?;
        let version = lead.u32()?;
        let next = lead.u64()?;
        let raw = lead.u64()?;
        if version != 4712 && version != 4713 {
            return Err(place.malformed(pos, BinaryDefect::TdmsVersion { found: version }));
        }
        if toc & TOC_BIG_ENDIAN != 0 {
            return Err(place.malformed(pos, BinaryDefect::BigEndian));
        }
        let start = pos + LEAD_IN;
        let end = if next == u64::MAX {
            file_len
        } else {
            usize::try_from(next)
                .ok()
                .and_then(|n| start.checked_add(n))
                .filter(|&e| e <= file_len)
                .ok_or_else(|| {
                    place.truncated(
                        pos,
                        BinaryPart::Segment,
                        next.saturating_add(LEAD_IN as u64),
                    )
                })?
        };
        let raw_start = usize::try_from(raw)
            .ok()
            .and_then(|r| start.checked_add(r))
            .filter(|&r| r <= end)
            .ok_or_else(|| {
                place.malformed(
                    pos,
                    BinaryDefect::RawDataOffset {
                        offset: raw,
                        segment: (end - start) as u64,
                    },
                )
            })?;
        if toc & TOC_NEW_OBJ_LIST != 0 {
            self.list.clear();
        }
        if toc & TOC_META_DATA != 0 {
            let meta = source.read(start, raw_start - start, buf)?;
            self.metadata(meta, start)?;
        }
        if toc & TOC_RAW_DATA != 0 {
            self.raw_data(raw_start, end, toc & TOC_INTERLEAVED != 0, pos)?;
        }
        Ok(end)
    }

    fn metadata(&mut self, bytes: &[u8], start: usize) -> Result<()> {
        let place = self.place;
        let mut c = Cursor::based(bytes, start, BinaryPart::Metadata, place);
        let objects = c.u32()?;
        for _ in 0..objects {
            let at = c.pos();
            let path = string(&mut c)?;
            let k = self.object(&path);
            let index_len = c.u32()?;
            let index = match index_len {
                NO_RAW_DATA => None,
                SAME_RAW_INDEX => Some(
                    self.objects[k]
                        .last
                        .ok_or_else(|| place.malformed(at, BinaryDefect::NoPreviousIndex))?,
                ),
                daqmx::FORMAT_CHANGING | daqmx::DIGITAL_LINE => {
                    let d = daqmx::read_index(&mut c, index_len, at, place)?;
                    let index = Index {
                        code: d.data_type,
                        count: d.count,
                        bytes: None,
                        daqmx: Some(self.daqmx.len()),
                    };
                    self.daqmx.push(d);
                    Some(index)
                }
                20 | 28 => {
                    let code = c.u32()?;
                    let dim = c.u32()?;
                    if dim != 1 {
                        return Err(
                            place.malformed(at, BinaryDefect::ArrayDimension { found: dim })
                        );
                    }
                    let count = c.u64()?;
                    let bytes = if code == TYPE_STRING {
                        if index_len != 28 {
                            return Err(
                                place.malformed(at, BinaryDefect::IndexLength { found: index_len })
                            );
                        }
                        Some(c.u64()?)
                    } else {
                        if index_len != 20 {
                            c.u64()?;
                        }
                        value_size(code).and_then(|s| count.checked_mul(s))
                    };
                    Some(Index {
                        code,
                        count,
                        bytes,
                        daqmx: None,
                    })
                }
                found => return Err(place.malformed(at, BinaryDefect::IndexLength { found })),
            };
            let obj = &mut self.objects[k];
            obj.index = index;
            if index.is_some() {
                obj.last = index;
            }
            if let Some(i) = index.filter(|i| obj.wanted && i.daqmx.is_none())
                && num_type(i.code).is_none()
            {
                obj.bad_type.get_or_insert(i.code);
            }
            if let Some(d) = index.and_then(|i| i.daqmx) {
                obj.daqmx_type = Some(self.daqmx[d].data_type);
            }
            if !self.list.contains(&k) {
                self.list.push(k);
            }
            let properties = c.u32()?;
            for _ in 0..properties {
                let at = c.pos();
                let name = string(&mut c)?;
                let code = c.u32()?;
                let value = property(&mut c, code)
                    .transpose()
                    .ok_or_else(|| place.malformed(at, BinaryDefect::PropertyType { code }))??;
                let obj = &mut self.objects[k];
                let number = match &value {
                    Some(Prop::Num(x)) => Some(*x),
                    _ => None,
                };
                match name.as_str() {
                    "wf_increment" => obj.wf_increment = number,
                    "wf_start_offset" => obj.wf_start = number,
                    n if n.starts_with("NI_") || n == "unit_string" => {
                        if let Some(v) = value {
                            obj.props.push((name.clone(), v));
                        }
                    }
                    _ => {}
                }
            }
        }
        Ok(())
    }

    /// The object of a path, created on first sight; a channel that one of the roles
    /// names (in the group asked for, else in the first group that has it) is claimed.
    fn object(&mut self, path: &str) -> usize {
        if let Some(&k) = self.by_path.get(path) {
            return k;
        }
        let k = self.objects.len();
        let name = channel_name(path);
        let mut wanted = self.all && name.is_some();
        if let Some((g, ch)) = &name
            && self.group.is_none_or(|want| want == g)
        {
            for (role, want) in self.roles.iter().enumerate() {
                if !want.is_empty() && want == ch && self.claimed[role].is_none() {
                    self.claimed[role] = Some(k);
                    wanted = true;
                }
            }
        }
        self.objects.push(Object {
            name,
            index: None,
            last: None,
            bad_type: None,
            wf_increment: None,
            wf_start: None,
            spans: Vec::new(),
            scalers: Vec::new(),
            daqmx_type: None,
            unsupported: None,
            props: Vec::new(),
            wanted,
        });
        self.by_path.insert(path.to_string(), k);
        k
    }

    fn raw_data(
        &mut self,
        raw_start: usize,
        end: usize,
        interleaved: bool,
        pos: usize,
    ) -> Result<()> {
        let place = self.place;
        let daqmx = self
            .list
            .iter()
            .any(|&k| self.objects[k].index.is_some_and(|i| i.daqmx.is_some()));
        if daqmx {
            return self.daqmx_raw_data(raw_start, end, pos);
        }
        // Bytes per chunk, and per row when interleaved.
        let mut chunk: u64 = 0;
        let mut row: u64 = 0;
        let mut rows: Option<u64> = None;
        for &k in &self.list {
            let Some(i) = self.objects[k].index else {
                continue;
            };
            let bytes = i
                .bytes
                .ok_or_else(|| place.malformed(pos, BinaryDefect::DataSize { code: i.code }))?;
            chunk = chunk.saturating_add(bytes);
            if interleaved {
                let size = value_size(i.code).filter(|_| i.code != TYPE_STRING);
                let same = rows.is_none_or(|r| r == i.count);
                match size {
                    Some(s) if same => row += s,
                    _ => return Err(place.malformed(pos, BinaryDefect::Interleaved)),
                }
                rows = Some(i.count);
            }
        }
        let len = (end - raw_start) as u64;
        if chunk == 0 || len < chunk {
            return Ok(());
        }
        let chunks = len / chunk;
        let mut before: u64 = 0;
        for &k in &self.list {
            let obj = &mut self.objects[k];
            let Some(i) = obj.index else {
                continue;
            };
            let size = if interleaved {
                value_size(i.code).unwrap_or(0)
            } else {
                0
            };
            if obj.wanted && i.count > 0 {
                let ty = num_type(i.code);
                // Offsets below lie within `end`, which is within the file.
                let as_usize = |x: u64| usize::try_from(x).unwrap_or(usize::MAX);
                if let Some(ty) = ty {
                    let (first, count, stride, step) = if interleaved {
                        (before, i.count * chunks, row, 0)
                    } else {
                        (before, i.count, ty.size() as u64, chunk)
                    };
                    let n = if interleaved { 1 } else { chunks };
                    for j in 0..n {
                        let span = Span {
                            ty,
                            offset: raw_start + as_usize(first + j * step),
                            count: as_usize(count),
                            stride: as_usize(stride),
                        };
                        push_span(&mut obj.spans, span);
                    }
                }
            }
            before += if interleaved {
                size
            } else {
                i.bytes.unwrap_or(0)
            };
        }
        Ok(())
    }

    /// The raw data of a DAQmx segment: per chunk, each raw buffer's interleaved rows; each
    /// scaler of a channel to read is a column of its buffer's rows.
    fn daqmx_raw_data(&mut self, raw_start: usize, end: usize, pos: usize) -> Result<()> {
        let place = self.place;
        let mut channels = Vec::new();
        for &k in &self.list {
            let Some(i) = self.objects[k].index else {
                continue;
            };
            // DAQmx raw data and plain data cannot share a segment.
            let d = i
                .daqmx
                .ok_or_else(|| place.malformed(pos, BinaryDefect::DaqmxRaw))?;
            channels.push((k, i.count, d));
        }
        let layout = daqmx::buffers(
            channels
                .iter()
                .map(|&(_, count, d)| (count, &self.daqmx[d])),
            pos,
            place,
        )?;
        let len = (end - raw_start) as u64;
        if layout.chunk == 0 || len < layout.chunk {
            return Ok(());
        }
        let chunks = len / layout.chunk;
        let as_usize = |x: u64| usize::try_from(x).unwrap_or(usize::MAX);
        for &(k, _, d) in &channels {
            let obj = &mut self.objects[k];
            let index = &self.daqmx[d];
            if !obj.wanted {
                continue;
            }
            if index.digital {
                obj.unsupported.get_or_insert(Unsupported::DigitalLine);
                continue;
            }
            for s in &index.scalers {
                let Some(ty) = daqmx::num_type(s.ty) else {
                    obj.unsupported.get_or_insert(Unsupported::DaqmxType(s.ty));
                    continue;
                };
                // `buffers` checked that the buffer exists.
                let (rows, width, start) = layout.buffers[s.buffer as usize];
                if u64::from(s.offset) + ty.size() as u64 > width {
                    return Err(place.malformed(
                        pos,
                        BinaryDefect::DaqmxScaler {
                            buffer: s.buffer,
                            offset: s.offset,
                            width: width as u32,
                        },
                    ));
                }
                let at = match obj.scalers.iter().position(|(id, _)| *id == s.scale_id) {
                    Some(at) => at,
                    None => {
                        obj.scalers.push((s.scale_id, Vec::new()));
                        obj.scalers.len() - 1
                    }
                };
                for j in 0..chunks {
                    let span = Span {
                        ty,
                        // Within the segment: chunks · chunk ≤ len.
                        offset: raw_start
                            + as_usize(j * layout.chunk + start + u64::from(s.offset)),
                        count: as_usize(rows),
                        stride: as_usize(width),
                    };
                    push_span(&mut obj.scalers[at].1, span);
                }
            }
        }
        Ok(())
    }

    /// The values of object `k` (named `name` in errors), scaled.
    fn values(
        &self,
        source: &Source<'_>,
        k: usize,
        name: &str,
        buf: &mut Vec<u8>,
    ) -> Result<Series> {
        let place = self.place;
        let obj = &self.objects[k];
        if let Some(code) = obj.bad_type {
            return Err(place.unsupported(name, Unsupported::TdmsType(code)));
        }
        if let Some(what) = &obj.unsupported {
            return Err(place.unsupported(name, what.clone()));
        }
        let unsupported = |what| place.unsupported(name, what);
        let scaling = Scaling::from_properties(&self.property_levels(k)).map_err(unsupported)?;
        let daqmx = obj.daqmx_type.is_some();
        let raw_leaf = match (daqmx, obj.scalers.as_slice()) {
            (false, _) => Leaf::Raw,
            // A DAQmx channel of a plain type: its one scaler's values are its raw values.
            (true, [(id, _)]) if obj.daqmx_type != Some(daqmx::RAW_DATA_TYPE) => Leaf::Scaler(*id),
            _ => Leaf::Raw,
        };
        let scaling = match scaling {
            Some(s) => s,
            // Unscaled DAQmx raw data: the values of its one scaler.
            None => Scaling::none(match (daqmx, obj.scalers.as_slice()) {
                (true, [(id, _)]) => Leaf::Scaler(*id),
                _ => raw_leaf,
            }),
        };
        let leaf = match scaling.leaf {
            Leaf::Raw => raw_leaf,
            scaler => scaler,
        };
        let spans: &[Span] = match leaf {
            Leaf::Raw if daqmx => {
                return Err(unsupported(Unsupported::TdmsScaling(
                    "raw input for DAQmx raw data (a scale must read a scaler)".into(),
                )));
            }
            Leaf::Raw => &obj.spans,
            Leaf::Scaler(id) => match obj.scalers.iter().find(|(s, _)| *s == id) {
                Some((_, spans)) => spans,
                None if obj.scalers.is_empty() && !daqmx => &obj.spans,
                None => {
                    return Err(unsupported(Unsupported::TdmsScaling(format!(
                        "no DAQmx scaler of scale id {id}"
                    ))));
                }
            },
        };
        let total: usize = spans.iter().map(|s| s.count).sum();
        // Every span's bytes lie in the file: `total` is bounded by its size.
        let mut values = vec![0.0; total];
        let mut at = 0;
        let mut finite = true;
        for s in spans {
            let out = &mut values[at..at + s.count];
            let (n, f) = source.decode_at(s.offset, out, s.ty, s.stride, buf)?;
            at += n;
            finite &= f;
        }
        values.truncate(at);
        // Scaled values are scanned again: a scale may overflow.
        scaling.apply(&mut values);
        let finite = finite && scaling.is_identity();
        Ok(Series {
            finite,
            ..series(name, values)
        })
    }

    /// The `NI_` properties of a channel, its group and the file, in that order.
    fn property_levels(&self, k: usize) -> [&[(String, Prop)]; 3] {
        let obj = &self.objects[k];
        let group = obj.name.as_ref().and_then(|(g, _)| {
            self.by_path
                .get(&format!("/'{}'", g.replace('\'', "''")))
                .map(|&i| self.objects[i].props.as_slice())
        });
        let root = self
            .by_path
            .get("/")
            .map(|&i| self.objects[i].props.as_slice());
        [
            obj.props.as_slice(),
            group.unwrap_or_default(),
            root.unwrap_or_default(),
        ]
    }

    /// `group/channel` as the file would name the channel asked for.
    fn qualified(&self, channel: &str) -> String {
        match self.group {
            Some(g) => format!("{g}/{channel}"),
            None => channel.to_string(),
        }
    }

    /// The channels of the file, as `group/channel`.
    fn available(&self) -> Vec<String> {
        self.objects
            .iter()
            .filter_map(|o| o.name.as_ref())
            .map(|(g, c)| format!("{g}/{c}"))
            .collect()
    }
}

/// Appends a span, joining it to the previous one when it continues it.
fn push_span(spans: &mut Vec<Span>, span: Span) {
    if let Some(last) = spans.last_mut()
        && last.stride == span.stride
        && last.ty == span.ty
        && last.offset + last.count * last.stride == span.offset
    {
        last.count += span.count;
        return;
    }
    spans.push(span);
}

/// A length-prefixed UTF-8 string (invalid UTF-8 replaced).
fn string(c: &mut Cursor<'_>) -> Result<String> {
    let n = c.u32()?;
    Ok(String::from_utf8_lossy(c.take(u64::from(n))?).into_owned())
}

/// `(group, channel)` of an object path `/'group'/'channel'` (quotes doubled inside).
fn channel_name(path: &str) -> Option<(String, String)> {
    let mut parts = Vec::new();
    let mut rest = path;
    while let Some(r) = rest.strip_prefix("/'") {
        let mut name = String::new();
        let mut chars = r.char_indices();
        let mut end = None;
        while let Some((i, ch)) = chars.next() {
            if ch == '\'' {
                if r[i + 1..].starts_with('\'') {
                    name.push('\'');
                    chars.next();
                } else {
                    end = Some(i + 1);
                    break;
                }
            } else {
                name.push(ch);
            }
        }
        parts.push(name);
        rest = &r[end?..];
    }
    match (rest.is_empty(), <[String; 2]>::try_from(parts)) {
        (true, Ok([g, c])) => Some((g, c)),
        _ => None,
    }
}

/// Bytes per value of a TDMS data type, when fixed.
fn value_size(code: u32) -> Option<u64> {
    Some(match code {
        0 => 0,
        1 | 5 | 0x21 => 1,
        2 | 6 => 2,
        3 | 7 | 9 | 0x19 => 4,
        4 | 8 | 10 | 0x1A | 0x08_000C => 8,
        11 | 0x44 | 0x10_000D => 16,
        _ => return None,
    })
}

/// The sample type of a TDMS data type the reader converts.
fn num_type(code: u32) -> Option<NumType> {
    Some(match code {
        1 => NumType::I8,
        2 => NumType::I16,
        3 => NumType::I32,
        4 => NumType::I64,
        5 => NumType::U8,
        6 => NumType::U16,
        7 => NumType::U32,
        8 => NumType::U64,
        9 | 0x19 => NumType::F32,
        10 | 0x1A => NumType::F64,
        _ => return None,
    })
}

/// A property's value: `Some(Some(value))` a number or a string, `Some(None)` another known
/// type (skipped), `None` an unknown type.
fn property(c: &mut Cursor<'_>, code: u32) -> Result<Option<Option<Prop>>> {
    if code == TYPE_STRING {
        return Ok(Some(Some(Prop::Text(string(c)?))));
    }
    let Some(size) = value_size(code) else {
        return Ok(None);
    };
    let bytes = c.take(size)?;
    Ok(Some(num_type(code).map(|ty| {
        let mut v = [f64::NAN];
        decode(&mut v, bytes, ty, ty.size());
        Prop::Num(v[0])
    })))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn object_paths() {
        assert_eq!(
            channel_name("/'probe'/'gap_um'"),
            Some(("probe".into(), "gap_um".into()))
        );
        assert_eq!(
            channel_name("/'it''s'/'a''b'"),
            Some(("it's".into(), "a'b".into()))
        );
        assert_eq!(channel_name("/'probe'"), None);
        assert_eq!(channel_name("/"), None);
        assert_eq!(channel_name("/'a'/'b'/'c'"), None);
        assert_eq!(channel_name("/'a"), None);
    }
}
