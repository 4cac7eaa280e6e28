//! `cargo xtask`: the centrifuge-cal command line.
//!
//! Each subcommand is a module with a clap-derived argument struct and a `run` method. Every
//! command prints through [`console::Console`], never `println!`: output that cannot be
//! written is an error (exit status 1 with a message) or, for a pipe closed by its reader, a
//! quiet exit with status 141; never a panic.

mod accuracy;
mod console;
mod harmonics;
mod identify;
mod paths;
mod plan;
mod regress;
mod simulate;
mod study;

use std::io::Write as _;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// centrifuge-cal: PIGA calibration on a precision centrifuge, and the spindle imbalance's
/// pseudo-second-order term.
#[derive(Debug, Parser)]
#[command(name = "cargo xtask", version, about)]
struct Cli {
    /// Show the study's steps (-v) and their details (-vv) on stderr.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    verbose: u8,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run a pre/post-balance study and write results.json, report.md and radius_error.svg.
    Study(study::Study),
    /// Run a study and compare it with its expected values; exits non-zero on a difference.
    Regress(regress::Regress),
    /// Score the least-squares solver on the NIST StRD linear-regression datasets (LRE).
    Accuracy(accuracy::Accuracy),
    /// Identify k0…k3 (eq. 18) from a PIGA output table, optionally compensating Δk2 (eq. 19).
    Identify(identify::Identify),
    /// Simulate a calibration from a scenario: probe recordings, piga.csv and truth.json.
    Simulate(simulate::Simulate),
    /// Fit eq. 20 per revolution to a probe recording and average the coefficients.
    Harmonics(Box<harmonics::Harmonics>),
    /// Plan a calibration campaign: rates, revolutions and U95(k2) for a target (issue 13).
    Plan(plan::PlanCmd),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_exit(&e),
    };
    let level = match cli.verbose {
        0 => tracing::Level::WARN,
        1 => tracing::Level::INFO,
        _ => tracing::Level::DEBUG,
    };
    tracing_subscriber::fmt()
        .with_writer(std::io::stderr)
        .with_target(false)
        .without_time()
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .with_max_level(level)
        .init();
    let outcome = match &cli.command {
        Command::Study(c) => c.run(),
        Command::Regress(c) => c.run(),
        Command::Accuracy(c) => c.run(),
        Command::Identify(c) => c.run(),
        Command::Simulate(c) => c.run(),
        Command::Harmonics(c) => c.run(),
        Command::Plan(c) => c.run(),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if console::closed_by_reader(&e) => ExitCode::from(console::CLOSED_PIPE_STATUS),
        Err(e) => fail(&error_chain(&e)),
    }
}

/// Prints `error: <message>` on standard error (if it can) and returns status 1.
fn fail(message: &str) -> ExitCode {
    // Nothing is left to report a failure of standard error to.
    let _ = writeln!(std::io::stderr(), "error: {message}");
    ExitCode::FAILURE
}

/// Prints clap's help, version or usage error and returns its status; help that cannot be
/// written to standard output fails as any other output does.
fn usage_exit(e: &clap::Error) -> ExitCode {
    match e.print() {
        Err(io) if !e.use_stderr() => match console::ConsoleError::from(io) {
            console::ConsoleError::Closed => ExitCode::from(console::CLOSED_PIPE_STATUS),
            other => fail(&error_chain(&anyhow::Error::new(other))),
        },
        // A usage error goes to standard error; if even that fails, the status still tells.
        _ => ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(2)),
    }
}

/// The error and its causes joined by `: `, leaving out a cause whose text the message
/// before it already contains (the libraries' messages include their source's).
fn error_chain(e: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if !out.contains(&text) {
            if !out.is_empty() {
                out.push_str(": ");
            }
            out.push_str(&text);
        }
    }
    out
}
