//! DAQmx-raw TDMS with NI_Scaling, as NI's DAQmx logging writes it: the files written from
//! the published format by `fixtures/recordings/binary/make_daqmx.py` are read to the values
//! npTDMS reads from the same bytes (stored beside them by the script).

use std::path::{Path, PathBuf};

use recording::{
    BinaryChannels, BinaryFormat, GapUnit, RecordingError, Unsupported, load_tdms, parse_tdms,
};

fn binary(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/recordings/binary")
        .join(name)
}

/// The columns of `NAME.expected.csv` (npTDMS's values).
fn expected(name: &str) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(binary(&format!("{name}.expected.csv"))).unwrap();
    let mut columns: Vec<Vec<f64>> = Vec::new();
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        for (k, v) in line.split(',').enumerate() {
            if columns.len() <= k {
                columns.push(Vec::new());
            }
            columns[k].push(v.parse().unwrap());
        }
    }
    columns
}

fn channels(angle: Option<&str>) -> BinaryChannels {
    BinaryChannels {
        group: Some("Probe".into()),
        time: None,
        gap: "gap".into(),
        gap_unit: GapUnit::Um,
        angle: angle.map(Into::into),
        ..BinaryChannels::default()
    }
}

/// `read` equals npTDMS's values to `rel` (relative, at least 1 unit in magnitude).
fn assert_same(read: &[f64], npt: &[f64], rel: f64, what: &str) {
    assert_eq!(read.len(), npt.len(), "{what}: sample count");
    for (i, (a, b)) in read.iter().zip(npt).enumerate() {
        assert!(
            (a - b).abs() <= rel * b.abs().max(1.0),
            "{what}[{i}]: read {a}, npTDMS {b}"
        );
    }
}

/// Integer scalers scaled in double precision: npTDMS and the reader agree to rounding.
const F64: f64 = 1e-13;
/// A float32 scaler under a linear scale: npTDMS keeps float32 (numpy keeps the array's
/// type for `data * slope + intercept`: two float32 roundings), the reader computes in
/// double precision; they agree to two float32 units in the last place.
const F32: f64 = 2.0 * f32::EPSILON as f64;

#[test]
fn daqmx_i16_scaler_polynomial_then_linear_reads_as_nptdms() {
    let want = expected("daqmx_i16_poly_linear");
    let rec = load_tdms(
        &binary("daqmx_i16_poly_linear.tdms"),
        &channels(Some("angle")),
    )
    .unwrap();
    assert_same(&rec.gap, &want[0], F64, "gap (µm)");
    // The angle channel in degrees (linear scale of uint16 counts), converted to radians.
    let angle_deg: Vec<f64> = rec
        .angle_rad
        .as_ref()
        .unwrap()
        .iter()
        .map(|a| a.to_degrees())
        .collect();
    assert_same(&angle_deg, &want[1], F64, "angle (deg)");
    // Two segments of 600 samples, the time from wf_increment.
    assert_eq!(rec.len(), 1200);
    approx::assert_relative_eq!(rec.time_s[1199], 1199.0 * 0.002, max_relative = 1e-12);
}

#[test]
fn daqmx_f32_channel_with_linear_scaling_of_its_raw_data_reads_as_nptdms() {
    let want = expected("daqmx_f32_linear");
    let bytes = std::fs::read(binary("daqmx_f32_linear.tdms")).unwrap();
    let rec = parse_tdms(&bytes, "f32.tdms".as_ref(), &channels(None)).unwrap();
    assert_same(&rec.gap, &want[0], F32, "gap (µm)");
    assert_eq!(rec.len(), 1200);
}

#[test]
fn a_daqmx_channel_in_volts_with_a_probe_sensitivity() {
    // A gap unit in volts converts after the file's own NI_Scaling: declared as volts of
    // 2 µm/V, the values are twice those npTDMS reads, and the sensitivity's relative u is
    // kept for the study.
    let want = expected("daqmx_f32_linear");
    let c = BinaryChannels {
        gap_unit: GapUnit::Volts {
            sensitivity: 2.0,
            sensitivity_unit: recording::SensitivityUnit::UmPerV,
            u_sensitivity: 0.01,
        },
        ..channels(None)
    };
    let rec = load_tdms(&binary("daqmx_f32_linear.tdms"), &c).unwrap();
    let doubled: Vec<f64> = want[0].iter().map(|v| 2.0 * v).collect();
    assert_same(&rec.gap, &doubled, F32, "gap");
    approx::assert_relative_eq!(rec.sensitivity.unwrap().relative_u(), 0.005);
}

#[test]
fn an_unread_scale_type_and_a_mangled_scaler_are_typed_errors() {
    let mut bytes = std::fs::read(binary("daqmx_f32_linear.tdms")).unwrap();
    // The linear scale's `Scale_Type` value (a string of length 6) patched to an unknown
    // type of the same length, in each of the three segments' metadata (a later segment's
    // property replaces an earlier one's).
    let at: Vec<usize> = bytes
        .windows(10)
        .enumerate()
        .filter(|(_, w)| w[..4] == 6u32.to_le_bytes() && &w[4..] == b"Linear")
        .map(|(i, _)| i + 4)
        .collect();
    assert_eq!(at.len(), 3);
    for value_at in at {
        bytes[value_at..value_at + 6].copy_from_slice(b"Tablex");
    }
    let err = parse_tdms(&bytes, "bad.tdms".as_ref(), &channels(None)).unwrap_err();
    assert!(
        matches!(
            &err,
            RecordingError::Unsupported { format: BinaryFormat::Tdms, what: Unsupported::TdmsScaling(t), .. }
                if t.contains("Tablex")
        ),
        "{err:?}"
    );
    // The message names the file and the channel.
    let text = err.to_string();
    assert!(
        text.starts_with("bad.tdms: ") && text.contains("`gap`"),
        "{text}"
    );
    // Any byte changed: an error or a recording, never a panic.
    let original = std::fs::read(binary("daqmx_i16_poly_linear.tdms")).unwrap();
    for i in (0..original.len().min(2000)).step_by(7) {
        let mut b = original.clone();
        b[i] ^= 0xA5;
        let _ = parse_tdms(&b, "m.tdms".as_ref(), &channels(Some("angle")));
    }
}
