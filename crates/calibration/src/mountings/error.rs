//! What a joint fit over several mountings refuses.

use identify::IdentifyError;

/// What a joint fit over several mountings refuses. Every variant names the field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MountingsError {
    /// No mounting, or no term chosen.
    #[error(
        "{field}: {what} — a joint fit needs at least one mounting with data and one chosen term"
    )]
    Empty {
        /// The field.
        field: String,
        /// What is empty, in words.
        what: &'static str,
    },
    /// A number outside its domain.
    #[error("{field} = {}: {reason}", units::Compact(*value))]
    Invalid {
        /// The field (`mountings[2].rates[4]`).
        field: String,
        /// Its value.
        value: f64,
        /// What is wrong, in words.
        reason: &'static str,
    },
    /// Lengths that do not match.
    #[error("{field}: {got} values for {expected} rates")]
    Length {
        /// The field.
        field: String,
        /// Values given.
        got: usize,
        /// Rates.
        expected: usize,
    },
    /// A mounting's declared axes are not a case frame.
    #[error("{field}: {source}")]
    Mounting {
        /// The mounting's field.
        field: String,
        /// Why.
        #[source]
        source: accel_model::AccelModelError,
    },
    /// The chosen mountings cannot separate the chosen terms: the design is rank deficient.
    #[error("{0}")]
    NotSeparable(Box<super::report::Separability>),
    /// The least-squares fit failed.
    #[error("the joint fit over the mountings: {0}")]
    Fit(#[source] IdentifyError),
}
