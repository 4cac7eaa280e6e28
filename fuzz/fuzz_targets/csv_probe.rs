//! Probe-recording CSV reader: no panic; the fast in-place path gives the same recording (or
//! the same error) as the field-by-field reference path; an `Ok` holds only finite numbers.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use recording::{
    AngleSource, AngleUnit, Column, DecimalMark, Delimiter, GapUnit, RecordingFormat,
    parse_recording, parse_recording_reference,
};

fuzz_target!(|data: &[u8]| {
    // The first byte picks the format: delimiter, decimal mark, gap unit, angle unit.
    let Some((&choice, text)) = data.split_first() else {
        return;
    };
    let delimiter = [
        Delimiter::Char(','),
        Delimiter::Char(';'),
        Delimiter::Whitespace,
        Delimiter::Char('\t'),
    ][usize::from(choice & 3)];
    // A decimal comma needs a delimiter other than `,`.
    let decimal = if choice & 0x80 != 0 && delimiter != Delimiter::Char(',') {
        DecimalMark::Comma
    } else {
        DecimalMark::Point
    };
    let defaults = RecordingFormat::default();
    let format = RecordingFormat {
        delimiter,
        decimal,
        gap: Column {
            unit: [GapUnit::Um, GapUnit::Mm, GapUnit::M][usize::from(choice >> 2) % 3],
            ..defaults.gap.clone()
        },
        angle: AngleSource::Encoder {
            column: "angle_deg".to_owned(),
            unit: if choice & 0x40 == 0 {
                AngleUnit::Deg
            } else {
                AngleUnit::Rad
            },
            optional: true,
        },
        ..defaults
    };
    let path = Path::new("fuzz.csv");
    let fast = parse_recording(text, path, &format);
    let reference = parse_recording_reference(text, path, &format);
    match (&fast, &reference) {
        (Ok(a), Ok(b)) => {
            assert_eq!(a, b, "fast and reference paths disagree");
            let angle = a.angle_rad.as_deref().unwrap_or(&[]);
            assert!(
                a.time_s.iter().chain(&a.gap).chain(angle).all(|v| v.is_finite()),
                "non-finite value in an Ok recording"
            );
            for row in 0..a.time_s.len() {
                assert!(a.line_of_sample(row) >= 1);
            }
        }
        (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
        _ => panic!("fast {fast:?} vs reference {reference:?}"),
    }
});
