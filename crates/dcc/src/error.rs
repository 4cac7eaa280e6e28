//! The DCC writer's errors: each names the certificate's field or the quantity concerned.

/// What keeps a study's results from being written as a DCC.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum DccError {
    /// The results have no certificate section (nothing to certify).
    #[error(
        "the study has no certificate section: a digital calibration certificate states its statements (docs/CERTIFICATE.md)"
    )]
    NoCertificate,
    /// The results have no calibration (no coefficients to certify).
    #[error(
        "the study has no calibration results: a certificate states a calibration's coefficients"
    )]
    NoCalibration,
    /// An identification holds a character that hides, reorders or acts instead of showing.
    #[error(
        "field `{field}` holds the character U+{code_point:04X} at character {position}: an identification in the digital certificate must read as what it is (no control character, no bidirectional override); write it without"
    )]
    HiddenCharacter {
        /// The field (`certificate.item.serial`).
        field: String,
        /// The character's code point.
        code_point: u32,
        /// Its position in the text, in characters from 1.
        position: usize,
    },
    /// A text the DCC requires is blank.
    #[error("field `{field}` is blank: the digital certificate requires it")]
    EmptyText {
        /// The field.
        field: String,
    },
    /// A date that is not a calendar date written as ISO 8601 gives it.
    #[error(
        "field `{field}` = {value:?}: the digital certificate needs {expected}, written as ISO 8601 does (2026-11-19{span})"
    )]
    Date {
        /// The field (`certificate.dates.measured`).
        field: String,
        /// Its text (hidden characters written visibly).
        value: String,
        /// What was expected, in words.
        expected: &'static str,
        /// The example's second part for a span (` to 2026-11-20`), else empty.
        span: &'static str,
    },
    /// A span of dates that ends before it begins.
    #[error(
        "field `certificate.dates.measured`: the measurement ends ({end}) before it begins ({begin})"
    )]
    DateOrder {
        /// The first day.
        begin: String,
        /// The last day.
        end: String,
    },
    /// A number that is not finite (results are checked before; a results file can still
    /// hold one).
    #[error("{quantity} is not finite ({value}): a digital certificate states finite numbers only")]
    NonFinite {
        /// The quantity.
        quantity: String,
        /// Its value, as Rust writes it.
        value: String,
    },
    /// A coverage factor below 1, or an uncertainty below 0, which D-SI cannot hold.
    #[error("{quantity} = {value}: {requirement}")]
    OutOfDomain {
        /// The quantity.
        quantity: String,
        /// Its value.
        value: String,
        /// What it must be.
        requirement: &'static str,
    },
    /// A covariance matrix whose size does not match its coefficients.
    #[error(
        "the covariance matrix of the certified coefficients is not {n}×{n} (one row and column per coefficient)"
    )]
    CovarianceShape {
        /// The number of coefficients.
        n: usize,
    },
    /// The XML writer failed (it writes into memory: not expected).
    #[error("the XML writer failed: {message}")]
    Write {
        /// What it reported.
        message: String,
    },
}

/// The DCC writer's result.
pub type Result<T> = std::result::Result<T, DccError>;

impl From<std::io::Error> for DccError {
    fn from(e: std::io::Error) -> Self {
        Self::Write {
            message: e.to_string(),
        }
    }
}
