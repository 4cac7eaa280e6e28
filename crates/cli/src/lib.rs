//! The centrifuge-cal command line: the binary `centrifuge-cal`, `cargo xtask` (a thin
//! wrapper in the workspace) and the Python package's console script all run [`run`] or
//! [`run_with`].
//!
//! Each subcommand is a module with a clap-derived argument struct and a `run` method. Every
//! command prints through `console::Console`, never `println!`: output that cannot be
//! written is an error (exit status 1 with a message) or, for a pipe closed by its reader, a
//! quiet exit with status 141; never a panic. The commands call the libraries; they are the
//! edge that touches files (`.ci/layering`).

// One feature set with the tests' build (crates/workspace-hack).
use workspace_hack as _;

mod accuracy;
mod certificate;
mod check;
mod console;
mod harmonics;
mod history;
mod identify;
mod init;
mod paths;
mod plan;
mod plan_two_orientation;
mod problems;
mod progress;
mod record;
mod regress;
mod simulate;
mod study;

use std::ffi::OsString;
use std::io::Write as _;
use std::process::ExitCode;

use clap::{CommandFactory as _, FromArgMatches as _, Parser, Subcommand};

pub use history::DEFAULT_SHARE;
pub use paths::Places;
pub use record::records_path;

/// centrifuge-cal: PIGA calibration on a precision centrifuge, and the spindle imbalance's
/// pseudo-second-order term.
#[derive(Debug, Parser)]
#[command(name = "centrifuge-cal", version, about)]
struct Cli {
    /// Show the study's steps (-v) and their details (-vv) on stderr.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    verbose: u8,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run a study from its configuration — probe phases (C_r and Δk2 each), and where
    /// configured the mechanism, the PIGA calibration with its uncertainty budget and the
    /// balancing — and write results.json, report.md and the figures.
    Study(study::Study),
    /// Run a study and compare it with its expected values; exits non-zero on a difference.
    Regress(regress::Regress),
    /// Score the least-squares solver on the NIST StRD linear-regression datasets (LRE).
    Accuracy(accuracy::Accuracy),
    /// Identify k0…k3 (eq. 18) from a PIGA output table, optionally compensating Δk2 (eq. 19).
    Identify(Box<identify::Identify>),
    /// Simulate a calibration from a scenario: probe recordings, piga.csv and truth.json.
    Simulate(simulate::Simulate),
    /// Fit eq. 20 per revolution to a probe recording and average the coefficients.
    Harmonics(Box<harmonics::Harmonics>),
    /// Plan a calibration campaign: rates, revolutions and U95(k2) for a target.
    Plan(plan::PlanCmd),
    /// Write a commented study configuration from a lab's files: each file's format and
    /// rate guessed with its evidence, placeholders for what the files cannot tell.
    Init(init::Init),
    /// Check a study configuration without running it: what the study will do, and every
    /// problem found in it and its files, grouped, with hints.
    Check(check::Check),
    /// Write the calibration certificate (PDF/A) of a study's results folder again, from its
    /// results.json: no browser, no study run.
    Certificate(certificate::Certificate),
    /// Record a study's outputs (results.json and its certificate) in the records database,
    /// or a balancing of a centrifuge (docs/RECORDS.md).
    Record(record::Record),
    /// A unit's certified coefficients across its certificates (drift, prediction, the
    /// recommended interval), or a centrifuge's health (--centrifuge), from the records.
    History(Box<history::History>),
}

/// Runs the command line as the installed `centrifuge-cal` ([`Places::installed`]).
///
/// `args` are the whole command line, the program's name first, as [`std::env::args_os`]
/// gives them (Python: `sys.argv`).
pub fn run<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    ExitCode::from(run_with(&Places::installed(), args))
}

/// Runs the command line with the defaults of `places` and returns the exit status: 0 on
/// success, 1 on an error (its message on standard error), 2 on a usage error, 141 when the
/// reader of standard output closed it. For callers that need the number (the Python
/// extension); [`run`] wraps it in an [`ExitCode`].
pub fn run_with<I, T>(places: &Places, args: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let matches = Cli::command()
        .name(places.program())
        .bin_name(places.program())
        .try_get_matches_from(args);
    let cli = match matches.and_then(|m| Cli::from_arg_matches(&m)) {
        Ok(cli) => cli,
        Err(e) => return usage_exit(&e),
    };
    let level = match cli.verbose {
        0 => tracing::Level::WARN,
        1 => tracing::Level::INFO,
        _ => tracing::Level::DEBUG,
    };
    // A second run in the same process (the Python extension) keeps the first subscriber.
    let _ = tracing_subscriber::fmt()
        .with_writer(std::io::stderr)
        .with_target(false)
        .without_time()
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .with_max_level(level)
        .try_init();
    let outcome = match &cli.command {
        Command::Study(c) => c.run(places),
        Command::Regress(c) => c.run(places),
        Command::Accuracy(c) => c.run(places),
        Command::Identify(c) => c.run(),
        Command::Simulate(c) => c.run(places),
        Command::Harmonics(c) => c.run(),
        Command::Plan(c) => c.run(places),
        Command::Init(c) => c.run(),
        Command::Check(c) => c.run(),
        Command::Certificate(c) => c.run(),
        Command::Record(c) => c.run(),
        Command::History(c) => c.run(),
    };
    match outcome {
        Ok(()) => 0,
        Err(e) if console::closed_by_reader(&e) => console::CLOSED_PIPE_STATUS,
        Err(e) => fail(&error_chain(&e)),
    }
}

/// Prints `error: <message>` on standard error (if it can) and returns status 1.
fn fail(message: &str) -> u8 {
    // Nothing is left to report a failure of standard error to.
    let _ = writeln!(
        std::io::stderr(),
        "error: {}",
        edge_io::visible_lines(message)
    );
    1
}

/// Prints clap's help, version or usage error and returns its status; help that cannot be
/// written to standard output fails as any other output does.
fn usage_exit(e: &clap::Error) -> u8 {
    match e.print() {
        Err(io) if !e.use_stderr() => match console::ConsoleError::from(io) {
            console::ConsoleError::Closed => console::CLOSED_PIPE_STATUS,
            other => fail(&error_chain(&anyhow::Error::new(other))),
        },
        // A usage error goes to standard error; if even that fails, the status still tells.
        _ => u8::try_from(e.exit_code()).unwrap_or(2),
    }
}

/// The error and its causes as one line ([`units::ErrorChain`], the one chain printer).
fn error_chain(e: &anyhow::Error) -> String {
    let e: &(dyn std::error::Error + 'static) = e.as_ref();
    units::ErrorChain(e).to_string()
}
