//! Where a binary reader reads from: bytes in memory or a regular file read with positioned
//! reads. The one file of the binary readers that touches the file system.

use std::path::Path;

use super::decode::{BLOCK, NumType, decode};
use crate::error::{RecordingError, Result};

/// The whole file at `path` (a binary recording whose digest is taken, then parsed from
/// memory).
pub(crate) fn read_whole(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|source| RecordingError::Io {
        path: path.to_path_buf(),
        source,
    })
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
