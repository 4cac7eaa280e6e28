//! TDMS and MAT readers on arbitrary bytes: no panic, no allocation beyond what the bytes
//! hold (every length field is checked first; `-rss_limit_mb` catches a runaway one); an
//! `Ok` holds only finite, increasing times and finite gaps.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use recording::{BinaryChannels, parse_mat, parse_tdms};

fuzz_target!(|data: &[u8]| {
    // The first byte picks the reader and the channels: TDMS or MAT, in group `probe` or
    // at the top level, with or without a time channel; bit 3 the channel names of the
    // DAQmx fixtures (group `Probe`, `gap` and `angle`, time from wf_increment).
    let Some((&choice, bytes)) = data.split_first() else {
        return;
    };
    let channels = if choice & 8 != 0 {
        BinaryChannels {
            group: (choice & 2 == 0).then(|| "Probe".to_owned()),
            time: None,
            gap: "gap".to_owned(),
            angle: Some("angle".to_owned()),
            ..BinaryChannels::default()
        }
    } else {
        BinaryChannels {
            group: (choice & 2 == 0).then(|| "probe".to_owned()),
            time: if choice & 4 == 0 {
                BinaryChannels::default().time
            } else {
                None
            },
            ..BinaryChannels::default()
        }
    };
    let path = Path::new("fuzz.bin");
    let result = if choice & 1 == 0 {
        parse_tdms(bytes, path, &channels)
    } else {
        parse_mat(bytes, path, &channels)
    };
    if let Ok(rec) = result {
        assert!(
            rec.time_s.iter().chain(&rec.gap).all(|v| v.is_finite()),
            "non-finite value in an Ok recording"
        );
        assert!(
            rec.time_s.windows(2).all(|w| w[1] > w[0]),
            "times not increasing in an Ok recording"
        );
    }
});
