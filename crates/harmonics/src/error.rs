//! The crate's error type.

/// Errors of the harmonic analysis.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum HarmonicsError {
    /// A geometric parameter is out of its domain (non-finite, zero or negative).
    #[error("invalid geometry: `{field}` = {value} (must be finite and > 0)")]
    InvalidGeometry {
        /// Name of the offending field.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// A harmonic coefficient is not finite.
    #[error("non-finite harmonic coefficient `{field}` = {value}")]
    NonFiniteCoefficient {
        /// Name of the offending coefficient.
        field: &'static str,
        /// The value given.
        value: f64,
    },
}

/// Result alias of this crate.
pub type Result<T> = std::result::Result<T, HarmonicsError>;
