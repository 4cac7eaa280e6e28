//! The TDMS reader's shared vocabulary (a leaf: the other parts use it, it uses none of them):
//! the lead-in's flags, the data types' sizes and sample types, the walk's state (objects,
//! their raw-data indexes and spans) and its lookups by name.

use std::collections::HashMap;

use crate::binary::channels::{Place, Series};
use crate::binary::daqmx::DaqmxIndex;
use crate::binary::decode::NumType;
use crate::binary::scaling::Prop;
use crate::error::Unsupported;

pub(super) const LEAD_IN: usize = 28;
pub(super) const TOC_META_DATA: u32 = 1 << 1;
pub(super) const TOC_NEW_OBJ_LIST: u32 = 1 << 2;
pub(super) const TOC_RAW_DATA: u32 = 1 << 3;
pub(super) const TOC_INTERLEAVED: u32 = 1 << 5;
pub(super) const TOC_BIG_ENDIAN: u32 = 1 << 6;
pub(super) const TYPE_STRING: u32 = 0x20;
pub(super) const NO_RAW_DATA: u32 = 0xFFFF_FFFF;
pub(super) const SAME_RAW_INDEX: u32 = 0;

/// Values of one channel in the file: `count` values from `offset`, `stride` bytes apart.
#[derive(Debug, Clone, Copy)]
pub(super) struct Span {
    pub(super) ty: NumType,
    pub(super) offset: usize,
    pub(super) count: usize,
    pub(super) stride: usize,
}

/// A channel's raw-data index: its data type and values per chunk.
#[derive(Debug, Clone, Copy)]
pub(super) struct Index {
    pub(super) code: u32,
    pub(super) count: u64,
    /// Bytes per chunk (for strings, from the index; else count × size), `None` when the
    /// type's size is unknown.
    pub(super) bytes: Option<u64>,
    /// The DAQmx part of the index, by its place in [`Walk::daqmx`].
    pub(super) daqmx: Option<usize>,
}

#[derive(Debug)]
pub(super) struct Object {
    /// `(group, channel)` of a channel object.
    pub(super) name: Option<(String, String)>,
    /// Index of the current segment (`None`: no data in it).
    pub(super) index: Option<Index>,
    /// Index last given, for a later segment's "same as before".
    pub(super) last: Option<Index>,
    /// A data type of a channel to read that is not converted.
    pub(super) bad_type: Option<u32>,
    pub(super) wf_increment: Option<f64>,
    pub(super) wf_start: Option<f64>,
    /// The channel's values, for channels to read.
    pub(super) spans: Vec<Span>,
    /// A DAQmx channel's values, by scaler: `(scale id, spans)`.
    pub(super) scalers: Vec<(u32, Vec<Span>)>,
    /// A DAQmx channel's TDMS data type.
    pub(super) daqmx_type: Option<u32>,
    /// What a DAQmx channel to read has that is not converted.
    pub(super) unsupported: Option<Unsupported>,
    /// Its `NI_` properties (scaling, unit description) and `unit_string`.
    pub(super) props: Vec<(String, Prop)>,
    pub(super) wanted: bool,
}

pub(super) struct Walk<'a> {
    pub(super) place: Place<'a>,
    pub(super) group: Option<&'a str>,
    /// Names of time, gap and angle ("" for none).
    pub(super) roles: &'a [&'a str],
    pub(super) objects: Vec<Object>,
    /// The DAQmx raw-data indexes read.
    pub(super) daqmx: Vec<DaqmxIndex>,
    pub(super) by_path: HashMap<String, usize>,
    /// The current segment's object list.
    pub(super) list: Vec<usize>,
    /// The object read for each role.
    pub(super) claimed: [Option<usize>; 3],
    /// Every channel is read (to list them).
    pub(super) all: bool,
}

impl Walk<'_> {
    /// The `NI_` properties of a channel, its group and the file, in that order.
    pub(super) fn property_levels(&self, k: usize) -> [&[(String, Prop)]; 3] {
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
    pub(super) fn qualified(&self, channel: &str) -> String {
        match self.group {
            Some(g) => format!("{g}/{channel}"),
            None => channel.to_string(),
        }
    }

    /// The channels of the file, as `group/channel`.
    pub(super) fn available(&self) -> Vec<String> {
        self.objects
            .iter()
            .filter_map(|o| o.name.as_ref())
            .map(|(g, c)| format!("{g}/{c}"))
            .collect()
    }
}

pub(super) fn series(name: &str, values: Vec<f64>) -> Series {
    Series {
        name: name.to_string(),
        values,
        finite: false,
    }
}

/// Appends a span, joining it to the previous one when it continues it.
pub(super) fn push_span(spans: &mut Vec<Span>, span: Span) {
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

/// Bytes per value of a TDMS data type, when fixed.
pub(super) fn value_size(code: u32) -> Option<u64> {
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
pub(super) fn num_type(code: u32) -> Option<NumType> {
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
