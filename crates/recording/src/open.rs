//! Opening a recording or table: a regular file only, checked on the open handle, never
//! blocking on a FIFO. The rule has one home, [`edge_io::open_regular`]; this module only says
//! its refusal in the recording crate's words ([`RecordingError`]), and every reader of the
//! crate opens through [`open_regular`].

use std::fs::{File, Metadata};
use std::path::Path;

use crate::error::{RecordingError, Result};

/// Opens `path` for reading if it names a regular file (links followed), with its metadata;
/// anything else is [`RecordingError::NotAFile`] naming what it is, refused unread (see
/// [`edge_io::open_regular`]: `O_NONBLOCK`, the check on the handle's own metadata).
pub(crate) fn open_regular(path: &Path) -> Result<(File, Metadata)> {
    edge_io::open_regular(path).map_err(|e| match e {
        edge_io::EdgeIoError::NotAFile { path, kind } => RecordingError::NotAFile { path, kind },
        edge_io::EdgeIoError::Read { path, source } => RecordingError::Io { path, source },
        // open_regular refuses only with the two above; any other is still an I/O failure
        other => RecordingError::Io {
            path: path.to_owned(),
            source: std::io::Error::other(other.to_string()),
        },
    })
}
