//! A test hook: make [`OutputSet`](crate::OutputSet) fail at a named file, on this thread.
//!
//! Tests of the crates that write through an output set (a study's outputs, a simulation)
//! use it to fail a run at its last file deterministically, whatever the user's permissions
//! (root ignores a read-only directory). It has no effect unless a test sets it.

use std::cell::RefCell;

thread_local! {
    static FAIL_AT: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// While the returned guard lives, writing an output file named `name` on this thread fails
/// with [`EdgeIoError::Write`](crate::EdgeIoError::Write) (an `Other` I/O error) after the
/// file has been created and partly written.
#[must_use = "the failure is armed only while the guard lives"]
pub fn fail_writing(name: &str) -> FailGuard {
    FAIL_AT.with(|f| *f.borrow_mut() = Some(name.to_owned()));
    FailGuard(())
}

/// Disarms the failure set by [`fail_writing`] when dropped.
#[derive(Debug)]
pub struct FailGuard(());

impl Drop for FailGuard {
    fn drop(&mut self) {
        FAIL_AT.with(|f| *f.borrow_mut() = None);
    }
}

/// Whether writing `name` must fail now.
pub(crate) fn armed_for(name: &str) -> bool {
    FAIL_AT.with(|f| f.borrow().as_deref() == Some(name))
}
