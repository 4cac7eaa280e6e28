//! Writes a simulated five-mounting campaign (issue 29, `docs/MODEL.md`) on the
//! two-orientation fixture's spindle (fixtures/scenarios/two_orientation.ron: C_r = 1.6e-6
//! m·s², a drift across the arm, an arm stretch of 0.48e-6 m·s² the probe does not see), so
//! that a study compensates it with that fixture's probe recordings. One table per mounting
//! (rates in deg/s, mean outputs with white noise), and `truth.json` with the true
//! coefficients, mountings and spindle.
//!
//! - a PIGA (outputs in rad/s, 1e-9 rad/s of noise), for fixtures/studies/mountings.ron:
//!   `cargo run -p simulate --example mountings_fixture -- fixtures/mountings`
//! - a pendulous (quartz-flexure) accelerometer (outputs in mA, 2 nA of noise; the worked
//!   example of docs/MODEL.md), for fixtures/studies/mountings_pendulous.ron:
//!   `cargo run -p simulate --example mountings_fixture -- fixtures/mountings_pendulous pendulous`

use std::fmt::Write as _;
use std::path::PathBuf;

use accel_model::{AccelKind, ModelCoefficients, MountingPreset, OutputUnit, Term};
use simulate::{CampaignMounting, MountingCampaign, campaign_points, noisy_outputs};

/// The mountings: preset, radius (m) and bias shift on remounting (rad/s).
const MOUNTINGS: [(MountingPreset, f64, f64); 5] = [
    (MountingPreset::IaIn, 2.5, 0.0),
    (MountingPreset::IaOut, 2.54, 4e-6),
    (MountingPreset::Ia45, 2.48, -2e-6),
    (MountingPreset::IaTangential, 2.52, 3e-6),
    (MountingPreset::IaAxial, 2.46, 1e-6),
];

/// What differs between the two kinds: the model, its truth, the noise, the tables' names.
struct Kind {
    kind: AccelKind,
    truth: &'static [(Term, f64)],
    noise: f64,
    /// The table's file prefix and output column.
    prefix: &'static str,
    column: &'static str,
    /// The output unit's suffix in truth.json's keys.
    suffix: &'static str,
    /// The bias shifts' scale on remounting, output units (the PIGA's are in rad/s).
    shift_scale: f64,
}

const SEED: u64 = 29;
const LATITUDE_DEG: f64 = simulate::FIXTURE_LATITUDE_DEG;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let usage = "usage: mountings_fixture OUT_DIR [piga|pendulous]";
    let out = PathBuf::from(std::env::args().nth(1).ok_or(usage)?);
    let kind = match std::env::args().nth(2).as_deref() {
        None | Some("piga") => Kind {
            kind: AccelKind::Piga,
            truth: &simulate::FIXTURE_PIGA_TRUTH,
            noise: 1e-9,
            prefix: "piga",
            column: "output_rad_s",
            suffix: "rad_s",
            shift_scale: 1.0,
        },
        Some("pendulous") => Kind {
            kind: AccelKind::Pendulous {
                unit: OutputUnit::MilliAmpere,
            },
            truth: &simulate::FIXTURE_PENDULOUS_TRUTH,
            noise: 2e-6,
            prefix: "accel",
            column: "output_ma",
            suffix: "ma",
            // the PIGA's shifts in g (output / k1), as outputs of a 1.3 mA/g accelerometer
            shift_scale: 1.3 / 0.56,
        },
        Some(_) => return Err(usage.into()),
    };
    std::fs::create_dir_all(&out)?;
    let spindle = simulate::fixture_spindle();
    let mut coefficients = ModelCoefficients::zero(kind.kind);
    for &(t, v) in kind.truth {
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
                bias_shift: shift * kind.shift_scale,
            })
            .collect(),
        rates_rad_s: rates_deg_s.iter().map(|r| r.to_radians()).collect(),
    };
    let points = campaign_points(&campaign)?;
    let outputs = noisy_outputs(&points, kind.noise, SEED, 0)?;
    for ((preset, ..), outs) in MOUNTINGS.iter().zip(&outputs) {
        let mut text = format!("rate_deg_s,{}\n", kind.column);
        for (r, y) in rates_deg_s.iter().zip(outs) {
            writeln!(text, "{r},{y:e}")?;
        }
        std::fs::write(
            out.join(format!("{}_{}.csv", kind.prefix, preset.tag())),
            text,
        )?;
    }
    // truth.json by hand: simulate keeps serde_json a test dependency
    let mut truth = String::from("{\n  \"coefficients\": {\n");
    let terms: Vec<String> = kind
        .truth
        .iter()
        .map(|(t, v)| format!("    \"{}\": {v:e}", t.symbol()))
        .collect();
    truth.push_str(&terms.join(",\n"));
    truth.push_str("\n  },\n  \"mountings\": [\n");
    let mountings: Vec<String> = MOUNTINGS
        .iter()
        .map(|(p, r, shift)| {
            format!(
                "    {{\"preset\": \"{}\", \"radius_m\": {r}, \"bias_shift_{}\": {:e}}}",
                p.tag(),
                kind.suffix,
                shift * kind.shift_scale
            )
        })
        .collect();
    truth.push_str(&mountings.join(",\n"));
    write!(
        truth,
        "\n  ],\n  \"spindle\": {{\"dr_xs_m\": 5.6e-6, \"dr_ys_m\": -1.97e-6, \"c_r_m_s2\": 1.6e-6, \
         \"c_r_y_m_s2\": 4e-7, \"arm_stretch_m_s2\": 4.8e-7}},\n  \"latitude_deg\": \
         {LATITUDE_DEG},\n  \"g_m_s2\": 9.8,\n  \"noise_{}\": {:e},\n  \"seed\": \
         {SEED}\n}}\n",
        kind.suffix, kind.noise
    )?;
    std::fs::write(out.join("truth.json"), truth)?;
    Ok(())
}
