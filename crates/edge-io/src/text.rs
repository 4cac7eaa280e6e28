//! Size-capped reads of configuration-like text files.

use std::io::Read as _;
use std::path::Path;

use crate::error::{EdgeIoError, Result};

/// The cap on every configuration-like file the workspace reads (study configuration,
/// simulation scenario, expected values): 16 MiB. The largest of the fixtures is a few KiB; a
/// hand-written RON file this large is a mistake (a recording passed as `--config`, a sparse
/// or device file), refused before it is read.
pub const CONFIG_MAX_BYTES: u64 = 16 * 1024 * 1024;

/// The UTF-8 encoding of U+FEFF, which some editors put at the start of a text file.
const BOM: &[u8] = b"\xEF\xBB\xBF";

/// Reads a UTF-8 text file of at most `max_bytes` bytes.
///
/// Only a regular file is read ([`open_regular`](crate::open_regular): a FIFO, a device or a
/// folder is [`EdgeIoError::NotAFile`], refused without blocking). A file whose size is above
/// the cap is refused from its metadata, without reading it; a file that grows while read is
/// read through [`Read::take`](std::io::Read::take) for at most `max_bytes + 1` bytes, so
/// memory stays bounded by the cap. A leading UTF-8 byte-order mark is dropped.
///
/// # Errors
/// [`EdgeIoError::Read`] when the file cannot be opened or read; [`EdgeIoError::NotAFile`]
/// for anything but a regular file; [`EdgeIoError::TooLarge`] above the cap, naming the file, its size and the limit;
/// [`EdgeIoError::InvalidUtf8`] naming the line, column and byte offset of the first byte that
/// is not UTF-8.
///
/// ```
/// # let dir = std::env::temp_dir().join(format!("edge-io-doc-{}", std::process::id()));
/// # std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("study.ron");
/// std::fs::write(&path, b"\xEF\xBB\xBF(name: \"paper\")").unwrap();
/// assert_eq!(edge_io::read_text_capped(&path, 1024).unwrap(), "(name: \"paper\")");
/// assert!(matches!(
///     edge_io::read_text_capped(&path, 8),
///     Err(edge_io::EdgeIoError::TooLarge { limit_bytes: 8, size_bytes: Some(18), .. })
/// ));
/// # std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn read_text_capped(path: &Path, max_bytes: u64) -> Result<String> {
    text_from_bytes(path, read_bytes_capped(path, max_bytes)?)
}

/// Reads a file of at most `max_bytes` bytes as [`read_text_capped`] does, without decoding
/// it: for a caller that also keeps the digest of what it read (the provenance of a study's
/// configuration), then decodes with [`text_from_bytes`].
///
/// # Errors
/// [`EdgeIoError::Read`] and [`EdgeIoError::TooLarge`] as [`read_text_capped`].
pub fn read_bytes_capped(path: &Path, max_bytes: u64) -> Result<Vec<u8>> {
    let read_error = |source| EdgeIoError::Read {
        path: path.to_owned(),
        source,
    };
    let too_large = |size_bytes| EdgeIoError::TooLarge {
        path: path.to_owned(),
        limit_bytes: max_bytes,
        size_bytes,
    };
    let (file, metadata) = crate::open::open_regular(path)?;
    let known_size = metadata.len();
    if known_size > max_bytes {
        return Err(too_large(Some(known_size)));
    }
    let capacity = known_size.min(max_bytes).saturating_add(1);
    let mut bytes = Vec::with_capacity(usize::try_from(capacity).unwrap_or(0));
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(read_error)?;
    if bytes.len() as u64 > max_bytes {
        // A regular file that grew past the cap since its metadata was read, or a stream.
        return Err(too_large(None));
    }
    Ok(bytes)
}

/// The UTF-8 text of a file's `bytes` (read from `path`, named in errors), a leading
/// byte-order mark dropped, as [`read_text_capped`] decodes it.
///
/// # Errors
/// [`EdgeIoError::InvalidUtf8`] naming the line, column and byte offset of the first byte that
/// is not UTF-8.
pub fn text_from_bytes(path: &Path, mut bytes: Vec<u8>) -> Result<String> {
    let skipped = if bytes.starts_with(BOM) {
        bytes.drain(..BOM.len());
        BOM.len()
    } else {
        0
    };
    String::from_utf8(bytes).map_err(|e| {
        let valid = e.utf8_error().valid_up_to();
        let before = &e.as_bytes()[..valid];
        let line_start = before
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1);
        // `before` is valid UTF-8 up to `valid`, so counting characters cannot fail.
        let column = std::str::from_utf8(&before[line_start..]).map_or(0, |s| s.chars().count());
        EdgeIoError::InvalidUtf8 {
            path: path.to_owned(),
            line: 1 + before.iter().filter(|&&b| b == b'\n').count(),
            column: column + 1,
            offset: (skipped + valid) as u64,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A directory under the system temp directory, removed on drop.
    struct TempDir(std::path::PathBuf);

    impl TempDir {
        fn new(name: &str) -> Self {
            let dir =
                std::env::temp_dir().join(format!("edge-io-text-{name}-{}", std::process::id()));
            let _ = std::fs::remove_dir_all(&dir);
            std::fs::create_dir_all(&dir).unwrap();
            Self(dir)
        }

        fn file(&self, name: &str, bytes: &[u8]) -> std::path::PathBuf {
            let path = self.0.join(name);
            std::fs::write(&path, bytes).unwrap();
            path
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    #[test]
    fn reads_text_up_to_the_cap_and_drops_a_bom() {
        let dir = TempDir::new("ok");
        let exact = dir.file("exact.ron", b"(a: 1)");
        assert_eq!(read_text_capped(&exact, 6).unwrap(), "(a: 1)");
        let bom = dir.file("bom.ron", b"\xEF\xBB\xBF(a: 1)");
        assert_eq!(read_text_capped(&bom, 9).unwrap(), "(a: 1)");
        // only a leading mark is dropped
        let inner = dir.file("inner.ron", "(a: \u{FEFF})".as_bytes());
        assert_eq!(read_text_capped(&inner, 64).unwrap(), "(a: \u{FEFF})");
        let empty = dir.file("empty.ron", b"");
        assert_eq!(read_text_capped(&empty, 0).unwrap(), "");
    }

    #[test]
    fn a_sparse_file_above_the_cap_is_refused_without_reading_it() {
        let dir = TempDir::new("sparse");
        let path = dir.0.join("huge.ron");
        let file = std::fs::File::create(&path).unwrap();
        // 2 GiB of holes: reading it would take seconds and 2 GiB of memory.
        file.set_len(2 << 30).unwrap();
        let start = std::time::Instant::now();
        let e = read_text_capped(&path, CONFIG_MAX_BYTES).unwrap_err();
        assert!(start.elapsed() < std::time::Duration::from_secs(1));
        match &e {
            EdgeIoError::TooLarge {
                path: p,
                limit_bytes,
                size_bytes,
            } => {
                assert_eq!(p, &path);
                assert_eq!(*limit_bytes, CONFIG_MAX_BYTES);
                assert_eq!(*size_bytes, Some(2 << 30));
            }
            other => panic!("expected TooLarge, got {other:?}"),
        }
        let text = e.to_string();
        assert!(
            text.contains("huge.ron")
                && text.contains("2147483648 bytes (2 GiB)")
                && text.contains("limit of 16777216 bytes (16 MiB)"),
            "{text}"
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_device_or_a_fifo_is_refused_unread_and_without_blocking() {
        // /dev/zero never ends; before issue 32 it was read up to the cap.
        let e = read_text_capped(Path::new("/dev/zero"), 4096).unwrap_err();
        assert!(
            matches!(
                e,
                EdgeIoError::NotAFile {
                    kind: "a character device",
                    ..
                }
            ),
            "{e:?}"
        );
        assert!(
            e.to_string().contains("/dev/zero is a character device"),
            "{e}"
        );
        // A FIFO no one writes to: a blocking open would wait forever.
        let dir = TempDir::new("fifo");
        let fifo = dir.0.join("study.ron");
        test_support::hostile::mkfifo(&fifo);
        let e = test_support::hostile::within(
            std::time::Duration::from_secs(10),
            "reading a FIFO",
            move || read_text_capped(&fifo, 4096),
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                EdgeIoError::NotAFile {
                    kind: "a named pipe (FIFO)",
                    ..
                }
            ),
            "{e:?}"
        );
        assert!(e.to_string().contains("not a regular file"), "{e}");
    }

    #[test]
    fn invalid_utf8_names_line_column_and_offset() {
        let dir = TempDir::new("utf8");
        let path = dir.file("latin1.ron", b"(\n  note: \"\xB5m\",\n)");
        let e = read_text_capped(&path, 1024).unwrap_err();
        match &e {
            EdgeIoError::InvalidUtf8 {
                line,
                column,
                offset,
                ..
            } => assert_eq!((*line, *column, *offset), (2, 10, 11)),
            other => panic!("expected InvalidUtf8, got {other:?}"),
        }
        assert!(e.to_string().contains("latin1.ron:2:10"), "{e}");
        // after a byte-order mark the offset still counts from the start of the file
        let path = dir.file("bom-latin1.ron", b"\xEF\xBB\xBF\xB5");
        assert!(matches!(
            read_text_capped(&path, 1024),
            Err(EdgeIoError::InvalidUtf8 {
                line: 1,
                column: 1,
                offset: 3,
                ..
            })
        ));
    }

    #[test]
    fn a_missing_file_is_a_read_error_naming_it() {
        let path = std::env::temp_dir().join("edge-io-no-such-file.ron");
        match read_text_capped(&path, 1024) {
            Err(EdgeIoError::Read { path: p, source }) => {
                assert_eq!(p, path);
                assert_eq!(source.kind(), std::io::ErrorKind::NotFound);
            }
            other => panic!("expected Read, got {other:?}"),
        }
    }
}
