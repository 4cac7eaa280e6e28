//! Throughput of the binary readers (issue 10, item 6): TDMS and MAT files of about ten
//! million samples, read from the file (page cache) and parsed from memory.
//!
//! `cargo bench -p recording --bench binary`. The files are written at bench time (3 400 000
//! rows of three float64 channels `time_s`, `gap_um`, `angle_deg`: 10.2 M samples, 82 MB
//! each) into `$BINARY_BENCH_DIR` (default: cargo's target tmp directory), where
//! `bench/binary_numpy.py` reads the same files with npTDMS and scipy. Throughput is in
//! samples (values of all three channels). `copy_floor` copies the TDMS file's bytes into a
//! new buffer: no reader can go faster than that on the same machine.

use std::hint::black_box;
use std::path::{Path, PathBuf};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use recording::{BinaryChannels, load_mat, load_tdms, parse_mat, parse_tdms};

const ROWS: usize = 3_400_000;
const CHANNELS: [&str; 3] = ["time_s", "gap_um", "angle_deg"];

/// The probe signal: 500 Hz, 120 deg/s, a first and second harmonic.
fn columns() -> [Vec<f64>; 3] {
    let t: Vec<f64> = (0..ROWS).map(|i| i as f64 * 0.002).collect();
    let angle: Vec<f64> = t.iter().map(|t| (120.0 * t) % 360.0).collect();
    let gap = angle
        .iter()
        .map(|a: &f64| {
            let th = a.to_radians();
            47.0 - 3.0 * th.cos() - 1.2 * th.sin() + 0.1 * (2.0 * th).cos()
        })
        .collect();
    [t, gap, angle]
}

fn le(values: &[f64]) -> impl Iterator<Item = u8> + '_ {
    values.iter().flat_map(|v| v.to_le_bytes())
}

/// One TDMS segment, group `probe`, contiguous float64 channels (NI's layout).
fn tdms(cols: &[Vec<f64>; 3]) -> Vec<u8> {
    let string = |out: &mut Vec<u8>, s: &str| {
        out.extend((s.len() as u32).to_le_bytes());
        out.extend(s.as_bytes());
    };
    let mut meta = Vec::new();
    meta.extend(4u32.to_le_bytes());
    string(&mut meta, "/'probe'");
    meta.extend(u32::MAX.to_le_bytes());
    meta.extend(0u32.to_le_bytes());
    for (name, values) in CHANNELS.iter().zip(cols) {
        string(&mut meta, &format!("/'probe'/'{name}'"));
        meta.extend(20u32.to_le_bytes());
        meta.extend(10u32.to_le_bytes());
        meta.extend(1u32.to_le_bytes());
        meta.extend((values.len() as u64).to_le_bytes());
        meta.extend(0u32.to_le_bytes());
    }
    let raw = (ROWS * 8 * 3) as u64;
    let mut out = b"TDSm".to_vec();
    out.extend((0b1110u32).to_le_bytes());
    out.extend(4713u32.to_le_bytes());
    out.extend((meta.len() as u64 + raw).to_le_bytes());
    out.extend((meta.len() as u64).to_le_bytes());
    out.extend(meta);
    for c in cols {
        out.extend(le(c));
    }
    out
}

/// A MAT v5 file of double row vectors, each compressed (v7) or not.
fn mat(cols: &[Vec<f64>; 3], compress: bool) -> Vec<u8> {
    let mut out = vec![b' '; 116];
    out[..19].copy_from_slice(b"MATLAB 5.0 MAT-file");
    out.extend([0; 8]);
    out.extend([0x00, 0x01, b'I', b'M']);
    let tag = |out: &mut Vec<u8>, ty: u32, data: &[u8]| {
        out.extend(ty.to_le_bytes());
        out.extend((data.len() as u32).to_le_bytes());
        out.extend(data);
        out.resize(out.len().next_multiple_of(8), 0);
    };
    for (name, values) in CHANNELS.iter().zip(cols) {
        let mut m = Vec::new();
        tag(&mut m, 6, &[6, 0, 0, 0, 0, 0, 0, 0]);
        let dims: Vec<u8> = [1u32, values.len() as u32]
            .iter()
            .flat_map(|d| d.to_le_bytes())
            .collect();
        tag(&mut m, 5, &dims);
        tag(&mut m, 1, name.as_bytes());
        tag(&mut m, 9, &le(values).collect::<Vec<u8>>());
        if compress {
            let mut element = Vec::new();
            tag(&mut element, 14, &m);
            let z = miniz_oxide::deflate::compress_to_vec_zlib(&element, 1);
            out.extend(15u32.to_le_bytes());
            out.extend((z.len() as u32).to_le_bytes());
            out.extend(z);
        } else {
            tag(&mut out, 14, &m);
        }
    }
    out
}

fn dir() -> PathBuf {
    std::env::var_os("BINARY_BENCH_DIR")
        .map_or_else(|| PathBuf::from(env!("CARGO_TARGET_TMPDIR")), PathBuf::from)
}

fn write(path: &Path, bytes: &[u8]) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, bytes).unwrap();
}

fn bench(c: &mut Criterion) {
    let cols = columns();
    let channels = BinaryChannels {
        group: Some("probe".into()),
        ..BinaryChannels::default()
    };
    let files = [
        ("tdms", dir().join("probe_10m.tdms"), tdms(&cols)),
        ("mat_v5", dir().join("probe_10m.mat"), mat(&cols, false)),
        ("mat_v7", dir().join("probe_10m_v7.mat"), mat(&cols, true)),
    ];
    let mut group = c.benchmark_group("binary_read");
    group.throughput(Throughput::Elements((ROWS * 3) as u64));
    group.sample_size(20);
    // The floor: copying the file's bytes into a new buffer (no conversion at all).
    let tdms_bytes = &files[0].2;
    group.bench_function("copy_floor/to_vec", |b| {
        b.iter_with_large_drop(|| black_box(black_box(tdms_bytes).to_vec()));
    });
    for (name, path, bytes) in &files {
        write(path, bytes);
        let tdms = name.starts_with("tdms");
        // Check once that the file reads back to the columns.
        let rec = if tdms {
            parse_tdms(bytes, path, &channels).unwrap()
        } else {
            parse_mat(bytes, path, &BinaryChannels::default()).unwrap()
        };
        assert_eq!(rec.gap, cols[1]);
        // The recording is returned, not dropped, inside the timing (criterion's
        // `iter_with_large_drop`): freeing 82 MB is the caller's cost, not the reader's.
        group.bench_function(format!("{name}/parse"), |b| {
            b.iter_with_large_drop(|| {
                let r = if tdms {
                    parse_tdms(black_box(bytes), path, &channels)
                } else {
                    parse_mat(black_box(bytes), path, &BinaryChannels::default())
                };
                black_box(r.unwrap())
            });
        });
        group.bench_function(format!("{name}/load"), |b| {
            b.iter_with_large_drop(|| {
                let r = if tdms {
                    load_tdms(black_box(path), &channels)
                } else {
                    load_mat(black_box(path), &BinaryChannels::default())
                };
                black_box(r.unwrap())
            });
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
