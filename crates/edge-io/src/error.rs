//! The crate's error type.

use std::path::PathBuf;

/// Errors of reading capped text and of writing an output set.
///
/// Every variant names the file or directory it concerns.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum EdgeIoError {
    /// The file could not be opened or read.
    #[error("cannot read {}", path.display())]
    Read {
        /// The file concerned.
        path: PathBuf,
        /// The underlying I/O error.
        source: std::io::Error,
    },
    /// The file is larger than the limit for its kind.
    #[error(
        "{}: {}, above the limit of {limit_bytes} bytes ({}) for this kind of file",
        path.display(),
        size_text(*size_bytes, *limit_bytes),
        binary_size(*limit_bytes)
    )]
    TooLarge {
        /// The file concerned.
        path: PathBuf,
        /// The largest size accepted, bytes.
        limit_bytes: u64,
        /// The file's size, when its metadata tells it (`None` for a pipe or a device, which
        /// gave more than `limit_bytes` bytes).
        size_bytes: Option<u64>,
    },
    /// The file is not UTF-8 text.
    #[error(
        "{}:{line}:{column}: not UTF-8 text (invalid byte at offset {offset})",
        path.display()
    )]
    InvalidUtf8 {
        /// The file concerned.
        path: PathBuf,
        /// 1-based line of the first invalid byte.
        line: usize,
        /// 1-based column (in characters) of the first invalid byte.
        column: usize,
        /// Byte offset of the first invalid byte from the start of the file.
        offset: u64,
    },
    /// A file or directory of an output set could not be created, written or synced.
    #[error("cannot write {}", path.display())]
    Write {
        /// The file or directory concerned.
        path: PathBuf,
        /// The underlying I/O error.
        source: std::io::Error,
    },
    /// The path names something other than a regular file (a folder, a FIFO, a device, a
    /// socket): reading it could block or never end, so it is refused unread.
    #[error(
        "{} is {kind}, not a regular file: name a file on disk (a pipe or a device could block \
         or never end, so it is not read)",
        path.display()
    )]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it names, in words ("a named pipe (FIFO)").
        kind: &'static str,
    },
    /// The new outputs could not be moved into place; the previous ones are still there.
    #[error("cannot move the new outputs into {}", target.display())]
    Replace {
        /// The output directory.
        target: PathBuf,
        /// The underlying I/O error.
        source: std::io::Error,
    },
    /// The output directory holds entries the tool did not write (or that changed since it
    /// wrote them); replacing it would delete them.
    #[error(
        "{} holds {count} entr{} this tool did not write (e.g. `{example}`: {why}); refusing to \
         replace it: name a new or empty output directory, or move them away",
        target.display(),
        if *count == 1 { "y" } else { "ies" }
    )]
    ForeignEntries {
        /// The output directory.
        target: PathBuf,
        /// How many foreign entries it holds.
        count: usize,
        /// The name of one of them.
        example: String,
        /// Why that one is foreign, in words.
        why: &'static str,
    },
    /// The output path exists and is not a directory, or names no directory (`/`, `..`).
    #[error("{} is not a directory that outputs can be written into", target.display())]
    NotADirectory {
        /// The output path.
        target: PathBuf,
    },
    /// An output file name is empty, has a path separator, is `.`/`..`, or was given twice.
    #[error("output file name `{name}` in {}: {reason}", target.display())]
    BadFileName {
        /// The output directory.
        target: PathBuf,
        /// The name given.
        name: String,
        /// What is wrong with it.
        reason: &'static str,
    },
}

/// Result alias of this crate.
pub type Result<T> = std::result::Result<T, EdgeIoError>;

/// `2147483648 bytes (2.0 GiB)`, or `more than …` when the size is unknown.
fn size_text(size_bytes: Option<u64>, limit_bytes: u64) -> String {
    match size_bytes {
        Some(size) => format!("{size} bytes ({})", binary_size(size)),
        None => format!("more than {limit_bytes} bytes"),
    }
}

/// A size in the largest binary unit that keeps it at least 1: `16 MiB`, `2.5 GiB`, `900 B`.
pub(crate) fn binary_size(bytes: u64) -> String {
    const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut unit = 0;
    let mut scaled = bytes as f64;
    while scaled >= 1024.0 && unit + 1 < UNITS.len() {
        scaled /= 1024.0;
        unit += 1;
    }
    if unit == 0 || scaled.fract() == 0.0 {
        format!("{scaled:.0} {}", UNITS[unit])
    } else {
        format!("{scaled:.1} {}", UNITS[unit])
    }
}

impl From<EdgeIoError> for std::io::Error {
    /// An [`std::io::Error`] for callers whose own error type already names the file: the
    /// kind is kept (`FileTooLarge`, `InvalidData`, or the underlying error's), and the
    /// message leaves out the path.
    fn from(e: EdgeIoError) -> Self {
        use std::io::{Error, ErrorKind};
        match e {
            EdgeIoError::Read { source, .. }
            | EdgeIoError::Write { source, .. }
            | EdgeIoError::Replace { source, .. } => source,
            EdgeIoError::TooLarge {
                limit_bytes,
                size_bytes,
                ..
            } => Error::new(
                ErrorKind::FileTooLarge,
                format!(
                    "{}, above the limit of {limit_bytes} bytes ({}) for this kind of file",
                    size_text(size_bytes, limit_bytes),
                    binary_size(limit_bytes)
                ),
            ),
            EdgeIoError::InvalidUtf8 {
                line,
                column,
                offset,
                ..
            } => Error::new(
                ErrorKind::InvalidData,
                format!(
                    "line {line}, column {column}: not UTF-8 text (invalid byte at offset {offset})"
                ),
            ),
            EdgeIoError::NotAFile { kind, .. } => Error::new(
                ErrorKind::InvalidInput,
                format!("{kind}, not a regular file: not read"),
            ),
            other @ (EdgeIoError::ForeignEntries { .. }
            | EdgeIoError::NotADirectory { .. }
            | EdgeIoError::BadFileName { .. }) => Error::other(other.to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_in_binary_units() {
        assert_eq!(binary_size(900), "900 B");
        assert_eq!(binary_size(16 * 1024 * 1024), "16 MiB");
        assert_eq!(binary_size(5 * 1024 * 1024 * 1024 / 2), "2.5 GiB");
    }

    #[test]
    fn io_conversion_keeps_the_kind_and_drops_the_path() {
        let e: std::io::Error = EdgeIoError::TooLarge {
            path: "/somewhere/study.ron".into(),
            limit_bytes: 16,
            size_bytes: Some(2048),
        }
        .into();
        assert_eq!(e.kind(), std::io::ErrorKind::FileTooLarge);
        let text = e.to_string();
        assert!(!text.contains("study.ron"), "{text}");
        assert!(
            text.contains("2048 bytes") && text.contains("limit of 16 bytes"),
            "{text}"
        );
    }
}
