//! A TDMS segment's raw data: where each channel's values lie (contiguous, interleaved or
//! in DAQmx raw buffers), and the values read from there and scaled.

use crate::binary::daqmx;
use crate::binary::scaling::{Leaf, Scaling};
use crate::binary::source::Source;
use crate::error::{BinaryDefect, Result, Unsupported};

use super::walk::{Span, TYPE_STRING, Walk, num_type, push_span, series, value_size};
use crate::binary::channels::Series;

impl Walk<'_> {
    pub(super) fn raw_data(
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
    pub(super) fn daqmx_raw_data(
        &mut self,
        raw_start: usize,
        end: usize,
        pos: usize,
    ) -> Result<()> {
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
    pub(super) fn values(
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
}
