//! A NaN sample or a dropout in a TDMS or MAT probe recording (written by npTDMS and scipy:
//! fixtures/recordings/binary/make_fixtures.py) is never a silent number: by default the
//! reader refuses it naming the file, the channel and the sample index, with the hint; with
//! the recording format's `on_non_finite` / `on_gap: drop_revolution` it is read and the
//! analysis drops the revolution it touches, exactly as for the same samples in a CSV file.

use std::path::{Path, PathBuf};

use harmonics::{FitConfig, HarmonicsError};
use recording::{
    BinaryFormat, OnBadSamples, RecordingAnalysis, RecordingError, RecordingFormat,
    analyze_recording, load_recording, parse_recording,
};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/recordings")
        .join(name)
}

/// The sample the script makes NaN, and the samples it removes (0-based).
const BAD_SAMPLE: usize = 1000;
const DROPOUT: std::ops::Range<usize> = 1000..1011;

/// The CSV fixture with `row` changed (or removed) for the sample of each index.
fn csv_with(change: impl Fn(usize, &str) -> Option<String>) -> Vec<u8> {
    let text = std::fs::read_to_string(fixture("probe_120deg_s.csv")).unwrap();
    let mut out = String::new();
    let mut sample = 0;
    for line in text.lines() {
        if line.starts_with('#') || line.starts_with("time_s") {
            out += line;
            out.push('\n');
            continue;
        }
        if let Some(l) = change(sample, line) {
            out += &l;
            out.push('\n');
        }
        sample += 1;
    }
    out.into_bytes()
}

fn analyze(rec: &recording::Recording) -> RecordingAnalysis {
    analyze_recording(rec, 120f64.to_radians(), &FitConfig::default()).unwrap()
}

/// The binary file and the CSV with the same samples, read with the same policy, analyse
/// to the same revolutions and coefficients.
fn assert_same_analysis(file: &str, csv: &[u8], format: &RecordingFormat) {
    for ext in ["tdms", "mat"] {
        let path = fixture(&format!("binary/{file}.{ext}"));
        let binary = load_recording(&path, format).unwrap();
        assert_eq!(binary.on_gap, format.on_gap);
        assert_eq!(binary.on_non_finite, format.on_non_finite);
        let text = parse_recording(csv, Path::new("same.csv"), format).unwrap();
        let (a, b) = (analyze(&binary), analyze(&text));
        assert_eq!(a.dropped_revolutions, 1, "{ext}");
        assert_eq!(a.dropped_revolutions, b.dropped_revolutions, "{ext}");
        assert_eq!(
            a.analysis.revolutions_used(),
            b.analysis.revolutions_used(),
            "{ext}"
        );
        let (ma, mb) = (&a.analysis.mean, &b.analysis.mean);
        let d = std::iter::once((ma.l0, mb.l0))
            .chain(ma.c.iter().copied().zip(mb.c.iter().copied()))
            .chain(ma.s.iter().copied().zip(mb.s.iter().copied()))
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        assert!(d <= 1e-12, "{ext}: coefficients differ by {d:e} um");
    }
}

#[test]
fn a_nan_sample_is_refused_by_channel_and_index_or_its_revolution_dropped() {
    for (ext, format) in [("tdms", BinaryFormat::Tdms), ("mat", BinaryFormat::Mat)] {
        let path = fixture(&format!("binary/probe_120deg_s_nan.{ext}"));
        let e = load_recording(&path, &RecordingFormat::default()).unwrap_err();
        match &e {
            RecordingError::NonFiniteSample {
                path: p,
                format: f,
                channel,
                index,
                ..
            } => {
                assert_eq!((p, *f), (&path, format));
                assert_eq!((channel.as_str(), *index), ("gap_um", BAD_SAMPLE));
            }
            other => panic!("{ext}: {other:?}"),
        }
        let message = e.to_string();
        assert!(
            message.contains("sample 1000") && message.contains("on_non_finite: drop_revolution"),
            "{message}"
        );
    }
    let csv = csv_with(|i, line| {
        Some(if i == BAD_SAMPLE {
            let f: Vec<&str> = line.split(',').collect();
            format!("{},NaN,{}", f[0], f[2])
        } else {
            line.to_owned()
        })
    });
    let drop = RecordingFormat {
        on_non_finite: OnBadSamples::DropRevolution,
        ..RecordingFormat::default()
    };
    assert_same_analysis("probe_120deg_s_nan", &csv, &drop);
}

#[test]
fn a_dropout_is_refused_by_sample_index_or_its_revolution_dropped() {
    for ext in ["tdms", "mat"] {
        let path = fixture(&format!("binary/probe_120deg_s_gap.{ext}"));
        let e = load_recording(&path, &RecordingFormat::default()).unwrap_err();
        match &e {
            RecordingError::TimeAxis {
                path: p,
                channel,
                source: HarmonicsError::SampleGap { index, .. },
                ..
            } => {
                assert_eq!(p, &path);
                assert_eq!(channel, "time_s");
                assert_eq!(*index, DROPOUT.start, "{ext}");
            }
            other => panic!("{ext}: {other:?}"),
        }
        assert!(e.to_string().contains("on_gap: drop_revolution"), "{e}");
        // A limit above the dropout reads it as it is (the format's own limit, as for CSV).
        let wide = RecordingFormat {
            max_gap_intervals: 20.0,
            ..RecordingFormat::default()
        };
        let rec = load_recording(&path, &wide).unwrap();
        assert_eq!(rec.max_gap_intervals, 20.0);
    }
    let csv = csv_with(|i, line| (!DROPOUT.contains(&i)).then(|| line.to_owned()));
    let drop = RecordingFormat {
        on_gap: OnBadSamples::DropRevolution,
        ..RecordingFormat::default()
    };
    assert_same_analysis("probe_120deg_s_gap", &csv, &drop);
}
