//! The crate's error type.

/// Everything that can go wrong when building or evaluating the kinematic chain.
///
/// Every variant names the offending input so that a scenario file can be fixed without
/// guessing.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum KinematicsError {
    /// An input that must be a finite number is NaN or infinite.
    #[error("{field} must be finite, got {}", units::Compact(*value))]
    NonFinite {
        /// Name of the input (as in the parameter structs, with its unit suffix).
        field: &'static str,
        /// The value that was given.
        value: f64,
    },
    /// An input that must be strictly positive is zero or negative.
    #[error("{field} must be > 0, got {}", units::Compact(*value))]
    NotPositive {
        /// Name of the input.
        field: &'static str,
        /// The value that was given.
        value: f64,
    },
    /// An input lies outside its admissible closed interval.
    #[error("{field} must lie in [{}, {}], got {}", units::Compact(*min), units::Compact(*max), units::Compact(*value))]
    OutOfRange {
        /// Name of the input.
        field: &'static str,
        /// The value that was given.
        value: f64,
        /// Smallest admissible value.
        min: f64,
        /// Largest admissible value.
        max: f64,
    },
    /// A spindle offset at a rate is not finite although the inputs were: the error-motion
    /// coefficients and the rate take it out of the range of double precision.
    #[error("{quantity} is not finite ({}) at rate_rad_s = {}", units::Compact(*value), units::Compact(*rate_rad_s))]
    NonFiniteResult {
        /// The offset (`dr_x_m`, `dr_y_m`, `dphi_x_rad`, `dphi_y_rad`).
        quantity: &'static str,
        /// The value computed.
        value: f64,
        /// The spindle rate, rad/s.
        rate_rad_s: f64,
    },
    /// A uniform rule with `points` nodes per revolution is not exact for harmonics up to
    /// `highest_harmonic`; at least `need` nodes are required.
    #[error(
        "{points} quadrature points per revolution cannot average harmonics up to {highest_harmonic} exactly; need at least {need}"
    )]
    TooFewQuadraturePoints {
        /// Number of nodes that was asked for.
        points: usize,
        /// Highest harmonic of the spindle angle present in the averaged quantity.
        highest_harmonic: usize,
        /// Smallest admissible number of nodes (`2 * highest_harmonic + 1`).
        need: usize,
    },
}

/// `Result` with this crate's [`KinematicsError`].
pub type Result<T> = core::result::Result<T, KinematicsError>;

impl From<units::Unmet<&'static str>> for KinematicsError {
    /// The shared checks (`units::finite`, `units::positive`, `units::require`) in this crate's
    /// words: a value that is not a number is `NonFinite` whatever was asked of it.
    fn from(u: units::Unmet<&'static str>) -> Self {
        let units::Unmet {
            field,
            value,
            requirement,
        } = u;
        match requirement {
            _ if !value.is_finite() => Self::NonFinite { field, value },
            units::Requirement::InRange { min, max } => Self::OutOfRange {
                field,
                value,
                min,
                max,
            },
            _ => Self::NotPositive { field, value },
        }
    }
}
