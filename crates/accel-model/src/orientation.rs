//! Which way the PIGA's input axis points on the arm: towards the spindle axis (IA in, the
//! paper's mounting, eq. 10) or away from it (IA out), the sign `s` of eq. 23. One home for
//! the simulator's mountings and the two-orientation calibration.

/// Which way the PIGA's input axis points on the arm.
///
/// ```
/// use accel_model::Orientation;
/// assert_eq!(Orientation::IaOut.sign(), -1.0);
/// assert_eq!(Orientation::IaIn.label(), "IA in");
/// assert_eq!(Orientation::IaOut.tag(), "ia_out");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum Orientation {
    /// IA towards the spindle axis (the paper's mounting, eq. 10), s = +1.
    IaIn,
    /// IA away from the spindle axis (the PIGA turned 180° about an axis parallel to the
    /// spindle), s = −1.
    IaOut,
}

impl Orientation {
    /// `s`: +1 for IA in, −1 for IA out.
    #[must_use]
    pub const fn sign(self) -> f64 {
        match self {
            Self::IaIn => 1.0,
            Self::IaOut => -1.0,
        }
    }

    /// Words for a reader: `IA in` / `IA out`.
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Self::IaIn => "IA in",
            Self::IaOut => "IA out",
        }
    }

    /// The tag used in configuration and file names: `ia_in` / `ia_out`.
    #[must_use]
    pub const fn tag(self) -> &'static str {
        match self {
            Self::IaIn => "ia_in",
            Self::IaOut => "ia_out",
        }
    }
}

impl std::fmt::Display for Orientation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.label())
    }
}
