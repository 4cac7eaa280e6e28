//! The crate's error type.

/// Everything that can go wrong when evaluating the PIGA model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AccelModelError {
    /// The centrifuge, site, error motion or quadrature was rejected by `kinematics`.
    #[error(transparent)]
    Kinematics(#[from] kinematics::KinematicsError),
    /// A PIGA coefficient is NaN or infinite.
    #[error("{field} must be finite, got {}", units::Compact(*value))]
    NonFinite {
        /// Name of the coefficient (with its unit suffix).
        field: &'static str,
        /// The value that was given.
        value: f64,
    },
    /// A rate in the list is NaN or infinite.
    #[error("rate #{index} must be finite, got {} rad/s", units::Compact(*value))]
    NonFiniteRate {
        /// Position of the rate in the list (from 0).
        index: usize,
        /// The value that was given.
        value: f64,
    },
    /// A result is not finite (NaN or ±∞) although every input was: the inputs named take it
    /// out of the range of double precision.
    #[error("{quantity} is not finite ({}) for {}", units::Compact(*value), units::CompactList(inputs))]
    NonFiniteResult {
        /// The quantity (`output_rad_s`, `a_x_g`, `omega_i_rad_s`, an eq. 17 term).
        quantity: &'static str,
        /// The value computed.
        value: f64,
        /// The scalar inputs that drove it out of range, by name, with their values.
        inputs: Vec<(&'static str, f64)>,
    },
    /// A quantity that must be > 0 is not.
    #[error("{field} must be finite and > 0, got {}", units::Compact(*value))]
    NotPositive {
        /// The field.
        field: &'static str,
        /// The value that was given.
        value: f64,
    },
    /// A mounting's case axes are not a right-handed orthonormal triad.
    #[error("the mounting's case axes are not a case frame: {reason}")]
    NotACaseFrame {
        /// What failed, in words.
        reason: &'static str,
    },
    /// The list of rates is empty.
    #[error("no rate points given")]
    NoRates,
}

/// `Result` with this crate's [`AccelModelError`].
pub type Result<T> = core::result::Result<T, AccelModelError>;
