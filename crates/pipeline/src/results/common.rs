//! Types several sections' results share: an estimate with its uncertainty and degrees of
//! freedom.

use serde::{Deserialize, Serialize};

/// Degrees of freedom of an uncertainty: a number, or `"infinite"` (Type B, or a combination
/// dominated by Type B contributions) — never a JSON `null` standing for infinity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum DegreesOfFreedom {
    /// A finite number of degrees of freedom.
    Finite(f64),
    /// Infinitely many, written as the string `"infinite"`.
    Infinite(InfiniteDof),
}

impl DegreesOfFreedom {
    /// The uncertainty engine's [`uncertainty::Dof`] as the results write it.
    #[must_use]
    pub const fn from_dof(dof: uncertainty::Dof) -> Self {
        match dof {
            uncertainty::Dof::Finite(nu) => Self::Finite(nu),
            uncertainty::Dof::Infinite => Self::Infinite(InfiniteDof::Infinite),
        }
    }

    /// The same as the uncertainty engine's [`uncertainty::Dof`].
    #[must_use]
    pub const fn as_dof(self) -> uncertainty::Dof {
        match self {
            Self::Finite(nu) => uncertainty::Dof::Finite(nu),
            Self::Infinite(_) => uncertainty::Dof::Infinite,
        }
    }
}

/// As a person reads them: the one formatter of degrees of freedom ([`uncertainty::Dof`]'s
/// `Display`: `12`, `4`, `2.3`, `> 1000`, `∞`).
impl std::fmt::Display for DegreesOfFreedom {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.as_dof().fmt(f)
    }
}

/// The marker `"infinite"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InfiniteDof {
    /// Infinitely many degrees of freedom.
    Infinite,
}

/// An estimate and its standard uncertainty.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// Its standard uncertainty.
    pub u: f64,
}

/// The covariance matrix of a GUM evaluation's outputs (JCGM 102 §6.2: `U_y = C·U_x·Cᵀ`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OutputCovariance {
    /// The outputs, in the matrix's order.
    pub outputs: Vec<String>,
    /// The matrix, row by row, in the outputs' units.
    pub matrix: Vec<Vec<f64>>,
}

impl OutputCovariance {
    /// The covariance of the first `n` outputs of the GUM evaluation `gum`, named as the
    /// evaluation names them.
    pub(crate) fn of(gum: &uncertainty::GumResult, n: usize) -> Self {
        let m = gum.outputs.len();
        Self {
            outputs: gum.outputs[..n].iter().map(|o| o.name.clone()).collect(),
            matrix: (0..n)
                .map(|i| (0..n).map(|j| gum.covariance[i * m + j]).collect())
                .collect(),
        }
    }
}
