//! The solver's enums in a person's words (`Display`): what a report or a terminal shows
//! of them, never the Rust names. The one table of these words: the command line prints
//! these `Display`s.

use std::fmt;

use crate::{FitWarning, RadiusModel, SolverPath};

impl fmt::Display for SolverPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::ScaledColPivQr => "column-pivoted QR of the column-scaled design",
            Self::RefinedScaledColPivQr => {
                "column-pivoted QR of the column-scaled design, refined in double-double"
            }
        })
    }
}

impl fmt::Display for FitWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::RefinementNotConverged {
                iterations,
                relative_correction,
            } => write!(
                f,
                "the iterative refinement stopped contracting after {iterations} iterations \
                 (last relative correction {}): the design is too ill-conditioned for the \
                 trailing digits to be established",
                units::Compact(*relative_correction)
            ),
        }
    }
}

impl fmt::Display for RadiusModel {
    /// The model's formula: `a + C_r·ω²` or `a + b·ω + C_r·ω²`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::TwoTerm => "a + C_r·ω²",
            Self::ThreeTerm => "a + b·ω + C_r·ω²",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_hold_no_rust_names() {
        let texts = [
            SolverPath::ScaledColPivQr.to_string(),
            SolverPath::RefinedScaledColPivQr.to_string(),
            FitWarning::RefinementNotConverged {
                iterations: 30,
                relative_correction: 1e-9,
            }
            .to_string(),
            RadiusModel::TwoTerm.to_string(),
            RadiusModel::ThreeTerm.to_string(),
        ];
        for t in &texts {
            assert!(
                !t.contains("Qr") && !t.contains("Refinement") && !t.contains("Term"),
                "{t}"
            );
        }
        assert_eq!(texts[3], "a + C_r·ω²");
        assert!(texts[2].contains("30 iterations"), "{}", texts[2]);
    }
}
