//! A recording analysed as it is read (`analyze_recording_file`, streamed) gives what
//! `load_recording` then `analyze_recording` give, to the bit: numbers, diagnostics and
//! errors with their lines (issue 32).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use harmonics::FitConfig;
use recording::{
    AngleSource, RecordingFormat, StreamOptions, TimeUnit, analyze_recording,
    analyze_recording_file, load_recording,
};

const RATE_DEG_S: f64 = 30.0;
/// Samples per revolution at 1 kHz.
const PER_REV: usize = 12_000;

/// A probe recording as a lab writes it: time, gap and encoder angle, with noise.
fn recording_text(samples: usize, spoil: impl Fn(usize, &mut (f64, f64, f64))) -> String {
    let mut s = String::from("# probe at 30 deg/s\ntime_s,gap_um,angle_deg\n");
    let rate = RATE_DEG_S.to_radians();
    for i in 0..samples {
        let t = 12.0 + i as f64 * 1e-3;
        let theta = rate * (t - 12.0) + 0.3;
        let noise = 0.01 * (((i * 7919) % 101) as f64 / 50.0 - 1.0);
        let gap = 50.0 - 3.2 * theta.cos() - 1.1 * theta.sin() + 0.2 * (4.0 * theta).cos() + noise;
        let mut row = (t, gap, theta.to_degrees() % 360.0);
        spoil(i, &mut row);
        writeln!(s, "{:.6},{:.6},{:.5}", row.0, row.1, row.2).unwrap();
    }
    s
}

fn write(name: &str, text: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("centrifuge-stream-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Both ways, as Debug text (every value printed exactly; errors with their lines).
fn both(
    path: &Path,
    format: &RecordingFormat,
    rate_deg_s: f64,
    config: &FitConfig,
    zero_deg: f64,
) -> (String, String, bool) {
    let rate = rate_deg_s.to_radians();
    let options = StreamOptions {
        angle_zero_rad: zero_deg.to_radians(),
        stream_from_bytes: 0,
    };
    let mut reports = 0;
    let streamed =
        analyze_recording_file(path, format, rate, config, options, &mut |_| reports += 1);
    let was_streamed = streamed.as_ref().is_ok_and(|s| s.streamed);
    let got = match streamed {
        Ok(s) => format!("{} {:?} {:?}", s.samples, s.gap_unit, s.analysis),
        Err(e) => format!("error: {e} {e:?}"),
    };
    let want = match load_recording(path, format).and_then(|mut r| {
        r.shift_angle_zero(zero_deg.to_radians());
        analyze_recording(&r, rate, config).map(|a| (r, a))
    }) {
        Ok((r, a)) => format!("{} {:?} {:?}", r.len(), r.gap_unit, a),
        Err(e) => format!("error: {e} {e:?}"),
    };
    assert!(reports > 0, "progress is reported");
    (got, want, was_streamed)
}

fn check(
    name: &str,
    text: &[u8],
    format: &RecordingFormat,
    rate_deg_s: f64,
    config: &FitConfig,
    zero_deg: f64,
) -> String {
    let path = write(name, text);
    let (got, want, streamed) = both(&path, format, rate_deg_s, config, zero_deg);
    assert_eq!(got, want, "{name}");
    std::fs::remove_file(&path).unwrap();
    if !want.starts_with("error: ") {
        assert!(streamed, "{name}: streamed");
    }
    want
}

#[test]
fn streamed_analysis_equals_the_analysis_in_memory() {
    let n = PER_REV * 6 + 500;
    let plain = recording_text(n, |_, _| {});
    let format = RecordingFormat::default();
    let config = FitConfig::default();
    let out = check(
        "plain.csv",
        plain.as_bytes(),
        &format,
        RATE_DEG_S,
        &config,
        0.0,
    );
    assert!(out.starts_with(&format!("{n} ")), "{out}");
    check(
        "zero.csv",
        plain.as_bytes(),
        &format,
        RATE_DEG_S,
        &config,
        10.0,
    );
    let drift = FitConfig {
        drift: true,
        order: 6,
        revolutions: Some(3),
        ..config.clone()
    };
    check(
        "drift.csv",
        plain.as_bytes(),
        &format,
        RATE_DEG_S,
        &drift,
        0.0,
    );
    let rate = RecordingFormat {
        angle: AngleSource::Rate {
            start_angle_deg: 17.2,
        },
        ..format.clone()
    };
    let out = check(
        "rate.csv",
        plain.as_bytes(),
        &rate,
        RATE_DEG_S,
        &config,
        0.0,
    );
    assert!(out.contains("AngleFromRate"), "{out}");
    // One glitch: an outlier revolution, whose largest residual is read again from the file.
    let glitch = recording_text(n, |i, row| {
        if i == 40_000 {
            row.1 += 900.0
        }
    });
    let out = check(
        "glitch.csv",
        glitch.as_bytes(),
        &format,
        RATE_DEG_S,
        &config,
        0.0,
    );
    assert!(out.contains("ResidualOutlier"), "{out}");
    // Every other sample zeroed: alternating residuals, from eight revolutions read again.
    let zeroed = recording_text(n, |i, row| {
        if i % 2 == 1 {
            row.1 = 0.0
        }
    });
    let out = check(
        "zeroed.csv",
        zeroed.as_bytes(),
        &format,
        RATE_DEG_S,
        &config,
        0.0,
    );
    assert!(out.contains("AlternatingResiduals"), "{out}");
    // Comments and blank lines among the rows, CRLF, a byte-order mark.
    let mut messy = String::from("\u{feff}");
    for (k, line) in plain.lines().enumerate() {
        messy.push_str(line);
        messy.push_str("\r\n");
        if k % 9_999 == 5 {
            messy.push_str("# a note\r\n\r\n");
        }
    }
    let out = check(
        "messy.csv",
        messy.as_bytes(),
        &format,
        RATE_DEG_S,
        &config,
        0.0,
    );
    assert!(!out.starts_with("error: "), "{out}");
    let cr = plain.replace('\n', "\r");
    check("cr.csv", cr.as_bytes(), &format, RATE_DEG_S, &config, 0.0);
    let glitch_cr = glitch.replace('\n', "\r");
    check(
        "glitch_cr.csv",
        glitch_cr.as_bytes(),
        &format,
        RATE_DEG_S,
        &config,
        0.0,
    );
    // Time in milliseconds.
    let ms = recording_text(n, |_, row| row.0 *= 1e3);
    let in_ms = RecordingFormat {
        time: recording::Column {
            column: "time_s".into(),
            unit: TimeUnit::Ms,
        },
        ..format.clone()
    };
    check("ms.csv", ms.as_bytes(), &in_ms, RATE_DEG_S, &config, 0.0);
}

#[test]
fn streamed_analysis_refuses_with_the_same_error_and_line() {
    let n = PER_REV * 4 + 500;
    let format = RecordingFormat::default();
    let config = FitConfig::default();
    type Spoil = Box<dyn Fn(usize, &mut (f64, f64, f64))>;
    let cases: [(&str, Spoil, f64); 6] = [
        (
            "back",
            Box::new(|i, row| {
                if i == 20_000 {
                    row.0 -= 0.5
                }
            }),
            RATE_DEG_S,
        ),
        (
            "gap",
            Box::new(|i, row| {
                if i >= 30_000 {
                    row.0 += 0.05
                }
            }),
            RATE_DEG_S,
        ),
        ("rate", Box::new(|_, _| {}), 40.0),
        (
            "angle back",
            Box::new(|i, row| {
                if i == 33_333 {
                    row.2 -= 40.0
                }
            }),
            RATE_DEG_S,
        ),
        ("aliasing", Box::new(|_, _| {}), 3_000.0),
        (
            "nan",
            Box::new(|i, row| {
                if i == 41_000 {
                    row.1 = f64::NAN
                }
            }),
            RATE_DEG_S,
        ),
    ];
    for (name, spoil, rate) in cases {
        let text = recording_text(n, spoil);
        let out = check(
            &format!("{name}.csv"),
            text.as_bytes(),
            &format,
            rate,
            &config,
            0.0,
        );
        assert!(
            out.starts_with("error: ") && out.contains("line"),
            "{name}: {out}"
        );
        let by_rate = RecordingFormat {
            angle: AngleSource::Rate {
                start_angle_deg: 0.0,
            },
            ..format.clone()
        };
        check(
            &format!("{name}-rate.csv"),
            text.as_bytes(),
            &by_rate,
            rate,
            &config,
            0.0,
        );
    }
    let order = FitConfig {
        order: 99,
        ..config
    };
    let text = recording_text(n, |_, _| {});
    check(
        "order.csv",
        text.as_bytes(),
        &format,
        RATE_DEG_S,
        &order,
        0.0,
    );
}

/// Environment variable that makes the memory test's child analyse the file it names.
const CHILD: &str = "CENTRIFUGE_CAL_STREAM_MEMORY_CHILD";
/// Rows of the memory test's recording: 8 M rows hold 192 MB of samples in memory.
const BIG_ROWS: usize = 8_000_000;
/// Peak resident memory the streamed analysis of that recording must stay under.
const BOUND_KIB: u64 = 64 * 1024;

/// Writes a long recording row by row (30 deg/s, 1 kHz, encoder), never held in memory
/// ([`recording::write_long_recording`]).
fn write_big(path: &Path, rows: usize) {
    let file = std::fs::File::create(path).unwrap();
    recording::write_long_recording(std::io::BufWriter::with_capacity(1 << 16, file), rows)
        .unwrap();
}

/// The peak resident memory of this process, KiB (`VmHWM` of /proc/self/status).
fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// The streamed analysis of a recording whose samples would take 192 MB in memory peaks
/// under 64 MiB: measured in a child process of its own (this test binary run again on
/// this test alone), whose peak resident memory (`VmHWM`) is the analysis's, not the
/// writer's or another test's. Not timed: only memory is asserted.
#[test]
fn streamed_analysis_holds_bounded_memory() {
    if let Ok(path) = std::env::var(CHILD) {
        let format = RecordingFormat::default();
        let done = analyze_recording_file(
            Path::new(&path),
            &format,
            RATE_DEG_S.to_radians(),
            &FitConfig::default(),
            StreamOptions {
                angle_zero_rad: 0.0,
                stream_from_bytes: 0,
            },
            &mut |_| {},
        )
        .unwrap();
        assert!(done.streamed);
        assert_eq!(done.samples, BIG_ROWS);
        // To the parent, which reads this process's standard output.
        use std::io::Write as _;
        writeln!(
            std::io::stdout(),
            "revolutions={} peak_kib={}",
            done.analysis.analysis.revolutions_used(),
            peak_rss_kib().unwrap_or(u64::MAX)
        )
        .unwrap();
        return;
    }
    if peak_rss_kib().is_none() {
        // No /proc/self/status here: the memory bound is checked on Linux.
        return;
    }
    let path = write("big.csv", b"");
    write_big(&path, BIG_ROWS);
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "stream::streamed_analysis_holds_bounded_memory",
            "--exact",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(CHILD, &path)
        .output()
        .unwrap();
    std::fs::remove_file(&path).unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let field = |key: &str| -> u64 {
        let at = stdout
            .find(key)
            .unwrap_or_else(|| panic!("{key} in {stdout}"))
            + key.len();
        stdout[at..]
            .split(|c: char| !c.is_ascii_digit())
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    // 8 M samples at 12,000 a revolution: 666 whole ones.
    assert_eq!(field("revolutions="), 666);
    let peak = field("peak_kib=");
    assert!(
        peak < BOUND_KIB,
        "peak resident memory {peak} KiB, bound {BOUND_KIB} KiB (the samples alone are 192 MB)"
    );
}
