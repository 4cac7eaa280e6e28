//! What kind of number an input's uncertainty is: its degrees of freedom, how it was evaluated
//! and the distribution a Monte Carlo trial draws it from. Plain values, imported by the
//! error type and the inputs alike.

/// Degrees of freedom of a standard uncertainty (JCGM 100 G.3, G.4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Dof {
    /// Finite degrees of freedom, ν > 0 (e.g. `n − 1` for the mean of `n` observations).
    Finite(f64),
    /// Infinite degrees of freedom: the standard uncertainty is known exactly.
    Infinite,
}

impl Dof {
    /// The number, `None` for infinity.
    pub fn finite(self) -> Option<f64> {
        match self {
            Dof::Finite(nu) => Some(nu),
            Dof::Infinite => None,
        }
    }
}

/// Degrees of freedom as a person reads them, the one way every output (terminal, report,
/// certificate) writes them: a whole number from 10 to 1000 (and a count below 10: `7`),
/// `> 1000` above, one decimal for a fraction below 10 (`2.3`), `∞` for infinitely many.
///
/// ```
/// use uncertainty::Dof;
/// assert_eq!(Dof::Finite(12.0).to_string(), "12");
/// assert_eq!(Dof::Finite(23.46).to_string(), "23");
/// assert_eq!(Dof::Finite(4.0).to_string(), "4");
/// assert_eq!(Dof::Finite(2.345).to_string(), "2.3");
/// assert_eq!(Dof::Finite(1.0e6).to_string(), "> 1000");
/// assert_eq!(Dof::Infinite.to_string(), "∞");
/// ```
impl std::fmt::Display for Dof {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Dof::Finite(nu) if nu > 1000.0 => f.write_str("> 1000"),
            Dof::Finite(nu) if nu >= 10.0 || nu.fract() == 0.0 => write!(f, "{nu:.0}"),
            Dof::Finite(nu) => write!(f, "{nu:.1}"),
            Dof::Infinite => f.write_str("∞"),
        }
    }
}

/// How a standard uncertainty was evaluated (JCGM 100 §4.2, §4.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Evaluation {
    /// Statistical analysis of a series of observations.
    TypeA,
    /// Any other means (certificates, specifications, judgement).
    TypeB,
}

/// The probability distribution a Monte Carlo trial draws an input from (JCGM 101 §6.4).
///
/// In every case `standard_uncertainty` is the standard uncertainty `u(x)` of the input; the
/// distribution's parameters follow from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Distribution {
    /// Gaussian `N(x, u²)` (§6.4.7).
    Normal,
    /// Rectangular on `[x − √3·u, x + √3·u]` (§6.4.2).
    Rectangular,
    /// Scaled and shifted t: `x + u·t_ν` with ν the input's (finite) degrees of freedom
    /// (§6.4.9: a Type A evaluation from `n` observations, `u = s/√n`, ν = `n − 1`). Its
    /// standard deviation is `u·√(ν/(ν−2))`, larger than `u`, and infinite for ν ≤ 2.
    StudentT,
}
