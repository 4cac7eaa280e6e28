//! Analyses a probe recording the two ways, for the memory and time figures of
//! docs/PERFORMANCE.md (issue 32): `--in-memory` reads it whole then fits it
//! (`load_recording` then `analyze_recording`, the path before streaming), the default
//! streams it (`analyze_recording_file`). Prints the first harmonic and the revolutions.
//!
//! ```text
//! cargo run --release -p recording --example analyze_file -- FILE.csv RATE_DEG_S [--in-memory]
//! cargo run --release -p recording --example analyze_file -- FILE.csv 30 --write ROWS
//! /usr/bin/time -v target/release/examples/analyze_file FILE.csv 30
//! ```
//!
//! `--write ROWS` writes FILE first: a 30 deg/s, 1 kHz recording with an encoder column,
//! row by row (37 M rows make 1 GB).
#![allow(clippy::print_stdout, clippy::print_stderr)]

use std::path::Path;
use std::process::ExitCode;

use harmonics::FitConfig;
use recording::{RecordingFormat, StreamOptions};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(file), Some(rate)) = (
        args.first(),
        args.get(1).and_then(|r| r.parse::<f64>().ok()),
    ) else {
        eprintln!("usage: analyze_file FILE RATE_DEG_S [--in-memory]");
        return ExitCode::FAILURE;
    };
    let path = Path::new(file);
    let rows = args
        .iter()
        .position(|a| a == "--write")
        .and_then(|k| args.get(k + 1)?.parse::<usize>().ok());
    if let Some(rows) = rows
        && let Err(e) = write_long(path, rows)
    {
        eprintln!("error: {e}");
        return ExitCode::FAILURE;
    }
    let format = RecordingFormat::default();
    let config = FitConfig::default();
    let rate_rad_s = rate.to_radians();
    let result = if args.iter().any(|a| a == "--in-memory") {
        recording::load_recording(path, &format)
            .and_then(|r| recording::analyze_recording(&r, rate_rad_s, &config))
    } else {
        let options = StreamOptions {
            stream_from_bytes: 0,
            ..StreamOptions::default()
        };
        recording::analyze_recording_file(path, &format, rate_rad_s, &config, options, &mut |_| {})
            .map(|s| s.analysis)
    };
    match result {
        Ok(a) => {
            println!(
                "c1 {:?} s1 {:?} revolutions {} residual_rms {:?} diagnostics {}",
                a.analysis.mean.c[0],
                a.analysis.mean.s[0],
                a.analysis.revolutions_used(),
                a.residual_rms,
                a.diagnostics.len()
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// A long recording at 30 deg/s and 1 kHz ([`recording::write_long_recording`]).
fn write_long(path: &Path, rows: usize) -> std::io::Result<()> {
    let file = std::fs::File::create(path)?;
    recording::write_long_recording(std::io::BufWriter::with_capacity(1 << 20, file), rows)
}
