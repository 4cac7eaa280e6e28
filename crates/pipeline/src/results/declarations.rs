//! The declarations that turn a probe's first harmonic into C_r with nothing in the data to
//! show them wrong: the probe's measuring direction and the angle zero. One place writes
//! their words, for the terminal, the report, the certificate and the errors.

use serde::{Deserialize, Serialize};

/// The probe's measuring direction, as the study file names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum ProbeSign {
    /// Against O1X1 (the paper's set-up): the reading falls when the spindle moves towards
    /// the PIGA (the gap closes).
    #[default]
    #[serde(rename = "against_o1_x1")]
    AgainstO1X1,
    /// Along O1X1: the reading rises when the spindle moves towards the PIGA.
    #[serde(rename = "along_o1_x1")]
    AlongO1X1,
}

impl ProbeSign {
    /// The name the study file gives it (`against_o1_x1`, `along_o1_x1`).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::AgainstO1X1 => "against_o1_x1",
            Self::AlongO1X1 => "along_o1_x1",
        }
    }

    /// The convention in the words a person checks at the machine: which way the probe's
    /// reading moves when the spindle moves towards the PIGA (the arm at the angle zero,
    /// its PIGA end pointing at the probe).
    #[must_use]
    pub const fn words(self) -> &'static str {
        match self {
            Self::AgainstO1X1 => {
                "the probe's gap closes (its reading falls) when the spindle moves towards the PIGA \
                 (probe measuring against O1X1, the paper's set-up)"
            }
            Self::AlongO1X1 => {
                "the probe's reading rises when the spindle moves towards the PIGA (probe \
                 measuring along O1X1)"
            }
        }
    }
}

/// The angle zero of eq. 20–21 as the study declares it (`lever.angle_zero_deg`): what the
/// spindle encoder reads when the arm's PIGA end points at the probe (the arm along O1X1).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct AngleZero {
    /// The encoder's reading at the angle zero, deg (0 when not stated); measured angles are
    /// taken less it.
    pub angle_zero_deg: f64,
    /// Whether the study states it; when not, 0 is taken and every output says so.
    pub stated: bool,
}

impl AngleZero {
    /// The declaration in words, with the field that states it.
    #[must_use]
    pub fn words(&self) -> String {
        let at = "when the arm's PIGA end points at the probe (the arm along O1X1)";
        if !self.stated {
            return format!(
                "not stated: the encoder is taken to read 0° (an index pulse to rise) {at}; an \
                 encoder zero elsewhere turns the first harmonic by its offset and changes C_r \
                 with no other sign (state it as `lever.angle_zero_deg`)"
            );
        }
        let deg = units::Compact(self.angle_zero_deg);
        if self.angle_zero_deg == 0.0 {
            format!("the encoder reads 0° (an index pulse rises) {at} (`lever.angle_zero_deg`: 0)")
        } else {
            format!(
                "the encoder reads {deg}° (an index pulse: the spindle has turned {deg}° past \
                 its rising edge) {at} (`lever.angle_zero_deg`): measured angles are taken less \
                 {deg}°"
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_angle_zero_says_whether_it_was_stated() {
        let none = AngleZero::default().words();
        assert!(none.starts_with("not stated"), "{none}");
        assert!(none.contains("`lever.angle_zero_deg`"), "{none}");
        let thirty = AngleZero {
            angle_zero_deg: 30.0,
            stated: true,
        }
        .words();
        assert!(thirty.contains("reads 30°"), "{thirty}");
        assert!(thirty.contains("less 30°"), "{thirty}");
    }
}
