//! What the lab declares: the accelerometer's kind and chosen terms, and each mounting with
//! its data and its own nuisance terms.

use accel_model::{AccelKind, Mounting, Term};

/// A mounting's own nuisance terms, as eq. 23 has them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Nuisances {
    /// Its own bias (remounting shifts the bias: eq. 23's `k0,s`); the bias shift against
    /// the reference mounting is reported. The first mounting never has one (k0 is its bias).
    pub own_bias: bool,
    /// Its own scale factor (eq. 23's `k1,s`: the static drift and a radius error of this
    /// mounting read as a change of k1). The first mounting never has one.
    pub own_scale: bool,
    /// Its own ω term (the spindle's static tilt seen by IA as a rate and as gravity, the
    /// Coriolis term of the vertical Earth rate: eq. 18's ω column, eq. 23's `b1,s`).
    pub tilt_rate: bool,
}

impl Nuisances {
    /// The reference mounting's: its ω term only.
    pub const REFERENCE: Self = Self {
        own_bias: false,
        own_scale: false,
        tilt_rate: true,
    };
    /// A remounting's: its own bias and ω term.
    pub const REMOUNTED: Self = Self {
        own_bias: true,
        own_scale: false,
        tilt_rate: true,
    };
}

/// One mounting's data.
#[derive(Debug, Clone, PartialEq)]
pub struct MountingData<'a> {
    /// Where it came from, for errors (`mountings[1]`).
    pub field: String,
    /// The mounting as declared: its axes, radius and angular uncertainty.
    pub mounting: Mounting,
    /// Its nuisance terms.
    pub nuisances: Nuisances,
    /// Spindle rates, rad/s (finite, > 0).
    pub rates_rad_s: &'a [f64],
    /// Mean outputs over whole revolutions, in the kind's unit.
    pub outputs: &'a [f64],
    /// Each output's standard uncertainty (`None`: unweighted). A weighted fit needs σ for
    /// every mounting.
    pub sigma: Option<&'a [f64]>,
}

/// Whether the arm stretch (radius growth the probe cannot see) is fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArmStretch {
    /// Not fitted: the radius grows by the probe's C_r only (or not at all).
    Off,
    /// Fitted (eq. 23's γ = k1·C/g, a column `c_i·ω⁴` with `c_i` each mounting's radial IA
    /// component); the design must separate it.
    Fit,
    /// Fitted when the mountings separate it from the chosen terms, else not, and said so.
    Auto,
}

/// The probe's dynamic radius coefficient, compensated along each mounting's axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeCompensation {
    /// The static radius error at the accelerometer (the probe's radius-error fit at ω = 0,
    /// eq. 22: Δr_xs), m.
    pub static_m: f64,
    /// C_r, m·s² (`Δr_xd = C_r·ω²`).
    pub c_r_m_s2: f64,
    /// The static drift across the arm at the accelerometer (`Δr_ys`, from the probe's sine
    /// component), m: a tangential axis reads `Δr_y/R` of the radial input.
    pub static_across_m: f64,
    /// Its dynamic coefficient `C_ry`, m·s² (`Δr_yd = C_ry·ω²`).
    pub c_ry_m_s2: f64,
    /// Its standard uncertainty, m·s².
    pub c_r_u_m_s2: f64,
}

/// The joint fit's declaration.
#[derive(Debug, Clone, PartialEq)]
pub struct JointSpec {
    /// The accelerometer's kind.
    pub kind: AccelKind,
    /// The terms the lab chooses (k0 and k1 are always among them; order does not matter).
    pub terms: Vec<Term>,
    /// The ω³ term shared by every mounting (the spindle's dynamic tilt C_φ and the Coriolis
    /// term of the radius growth: eq. 18's and eq. 23's ω³ column, `c_i·ω³`).
    pub omega3: bool,
    /// The arm stretch.
    pub arm_stretch: ArmStretch,
    /// Gravity, m/s².
    pub g_m_s2: f64,
    /// The vertical Earth rate `ω_ie·sin L`, rad/s: a PIGA's IA with a vertical component
    /// reads it (with the spindle's rate) as a known rate, moved to the left.
    pub earth_rate_vertical_rad_s: f64,
    /// The probe's C_r, compensated in the nominal inputs (the radius at rate ω is
    /// `R + C_r·ω²`), or none.
    pub probe: Option<ProbeCompensation>,
}

impl JointSpec {
    /// The chosen terms, deduplicated, in the model's order.
    #[must_use]
    pub fn chosen_terms(&self) -> Vec<Term> {
        let mut t = self.terms.clone();
        t.sort();
        t.dedup();
        t
    }
}
