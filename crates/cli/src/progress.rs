//! Progress of long work on standard error: a spinner or a bar while recordings are read and
//! analysed, the Monte Carlo runs, a plan is simulated. Drawn only when standard error is a
//! terminal; in a pipe or a file nothing at all is written (no spinner, no escape sequence),
//! so logs and captured output stay clean. Only the command line draws; libraries at most
//! report events through a callback (`pipeline::run_with_progress`).

use std::borrow::Cow;
use std::io::IsTerminal as _;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Whether progress is drawn: standard error is a terminal.
pub(crate) fn shown() -> bool {
    std::io::stderr().is_terminal()
}

/// A bar drawn on standard error when it is a terminal, else hidden.
fn new_bar(len: Option<u64>) -> ProgressBar {
    if shown() {
        ProgressBar::with_draw_target(len, ProgressDrawTarget::stderr())
    } else {
        ProgressBar::hidden()
    }
}

/// A spinner showing `message` and the time spent, ticking on its own.
pub(crate) fn spinner(message: impl Into<Cow<'static, str>>) -> ProgressBar {
    let bar = new_bar(None);
    to_spinner(&bar, message);
    bar
}

/// Turns `bar` into a spinner showing `message`.
pub(crate) fn to_spinner(bar: &ProgressBar, message: impl Into<Cow<'static, str>>) {
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    bar.set_message(message);
    bar.enable_steady_tick(Duration::from_millis(120));
}

/// Turns `bar` into a bar of `len` steps described by `what` (`{pos}/{len} what {msg}`).
pub(crate) fn to_bar(bar: &ProgressBar, len: u64, what: &str) {
    bar.disable_steady_tick();
    bar.set_length(len);
    bar.set_position(0);
    bar.set_message("");
    bar.set_style(
        ProgressStyle::with_template(&format!("{{bar:30}} {{pos}}/{{len}} {what} {{msg}}"))
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
}

/// A bar for reading a recording file: hidden until a file of at least
/// [`recording::STREAM_FROM_BYTES`] is read (a short file is read before a bar would
/// show), and always hidden when standard error is not a terminal.
pub(crate) fn file_bar() -> ProgressBar {
    ProgressBar::hidden()
}

/// Shows how far a recording is read: the bytes of the file in the current pass.
pub(crate) fn show_read(bar: &ProgressBar, p: recording::ReadProgress) {
    if p.bytes_total < recording::STREAM_FROM_BYTES || !shown() {
        return;
    }
    if bar.is_hidden() {
        bar.set_draw_target(ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template(
                "{msg} {bar:30} {binary_bytes}/{binary_total_bytes} ({eta})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
    }
    let stage = match p.stage {
        recording::ReadStage::Counting => "counting rows",
        recording::ReadStage::Fitting => "fitting revolutions",
        recording::ReadStage::Reading => "reading",
    };
    if bar.length() != Some(p.bytes_total) {
        bar.set_length(p.bytes_total);
    }
    bar.set_message(stage);
    bar.set_position(p.bytes_read);
}
