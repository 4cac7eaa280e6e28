//! Probe recordings: delimited text files of time, probe gap and, optionally, the spindle
//! encoder's angle, one sample per row (the raw data behind eq. 20).
//!
//! A file is streamed through one reused buffer of about a megabyte and parsed in a single
//! pass without an allocation per row: fields are parsed in place by a fast decimal parser
//! (exact for up to 19 significant digits and exponents within ±22, the standard library's
//! parser otherwise). Lines end with LF, CRLF, or (in a file whose first line end is one) a
//! lone CR; a leading UTF-8 byte-order mark is skipped; fields may be quoted. Errors name the
//! file and the 1-based line.
//!
//! ```
//! use recording::{parse_recording, RecordingFormat};
//! let text = "# probe at 10 deg/s\ntime_s,gap_um,angle_deg\n0.000,12.5,359.9\n0.001,12.6,0.1\n";
//! let rec = parse_recording(text.as_bytes(), "probe.csv".as_ref(), &RecordingFormat::default())?;
//! assert_eq!(rec.time_s, [0.0, 0.001]);
//! approx::assert_relative_eq!(rec.angle_rad.as_ref().unwrap()[1], 0.1f64.to_radians());
//! # Ok::<(), recording::RecordingError>(())
//! ```

mod error;
mod format;
mod lines;
mod number;
mod rows;
#[cfg(feature = "synthetic")]
mod synth;
mod write;

use std::path::{Path, PathBuf};

use harmonics::{HarmonicsError, ProbeSignal, SpindleAngle};

pub use error::{RecordingError, Result};
pub use format::{AngleUnit, LengthUnit, RecordingFormat};
#[cfg(feature = "synthetic")]
pub use synth::SyntheticSpec;
pub use write::{ProbeColumns, WriteOptions, write_probe_csv};

use lines::{BOM, line_of_row, lone_cr_line_ends, normalized};
use rows::RowParser;

/// A probe recording in memory.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// The file it was read from.
    pub path: PathBuf,
    /// Sample times, s (strictly increasing, no gap above the format's limit).
    pub time_s: Vec<f64>,
    /// Probe gap of each sample, in [`Recording::gap_unit`].
    pub gap: Vec<f64>,
    /// Unit of [`Recording::gap`].
    pub gap_unit: LengthUnit,
    /// Encoder angle of each sample, rad, when the file has the angle column.
    pub angle_rad: Option<Vec<f64>>,
}

impl Recording {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }

    /// Whether there are no samples (never true for a loaded recording).
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }

    /// The samples as a [`ProbeSignal`]: angles from the encoder column when present, else
    /// `θ = ω·(t − t₀) + θ₀` from the given rate and first-sample angle.
    pub fn signal(&self, rate_rad_s: f64, start_angle_rad: f64) -> ProbeSignal<'_> {
        let angle = match &self.angle_rad {
            Some(a) => SpindleAngle::Encoder(a),
            None => SpindleAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            },
        };
        ProbeSignal {
            time_s: &self.time_s,
            gap: &self.gap,
            angle,
        }
    }
}

/// Fits eq. 20 per revolution to a loaded recording ([`harmonics::analyze`]), with the angle
/// from the encoder column when present, else from the rate; an error naming a sample is
/// given the sample's line in the file.
///
/// With an encoder column, the encoder's mean rate must match `rate_rad_s` within
/// [`harmonics::ENCODER_RATE_TOLERANCE`] (2 %), else [`HarmonicsError::RateMismatch`]: a
/// study fits with the declared rate, so a file attached to the wrong rate point is refused.
pub fn analyze_recording(
    recording: &Recording,
    rate_rad_s: f64,
    start_angle_rad: f64,
    config: &harmonics::FitConfig,
) -> Result<harmonics::HarmonicAnalysis, RecordingError> {
    let located = |source: HarmonicsError| {
        let line = sample_index(&source).and_then(|row| {
            let text = std::fs::read(&recording.path).ok()?;
            Some(line_of_row(&text, row))
        });
        RecordingError::Samples {
            path: recording.path.clone(),
            line,
            error: source,
        }
    };
    let signal = recording.signal(rate_rad_s, start_angle_rad);
    let analysis = harmonics::analyze(&signal, config).map_err(located)?;
    // The encoder gives the angle, but the declared rate is the ω a study fits with.
    harmonics::check_encoder_rate(&signal, rate_rad_s, harmonics::ENCODER_RATE_TOLERANCE)
        .map_err(located)?;
    Ok(analysis)
}

/// The sample an analysis error names, if any.
fn sample_index(error: &HarmonicsError) -> Option<usize> {
    match error {
        HarmonicsError::NonFinite { index, .. }
        | HarmonicsError::NonFiniteInterval { index, .. }
        | HarmonicsError::TimeNotIncreasing { index, .. }
        | HarmonicsError::SampleGap { index, .. }
        | HarmonicsError::AngleNotIncreasing { index, .. } => Some(*index),
        HarmonicsError::TooFewSamples { first_sample, .. } => Some(*first_sample),
        HarmonicsError::Aliasing { after_sample, .. } => Some(*after_sample),
        _ => None,
    }
}

/// Bytes read from the file at a time by [`load_recording`].
const CHUNK_BYTES: usize = 1 << 20;

/// Longest line [`load_recording`] accepts, bytes (16 MiB): a file without a line end
/// within it is refused rather than read whole.
pub(crate) const MAX_LINE_BYTES: usize = 16 << 20;

/// Reads a probe recording from a file, streaming it through one reused buffer of about
/// a megabyte (whole lines are parsed; a partial last line waits for the next read). A
/// line longer than 16 MiB is refused ([`RecordingError::LineTooLong`]).
pub fn load_recording(path: &Path, format: &RecordingFormat) -> Result<Recording, RecordingError> {
    use std::io::Read as _;
    let io = |error| RecordingError::Io {
        path: path.to_owned(),
        error,
    };
    let mut file = std::fs::File::open(path).map_err(io)?;
    let size = file.metadata().map_or(0, |m| m.len() as usize);
    let mut parser = RowParser::new(path, format, size)?;
    let mut buf: Vec<u8> = Vec::with_capacity(CHUNK_BYTES + 64 * 1024);
    let mut eof = false;
    let mut start = true;
    // Whether line ends are lone CRs (decided at the first line end), and how much of the
    // buffer is known to hold no line end (so that a long line is scanned once).
    let mut lone_cr = None;
    let mut scanned: usize = 0;
    while !eof {
        // Top the buffer up to a chunk, or double it while one line is longer than that.
        let target = if scanned > 0 {
            (2 * buf.len()).max(CHUNK_BYTES)
        } else {
            CHUNK_BYTES
        };
        while buf.len() < target {
            let old = buf.len();
            buf.resize(target, 0);
            let got = file.read(&mut buf[old..]).map_err(io)?;
            buf.truncate(old + got);
            if got == 0 {
                eof = true;
                break;
            }
        }
        if start {
            if buf.starts_with(BOM) {
                buf.drain(..BOM.len());
            }
            start = false;
        }
        if lone_cr.is_none() {
            lone_cr = lone_cr_line_ends(&buf, eof);
        }
        // A CR at the end of the part already scanned may just have been found lone.
        let from = scanned.saturating_sub(1);
        if lone_cr == Some(true) {
            for b in &mut buf[from..] {
                if *b == b'\r' {
                    *b = b'\n';
                }
            }
        }
        let last_end = buf[from..]
            .iter()
            .rposition(|&b| b == b'\n')
            .map(|i| from + i + 1);
        if last_end.is_none() && buf.len() > MAX_LINE_BYTES {
            return Err(RecordingError::LineTooLong {
                path: path.to_owned(),
                line: parser.line + 1,
                max_bytes: MAX_LINE_BYTES,
            });
        }
        let complete = match (eof, last_end) {
            (true, _) => buf.len(),
            (false, Some(end)) => end,
            (false, None) => {
                scanned = buf.len();
                continue;
            }
        };
        parser.feed(&buf[..complete])?;
        buf.drain(..complete);
        scanned = 0;
    }
    parser.finish(None)
}

/// Parses a probe recording held in memory; `path` names it in errors.
pub fn parse_recording(
    text: &[u8],
    path: &Path,
    format: &RecordingFormat,
) -> Result<Recording, RecordingError> {
    let text = normalized(text);
    let mut parser = RowParser::new(path, format, text.len())?;
    parser.feed(&text)?;
    parser.finish(Some(&text))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Recording, RecordingError> {
        parse_recording(
            text.as_bytes(),
            Path::new("rec.csv"),
            &RecordingFormat::default(),
        )
    }

    fn rows(n: usize) -> String {
        let mut s = String::from("time_s,gap_um\n");
        for i in 0..n {
            s += &format!("{},{}\n", i as f64 * 0.001, 10.0 + (i as f64).sin());
        }
        s
    }

    #[test]
    fn default_columns_comments_blank_lines_and_crlf() {
        let text = "# a comment\r\n\r\n time_s , gap_um ,angle_deg\r\n0.0,1.5,359.0\r\n# mid comment\r\n0.001,-2e-1,1.0\r\n0.002,3,2";
        let rec = parse(text).unwrap();
        assert_eq!(rec.time_s, [0.0, 0.001, 0.002]);
        assert_eq!(rec.gap, [1.5, -0.2, 3.0]);
        let a = rec.angle_rad.unwrap();
        approx::assert_relative_eq!(a[0], 359f64.to_radians(), max_relative = 1e-15);
        approx::assert_relative_eq!(a[2], 2f64.to_radians(), max_relative = 1e-15);
        assert_eq!(rec.gap_unit, LengthUnit::Um);
    }

    #[test]
    fn configured_names_units_delimiter_and_column_order() {
        let format = RecordingFormat {
            time_column: "t".into(),
            gap_column: "d".into(),
            angle_column: "phi".into(),
            gap_unit: LengthUnit::Mm,
            angle_unit: AngleUnit::Rad,
            delimiter: ';',
            ..RecordingFormat::default()
        };
        let text = "phi;extra;d;t\n0.5;x;0.0125;10\n0.6;y;0.0126;10.001\n";
        let rec = parse_recording(text.as_bytes(), Path::new("r.txt"), &format).unwrap();
        assert_eq!(rec.time_s, [10.0, 10.001]);
        assert_eq!(rec.gap, [0.0125, 0.0126]);
        assert_eq!(rec.gap_unit.um_per_unit(), 1e3);
        assert_eq!(rec.angle_rad.unwrap(), [0.5, 0.6]);
        // Blank-separated, runs of blanks count once.
        let format = RecordingFormat {
            delimiter: ' ',
            ..RecordingFormat::default()
        };
        let text = "time_s   gap_um\n 0.0   1.0\n0.001\t 2.0  \n";
        let rec = parse_recording(text.as_bytes(), Path::new("r.txt"), &format).unwrap();
        assert_eq!(rec.gap, [1.0, 2.0]);
        assert!(rec.angle_rad.is_none());
    }

    #[test]
    fn ron_format_with_defaults() {
        let f: RecordingFormat = ron::from_str("(gap_unit: mm, delimiter: ';')").unwrap();
        assert_eq!(f.gap_unit, LengthUnit::Mm);
        assert_eq!(f.time_column, "time_s");
        assert!(ron::from_str::<RecordingFormat>("(gap_units: mm)").is_err());
    }

    #[test]
    fn empty_file() {
        for text in ["", "\n\n", "# only a comment\n  \n"] {
            assert!(
                matches!(parse(text), Err(RecordingError::Empty { .. })),
                "{text:?}"
            );
        }
        assert!(matches!(
            parse("time_s,gap_um\n# nothing\n"),
            Err(RecordingError::NoSamples { line: 1, .. })
        ));
    }

    #[test]
    fn missing_columns() {
        let e = parse("time_s,gap_mm\n0,1\n").unwrap_err();
        match &e {
            RecordingError::MissingColumn {
                line: 1,
                column,
                header,
                ..
            } => {
                assert_eq!(column, "gap_um");
                assert_eq!(header, &["time_s", "gap_mm"]);
            }
            e => panic!("{e}"),
        }
        assert!(
            e.to_string().starts_with("rec.csv:1: no column `gap_um`"),
            "{e}"
        );
        assert!(matches!(
            parse("t,gap_um\n0,1\n"),
            Err(RecordingError::MissingColumn { .. })
        ));
        let e = parse("time_s,gap_um\n0,1\n0.001\n").unwrap_err();
        assert!(
            matches!(&e, RecordingError::MissingField { line: 3, column, .. } if column == "gap_um"),
            "{e}"
        );
    }

    #[test]
    fn unparsable_numbers() {
        let e = parse("time_s,gap_um\n0,1\n0.001,1.2.3\n").unwrap_err();
        assert!(
            matches!(&e, RecordingError::Parse { line: 3, column, text, .. } if column == "gap_um" && text == "1.2.3"),
            "{e}"
        );
        assert_eq!(
            e.to_string(),
            "rec.csv:3: column `gap_um`: cannot parse \"1.2.3\" as a number"
        );
        let e = parse("# c\ntime_s,gap_um\n0,1\nzero,1\n").unwrap_err();
        assert!(
            matches!(&e, RecordingError::Parse { line: 4, column, .. } if column == "time_s"),
            "{e}"
        );
    }

    #[test]
    fn nan_and_infinite_values() {
        let e = parse("time_s,gap_um\n0,1\n0.001,NaN\n").unwrap_err();
        assert!(
            matches!(&e, RecordingError::NonFinite { line: 3, column, .. } if column == "gap_um"),
            "{e}"
        );
        let e = parse("time_s,gap_um,angle_deg\n0,1,0\n0.001,1,inf\n").unwrap_err();
        assert!(
            matches!(&e, RecordingError::NonFinite { line: 3, column, .. } if column == "angle_deg"),
            "{e}"
        );
        let e = parse("time_s,gap_um\n-inf,1\n").unwrap_err();
        assert!(
            matches!(e, RecordingError::NonFinite { line: 2, .. }),
            "{e}"
        );
    }

    #[test]
    fn time_not_increasing() {
        let e = parse("time_s,gap_um\n0,1\n0.001,1\n# c\n0.001,1\n").unwrap_err();
        assert!(
            matches!(e, RecordingError::TimeNotIncreasing { line: 5, .. }),
            "{e}"
        );
        let e = parse("time_s,gap_um\n0,1\n-0.001,1\n").unwrap_err();
        assert!(
            matches!(e, RecordingError::TimeNotIncreasing { line: 3, .. }),
            "{e}"
        );
    }

    #[test]
    fn gap_of_several_sample_intervals() {
        let mut text = String::from("time_s,gap_um\n# header comment\n");
        for i in 0..100 {
            let t = if i < 60 {
                i as f64 * 0.001
            } else {
                (i + 4) as f64 * 0.001
            };
            text += &format!("{t},1\n");
        }
        let e = parse(&text).unwrap_err();
        match e {
            // Row 60 (0-based) is on line 2 + 1 + 60 = 63.
            RecordingError::SampleGap {
                line,
                interval_s,
                nominal_interval_s,
                ..
            } => {
                assert_eq!(line, 63);
                approx::assert_relative_eq!(interval_s, 0.005, max_relative = 1e-9);
                approx::assert_relative_eq!(nominal_interval_s, 0.001, max_relative = 1e-9);
            }
            e => panic!("{e}"),
        }
        assert!(parse(&rows(100)).is_ok());
    }

    #[test]
    fn streamed_file_equals_in_memory_parse() {
        // Over two chunks of comments before the header, then rows with CRLF, comments,
        // blank lines and rows the fast path declines, crossing several chunk boundaries.
        let mut text = String::new();
        while text.len() < CHUNK_BYTES + CHUNK_BYTES / 2 {
            text += "# a long preamble of comments ............................................\n";
        }
        text += "time_s,gap_um,angle_deg\r\n";
        for i in 0..120_000 {
            let t = i as f64 * 0.001;
            match i % 1000 {
                7 => text += "# comment\n\n",
                8 => text += &format!(" {t} , {} ,{}\r\n", -1.5e-3 * i as f64, (i % 360) as f64),
                _ => {
                    text += &format!(
                        "{t:.6},{:.6},{:.4}\n",
                        50.0 + (i as f64).sin(),
                        (i % 360) as f64
                    )
                }
            }
        }
        text += "120.0,1.0,2.0"; // no final line end
        let dir = std::env::temp_dir().join(format!("recording-stream-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("big.csv");
        std::fs::write(&path, &text).unwrap();
        let loaded = load_recording(&path, &RecordingFormat::default()).unwrap();
        let parsed = parse_recording(text.as_bytes(), &path, &RecordingFormat::default()).unwrap();
        assert_eq!(loaded, parsed);
        assert_eq!(loaded.len(), 120_000 - 120 + 1); // every thousandth row is a comment
        // An error deep in the file names its line when streamed too.
        let bad = text.replacen("99.999000,", "99.999000x,", 1);
        std::fs::write(&path, &bad).unwrap();
        let e = load_recording(&path, &RecordingFormat::default()).unwrap_err();
        let header_line = text.lines().position(|l| l.starts_with("time_s")).unwrap() + 1;
        let line = bad
            .lines()
            .position(|l| l.starts_with("99.999000x"))
            .unwrap()
            + 1;
        assert!(line > header_line);
        assert!(
            matches!(e, RecordingError::Parse { line: l, .. } if l == line),
            "{e}"
        );
        // A gap, found after the parse, is located by reading the file again.
        let gap: String = text
            .split_inclusive('\n')
            .filter(|l| {
                !["100.000", "100.001", "100.002", "100.003", "100.004"]
                    .iter()
                    .any(|p| l.starts_with(p))
            })
            .collect();
        std::fs::write(&path, &gap).unwrap();
        let e = load_recording(&path, &RecordingFormat::default()).unwrap_err();
        let line = gap
            .lines()
            .position(|l| l.starts_with("100.005000,"))
            .unwrap()
            + 1;
        assert!(
            matches!(e, RecordingError::SampleGap { line: l, .. } if l == line),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Fixed-width rows, so that editing a value keeps every byte offset.
    fn fixed_rows(n: usize, time_of: impl Fn(usize) -> f64) -> String {
        let mut text = String::from("time_s,gap_um\n");
        for i in 0..n {
            text += &format!(
                "{:014.6},{:09.6}\n",
                time_of(i),
                50.0 + (i as f64 * 0.01).sin()
            );
        }
        text
    }

    #[test]
    fn parallel_halves_join_in_order_and_locate_errors() {
        let n = 40_000; // 1 MB: parsed in two halves
        let text = fixed_rows(n, |i| i as f64 * 0.001);
        assert!(text.len() >= 2 * rows::PARALLEL_BYTES);
        let rec = parse(&text).unwrap();
        assert_eq!(rec.len(), n);
        assert!(rec.time_s.windows(2).all(|w| w[1] > w[0]));
        assert_eq!(rec.time_s[n - 1], (n - 1) as f64 * 0.001);
        // Where the halves meet: the row starting after the line end past the middle.
        let header_end = text.find('\n').unwrap() + 1;
        let mid = header_end + (text.len() - header_end) / 2;
        let cut = mid + text[mid..].find('\n').unwrap() + 1;
        let row_at_cut = text[header_end..cut].matches('\n').count();
        let line_at_cut = row_at_cut + 2;
        // A time that steps back exactly at the join, inside the second half, and inside
        // the first half: each names its own line.
        for row in [row_at_cut, row_at_cut + 1000, row_at_cut - 1000] {
            let bad = fixed_rows(n, |i| {
                if i >= row {
                    i as f64 * 0.001 - 1.0
                } else {
                    i as f64 * 0.001
                }
            });
            let e = parse(&bad).unwrap_err();
            assert!(
                matches!(e, RecordingError::TimeNotIncreasing { line, .. } if line == row + 2),
                "row {row}: {e}"
            );
        }
        // Parse errors and non-finite values in the second half name their line.
        let lines: Vec<&str> = text.lines().collect();
        let target = line_at_cut + 500;
        let broken = text.replacen(lines[target - 1], &lines[target - 1].replace(',', ";"), 1);
        let e = parse(&broken).unwrap_err();
        assert!(
            matches!(e, RecordingError::Parse { line, .. } if line == target),
            "{e}"
        );
        let nan = text.replacen(
            lines[target - 1],
            &format!("{},NaN", &lines[target - 1][..14]),
            1,
        );
        let e = parse(&nan).unwrap_err();
        assert!(
            matches!(e, RecordingError::NonFinite { line, .. } if line == target),
            "{e}"
        );
    }

    #[test]
    fn io_error_names_the_file() {
        let e = load_recording(
            Path::new("/nonexistent/rec.csv"),
            &RecordingFormat::default(),
        )
        .unwrap_err();
        assert!(matches!(e, RecordingError::Io { .. }));
        assert!(e.to_string().starts_with("/nonexistent/rec.csv: "), "{e}");
    }

    #[test]
    fn bad_format() {
        let format = RecordingFormat {
            delimiter: '.',
            ..RecordingFormat::default()
        };
        let e = parse_recording(b"time_s.gap_um\n", Path::new("r"), &format).unwrap_err();
        assert!(matches!(
            e,
            RecordingError::InvalidFormat {
                field: "delimiter",
                ..
            }
        ));
    }

    #[test]
    fn fixture_is_the_generator_output_and_gives_its_coefficients() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../fixtures/recordings/probe_120deg_s.csv");
        let spec = SyntheticSpec::default();
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            text,
            spec.csv().unwrap(),
            "regenerate with the synth_recording example"
        );
        assert!(text.len() < 300_000);
        let rec = load_recording(&path, &RecordingFormat::default()).unwrap();
        let fit = analyze_recording(
            &rec,
            120f64.to_radians(),
            0.0,
            &harmonics::FitConfig::default(),
        )
        .unwrap();
        assert_eq!(fit.revolutions_used(), 2);
        assert!(fit.incomplete.is_some());
        let n = fit.revolutions.iter().map(|r| r.samples).sum::<usize>() as f64;
        let bound = 6.0 * spec.noise_um * (2.0 / n).sqrt();
        for k in 0..4 {
            approx::assert_abs_diff_eq!(fit.mean.c[k], spec.coefficients.c[k], epsilon = bound);
            approx::assert_abs_diff_eq!(fit.mean.s[k], spec.coefficients.s[k], epsilon = bound);
        }
    }

    #[test]
    fn analysis_errors_name_the_line() {
        let dir = std::env::temp_dir().join(format!("recording-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // Half a revolution: no complete revolution.
        let spec = SyntheticSpec {
            revolutions: 0.5,
            ..SyntheticSpec::default()
        };
        let path = dir.join("half.csv");
        std::fs::write(&path, spec.csv().unwrap()).unwrap();
        let rec = load_recording(&path, &RecordingFormat::default()).unwrap();
        let e = analyze_recording(
            &rec,
            120f64.to_radians(),
            0.0,
            &harmonics::FitConfig::default(),
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                RecordingError::Samples {
                    error: HarmonicsError::NoCompleteRevolution { .. },
                    ..
                }
            ),
            "{e}"
        );
        // An encoder stepping back at row 100, line 103 (after the comment and the header).
        let mut text = SyntheticSpec::default().csv().unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let fields: Vec<&str> = lines[102].split(',').collect();
        let back = format!(
            "{},{},{}",
            fields[0],
            fields[1],
            fields[2].parse::<f64>().unwrap() - 1.0
        );
        text = text.replacen(lines[102], &back, 1);
        let path = dir.join("back.csv");
        std::fs::write(&path, &text).unwrap();
        let rec = load_recording(&path, &RecordingFormat::default()).unwrap();
        let e = analyze_recording(
            &rec,
            120f64.to_radians(),
            0.0,
            &harmonics::FitConfig::default(),
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                RecordingError::Samples {
                    line: Some(103),
                    error: HarmonicsError::AngleNotIncreasing { index: 100, .. },
                    ..
                }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("back.csv:103: sample 100"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn encoder_file_at_another_rate_than_declared_is_refused() {
        let spec = SyntheticSpec::default(); // 120 deg/s, with an encoder and speed ripple
        let rec = parse(&spec.csv().unwrap()).unwrap();
        let config = harmonics::FitConfig::default();
        assert!(analyze_recording(&rec, 120f64.to_radians(), 0.0, &config).is_ok());
        assert!(analyze_recording(&rec, 118f64.to_radians(), 0.0, &config).is_ok());
        let e = analyze_recording(&rec, 10f64.to_radians(), 0.0, &config).unwrap_err();
        match &e {
            RecordingError::Samples {
                line: None,
                error:
                    HarmonicsError::RateMismatch {
                        declared_rad_s,
                        encoder_rad_s,
                        ..
                    },
                ..
            } => {
                approx::assert_relative_eq!(*declared_rad_s, 10f64.to_radians());
                approx::assert_relative_eq!(
                    *encoder_rad_s,
                    120f64.to_radians(),
                    max_relative = 1e-2 // the ripple moves the mean by 0.3 %
                );
            }
            e => panic!("{e}"),
        }
        assert!(
            e.to_string().starts_with("rec.csv: declared spindle rate"),
            "{e}"
        );
        // Without the encoder column the rate gives the angle and nothing is compared.
        let no_encoder = SyntheticSpec {
            encoder: false,
            ..spec
        };
        let rec = parse(&no_encoder.csv().unwrap()).unwrap();
        assert!(analyze_recording(&rec, 120f64.to_radians(), 0.0, &config).is_ok());
    }

    #[test]
    fn overflowing_time_intervals_are_an_error() {
        let e = parse("time_s,gap_um\n-1e308,1\n1e308,1\n").unwrap_err();
        assert!(
            matches!(
                e,
                RecordingError::Samples {
                    line: Some(3),
                    error: HarmonicsError::NonFiniteInterval { index: 1, .. },
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn signal_uses_the_encoder_when_present() {
        let rec = parse("time_s,gap_um,angle_deg\n0,1,10\n0.001,1,11\n").unwrap();
        assert!(matches!(
            rec.signal(1.0, 0.0).angle,
            SpindleAngle::Encoder(_)
        ));
        let rec = parse("time_s,gap_um\n0,1\n0.001,1\n").unwrap();
        assert_eq!(
            rec.signal(2.0, 0.5).angle,
            SpindleAngle::Rate {
                rate_rad_s: 2.0,
                start_angle_rad: 0.5
            }
        );
    }

    #[test]
    fn header_as_last_line_without_line_end_is_no_samples() {
        for text in [
            "time_s,gap_um",
            "# c\ntime_s,gap_um\r",
            "# c\r\ntime_s,gap_um\r\n",
        ] {
            let e = parse(text).unwrap_err();
            assert!(
                matches!(e, RecordingError::NoSamples { .. }),
                "{text:?}: {e}"
            );
        }
    }

    #[test]
    fn comment_is_not_data_when_the_first_column_is_skipped() {
        let text = "label,time_s,gap_um\nx,0,1\n#note,0.0005,999\n  #note,0.0007,999\nx,0.001,2\n";
        let rec = parse(text).unwrap();
        assert_eq!(rec.time_s, [0.0, 0.001]);
        assert_eq!(rec.gap, [1.0, 2.0]);
    }

    #[test]
    fn utf8_byte_order_mark_is_skipped() {
        let rec = parse("\u{feff}time_s,gap_um\n0,1\n0.001,2\n").unwrap();
        assert_eq!(rec.gap, [1.0, 2.0]);
        let rec = parse("\u{feff}# c\ntime_s,gap_um\n0,1\n0.001,2\n").unwrap();
        assert_eq!(rec.gap, [1.0, 2.0]);
    }

    #[test]
    fn lone_carriage_returns_end_lines() {
        let text = "# c\rtime_s,gap_um\r0,1\r\r0.001,2\r0.002,3";
        let rec = parse(text).unwrap();
        assert_eq!(rec.gap, [1.0, 2.0, 3.0]);
        let e = parse("time_s,gap_um\r0,1\r0.001,x\r").unwrap_err();
        assert!(matches!(e, RecordingError::Parse { line: 3, .. }), "{e}");
    }

    #[test]
    fn fast_and_slow_paths_split_blank_delimited_fields_alike() {
        let format = RecordingFormat {
            delimiter: ' ',
            ..RecordingFormat::default()
        };
        // A tab inside the skipped first field, and a run of blanks after it.
        let text = "idx\ttime_s gap_um\n0\t0.000 47.0 0\n1\t0.001 48.0 0\n";
        let rec = parse_recording(text.as_bytes(), Path::new("r.txt"), &format).unwrap();
        assert_eq!(rec.time_s, [0.0, 0.001]);
        assert_eq!(rec.gap, [47.0, 48.0]);
        // A run of blanks after a skipped field is one separator, not an empty field.
        let text = "a b time_s gap_um\nx  5 0 1\nx  6 0.001 2\n";
        let rec = parse_recording(text.as_bytes(), Path::new("r.txt"), &format).unwrap();
        assert_eq!(rec.time_s, [0.0, 0.001]);
        assert_eq!(rec.gap, [1.0, 2.0]);
    }

    #[test]
    fn quoted_numbers_are_read() {
        let rec =
            parse("\"time_s\",\"gap_um\"\n\"0.000000\",\"1.5\"\n\"0.001\", \"2\" \n").unwrap();
        assert_eq!(rec.time_s, [0.0, 0.001]);
        assert_eq!(rec.gap, [1.5, 2.0]);
    }

    #[test]
    fn overlapping_column_names_are_refused() {
        for (time, gap, angle, field) in [
            ("t", "t", "a", "gap_column"),
            ("t", "g", "t", "angle_column"),
            ("t", "g", "g", "angle_column"),
        ] {
            let format = RecordingFormat {
                time_column: time.into(),
                gap_column: gap.into(),
                angle_column: angle.into(),
                ..RecordingFormat::default()
            };
            let e = parse_recording(b"t,g\n0,1\n", Path::new("r"), &format).unwrap_err();
            assert!(
                matches!(e, RecordingError::InvalidFormat { field: f, .. } if f == field),
                "{e}"
            );
        }
    }

    #[test]
    fn file_without_line_feeds_loads_in_linear_time() {
        let dir = std::env::temp_dir().join(format!("recording-cr-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // CR-only line ends over several chunks: read once, lines ended by CR.
        let mut text = String::from("time_s,gap_um\r");
        let mut i = 0;
        while text.len() < 3 * CHUNK_BYTES {
            text += &format!("{:.6},{:.6}\r", i as f64 * 0.001, (i as f64).sin());
            i += 1;
        }
        let path = dir.join("cr.csv");
        std::fs::write(&path, &text).unwrap();
        let start = std::time::Instant::now();
        let rec = load_recording(&path, &RecordingFormat::default()).unwrap();
        assert_eq!(rec.len(), i);
        assert_eq!(
            rec,
            parse_recording(text.as_bytes(), &path, &RecordingFormat::default()).unwrap()
        );
        // A file with no line end at all is refused once the longest line is exceeded.
        let binary = vec![b'x'; MAX_LINE_BYTES + 10];
        std::fs::write(&path, &binary).unwrap();
        let e = load_recording(&path, &RecordingFormat::default()).unwrap_err();
        assert!(
            matches!(e, RecordingError::LineTooLong { line: 1, .. }),
            "{e}"
        );
        assert!(e.to_string().contains("cr.csv"), "{e}");
        assert!(start.elapsed().as_secs_f64() < 5.0);
        // BOM in a streamed file too.
        std::fs::write(&path, "\u{feff}time_s,gap_um\n0,1\n0.001,2\n").unwrap();
        assert_eq!(
            load_recording(&path, &RecordingFormat::default())
                .unwrap()
                .gap,
            [1.0, 2.0]
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
