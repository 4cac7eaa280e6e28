//! Streaming a file through one reused buffer into a table parser.

use std::io::Read as _;
use std::path::Path;

use super::lines::{BOM, lone_cr_line_ends};
use crate::digest::Hasher;
use crate::error::{RecordingError, Result};

/// Bytes read from a file at a time.
pub(crate) const CHUNK_BYTES: usize = 1 << 20;

/// Longest line accepted, bytes (16 MiB): a file without a line end within it is refused
/// rather than read whole.
pub(crate) const MAX_LINE_BYTES: usize = 16 << 20;

/// A parser fed with whole lines (the table parser).
pub(crate) trait LineSink {
    /// Parses whole lines (the text ends at a line end, or is the file's last piece).
    fn feed(&mut self, text: &[u8]) -> Result<()>;
    /// Lines fed so far.
    fn lines_fed(&self) -> usize;
    /// The next text fed starts at this byte of the file (after a byte-order mark); called
    /// before each feed, for a reader that comes back to a place later.
    fn at_offset(&mut self, _offset: u64) {}
    /// Whether the parser has read all it wants (the rest of the file is not read).
    fn done(&self) -> bool {
        false
    }
}

/// Where to start streaming a file: its beginning, or a place recorded by
/// [`LineSink::at_offset`] earlier (with the line ends then found).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Resume {
    /// Byte of the file at which a line starts.
    pub(crate) offset: u64,
    /// Whether line ends are lone CRs (`None`: decide from the text, at the beginning).
    pub(crate) lone_cr: Option<bool>,
}

/// Feeds the file's whole lines to `parser` (a regular file only: anything else is
/// [`RecordingError::NotAFile`], refused without blocking), a chunk of about a megabyte at a time (a
/// partial last line waits for the next read). The buffer grows beyond a chunk only while
/// one line is longer than that, and never beyond [`MAX_LINE_BYTES`] + 1 bytes: a longer
/// line is [`RecordingError::LineTooLong`]. Every byte read, as read (a byte-order mark and
/// line ends included), goes to `hasher` when one is given.
pub(crate) fn stream_file(
    path: &Path,
    parser: &mut impl LineSink,
    hasher: Option<&mut Hasher>,
) -> Result<()> {
    stream_file_from(path, Resume::default(), parser, hasher).map(|_| ())
}

/// [`stream_file`] from a place in the file (a line's start, as [`LineSink::at_offset`]
/// gave it), stopping early when the parser is [`LineSink::done`]. Returns whether line
/// ends are lone CRs.
pub(crate) fn stream_file_from(
    path: &Path,
    resume: Resume,
    parser: &mut impl LineSink,
    mut hasher: Option<&mut Hasher>,
) -> Result<Option<bool>> {
    use std::io::{Seek as _, SeekFrom};
    let io = |source| RecordingError::Io {
        path: path.to_owned(),
        source,
    };
    let (mut file, _) = crate::open::open_regular(path)?;
    if resume.offset > 0 {
        file.seek(SeekFrom::Start(resume.offset)).map_err(io)?;
    }
    let mut buf: Vec<u8> = Vec::with_capacity(CHUNK_BYTES + 64 * 1024);
    let mut eof = false;
    let mut start = resume.offset == 0;
    // The file's byte at the buffer's start.
    let mut offset = resume.offset;
    // Whether line ends are lone CRs (decided at the first line end), and how much of the
    // buffer is known to hold no line end (so that a long line is scanned once).
    let mut lone_cr = resume.lone_cr;
    let mut scanned: usize = 0;
    while !eof && !parser.done() {
        // Top the buffer up to a chunk, or double it while one line is longer than that.
        let target = if scanned > 0 {
            (2 * buf.len()).clamp(CHUNK_BYTES, MAX_LINE_BYTES + 1)
        } else {
            CHUNK_BYTES
        };
        while buf.len() < target {
            let old = buf.len();
            buf.resize(target, 0);
            let got = file.read(&mut buf[old..]).map_err(io)?;
            buf.truncate(old + got);
            if let Some(h) = hasher.as_deref_mut() {
                h.update(&buf[old..]);
            }
            if got == 0 {
                eof = true;
                break;
            }
        }
        if start {
            if buf.starts_with(BOM) {
                buf.drain(..BOM.len());
                offset += BOM.len() as u64;
            }
            start = false;
        }
        if lone_cr.is_none() {
            lone_cr = lone_cr_line_ends(&buf, eof);
        }
        // A CR at the end of the part already scanned may just have been found lone.
        let from = scanned.saturating_sub(1);
        if lone_cr == Some(true) {
            for b in &mut buf[from..] {
                if *b == b'\r' {
                    *b = b'\n';
                }
            }
        }
        let last_end = buf[from..]
            .iter()
            .rposition(|&b| b == b'\n')
            .map(|i| from + i + 1);
        if last_end.is_none() && buf.len() > MAX_LINE_BYTES {
            return Err(RecordingError::LineTooLong {
                path: path.to_owned(),
                line: parser.lines_fed() + 1,
                max_bytes: MAX_LINE_BYTES,
            });
        }
        let complete = match (eof, last_end) {
            (true, _) => buf.len(),
            (false, Some(end)) => end,
            (false, None) => {
                scanned = buf.len();
                continue;
            }
        };
        parser.at_offset(offset);
        parser.feed(&buf[..complete])?;
        buf.drain(..complete);
        offset += complete as u64;
        scanned = 0;
    }
    Ok(lone_cr)
}
