//! Behaviour tests of the harmonic analysis: recovery of known coefficients, agreement with
//! QR on the explicit design matrix, and every refusal.

use harmonics::{
    Coefficients, DeclaredRate, FitConfig, HarmonicsError, MAX_ORDER, ProbeSignal, Requirement,
    SpindleAngle, SyntheticRecording, SyntheticSamples, analyze, check_encoder_rate,
    check_time_axis,
};

/// Coefficients of order `n` with distinct, non-trivial values.
fn coefficients(order: usize, l0: f64) -> Coefficients {
    Coefficients {
        l0,
        c: (1..=order)
            .map(|k| -3.2 / k as f64 + 0.1 * k as f64)
            .collect(),
        s: (1..=order).map(|k| 1.1 / (k * k) as f64 - 0.05).collect(),
        drift_per_s: None,
    }
}

fn recording(order: usize, revolutions: f64) -> SyntheticRecording {
    let rate_rad_s = 60f64.to_radians();
    let sample_rate_hz = 500.0;
    let per_rev = std::f64::consts::TAU / rate_rad_s * sample_rate_hz;
    SyntheticRecording {
        rate_rad_s,
        sample_rate_hz,
        samples: (revolutions * per_rev).round() as usize,
        start_time_s: 12.5,
        start_angle_rad: 0.7,
        coefficients: coefficients(order, 250.0),
        noise_std: 0.0,
        wobble_rad: 0.0,
        seed: 3,
    }
}

fn rate_signal<'a>(rec: &SyntheticRecording, data: &'a SyntheticSamples) -> ProbeSignal<'a> {
    ProbeSignal {
        time_s: &data.time_s,
        gap: &data.gap,
        angle: SpindleAngle::Rate {
            rate_rad_s: rec.rate_rad_s,
            start_angle_rad: rec.start_angle_rad,
        },
    }
}

fn encoder_signal(data: &SyntheticSamples) -> ProbeSignal<'_> {
    ProbeSignal {
        time_s: &data.time_s,
        gap: &data.gap,
        angle: SpindleAngle::Encoder(&data.angle_rad),
    }
}

fn max_error(a: &Coefficients, b: &Coefficients) -> f64 {
    let mut e = (a.l0 - b.l0).abs();
    for (x, y) in a.c.iter().chain(&a.s).zip(b.c.iter().chain(&b.s)) {
        e = e.max((x - y).abs());
    }
    e
}

mod recovery {
    use super::*;

    #[test]
    fn every_order_from_rate_and_from_encoder() {
        for order in 1..=MAX_ORDER {
            let rec = recording(order, 3.4);
            let data = rec.generate();
            let config = FitConfig {
                order,
                ..FitConfig::default()
            };
            for signal in [rate_signal(&rec, &data), encoder_signal(&data)] {
                let fit = analyze(&signal, &config).unwrap();
                assert_eq!(fit.revolutions_used(), 3, "order {order}");
                assert!(
                    max_error(&fit.mean, &rec.coefficients) < 1e-9,
                    "order {order}: {:?}",
                    fit.mean
                );
                for r in &fit.revolutions {
                    assert!(
                        r.residual_rms < 1e-6,
                        "order {order}: rms {}",
                        r.residual_rms
                    );
                    assert!(
                        r.condition < 10.0,
                        "order {order}: condition {}",
                        r.condition
                    );
                }
                let std = fit.std.as_ref().unwrap();
                assert!(std.c.iter().chain(&std.s).all(|v| *v < 1e-9));
            }
        }
    }

    #[test]
    fn partial_last_revolution_is_dropped_and_reported() {
        let rec = recording(4, 2.4);
        let data = rec.generate();
        let fit = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap();
        assert_eq!(fit.revolutions_used(), 2);
        let inc = fit.incomplete.as_ref().expect("a partial revolution");
        approx::assert_abs_diff_eq!(inc.turns, 0.4, epsilon = 0.01);
        assert_eq!(inc.samples.end, data.time_s.len());
        // Exactly two whole revolutions (the last sample one step short of closing): no drop.
        let rec = recording(4, 2.0);
        let data = rec.generate();
        let fit = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap();
        assert_eq!(fit.revolutions_used(), 2);
        assert!(fit.incomplete.is_none());
    }

    #[test]
    fn revolutions_limit_uses_the_first_ones() {
        let rec = recording(2, 5.0);
        let data = rec.generate();
        let config = FitConfig {
            order: 2,
            revolutions: Some(3),
            ..FitConfig::default()
        };
        let fit = analyze(&rate_signal(&rec, &data), &config).unwrap();
        assert_eq!(fit.revolutions_used(), 3);
        assert_eq!(fit.revolutions_available, 5);
        assert_eq!(fit.revolutions[0].first_sample, 0);
    }

    #[test]
    fn noise_is_averaged_to_its_standard_error() {
        let sigma = 0.3;
        let rec = SyntheticRecording {
            noise_std: sigma,
            seed: 11,
            ..recording(4, 8.0)
        };
        let data = rec.generate();
        let fit = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap();
        let n = fit.revolutions[0].samples as f64;
        // Per-revolution standard error of a harmonic coefficient: σ·√(2/n).
        let per_rev = sigma * (2.0 / n).sqrt();
        let of_mean = per_rev / (fit.revolutions_used() as f64).sqrt();
        assert!(max_error(&fit.mean, &rec.coefficients) < 5.0 * of_mean);
        for r in &fit.revolutions {
            approx::assert_relative_eq!(r.residual_rms, sigma, max_relative = 0.1);
        }
        let std = fit.std.as_ref().unwrap();
        let mean_std = std.c.iter().chain(&std.s).sum::<f64>() / 8.0;
        approx::assert_relative_eq!(mean_std, per_rev, max_relative = 0.4);
        let se = fit.std_error.as_ref().unwrap();
        approx::assert_relative_eq!(se.c[0], std.c[0] / 8f64.sqrt(), max_relative = 1e-12);
    }

    #[test]
    fn drift_is_fitted_when_asked() {
        let mut rec = recording(3, 4.0);
        rec.coefficients.drift_per_s = Some(0.02);
        let data = rec.generate();
        let signal = rate_signal(&rec, &data);
        let with = analyze(
            &signal,
            &FitConfig {
                order: 3,
                drift: true,
                ..FitConfig::default()
            },
        )
        .unwrap();
        for r in &with.revolutions {
            let k = &r.coefficients;
            approx::assert_relative_eq!(k.drift_per_s.unwrap(), 0.02, max_relative = 1e-8);
            // l0 is the value at the revolution's middle time.
            let t = &data.time_s[r.first_sample..r.first_sample + r.samples];
            let t_mid = 0.5 * (t[0] + t[t.len() - 1]);
            approx::assert_relative_eq!(
                k.l0,
                250.0 + 0.02 * (t_mid - rec.start_time_s),
                max_relative = 1e-12
            );
            approx::assert_abs_diff_eq!(k.c[0], rec.coefficients.c[0], epsilon = 1e-9);
            approx::assert_abs_diff_eq!(k.s[2], rec.coefficients.s[2], epsilon = 1e-9);
        }
        // Without the drift term the drift leaks into the sines and the residual.
        let without = analyze(
            &signal,
            &FitConfig {
                order: 3,
                ..FitConfig::default()
            },
        )
        .unwrap();
        assert!((without.mean.s[0] - rec.coefficients.s[0]).abs() > 1e-3);
        assert!(without.revolutions[0].residual_rms > 1e-3);
    }

    #[test]
    fn fit_follows_a_non_uniform_encoder() {
        let rec = SyntheticRecording {
            wobble_rad: 1.2,
            ..recording(4, 3.5)
        };
        let data = rec.generate();
        let by_encoder = analyze(&encoder_signal(&data), &FitConfig::default()).unwrap();
        assert!(max_error(&by_encoder.mean, &rec.coefficients) < 1e-9);
        // The nominal rate does not describe this spindle: the fit from it is wrong.
        let by_rate = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap();
        assert!(max_error(&by_rate.mean, &rec.coefficients) > 0.1);
    }

    #[test]
    fn encoder_in_degrees_wrapped_anywhere_is_the_same() {
        // The encoder may wrap at 2π or be unwrapped already; both give the same fit.
        let rec = recording(4, 3.0);
        let data = rec.generate();
        let unwrapped: Vec<f64> = data.time_s.iter().map(|&t| rec.angle_at(t)).collect();
        let a = analyze(&encoder_signal(&data), &FitConfig::default()).unwrap();
        let b = analyze(
            &ProbeSignal {
                angle: SpindleAngle::Encoder(&unwrapped),
                ..encoder_signal(&data)
            },
            &FitConfig::default(),
        )
        .unwrap();
        assert_eq!(a.revolutions.len(), b.revolutions.len());
        assert!(max_error(&a.mean, &b.mean) < 1e-10);
    }

    #[test]
    fn first_harmonic_and_azimuth() {
        let mut rec = recording(4, 2.0);
        rec.coefficients.c[0] = -3.2385;
        rec.coefficients.s[0] = -1.1406;
        let data = rec.generate();
        let fit = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap();
        let h = fit.first_harmonic().unwrap();
        approx::assert_relative_eq!(h.amplitude(), 3.2385f64.hypot(1.1406), max_relative = 1e-9);
        let beta = harmonics::ProbeDirection::AgainstO1X1.beta_rad(h);
        approx::assert_relative_eq!(beta, (-1.1406f64).atan2(3.2385), max_relative = 1e-9);
    }
}

mod versus_qr {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// Column-scaled QR least squares on the explicit design matrix.
    fn qr_fit(theta: &[f64], tau: Option<&[f64]>, y: &[f64], order: usize) -> Vec<f64> {
        let p = 2 * order + 1 + usize::from(tau.is_some());
        let a = DMatrix::from_fn(y.len(), p, |i, j| match j {
            0 => 1.0,
            j if j <= order => (j as f64 * theta[i]).cos(),
            j if j <= 2 * order => ((j - order) as f64 * theta[i]).sin(),
            _ => tau.unwrap()[i],
        });
        let norms: Vec<f64> = a.column_iter().map(|c| c.norm()).collect();
        let scaled = DMatrix::from_fn(a.nrows(), p, |i, j| a[(i, j)] / norms[j]);
        let qr = scaled.qr();
        let qty = qr.q().transpose() * DVector::from_column_slice(y);
        let x = qr.r().solve_upper_triangular(&qty).unwrap();
        (0..p).map(|j| x[j] / norms[j]).collect()
    }

    #[test]
    fn normal_equations_match_qr() {
        for (order, drift) in [(1, false), (4, false), (4, true), (8, true)] {
            let mut rec = SyntheticRecording {
                wobble_rad: 0.8,
                noise_std: 0.2,
                seed: 5,
                ..recording(order, 1.0)
            };
            rec.coefficients.drift_per_s = Some(0.01);
            let data = rec.generate();
            let config = FitConfig {
                order,
                drift,
                ..FitConfig::default()
            };
            let fit = analyze(&encoder_signal(&data), &config).unwrap();
            let r = &fit.revolutions[0];
            let range = r.first_sample..r.first_sample + r.samples;
            let t = &data.time_s[range.clone()];
            let (t_mid, half) = (0.5 * (t[0] + t[t.len() - 1]), 0.5 * (t[t.len() - 1] - t[0]));
            let tau: Vec<f64> = t.iter().map(|t| (t - t_mid) / half).collect();
            let x = qr_fit(
                &data.angle_rad[range.clone()],
                drift.then_some(&tau[..]),
                &data.gap[range],
                order,
            );
            let k = &r.coefficients;
            approx::assert_relative_eq!(k.l0, x[0], max_relative = 1e-12);
            for j in 0..order {
                approx::assert_abs_diff_eq!(k.c[j], x[1 + j], epsilon = 1e-10);
                approx::assert_abs_diff_eq!(k.s[j], x[1 + order + j], epsilon = 1e-10);
            }
            if drift {
                approx::assert_relative_eq!(
                    k.drift_per_s.unwrap(),
                    x[2 * order + 1] / half,
                    max_relative = 1e-8
                );
            }
            // Residual RMS against the explicit residual.
            let rms = {
                let ss: f64 = (0..t.len())
                    .map(|i| {
                        let th = data.angle_rad[r.first_sample + i];
                        let mut v = x[0];
                        for j in 0..order {
                            let kk = (j + 1) as f64;
                            v += x[1 + j] * (kk * th).cos() + x[1 + order + j] * (kk * th).sin();
                        }
                        if drift {
                            v += x[2 * order + 1] * tau[i];
                        }
                        (data.gap[r.first_sample + i] - v).powi(2)
                    })
                    .sum();
                (ss / t.len() as f64).sqrt()
            };
            approx::assert_relative_eq!(r.residual_rms, rms, max_relative = 1e-6);
        }
    }
}

mod refusals {
    use super::*;

    fn base() -> (SyntheticRecording, SyntheticSamples) {
        let rec = recording(4, 2.5);
        let data = rec.generate();
        (rec, data)
    }

    #[test]
    fn non_finite_values_name_the_sample() {
        let (rec, mut data) = base();
        data.gap[17] = f64::NAN;
        let e = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap_err();
        assert!(
            matches!(
                e,
                HarmonicsError::NonFinite {
                    index: 17,
                    column: "gap",
                    ..
                }
            ),
            "{e}"
        );
        let (rec, mut data) = base();
        data.time_s[40] = f64::INFINITY;
        let e = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap_err();
        assert!(
            matches!(
                e,
                HarmonicsError::NonFinite {
                    index: 40,
                    column: "time",
                    ..
                }
            ),
            "{e}"
        );
        let (_, mut data) = base();
        data.angle_rad[5] = f64::NEG_INFINITY;
        let e = analyze(&encoder_signal(&data), &FitConfig::default()).unwrap_err();
        assert!(
            matches!(
                e,
                HarmonicsError::NonFinite {
                    index: 5,
                    column: "angle",
                    ..
                }
            ),
            "{e}"
        );
    }

    /// The gap is checked inside the fit's pass and outside the revolutions fitted: the
    /// error names the recording's first non-finite sample wherever it lies.
    #[test]
    fn a_non_finite_gap_is_named_by_its_first_sample_wherever_it_lies() {
        let gap_error =
            |data: &SyntheticSamples, rec: &SyntheticRecording, config: &FitConfig| match analyze(
                &rate_signal(rec, data),
                config,
            )
            .unwrap_err()
            {
                HarmonicsError::NonFinite {
                    index,
                    column: "gap",
                    ..
                } => index,
                e => panic!("{e}"),
            };
        let (rec, mut data) = base();
        let last = data.gap.len() - 1; // in the trailing incomplete revolution
        data.gap[last] = f64::INFINITY;
        assert_eq!(gap_error(&data, &rec, &FitConfig::default()), last);
        // Bad samples in the first revolution and after the last: the first by index.
        data.gap[last - 3] = f64::NAN;
        data.gap[20] = f64::NAN;
        assert_eq!(gap_error(&data, &rec, &FitConfig::default()), 20);
        // A sample beyond the revolutions asked for is still refused.
        let (rec, mut data) = base();
        data.gap[last] = f64::NAN;
        let one = FitConfig {
            revolutions: Some(1),
            ..FitConfig::default()
        };
        assert_eq!(gap_error(&data, &rec, &one), last);
    }

    #[test]
    fn a_finite_but_huge_sample_is_a_named_non_finite_result() {
        // One gap of 1e160 (finite): its square overflows ΣY². Before: Ok with std = inf and a
        // residual RMS of 0 (with drift) or of NaN; now an error naming the sample.
        for drift in [true, false] {
            let (rec, mut data) = base();
            data.gap[123] = 1e160;
            let config = FitConfig {
                drift,
                ..FitConfig::default()
            };
            let e = analyze(&rate_signal(&rec, &data), &config).unwrap_err();
            assert!(
                matches!(
                    e,
                    HarmonicsError::NonFiniteResult {
                        at_sample: 123,
                        largest_gap: 1e160,
                        ..
                    }
                ),
                "{e:?}"
            );
            assert!(e.to_string().contains("1e160 at sample 123"), "{e}");
        }
        // Just below the range: 1e150 squares to 1e300, and the fit is finite.
        let (rec, mut data) = base();
        data.gap[123] = 1e150;
        let fit = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap();
        assert!(fit.revolutions.iter().all(|r| r.residual_rms.is_finite()));
    }

    #[test]
    fn time_not_increasing() {
        let (rec, mut data) = base();
        data.time_s[100] = data.time_s[99];
        let e = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap_err();
        assert!(
            matches!(e, HarmonicsError::TimeNotIncreasing { index: 100, .. }),
            "{e}"
        );
    }

    #[test]
    fn gap_of_several_intervals() {
        let (rec, mut data) = base();
        for t in &mut data.time_s[300..] {
            *t += 0.01; // five intervals of 2 ms missing
        }
        let e = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap_err();
        assert!(
            matches!(e, HarmonicsError::SampleGap { index: 300, .. }),
            "{e}"
        );
        // Allowed with a wider tolerance.
        let loose = FitConfig {
            max_gap_intervals: 10.0,
            ..FitConfig::default()
        };
        assert!(analyze(&rate_signal(&rec, &data), &loose).is_ok());
    }

    #[test]
    fn encoder_stepping_back() {
        let (_, mut data) = base();
        data.angle_rad[250] = data.angle_rad[249] - 1e-3;
        let e = analyze(&encoder_signal(&data), &FitConfig::default()).unwrap_err();
        assert!(
            matches!(e, HarmonicsError::AngleNotIncreasing { index: 250, .. }),
            "{e}"
        );
    }

    #[test]
    fn less_than_one_revolution() {
        let rec = recording(4, 0.9);
        let data = rec.generate();
        let e = analyze(&rate_signal(&rec, &data), &FitConfig::default()).unwrap_err();
        match e {
            HarmonicsError::NoCompleteRevolution { turns, .. } => {
                approx::assert_abs_diff_eq!(turns, 0.9, epsilon = 0.01)
            }
            e => panic!("{e}"),
        }
        let e = analyze(&encoder_signal(&data), &FitConfig::default()).unwrap_err();
        assert!(
            matches!(e, HarmonicsError::NoCompleteRevolution { .. }),
            "{e}"
        );
        let one = [0.0];
        let signal = ProbeSignal {
            time_s: &one,
            gap: &one,
            angle: SpindleAngle::Encoder(&one),
        };
        assert!(matches!(
            analyze(&signal, &FitConfig::default()),
            Err(HarmonicsError::NoCompleteRevolution { samples: 1, .. })
        ));
    }

    #[test]
    fn too_few_revolutions_for_the_request() {
        let (rec, data) = base();
        let config = FitConfig {
            revolutions: Some(3),
            ..FitConfig::default()
        };
        let e = analyze(&rate_signal(&rec, &data), &config).unwrap_err();
        assert_eq!(
            e,
            HarmonicsError::TooFewRevolutions {
                requested: 3,
                available: 2
            }
        );
    }

    /// `per_rev` samples per revolution, uniform in time and angle.
    fn sparse(per_rev: usize, revolutions: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let n = per_rev * revolutions;
        let step = std::f64::consts::TAU / per_rev as f64;
        let t: Vec<f64> = (0..n).map(|i| i as f64 * 0.01).collect();
        let a: Vec<f64> = (0..n).map(|i| i as f64 * step).collect();
        let y: Vec<f64> = a.iter().map(|a| a.cos()).collect();
        (t, y, a)
    }

    #[test]
    fn too_few_samples_for_the_order() {
        let (t, y, a) = sparse(12, 3);
        let signal = ProbeSignal {
            time_s: &t,
            gap: &y,
            angle: SpindleAngle::Encoder(&a),
        };
        // 12 samples resolve order 5 (needs 12) but not order 6 (needs 14).
        assert!(
            analyze(
                &signal,
                &FitConfig {
                    order: 5,
                    ..FitConfig::default()
                }
            )
            .is_ok()
        );
        let e = analyze(
            &signal,
            &FitConfig {
                order: 6,
                ..FitConfig::default()
            },
        )
        .unwrap_err();
        assert_eq!(
            e,
            HarmonicsError::TooFewSamples {
                revolution: 0,
                first_sample: 0,
                got: 12,
                need: 14
            }
        );
        // The drift term needs one sample more at order 5.
        let e = analyze(
            &signal,
            &FitConfig {
                order: 5,
                drift: true,
                ..FitConfig::default()
            },
        )
        .unwrap_err();
        assert!(
            matches!(e, HarmonicsError::TooFewSamples { need: 13, .. }),
            "{e}"
        );
    }

    #[test]
    fn aliasing_is_refused() {
        // 40 samples per revolution, uniform in time, but the encoder shows the spindle
        // crossing 60° between two samples: order 4 (gap must stay below 45°) is aliased,
        // order 2 (below 90°) is not.
        let per_rev = 40;
        let n = per_rev * 3;
        let t: Vec<f64> = (0..n).map(|i| i as f64 * 0.01).collect();
        let hole = 60f64.to_radians();
        let rest = (std::f64::consts::TAU - hole) / (per_rev - 1) as f64;
        let a: Vec<f64> = (0..n)
            .map(|i| {
                let (r, j) = (i / per_rev, i % per_rev);
                r as f64 * std::f64::consts::TAU + j as f64 * rest
            })
            .collect();
        let y: Vec<f64> = a.iter().map(|a| 2.0 * a.sin()).collect();
        let signal = ProbeSignal {
            time_s: &t,
            gap: &y,
            angle: SpindleAngle::Encoder(&a),
        };
        let e = analyze(&signal, &FitConfig::default()).unwrap_err();
        match e {
            HarmonicsError::Aliasing {
                revolution: 0,
                order: 4,
                max_gap_rad,
                after_sample,
                ..
            } => {
                approx::assert_relative_eq!(max_gap_rad, hole, max_relative = 1e-9);
                assert_eq!(after_sample, per_rev - 1);
            }
            e => panic!("{e}"),
        }
        let fit = analyze(
            &signal,
            &FitConfig {
                order: 2,
                ..FitConfig::default()
            },
        )
        .unwrap();
        approx::assert_relative_eq!(fit.mean.s[0], 2.0, max_relative = 1e-9);
        // A sparse constant-rate recording: 10 samples per revolution resolve order 4 only.
        let (t, y, _) = sparse(10, 3);
        let signal = ProbeSignal {
            time_s: &t,
            gap: &y,
            angle: SpindleAngle::Rate {
                rate_rad_s: std::f64::consts::TAU / 0.1,
                start_angle_rad: 0.0,
            },
        };
        assert!(analyze(&signal, &FitConfig::default()).is_ok());
        let e = analyze(
            &signal,
            &FitConfig {
                order: 5,
                ..FitConfig::default()
            },
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                HarmonicsError::TooFewSamples { .. }
                    | HarmonicsError::Aliasing { .. }
                    | HarmonicsError::RateAliases { .. }
            ),
            "{e}"
        );
    }

    #[test]
    fn overflowing_intervals_are_refused() {
        for t in [vec![-1e308, 1e308], vec![-1e308, 1e308, 1.5e308]] {
            let e = check_time_axis(&t, 3.0).unwrap_err();
            assert!(
                matches!(e, HarmonicsError::NonFiniteInterval { index: 1, .. }),
                "{e}"
            );
            let y = vec![1.0; t.len()];
            let signal = ProbeSignal {
                time_s: &t,
                gap: &y,
                angle: SpindleAngle::Rate {
                    rate_rad_s: 1.0,
                    start_angle_rad: 0.0,
                },
            };
            assert!(matches!(
                analyze(&signal, &FitConfig::default()),
                Err(HarmonicsError::NonFiniteInterval { index: 1, .. })
            ));
        }
    }

    #[test]
    fn rate_too_fast_for_the_sampling_is_refused_before_segmenting() {
        let (rec, data) = base();
        // 1e300 rad/s overflowed the revolution count; 1e12 asked for terabytes.
        for rate_rad_s in [1e300, 1e12, f64::MAX] {
            let signal = ProbeSignal {
                angle: SpindleAngle::Rate {
                    rate_rad_s,
                    start_angle_rad: 0.0,
                },
                ..rate_signal(&rec, &data)
            };
            let e = analyze(&signal, &FitConfig::default()).unwrap_err();
            match e {
                HarmonicsError::RateAliases {
                    order: 4,
                    interval_s,
                    limit_rad,
                    ..
                } => {
                    approx::assert_relative_eq!(interval_s, 0.002, max_relative = 1e-9);
                    approx::assert_relative_eq!(
                        limit_rad,
                        std::f64::consts::FRAC_PI_4,
                        max_relative = 1e-15
                    );
                }
                e => panic!("{e}"),
            }
        }
        // Just below π/4 per interval the rate is accepted (then the revolutions are short).
        let signal = ProbeSignal {
            angle: SpindleAngle::Rate {
                rate_rad_s: 0.99 * std::f64::consts::FRAC_PI_4 / 0.002,
                start_angle_rad: 0.0,
            },
            ..rate_signal(&rec, &data)
        };
        assert!(!matches!(
            analyze(&signal, &FitConfig::default()),
            Err(HarmonicsError::RateAliases { .. })
        ));
        // A recording spanning more turns than samples, with a long gap allowed.
        let t = [0.0, 0.001, 0.002, 1e6];
        let y = [0.0; 4];
        let signal = ProbeSignal {
            time_s: &t,
            gap: &y,
            angle: SpindleAngle::Rate {
                rate_rad_s: 1.0,
                start_angle_rad: 0.0,
            },
        };
        let config = FitConfig {
            max_gap_intervals: 1e12,
            ..FitConfig::default()
        };
        assert!(matches!(
            analyze(&signal, &config),
            Err(HarmonicsError::RateAliases { interval_s, .. }) if interval_s > 9e5
        ));
    }

    #[test]
    fn encoder_rate_must_match_the_declared_rate() {
        let (rec, data) = base();
        let signal = encoder_signal(&data);
        let w = rec.rate_rad_s;
        // Within 2 %, on either side.
        for declared in [w, w * 1.019, w / 1.019] {
            assert!(check_encoder_rate(&signal, DeclaredRate::new(declared)).is_ok());
        }
        for declared in [w * 1.021, w / 1.021, 10f64.to_radians()] {
            match check_encoder_rate(&signal, DeclaredRate::new(declared)) {
                Err(HarmonicsError::RateMismatch {
                    declared_rad_s,
                    encoder_rad_s,
                    ..
                }) => {
                    assert_eq!(declared_rad_s, declared);
                    approx::assert_relative_eq!(encoder_rad_s, w, max_relative = 1e-9);
                }
                other => panic!("{other:?}"),
            }
        }
        // A speed ripple leaves the mean rate within the tolerance.
        let wobbly = SyntheticRecording {
            wobble_rad: 0.05,
            ..rec.clone()
        }
        .generate();
        assert!(check_encoder_rate(&encoder_signal(&wobbly), DeclaredRate::new(w)).is_ok());
        // The rate mode has nothing to compare; bad settings are refused.
        assert!(check_encoder_rate(&rate_signal(&rec, &data), DeclaredRate::new(1.0)).is_ok());
        assert!(matches!(
            check_encoder_rate(&signal, DeclaredRate::new(-1.0)),
            Err(HarmonicsError::InvalidRate { .. })
        ));
        assert!(matches!(
            check_encoder_rate(
                &signal,
                DeclaredRate {
                    rate_rad_s: w,
                    relative_tolerance: f64::NAN
                }
            ),
            Err(HarmonicsError::InvalidSetting {
                field: "relative_tolerance",
                requirement: Requirement::NonNegative,
                ..
            })
        ));
    }

    #[test]
    fn bad_settings() {
        let (rec, data) = base();
        let signal = rate_signal(&rec, &data);
        for order in [0, MAX_ORDER + 1] {
            let e = analyze(
                &signal,
                &FitConfig {
                    order,
                    ..FitConfig::default()
                },
            )
            .unwrap_err();
            assert_eq!(
                e,
                HarmonicsError::InvalidOrder {
                    order,
                    max: MAX_ORDER
                }
            );
        }
        let e = analyze(
            &signal,
            &FitConfig {
                max_gap_intervals: 0.5,
                ..FitConfig::default()
            },
        )
        .unwrap_err();
        assert!(matches!(
            e,
            HarmonicsError::InvalidSetting {
                field: "max_gap_intervals",
                ..
            }
        ));
        let e = analyze(
            &signal,
            &FitConfig {
                revolutions: Some(0),
                ..FitConfig::default()
            },
        )
        .unwrap_err();
        assert!(matches!(
            e,
            HarmonicsError::InvalidSetting {
                field: "revolutions",
                ..
            }
        ));
        let bad_rate = ProbeSignal {
            angle: SpindleAngle::Rate {
                rate_rad_s: -1.0,
                start_angle_rad: 0.0,
            },
            ..signal
        };
        assert_eq!(
            analyze(&bad_rate, &FitConfig::default()).unwrap_err(),
            HarmonicsError::InvalidRate { rate_rad_s: -1.0 }
        );
        let short = ProbeSignal {
            gap: &data.gap[1..],
            ..signal
        };
        assert!(matches!(
            analyze(&short, &FitConfig::default()),
            Err(HarmonicsError::LengthMismatch { column: "gap", .. })
        ));
    }
}

mod properties {
    use super::*;
    use proptest::prelude::*;

    prop_compose! {
        fn any_recording()(
            order in 1..=MAX_ORDER,
            rate_deg_s in 5.0..300.0_f64,
            sample_rate_hz in 200.0..3000.0_f64,
            start_angle_rad in -10.0..10.0_f64,
            start_time_s in -100.0..1000.0_f64,
            turns in 1.05..3.95_f64,
            l0 in -500.0..500.0_f64,
            scale in 0.1..10.0_f64,
            wobble_rad in 0.0..2.0_f64,
            seed in any::<u64>(),
        ) -> SyntheticRecording {
            let rate_rad_s = rate_deg_s.to_radians();
            let per_rev = std::f64::consts::TAU / rate_rad_s * sample_rate_hz;
            let mut coefficients = coefficients(order, l0);
            for v in coefficients.c.iter_mut().chain(coefficients.s.iter_mut()) {
                *v *= scale;
            }
            SyntheticRecording {
                rate_rad_s, sample_rate_hz, samples: (turns * per_rev) as usize, start_time_s,
                start_angle_rad, coefficients, noise_std: 0.0, wobble_rad, seed,
            }
        }
    }

    fn resolvable(rec: &SyntheticRecording) -> bool {
        // Slowest angular speed ω(1 − A/3); the largest step must resolve the order.
        let order = rec.coefficients.order() as f64;
        let max_step = rec.rate_rad_s * (1.0 + rec.wobble_rad / 3.0) / rec.sample_rate_hz;
        max_step < 0.5 * std::f64::consts::PI / order
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

        #[test]
        fn noise_free_coefficients_are_recovered(rec in any_recording()) {
            prop_assume!(resolvable(&rec));
            let data = rec.generate();
            let config = FitConfig { order: rec.coefficients.order(), max_gap_intervals: 5.0, ..FitConfig::default() };
            // The encoder angle describes the spindle whatever its wobble.
            let fit = analyze(&encoder_signal(&data), &config).unwrap();
            let tol = 1e-8 * (1.0 + rec.coefficients.l0.abs());
            prop_assert!(max_error(&fit.mean, &rec.coefficients) < tol, "{:?}", fit.mean);
            // All whole turns of the true angle are used (the last one may be short of closing
            // by less than a step, or dropped when it is short by more).
            let last = *data.time_s.last().unwrap();
            let turns = (rec.angle_at(last) - rec.start_angle_rad) / std::f64::consts::TAU;
            let used = fit.revolutions_used() as f64;
            prop_assert!(used <= turns.ceil() && used >= turns.floor(), "used {} of {} turns", used, turns);
            // Without wobble the rate gives the same angles.
            if rec.wobble_rad == 0.0 {
                let fit = analyze(&rate_signal(&rec, &data), &config).unwrap();
                prop_assert!(max_error(&fit.mean, &rec.coefficients) < tol);
            }
        }

        #[test]
        fn noisy_coefficients_are_recovered_within_the_noise(
            rec in any_recording(), sigma in 0.01..1.0_f64,
        ) {
            prop_assume!(resolvable(&rec));
            let rec = SyntheticRecording { noise_std: sigma, ..rec };
            let data = rec.generate();
            let config = FitConfig { order: rec.coefficients.order(), max_gap_intervals: 5.0, ..FitConfig::default() };
            let fit = analyze(&encoder_signal(&data), &config).unwrap();
            let samples: usize = fit.revolutions.iter().map(|r| r.samples).sum();
            // Standard error of a coefficient of the mean ≈ σ·√(2/samples); 6σ bound, with
            // room for the non-uniform angular density of a wobbling spindle.
            let bound = 6.0 * sigma * (2.0 / samples as f64).sqrt() * (1.0 + rec.wobble_rad);
            prop_assert!(max_error(&fit.mean, &rec.coefficients) < bound,
                "error {} bound {}", max_error(&fit.mean, &rec.coefficients), bound);
        }
    }
}
