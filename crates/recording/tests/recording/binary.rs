//! The binary readers (TDMS, MAT): the fixtures written by npTDMS and scipy give the CSV's
//! coefficients, and every malformed file gives a typed error, never a panic.

use std::path::{Path, PathBuf};

use harmonics::{Coefficients, FitConfig, HarmonicAnalysis};
use proptest::prelude::*;
use recording::{
    BinaryChannels, BinaryFormat, Recording, RecordingError, RecordingFormat, analyze_recording,
    load_mat, load_recording, load_tdms, parse_mat, parse_tdms,
};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/recordings")
        .join(name)
}

fn binary(name: &str) -> PathBuf {
    fixture(&format!("binary/{name}"))
}

fn csv() -> Recording {
    load_recording(&fixture("probe_120deg_s.csv"), &RecordingFormat::default()).unwrap()
}

fn analyze(rec: &Recording) -> HarmonicAnalysis {
    analyze_recording(rec, 120f64.to_radians(), &FitConfig::default())
        .unwrap()
        .analysis
}

/// Largest difference between two sets of mean coefficients, µm.
fn max_difference(a: &Coefficients, b: &Coefficients) -> f64 {
    let pairs = std::iter::once((a.l0, b.l0))
        .chain(a.c.iter().copied().zip(b.c.iter().copied()))
        .chain(a.s.iter().copied().zip(b.s.iter().copied()));
    pairs.map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

fn assert_same_fit(rec: &Recording, reference: &Recording) {
    let (a, b) = (analyze(rec), analyze(reference));
    assert_eq!(a.revolutions_used(), b.revolutions_used());
    assert_eq!(a.mean.c.len(), 4);
    let d = max_difference(&a.mean, &b.mean);
    assert!(
        d <= 1e-12,
        "{}: mean coefficients differ by {d:e} um",
        rec.path.display()
    );
    for (ra, rb) in a.revolutions.iter().zip(&b.revolutions) {
        assert_eq!(ra.first_sample, rb.first_sample);
        assert!(max_difference(&ra.coefficients, &rb.coefficients) <= 1e-12);
    }
}

/// The CSV's samples as float32 would store them (time kept).
fn csv_as_f32() -> Recording {
    let mut rec = csv();
    rec.gap = rec.gap.iter().map(|&x| f64::from(x as f32)).collect();
    // The file stores degrees as float32; the reader converts to radians in f64.
    let deg: Vec<f64> = load_recording(
        &fixture("probe_120deg_s.csv"),
        &RecordingFormat {
            angle: recording::AngleSource::Encoder {
                column: "angle_deg".into(),
                unit: recording::AngleUnit::Rad,
                optional: false,
            },
            ..RecordingFormat::default()
        },
    )
    .unwrap()
    .angle_rad
    .unwrap();
    rec.angle_rad = Some(
        deg.iter()
            .map(|&d| f64::from(d as f32) * (std::f64::consts::PI / 180.0))
            .collect(),
    );
    rec
}

fn group() -> BinaryChannels {
    BinaryChannels {
        group: Some("probe".into()),
        ..BinaryChannels::default()
    }
}

#[test]
fn tdms_of_two_segments_gives_the_csv_coefficients() {
    let rec = load_tdms(&binary("probe_120deg_s.tdms"), &group()).unwrap();
    let reference = csv();
    assert_eq!(rec.time_s, reference.time_s);
    assert_eq!(rec.gap, reference.gap);
    assert_eq!(rec.angle_rad, reference.angle_rad);
    assert_eq!(rec.line_of_sample(10), 0);
    assert_same_fit(&rec, &reference);
    // Without a group the first group with the channel is read.
    let any = load_tdms(&binary("probe_120deg_s.tdms"), &BinaryChannels::default()).unwrap();
    assert_eq!(any, rec);
}

#[test]
fn tdms_time_from_the_waveform_properties() {
    let channels = BinaryChannels {
        time: None,
        ..group()
    };
    let rec = load_tdms(&binary("probe_120deg_s.tdms"), &channels).unwrap();
    let reference = csv();
    for (i, (&t, &r)) in rec.time_s.iter().zip(&reference.time_s).enumerate() {
        assert!((t - r).abs() <= 1e-14, "sample {i}: {t} vs {r}");
    }
    assert_same_fit(&rec, &reference);
}

#[test]
fn interleaved_f32_tdms_gives_the_coefficients_of_the_csv_in_f32() {
    let channels = BinaryChannels {
        time: None,
        ..group()
    };
    let rec = load_tdms(&binary("probe_120deg_s_interleaved_f32.tdms"), &channels).unwrap();
    let reference = csv_as_f32();
    assert_eq!(rec.len(), reference.len());
    assert_eq!(rec.gap, reference.gap);
    assert_same_fit(&rec, &reference);
    // The f32 rounding itself moves the coefficients by far more than the comparison's
    // tolerance: the comparison can fail.
    let d = max_difference(&analyze(&rec).mean, &analyze(&csv()).mean);
    assert!(d > 1e-9, "{d:e}");
}

#[test]
fn mat_v5_and_compressed_v7_struct_give_the_csv_coefficients() {
    let reference = csv();
    let v5 = load_mat(&binary("probe_120deg_s.mat"), &BinaryChannels::default()).unwrap();
    assert_eq!(v5.gap, reference.gap);
    assert_same_fit(&v5, &reference);
    let v7 = load_mat(
        &binary("probe_120deg_s_v7.mat"),
        &BinaryChannels {
            group: Some("rec".into()),
            ..BinaryChannels::default()
        },
    )
    .unwrap();
    assert_eq!(v7.time_s, reference.time_s);
    assert_same_fit(&v7, &reference);
    // A dotted path names the same field.
    let dotted = BinaryChannels {
        time: Some("rec.time_s".into()),
        gap: "rec.gap_um".into(),
        angle: Some("rec.angle_deg".into()),
        ..BinaryChannels::default()
    };
    let rec = load_mat(&binary("probe_120deg_s_v7.mat"), &dotted).unwrap();
    assert_eq!(rec.gap, v7.gap);
}

#[test]
fn missing_channel_names_the_available_ones() {
    let channels = BinaryChannels {
        gap: "gap_mm".into(),
        ..group()
    };
    let e = load_tdms(&binary("probe_120deg_s.tdms"), &channels).unwrap_err();
    match &e {
        RecordingError::MissingChannel {
            format,
            channel,
            available,
            ..
        } => {
            assert_eq!(*format, BinaryFormat::Tdms);
            assert_eq!(channel, "probe/gap_mm");
            assert_eq!(
                available,
                &["probe/time_s", "probe/gap_um", "probe/angle_deg"]
            );
        }
        other => panic!("{other:?}"),
    }
    assert!(e.to_string().contains("probe/gap_um"), "{e}");
    let e = load_mat(&binary("probe_120deg_s_v7.mat"), &BinaryChannels::default()).unwrap_err();
    match &e {
        RecordingError::MissingChannel {
            channel, available, ..
        } => {
            assert_eq!(channel, "gap_um");
            assert!(
                available.contains(&"rec.gap_um".to_string()),
                "{available:?}"
            );
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn v73_header_is_refused_by_name() {
    // A v7.3 file: a 512-byte MAT header (version 0x0200), then HDF5.
    let mut bytes = vec![b' '; 512];
    let text =
        b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Mon Nov 23 2026 HDF5 schema 1.00 .";
    bytes[..text.len()].copy_from_slice(text);
    bytes[124..128].copy_from_slice(&[0x00, 0x02, b'I', b'M']);
    bytes.extend_from_slice(b"\x89HDF\r\n\x1a\n");
    bytes.resize(2048, 0);
    let e = parse_mat(&bytes, Path::new("v73.mat"), &BinaryChannels::default()).unwrap_err();
    assert!(matches!(e, RecordingError::MatV73 { .. }), "{e:?}");
    assert!(e.to_string().contains("save with -v7 or older"), "{e}");
    // The version word alone is enough.
    bytes[..10].copy_from_slice(b"MATLAB 5.0");
    let e = parse_mat(&bytes, Path::new("v73.mat"), &BinaryChannels::default()).unwrap_err();
    assert!(matches!(e, RecordingError::MatV73 { .. }), "{e:?}");
}

#[test]
fn wrong_signatures_are_bad_magic() {
    let csv = std::fs::read(fixture("probe_120deg_s.csv")).unwrap();
    let e = parse_tdms(&csv, Path::new("x.tdms"), &group()).unwrap_err();
    assert!(
        matches!(
            e,
            RecordingError::BadMagic {
                format: BinaryFormat::Tdms,
                offset: 0,
                ..
            }
        ),
        "{e:?}"
    );
    let e = parse_mat(&csv, Path::new("x.mat"), &BinaryChannels::default()).unwrap_err();
    assert!(
        matches!(
            e,
            RecordingError::BadMagic {
                format: BinaryFormat::Mat,
                ..
            }
        ),
        "{e:?}"
    );
}

/// A reader of bytes in memory.
type Parser = fn(&[u8], &Path) -> Result<Recording, RecordingError>;

/// Every prefix cut at these offsets is a typed error naming the file.
#[test]
fn truncated_files_are_typed_errors() {
    let cases: [(&str, Parser); 4] = [
        ("probe_120deg_s.tdms", |b, p| parse_tdms(b, p, &group())),
        ("probe_120deg_s_interleaved_f32.tdms", |b, p| {
            parse_tdms(
                b,
                p,
                &BinaryChannels {
                    time: None,
                    ..group()
                },
            )
        }),
        ("probe_120deg_s.mat", |b, p| {
            parse_mat(b, p, &BinaryChannels::default())
        }),
        ("probe_120deg_s_v7.mat", |b, p| {
            parse_mat(
                b,
                p,
                &BinaryChannels {
                    group: Some("rec".into()),
                    ..BinaryChannels::default()
                },
            )
        }),
    ];
    for (name, parse) in cases {
        let bytes = std::fs::read(binary(name)).unwrap();
        let path = Path::new(name);
        // (A MAT file cut at 128 bytes is a valid file without variables.)
        let mut offsets = vec![0, 1, 3, 4, 10, 27, 28, 100, 127, 131, 136, 200, 1000];
        offsets.extend([
            bytes.len() / 3,
            bytes.len() / 2,
            bytes.len() - 8,
            bytes.len() - 1,
        ]);
        for cut in offsets {
            let e = match parse(&bytes[..cut], path) {
                Err(e) => e,
                Ok(r) => panic!("{name} cut at {cut}: read {} samples", r.len()),
            };
            assert!(e.to_string().starts_with(name), "{name} cut at {cut}: {e}");
            assert!(
                matches!(
                    e,
                    RecordingError::Truncated { .. }
                        | RecordingError::Malformed { .. }
                        | RecordingError::BadMagic { .. }
                ),
                "{name} cut at {cut}: {e:?}"
            );
        }
    }
    // Cut inside the raw data of the TDMS file's first segment: the lead-in's next-segment
    // offset points past the end.
    let bytes = std::fs::read(binary("probe_120deg_s.tdms")).unwrap();
    let e = parse_tdms(&bytes[..5000], Path::new("t.tdms"), &group()).unwrap_err();
    assert!(
        matches!(
            e,
            RecordingError::Truncated {
                offset: 0,
                what: recording::BinaryPart::Segment,
                ..
            }
        ),
        "{e:?}"
    );
}

#[test]
fn non_finite_sample_is_named_by_channel_and_index() {
    let mut bytes = std::fs::read(binary("probe_120deg_s.mat")).unwrap();
    // The first sample of `gap_um` becomes NaN.
    let first = csv().gap[0].to_le_bytes();
    let at = bytes.windows(8).position(|w| w == first).unwrap();
    bytes[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    let e = parse_mat(&bytes, Path::new("n.mat"), &BinaryChannels::default()).unwrap_err();
    match e {
        RecordingError::NonFiniteSample { channel, index, .. } => {
            assert_eq!((channel.as_str(), index), ("gap_um", 0));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn length_mismatch_and_unsupported_type() {
    let mut bytes = std::fs::read(binary("probe_120deg_s.tdms")).unwrap();
    // Make `angle_deg` of the first segment a string channel (type 0x20): it is refused.
    let path = b"/'probe'/'angle_deg'";
    let at = bytes.windows(path.len()).position(|w| w == path).unwrap() + path.len();
    // raw-data index length (4), then the data type.
    bytes[at + 4..at + 8].copy_from_slice(&0x44u32.to_le_bytes());
    let e = parse_tdms(&bytes, Path::new("u.tdms"), &group()).unwrap_err();
    assert!(
        matches!(e, RecordingError::Unsupported { ref channel, .. } if channel == "angle_deg"),
        "{e:?}"
    );
    // Time from one MAT variable, gap from a shorter one: a length mismatch.
    let bytes = mat_file(&[("time_s", &[0.0, 0.1, 0.2]), ("gap_um", &[1.0, 2.0])]);
    let e = parse_mat(&bytes, Path::new("l.mat"), &BinaryChannels::default()).unwrap_err();
    match e {
        RecordingError::ChannelLength {
            channel,
            reference,
            expected,
            found,
            ..
        } => {
            assert_eq!(
                (channel.as_str(), reference.as_str(), expected, found),
                ("gap_um", "time_s", 3, 2)
            );
        }
        other => panic!("{other:?}"),
    }
    // Times that do not increase: a time-axis error naming the sample in its source.
    let bytes = mat_file(&[("time_s", &[0.0, 0.1, 0.1]), ("gap_um", &[1.0, 2.0, 3.0])]);
    let e = parse_mat(&bytes, Path::new("t.mat"), &BinaryChannels::default()).unwrap_err();
    assert!(
        matches!(e, RecordingError::TimeAxis { ref channel, .. } if channel == "time_s"),
        "{e:?}"
    );
    // A header alone: no variables.
    let e = parse_mat(
        &mat_file(&[]),
        Path::new("e.mat"),
        &BinaryChannels::default(),
    )
    .unwrap_err();
    assert!(
        matches!(e, RecordingError::MissingChannel { ref available, .. } if available.is_empty()),
        "{e:?}"
    );
}

/// A MAT v5 file of double row vectors (header, then one uncompressed miMATRIX each).
fn mat_file(vars: &[(&str, &[f64])]) -> Vec<u8> {
    let mut out = vec![b' '; 116];
    out[..19].copy_from_slice(b"MATLAB 5.0 MAT-file");
    out.extend_from_slice(&[0; 8]);
    out.extend_from_slice(&[0x00, 0x01, b'I', b'M']);
    let tag = |out: &mut Vec<u8>, ty: u32, data: &[u8]| {
        out.extend_from_slice(&ty.to_le_bytes());
        out.extend_from_slice(&(data.len() as u32).to_le_bytes());
        out.extend_from_slice(data);
        out.resize(out.len().next_multiple_of(8), 0);
    };
    for (name, values) in vars {
        let mut m = Vec::new();
        tag(&mut m, 6, &[6, 0, 0, 0, 0, 0, 0, 0]);
        let dims: Vec<u8> = [1i32, values.len() as i32]
            .iter()
            .flat_map(|d| d.to_le_bytes())
            .collect();
        tag(&mut m, 5, &dims);
        tag(&mut m, 1, name.as_bytes());
        let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        tag(&mut m, 9, &data);
        tag(&mut out, 14, &m);
    }
    out
}

/// Random bytes and fixture bytes with random bytes changed or cut: never a panic, and a
/// recording read is finite throughout.
fn check_no_panic(bytes: &[u8]) {
    let tdms = [
        group(),
        BinaryChannels {
            time: None,
            ..group()
        },
    ];
    for c in &tdms {
        if let Ok(r) = parse_tdms(bytes, Path::new("f.tdms"), c) {
            assert_finite(&r);
        }
    }
    let mats = [
        BinaryChannels::default(),
        BinaryChannels {
            group: Some("rec".into()),
            ..BinaryChannels::default()
        },
    ];
    for c in &mats {
        if let Ok(r) = parse_mat(bytes, Path::new("f.mat"), c) {
            assert_finite(&r);
        }
    }
}

fn assert_finite(r: &Recording) {
    assert!(!r.is_empty());
    assert!(r.time_s.iter().chain(&r.gap).all(|x| x.is_finite()));
    if let Some(a) = &r.angle_rad {
        assert!(a.iter().all(|x| x.is_finite()));
    }
}

fn fixtures_bytes() -> Vec<Vec<u8>> {
    [
        "probe_120deg_s.tdms",
        "probe_120deg_s_interleaved_f32.tdms",
        "probe_120deg_s.mat",
        "probe_120deg_s_v7.mat",
    ]
    .iter()
    .map(|n| std::fs::read(binary(n)).unwrap())
    .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..2048)) {
        check_no_panic(&bytes);
        // The same bytes behind each format's signature reach the parsers' inner layers.
        let mut tdms = b"TDSm".to_vec();
        tdms.extend_from_slice(&bytes);
        check_no_panic(&tdms);
        let mut mat = std::fs::read(binary("probe_120deg_s.mat")).unwrap()[..128].to_vec();
        mat.extend_from_slice(&bytes);
        check_no_panic(&mat);
    }

    #[test]
    fn mutated_fixtures_never_panic(
        which in 0usize..4,
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..8),
        cut in any::<prop::sample::Index>(),
        do_cut in any::<bool>(),
    ) {
        let mut bytes = fixtures_bytes().swap_remove(which);
        // Edits land mostly in the structures at the front (headers, metadata, tags).
        let front = bytes.len().min(600);
        for (i, b) in edits {
            let k = i.index(front);
            bytes[k] = b;
        }
        if do_cut {
            bytes.truncate(cut.index(bytes.len()));
        }
        check_no_panic(&bytes);
    }
}

/// A file is read piece by piece, bytes in memory at once: both give the same recording or
/// the same error, cut anywhere.
#[test]
fn file_and_memory_readers_agree() {
    let dir = std::env::temp_dir().join(format!("recording-binary-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let tdms = BinaryChannels {
        time: None,
        ..group()
    };
    let struct_rec = BinaryChannels {
        group: Some("rec".into()),
        ..BinaryChannels::default()
    };
    for (name, channels) in [
        ("probe_120deg_s.tdms", group()),
        ("probe_120deg_s_interleaved_f32.tdms", tdms),
        ("probe_120deg_s.mat", BinaryChannels::default()),
        ("probe_120deg_s_v7.mat", struct_rec),
    ] {
        let bytes = std::fs::read(binary(name)).unwrap();
        let path = dir.join(name);
        for cut in [bytes.len(), bytes.len() - 3, bytes.len() / 2, 700, 140, 20] {
            std::fs::write(&path, &bytes[..cut]).unwrap();
            let (from_file, from_memory) = if name.ends_with(".tdms") {
                (
                    load_tdms(&path, &channels),
                    parse_tdms(&bytes[..cut], &path, &channels),
                )
            } else {
                (
                    load_mat(&path, &channels),
                    parse_mat(&bytes[..cut], &path, &channels),
                )
            };
            assert_eq!(
                format!("{from_file:?}"),
                format!("{from_memory:?}"),
                "{name} cut at {cut}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `load_recording` reads `.tdms` and `.mat` files by their extension with a
/// [`RecordingFormat`]'s names and units (the study's path), as the binary readers do.
#[test]
fn load_recording_reads_binary_files_by_their_extension() {
    let reference = csv();
    let tdms_format = RecordingFormat {
        group: Some("probe".into()),
        ..RecordingFormat::default()
    };
    let rec = load_recording(&binary("probe_120deg_s.tdms"), &tdms_format).unwrap();
    assert_eq!(rec.gap, reference.gap);
    assert_eq!(rec.angle_rad, reference.angle_rad);
    // The waveform timing instead of the time channel.
    let waveform = RecordingFormat {
        waveform_time: true,
        ..tdms_format.clone()
    };
    let rec = load_recording(&binary("probe_120deg_s.tdms"), &waveform).unwrap();
    assert_eq!(rec.gap, reference.gap);
    assert!((rec.time_s[100] - 0.2).abs() < 1e-12);
    // A MAT file held in memory, its reader chosen by the name's extension.
    let bytes = std::fs::read(binary("probe_120deg_s.mat")).unwrap();
    let rec = recording::parse_recording(&bytes, Path::new("x.mat"), &RecordingFormat::default())
        .unwrap();
    assert_eq!(rec.time_s, reference.time_s);
    let declared = RecordingFormat {
        angle: recording::AngleSource::Rate {
            start_angle_deg: 30.0,
        },
        ..RecordingFormat::default()
    };
    let rec = load_recording(&binary("probe_120deg_s.mat"), &declared).unwrap();
    assert!(rec.angle_rad.is_none());
    assert!((rec.start_angle_rad - 30f64.to_radians()).abs() < 1e-15);
    // A required encoder channel the file lacks: the reader's missing-channel error.
    let required = RecordingFormat {
        angle: recording::AngleSource::Encoder {
            column: "Winkel".into(),
            unit: recording::AngleUnit::Deg,
            optional: false,
        },
        ..tdms_format.clone()
    };
    let err = load_recording(&binary("probe_120deg_s.tdms"), &required).unwrap_err();
    assert!(
        matches!(&err, RecordingError::MissingChannel { channel, .. } if channel.contains("Winkel")),
        "{err:?}"
    );
    // Settings of binary files refused for a text file, and `waveform_time` for MAT.
    let err = load_recording(&fixture("probe_120deg_s.csv"), &tdms_format).unwrap_err();
    assert!(
        err.to_string()
            .ends_with("the format's `group` applies to TDMS and MAT files only"),
        "{err}"
    );
    let err = load_recording(&binary("probe_120deg_s.mat"), &waveform).unwrap_err();
    assert!(
        err.to_string()
            .contains("`waveform_time` applies to TDMS files only"),
        "{err}"
    );
}
