//! PIGA tables as labs export them: the `format` block of a probe recording (delimiter,
//! decimal comma, lines before the header, named columns with units), a σ column and
//! labels; a German DAQ export read unchanged; hints that name only the format's keys.

use std::path::{Path, PathBuf};

use recording::{
    Hint, PigaTableFormat, RateUnit, RecordingError, load_piga_table, load_piga_table_with,
    parse_piga_table_with,
};

fn fixture(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(path)
}

/// The format of the German export, as a study configuration writes it.
fn german() -> PigaTableFormat {
    ron::from_str(
        r#"(
            delimiter: ';', decimal: comma, skip_lines: 5,
            rate: (column: "Drehrate [°/s]", unit: deg_s),
            output: (column: "Ausgang [rad/s]", unit: rad_s),
            label: Some("Lage"),
        )"#,
    )
    .unwrap()
}

#[test]
fn german_daq_export_is_read_unchanged_in_utf8_and_cp1252() {
    // The same 13 points as the campaign's table, exported by a German DAQ: a byte-order
    // mark, CRLF, five metadata lines, `;`, decimal comma, units in the headers, an extra
    // temperature column and an orientation label; once as UTF-8, once in code page 1252.
    let reference = load_piga_table(&fixture("campaign/piga.csv")).unwrap();
    for file in ["piga_export_utf8.csv", "piga_export_cp1252.csv"] {
        let path = fixture(&format!("recordings/piga-table-de/{file}"));
        let table = load_piga_table_with(&path, &german()).unwrap();
        assert_eq!(table.len(), 13, "{file}");
        assert_eq!(table.rate_deg_s, reference.rate_deg_s[..13], "{file}");
        // The same decimal digits with a comma: the same doubles.
        assert_eq!(table.output_rad_s, reference.output_rad_s[..13], "{file}");
        assert_eq!(table.sigma_rad_s, None);
        let labels = table.labels.as_deref().unwrap();
        assert_eq!(labels[..3], ["oben", "unten", "oben"], "{file}");
        // Header on line 6, first row on line 7.
        assert_eq!(table.line_of_row(0), 7, "{file}");
        assert_eq!(table.line_of_row(12), 19, "{file}");
    }
}

#[test]
fn units_are_converted_and_a_sigma_column_is_read() {
    let format: PigaTableFormat = ron::from_str(
        r#"(
            delimiter: whitespace,
            rate: (column: "n[U/min]", unit: rpm),
            output: (column: "out_deg_s", unit: deg_s),
            sigma: Some((column: "u_deg_h", unit: deg_h)),
        )"#,
    )
    .unwrap();
    let text = "n[U/min]  out_deg_s  u_deg_h\n60  1.0  3.6\n120\t2.0\t7.2\n";
    let t = parse_piga_table_with(text.as_bytes(), "t.txt".as_ref(), &format).unwrap();
    approx::assert_relative_eq!(t.rate_deg_s[..], [360.0, 720.0][..], max_relative = 1e-15);
    approx::assert_relative_eq!(
        t.output_rad_s[..],
        [1f64.to_radians(), 2f64.to_radians()][..],
        max_relative = 1e-15
    );
    let sigma = t.sigma_rad_s.unwrap();
    approx::assert_relative_eq!(sigma[0], 1e-3f64.to_radians(), max_relative = 1e-12);
    approx::assert_relative_eq!(sigma[1], 2e-3f64.to_radians(), max_relative = 1e-12);
    assert_eq!(t.labels, None);
}

#[test]
fn a_header_unit_other_than_the_declared_one_is_refused() {
    // `Drehrate [°/s]` declared in rad/s would be read 57 times too fast.
    let format = PigaTableFormat {
        rate: recording::Column {
            column: "Drehrate [°/s]".into(),
            unit: RateUnit::RadS,
        },
        ..german()
    };
    let path = fixture("recordings/piga-table-de/piga_export_utf8.csv");
    let err = load_piga_table_with(&path, &format).unwrap_err();
    assert!(
        matches!(
            &err,
            RecordingError::ColumnUnit {
                line: 6,
                declared: "rad_s",
                suggested: "deg_s",
                ..
            }
        ),
        "{err:?}"
    );
    let text = err.to_string();
    assert!(
        text.contains("piga_export_utf8.csv:6: column `Drehrate [°/s]` states its unit as \"°/s\""),
        "{text}"
    );
    assert!(text.contains("set `unit: deg_s`"), "{text}");
}

#[test]
fn unknown_keys_are_refused_with_the_keys_the_format_has() {
    let err =
        ron::from_str::<PigaTableFormat>("(decimal: comma, sigma_column: \"u\")").unwrap_err();
    let text = err.to_string();
    assert!(text.contains("sigma_column"), "{text}");
    for key in [
        "delimiter",
        "decimal",
        "skip_lines",
        "rate",
        "output",
        "sigma",
        "label",
    ] {
        assert!(text.contains(key), "{key} not offered: {text}");
    }
}

/// Every hint's key is one the PIGA table's format accepts (serde's own field list).
fn assert_hint_is_a_key(err: &RecordingError) {
    let hint = match err {
        RecordingError::Parse { hint, .. }
        | RecordingError::NonFinite { hint, .. }
        | RecordingError::MissingColumn { hint, .. } => *hint,
        _ => None,
    };
    if let Some(h) = hint {
        let probe = format!("({}: ())", h.key());
        // `()` is a value of some keys (`delimiter: ()` reads as whitespace): a key it reads.
        let e = ron::from_str::<PigaTableFormat>(&probe)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            !e.contains("Unexpected field"),
            "hint {h} names `{}`, which the PIGA table's format refuses: {e}",
            h.key()
        );
    }
}

#[test]
fn hints_name_only_keys_of_the_piga_table_format() {
    let path = fixture("recordings/piga-table-de/piga_export_utf8.csv");
    let bytes = std::fs::read(&path).unwrap();
    // Read without `decimal: comma`: the hint is `decimal: comma`, a key the format has.
    let no_comma = PigaTableFormat {
        decimal: recording::DecimalMark::Point,
        ..german()
    };
    let err = parse_piga_table_with(&bytes, &path, &no_comma).unwrap_err();
    assert!(
        matches!(
            &err,
            RecordingError::Parse {
                line: 7,
                hint: Some(Hint::DecimalComma),
                ..
            }
        ),
        "{err:?}"
    );
    assert_hint_is_a_key(&err);
    // Without `skip_lines`: the hint names `skip_lines`.
    let no_skip = PigaTableFormat {
        skip_lines: 0,
        ..german()
    };
    let err = parse_piga_table_with(&bytes, &path, &no_skip).unwrap_err();
    assert!(
        matches!(
            &err,
            RecordingError::MissingColumn {
                line: 1,
                hint: Some(Hint::SkipLines),
                ..
            }
        ),
        "{err:?}"
    );
    assert_hint_is_a_key(&err);
    // The lines skipped but read at commas (the default): the header is one name that
    // splits at `;`, so the hint names the delimiter (it once blamed metadata lines).
    let at_commas = PigaTableFormat {
        delimiter: recording::Delimiter::Char(','),
        decimal: recording::DecimalMark::Point,
        ..german()
    };
    let err = parse_piga_table_with(&bytes, &path, &at_commas).unwrap_err();
    assert!(
        matches!(
            &err,
            RecordingError::MissingColumn {
                line: 6,
                hint: Some(Hint::HeaderDelimiter { found: ';' }),
                ..
            }
        ),
        "{err:?}"
    );
    assert_hint_is_a_key(&err);
    // The same in a two-column export with nothing above its header.
    let two_columns = "Drehrate [°/s];Ausgang [rad/s]\n20,0;0,0174\n";
    let err = parse_piga_table_with(
        two_columns.as_bytes(),
        "t.csv".as_ref(),
        &PigaTableFormat {
            skip_lines: 0,
            ..at_commas
        },
    )
    .unwrap_err();
    assert!(
        err.to_string()
            .contains("the header looks separated by ';'"),
        "{err}"
    );
    // A NaN in a table: a recording's hint would be `on_non_finite`, which a table does not
    // have; no hint is given.
    let text = "rate_deg_s,output_rad_s\n10,NaN\n";
    let err = parse_piga_table_with(
        text.as_bytes(),
        "t.csv".as_ref(),
        &PigaTableFormat::default(),
    )
    .unwrap_err();
    assert!(
        matches!(
            &err,
            RecordingError::NonFinite {
                line: 2,
                hint: None,
                ..
            }
        ),
        "{err:?}"
    );
    assert!(!err.to_string().contains("on_non_finite"), "{err}");
    // With `,` as the delimiter and a decimal comma, the format itself is refused.
    let bad = PigaTableFormat {
        delimiter: recording::Delimiter::Char(','),
        ..german()
    };
    assert!(matches!(
        parse_piga_table_with(&bytes, &path, &bad),
        Err(RecordingError::InvalidDelimiter { delimiter: ',' })
    ));
}

#[test]
fn header_units_are_recognised() {
    for (header, unit) in [
        ("Drehrate [°/s]", Some(RateUnit::DegS)),
        ("rate (deg/s)", Some(RateUnit::DegS)),
        ("Winkelgeschw. [Grad/s]", Some(RateUnit::DegS)),
        ("Ausgang [rad/s]", Some(RateUnit::RadS)),
        ("n [U/min]", Some(RateUnit::Rpm)),
        ("speed (rpm)", Some(RateUnit::Rpm)),
        ("drift [°/h]", Some(RateUnit::DegH)),
        ("Spalt [mm]", None),
        ("rate_deg_s", None),
    ] {
        assert_eq!(RateUnit::in_header(header), unit, "{header}");
    }
}
