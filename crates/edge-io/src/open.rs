//! Opening a file that must be a regular file, without blocking on what is not one.

use std::fs::{File, Metadata};
use std::path::Path;

use crate::error::{EdgeIoError, Result};

/// Opens `path` for reading if it names a regular file (links followed), and returns it with
/// its metadata; anything else is [`EdgeIoError::NotAFile`] naming what it is.
///
/// The check is made on the open handle (`fstat`), not on the path beforehand, so a path
/// swapped for a FIFO between a check and the open cannot make the reader block. On Unix
/// the file is opened with `O_NONBLOCK` (and `O_NOCTTY`): opening a FIFO for reading then
/// returns at once instead of waiting for a writer, and the FIFO is refused unread. On a
/// regular file the flag changes nothing.
///
/// # Errors
/// [`EdgeIoError::Read`] when the path cannot be opened; [`EdgeIoError::NotAFile`] for a
/// folder, a FIFO, a device or a socket.
pub fn open_regular(path: &Path) -> Result<(File, Metadata)> {
    let read_error = |source| EdgeIoError::Read {
        path: path.to_owned(),
        source,
    };
    let not_a_file = |metadata: &Metadata| EdgeIoError::NotAFile {
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
        Err(e) => {
            // A socket cannot be opened at all (ENXIO): say what it is.
            return Err(match std::fs::metadata(path) {
                Ok(m) if !m.is_file() => not_a_file(&m),
                _ => read_error(e),
            });
        }
    };
    let metadata = file.metadata().map_err(read_error)?;
    if !metadata.is_file() {
        return Err(not_a_file(&metadata));
    }
    Ok((file, metadata))
}

/// What a path that is not a regular file names, in words ("a named pipe (FIFO)").
#[must_use]
pub fn kind_of(metadata: &Metadata) -> &'static str {
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
    if t.is_file() {
        "a regular file"
    } else {
        "not a regular file"
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn devices_and_folders_are_refused_by_name() {
        for (path, kind) in [
            ("/dev/zero", "a character device"),
            ("/dev/null", "a character device"),
            ("/", "a folder"),
        ] {
            match open_regular(Path::new(path)) {
                Err(EdgeIoError::NotAFile { path: p, kind: k }) => {
                    assert_eq!((p.as_path(), k), (Path::new(path), kind));
                }
                other => panic!("{path}: {other:?}"),
            }
        }
    }
}
