//! The study's mechanism section: a PIGA calibration simulated through the exact kinematic
//! chain with the C_r the study measured, identified with and without compensation.
//!
//! For each phase the spindle is given the measured static offset and dynamic coefficient
//! (`Δr_x = a + C_r·ω²`, everything else ideal), the PIGA model of eq. 15 is averaged over whole
//! revolutions of the exact chain (eq. 5–13) at each calibration rate, and the eq. 18 design is
//! fitted twice: as measured, whose a² coefficient is `k2 + Δk2`, and after removing
//! `k1·C_r·ω⁴/g`, whose a² coefficient is k2 (eq. 17–19).

use std::path::Path;

use accel_model::PigaCoefficients;
use identify::{Compensation, K1Source};
use kinematics::{Centrifuge, ErrorMotion, Site};
use rand::{SeedableRng, rngs::StdRng};
use rand_distr::{Distribution, Normal};
use serde::{Deserialize, Serialize};

use crate::config::StudyConfig;
use crate::error::{PipelineError, Result};
use crate::results::PhaseResults;
use units::{deg_s_to_rad_s, um_to_m};

/// Configuration of the mechanism section (`mechanism: (...)` in the study file).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MechanismConfig {
    /// PIGA bias k0 of the simulated instrument, rad/s (k1 is the study's `k1_rad_s_g`).
    #[serde(default)]
    pub k0_rad_s: f64,
    /// True second-order coefficient k2, rad/(s·g²).
    pub k2_rad_s_g2: f64,
    /// Third-order coefficient k3, rad/(s·g³).
    #[serde(default)]
    pub k3_rad_s_g3: f64,
    /// Latitude of the centrifuge, degrees (default 45).
    #[serde(default = "default_latitude")]
    pub latitude_deg: f64,
    /// Earth rotation rate, rad/s (default [`kinematics::EARTH_RATE_RAD_S`]).
    #[serde(default = "default_earth_rate")]
    pub earth_rate_rad_s: f64,
    /// Calibration rates, deg/s: at least seven distinct (six unknowns and a residual degree
    /// of freedom).
    pub rates_deg_s: Vec<f64>,
    /// Standard deviation of the noise added to each per-rate mean output, rad/s (default 0:
    /// noise-free).
    #[serde(default)]
    pub output_noise_rad_s: f64,
    /// Seed of the output noise.
    #[serde(default)]
    pub seed: u64,
}

const fn default_latitude() -> f64 {
    45.0
}

const fn default_earth_rate() -> f64 {
    kinematics::EARTH_RATE_RAD_S
}

/// Least number of distinct calibration rates: six unknowns plus one degree of freedom.
pub(crate) const MIN_MECHANISM_RATES: usize = identify::MIN_DISTINCT_RATES + 1;

/// The mechanism section of the results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MechanismResults {
    /// Calibration rates, deg/s.
    pub rates_deg_s: Vec<f64>,
    /// The simulated PIGA.
    pub piga: PigaCoefficients,
    /// Latitude used, degrees.
    pub latitude_deg: f64,
    /// Noise added to each mean output, rad/s.
    pub output_noise_rad_s: f64,
    /// Before balancing.
    pub pre_balance: MechanismPhase,
    /// After balancing.
    pub post_balance: MechanismPhase,
}

/// One phase's simulated calibration. Coefficients in rad/(s·g²).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MechanismPhase {
    /// The measured C_r the spindle was given, m·s².
    pub c_r_m_s2: f64,
    /// Its standard deviation, m·s² (`None` when the phase has none, e.g. the exact
    /// two-point form; the compensation then takes C_r as exact).
    pub c_r_sigma_m_s2: Option<f64>,
    /// The simulated PIGA's k2.
    pub k2_true: f64,
    /// The a² coefficient of the plain eq. 18 fit: `k2 + Δk2`.
    pub k2_uncompensated: f64,
    /// Its standard error from the fit's residuals.
    pub k2_uncompensated_sigma: f64,
    /// The a² coefficient after removing `k1·C_r·ω⁴/g`.
    pub k2_compensated: f64,
    /// Its standard deviation: the fit's and σ(C_r)'s contributions (`None` when σ(C_r) is
    /// unknown).
    pub k2_compensated_sigma: Option<f64>,
    /// `Δk2 = k1·C_r·g/R²` (eq. 19).
    pub delta_k2_predicted: f64,
    /// `k2_uncompensated − k2_true`: the pseudo-second-order error the fit absorbed.
    pub delta_k2_apparent: f64,
    /// `k2_compensated − k2_true`: what compensation leaves.
    pub k2_error_compensated: f64,
    /// Condition number of the column-scaled eq. 18 design.
    pub condition_number: f64,
}

impl MechanismConfig {
    /// Checks every number, the rates' uniqueness and their number.
    pub(crate) fn validate(&self, path: &Path) -> Result<()> {
        let invalid = |field: String, value: f64, reason| PipelineError::InvalidField {
            path: path.to_owned(),
            field,
            value,
            reason,
        };
        for (field, value) in [
            ("mechanism.k0_rad_s", self.k0_rad_s),
            ("mechanism.k2_rad_s_g2", self.k2_rad_s_g2),
            ("mechanism.k3_rad_s_g3", self.k3_rad_s_g3),
        ] {
            if !value.is_finite() {
                return Err(invalid(field.to_owned(), value, "must be finite"));
            }
        }
        if !(self.latitude_deg.is_finite() && self.latitude_deg.abs() <= 90.0) {
            return Err(invalid(
                "mechanism.latitude_deg".to_owned(),
                self.latitude_deg,
                "must be finite and within ±90",
            ));
        }
        for (field, value) in [
            ("mechanism.earth_rate_rad_s", self.earth_rate_rad_s),
            ("mechanism.output_noise_rad_s", self.output_noise_rad_s),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(invalid(field.to_owned(), value, "must be finite and ≥ 0"));
            }
        }
        for (i, &rate) in self.rates_deg_s.iter().enumerate() {
            let field = format!("mechanism.rates_deg_s[{i}]");
            if !(rate.is_finite() && rate > 0.0) {
                return Err(invalid(field, rate, "a rate must be finite and > 0"));
            }
            if let Some(j) = self.rates_deg_s[..i].iter().position(|&q| q == rate) {
                return Err(PipelineError::DuplicateRate {
                    path: path.to_owned(),
                    field,
                    first: format!("mechanism.rates_deg_s[{j}]"),
                    rate_deg_s: rate,
                });
            }
        }
        if self.rates_deg_s.len() < MIN_MECHANISM_RATES {
            return Err(PipelineError::TooFewPoints {
                path: path.to_owned(),
                field: "mechanism.rates_deg_s".to_owned(),
                got: self.rates_deg_s.len(),
                need: MIN_MECHANISM_RATES,
                model: "eq. 18 calibration",
            });
        }
        Ok(())
    }
}

/// Runs the mechanism section for both phases.
pub(crate) fn run(
    config: &StudyConfig,
    mechanism: &MechanismConfig,
    pre: &PhaseResults,
    post: &PhaseResults,
    path: &Path,
) -> Result<MechanismResults> {
    let piga = PigaCoefficients {
        k0_rad_s: mechanism.k0_rad_s,
        k1_rad_s_g: config.k1_rad_s_g,
        k2_rad_s_g2: mechanism.k2_rad_s_g2,
        k3_rad_s_g3: mechanism.k3_rad_s_g3,
    };
    let phase = |phase: &PhaseResults, section: &str, seed: u64| {
        run_phase(config, mechanism, &piga, phase, seed).map_err(|e| e.locate(path, section))
    };
    Ok(MechanismResults {
        rates_deg_s: mechanism.rates_deg_s.clone(),
        piga,
        latitude_deg: mechanism.latitude_deg,
        output_noise_rad_s: mechanism.output_noise_rad_s,
        pre_balance: phase(pre, "mechanism.pre_balance", mechanism.seed)?,
        post_balance: phase(
            post,
            "mechanism.post_balance",
            mechanism.seed.wrapping_add(1),
        )?,
    })
}

/// A failure inside one phase, located by [`PhaseFailure::locate`].
enum PhaseFailure {
    Model(accel_model::Error),
    Identify(identify::IdentifyError),
}

impl PhaseFailure {
    fn locate(self, path: &Path, field: &str) -> PipelineError {
        match self {
            Self::Model(source) => PipelineError::AccelModel {
                path: path.to_owned(),
                field: field.to_owned(),
                source,
            },
            Self::Identify(source) => PipelineError::Identify {
                path: path.to_owned(),
                field: field.to_owned(),
                source,
            },
        }
    }
}

fn run_phase(
    config: &StudyConfig,
    mechanism: &MechanismConfig,
    piga: &PigaCoefficients,
    phase: &PhaseResults,
    seed: u64,
) -> std::result::Result<MechanismPhase, PhaseFailure> {
    let c_r_m_s2 = phase.fit.c_r_m_s2;
    let c_r_sigma_m_s2 = phase.fit.c_r_sigma_m_s2;
    let centrifuge = Centrifuge {
        radius_m: config.radius_m,
        site: Site {
            latitude_deg: mechanism.latitude_deg,
            earth_rate_rad_s: mechanism.earth_rate_rad_s,
            gravity_m_s2: config.g_m_s2,
        },
        error_motion: ErrorMotion {
            dr_xs_m: um_to_m(phase.fit.offset_um),
            c_r_m_s2,
            ..ErrorMotion::ZERO
        },
    };
    let rates_rad_s: Vec<f64> = mechanism
        .rates_deg_s
        .iter()
        .map(|&r| deg_s_to_rad_s(r))
        .collect();
    let points =
        accel_model::rate_points(&centrifuge, piga, &rates_rad_s).map_err(PhaseFailure::Model)?;
    let mut outputs: Vec<f64> = points.iter().map(|p| p.output_rad_s).collect();
    if mechanism.output_noise_rad_s > 0.0 {
        let mut rng = StdRng::seed_from_u64(seed);
        let normal = Normal::new(0.0, mechanism.output_noise_rad_s)
            .expect("σ was validated finite and positive");
        for y in &mut outputs {
            *y += normal.sample(&mut rng);
        }
    }
    let compensation = Compensation {
        c_r_m_s2,
        c_r_sigma_m_s2: c_r_sigma_m_s2.unwrap_or(0.0),
        k1: K1Source::Given {
            k1_rad_s_g: config.k1_rad_s_g,
        },
    };
    let cal = identify::identify_compensated(
        &rates_rad_s,
        &outputs,
        config.radius_m,
        config.g_m_s2,
        &compensation,
    )
    .map_err(PhaseFailure::Identify)?;
    let k2_true = piga.k2_rad_s_g2;
    let k2_uncompensated = cal.uncompensated.k2_apparent_rad_s_g2;
    Ok(MechanismPhase {
        c_r_m_s2,
        c_r_sigma_m_s2,
        k2_true,
        k2_uncompensated,
        k2_uncompensated_sigma: cal.uncompensated.k2_apparent_sigma_rad_s_g2,
        k2_compensated: cal.k2_rad_s_g2,
        k2_compensated_sigma: c_r_sigma_m_s2.map(|_| cal.k2_sigma_rad_s_g2),
        delta_k2_predicted: cal.delta_k2.delta_k2_rad_s_g2,
        delta_k2_apparent: k2_uncompensated - k2_true,
        k2_error_compensated: cal.k2_rad_s_g2 - k2_true,
        condition_number: cal.uncompensated.fit.condition_number,
    })
}
