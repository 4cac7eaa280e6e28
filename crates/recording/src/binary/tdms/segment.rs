//! The walk over a TDMS file's segments: each lead-in checked (`TDSm`, version, offsets
//! inside the file), then its metadata and raw data handed on.

use crate::binary::channels::Cursor;
use crate::binary::source::Source;
use crate::error::{BinaryDefect, BinaryFormat, BinaryPart, RecordingError, Result};

use super::walk::{
    LEAD_IN, TOC_BIG_ENDIAN, TOC_INTERLEAVED, TOC_META_DATA, TOC_NEW_OBJ_LIST, TOC_RAW_DATA, Walk,
};

impl Walk<'_> {
    pub(super) fn walk(&mut self, source: &Source<'_>, buf: &mut Vec<u8>) -> Result<()> {
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
    pub(super) fn segment(
        &mut self,
        source: &Source<'_>,
        pos: usize,
        buf: &mut Vec<u8>,
    ) -> Result<usize> {
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
}
