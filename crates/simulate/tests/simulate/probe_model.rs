//! The probe model: for the noise-free signal, eq. 21 and eq. 22 hold exactly, so the
//! study's analysis (harmonic fit → lever projection) returns the PIGA-plane Δr_x.

use approx::assert_relative_eq;
use harmonics::{FitConfig, LeverGeometry, ProbeDirection, ProbeSignal, SpindleAngle, analyze};
use simulate::{LoadedScenario, SimulatedRecording, simulate};

use crate::common::{fit_order, modified, post_balance, pre_balance};

/// The harmonic fit of a recording, with the encoder angle when there is one.
fn fit(
    rec: &SimulatedRecording,
    rate_rad_s: f64,
    start_angle_rad: f64,
    order: usize,
) -> harmonics::HarmonicAnalysis {
    let angle_rad = rec.angle_rad();
    let angle = match &angle_rad {
        Some(a) => SpindleAngle::Encoder(a),
        None => SpindleAngle::Rate {
            rate_rad_s,
            start_angle_rad,
        },
    };
    let signal = ProbeSignal {
        time_s: &rec.time_s,
        gap: &rec.gap_um,
        angle,
    };
    let config = FitConfig {
        order,
        ..FitConfig::default()
    };
    analyze(&signal, &config).expect("simulated recordings are analysable")
}

fn noise_free(base: &LoadedScenario) -> LoadedScenario {
    modified(base, |s| {
        s.probe.noise_um = 0.0;
        s.piga.noise_rad_s = 0.0;
    })
}

/// Checks eq. 21–22 on every rate of a noise-free scenario.
fn check_exact(loaded: &LoadedScenario) {
    let s = &loaded.scenario;
    let sim = simulate(loaded).unwrap();
    let lever: LeverGeometry = s.probe.lever;
    let ratio = lever.lever_ratio().unwrap();
    let order = fit_order(s);
    for (rec, truth) in sim.recordings.iter().zip(&sim.truth.rates) {
        let a = fit(
            rec,
            truth.rate_rad_s,
            s.probe.start_angle_deg.to_radians(),
            order,
        );
        assert_eq!(a.revolutions_used(), truth.revolutions, "{}", rec.file_name);
        let h = a.first_harmonic().unwrap();
        let off = truth.offsets;
        // ΔR1 and β in the probe plane (eq. 6, 7 scaled by the cone)
        let dr1_um = off.drift_magnitude_m() * 1e6 / ratio;
        let beta = off.drift_azimuth_rad();
        let sign = match lever.probe_direction {
            ProbeDirection::AgainstO1X1 => -1.0,
            ProbeDirection::AlongO1X1 => 1.0,
        };
        // eq. 21: against O1X1, d_c1 = −ΔR1 cos β and d_s1 = ΔR1 sin β (signs flip along)
        assert_relative_eq!(h.c1, sign * dr1_um * beta.cos(), epsilon = 1e-9);
        assert_relative_eq!(h.s1, -sign * dr1_um * beta.sin(), epsilon = 1e-9);
        assert_relative_eq!(h.c1, truth.probe_first_harmonic.dc1_um, epsilon = 1e-9);
        assert_relative_eq!(h.s1, truth.probe_first_harmonic.ds1_um, epsilon = 1e-9);
        // the sleeve harmonics come back too
        for sh in &s.probe.sleeve_harmonics {
            assert_relative_eq!(a.mean.c[sh.order - 1], sh.c_um, epsilon = 1e-9);
            assert_relative_eq!(a.mean.s[sh.order - 1], sh.s_um, epsilon = 1e-9);
        }
        assert_relative_eq!(a.mean.l0, s.probe.l0_um, epsilon = 1e-9);
        // eq. 22: the projection is the PIGA-plane Δr_x = Δr_xs + C_r ω², exactly
        let d = lever.project(h).unwrap();
        let expect_um = (loaded.error_motion.dr_xs_m
            + loaded.error_motion.c_r_m_s2 * truth.rate_rad_s * truth.rate_rad_s)
            * 1e6;
        assert_relative_eq!(d.radius_error, expect_um, epsilon = 1e-9);
        assert_relative_eq!(d.radius_error, truth.radius_error_um, epsilon = 1e-9);
        assert_relative_eq!(d.beta_rad, beta, epsilon = 1e-9);
    }
}

#[test]
fn eq21_and_eq22_hold_exactly_without_noise_post_balance() {
    check_exact(&noise_free(&post_balance()));
}

#[test]
fn eq21_and_eq22_hold_exactly_without_noise_pre_balance() {
    check_exact(&noise_free(&pre_balance()));
}

#[test]
fn a_probe_along_o1x1_sees_the_negated_first_harmonic_and_the_same_radius_error() {
    let against = noise_free(&post_balance());
    let along = modified(&against, |s| {
        s.probe.lever.probe_direction = ProbeDirection::AlongO1X1;
    });
    check_exact(&along);
    let a = simulate(&against).unwrap();
    let b = simulate(&along).unwrap();
    for (x, y) in a.truth.rates.iter().zip(&b.truth.rates) {
        assert_eq!(
            x.probe_first_harmonic.dc1_um,
            -y.probe_first_harmonic.dc1_um
        );
        assert_eq!(
            x.probe_first_harmonic.ds1_um,
            -y.probe_first_harmonic.ds1_um
        );
    }
}

#[test]
fn without_encoder_and_ripple_the_rate_gives_the_angle() {
    let loaded = modified(&noise_free(&post_balance()), |s| {
        s.probe.encoder_angle = false;
        s.probe.speed_ripple = None;
        s.probe.start_angle_deg = 123.0;
    });
    let sim = simulate(&loaded).unwrap();
    assert!(sim.recordings.iter().all(|r| r.angle_deg.is_none()));
    check_exact(&loaded);
}

#[test]
fn the_gap_is_the_first_harmonic_plus_the_sleeve_at_every_sample() {
    let loaded = noise_free(&post_balance());
    let s = &loaded.scenario;
    let sim = simulate(&loaded).unwrap();
    for (rec, truth) in sim.recordings.iter().zip(&sim.truth.rates) {
        let angles = rec.angle_rad().unwrap();
        let h = truth.probe_first_harmonic;
        for (i, (&gap, &theta)) in rec.gap_um.iter().zip(&angles).enumerate() {
            let sleeve: f64 = s
                .probe
                .sleeve_harmonics
                .iter()
                .map(|k| {
                    let x = k.order as f64 * theta;
                    k.c_um * x.cos() + k.s_um * x.sin()
                })
                .sum();
            let model = s.probe.l0_um + h.dc1_um * theta.cos() + h.ds1_um * theta.sin() + sleeve;
            assert!((gap - model).abs() < 1e-9, "{} sample {i}", rec.file_name);
        }
    }
}

#[test]
fn speed_ripple_makes_the_encoder_angle_advance_unevenly_and_the_fit_follows_it() {
    let loaded = modified(&noise_free(&post_balance()), |s| {
        s.probe.speed_ripple = Some(simulate::SpeedRipple {
            amplitude_deg: 5.0,
            phase_deg: 25.0,
        });
    });
    let ripple_rad = 5f64.to_radians();
    let sim = simulate(&loaded).unwrap();
    let rec = &sim.recordings[0];
    let a = rec.angle_rad().unwrap();
    let w = sim.truth.rates[0].rate_rad_s;
    // the angle departs from ω·t by up to twice the ripple's amplitude
    let dev = a
        .iter()
        .zip(&rec.time_s)
        .map(|(theta, t)| {
            let d = (theta - w * t).rem_euclid(std::f64::consts::TAU);
            d.min(std::f64::consts::TAU - d)
        })
        .fold(0.0, f64::max);
    assert!(dev > ripple_rad && dev <= 2.0 * ripple_rad + 1e-12, "{dev}");
    // with the encoder the fit is exact (check_exact); assuming a uniform angle it is not
    let uniform = fit_uniform(rec, w);
    let truth = sim.truth.rates[0].probe_first_harmonic;
    let off = (uniform.first_harmonic().unwrap().c1 - truth.dc1_um).abs();
    assert!(off > 5e-3, "{off}");
    check_exact(&loaded);
}

fn fit_uniform(rec: &SimulatedRecording, rate_rad_s: f64) -> harmonics::HarmonicAnalysis {
    let signal = ProbeSignal {
        time_s: &rec.time_s,
        gap: &rec.gap_um,
        angle: SpindleAngle::Rate {
            rate_rad_s,
            start_angle_rad: 0.0,
        },
    };
    analyze(
        &signal,
        &FitConfig {
            order: 8,
            ..FitConfig::default()
        },
    )
    .unwrap()
}

/// Two probes: each reads the axis line `T + z·L` at its own height (no cone), so the two
/// noise-free first harmonics give back the chain's translation at the PIGA plane and the
/// lean; the second probe's recordings have their own names.
#[test]
fn two_probes_read_the_axis_line_at_their_heights() {
    let loaded = modified(&noise_free(&pre_balance()), |s| {
        s.second_probe = Some(simulate::SecondProbeSpec {
            probe_to_piga_mm: 1110.0,
            probe_direction: ProbeDirection::AlongO1X1,
        });
    });
    let s = &loaded.scenario;
    let sim = simulate(&loaded).unwrap();
    assert_eq!(sim.second_recordings.len(), sim.recordings.len());
    let order = fit_order(s);
    let start = s.probe.start_angle_deg.to_radians();
    for ((r1, r2), truth) in sim
        .recordings
        .iter()
        .zip(&sim.second_recordings)
        .zip(&sim.truth.rates)
    {
        assert_eq!(
            r2.file_name,
            simulate::second_recording_file_name(r1.rate_deg_s)
        );
        let h1 = fit(r1, truth.rate_rad_s, start, order)
            .first_harmonic()
            .unwrap();
        let h2 = fit(r2, truth.rate_rad_s, start, order)
            .first_harmonic()
            .unwrap();
        // the probes' axis points in O2 (µm): against O1X1 x = −d_c1, along x = d_c1
        let p1 = (-h1.c1, h1.s1);
        let p2 = (h2.c1, -h2.s1);
        let (z1, z2) = (-0.51, -1.11);
        let o = truth.offsets;
        // lean L = (Δφ_y, −Δφ_x) in µrad; translation T = Δr at the PIGA plane in µm
        let lean = ((p1.0 - p2.0) / (z1 - z2), (p1.1 - p2.1) / (z1 - z2));
        let t = (p1.0 - z1 * lean.0, p1.1 - z1 * lean.1);
        let tol = 1e-6;
        assert!((t.0 - o.dr_x_m * 1e6).abs() < tol, "{t:?} vs {o:?}");
        assert!((t.1 - o.dr_y_m * 1e6).abs() < tol, "{t:?} vs {o:?}");
        assert!(
            (lean.0 - o.dphi_y_rad * 1e6).abs() < tol,
            "{lean:?} vs {o:?}"
        );
        assert!(
            (lean.1 + o.dphi_x_rad * 1e6).abs() < tol,
            "{lean:?} vs {o:?}"
        );
        let second = truth.second_probe_first_harmonic.unwrap();
        assert_relative_eq!(second.dc1_um, h2.c1, epsilon = 1e-6);
        assert_relative_eq!(second.ds1_um, h2.s1, epsilon = 1e-6);
    }
    // a scenario without a second probe writes none and its truth has none
    let one = simulate(&noise_free(&pre_balance())).unwrap();
    assert!(one.second_recordings.is_empty());
    assert!(one.truth.rates[0].second_probe_first_harmonic.is_none());
}
