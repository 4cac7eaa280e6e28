//! The crate's error type.

/// Everything that can go wrong in `identify`.
///
/// Bad input never panics: it is reported through one of these variants, each carrying the
/// indices or values needed to locate the problem.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum IdentifyError {
    /// The design has no columns.
    #[error("the design matrix has no columns (nothing to estimate)")]
    NoUnknowns,
    /// Fewer observations than needed: least squares with a residual standard deviation needs
    /// at least one residual degree of freedom, i.e. `observations > unknowns`.
    #[error(
        "{observations} observations for {unknowns} unknowns: need more observations than unknowns"
    )]
    TooFewObservations {
        /// Number of observations (rows of the design).
        observations: usize,
        /// Number of unknowns (columns of the design).
        unknowns: usize,
    },
    /// The column-scaled design is numerically rank deficient: after column-pivoted QR only
    /// `rank` diagonal entries of R exceed `tolerance·|R₀₀|`.
    #[error(
        "design is rank deficient: numerical rank {rank} < {unknowns} unknowns at relative tolerance {tolerance_c}", tolerance_c = units::Compact(*tolerance)
    )]
    RankDeficient {
        /// Numerical rank found.
        rank: usize,
        /// Number of unknowns (columns).
        unknowns: usize,
        /// Relative tolerance on the diagonal of R that was applied.
        tolerance: f64,
    },
    /// A non-finite number (NaN or ±∞) in the input.
    #[error("non-finite value at row {row}{}", match column { Some(c) => format!(", column {c} of the design"), None => " of the observations".to_string() })]
    NonFinite {
        /// Row (observation index, 0-based).
        row: usize,
        /// Design column (0-based), or `None` when the value is in the observation vector.
        column: Option<usize>,
    },
    /// Lengths of inputs that must agree do not.
    #[error("dimension mismatch: {what} has {got} entries, expected {expected}")]
    DimensionMismatch {
        /// Which input is the wrong size.
        what: &'static str,
        /// Its size.
        got: usize,
        /// The size it must have.
        expected: usize,
    },
    /// A scalar parameter is out of its domain (e.g. a non-positive radius).
    #[error("invalid parameter {name} = {}: {requirement}", units::Compact(*value))]
    InvalidParameter {
        /// Name of the parameter, as in the function signature or the parameter struct.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What the value must satisfy.
        requirement: Requirement,
    },
    /// The calibration design of eq. 18 needs at least `need` distinct rates.
    #[error("{distinct} distinct rates: the eq. 18 calibration needs at least {need}")]
    TooFewDistinctRates {
        /// Distinct rates given.
        distinct: usize,
        /// Distinct rates needed.
        need: usize,
    },
    /// A result that is not finite (NaN or ±∞) although every input was: the inputs named
    /// take it out of the range of double precision.
    #[error("{quantity} is not finite ({}) for {}", units::Compact(*value), units::CompactList(inputs))]
    NonFiniteResult {
        /// The quantity, by the name its caller knows (`k2_sigma_rad_s_g2`, `delta_k2_rad_s_g2`).
        quantity: &'static str,
        /// The value computed (NaN or ±∞).
        value: f64,
        /// The scalar inputs that drove it out of range, by name, with their values.
        inputs: Vec<(&'static str, f64)>,
    },
    /// Numbers too large for double precision: the result would not be finite.
    #[error("{what} overflows double precision; rescale the data")]
    Overflow {
        /// What overflowed.
        what: &'static str,
    },
}

/// What a scalar parameter must satisfy ([`IdentifyError::InvalidParameter`]): the workspace's
/// one requirement vocabulary.
pub use units::Requirement;

impl From<units::Unmet<&'static str>> for IdentifyError {
    fn from(u: units::Unmet<&'static str>) -> Self {
        Self::InvalidParameter {
            name: u.field,
            value: u.value,
            requirement: u.requirement,
        }
    }
}

/// `Result` with [`IdentifyError`].
pub type Result<T> = std::result::Result<T, IdentifyError>;
