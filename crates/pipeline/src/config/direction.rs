//! The probe's measuring direction as a study file or a lab profile names it (a leaf: the
//! study's `lever` and the profile's centrifuges both use it).

use serde::{Deserialize, Serialize};

use crate::results::ProbeSign;

/// Direction in which the displacement probe measures, relative to the sleeve axis O1X1:
/// which way its reading moves when the spindle moves towards the PIGA, the arm at the
/// angle zero. Each has a name that says it (`reading_falls_towards_piga`,
/// `reading_rises_towards_piga`) beside the paper's (`against_o1_x1`, `along_o1_x1`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum ProbeDirectionName {
    /// Against O1X1 (the paper's set-up, Fig. 3): the reading falls (the gap closes) when
    /// the spindle moves towards the PIGA.
    #[default]
    #[serde(rename = "against_o1_x1", alias = "reading_falls_towards_piga")]
    AgainstO1X1,
    /// Along O1X1: the reading rises when the spindle moves towards the PIGA.
    #[serde(rename = "along_o1_x1", alias = "reading_rises_towards_piga")]
    AlongO1X1,
}

impl ProbeDirectionName {
    /// The direction as results.json and the report state it ([`ProbeSign::words`] are its
    /// words, the one place they are written).
    #[must_use]
    pub const fn sign(self) -> ProbeSign {
        match self {
            Self::AgainstO1X1 => ProbeSign::AgainstO1X1,
            Self::AlongO1X1 => ProbeSign::AlongO1X1,
        }
    }

    /// The words a person checks at the machine ([`ProbeSign::words`]).
    #[must_use]
    pub const fn words(self) -> &'static str {
        self.sign().words()
    }
}
