//! A probe gap recorded in volts with the probe's stated sensitivity, header units checked
//! against the declared ones, and the warning for a signal implausible for its unit.

use std::path::Path;

use harmonics::FitConfig;
use recording::{
    Diagnostic, GapUnit, LengthUnit, RecordingError, RecordingFormat, SensitivityUnit,
    SyntheticSpec, analyze_recording, parse_recording,
};

/// The synthetic recording's CSV with its gap column rewritten by `f` under `header`.
fn rewritten(header: &str, f: impl Fn(f64) -> f64) -> String {
    let csv = SyntheticSpec::default().csv().unwrap();
    let mut out = String::new();
    for line in csv.lines() {
        if line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').collect();
        if fields[0] == "time_s" {
            out += &format!("time_s,{header},angle_deg\n");
        } else {
            let gap: f64 = fields[1].parse().unwrap();
            out += &format!("{},{:.12},{}\n", fields[0], f(gap), fields[2]);
        }
    }
    out
}

fn format(column: &str, unit: GapUnit) -> RecordingFormat {
    let mut f = RecordingFormat::default();
    f.gap.column = column.into();
    f.gap.unit = unit;
    f
}

fn rate() -> f64 {
    SyntheticSpec::default().rate_deg_s.to_radians()
}

#[test]
fn a_gap_in_volts_gives_the_first_harmonic_of_the_same_data_in_um() {
    let um = rewritten("gap_um", |g| g);
    let reference = parse_recording(
        um.as_bytes(),
        "um.csv".as_ref(),
        &RecordingFormat::default(),
    )
    .unwrap();
    let reference = analyze_recording(&reference, rate(), &FitConfig::default()).unwrap();
    // An eddy-current probe of 8 V/mm: the conditioner's volts, as the lab records them.
    let v_per_mm = 8.0;
    let volts = rewritten("Spalt [V]", |g| g * v_per_mm / 1e3);
    for (stated, unit, u) in [
        (v_per_mm, SensitivityUnit::VPerMm, 0.04),
        (1e3 / v_per_mm, SensitivityUnit::UmPerV, 0.625),
        (1.0 / v_per_mm, SensitivityUnit::MmPerV, 6.25e-4),
    ] {
        let unit = GapUnit::Volts {
            sensitivity: stated,
            sensitivity_unit: unit,
            u_sensitivity: u,
        };
        let rec = parse_recording(
            volts.as_bytes(),
            "v.csv".as_ref(),
            &format("Spalt [V]", unit),
        )
        .unwrap();
        assert_eq!(rec.gap_unit, LengthUnit::Um);
        let s = rec.sensitivity.unwrap();
        approx::assert_relative_eq!(s.um_per_v(), 125.0, max_relative = 1e-12);
        // The probe gain's relative standard uncertainty, stated once: 0.5 %.
        approx::assert_relative_eq!(s.relative_u(), 0.005, max_relative = 1e-9);
        let a = analyze_recording(&rec, rate(), &FitConfig::default()).unwrap();
        for (x, y) in [
            (a.analysis.mean.c[0], reference.analysis.mean.c[0]),
            (a.analysis.mean.s[0], reference.analysis.mean.s[0]),
        ] {
            approx::assert_relative_eq!(x, y, max_relative = 1e-9);
        }
    }
}

#[test]
fn a_sensitivity_without_its_uncertainty_is_refused() {
    let volts = rewritten("gap_v", |g| g / 125.0);
    for (s, u, field) in [
        (125.0, 0.0, "u_sensitivity"),
        (0.0, 0.1, "sensitivity"),
        (f64::NAN, 0.1, "sensitivity"),
    ] {
        let unit = GapUnit::Volts {
            sensitivity: s,
            sensitivity_unit: SensitivityUnit::UmPerV,
            u_sensitivity: u,
        };
        let err = parse_recording(volts.as_bytes(), "v.csv".as_ref(), &format("gap_v", unit))
            .unwrap_err();
        assert!(
            matches!(&err, RecordingError::InvalidSensitivity { field: f, .. } if *f == field),
            "{err:?}"
        );
    }
    // In a configuration: `u_sensitivity` has no default.
    let e = ron::from_str::<RecordingFormat>(
        "(gap: (column: \"g\", unit: volts(sensitivity: 125.0, sensitivity_unit: um_per_v)))",
    )
    .unwrap_err();
    assert!(e.to_string().contains("u_sensitivity"), "{e}");
    let f: RecordingFormat = ron::from_str(
        "(gap: (column: \"g\", unit: volts(sensitivity: 8.0, sensitivity_unit: v_per_mm, \
         u_sensitivity: 0.04)))",
    )
    .unwrap();
    assert!(matches!(f.gap.unit, GapUnit::Volts { .. }));
}

#[test]
fn a_header_stating_another_unit_than_declared_is_refused() {
    // `Spalt [mm]` declared `um` (the default): C_r would be 1000 times too small.
    let mm = rewritten("Spalt [mm]", |g| g / 1e3);
    let err = parse_recording(
        mm.as_bytes(),
        Path::new("mm.csv"),
        &format("Spalt [mm]", GapUnit::Um),
    )
    .unwrap_err();
    assert!(
        matches!(
            &err,
            RecordingError::ColumnUnit {
                line: 1,
                declared: "um",
                suggested: "mm",
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("set `unit: mm`"), "{err}");
    // A volts header declared as a length.
    let v = rewritten("gap [V]", |g| g / 125.0);
    let err = parse_recording(
        v.as_bytes(),
        Path::new("v.csv"),
        &format("gap [V]", GapUnit::Um),
    )
    .unwrap_err();
    assert!(
        matches!(&err, RecordingError::ColumnUnit { declared: "um", .. }),
        "{err:?}"
    );
    // Declared as stated: read.
    assert!(
        parse_recording(
            mm.as_bytes(),
            Path::new("mm.csv"),
            &format("Spalt [mm]", GapUnit::Mm)
        )
        .is_ok()
    );
}

#[test]
fn a_mm_column_declared_um_warns_naming_the_unit() {
    // The same probe signal in mm under a header that does not state its unit, declared
    // `um` (the slip of issue 19): the mean gap of 0.05 "µm" is implausible.
    let mm = rewritten("gap", |g| g / 1e3);
    let rec = parse_recording(
        mm.as_bytes(),
        Path::new("mm.csv"),
        &format("gap", GapUnit::Um),
    )
    .unwrap();
    let a = analyze_recording(&rec, rate(), &FitConfig::default()).unwrap();
    let warning = a
        .diagnostics
        .iter()
        .find(|d| d.code() == "implausible_gap_unit")
        .unwrap_or_else(|| panic!("no warning: {:?}", a.diagnostics));
    assert!(matches!(
        warning,
        Diagnostic::ImplausibleGap {
            unit: LengthUnit::Um,
            ..
        }
    ));
    let text = warning.to_string();
    assert!(text.contains("declared unit `um`"), "{text}");
    assert!(text.contains("mean gap of 5.000e-2 µm"), "{text}");
    // Declared `mm`: no warning.
    let rec = parse_recording(
        mm.as_bytes(),
        Path::new("mm.csv"),
        &format("gap", GapUnit::Mm),
    )
    .unwrap();
    let a = analyze_recording(&rec, rate(), &FitConfig::default()).unwrap();
    assert!(
        a.diagnostics
            .iter()
            .all(|d| d.code() != "implausible_gap_unit"),
        "{:?}",
        a.diagnostics
    );
}
