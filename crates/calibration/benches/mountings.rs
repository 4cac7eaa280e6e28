//! The joint fit of the IEEE 836 model over five mountings (issue 29's speed line), on the
//! simulated PIGA campaign of `crates/calibration/tests/mountings` (IA in, out, at 45°,
//! tangential and up; 12 rates each, 60 points; the spindle's drift compensated, the arm
//! stretch fitted).
//!
//! `cargo bench -p calibration --bench mountings`:
//! - `fit`: one `fit_mountings` (the separability check, the design, the weighted QR fit);
//! - `gum_budget`: the fit and its Type B budget (`type_b_contributions`: five radii, fifteen
//!   fixture angles, g, the rate scale and the probe's scale, each by two refits: 47 fits),
//!   what a study's mountings section runs besides the probe's inputs.
//!
//! `bench/model_numpy.py --time` runs the same count of fits in NumPy (docs/PERFORMANCE.md).
//! The campaign is written for that script by the test `numpy_data` (`MODEL_NUMPY_DIR`).

use std::hint::black_box;

use accel_model::{AccelKind, ModelCoefficients, Mounting, MountingPreset, Term};
use calibration::{
    ArmStretch, JointSpec, MountingData, MountingsTypeB, Nuisances, ProbeCompensation,
    fit_mountings, type_b_contributions,
};
use criterion::{Criterion, criterion_group, criterion_main};
use kinematics::EARTH_RATE_RAD_S;
use simulate::{CampaignMounting, MountingCampaign, campaign_points, noisy_outputs};

const PRESETS: [(MountingPreset, f64); 5] = simulate::FIXTURE_MOUNTINGS;
const TRUTH: [(Term, f64); 8] = simulate::FIXTURE_PIGA_TRUTH;
const LATITUDE_DEG: f64 = simulate::FIXTURE_LATITUDE_DEG;
const PROBE: ProbeCompensation = ProbeCompensation {
    static_m: 5.6e-6,
    c_r_m_s2: 1.6e-6,
    c_r_u_m_s2: 0.0,
    static_across_m: -1.97e-6,
    c_ry_m_s2: 0.4e-6,
};

fn bench(c: &mut Criterion) {
    let spindle = simulate::fixture_spindle();
    let mut coefficients = ModelCoefficients::zero(AccelKind::Piga);
    for (t, v) in TRUTH {
        coefficients.set(t, v);
    }
    let rates: Vec<f64> = (0..12)
        .map(|i| (35.0 + 15.0 * f64::from(i)).to_radians())
        .collect();
    let campaign = MountingCampaign {
        spindle,
        coefficients,
        mountings: PRESETS
            .iter()
            .enumerate()
            .map(|(m, &(p, r))| CampaignMounting {
                axes: p.axes(),
                radius_m: r,
                bias_shift: 3e-6 * m as f64 * 0.56,
            })
            .collect(),
        rates_rad_s: rates.clone(),
    };
    let points = campaign_points(&campaign).expect("the campaign simulates");
    let outputs = noisy_outputs(&points, 1e-9, 4711, 0).expect("noise");
    let data: Vec<MountingData<'_>> = PRESETS
        .iter()
        .enumerate()
        .map(|(m, &(p, r))| MountingData {
            field: format!("mountings[{m}]"),
            mounting: Mounting::preset(p, r, 0.001),
            nuisances: if m == 0 {
                Nuisances::REFERENCE
            } else {
                Nuisances::REMOUNTED
            },
            rates_rad_s: &rates,
            outputs: &outputs[m],
            sigma: None,
        })
        .collect();
    let spec = JointSpec {
        kind: AccelKind::Piga,
        terms: TRUTH.iter().map(|(t, _)| *t).collect(),
        omega3: true,
        arm_stretch: ArmStretch::Fit,
        g_m_s2: 9.8,
        earth_rate_vertical_rad_s: EARTH_RATE_RAD_S * LATITUDE_DEG.to_radians().sin(),
        probe: Some(PROBE),
    };
    let type_b = MountingsTypeB {
        radius_u_m: 5e-6,
        g_u_m_s2: 1e-5,
        rate_u_relative: 1e-6,
        probe_scale_u_relative: 2e-3,
    };
    let lines = type_b_contributions(&spec, &data, &type_b).expect("the budget");
    assert_eq!(
        lines.len(),
        23,
        "five radii, fifteen angles, g, rate scale, probe scale"
    );

    let mut group = c.benchmark_group("mountings");
    group.bench_function("fit", |b| {
        b.iter(|| fit_mountings(black_box(&spec), black_box(&data)).expect("fits"));
    });
    group.bench_function("gum_budget", |b| {
        b.iter(|| {
            let fit = fit_mountings(black_box(&spec), black_box(&data)).expect("fits");
            let lines = type_b_contributions(&spec, &data, &type_b).expect("the budget");
            (fit, lines)
        });
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
