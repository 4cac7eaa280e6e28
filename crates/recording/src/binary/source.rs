//! Where a binary reader reads from: bytes in memory or a regular file read with positioned
//! reads. The one file of the binary readers that touches the file system.

use std::path::Path;

use super::decode::{BLOCK, NumType, decode};
use crate::digest::{FileDigest, Hasher};
use crate::error::{RecordingError, Result};

/// Where a reader reads from: bytes in memory, or a regular file read piece by piece with
/// positioned reads (only the structures and the samples asked for are read, through a
/// reused buffer, so no copy of the whole file is made). Every read is within `len`.
pub(crate) enum Source<'a> {
    /// Bytes in memory.
    Bytes(&'a [u8]),
    /// A regular file of `len` bytes.
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
            Self::File { file, path, .. } => {
                let n = end - offset;
                if buf.len() < n {
                    buf.resize(n, 0);
                }
                read_exact_at(file, &mut buf[..n], offset as u64).map_err(|source| {
                    RecordingError::Io {
                        path: path.to_path_buf(),
                        source,
                    }
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

impl Source<'_> {
    /// The size and SHA-256 of the whole source, a file read piece by piece (a megabyte at a
    /// time) from the handle the reader used.
    pub(crate) fn digest(&self) -> Result<FileDigest> {
        const PIECE: usize = 1 << 20;
        let mut hasher = Hasher::default();
        let mut buf = Vec::new();
        let mut at = 0;
        while at < self.len() {
            let n = PIECE.min(self.len() - at);
            hasher.update(self.read(at, n, &mut buf)?);
            at += n;
        }
        Ok(hasher.finish())
    }
}

/// Positioned read of exactly `buf.len()` bytes at `offset`.
fn read_exact_at(file: &std::fs::File, buf: &mut [u8], offset: u64) -> std::io::Result<()> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileExt as _;
        file.read_exact_at(buf, offset)
    }
    #[cfg(not(unix))]
    {
        use std::io::{Read as _, Seek as _, SeekFrom};
        let mut file = file;
        file.seek(SeekFrom::Start(offset))?;
        file.read_exact(buf)
    }
}

/// Runs a reader on the file at `path` as [`Source::File`]: a regular file only (anything
/// else is [`RecordingError::NotAFile`], refused without blocking), read by positioned reads;
/// its size, taken from the open handle, bounds every read and allocation.
pub(crate) fn with_source<T>(
    path: &Path,
    read: impl FnOnce(&Source<'_>) -> Result<T>,
) -> Result<T> {
    let (file, meta) = crate::open::open_regular(path)?;
    let len = usize::try_from(meta.len()).map_err(|_| RecordingError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            "larger than this platform's address space",
        ),
    })?;
    read(&Source::File { file, len, path })
}
