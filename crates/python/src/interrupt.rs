//! Long calls that Ctrl-C stops: the work runs on its own thread with the GIL released,
//! while the calling thread looks for Python's signals every [`POLL`]; on one (a
//! `KeyboardInterrupt` from SIGINT), the work is asked to stop (the Monte Carlo method stops
//! before its next batch of 10⁴ trials, `uncertainty::stoppable`) and the signal's exception
//! is raised at once.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{RecvTimeoutError, sync_channel};
use std::time::Duration;

use pyo3::prelude::*;

use crate::errors::{self, Kind, Located};

/// How often the calling thread looks for a signal.
const POLL: Duration = Duration::from_millis(10);

/// How long, after a signal, the call waits for the work to stop before it raises (work
/// that does not stop by then finishes on its own thread, its result dropped).
const GRACE: Duration = Duration::from_millis(50);

/// Runs `work` to its end, or until a Python signal handler raises (Ctrl-C); the GIL is
/// released meanwhile, so other Python threads run.
pub(crate) fn interruptible<T: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce() -> T + Send + 'static,
) -> PyResult<T> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let (done, result) = sync_channel(1);
    std::thread::Builder::new()
        .name("centrifuge-cal".into())
        .spawn(move || {
            let out = catch_unwind(AssertUnwindSafe(|| uncertainty::stoppable(&flag, work)));
            // the caller may have left on a signal: then nobody listens, and that is fine
            let _ = done.send(out);
        })
        .map_err(|e| {
            errors::raise(
                py,
                Kind::Computation,
                format!("cannot start the computation's thread: {e}"),
                Located::default(),
            )
        })?;
    let mut result = result;
    loop {
        // the receiver is moved into the released-GIL closure and back (it is `Send`, not
        // `Sync`)
        let (back, received) = py.detach(move || {
            let received = result.recv_timeout(POLL);
            (result, received)
        });
        result = back;
        match received {
            Ok(Ok(out)) => return Ok(out),
            Ok(Err(panic)) => return Err(panicked(py, panic.as_ref())),
            Err(RecvTimeoutError::Timeout) => {
                if let Err(signal) = py.check_signals() {
                    stop.store(true, Ordering::Relaxed);
                    let _ = py.detach(move || result.recv_timeout(GRACE).is_ok());
                    return Err(signal);
                }
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(panicked(
                    py,
                    &"the computation's thread ended without a result",
                ));
            }
        }
    }
}

/// A panic of the work as a [`Kind::Computation`] error: a defect of this package, never
/// the caller's.
fn panicked(py: Python<'_>, panic: &(dyn std::any::Any + Send)) -> PyErr {
    let what = panic
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic".to_owned());
    errors::raise(
        py,
        Kind::Computation,
        format!("internal error (please report it with the inputs that caused it): {what}"),
        Located::default(),
    )
}
