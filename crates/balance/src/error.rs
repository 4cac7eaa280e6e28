//! The balance advisor's one error type.

/// Result of the balance advisor.
pub type Result<T> = std::result::Result<T, BalanceError>;

/// Why the balance advisor refused its input. Every variant names the field, as a path the
/// caller chose (`initial.points[2].dc1_um`, `trial_mass.mass_kg`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BalanceError {
    /// A number outside its domain.
    #[error("{field} = {}: {requirement}", units::Compact(*value))]
    InvalidField {
        /// Path of the field.
        field: String,
        /// The value given.
        value: f64,
        /// What the field must be.
        requirement: Requirement,
    },
    /// The two probe planes at the same height: the axis through them is not determined.
    #[error("{field} = {}: must differ from the other plane's height", units::Compact(*value))]
    SameHeight {
        /// Path of the second plane's height.
        field: String,
        /// The height given, m.
        value: f64,
    },
    /// A phase with fewer rates than the phasor fit needs.
    #[error("{field}: {got} rates, the static/dynamic phasor fit needs at least {need}")]
    TooFewRates {
        /// Path of the phase's points.
        field: String,
        /// Rates given.
        got: usize,
        /// Rates needed.
        need: usize,
    },
    /// Two points of a phase at the same rate.
    #[error("{field}: rate {rate_rad_s} rad/s given twice")]
    DuplicateRate {
        /// Path of the second point.
        field: String,
        /// The rate, rad/s.
        rate_rad_s: f64,
    },
    /// The trial phase's dynamic phasor does not differ measurably from the initial one, so
    /// the influence coefficient is zero or lost in the noise (singular).
    #[error(
        "{field}: the trial run's dynamic phasor differs from the initial one by {change_um_s2} µm·s², \
         not more than 3σ = {three_sigma_um_s2} µm·s²: the influence coefficient is singular"
    )]
    SingularInfluence {
        /// Path of the trial phase.
        field: String,
        /// |D_trial − D_initial| at the PIGA plane, µm·s².
        change_um_s2: f64,
        /// Three standard deviations of that change along its largest principal axis, µm·s².
        three_sigma_um_s2: f64,
    },
    /// The correction's azimuth lies in a gap of 180° or more between the fixed mounting
    /// positions, so it cannot be split into non-negative masses on the two neighbours.
    #[error(
        "{field}: no two mounting positions less than 180° apart bracket the correction azimuth {azimuth_deg}°"
    )]
    CannotSplit {
        /// Path of the list of positions.
        field: String,
        /// The correction's azimuth, deg.
        azimuth_deg: f64,
    },
    /// The least-squares fit of the phasors failed.
    #[error("{field}: phasor fit")]
    Fit {
        /// Path of the phase.
        field: String,
        /// The solver's error.
        #[source]
        source: identify::IdentifyError,
    },
    /// The probe geometry was refused.
    #[error("{field}: probe geometry")]
    Geometry {
        /// Path of the geometry.
        field: String,
        /// The geometry's error.
        #[source]
        source: harmonics::HarmonicsError,
    },
    /// A result would not be a finite number (inputs at the edge of the floating-point range).
    #[error("{field}: the result is not finite")]
    NonFiniteResult {
        /// What was being computed.
        field: String,
    },
}

/// What a field must be: the workspace's one requirement vocabulary.
pub use units::Requirement;

impl From<units::Unmet<String>> for BalanceError {
    fn from(u: units::Unmet<String>) -> Self {
        Self::InvalidField {
            field: u.field,
            value: u.value,
            requirement: u.requirement,
        }
    }
}

impl From<units::Unmet<&str>> for BalanceError {
    fn from(u: units::Unmet<&str>) -> Self {
        Self::InvalidField {
            field: u.field.to_owned(),
            value: u.value,
            requirement: u.requirement,
        }
    }
}

/// `Ok(value)` when finite, else [`BalanceError::NonFiniteResult`].
pub(crate) fn finite_result(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(BalanceError::NonFiniteResult {
            field: field.to_owned(),
        })
    }
}
