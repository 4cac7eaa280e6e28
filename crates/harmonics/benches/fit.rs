//! Throughput of the in-memory harmonic fit (issue 3, Performance).
//!
//! `cargo bench -p harmonics --bench fit`. Recordings: 8 revolutions at 10 deg/s sampled at
//! 1 kHz (288 000 samples) and one ten times longer, order 4, as the paper.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use harmonics::{Coefficients, FitConfig, ProbeSignal, SpindleAngle, SyntheticRecording, analyze};

fn recording(samples: usize) -> SyntheticRecording {
    SyntheticRecording {
        rate_rad_s: 10f64.to_radians(),
        sample_rate_hz: 1000.0,
        samples,
        start_time_s: 0.0,
        start_angle_rad: 0.0,
        coefficients: Coefficients {
            l0: 120.0,
            c: vec![-3.2385, 0.4, -0.1, 0.05],
            s: vec![-1.1406, 0.2, 0.08, -0.02],
            drift_per_s: None,
        },
        noise_std: 0.05,
        wobble_rad: 0.0,
        seed: 1,
    }
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("harmonic_fit");
    for samples in [288_000, 2_880_000] {
        let rec = recording(samples);
        let data = rec.generate();
        group.throughput(Throughput::Elements(samples as u64));
        let rate = ProbeSignal {
            time_s: &data.time_s,
            gap: &data.gap,
            angle: SpindleAngle::Rate {
                rate_rad_s: rec.rate_rad_s,
                start_angle_rad: 0.0,
            },
        };
        let encoder = ProbeSignal {
            angle: SpindleAngle::Encoder(&data.angle_rad),
            ..rate
        };
        for (name, signal) in [("rate", rate), ("encoder", encoder)] {
            for (label, drift) in [("", false), ("+drift", true)] {
                let config = FitConfig {
                    drift,
                    ..FitConfig::default()
                };
                group.bench_function(format!("{name}{label}/order4/{samples}"), |b| {
                    b.iter(|| {
                        analyze(black_box(&signal), black_box(&config)).expect("valid recording")
                    })
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
