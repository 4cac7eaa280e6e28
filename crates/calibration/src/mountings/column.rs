//! The columns of the joint design, and their words.

use accel_model::Term;

use super::spec::MountingData;

/// A column of the joint design.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Column {
    /// A chosen term (shared by every mounting; k0 on the rows of the mountings without
    /// their own bias, k1 on those without their own scale factor).
    Term(Term),
    /// Mounting m's own bias (an indicator of its rows).
    OwnBias(usize),
    /// Mounting m's own scale factor (`A_i` on its rows).
    OwnScale(usize),
    /// Mounting m's ω term (`±ω` on its rows, the sign of its IA's radial component).
    TiltRate(usize),
    /// The shared ω³ term, `c_i·ω³`.
    Omega3,
    /// The arm stretch, `c_i·ω⁴`, coefficient γ = k1·C/g.
    ArmStretch,
}

impl Column {
    /// The column in a person's words, with the mountings' labels.
    #[must_use]
    pub fn label(&self, data: &[MountingData<'_>]) -> String {
        let name = |m: usize| data.get(m).map_or("?", |d| d.mounting.label.as_str());
        match *self {
            Self::Term(t) => t.symbol().to_owned(),
            Self::OwnBias(m) => format!("bias of {}", name(m)),
            Self::OwnScale(m) => format!("k1 of {}", name(m)),
            Self::TiltRate(m) => format!("ω term of {} (tilt, Coriolis)", name(m)),
            Self::Omega3 => "ω³ term (dynamic tilt)".to_owned(),
            Self::ArmStretch => "arm stretch C".to_owned(),
        }
    }
}
