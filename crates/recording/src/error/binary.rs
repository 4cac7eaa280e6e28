//! The details of a binary file's error: which format, which structure, what is wrong,
//! what is not converted (the parts of [`RecordingError`](super::RecordingError)'s binary
//! variants).

use std::fmt;

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
    /// DAQmx raw data and plain raw data in one segment.
    DaqmxRaw,
    /// DAQmx channels of one segment with different raw-buffer widths.
    DaqmxWidths,
    /// A DAQmx scaler outside its raw buffer's rows.
    DaqmxScaler {
        /// Its raw buffer.
        buffer: u32,
        /// Its byte offset in the buffer's row.
        offset: u32,
        /// The row's width, bytes (0: no such buffer).
        width: u32,
    },
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
            Self::DaqmxRaw => f.write_str("DAQmx raw data mixed with plain raw data in a segment"),
            Self::DaqmxWidths => {
                f.write_str("DAQmx channels of a segment with different raw-buffer widths")
            }
            Self::DaqmxScaler {
                buffer,
                offset,
                width,
            } => write!(
                f,
                "DAQmx scaler at byte {offset} of raw buffer {buffer}, whose rows are {width} \
                 bytes wide"
            ),
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
    /// A DAQmx scaler data type (code) that is not numeric.
    DaqmxType(u32),
    /// DAQmx digital-line (bit) data.
    DigitalLine,
    /// A TDMS channel scaling (`NI_Scaling` properties) that is not read: a scale type other
    /// than linear, polynomial or a DAQmx scaler, or an incomplete or looping chain.
    TdmsScaling(String),
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
            Self::DaqmxType(code) => write!(f, "DAQmx data type {code}"),
            Self::DigitalLine => f.write_str("DAQmx digital-line data (a probe gap is analog)"),
            Self::TdmsScaling(what) => write!(
                f,
                "NI_Scaling: {what} (linear and polynomial scales are read; export the channel \
                 scaled, or as plain TDMS or CSV in the gap's unit)"
            ),
        }
    }
}
