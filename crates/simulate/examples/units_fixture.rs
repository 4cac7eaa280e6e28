//! Writes `fixtures/units/`: two PIGAs with different k0…k3 calibrated in one centrifuge run
//! (issue 30 part 4, several units per campaign). The scenario (fixtures/scenarios/units.ron)
//! is simulated once per unit, each with its own coefficients and its own noise seed; the
//! probe recordings of the first simulation are the run's (the spindle, the probe and their
//! seed are the scenario's, so every unit's simulation sees the same spindle), and each unit
//! gets its table of mean outputs with their σ (`piga_<label>.csv`: rate, output, σ). The
//! study fixtures/studies/units.ron measures C_r once from the probe recordings and
//! calibrates both units from it; `truth.json` holds each unit's coefficients and the spindle.
//!
//! `cargo run -p simulate --example units_fixture -- fixtures/scenarios/units.ron fixtures/units`

use std::fmt::Write as _;
use std::path::PathBuf;

use accel_model::PigaCoefficients;
use simulate::{Scenario, simulate};

/// The units: label, coefficients, and the offset of its noise seed from the scenario's.
const UNITS: [(&str, PigaCoefficients, u64); 2] = [
    (
        "A",
        PigaCoefficients {
            k0_rad_s: 1.0e-5,
            k1_rad_s_g: 0.56,
            k2_rad_s_g2: 5.0e-7,
            k3_rad_s_g3: 2.0e-8,
        },
        0,
    ),
    (
        "B",
        PigaCoefficients {
            k0_rad_s: -2.0e-5,
            k1_rad_s_g: 0.61,
            k2_rad_s_g2: -3.0e-7,
            k3_rad_s_g3: 1.0e-8,
        },
        1,
    ),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let (Some(scenario), Some(out)) = (args.next(), args.next()) else {
        return Err("usage: units_fixture SCENARIO OUT_DIR".into());
    };
    let out = PathBuf::from(out);
    std::fs::create_dir_all(&out)?;
    let base = Scenario::load(std::path::Path::new(&scenario))?;
    let seed = base.scenario.seed;
    let noise = base.scenario.piga.noise_rad_s;
    let mut truth_units = Vec::new();
    for (i, (label, coefficients, seed_offset)) in UNITS.iter().enumerate() {
        let mut loaded = base.clone();
        loaded.scenario.piga.coefficients = *coefficients;
        loaded.scenario.seed = seed + seed_offset;
        let sim = simulate(&loaded)?;
        if i == 0 {
            for r in &sim.recordings {
                let mut bytes = Vec::new();
                r.write_csv(&mut bytes)?;
                std::fs::write(out.join(&r.file_name), bytes)?;
            }
        }
        let mut table = String::from("rate_deg_s,output_rad_s,u_rad_s\n");
        for row in &sim.piga {
            writeln!(table, "{},{},{noise:e}", row.rate_deg_s, row.output_rad_s)?;
        }
        std::fs::write(out.join(format!("piga_{label}.csv")), table)?;
        let k = coefficients;
        truth_units.push(format!(
            "    {{\"label\": \"{label}\", \"k0_rad_s\": {:e}, \"k1_rad_s_g\": {}, \
             \"k2_rad_s_g2\": {:e}, \"k3_rad_s_g3\": {:e}, \"seed\": {}}}",
            k.k0_rad_s,
            k.k1_rad_s_g,
            k.k2_rad_s_g2,
            k.k3_rad_s_g3,
            seed + seed_offset
        ));
    }
    // truth.json by hand: simulate keeps serde_json a test dependency
    let m = &base.error_motion;
    let truth = format!(
        "{{\n  \"units\": [\n{}\n  ],\n  \"spindle\": {{\"dr_xs_m\": {:e}, \"dr_ys_m\": {:e}, \
         \"c_r_m_s2\": {:e}, \"c_r_y_m_s2\": {:e}}},\n  \"radius_m\": {},\n  \"g_m_s2\": {},\n  \
         \"noise_rad_s\": {noise:e},\n  \"probe_seed\": {seed}\n}}\n",
        truth_units.join(",\n"),
        m.dr_xs_m,
        m.dr_ys_m,
        m.c_r_m_s2,
        m.c_r_y_m_s2,
        base.scenario.centrifuge.radius_m,
        base.scenario.centrifuge.site.gravity_m_s2,
    );
    std::fs::write(out.join("truth.json"), truth)?;
    Ok(())
}
