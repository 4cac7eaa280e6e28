//! `harmonics::analyze` on arbitrary short recordings: no panic, and an `Ok` analysis holds
//! only finite numbers (checked on its whole serialized tree).
#![no_main]

use harmonics::{FitConfig, ProbeSignal, SpindleAngle, analyze};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((head, rest)) = data.split_first_chunk::<4>() else {
        return;
    };
    let [settings, rate, step, start] = *head;
    // Samples: 8 bytes each, the gap as any f64 bit pattern (huge values included); at most
    // 4096 samples so that a run stays fast.
    let gap: Vec<f64> = rest
        .chunks_exact(8)
        .take(4096)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    let n = gap.len();
    if n < 4 {
        return;
    }
    let interval_s = 1e-3 * f64::from(step.max(1));
    let time_s: Vec<f64> = (0..n).map(|i| f64::from(start) + i as f64 * interval_s).collect();
    // A rate that turns between a fraction of a revolution and several over the recording.
    let rate_rad_s = std::f64::consts::TAU * (0.25 + f64::from(rate) / 16.0) / (n as f64 * interval_s);
    let encoder: Vec<f64>;
    let angle = if settings & 0x80 == 0 {
        SpindleAngle::Rate {
            rate_rad_s,
            start_angle_rad: f64::from(start) / 40.0,
        }
    } else {
        encoder = time_s.iter().map(|t| rate_rad_s * t).collect();
        SpindleAngle::Encoder(&encoder)
    };
    let config = FitConfig {
        order: usize::from(settings & 7).max(1),
        drift: settings & 8 != 0,
        revolutions: (settings & 0x30 != 0).then_some(usize::from((settings >> 4) & 3)),
        ..FitConfig::default()
    };
    let signal = ProbeSignal {
        time_s: &time_s,
        gap: &gap,
        angle,
    };
    if let Ok(analysis) = analyze(&signal, &config) {
        if let Err(e) = edge_io::check_finite(&analysis) {
            panic!("non-finite Ok: {e}");
        }
    }
});
