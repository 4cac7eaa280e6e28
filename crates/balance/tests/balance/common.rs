//! A simulated spindle, its probe phases and their first harmonics.

use std::path::Path;

use balance::{
    CalibrationContext, CorrectionPlane, PhasorFit, ProbePhase, ProbePoint, fit_phasors,
};
use harmonics::{FitConfig, ProbeSignal, SpindleAngle, analyze};
use kinematics::{ErrorMotionSpec, ImbalanceMass};
use simulate::{LoadedScenario, Scenario, simulate};

pub(crate) const PRE_BALANCE: &str = include_str!("../../../../fixtures/scenarios/pre-balance.ron");

/// The pre-balance fixture: 32 kg at 2.5 m on k_r = 5e7 N/m, C_r = 1.6e-6 m·s² (the paper's
/// pre-balance size), with `edit` applied.
pub(crate) fn scenario(edit: impl FnOnce(&mut Scenario)) -> LoadedScenario {
    let mut s = Scenario::parse(PRE_BALANCE, Path::new("pre-balance.ron"))
        .expect("fixture is valid")
        .scenario;
    edit(&mut s);
    s.check(Path::new("pre-balance.ron"))
        .expect("valid scenario")
}

/// Adds masses to the scenario's physical imbalance.
pub(crate) fn with_masses(s: &mut Scenario, masses: &[ImbalanceMass]) {
    let ErrorMotionSpec::Physical(p) = &mut s.error_motion else {
        panic!("the fixture is physical");
    };
    p.masses.extend_from_slice(masses);
}

/// The probe phase of a simulated run: per rate, the mean first harmonic and its white-noise
/// standard error (as the study computes it from the per-revolution fit residuals).
pub(crate) fn probe_points(loaded: &LoadedScenario) -> Vec<ProbePoint> {
    let sim = simulate(loaded).expect("simulates");
    recording_points(&sim.recordings, &sim.truth.rates)
}

/// Per rate, the mean first harmonic of recordings and its white-noise standard error.
pub(crate) fn recording_points(
    recordings: &[simulate::SimulatedRecording],
    rates: &[simulate::TruthRate],
) -> Vec<ProbePoint> {
    recordings
        .iter()
        .zip(rates)
        .map(|(rec, truth)| {
            let angle_rad = rec.angle_rad().expect("the fixture has an encoder");
            let signal = ProbeSignal {
                time_s: &rec.time_s,
                gap: &rec.gap_um,
                angle: SpindleAngle::Encoder(&angle_rad),
            };
            let a = analyze(&signal, &FitConfig::default()).expect("analysable");
            let h = a.first_harmonic().expect("finite");
            let samples: usize = a.revolutions.iter().map(|r| r.samples).sum();
            let pooled = a
                .revolutions
                .iter()
                .map(|r| r.residual_rms * r.residual_rms * r.samples as f64)
                .sum::<f64>()
                / samples as f64;
            let k = a.revolutions.len() as f64;
            let sigma = a
                .revolutions
                .iter()
                .map(|r| 2.0 * pooled / r.samples as f64)
                .sum::<f64>()
                .sqrt()
                / k;
            ProbePoint {
                rate_rad_s: truth.rate_rad_s,
                dc1_um: h.c1,
                ds1_um: h.s1,
                sigma_um: Some(sigma),
            }
        })
        .collect()
}

/// The phasor fit of a simulated run.
pub(crate) fn fit(loaded: &LoadedScenario, field: &str) -> PhasorFit {
    let points = probe_points(loaded);
    fit_phasors(&ProbePhase {
        field,
        points: &points,
        lever: loaded.scenario.probe.lever,
    })
    .expect("fits")
}

/// The fixture's calibration: k1 = 0.56, R = 2.5 m, g = 9.8, top rate 200.1234 deg/s, a
/// rotor of 2000 kg.
pub(crate) fn context() -> CalibrationContext {
    CalibrationContext {
        k1_rad_s_g: 0.56,
        radius_m: 2.5,
        g_m_s2: 9.8,
        top_rate_rad_s: 200.1234_f64.to_radians(),
        rotor_mass_kg: Some(2000.0),
    }
}

/// Correction masses at 2.5 m, any azimuth.
pub(crate) fn plane() -> CorrectionPlane {
    CorrectionPlane {
        radius_m: 2.5,
        fixed_azimuths_deg: vec![],
    }
}
