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
//! The whole file is read into memory (its size is the bound), and every length field is
//! checked against the bytes that remain before anything is sliced or allocated from it:
//! a sample vector is allocated only for samples whose bytes are in the file. A compressed
//! MAT variable grows only with its inflated output, at most 1032 times its compressed size
//! (DEFLATE's largest ratio).

use std::fmt;
use std::path::{Path, PathBuf};

use crate::error::{RecordingError, Result};
use crate::format::{ANGLE_COLUMN, AngleUnit, GAP_COLUMN, LengthUnit, TIME_COLUMN};
use crate::probe::Recording;

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
    pub gap_unit: LengthUnit,
    /// The encoder-angle channel, in [`BinaryChannels::angle_unit`], used when the file has
    /// it (as the CSV reader's angle column); zero at the O1X1 reference, may wrap.
    pub angle: Option<String>,
    /// Unit of the angle channel.
    pub angle_unit: AngleUnit,
    /// Largest interval between samples, in nominal (median) sample intervals, before the
    /// recording is refused as having a gap (default 3, as for CSV).
    pub max_gap_intervals: f64,
}

impl Default for BinaryChannels {
    fn default() -> Self {
        Self {
            group: None,
            time: Some(TIME_COLUMN.into()),
            gap: GAP_COLUMN.into(),
            gap_unit: LengthUnit::Um,
            angle: Some(ANGLE_COLUMN.into()),
            angle_unit: AngleUnit::Deg,
            max_gap_intervals: 3.0,
        }
    }
}

/// The MAT reader's name for [`BinaryChannels`]: variables instead of channels, `group` a
/// struct variable.
pub type MatVariables = BinaryChannels;

/// A binary recording format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum BinaryFormat {
    /// NI TDMS.
    Tdms,
    /// MATLAB MAT-file, level 5 (v5, v6, v7).
    Mat,
}

impl BinaryFormat {
    /// What the format calls a named series: `channel` or `variable`.
    pub const fn item(self) -> &'static str {
        match self {
            Self::Tdms => "channel",
            Self::Mat => "variable",
        }
    }
}

impl fmt::Display for BinaryFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Tdms => "TDMS",
            Self::Mat => "MAT",
        })
    }
}

/// The structure a truncated binary file ends in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum BinaryPart {
    /// A TDMS segment's 28-byte lead-in.
    LeadIn,
    /// A TDMS segment (its lead-in's next-segment offset points past the end).
    Segment,
    /// A TDMS segment's metadata.
    Metadata,
    /// The MAT file's 128-byte header.
    Header,
    /// A MAT data element's 8-byte tag.
    ElementTag,
    /// A MAT data element's data.
    Element,
}

impl fmt::Display for BinaryPart {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::LeadIn => "a segment lead-in",
            Self::Segment => "a segment",
            Self::Metadata => "segment metadata",
            Self::Header => "the file header",
            Self::ElementTag => "a data element tag",
            Self::Element => "a data element",
        })
    }
}

/// What is wrong with a structure of a binary file.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum BinaryDefect {
    /// A TDMS version other than 4712 or 4713.
    TdmsVersion {
        /// The version found.
        found: u32,
    },
    /// A big-endian TDMS segment (not read).
    BigEndian,
    /// DAQmx raw data (not read: save the channels as plain TDMS).
    DaqmxRaw,
    /// A TDMS raw-data offset beyond its segment.
    RawDataOffset {
        /// The offset, from the end of the lead-in.
        offset: u64,
        /// The segment's length after its lead-in.
        segment: u64,
    },
    /// A TDMS raw-data index of a length other than 20 or 28 bytes.
    IndexLength {
        /// The length found.
        found: u32,
    },
    /// A TDMS channel of more than one dimension.
    ArrayDimension {
        /// The dimension found.
        found: u32,
    },
    /// A TDMS object reuses the previous segment's raw-data index, but has none.
    NoPreviousIndex,
    /// A TDMS property of an unknown data type.
    PropertyType {
        /// The type code.
        code: u32,
    },
    /// TDMS interleaved data with channels of different lengths or variable-size values.
    Interleaved,
    /// A TDMS channel's values whose size is unknown, in a segment with raw data.
    DataSize {
        /// The type code.
        code: u32,
    },
    /// A MAT version other than 0x0100.
    MatVersion {
        /// The version found.
        found: u16,
    },
    /// A big-endian MAT file (not read).
    MatEndian,
    /// A MAT data element of another type than expected.
    ElementType {
        /// The type expected.
        expected: &'static str,
        /// The type found.
        found: u32,
    },
    /// A MAT small data element of more than 4 bytes.
    SmallElement {
        /// The length found.
        found: u32,
    },
    /// A MAT array's data does not hold as many values as its dimensions say.
    ArraySize {
        /// Values the dimensions give (saturated).
        expected: u64,
        /// Bytes of data.
        bytes: u64,
    },
    /// A MAT struct field-name length of 0.
    FieldNameLength,
    /// Structs nested more deeply than the reader follows (16).
    NestingTooDeep,
    /// The data ends inside a structure (within a compressed MAT element).
    Ends {
        /// The structure.
        what: BinaryPart,
        /// Bytes it needs.
        needed: u64,
    },
    /// A compressed MAT element that does not inflate.
    Inflate,
    /// The data within a compressed MAT element: the byte offset is of the compressed
    /// element; the defect inside is given.
    InCompressed {
        /// Offset within the inflated data.
        offset: u64,
        /// The defect there.
        defect: Box<BinaryDefect>,
    },
}

impl fmt::Display for BinaryDefect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TdmsVersion { found } => write!(f, "TDMS version {found}, expected 4712 or 4713"),
            Self::BigEndian => f.write_str("big-endian segment (not read)"),
            Self::DaqmxRaw => f.write_str("DAQmx raw data (not read; save as plain TDMS)"),
            Self::RawDataOffset { offset, segment } => write!(
                f,
                "raw-data offset {offset} beyond the segment's {segment} bytes"
            ),
            Self::IndexLength { found } => {
                write!(f, "raw-data index of {found} bytes, expected 20 or 28")
            }
            Self::ArrayDimension { found } => write!(f, "array dimension {found}, expected 1"),
            Self::NoPreviousIndex => {
                f.write_str("object reuses a previous raw-data index, but has none")
            }
            Self::PropertyType { code } => write!(f, "property of unknown type {code:#x}"),
            Self::Interleaved => f.write_str(
                "interleaved data with channels of different lengths or variable-size values",
            ),
            Self::DataSize { code } => write!(f, "raw data of type {code:#x}, of unknown size"),
            Self::MatVersion { found } => write!(f, "version {found:#06x}, expected 0x0100"),
            Self::MatEndian => f.write_str("big-endian file (not read)"),
            Self::ElementType { expected, found } => {
                write!(f, "data element of type {found}, expected {expected}")
            }
            Self::SmallElement { found } => {
                write!(f, "small data element of {found} bytes (at most 4)")
            }
            Self::ArraySize { expected, bytes } => {
                write!(f, "array of {expected} values whose data has {bytes} bytes")
            }
            Self::FieldNameLength => f.write_str("struct field-name length 0"),
            Self::NestingTooDeep => f.write_str("structs nested more than 16 deep"),
            Self::Ends { what, needed } => {
                write!(f, "data ends inside {what} that needs {needed} bytes")
            }
            Self::Inflate => f.write_str("compressed element does not inflate"),
            Self::InCompressed { offset, defect } => {
                write!(f, "inflated byte {offset}: {defect}")
            }
        }
    }
}

/// What a channel or variable to read has that the readers do not convert.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum Unsupported {
    /// A TDMS data type (code) other than integers and single or double floats.
    TdmsType(u32),
    /// A MAT class (code) other than the numeric ones.
    MatClass(u8),
    /// A MAT numeric data type (code) that is not numeric.
    MatType(u32),
    /// Complex values.
    Complex,
    /// A MAT array that is not a vector.
    NotVector {
        /// Its dimensions.
        dims: Vec<usize>,
    },
    /// A channel with no samples.
    NoSamples,
}

impl fmt::Display for Unsupported {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TdmsType(code) => write!(f, "data type {code:#x}"),
            Self::MatClass(code) => write!(f, "MATLAB class {code} (a numeric array is read)"),
            Self::MatType(code) => write!(f, "data type {code}"),
            Self::Complex => f.write_str("complex values"),
            Self::NotVector { dims } => {
                let dims: Vec<String> = dims.iter().map(ToString::to_string).collect();
                write!(f, "array of size {} (a vector is read)", dims.join("x"))
            }
            Self::NoSamples => f.write_str("channel with no samples"),
        }
    }
}

/// The numeric sample types both formats store, little-endian.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum NumType {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
}

impl NumType {
    /// Bytes per value.
    pub(crate) const fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::I64 | Self::U64 | Self::F64 => 8,
        }
    }
}

/// Values decoded per block: blocks of a long channel are decoded on all cores (rayon).
const BLOCK: usize = 1 << 16;

/// Fills `out` with values of type `ty` starting at `bytes[0]`, each `stride` bytes after
/// the previous; returns how many were in `bytes` (the caller has checked that all are) and
/// whether all of them are finite (each block is scanned while it is in cache).
/// Give it memory from `vec![0.0; n]`, which the allocator takes zeroed from the system
/// without writing it; long outputs are filled in blocks on all cores (rayon).
pub(crate) fn decode(out: &mut [f64], bytes: &[u8], ty: NumType, stride: usize) -> (usize, bool) {
    let size = ty.size();
    if stride < size {
        return (0, true);
    }
    // Whole values in `bytes`.
    let fit = if bytes.len() < size {
        0
    } else {
        (bytes.len() - size) / stride + 1
    };
    let count = out.len().min(fit);
    let out = &mut out[..count];
    let finite = if count <= BLOCK {
        decode_into(out, bytes, ty, stride)
    } else {
        use rayon::prelude::*;
        // `reduce`, not `all`: every block is decoded, whatever the others hold.
        out.par_chunks_mut(BLOCK)
            .enumerate()
            .map(|(k, block)| decode_into(block, &bytes[k * BLOCK * stride..], ty, stride))
            .reduce(|| true, |a, b| a && b)
    };
    (count, finite)
}

/// Fills `out` with values of type `ty` from `bytes`, `stride` bytes apart (all in `bytes`);
/// whether all are finite.
fn decode_into(out: &mut [f64], bytes: &[u8], ty: NumType, stride: usize) -> bool {
    fn run<const N: usize>(
        out: &mut [f64],
        bytes: &[u8],
        stride: usize,
        f: impl Fn([u8; N]) -> f64,
    ) {
        let value = |c: &[u8]| <[u8; N]>::try_from(&c[..N]).map_or(f64::NAN, &f);
        if stride == N {
            // Contiguous: a loop the compiler vectorises.
            for (o, c) in out.iter_mut().zip(bytes.chunks_exact(N)) {
                *o = value(c);
            }
        } else {
            for (o, c) in out.iter_mut().zip(bytes.chunks(stride)) {
                if c.len() >= N {
                    *o = value(c);
                }
            }
        }
    }
    match ty {
        NumType::I8 => run::<1>(out, bytes, stride, |b| f64::from(i8::from_le_bytes(b))),
        NumType::U8 => run::<1>(out, bytes, stride, |b| f64::from(b[0])),
        NumType::I16 => run::<2>(out, bytes, stride, |b| f64::from(i16::from_le_bytes(b))),
        NumType::U16 => run::<2>(out, bytes, stride, |b| f64::from(u16::from_le_bytes(b))),
        NumType::I32 => run::<4>(out, bytes, stride, |b| f64::from(i32::from_le_bytes(b))),
        NumType::U32 => run::<4>(out, bytes, stride, |b| f64::from(u32::from_le_bytes(b))),
        // 64-bit integers above 2^53 round to the nearest double.
        NumType::I64 => run::<8>(out, bytes, stride, |b| i64::from_le_bytes(b) as f64),
        NumType::U64 => run::<8>(out, bytes, stride, |b| u64::from_le_bytes(b) as f64),
        NumType::F32 => run::<4>(out, bytes, stride, |b| f64::from(f32::from_le_bytes(b))),
        NumType::F64 => run::<8>(out, bytes, stride, f64::from_le_bytes),
    }
    first_non_finite(out).is_none()
}

/// The index of the first value that is NaN or infinite, if any (a branch-free scan of
/// eight lanes, then a search only when one is found).
pub(crate) fn first_non_finite(values: &[f64]) -> Option<usize> {
    if values.len() > BLOCK {
        use rayon::prelude::*;
        return values
            .par_chunks(BLOCK)
            .enumerate()
            .filter_map(|(k, block)| first_non_finite(block).map(|i| k * BLOCK + i))
            .min();
    }
    let mut lanes = [0.0f64; 8];
    let chunks = values.chunks_exact(8);
    let rest = chunks.remainder();
    for c in chunks {
        for (l, &x) in lanes.iter_mut().zip(c) {
            // x · 0 is 0 for a finite x and NaN otherwise.
            *l += x * 0.0;
        }
    }
    let tail: f64 = rest.iter().map(|&x| x * 0.0).sum();
    if lanes.iter().sum::<f64>() + tail == 0.0 {
        None
    } else {
        values.iter().position(|x| !x.is_finite())
    }
}

/// Where a reader reads from: bytes in memory, or a regular file read piece by piece with
/// positioned reads (only the structures and the samples asked for are read, through a
/// reused buffer, so no copy of the whole file is made). Every read is within `len`.
pub(crate) enum Source<'a> {
    /// Bytes in memory.
    Bytes(&'a [u8]),
    /// A regular file of `len` bytes.
    #[cfg(unix)]
    File {
        /// The file.
        file: std::fs::File,
        /// Its size when opened.
        len: usize,
        /// Its path, for errors.
        path: &'a Path,
    },
}

impl Source<'_> {
    /// Size in bytes.
    pub(crate) fn len(&self) -> usize {
        match self {
            Self::Bytes(b) => b.len(),
            #[cfg(unix)]
            Self::File { len, .. } => *len,
        }
    }

    /// The `n` bytes at `offset`, or as many as there are; `buf` holds them for a file.
    pub(crate) fn read<'s>(
        &'s self,
        offset: usize,
        n: usize,
        buf: &'s mut Vec<u8>,
    ) -> Result<&'s [u8]> {
        let end = offset.saturating_add(n).min(self.len());
        let offset = offset.min(end);
        match self {
            Self::Bytes(b) => Ok(&b[offset..end]),
            #[cfg(unix)]
            Self::File { file, path, .. } => {
                use std::os::unix::fs::FileExt;
                let n = end - offset;
                if buf.len() < n {
                    buf.resize(n, 0);
                }
                file.read_exact_at(&mut buf[..n], offset as u64)
                    .map_err(|source| RecordingError::Io {
                        path: path.to_path_buf(),
                        source,
                    })?;
                Ok(&buf[..n])
            }
        }
    }

    /// Fills `out` with the values of type `ty` from `offset`, `stride` bytes apart, as
    /// far as the source holds them; returns how many, and whether all are finite. A file
    /// is read in pieces of about a million values through `buf`.
    pub(crate) fn decode_at(
        &self,
        offset: usize,
        out: &mut [f64],
        ty: NumType,
        stride: usize,
        buf: &mut Vec<u8>,
    ) -> Result<(usize, bool)> {
        const PIECE: usize = 16 * BLOCK;
        let mut done = 0;
        let mut all_finite = true;
        while done < out.len() {
            let n = (out.len() - done).min(PIECE);
            let at = offset.saturating_add(done.saturating_mul(stride));
            let bytes = (n - 1).saturating_mul(stride).saturating_add(ty.size());
            let (got, finite) = decode(
                &mut out[done..done + n],
                self.read(at, bytes, buf)?,
                ty,
                stride,
            );
            done += got;
            all_finite &= finite;
            if got < n {
                break;
            }
        }
        Ok((done, all_finite))
    }
}

/// Runs a reader on the file at `path`: a regular file as [`Source::File`] (its size
/// bounds every allocation), anything else read whole into memory.
pub(crate) fn with_source<T>(
    path: &Path,
    read: impl FnOnce(&Source<'_>) -> Result<T>,
) -> Result<T> {
    let io = |source| RecordingError::Io {
        path: path.to_path_buf(),
        source,
    };
    #[cfg(unix)]
    {
        let file = std::fs::File::open(path).map_err(io)?;
        let meta = file.metadata().map_err(io)?;
        if let (true, Ok(len)) = (meta.is_file(), usize::try_from(meta.len())) {
            return read(&Source::File { file, len, path });
        }
    }
    let bytes = std::fs::read(path).map_err(io)?;
    read(&Source::Bytes(&bytes))
}

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
        if let Some(index) = (!s.finite).then(|| first_non_finite(&s.values)).flatten() {
            return Err(RecordingError::NonFiniteSample {
                path: path.to_path_buf(),
                format,
                channel: s.name.clone(),
                index,
                value: s.values[index],
            });
        }
    }
    if time.values.len() > 1 {
        harmonics::check_time_axis(&time.values, channels.max_gap_intervals).map_err(|source| {
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
    Ok(Recording::from_samples(
        path.to_path_buf(),
        time.values,
        gap.values,
        channels.gap_unit,
        angle_rad,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decode_contiguous_and_strided() {
        let bytes: Vec<u8> = [1.5f64, -2.0, 3.25]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let mut out = vec![0.0; 3];
        assert_eq!(decode(&mut out, &bytes, NumType::F64, 8), (3, true));
        assert_eq!(out, [1.5, -2.0, 3.25]);
        assert_eq!(decode(&mut out[..2], &bytes, NumType::F64, 16), (2, true));
        assert_eq!(out[..2], [1.5, 3.25]);
        // Only whole values in the bytes.
        assert_eq!(decode(&mut out, &bytes[..20], NumType::F64, 8).0, 2);
        assert_eq!(
            decode(&mut out[..2], &[0xff, 0x7f, 0x00, 0x80], NumType::I16, 2),
            (2, true)
        );
        assert_eq!(out[..2], [32767.0, -32768.0]);
        // Long outputs are decoded in blocks on several threads, in order.
        let n = 3 * BLOCK + 5;
        let bytes: Vec<u8> = (0..n).flat_map(|i| (i as f32).to_le_bytes()).collect();
        let mut out = vec![0.0; n];
        assert_eq!(decode(&mut out, &bytes, NumType::F32, 4), (n, true));
        assert!(out.iter().enumerate().all(|(i, &x)| x == i as f64));
        let mut out = vec![0.0; n / 2];
        assert_eq!(decode(&mut out, &bytes, NumType::F32, 8), (n / 2, true));
        assert!(out.iter().enumerate().all(|(i, &x)| x == (2 * i) as f64));
        // A NaN in any block is reported, and every block is still decoded.
        let mut bytes = bytes;
        bytes[4 * (2 * BLOCK + 3)..][..4].copy_from_slice(&f32::NAN.to_le_bytes());
        let mut out = vec![0.0; n];
        assert_eq!(decode(&mut out, &bytes, NumType::F32, 4), (n, false));
        assert_eq!(out[n - 1], (n - 1) as f64);
        assert!(out[2 * BLOCK + 3].is_nan());
    }

    #[test]
    fn non_finite_found_in_any_lane() {
        let mut v = vec![1.0; 21];
        assert_eq!(first_non_finite(&v), None);
        for i in [0, 7, 8, 20] {
            v[i] = f64::INFINITY;
            assert_eq!(first_non_finite(&v), Some(i));
            v[i] = 1.0;
        }
    }
}
