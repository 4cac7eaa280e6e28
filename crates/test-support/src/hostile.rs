//! Hostile files for the tests of issue 32 (a FIFO, a sparse file) and a watchdog, so that a
//! test of "does not block" fails instead of hanging CI when the code blocks after all.

use std::path::Path;
use std::time::Duration;

/// Makes a FIFO (named pipe) at `path` with the system's `mkfifo`: nothing ever writes to
/// it, so a reader that opens it blocking waits forever.
///
/// # Panics
/// When `mkfifo` cannot be run or fails (a test set-up failure).
pub fn mkfifo(path: &Path) {
    let status = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success(), "mkfifo {} failed", path.display());
}

/// Makes a sparse file of `bytes` bytes (holes: no disk space, read as zeros), optionally
/// starting with `head`.
///
/// # Panics
/// When the file cannot be written (a test set-up failure).
pub fn sparse_file(path: &Path, head: &[u8], bytes: u64) {
    std::fs::write(path, head).expect("a sparse file's head");
    std::fs::OpenOptions::new()
        .write(true)
        .open(path)
        .and_then(|f| f.set_len(bytes))
        .expect("a sparse file");
}

/// Runs `f` on a thread of its own and returns its result if it ends within `limit`.
///
/// # Panics
/// When `f` takes longer than `limit` (the test fails, naming `what`; the thread is left
/// behind, blocked, and ends with the test process), or when `f` panics.
pub fn within<T: Send + 'static>(
    limit: Duration,
    what: &str,
    f: impl FnOnce() -> T + Send + 'static,
) -> T {
    let (send, receive) = std::sync::mpsc::channel();
    let worker = std::thread::spawn(move || {
        let _ = send.send(f());
    });
    match receive.recv_timeout(limit) {
        Ok(value) => value,
        Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
            panic!("{what}: no answer within {limit:?} (blocked or unbounded)")
        }
        Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
            let _ = worker.join();
            panic!("{what}: panicked")
        }
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn the_watchdog_fails_a_call_that_blocks_and_passes_one_that_ends() {
        assert_eq!(within(Duration::from_secs(5), "quick", || 7), 7);
        let blocked = std::panic::catch_unwind(|| {
            within(Duration::from_millis(50), "blocked", || {
                std::thread::sleep(Duration::from_secs(3600));
            });
        });
        assert!(blocked.is_err());
    }
}
