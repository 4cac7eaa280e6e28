//! MATLAB MAT-files of level 5 (versions 5, 6 and 7), read from MathWorks' public
//! description ("MAT-File Format").
//!
//! A file is a 128-byte header (text, subsystem offset, version 0x0100, endian indicator
//! `IM`) and a sequence of data elements, each an 8-byte tag (type, byte count; or a
//! small element of at most 4 bytes packed into the tag) and its data padded to 8 bytes.
//! A variable is an `miMATRIX` element: array flags (class, complex), dimensions, name,
//! then for a numeric array its real part, for a struct its field names and one `miMATRIX`
//! per field. Version 7 compresses each variable into an `miCOMPRESSED` element (zlib,
//! inflated by `miniz_oxide`).
//!
//! Read: numeric vectors of any class (double, single, 8- to 64-bit integers; stored in any
//! numeric type), at top level or as fields of 1×1 structs (named by a dotted path,
//! `rec.gap_um`, or with [`BinaryChannels::group`]). Refused with a typed error: v7.3
//! (HDF5) files ([`RecordingError::MatV73`]), big-endian files, complex, sparse, cell, char
//! or other classes and non-vector arrays when asked for.

use std::path::Path;

use super::channels::{BinaryChannels, ChannelInfo, Cursor, Place, Series, assemble};
use super::decode::{NumType, decode};
use super::source::{Source, with_source};
use crate::error::{BinaryDefect, BinaryFormat, BinaryPart, RecordingError, Result, Unsupported};
use crate::lab::probe::Recording;

const HEADER: usize = 128;
const MI_INT8: u32 = 1;
const MI_INT32: u32 = 5;
const MI_UINT32: u32 = 6;
const MI_MATRIX: u32 = 14;
const MI_COMPRESSED: u32 = 15;
const MX_STRUCT: u8 = 2;
const COMPLEX_FLAG: u32 = 0x0800;
const MAX_DEPTH: usize = 16;
/// DEFLATE's largest expansion ratio: an inflated element is at most this many times its
/// compressed size.
const MAX_INFLATE_RATIO: usize = 1032;

/// Reads the variables of a probe recording from a MAT-file (see [`parse_mat`]), one
/// top-level element at a time through a reused buffer.
pub fn load_mat(path: &Path, variables: &BinaryChannels) -> Result<Recording> {
    with_source(path, |source| read(source, path, variables))
}

/// Parses the variables of a probe recording from a MAT-file held in memory; `path` names
/// it in errors. Never panics; an error names the file and the byte offset or variable.
pub fn parse_mat(bytes: &[u8], path: &Path, variables: &BinaryChannels) -> Result<Recording> {
    read(&Source::Bytes(bytes), path, variables)
}

/// The variables of a probe recording from a MAT file read from `source`.
pub(crate) fn read(
    source: &Source<'_>,
    path: &Path,
    variables: &BinaryChannels,
) -> Result<Recording> {
    let place = Place {
        path,
        format: BinaryFormat::Mat,
    };
    let mut buf = Vec::new();
    // The header, and where a v7.3 file has its HDF5 signature.
    header(source.read(0, 520, &mut buf)?, place)?;
    let full = |name: &str| match &variables.group {
        Some(g) => format!("{g}.{name}"),
        None => name.to_string(),
    };
    let wanted: Vec<String> = [
        variables.time.as_deref(),
        Some(variables.gap.as_str()),
        variables.angle.as_deref(),
    ]
    .into_iter()
    .map(|n| n.map(full).unwrap_or_default())
    .collect();
    // The values of each role, and whether they are all finite.
    let mut found: [Option<(Vec<f64>, bool)>; 3] = [None, None, None];
    let mut available = Vec::new();
    let mut visit = |name: &str, item: Item<'_>| -> Result<()> {
        available.push(name.to_string());
        for (role, want) in wanted.iter().enumerate() {
            if want.as_str() != name || found[role].is_some() {
                continue;
            }
            let values = match &item {
                Item::Numeric { ty, data, count } => {
                    // `count` values are in `data`, checked against its length.
                    let mut v = vec![0.0; *count];
                    let (_, finite) = decode(&mut v, data, *ty, ty.size());
                    (v, finite)
                }
                Item::Unsupported(what) => return Err(place.unsupported(name, what.clone())),
            };
            found[role] = Some(values);
        }
        Ok(())
    };
    elements(source, place, &mut buf, &mut visit)?;
    let mut series = |role: usize| -> Option<Series> {
        found[role].take().map(|(values, finite)| Series {
            name: wanted[role].clone(),
            values,
            finite,
        })
    };
    let missing = |name: &str| place.missing(&full(name), available.clone());
    let (time, gap, angle) = (series(0), series(1), series(2));
    let gap = gap.ok_or_else(|| missing(&variables.gap))?;
    let time = match (&variables.time, time) {
        (_, Some(t)) => t,
        (Some(name), None) => return Err(missing(name)),
        (None, None) => {
            return Err(RecordingError::NoTimeBase {
                path: place.path(),
                channel: variables.gap.clone(),
            });
        }
    };
    let angle = angle.filter(|_| variables.angle.is_some());
    assemble(path, BinaryFormat::Mat, variables, time, gap, angle)
}

/// Gives every variable of the file after its header (inflating compressed ones) to
/// `visit`, with its dotted path.
fn elements<'a>(
    source: &Source<'_>,
    place: Place<'a>,
    buf: &mut Vec<u8>,
    visit: &mut dyn FnMut(&str, Item<'_>) -> Result<()>,
) -> Result<()> {
    let mut pos = HEADER;
    let len = source.len();
    while pos < len {
        let mut tag = Cursor::based(
            source.read(pos, 8, buf)?,
            pos,
            BinaryPart::ElementTag,
            place,
        );
        let ty = tag.u32()?;
        let n = tag.u32()?;
        if ty >> 16 != 0 {
            // A small element at top level holds no variable.
            pos += 8;
            continue;
        }
        let start = pos + 8;
        let end = usize::try_from(n)
            .ok()
            .and_then(|n| start.checked_add(n))
            .filter(|&e| e <= len)
            .ok_or_else(|| place.truncated(start, BinaryPart::Element, u64::from(n)))?;
        let next = if ty == MI_COMPRESSED {
            end
        } else {
            end.saturating_add((8 - end % 8) % 8).min(len)
        };
        let data = match ty {
            MI_MATRIX | MI_COMPRESSED => source.read(start, end - start, buf)?,
            _ => &[],
        };
        match ty {
            MI_MATRIX => matrix(data, pos + 8, "", 0, place, visit)?,
            MI_COMPRESSED => {
                let limit = data
                    .len()
                    .saturating_mul(MAX_INFLATE_RATIO)
                    .saturating_add(64);
                let inflated = miniz_oxide::inflate::decompress_to_vec_zlib_with_limit(data, limit)
                    .map_err(|_| place.malformed(pos, BinaryDefect::Inflate))?;
                let inner = place;
                let mut at = 0;
                while at < inflated.len() {
                    let parsed = element(&inflated, at, inner).and_then(|(ty, data, next)| {
                        if ty == MI_MATRIX {
                            matrix(data, at + 8, "", 0, inner, visit)?;
                        }
                        Ok(next)
                    });
                    at = parsed.map_err(|e| within_compressed(e, pos))?;
                }
            }
            _ => {}
        }
        pos = next;
    }
    Ok(())
}

/// The numeric variables of a MAT-file held in memory (top-level ones and the fields of
/// 1×1 structs, `group` the struct), with their lengths (`None`: a class or shape the
/// reader does not convert); for `init`. A MAT-file states no units. `path` names the file
/// in errors.
///
/// # Errors
/// As [`parse_mat`], for a file whose structure cannot be read.
pub fn list_mat(bytes: &[u8], path: &Path) -> Result<Vec<ChannelInfo>> {
    let place = Place {
        path,
        format: BinaryFormat::Mat,
    };
    let source = Source::Bytes(bytes);
    let mut buf = Vec::new();
    header(source.read(0, 520, &mut buf)?, place)?;
    let mut found = Vec::new();
    elements(&source, place, &mut buf, &mut |name, item| {
        let (group, name) = match name.split_once('.') {
            Some((g, n)) => (Some(g.to_owned()), n.to_owned()),
            None => (None, name.to_owned()),
        };
        found.push(ChannelInfo {
            group,
            name,
            unit: None,
            waveform: false,
            samples: match item {
                Item::Numeric { count, .. } => Some(count),
                Item::Unsupported(_) => None,
            },
        });
        Ok(())
    })?;
    Ok(found)
}

/// The values of one numeric variable of a MAT-file held in memory (a field of the struct
/// `group` when given); for `init`.
///
/// # Errors
/// As [`parse_mat`]; [`RecordingError::MissingChannel`] when the file has no such variable.
pub fn mat_variable(
    bytes: &[u8],
    path: &Path,
    group: Option<&str>,
    name: &str,
) -> Result<Vec<f64>> {
    let place = Place {
        path,
        format: BinaryFormat::Mat,
    };
    let source = Source::Bytes(bytes);
    let mut buf = Vec::new();
    header(source.read(0, 520, &mut buf)?, place)?;
    let want = match group {
        Some(g) => format!("{g}.{name}"),
        None => name.to_owned(),
    };
    let mut found = None;
    let mut available = Vec::new();
    elements(&source, place, &mut buf, &mut |n, item| {
        available.push(n.to_owned());
        if n == want && found.is_none() {
            found = Some(match item {
                Item::Numeric { ty, data, count } => {
                    let mut v = vec![0.0; count];
                    decode(&mut v, data, ty, ty.size());
                    v
                }
                Item::Unsupported(what) => return Err(place.unsupported(n, what)),
            });
        }
        Ok(())
    })?;
    found.ok_or_else(|| place.missing(&want, available))
}

/// Checks the 128-byte header: level 5, little-endian; v7.3 (HDF5) refused by name.
fn header(bytes: &[u8], place: Place<'_>) -> Result<()> {
    const HDF5: &[u8] = b"\x89HDF\r\n\x1a\n";
    if bytes.starts_with(HDF5) || bytes.get(512..520) == Some(HDF5) {
        return Err(RecordingError::MatV73 { path: place.path() });
    }
    let Some(h) = bytes.get(..HEADER) else {
        if bytes.starts_with(b"MATLAB") || b"MATLAB".starts_with(bytes) {
            return Err(place.truncated(0, BinaryPart::Header, HEADER as u64));
        }
        return Err(RecordingError::BadMagic {
            path: place.path(),
            format: BinaryFormat::Mat,
            offset: 0,
        });
    };
    let version = u16::from_le_bytes([h[124], h[125]]);
    if h.starts_with(b"MATLAB 7.3") || version == 0x0200 {
        return Err(RecordingError::MatV73 { path: place.path() });
    }
    match &h[126..128] {
        b"IM" => {}
        b"MI" => return Err(place.malformed(126, BinaryDefect::MatEndian)),
        _ => {
            return Err(RecordingError::BadMagic {
                path: place.path(),
                format: BinaryFormat::Mat,
                offset: 126,
            });
        }
    }
    if version != 0x0100 {
        return Err(place.malformed(124, BinaryDefect::MatVersion { found: version }));
    }
    Ok(())
}

/// The data element at `pos`: its type, its data, and the position of the next element
/// (after the padding to 8 bytes, which a compressed element and the last one may lack).
fn element<'a>(bytes: &'a [u8], pos: usize, place: Place<'a>) -> Result<(u32, &'a [u8], usize)> {
    let mut c = Cursor::new(bytes, pos, BinaryPart::ElementTag, place);
    let first = c.u32()?;
    if first >> 16 != 0 {
        // Small data element: type and length in the first word, data in the second.
        let n = first >> 16;
        if n > 4 {
            return Err(place.malformed(pos, BinaryDefect::SmallElement { found: n }));
        }
        let data = c.take(4)?;
        return Ok((first & 0xFFFF, &data[..n as usize], c.pos()));
    }
    let n = c.u32()?;
    let mut data = Cursor::new(bytes, c.pos(), BinaryPart::Element, place);
    let d = data.take(u64::from(n))?;
    let mut next = data.pos();
    if first != MI_COMPRESSED {
        next = next
            .saturating_add((8 - n as usize % 8) % 8)
            .min(bytes.len());
    }
    Ok((first, d, next))
}

/// What a variable holds, for the visitor.
enum Item<'a> {
    /// `count` values of type `ty`, contiguous in `data`.
    Numeric {
        ty: NumType,
        data: &'a [u8],
        count: usize,
    },
    /// Something the reader does not convert.
    Unsupported(Unsupported),
}

/// Parses the content of an `miMATRIX` element starting at `pos` (the offset of `data` in
/// its buffer, for errors) and gives each numeric array (dotted path under `prefix`) or
/// unsupported variable to `visit`.
fn matrix<'a>(
    data: &'a [u8],
    pos: usize,
    prefix: &str,
    depth: usize,
    place: Place<'a>,
    visit: &mut dyn FnMut(&str, Item<'_>) -> Result<()>,
) -> Result<()> {
    if depth > MAX_DEPTH {
        return Err(place.malformed(pos, BinaryDefect::NestingTooDeep));
    }
    // Sub-elements are at offsets within `data`; errors give offsets in the buffer.
    let shift = |e: RecordingError| shift_offset(e, pos);
    let mut at = 0;
    let next = |at: &mut usize, expected: &'static str, want: &[u32]| -> Result<&'a [u8]> {
        let (ty, d, n) = element(data, *at, place).map_err(shift)?;
        if !want.contains(&ty) {
            return Err(place.malformed(
                pos + *at,
                BinaryDefect::ElementType {
                    expected,
                    found: ty,
                },
            ));
        }
        *at = n;
        Ok(d)
    };
    let flags = next(&mut at, "miUINT32 array flags", &[MI_UINT32])?;
    let flags = u32::from_le_bytes(
        flags
            .get(..4)
            .and_then(|f| f.try_into().ok())
            .unwrap_or([0; 4]),
    );
    let class = (flags & 0xFF) as u8;
    let dims: Vec<usize> = next(&mut at, "miINT32 dimensions", &[MI_INT32])?
        .chunks_exact(4)
        .map(|d| usize::try_from(i32::from_le_bytes([d[0], d[1], d[2], d[3]])).unwrap_or(0))
        .collect();
    let name =
        String::from_utf8_lossy(next(&mut at, "miINT8 array name", &[MI_INT8])?).into_owned();
    // A struct's field is named by the struct's path and its field name (its own is empty).
    let full = match (prefix.is_empty(), name.is_empty()) {
        (true, _) => name,
        (false, true) => prefix.to_string(),
        (false, false) => format!("{prefix}.{name}"),
    };
    let numel = dims.iter().try_fold(1usize, |a, &d| a.checked_mul(d));
    if class == MX_STRUCT {
        if numel != Some(1) {
            return visit(&full, Item::Unsupported(Unsupported::NotVector { dims }));
        }
        let len = next(&mut at, "miINT32 field-name length", &[MI_INT32])?;
        let len = len.get(..4).map_or(0, |l| {
            i32::from_le_bytes([l[0], l[1], l[2], l[3]]).max(0) as usize
        });
        if len == 0 {
            return Err(place.malformed(pos + at, BinaryDefect::FieldNameLength));
        }
        let names = next(&mut at, "miINT8 field names", &[MI_INT8])?;
        for field in names.chunks(len) {
            let end = field.iter().position(|&b| b == 0).unwrap_or(field.len());
            let field_name = String::from_utf8_lossy(&field[..end]).into_owned();
            let start = at;
            let d = next(&mut at, "miMATRIX field", &[MI_MATRIX])?;
            let path = format!("{full}.{field_name}");
            matrix(d, pos + start + 8, &path, depth + 1, place, visit)?;
        }
        return Ok(());
    }
    if flags & COMPLEX_FLAG != 0 {
        return visit(&full, Item::Unsupported(Unsupported::Complex));
    }
    if !(6..=15).contains(&class) {
        return visit(&full, Item::Unsupported(Unsupported::MatClass(class)));
    }
    let real_at = pos + at;
    let (ty_code, real, _) = element(data, at, place).map_err(shift)?;
    let Some(ty) = mat_type(ty_code) else {
        return visit(&full, Item::Unsupported(Unsupported::MatType(ty_code)));
    };
    let count = real.len() / ty.size();
    if numel != Some(count) || real.len() % ty.size() != 0 {
        return Err(place.malformed(
            real_at,
            BinaryDefect::ArraySize {
                expected: numel.map_or(u64::MAX, |n| n as u64),
                bytes: real.len() as u64,
            },
        ));
    }
    if dims.iter().filter(|&&d| d > 1).count() > 1 {
        return visit(&full, Item::Unsupported(Unsupported::NotVector { dims }));
    }
    visit(
        &full,
        Item::Numeric {
            ty,
            data: real,
            count,
        },
    )
}

/// The sample type of a MAT numeric data type.
fn mat_type(code: u32) -> Option<NumType> {
    Some(match code {
        1 => NumType::I8,
        2 => NumType::U8,
        3 => NumType::I16,
        4 => NumType::U16,
        5 => NumType::I32,
        6 => NumType::U32,
        7 => NumType::F32,
        9 => NumType::F64,
        12 => NumType::I64,
        13 => NumType::U64,
        _ => return None,
    })
}

/// A structural error found at an offset within `data` moved to the buffer's offset.
fn shift_offset(e: RecordingError, by: usize) -> RecordingError {
    match e {
        RecordingError::Truncated {
            path,
            format,
            offset,
            what,
            needed,
        } => RecordingError::Truncated {
            path,
            format,
            offset: offset + by as u64,
            what,
            needed,
        },
        RecordingError::Malformed {
            path,
            format,
            offset,
            defect,
        } => RecordingError::Malformed {
            path,
            format,
            offset: offset + by as u64,
            defect,
        },
        other => other,
    }
}

/// A structural error inside the inflated data of the compressed element at `pos`: named
/// at the element, with the defect and its offset inside.
fn within_compressed(e: RecordingError, pos: usize) -> RecordingError {
    match e {
        RecordingError::Truncated {
            path,
            format,
            offset,
            what,
            needed,
        } => RecordingError::Malformed {
            path,
            format,
            offset: pos as u64,
            defect: BinaryDefect::InCompressed {
                offset,
                defect: Box::new(BinaryDefect::Ends { what, needed }),
            },
        },
        RecordingError::Malformed {
            path,
            format,
            offset,
            defect,
        } => RecordingError::Malformed {
            path,
            format,
            offset: pos as u64,
            defect: BinaryDefect::InCompressed {
                offset,
                defect: Box::new(defect),
            },
        },
        other => other,
    }
}
