//! Writes `fixtures/mountings/`: a simulated five-mounting PIGA campaign (issue 29,
//! `docs/MODEL.md`) on the two-orientation fixture's spindle (fixtures/scenarios/
//! two_orientation.ron: C_r = 1.6e-6 m·s², a drift across the arm, an arm stretch of
//! 0.48e-6 m·s² the probe does not see), so that the study fixtures/studies/mountings.ron
//! compensates it with that fixture's probe recordings. One table per mounting (rates in
//! deg/s, mean outputs in rad/s with 1e-9 rad/s of noise), and `truth.json` with the true
//! coefficients, mountings and spindle.
//!
//! `cargo run -p simulate --example mountings_fixture -- fixtures/mountings`

use std::fmt::Write as _;
use std::path::PathBuf;

use accel_model::{AccelKind, ModelCoefficients, MountedSpindle, MountingPreset, Term};
use kinematics::{Centrifuge, EARTH_RATE_RAD_S, ErrorMotion, Site};
use simulate::{CampaignMounting, MountingCampaign, campaign_points, noisy_outputs};

/// The mountings: preset, radius (m) and bias shift on remounting (rad/s).
const MOUNTINGS: [(MountingPreset, f64, f64); 5] = [
    (MountingPreset::IaIn, 2.5, 0.0),
    (MountingPreset::IaOut, 2.54, 4e-6),
    (MountingPreset::Ia45, 2.48, -2e-6),
    (MountingPreset::IaTangential, 2.52, 3e-6),
    (MountingPreset::IaAxial, 2.46, 1e-6),
];

/// The true coefficients (rad/s per gⁿ; misalignments in rad).
const TRUTH: [(Term, f64); 8] = [
    (Term::K0, 1e-5),
    (Term::K1, 0.56),
    (Term::K2, 5e-7),
    (Term::K3, 2e-8),
    (Term::Koq, 3e-7),
    (Term::Kio, 1e-6),
    (Term::DeltaO, 1e-4),
    (Term::DeltaP, -5e-5),
];

const NOISE_RAD_S: f64 = 1e-9;
const SEED: u64 = 29;
const LATITUDE_DEG: f64 = 39.9;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .ok_or("usage: mountings_fixture OUT_DIR")?,
    );
    std::fs::create_dir_all(&out)?;
    let spindle = MountedSpindle {
        centrifuge: Centrifuge {
            radius_m: 2.5,
            site: Site {
                latitude_deg: LATITUDE_DEG,
                earth_rate_rad_s: EARTH_RATE_RAD_S,
                gravity_m_s2: 9.8,
            },
            error_motion: ErrorMotion {
                dr_xs_m: 5.6e-6,
                dr_ys_m: -1.97e-6,
                c_r_m_s2: 1.6e-6,
                c_r_y_m_s2: 0.4e-6,
                ..ErrorMotion::ZERO
            },
        },
        arm_stretch_m_s2: 0.48e-6,
    };
    let mut coefficients = ModelCoefficients::zero(AccelKind::Piga);
    for (t, v) in TRUTH {
        coefficients.set(t, v);
    }
    let rates_deg_s: Vec<f64> = (0..12).map(|i| 35.0 + 15.0 * f64::from(i)).collect();
    let campaign = MountingCampaign {
        spindle,
        coefficients,
        mountings: MOUNTINGS
            .iter()
            .map(|&(p, r, shift)| CampaignMounting {
                axes: p.axes(),
                radius_m: r,
                bias_shift: shift,
            })
            .collect(),
        rates_rad_s: rates_deg_s.iter().map(|r| r.to_radians()).collect(),
    };
    let points = campaign_points(&campaign)?;
    let outputs = noisy_outputs(&points, NOISE_RAD_S, SEED, 0)?;
    for ((preset, ..), outs) in MOUNTINGS.iter().zip(&outputs) {
        let mut text = String::from("rate_deg_s,output_rad_s\n");
        for (r, y) in rates_deg_s.iter().zip(outs) {
            writeln!(text, "{r},{y:e}")?;
        }
        std::fs::write(out.join(format!("piga_{}.csv", preset.tag())), text)?;
    }
    // truth.json by hand: simulate keeps serde_json a test dependency
    let mut truth = String::from("{\n  \"coefficients\": {\n");
    let terms: Vec<String> = TRUTH
        .iter()
        .map(|(t, v)| format!("    \"{}\": {v:e}", t.symbol()))
        .collect();
    truth.push_str(&terms.join(",\n"));
    truth.push_str("\n  },\n  \"mountings\": [\n");
    let mountings: Vec<String> = MOUNTINGS
        .iter()
        .map(|(p, r, shift)| {
            format!(
                "    {{\"preset\": \"{}\", \"radius_m\": {r}, \"bias_shift_rad_s\": {shift:e}}}",
                p.tag()
            )
        })
        .collect();
    truth.push_str(&mountings.join(",\n"));
    write!(
        truth,
        "\n  ],\n  \"spindle\": {{\"dr_xs_m\": 5.6e-6, \"dr_ys_m\": -1.97e-6, \"c_r_m_s2\": 1.6e-6, \
         \"c_r_y_m_s2\": 4e-7, \"arm_stretch_m_s2\": 4.8e-7}},\n  \"latitude_deg\": \
         {LATITUDE_DEG},\n  \"g_m_s2\": 9.8,\n  \"noise_rad_s\": {NOISE_RAD_S:e},\n  \"seed\": \
         {SEED}\n}}\n"
    )?;
    std::fs::write(out.join("truth.json"), truth)?;
    Ok(())
}
