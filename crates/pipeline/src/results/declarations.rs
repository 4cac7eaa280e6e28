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
    /// Whether a probe recording of the study measures its angle (an encoder or an index
    /// pulse): when none does, the angle zero moves nothing.
    #[serde(default)]
    pub measured_angles: bool,
}

impl AngleZero {
    /// The declaration in words, with the field that states it.
    #[must_use]
    pub fn words(&self) -> String {
        let at = "when the arm's PIGA end points at the probe (the arm along O1X1)";
        let deg = units::Compact(self.angle_zero_deg);
        if !self.measured_angles {
            let stated = if self.stated {
                format!("`lever.angle_zero_deg` = {deg}°")
            } else {
                "not stated".to_owned()
            };
            return format!(
                "{stated}; no probe recording of this study measures its angle, so it moves \
                 nothing (given first harmonics are taken as fitted from the angle zero, the \
                 arm's PIGA end pointing at the probe)"
            );
        }
        if !self.stated {
            return format!(
                "not stated: the encoder is taken to read 0° (an index pulse to rise) {at}; an \
                 encoder zero elsewhere turns the first harmonic by its offset and changes C_r \
                 with no other sign (state it as `lever.angle_zero_deg`)"
            );
        }
        if self.angle_zero_deg == 0.0 {
            format!("`lever.angle_zero_deg` = 0°: the encoder reads 0° (an index pulse rises) {at}")
        } else {
            format!(
                "`lever.angle_zero_deg` = {deg}°: the encoder reads {deg}° (an index pulse: the \
                 spindle has turned {deg}° past its rising edge) {at}; measured angles are taken \
                 less {deg}°"
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_angle_zero_says_whether_it_was_stated() {
        let none = AngleZero {
            measured_angles: true,
            ..AngleZero::default()
        }
        .words();
        assert!(none.starts_with("not stated"), "{none}");
        assert!(none.contains("`lever.angle_zero_deg`"), "{none}");
        let mut thirty = AngleZero {
            angle_zero_deg: 30.0,
            stated: true,
            measured_angles: true,
        };
        let words = thirty.words();
        assert!(words.contains("reads 30°"), "{words}");
        assert!(words.contains("less 30°"), "{words}");
        thirty.measured_angles = false;
        let words = thirty.words();
        assert!(
            words.starts_with("`lever.angle_zero_deg` = 30°;") && words.contains("moves nothing"),
            "{words}"
        );
    }
}
