//! Writes a deterministic synthetic probe recording (CSV) with known Fourier coefficients.
//!
//! ```text
//! cargo run -p recording --features synthetic --example synth_recording -- OUT.csv [--rate-deg-s W] [--sample-rate-hz F]
//!     [--revolutions R] [--encoder | --no-encoder] [--noise-um S] [--wobble-rad A]
//!     [--start-angle-deg D] [--seed N]
//! ```
//!
//! Defaults give the repository's fixture `fixtures/recordings/probe_120deg_s.csv`:
//! `--rate-deg-s 120 --sample-rate-hz 500 --revolutions 2.5 --encoder --noise-um 0.02
//! --wobble-rad 0.05 --seed 20250101`. The benchmark recordings of docs/PERFORMANCE.md are
//! `--rate-deg-s 10 --sample-rate-hz 1000 --revolutions 8 --noise-um 0.05` (288 000 samples)
//! and `--revolutions 80` (2 880 000).
#![allow(clippy::print_stdout, clippy::print_stderr)]

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &[String]) -> Result<(), String> {
    let mut spec = recording::SyntheticSpec::default();
    let mut out = None;
    let mut i = 0;
    while i < args.len() {
        let value = |i: usize| -> Result<f64, String> {
            args.get(i + 1)
                .ok_or(format!("{} needs a value", args[i]))?
                .parse()
                .map_err(|e| format!("{}: {e}", args[i]))
        };
        match args[i].as_str() {
            "--rate-deg-s" => spec.rate_deg_s = value(i)?,
            "--sample-rate-hz" => spec.sample_rate_hz = value(i)?,
            "--revolutions" => spec.revolutions = value(i)?,
            "--noise-um" => spec.noise_um = value(i)?,
            "--wobble-rad" => spec.wobble_rad = value(i)?,
            "--start-angle-deg" => spec.start_angle_deg = value(i)?,
            "--seed" => spec.seed = value(i)? as u64,
            "--encoder" => {
                spec.encoder = true;
                i += 1;
                continue;
            }
            "--no-encoder" => {
                spec.encoder = false;
                i += 1;
                continue;
            }
            path if !path.starts_with("--") && out.is_none() => {
                out = Some(path.to_owned());
                i += 1;
                continue;
            }
            other => return Err(format!("unexpected argument {other:?}")),
        }
        i += 2;
    }
    let out = out.ok_or("usage: synth_recording OUT.csv [options]")?;
    let text = spec.csv().map_err(|e| e.to_string())?;
    std::fs::write(&out, &text).map_err(|e| format!("{out}: {e}"))?;
    println!("{out}: {} bytes, {} samples", text.len(), spec.samples());
    Ok(())
}
