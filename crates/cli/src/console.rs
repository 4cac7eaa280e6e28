//! The one way the command line writes to standard output.
//!
//! `println!` panics when standard output cannot be written (`> /dev/full`, a closed pipe),
//! and Rust's exit flush drops the error of anything still buffered. Every command prints
//! through a [`Console`] instead: each write is flushed at once and its failure is a
//! [`ConsoleError`], which `main` turns into exit status 1 with a message on standard error,
//! or, when the reader has gone (`| head`), into a quiet exit with status 141, as a shell
//! reports a program that SIGPIPE ended.

use std::fmt;
use std::io::{self, Write};

/// Exit status of a command whose standard output was closed by its reader: 128 + SIGPIPE.
pub(crate) const CLOSED_PIPE_STATUS: u8 = 141;

/// Standard output could not be written.
#[derive(Debug, thiserror::Error)]
pub(crate) enum ConsoleError {
    /// The reader closed the pipe (`EPIPE`): nobody is left to tell.
    #[error("standard output was closed by its reader")]
    Closed,
    /// Any other failure (a full disk, `/dev/full`, a closed descriptor).
    #[error("cannot write to standard output")]
    Write {
        /// The underlying I/O error.
        source: io::Error,
    },
}

impl From<io::Error> for ConsoleError {
    fn from(source: io::Error) -> Self {
        if source.kind() == io::ErrorKind::BrokenPipe {
            Self::Closed
        } else {
            Self::Write { source }
        }
    }
}

/// Standard output (or, in tests, any writer), written with `write!`/`writeln!`, each write
/// flushed, each failure a [`ConsoleError`].
pub(crate) struct Console<W: Write = io::Stdout> {
    out: W,
}

impl Console {
    /// The process's standard output.
    pub(crate) fn stdout() -> Self {
        Self { out: io::stdout() }
    }
}

impl<W: Write> Console<W> {
    /// Writes formatted text and flushes it (what `write!` and `writeln!` call).
    pub(crate) fn write_fmt(&mut self, args: fmt::Arguments<'_>) -> Result<(), ConsoleError> {
        match args.as_str() {
            Some(text) => self.write_str(text),
            None => self.write_str(&args.to_string()),
        }
    }

    /// Writes text and flushes it. Characters that would act on a terminal instead of
    /// showing (ESC and the other control characters but line feed and tab, bidirectional
    /// overrides), which text from a file or configuration can hold, are written visibly
    /// (`\u{1b}`, `<U+202E>`).
    pub(crate) fn write_str(&mut self, text: &str) -> Result<(), ConsoleError> {
        self.out
            .write_all(edge_io::visible_lines(text).as_bytes())?;
        Ok(self.out.flush()?)
    }
}

/// Whether an error (or one of its causes) is standard output closed by its reader.
pub(crate) fn closed_by_reader(e: &anyhow::Error) -> bool {
    e.chain()
        .any(|cause| matches!(cause.downcast_ref(), Some(ConsoleError::Closed)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer that fails every write with the given kind.
    struct Failing(io::ErrorKind);

    impl Write for Failing {
        fn write(&mut self, _: &[u8]) -> io::Result<usize> {
            Err(io::Error::from(self.0))
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn writes_reach_the_writer() {
        let mut console = Console { out: Vec::new() };
        writeln!(console, "a {}", 1).unwrap();
        console.write_str("b\n").unwrap();
        assert_eq!(console.out, b"a 1\nb\n");
    }

    #[test]
    fn a_full_device_is_a_write_error_and_a_closed_pipe_is_closed() {
        let mut full = Console {
            out: Failing(io::ErrorKind::StorageFull),
        };
        match writeln!(full, "x") {
            Err(ConsoleError::Write { source }) => {
                assert_eq!(source.kind(), io::ErrorKind::StorageFull);
            }
            other => panic!("expected Write, got {other:?}"),
        }
        let mut pipe = Console {
            out: Failing(io::ErrorKind::BrokenPipe),
        };
        let e = pipe.write_str("x").unwrap_err();
        assert!(matches!(e, ConsoleError::Closed));
        let wrapped = anyhow::Error::new(e).context("printing the table");
        assert!(closed_by_reader(&wrapped));
        let full = anyhow::Error::new(full.write_str("x").unwrap_err());
        assert!(!closed_by_reader(&full));
    }
}
