//! DAQmx raw data in TDMS, as NI's DAQmx logging writes it: a channel's raw-data index
//! names its "scalers" (each a DAQmx data type at a byte offset in an interleaved row of a
//! raw buffer) and the raw buffers' widths; a segment's raw data is, per chunk, each
//! buffer's rows one after another. Read from NI's "TDMS File Format Internal Structure",
//! checked against npTDMS reading the same bytes (`fixtures/recordings/binary/make_daqmx.py`).

use super::channels::{Cursor, Place};
use super::decode::NumType;
use crate::error::{BinaryDefect, Result};

/// The raw-data index header of a channel with format-changing scalers.
pub(super) const FORMAT_CHANGING: u32 = 0x0000_1269;
/// The raw-data index header of a channel with digital-line scalers.
pub(super) const DIGITAL_LINE: u32 = 0x0000_126A;
/// The TDMS data type of a channel whose values are DAQmx raw data (only its scalers).
pub(super) const RAW_DATA_TYPE: u32 = 0xFFFF_FFFF;

/// One scaler of a DAQmx channel: where its values are in a raw buffer's rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Scaler {
    /// DAQmx data type code (0 u8, 1 i8, 2 u16, 3 i16, 4 u32, 5 i32, 6 u64, 7 i64, 8 f32,
    /// 9 f64).
    pub(super) ty: u32,
    /// The raw buffer holding it.
    pub(super) buffer: u32,
    /// Byte offset in the buffer's row (bit offset for a digital line).
    pub(super) offset: u32,
    /// Its scale id (the index of the scale that reads it).
    pub(super) scale_id: u32,
}

/// A DAQmx channel's raw-data index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct DaqmxIndex {
    /// The channel's TDMS data type ([`RAW_DATA_TYPE`] for raw scaler data).
    pub(super) data_type: u32,
    /// Values per chunk.
    pub(super) count: u64,
    /// Digital-line scalers (bits), not format-changing ones.
    pub(super) digital: bool,
    /// The scalers.
    pub(super) scalers: Vec<Scaler>,
    /// The raw buffers' row widths, bytes.
    pub(super) widths: Vec<u32>,
}

/// Reads the DAQmx part of a raw-data index after its header (`FORMAT_CHANGING` or
/// `DIGITAL_LINE`); `at` is the object's offset, for errors.
pub(super) fn read_index(
    c: &mut Cursor<'_>,
    header: u32,
    at: usize,
    place: Place<'_>,
) -> Result<DaqmxIndex> {
    let data_type = c.u32()?;
    let dim = c.u32()?;
    if dim != 1 {
        return Err(place.malformed(at, BinaryDefect::ArrayDimension { found: dim }));
    }
    let count = c.u64()?;
    let digital = header == DIGITAL_LINE;
    let n = c.u32()?;
    let mut scalers = Vec::new();
    for _ in 0..n {
        let ty = c.u32()?;
        let buffer = c.u32()?;
        let offset = c.u32()?;
        // The sample-format bitmap: four bytes, one for a digital line.
        if digital {
            c.take(1)?;
        } else {
            c.u32()?;
        }
        let scale_id = c.u32()?;
        scalers.push(Scaler {
            ty,
            buffer,
            offset,
            scale_id,
        });
    }
    let n = c.u32()?;
    let mut widths = Vec::new();
    for _ in 0..n {
        widths.push(c.u32()?);
    }
    Ok(DaqmxIndex {
        data_type,
        count,
        digital,
        scalers,
        widths,
    })
}

/// The sample type of a DAQmx data type code.
pub(super) fn num_type(code: u32) -> Option<NumType> {
    Some(match code {
        0 => NumType::U8,
        1 => NumType::I8,
        2 => NumType::U16,
        3 => NumType::I16,
        4 => NumType::U32,
        5 => NumType::I32,
        6 => NumType::U64,
        7 => NumType::I64,
        8 => NumType::F32,
        9 => NumType::F64,
        _ => return None,
    })
}

/// The raw buffers of a DAQmx segment: per buffer its rows per chunk, its row width and its
/// start in the chunk; and the chunk's bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Buffers {
    /// `(rows, width, start)` of each buffer.
    pub(super) buffers: Vec<(u64, u64, u64)>,
    /// Bytes per chunk.
    pub(super) chunk: u64,
}

/// The buffers of the channels of a segment (each `(values per chunk, index)`): every
/// channel must give the same widths; a buffer's rows are the most values any of its
/// channels has (as npTDMS reads them).
pub(super) fn buffers<'a>(
    channels: impl Iterator<Item = (u64, &'a DaqmxIndex)>,
    at: usize,
    place: Place<'_>,
) -> Result<Buffers> {
    let mut widths: Option<&[u32]> = None;
    let mut rows: Vec<u64> = Vec::new();
    for (count, d) in channels {
        match widths {
            None => {
                widths = Some(&d.widths);
                rows = vec![0; d.widths.len()];
            }
            Some(w) if w != d.widths.as_slice() => {
                return Err(place.malformed(at, BinaryDefect::DaqmxWidths));
            }
            Some(_) => {}
        }
        for s in &d.scalers {
            let b = s.buffer as usize;
            let Some(r) = rows.get_mut(b) else {
                return Err(place.malformed(
                    at,
                    BinaryDefect::DaqmxScaler {
                        buffer: s.buffer,
                        offset: s.offset,
                        width: 0,
                    },
                ));
            };
            *r = (*r).max(count);
        }
    }
    let mut chunk: u64 = 0;
    let mut buffers = Vec::new();
    for (&r, &w) in rows.iter().zip(widths.unwrap_or_default()) {
        buffers.push((r, u64::from(w), chunk));
        chunk = chunk.saturating_add(r.saturating_mul(u64::from(w)));
    }
    Ok(Buffers { buffers, chunk })
}
