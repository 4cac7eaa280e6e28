//! The study configuration, read from RON.
//!
//! A study names the centrifuge geometry, the PIGA scale factor, gravity, the radius-error
//! model, and for the pre- and post-balance phases the rate points with what was measured at
//! each. See `docs/CONFIGURATION.md` for the file format.

use std::path::{Path, PathBuf};

use harmonics::LeverGeometry;
use identify::RadiusModel;
use serde::{Deserialize, Serialize};

use crate::error::{PipelineError, Result};
use crate::mechanism::MechanismConfig;
use crate::probe_analysis::RecordingSet;

/// A whole study: one centrifuge, one PIGA, a pre- and a post-balance phase.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyConfig {
    /// A short name for the study, used in reports.
    pub name: String,
    /// Static working radius `R` (PIGA centre of mass to spindle axis), m.
    pub radius_m: f64,
    /// Gravity used to express specific force in g, m/s².
    pub g_m_s2: f64,
    /// PIGA scale factor `k1`, rad/(s·g).
    pub k1_rad_s_g: f64,
    /// Heights that carry the probe's first harmonic to the PIGA plane, and the probe direction.
    pub lever: LeverGeometry,
    /// Model of the radius error against rate (default: the paper's `a + C_r·ω²`).
    #[serde(default = "default_model")]
    pub radius_model: RadiusModel,
    /// The phase measured before balancing.
    pub pre_balance: PhaseConfig,
    /// The phase measured after balancing.
    pub post_balance: PhaseConfig,
    /// A PIGA calibration simulated with the measured C_r, identified with and without
    /// compensation (absent: not run).
    #[serde(default)]
    pub mechanism: Option<MechanismConfig>,
}

const fn default_model() -> RadiusModel {
    RadiusModel::TwoTerm
}

/// The measurements of one phase (pre- or post-balance).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PhaseConfig {
    /// What was measured at each rate.
    pub points: Points,
    /// How the radius-error fit weighs the points (default: unweighted, the paper's).
    #[serde(default)]
    pub weighting: Weighting,
}

/// How the radius-error fit weighs its points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Weighting {
    /// Ordinary least squares: every point counts the same (the paper's fit).
    #[default]
    Unweighted,
    /// Each point weighted by `1/σ²` of its radius error, σ from the spread of its
    /// recording's per-revolution first harmonics (recordings with ≥ 2 revolutions only).
    /// Right when the rates were recorded with different numbers of samples or noise.
    InverseVariance,
}

/// What a phase provides at its rate points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Points {
    /// First-harmonic probe coefficients per rate (Table 1 of the paper).
    FirstHarmonic(Vec<HarmonicPoint>),
    /// Radius errors at the PIGA plane per rate.
    RadiusError(Vec<RadiusPoint>),
    /// Probe recordings, one per rate, fitted per revolution (eq. 20) for their first harmonic.
    Recordings(RecordingSet),
    /// Only the change of radius error between two rates, as the paper publishes for the
    /// pre-balance phase. It determines `C_r` exactly, with no standard error.
    RadiusChange {
        /// The lower rate, deg/s.
        from_rate_deg_s: f64,
        /// The higher rate, deg/s.
        to_rate_deg_s: f64,
        /// Radius error at `to_rate_deg_s` minus that at `from_rate_deg_s`, µm.
        change_um: f64,
    },
}

/// First-harmonic probe coefficients at one rate (eq. 21).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HarmonicPoint {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// Cosine coefficient of the probe's first harmonic, µm.
    pub dc1_um: f64,
    /// Sine coefficient of the probe's first harmonic, µm.
    pub ds1_um: f64,
}

/// Radius error at the PIGA plane at one rate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RadiusPoint {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// Radius error `Δr_xd + Δr_xs`, µm.
    pub radius_error_um: f64,
}

/// A configuration that was read from a file and validated.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedStudy {
    /// The file it came from (named in every later error).
    pub path: PathBuf,
    /// The validated configuration.
    pub config: StudyConfig,
}

impl StudyConfig {
    /// Reads and validates a study configuration.
    pub fn load(path: &Path) -> Result<LoadedStudy> {
        let text = std::fs::read_to_string(path).map_err(|source| PipelineError::Io {
            path: path.to_owned(),
            source,
        })?;
        Self::parse(&text, path)
    }

    /// Parses and validates RON text; `path` is only used to name the source in errors.
    pub fn parse(text: &str, path: &Path) -> Result<LoadedStudy> {
        // Optional sections are written without `Some(...)`.
        let options = ron::Options::default()
            .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
        let config: StudyConfig = options.from_str(text).map_err(|e| PipelineError::Parse {
            path: path.to_owned(),
            line: e.span.start.line,
            column: e.span.start.col,
            message: e.code.to_string(),
        })?;
        config.validate(path)?;
        Ok(LoadedStudy {
            path: path.to_owned(),
            config,
        })
    }

    /// Checks every number's domain, the rates' uniqueness and the number of points.
    pub fn validate(&self, path: &Path) -> Result<()> {
        let invalid = |field: String, value: f64, reason| PipelineError::InvalidField {
            path: path.to_owned(),
            field,
            value,
            reason,
        };
        let positive = |field: &str, value: f64| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(invalid(field.to_owned(), value, "must be finite and > 0"))
            }
        };
        positive("radius_m", self.radius_m)?;
        positive("g_m_s2", self.g_m_s2)?;
        positive("k1_rad_s_g", self.k1_rad_s_g)?;
        self.lever
            .validate()
            .map_err(|source| PipelineError::Harmonics {
                path: path.to_owned(),
                field: "lever".to_owned(),
                source,
            })?;
        for (name, phase) in [
            ("pre_balance", &self.pre_balance),
            ("post_balance", &self.post_balance),
        ] {
            phase.validate(name, self.radius_model, path)?;
        }
        if let Some(mechanism) = &self.mechanism {
            mechanism.validate(path)?;
        }
        Ok(())
    }
}

impl PhaseConfig {
    fn validate(&self, section: &str, model: RadiusModel, path: &Path) -> Result<()> {
        let invalid = |field: String, value: f64, reason| PipelineError::InvalidField {
            path: path.to_owned(),
            field,
            value,
            reason,
        };
        let finite = |field: String, value: f64| {
            if value.is_finite() {
                Ok(())
            } else {
                Err(invalid(field, value, "must be finite"))
            }
        };
        let rate = |field: String, value: f64| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(invalid(field, value, "a rate must be finite and > 0"))
            }
        };
        let list = format!("{section}.points");
        if self.weighting == Weighting::InverseVariance
            && !matches!(self.points, Points::Recordings(_))
        {
            return Err(PipelineError::Unsupported {
                path: path.to_owned(),
                field: format!("{section}.weighting"),
                reason: "inverse_variance weighting needs points given as recordings",
            });
        }
        let rates: Vec<f64> = match &self.points {
            Points::FirstHarmonic(points) => {
                for (i, p) in points.iter().enumerate() {
                    rate(format!("{list}[{i}].rate_deg_s"), p.rate_deg_s)?;
                    finite(format!("{list}[{i}].dc1_um"), p.dc1_um)?;
                    finite(format!("{list}[{i}].ds1_um"), p.ds1_um)?;
                }
                points.iter().map(|p| p.rate_deg_s).collect()
            }
            Points::RadiusError(points) => {
                for (i, p) in points.iter().enumerate() {
                    rate(format!("{list}[{i}].rate_deg_s"), p.rate_deg_s)?;
                    finite(format!("{list}[{i}].radius_error_um"), p.radius_error_um)?;
                }
                points.iter().map(|p| p.rate_deg_s).collect()
            }
            Points::Recordings(set) => {
                if set.files.is_empty() {
                    return Err(PipelineError::EmptyList {
                        path: path.to_owned(),
                        field: format!("{list}.files"),
                    });
                }
                set.fit
                    .validate()
                    .map_err(|source| PipelineError::Harmonics {
                        path: path.to_owned(),
                        field: format!("{list}.fit"),
                        source,
                    })?;
                finite(format!("{list}.start_angle_deg"), set.start_angle_deg)?;
                for (i, p) in set.files.iter().enumerate() {
                    rate(format!("{list}.files[{i}].rate_deg_s"), p.rate_deg_s)?;
                }
                set.files.iter().map(|p| p.rate_deg_s).collect()
            }
            Points::RadiusChange {
                from_rate_deg_s,
                to_rate_deg_s,
                change_um,
            } => {
                rate(format!("{list}.from_rate_deg_s"), *from_rate_deg_s)?;
                rate(format!("{list}.to_rate_deg_s"), *to_rate_deg_s)?;
                finite(format!("{list}.change_um"), *change_um)?;
                if from_rate_deg_s == to_rate_deg_s {
                    return Err(PipelineError::DuplicateRate {
                        path: path.to_owned(),
                        field: format!("{list}.to_rate_deg_s"),
                        first: format!("{list}.from_rate_deg_s"),
                        rate_deg_s: *to_rate_deg_s,
                    });
                }
                return Ok(());
            }
        };
        let items = match &self.points {
            Points::Recordings(_) => format!("{list}.files"),
            _ => list.clone(),
        };
        for (i, r) in rates.iter().enumerate() {
            if let Some(j) = rates[..i].iter().position(|q| q == r) {
                return Err(PipelineError::DuplicateRate {
                    path: path.to_owned(),
                    field: format!("{items}[{i}].rate_deg_s"),
                    first: format!("{items}[{j}].rate_deg_s"),
                    rate_deg_s: *r,
                });
            }
        }
        // One point more than the unknowns, so that the fit has a standard error.
        let need = model.unknowns() + 1;
        if rates.len() < need {
            return Err(PipelineError::TooFewPoints {
                path: path.to_owned(),
                field: list,
                got: rates.len(),
                need,
                model: model_name(model),
            });
        }
        Ok(())
    }
}

/// A human name of a radius-error model.
pub const fn model_name(model: RadiusModel) -> &'static str {
    match model {
        RadiusModel::TwoTerm => "a + C_r·ω²",
        RadiusModel::ThreeTerm => "a + b·ω + C_r·ω²",
    }
}
