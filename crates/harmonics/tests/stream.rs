//! The streamed analysis is `analyze`'s, to the bit, whatever the pieces it is fed in, and
//! refuses what `analyze` refuses with the same error (issue 32: recordings of any size).

use harmonics::{
    Coefficients, FitConfig, HarmonicsError, ProbeSignal, SpindleAngle, StreamAngle, StreamError,
    StreamingFit, SyntheticRecording, analyze, check_time_axis,
};

fn synthetic(samples: usize, wobble: f64, noise: f64) -> harmonics::SyntheticSamples {
    SyntheticRecording {
        rate_rad_s: 30f64.to_radians(),
        sample_rate_hz: 1000.0,
        samples,
        start_time_s: 12.5,
        start_angle_rad: 0.7,
        coefficients: Coefficients {
            l0: 50.0,
            c: vec![-3.2, 0.1, 0.02, 0.2],
            s: vec![-1.1, 0.05, 0.0, -0.01],
            drift_per_s: Some(0.001),
        },
        noise_std: noise,
        wobble_rad: wobble,
        seed: 7,
    }
    .generate()
}

/// The streamed analysis of `signal` fed in pieces of `piece` samples.
fn streamed(
    signal: &ProbeSignal<'_>,
    config: &FitConfig,
    piece: usize,
) -> Result<harmonics::HarmonicAnalysis, HarmonicsError> {
    let (angle, a) = match signal.angle {
        SpindleAngle::Encoder(a) => (StreamAngle::Encoder, Some(a)),
        SpindleAngle::Rate {
            rate_rad_s,
            start_angle_rad,
        } => (
            StreamAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            },
            None,
        ),
    };
    let n = signal.time_s.len();
    let mut fit = StreamingFit::new(config, angle, n)?;
    let mut i = 0;
    while i < n {
        let j = (i + piece).min(n);
        fit.push(&signal.time_s[i..j], &signal.gap[i..j], a.map(|a| &a[i..j]));
        i = j;
    }
    match fit.finish() {
        Ok(s) => Ok(s.analysis),
        Err(StreamError::TimeAxis(e) | StreamError::Analysis(e)) => Err(e),
    }
}

fn both_ways(signal: &ProbeSignal<'_>, config: &FitConfig) {
    let want = analyze(signal, config);
    for piece in [1, 7, 4096, usize::MAX / 2] {
        let got = streamed(signal, config, piece);
        assert_eq!(got, want, "pieces of {piece}");
    }
}

#[test]
fn streamed_fit_equals_analyze_bit_for_bit() {
    let s = synthetic(12_000 * 5 + 3_000, 0.01, 0.05);
    let rate = SpindleAngle::Rate {
        rate_rad_s: 30f64.to_radians(),
        start_angle_rad: 0.7,
    };
    for angle in [SpindleAngle::Encoder(&s.angle_rad), rate] {
        let signal = ProbeSignal {
            time_s: &s.time_s,
            gap: &s.gap,
            angle,
        };
        for config in [
            FitConfig::default(),
            FitConfig {
                drift: true,
                order: 6,
                ..FitConfig::default()
            },
            FitConfig {
                revolutions: Some(2),
                ..FitConfig::default()
            },
            FitConfig {
                revolutions: Some(40),
                ..FitConfig::default()
            },
        ] {
            both_ways(&signal, &config);
        }
        assert!(analyze(&signal, &FitConfig::default()).is_ok());
    }
}

#[test]
fn streamed_fit_refuses_what_analyze_refuses() {
    let s = synthetic(12_000 * 3 + 11_990, 0.0, 0.01);
    type Spoil = Box<dyn Fn(&mut harmonics::SyntheticSamples)>;
    let cases: Vec<(&str, Spoil)> = vec![
        (
            "gap",
            Box::new(|s| s.time_s[20_000..].iter_mut().for_each(|t| *t += 0.01)),
        ),
        (
            "time back",
            Box::new(|s| s.time_s[15_000] = s.time_s[14_998]),
        ),
        ("nan time", Box::new(|s| s.time_s[15_000] = f64::NAN)),
        ("nan gap", Box::new(|s| s.gap[25_000] = f64::NAN)),
        ("nan gap late", Box::new(|s| s.gap[47_000] = f64::INFINITY)),
        ("huge gap", Box::new(|s| s.gap[25_000] = 1e300)),
        ("angle back", Box::new(|s| s.angle_rad[30_000] -= 0.5)),
        ("angle nan", Box::new(|s| s.angle_rad[30_000] = f64::NAN)),
        (
            "angle jump",
            Box::new(|s| s.angle_rad[30_000..].iter_mut().for_each(|a| *a += 1.0)),
        ),
        (
            "short",
            Box::new(|s| {
                s.time_s.truncate(5_000);
                s.gap.truncate(5_000);
                s.angle_rad.truncate(5_000);
            }),
        ),
        (
            "sparse",
            Box::new(|s| {
                // Every 800th sample: too few per revolution for order 4, and aliasing.
                let keep = |v: &mut Vec<f64>| *v = v.iter().copied().step_by(800).collect();
                keep(&mut s.time_s);
                keep(&mut s.gap);
                keep(&mut s.angle_rad);
            }),
        ),
    ];
    for (name, spoil) in cases {
        let mut s = s.clone();
        spoil(&mut s);
        for angle in [
            SpindleAngle::Encoder(&s.angle_rad),
            SpindleAngle::Rate {
                rate_rad_s: 30f64.to_radians(),
                start_angle_rad: 0.7,
            },
            SpindleAngle::Rate {
                rate_rad_s: 3000f64.to_radians(),
                start_angle_rad: 0.7,
            },
        ] {
            let signal = ProbeSignal {
                time_s: &s.time_s,
                gap: &s.gap,
                angle,
            };
            for config in [
                FitConfig::default(),
                FitConfig {
                    order: 8,
                    ..FitConfig::default()
                },
            ] {
                let want = analyze(&signal, &config);
                let got = streamed(&signal, &config, 1000);
                // Debug text: NaN in an error equals NaN, and every value prints exactly.
                let kind = match angle {
                    SpindleAngle::Encoder(_) => "encoder".to_string(),
                    SpindleAngle::Rate { rate_rad_s, .. } => format!("rate {rate_rad_s}"),
                };
                assert_eq!(
                    format!("{got:?}"),
                    format!("{want:?}"),
                    "{name}, {kind}, order {}",
                    config.order
                );
            }
        }
    }
}

#[test]
fn streamed_time_axis_is_check_time_axis() {
    let s = synthetic(30_000, 0.0, 0.0);
    let mut t = s.time_s.clone();
    t[10_000..].iter_mut().for_each(|v| *v += 0.0025);
    t[20_000..].iter_mut().for_each(|v| *v += 0.01);
    let mut fit = StreamingFit::new(&FitConfig::default(), StreamAngle::Encoder, t.len()).unwrap();
    fit.push(&t, &s.gap, Some(&s.angle_rad));
    assert_eq!(fit.check_time_axis(), check_time_axis(&t, 3.0));
    assert!(matches!(
        fit.check_time_axis(),
        Err(HarmonicsError::SampleGap { index: 10_000, .. })
    ));
}
