//! Raw PIGA output recording: reading (units, unwrapping) and the reduction to a mean output
//! rate never panic; an `Ok` holds only finite numbers, a standard uncertainty ≥ 0 and at
//! least two revolutions.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use recording::{
    AngleUnit, Column, PigaRecordingFormat, parse_piga_recording, reduce_piga_recording,
};

fuzz_target!(|data: &[u8]| {
    // The first byte picks the output unit, the harmonic order and the declared rate.
    let Some((&choice, text)) = data.split_first() else {
        return;
    };
    let unit = match choice & 3 {
        0 => AngleUnit::Rad,
        1 => AngleUnit::Deg,
        2 => AngleUnit::Counts { per_rev: 4096 },
        _ => AngleUnit::Counts { per_rev: 1 },
    };
    let format = PigaRecordingFormat {
        output: Column {
            column: "output_rad".to_owned(),
            unit,
        },
        ..PigaRecordingFormat::default()
    };
    let Ok(recording) = parse_piga_recording(text, Path::new("fuzz.csv"), &format) else {
        return;
    };
    assert!(
        recording.output_rad().iter().all(|v| v.is_finite()),
        "non-finite output in an Ok recording"
    );
    let order = usize::from((choice >> 2) & 7) + 1;
    let rate_deg_s: f64 = [1.0, 36.0, 100.0, 360.0][usize::from(choice >> 6)];
    if let Ok(r) = reduce_piga_recording(&recording, rate_deg_s.to_radians(), order) {
        assert!(r.output_rad_s.is_finite(), "{r:?}");
        assert!(r.output_u_rad_s.is_finite() && r.output_u_rad_s >= 0.0, "{r:?}");
        assert!(r.revolutions >= 2, "{r:?}");
    }
});
