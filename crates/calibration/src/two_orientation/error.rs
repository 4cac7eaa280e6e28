//! What a two-orientation calibration refuses.

use identify::IdentifyError;
use uncertainty::UncertaintyError;

/// What a two-orientation calibration refuses. Every variant names the data set's field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TwoOrientationError {
    /// Fewer or more than two data sets, or one orientation only.
    #[error(
        "{field}: a two-orientation calibration needs one data set with the IA in and one with the IA out; got {got}"
    )]
    OneOrientationOnly {
        /// The list's field.
        field: String,
        /// What was given, in words.
        got: String,
    },
    /// Both data sets declare the same orientation.
    #[error(
        "{field}: both data sets are `{orientation}` (`{first}` and `{field}`); one must be IA in and the other IA out"
    )]
    SameOrientation {
        /// The second data set.
        field: String,
        /// The first.
        first: String,
        /// Their orientation, in words.
        orientation: &'static str,
    },
    /// A data set does not declare its orientation.
    #[error("{field}: the orientation is missing (`ia_in` or `ia_out`)")]
    MissingOrientation {
        /// The data set.
        field: String,
    },
    /// A data set does not declare its radius.
    #[error(
        "{field}: the radius is missing (`radius_m`: the PIGA's centre of mass to the spindle axis in this mounting)"
    )]
    MissingRadius {
        /// The data set.
        field: String,
    },
    /// A number outside its domain.
    #[error("{field} = {value}: {reason}")]
    Invalid {
        /// The field.
        field: String,
        /// Its value.
        value: f64,
        /// What is wrong.
        reason: &'static str,
    },
    /// Too few distinct rates in one orientation.
    #[error(
        "{field}: {distinct} distinct rates in the {orientation} data set; the joint model needs at least {need} per orientation"
    )]
    TooFewRates {
        /// The data set.
        field: String,
        /// Its orientation, in words.
        orientation: &'static str,
        /// Distinct rates given.
        distinct: usize,
        /// Distinct rates needed.
        need: usize,
    },
    /// The least-squares fit failed.
    #[error("the two-orientation fit: {0}")]
    Fit(#[source] IdentifyError),
    /// The IA-in data set's own eq. 18 calibration (k2 by the probe method) refused it.
    #[error("the IA-in data set's calibration: {0}")]
    Calibration(#[source] crate::CalibrationError),
    /// The uncertainty evaluation failed.
    #[error("the two-orientation uncertainty: {0}")]
    Uncertainty(#[source] UncertaintyError),
}
