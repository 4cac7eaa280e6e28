//! Opening a recording or table: a regular file only, checked on the open handle, never
//! blocking on a FIFO. The same rule as `edge_io::open_regular` (this crate cannot depend on
//! `edge-io`, which carries RON); every reader of the crate opens through [`open_regular`].

use std::fs::{File, Metadata};
use std::path::Path;

use crate::error::{RecordingError, Result};

/// Opens `path` for reading if it names a regular file (links followed), with its metadata;
/// anything else is [`RecordingError::NotAFile`] naming what it is, refused unread.
///
/// On Unix the file is opened with `O_NONBLOCK` and `O_NOCTTY`, so opening a FIFO returns at
/// once (a blocking open waits for a writer, forever if there is none) and the check of the
/// handle's own metadata (`fstat`) refuses it: no window between a check and the open. On a
/// regular file the flags change nothing.
pub(crate) fn open_regular(path: &Path) -> Result<(File, Metadata)> {
    let io = |source| RecordingError::Io {
        path: path.to_owned(),
        source,
    };
    let not_a_file = |metadata: &Metadata| RecordingError::NotAFile {
        path: path.to_owned(),
        kind: kind_of(metadata),
    };
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt as _;
        options.custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY);
    }
    let file = match options.open(path) {
        Ok(file) => file,
        // A socket cannot be opened at all (ENXIO): say what it is.
        Err(e) => {
            return Err(match std::fs::metadata(path) {
                Ok(m) if !m.is_file() => not_a_file(&m),
                _ => io(e),
            });
        }
    };
    let metadata = file.metadata().map_err(io)?;
    if !metadata.is_file() {
        return Err(not_a_file(&metadata));
    }
    Ok((file, metadata))
}

/// What a path that is not a regular file names, in words.
fn kind_of(metadata: &Metadata) -> &'static str {
    let t = metadata.file_type();
    if t.is_dir() {
        return "a folder";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
        if t.is_fifo() {
            return "a named pipe (FIFO)";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "not a regular file"
}
