//! Probe recordings: the format, parse errors with their lines, streaming, the fixture and
//! the analysis's errors.

use std::path::Path;

use harmonics::{HarmonicsError, SpindleAngle};
use recording::{
    AngleSource, AngleUnit, Column, Delimiter, GapUnit, LengthUnit, Recording, RecordingError,
    RecordingFormat, SyntheticSpec, TimeUnit, analyze_recording, load_recording, parse_recording,
};

/// Bytes read from a file at a time.
const CHUNK_BYTES: usize = 1 << 20;
/// Longest line accepted.
const MAX_LINE_BYTES: usize = 16 << 20;
/// Pieces of text at least this long are parsed on two threads.
const PARALLEL_BYTES: usize = 256 * 1024;

fn parse(text: &str) -> Result<Recording, RecordingError> {
    parse_recording(
        text.as_bytes(),
        Path::new("rec.csv"),
        &RecordingFormat::default(),
    )
}

/// The message of an error and of each of its sources, joined by `: `.
fn chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        text = format!("{text}: {s}");
        source = s.source();
    }
    text
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
        time: Column {
            column: "t".into(),
            unit: TimeUnit::S,
        },
        gap: Column {
            column: "d".into(),
            unit: GapUnit::Mm,
        },
        angle: AngleSource::Encoder {
            column: "phi".into(),
            unit: AngleUnit::Rad,
            optional: false,
        },
        delimiter: Delimiter::Char(';'),
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
        delimiter: Delimiter::Whitespace,
        ..RecordingFormat::default()
    };
    let text = "time_s   gap_um\n 0.0   1.0\n0.001\t 2.0  \n";
    let rec = parse_recording(text.as_bytes(), Path::new("r.txt"), &format).unwrap();
    assert_eq!(rec.gap, [1.0, 2.0]);
    assert!(rec.angle_rad.is_none());
}

#[test]
fn ron_format_with_defaults() {
    let f: RecordingFormat =
        ron::from_str("(gap: (column: \"gap_um\", unit: mm), delimiter: ';')").unwrap();
    assert_eq!(f.gap.unit, GapUnit::Mm);
    assert_eq!(f.delimiter, Delimiter::Char(';'));
    assert_eq!(f.time.column, "time_s");
    assert!(ron::from_str::<RecordingFormat>("(gap_unit: mm)").is_err());
    let f: RecordingFormat = ron::from_str("(delimiter: whitespace)").unwrap();
    assert_eq!(f.delimiter, Delimiter::Whitespace);
    let f: RecordingFormat =
        ron::from_str("(delimiter: '\\t', angle: index_pulse(column: \"Index\"))").unwrap();
    assert_eq!(f.delimiter, Delimiter::Char('\t'));
    assert_eq!(
        f.angle,
        AngleSource::IndexPulse {
            column: "Index".into()
        }
    );
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
        Err(RecordingError::NoRows { line: 1, .. })
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
    // Every sample's line, past comments, blank lines and chunk boundaries.
    let mut data_lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .map(|(i, _)| i + 1)
        .skip(1); // the header
    for i in 0..loaded.len() {
        assert_eq!(
            loaded.line_of_sample(i),
            data_lines.next().unwrap(),
            "sample {i}"
        );
    }
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
    // A gap, found after the parse, is located by the row → line table.
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
    assert!(text.len() >= 2 * PARALLEL_BYTES);
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
    assert_eq!(e.to_string(), "/nonexistent/rec.csv: cannot read");
    // The I/O error is the source, not part of the message.
    let source = std::error::Error::source(&e).unwrap();
    assert!(source.downcast_ref::<std::io::Error>().is_some());
}

#[test]
fn bad_format() {
    let format = RecordingFormat {
        delimiter: Delimiter::Char('.'),
        ..RecordingFormat::default()
    };
    let e = parse_recording(b"time_s.gap_um\n", Path::new("r"), &format).unwrap_err();
    assert!(matches!(
        e,
        RecordingError::InvalidDelimiter { delimiter: '.' }
    ));
    let format = RecordingFormat {
        max_gap_intervals: 0.5,
        ..RecordingFormat::default()
    };
    let e = parse_recording(
        b"time_s,gap_um
",
        Path::new("r"),
        &format,
    )
    .unwrap_err();
    assert!(matches!(e, RecordingError::InvalidGapLimit { value: 0.5 }));
}

#[test]
fn fixture_is_the_generator_output_and_gives_its_coefficients() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/recordings/probe_120deg_s.csv");
    let spec = SyntheticSpec::default();
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        text,
        spec.csv().unwrap(),
        "regenerate with the synth_recording example"
    );
    assert!(text.len() < 300_000);
    let rec = load_recording(&path, &RecordingFormat::default()).unwrap();
    let fit =
        analyze_recording(&rec, 120f64.to_radians(), &harmonics::FitConfig::default()).unwrap();
    assert_eq!(fit.analysis.revolutions_used(), 2);
    assert!(fit.analysis.incomplete.is_some());
    let n = fit
        .analysis
        .revolutions
        .iter()
        .map(|r| r.samples)
        .sum::<usize>() as f64;
    let bound = 6.0 * spec.noise_um * (2.0 / n).sqrt();
    for k in 0..4 {
        approx::assert_abs_diff_eq!(
            fit.analysis.mean.c[k],
            spec.coefficients.c[k],
            epsilon = bound
        );
        approx::assert_abs_diff_eq!(
            fit.analysis.mean.s[k],
            spec.coefficients.s[k],
            epsilon = bound
        );
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
    let e =
        analyze_recording(&rec, 120f64.to_radians(), &harmonics::FitConfig::default()).unwrap_err();
    assert!(
        matches!(
            e,
            RecordingError::Samples {
                source: HarmonicsError::NoCompleteRevolution { .. },
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
    let e =
        analyze_recording(&rec, 120f64.to_radians(), &harmonics::FitConfig::default()).unwrap_err();
    assert!(
        matches!(
            e,
            RecordingError::Samples {
                line: Some(103),
                source: HarmonicsError::AngleNotIncreasing { index: 100, .. },
                ..
            }
        ),
        "{e}"
    );
    assert!(
        e.to_string().ends_with(
            "back.csv:103: cannot analyse the samples (hint: encoder in counts? set \
             `angle: encoder(column: ..., unit: counts(per_rev: N))`)"
        ),
        "{e}"
    );
    assert!(
        chain(&e).contains("unit: counts(per_rev: N))`): sample 100"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn encoder_file_at_another_rate_than_declared_is_refused() {
    let spec = SyntheticSpec::default(); // 120 deg/s, with an encoder and speed ripple
    let rec = parse(&spec.csv().unwrap()).unwrap();
    let config = harmonics::FitConfig::default();
    assert!(analyze_recording(&rec, 120f64.to_radians(), &config).is_ok());
    assert!(analyze_recording(&rec, 118f64.to_radians(), &config).is_ok());
    let e = analyze_recording(&rec, 10f64.to_radians(), &config).unwrap_err();
    match &e {
        RecordingError::Samples {
            line: None,
            source:
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
        chain(&e).starts_with("rec.csv: cannot analyse the samples: declared spindle rate"),
        "{}",
        chain(&e)
    );
    // Without the encoder column the rate gives the angle and nothing is compared.
    let no_encoder = SyntheticSpec {
        encoder: false,
        ..spec
    };
    let rec = parse(&no_encoder.csv().unwrap()).unwrap();
    assert!(analyze_recording(&rec, 120f64.to_radians(), &config).is_ok());
}

#[test]
fn overflowing_time_intervals_are_an_error() {
    let e = parse("time_s,gap_um\n-1e308,1\n1e308,1\n").unwrap_err();
    assert!(
        matches!(
            e,
            RecordingError::Samples {
                line: Some(3),
                source: HarmonicsError::NonFiniteInterval { index: 1, .. },
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn signal_uses_the_encoder_when_present() {
    let rec = parse("time_s,gap_um,angle_deg\n0,1,10\n0.001,1,11\n").unwrap();
    assert!(matches!(rec.signal(1.0).angle, SpindleAngle::Encoder(_)));
    let rec = parse("time_s,gap_um\n0,1\n0.001,1\n").unwrap();
    assert_eq!(
        rec.signal(2.0).angle,
        SpindleAngle::Rate {
            rate_rad_s: 2.0,
            start_angle_rad: 0.0
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
        assert!(matches!(e, RecordingError::NoRows { .. }), "{text:?}: {e}");
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
        delimiter: Delimiter::Whitespace,
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

/// Found by the `csv_probe` fuzz target: a lone CR between blanks of a blank-delimited row
/// was a skipped field for the fast path and whitespace for the slow one, so the same file
/// gave two different errors. Both paths now read it alike.
#[test]
fn fast_and_slow_paths_agree_on_a_lone_cr_between_blanks() {
    let format = RecordingFormat {
        delimiter: recording::Delimiter::Whitespace,
        ..RecordingFormat::default()
    };
    for text in [
        &b"time_s gs gap_um\r\n1 \r .0\n.?\r\n"[..],
        b"time_s gs gap_um\r\n0 x 1\r\n0.001 \r 2\r\n",
        b"time_s gs gap_um\n0 \x0c 1\n0.001 y 2\n",
    ] {
        let path = Path::new("r.txt");
        let fast = parse_recording(text, path, &format).map_err(|e| e.to_string());
        let reference =
            recording::parse_recording_reference(text, path, &format).map_err(|e| e.to_string());
        assert_eq!(fast, reference, "{}", String::from_utf8_lossy(text));
    }
}

#[test]
fn quoted_numbers_are_read() {
    let rec = parse("\"time_s\",\"gap_um\"\n\"0.000000\",\"1.5\"\n\"0.001\", \"2\" \n").unwrap();
    assert_eq!(rec.time_s, [0.0, 0.001]);
    assert_eq!(rec.gap, [1.5, 2.0]);
}

#[test]
fn overlapping_column_names_are_refused() {
    for (time, gap, angle, field) in [
        ("t", "t", "a", "gap"),
        ("t", "g", "t", "angle"),
        ("t", "g", "g", "angle"),
    ] {
        let format = RecordingFormat {
            time: Column {
                column: time.into(),
                unit: TimeUnit::S,
            },
            gap: Column {
                column: gap.into(),
                unit: GapUnit::Um,
            },
            angle: AngleSource::Encoder {
                column: angle.into(),
                unit: AngleUnit::Deg,
                optional: true,
            },
            ..RecordingFormat::default()
        };
        let e = parse_recording(b"t,g\n0,1\n", Path::new("r"), &format).unwrap_err();
        assert!(
            matches!(e, RecordingError::DuplicateColumn { field: f, .. } if f == field),
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

/// The fixture's text with a comment and a blank line before every fiftieth row and the
/// encoder stepping back at sample 300; also the line of that sample.
fn commented_text_with_a_bad_sample() -> (String, usize) {
    let text = SyntheticSpec::default().csv().unwrap();
    let mut out = String::new();
    let mut row = None;
    let mut bad_line = 0;
    for l in text.lines() {
        match row {
            None => {
                out += l;
                if l.starts_with("time_s") {
                    row = Some(0);
                }
            }
            Some(r) => {
                if r % 50 == 7 {
                    out += "# operator's note\n\n";
                }
                if r == 300 {
                    let fields: Vec<&str> = l.split(',').collect();
                    let angle: f64 = fields[2].parse().unwrap();
                    bad_line = out.lines().count() + 1;
                    out += &format!("{},{},{}", fields[0], fields[1], angle - 1.0);
                } else {
                    out += l;
                }
                row = Some(r + 1);
            }
        }
        out.push('\n');
    }
    (out, bad_line)
}

#[test]
fn analysis_errors_after_comments_name_the_line_without_the_file() {
    let (text, bad_line) = commented_text_with_a_bad_sample();
    assert_eq!(bad_line, 2 + 300 + 1 + 2 * 6); // comment, header, 300 rows, 6 notes
    let dir = std::env::temp_dir().join(format!("recording-moved-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("noted.csv");
    std::fs::write(&path, &text).unwrap();
    let loaded = load_recording(&path, &RecordingFormat::default()).unwrap();
    let parsed = parse_recording(text.as_bytes(), &path, &RecordingFormat::default()).unwrap();
    assert_eq!(loaded, parsed);
    // The file is gone (renamed, then removed) before the analysis names the line.
    std::fs::rename(&path, dir.join("renamed.csv")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    for rec in [&loaded, &parsed] {
        assert_eq!(rec.line_of_sample(300), bad_line);
        let e = analyze_recording(rec, 120f64.to_radians(), &harmonics::FitConfig::default())
            .unwrap_err();
        match &e {
            RecordingError::Samples {
                line: Some(line),
                source: HarmonicsError::AngleNotIncreasing { index: 300, .. },
                ..
            } => assert_eq!(*line, bad_line),
            e => panic!("{e}"),
        }
        let prefix = format!("{}:{bad_line}: ", path.display());
        assert!(e.to_string().starts_with(&prefix), "{e}");
    }
}
