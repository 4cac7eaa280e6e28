//! The mechanism section's run: a PIGA calibration simulated through the exact kinematic
//! chain with the C_r a phase measured, identified with and without compensation.
//!
//! The spindle is given the phase's static offset and dynamic coefficient
//! (`Δr_x = a + C_r·ω²`, everything else ideal); the simulator's PIGA table
//! ([`simulate::piga_table`]: eq. 15 averaged over whole revolutions of the exact chain,
//! eq. 5–13) gives the output at each calibration rate, and the eq. 18 design is fitted twice:
//! as measured, whose a² coefficient is `k2 + Δk2`, and after removing `k1·C_r·ω⁴/g`, whose a²
//! coefficient is k2 (eq. 17–19).

use identify::{Compensation, CrEstimate, Geometry, K1Source};
use kinematics::{Centrifuge, ErrorMotion, Site};
use simulate::{OutputNoise, piga_table};
use units::{deg_s_to_rad_s, um_to_m};

use super::validate::Mechanism;
use crate::error::{PipelineError, Result};
use crate::inputs::Core;
use crate::results::{MechanismPhase, MechanismResults, PhaseResults, PigaResult};

/// What the mechanism needs of a phase's radius-error fit.
#[derive(Debug, Clone, Copy, PartialEq)]
struct MeasuredDrift {
    /// `C_r`, m·s².
    pub(crate) c_r_m_s2: f64,
    /// σ(C_r), m·s², when the fit has one.
    pub(crate) c_r_sigma_m_s2: Option<f64>,
    /// The static offset `a`, µm.
    pub(crate) offset_um: f64,
}

/// A failure inside one phase, located by the caller.
#[derive(Debug)]
enum PhaseFailure {
    Model(accel_model::AccelModelError),
    Identify(identify::IdentifyError),
}

/// Simulates and identifies one phase's calibration; `seed` draws the output noise.
fn run_phase(
    geometry: Geometry,
    mechanism: &Mechanism,
    drift: MeasuredDrift,
    seed: u64,
) -> std::result::Result<MechanismPhase, PhaseFailure> {
    let piga = &mechanism.piga;
    let centrifuge = Centrifuge {
        radius_m: geometry.radius_m,
        site: Site {
            latitude_deg: mechanism.latitude_deg,
            earth_rate_rad_s: mechanism.earth_rate_rad_s,
            gravity_m_s2: geometry.g_m_s2,
        },
        error_motion: ErrorMotion {
            dr_xs_m: um_to_m(drift.offset_um),
            c_r_m_s2: drift.c_r_m_s2,
            ..ErrorMotion::ZERO
        },
    };
    let noise = OutputNoise {
        sigma_rad_s: mechanism.output_noise_rad_s,
        seed,
    };
    let rows = piga_table(&centrifuge, piga, &mechanism.rates_deg_s, &noise)
        .map_err(PhaseFailure::Model)?;
    let rates_rad_s: Vec<f64> = rows.iter().map(|r| deg_s_to_rad_s(r.rate_deg_s)).collect();
    let outputs: Vec<f64> = rows.iter().map(|r| r.output_rad_s).collect();
    let compensation = Compensation {
        c_r: CrEstimate {
            c_r_m_s2: drift.c_r_m_s2,
            c_r_sigma_m_s2: drift.c_r_sigma_m_s2.unwrap_or(0.0),
        },
        k1: K1Source::Given {
            k1_rad_s_g: piga.k1_rad_s_g,
        },
    };
    let cal = identify::identify_compensated(&rates_rad_s, &outputs, geometry, &compensation)
        .map_err(PhaseFailure::Identify)?;
    let k2_true = piga.k2_rad_s_g2;
    let k2_uncompensated = cal.uncompensated.k2_apparent_rad_s_g2;
    Ok(MechanismPhase {
        phase: String::new(),
        c_r_m_s2: drift.c_r_m_s2,
        c_r_sigma_m_s2: drift.c_r_sigma_m_s2,
        k2_true,
        k2_uncompensated,
        k2_uncompensated_sigma: cal.uncompensated.k2_apparent_sigma_rad_s_g2,
        k2_compensated: cal.k2_rad_s_g2,
        k2_compensated_sigma: drift.c_r_sigma_m_s2.map(|_| cal.k2_sigma_rad_s_g2),
        delta_k2_predicted: cal.delta_k2.delta_k2_rad_s_g2,
        delta_k2_apparent: k2_uncompensated - k2_true,
        k2_error_compensated: cal.k2_rad_s_g2 - k2_true,
        condition_number: cal.uncompensated.fit.condition_number,
    })
}

/// The label of the simulated phases' noise streams (`units::stream_seed`).
const PHASE_STREAM: u64 = 0x3EC4_A515;

/// The seed of simulated phase `n`'s output noise under the section's `seed`.
const fn phase_seed(seed: u64, n: usize) -> u64 {
    units::stream_seed(seed, PHASE_STREAM, n as u64)
}

/// Runs the mechanism section with the phases' radius-error fits `phases`.
pub(crate) fn run(
    inputs: &Core,
    m: &Mechanism,
    phases: &[PhaseResults],
) -> Result<MechanismResults> {
    let _span = tracing::info_span!("mechanism").entered();
    let geometry = inputs.geometry();
    let phase = |(n, &p): (usize, &usize)| {
        let results: &PhaseResults = &phases[p];
        let drift = MeasuredDrift {
            c_r_m_s2: results.fit.c_r_m_s2,
            c_r_sigma_m_s2: results.fit.c_r_sigma_m_s2,
            offset_um: results.fit.offset_um,
        };
        // One noise stream per simulated phase: the seed and the phase through
        // `units::stream_seed` (with `seed + n`, seed 1's phase 1 drew seed 2's phase 0)
        run_phase(geometry, m, drift, phase_seed(m.seed, n))
            .map(|phase| MechanismPhase {
                phase: results.name.clone(),
                ..phase
            })
            .map_err(|e| locate(e, &inputs.source, &format!("mechanism.phases[{n}]")))
    };
    Ok(MechanismResults {
        rates_deg_s: m.rates_deg_s.clone(),
        piga: PigaResult {
            k0_rad_s: m.piga.k0_rad_s,
            k1_rad_s_g: m.piga.k1_rad_s_g,
            k2_rad_s_g2: m.piga.k2_rad_s_g2,
            k3_rad_s_g3: m.piga.k3_rad_s_g3,
        },
        latitude_deg: m.latitude_deg,
        output_noise_rad_s: m.output_noise_rad_s,
        phases: m
            .phases
            .iter()
            .enumerate()
            .map(phase)
            .collect::<Result<Vec<_>>>()?,
    })
}

/// A mechanism failure as a study error naming the configuration and the section.
fn locate(failure: PhaseFailure, path: &std::path::Path, field: &str) -> PipelineError {
    match failure {
        PhaseFailure::Model(source) => PipelineError::AccelModel {
            path: path.to_owned(),
            field: field.to_owned(),
            source,
        },
        PhaseFailure::Identify(source) => PipelineError::Identify {
            path: path.to_owned(),
            field: field.to_owned(),
            source,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No phase of one seed draws the noise of a phase of a neighbouring seed.
    #[test]
    fn phase_seeds_do_not_depend_on_the_seed_plus_the_phase() {
        let seed1: Vec<u64> = (1..200).map(|n| phase_seed(1, n)).collect();
        let seed2: Vec<u64> = (0..199).map(|n| phase_seed(2, n)).collect();
        assert!(seed1.iter().all(|x| !seed2.contains(x)));
        assert_eq!(phase_seed(7, 3), phase_seed(7, 3));
    }
}
