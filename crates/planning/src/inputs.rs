//! What a plan is made from, and its validation into a [`Problem`].

use crate::error::{PlanningError, Result};
use crate::grid::Grid;

/// Everything a plan needs: the centrifuge, the PIGA, the probe, the expected imbalance, the
/// Type B uncertainties, the schedule's limits, the target and the search's settings.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct PlanInputs {
    /// The centrifuge and the rates it may run at.
    pub centrifuge: CentrifugeSpec,
    /// The PIGA's nominal coefficients and output noise.
    pub piga: PigaSpec,
    /// The displacement probe that measures C_r during the same campaign.
    pub probe: ProbeSpec,
    /// The spindle's expected imbalance coefficient.
    pub c_r: CrSpec,
    /// Type B standard uncertainties (as the study's `uncertainty` section).
    #[cfg_attr(feature = "serde", serde(default))]
    pub type_b: TypeB,
    /// Number of points, time budget, settling and minimum revolutions.
    pub schedule: Schedule,
    /// The uncertainty target and the k2 tolerance.
    pub target: Target,
    /// The design criterion and the exchange algorithm's settings.
    #[cfg_attr(feature = "serde", serde(default))]
    pub search: Search,
    /// Both orientations (IA in and IA out) for the probe-free calibration of issue 20
    /// ([`plan_two_orientation`](crate::plan_two_orientation)); absent: the probe method only.
    #[cfg_attr(feature = "serde", serde(default, alias = "two_orientations"))]
    pub two_orientation: Option<crate::TwoOrientationPlanInputs>,
}

impl PlanInputs {
    /// The plan's centrifuge at `latitude_deg` (its radius, g and the expected C_r as the
    /// spindle's dynamic drift) and its PIGA's nominal coefficients, as `simulate` takes
    /// them: what a plan's simulation check (`plan --simulate`, one mounting or two)
    /// simulates.
    #[must_use]
    pub fn simulated(
        &self,
        latitude_deg: f64,
    ) -> (kinematics::Centrifuge, accel_model::PigaCoefficients) {
        let centrifuge = kinematics::Centrifuge {
            radius_m: self.centrifuge.radius_m,
            site: kinematics::Site {
                latitude_deg,
                earth_rate_rad_s: kinematics::EARTH_RATE_RAD_S,
                gravity_m_s2: self.centrifuge.g_m_s2,
            },
            error_motion: kinematics::ErrorMotion {
                c_r_m_s2: self.c_r.expected_m_s2,
                ..kinematics::ErrorMotion::ZERO
            },
        };
        let p = &self.piga;
        let piga = accel_model::PigaCoefficients {
            k0_rad_s: p.k0_rad_s,
            k1_rad_s_g: p.k1_rad_s_g,
            k2_rad_s_g2: p.k2_rad_s_g2,
            k3_rad_s_g3: p.k3_rad_s_g3,
        };
        (centrifuge, piga)
    }
}

/// The centrifuge.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct CentrifugeSpec {
    /// Working radius R, m.
    pub radius_m: f64,
    /// Gravity g, m/s².
    pub g_m_s2: f64,
    /// Lowest rate to use, deg/s (> 0).
    pub min_rate_deg_s: f64,
    /// Highest rate of the machine, deg/s.
    pub max_rate_deg_s: f64,
    /// Highest centripetal acceleration R·ω²/g allowed, g (absent: no limit beyond the rate).
    #[cfg_attr(feature = "serde", serde(default))]
    pub max_acceleration_g: Option<f64>,
    /// The candidate rates.
    pub candidates: Candidates,
}

/// The rates the planner may choose from.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum Candidates {
    /// `count` evenly spaced rates from `from_deg_s` to `to_deg_s`, both included.
    Grid {
        /// First rate, deg/s.
        from_deg_s: f64,
        /// Last rate, deg/s.
        to_deg_s: f64,
        /// Number of rates (≥ 2).
        count: usize,
    },
    /// These rates, deg/s.
    List(Vec<f64>),
}

/// The PIGA.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct PigaSpec {
    /// Nominal k0, rad/s.
    #[cfg_attr(feature = "serde", serde(default))]
    pub k0_rad_s: f64,
    /// Nominal k1, rad/(s·g) (non-zero).
    pub k1_rad_s_g: f64,
    /// Nominal k2, rad/(s·g²).
    #[cfg_attr(feature = "serde", serde(default))]
    pub k2_rad_s_g2: f64,
    /// Nominal k3, rad/(s·g³).
    #[cfg_attr(feature = "serde", serde(default))]
    pub k3_rad_s_g3: f64,
    /// Standard uncertainty of k1 when the calibration takes it as given, rad/(s·g) (default 0).
    #[cfg_attr(feature = "serde", serde(default))]
    pub k1_u_rad_s_g: f64,
    /// The noise of the PIGA's mean output.
    pub noise: NoiseSpec,
}

/// The noise of the PIGA's mean output at one rate point.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum NoiseSpec {
    /// σ of the mean output over one revolution, rad/s: the mean over n revolutions has
    /// σ/√n.
    PerRevolution {
        /// σ per revolution, rad/s.
        sigma_rad_s: f64,
    },
    /// σ of the mean output over one second, rad/s (a white-noise density, rad/s·√s): the
    /// mean over a dwell of T seconds has σ/√T.
    Density {
        /// σ of a one-second mean, rad/s·√s.
        sigma_1s_rad_s: f64,
    },
}

impl NoiseSpec {
    /// Weight (1/variance of the mean output) per second of recording at a rate with `tau_s`
    /// seconds per revolution, 1/(rad/s)².
    pub(crate) fn info_per_s(self, tau_s: f64) -> f64 {
        match self {
            NoiseSpec::PerRevolution { sigma_rad_s } => 1.0 / (tau_s * sigma_rad_s * sigma_rad_s),
            NoiseSpec::Density { sigma_1s_rad_s } => 1.0 / (sigma_1s_rad_s * sigma_1s_rad_s),
        }
    }
}

/// The displacement probe.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct ProbeSpec {
    /// Standard deviation of one gap sample, µm.
    pub noise_um: f64,
    /// Sampling rate, Hz.
    pub sample_rate_hz: f64,
    /// Height from the tilt pivot to the probe plane, mm.
    pub pivot_to_probe_mm: f64,
    /// Height from the probe plane to the PIGA plane, mm.
    pub probe_to_piga_mm: f64,
}

/// The spindle's imbalance coefficient.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct CrSpec {
    /// The C_r expected after balancing, m·s² (sets the uncompensated bias Δk2).
    pub expected_m_s2: f64,
    /// Its standard uncertainty for the compensation, m·s². Absent: predicted from the probe
    /// recorded at the plan's own points.
    #[cfg_attr(feature = "serde", serde(default))]
    pub u_m_s2: Option<f64>,
}

/// Type B standard uncertainties of the calibration's inputs, as the study's `uncertainty`
/// section (docs/CONFIGURATION.md), all defaulting to 0: the calibration's own
/// ([`calibration::TypeB`]), one definition for the study and the planner.
pub use calibration::TypeB;

/// The schedule's limits.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Schedule {
    /// Number of rate points (≥ 7: six unknowns and a residual degree of freedom).
    pub points: usize,
    /// Centrifuge time available, s: settling plus recording at every point.
    pub budget_s: f64,
    /// Time to change rate and settle before each point is recorded, s (default 0).
    #[cfg_attr(feature = "serde", serde(default))]
    pub settling_s: f64,
    /// Least number of whole revolutions recorded at a point (default 1).
    #[cfg_attr(feature = "serde", serde(default = "one"))]
    pub min_revolutions: u32,
    /// Whether two points may share a rate (default false).
    #[cfg_attr(feature = "serde", serde(default))]
    pub allow_repeats: bool,
}

#[cfg(feature = "serde")]
const fn one() -> u32 {
    1
}

/// What the calibration must achieve.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Target {
    /// The largest acceptable U95(k2) of the compensated calibration, rad/(s·g²).
    pub u95_k2_rad_s_g2: f64,
    /// The tolerance of k2 the calibration checks against (± this), rad/(s·g²), for the
    /// test-uncertainty ratio.
    pub tolerance_k2_rad_s_g2: f64,
    /// The fraction of the uncompensated U95 the uncompensated bias Δk2 may reach (default
    /// 0.1), for the largest acceptable |C_r|.
    #[cfg_attr(feature = "serde", serde(default = "tenth"))]
    pub bias_fraction: f64,
}

#[cfg(feature = "serde")]
const fn tenth() -> f64 {
    0.1
}

/// The design criterion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum Criterion {
    /// Smallest var(k2): c-optimal for the a² coefficient (the default).
    #[default]
    K2,
    /// Largest det(XᵀWX): D-optimal for all six coefficients.
    D,
}

impl std::fmt::Display for Criterion {
    /// The criterion in words, as the command line prints it: `smallest u(k2) (c-optimal)` or
    /// `largest det(XᵀWX) (D-optimal, all six coefficients)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::K2 => "smallest u(k2) (c-optimal)",
            Self::D => "largest det(XᵀWX) (D-optimal, all six coefficients)",
        })
    }
}

/// The exchange algorithm's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct Search {
    /// The criterion.
    pub criterion: Criterion,
    /// Random starts besides the evenly spread one (default 6).
    pub restarts: usize,
    /// Seed of the random starts (default 1).
    pub seed: u64,
}

impl Default for Search {
    fn default() -> Self {
        Search {
            criterion: Criterion::K2,
            restarts: 6,
            seed: 1,
        }
    }
}

/// Unknowns of the eq. 18 design ([`calibration::TERMS`]).
pub const UNKNOWNS: usize = calibration::TERMS;
/// The most revolutions a budget may hold at the fastest candidate (whole revolutions are
/// counted in `u32`).
const MAX_REVOLUTIONS: f64 = 1e9;
/// Index of the a² coefficient (k2) in the eq. 18 design ([`calibration::A2_TERM`]).
pub const K2: usize = calibration::A2_TERM;

/// The validated problem: candidates in range with their regressors, costs and information
/// per second.
#[derive(Debug, Clone)]
pub(crate) struct Problem {
    pub(crate) inputs: PlanInputs,
    /// Candidate rates, rad/s, ascending.
    pub(crate) rates_rad_s: Vec<f64>,
    /// Their eq. 18 regressors (scaled), seconds per revolution and weight per second.
    pub(crate) grid: Grid<UNKNOWNS>,
    /// The highest allowed rate (the lower of the rate and acceleration limits), deg/s.
    pub(crate) max_rate_deg_s: f64,
}

fn field(name: &'static str, value: f64, ok: bool, requirement: &'static str) -> Result<()> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(PlanningError::InvalidField {
            field: name,
            value,
            requirement,
        })
    }
}

/// What `centrifuge.g_m_s2` must be: [`units::GRAVITY_RANGE_M_S2`] in words.
const GRAVITY_REQUIREMENT: &str =
    "must lie within 9.7…9.9 m/s² (local gravity on the Earth's surface)";

fn positive(name: &'static str, value: f64) -> Result<()> {
    field(name, value, value > 0.0, "must be finite and > 0")
}

fn non_negative(name: &'static str, value: f64) -> Result<()> {
    field(name, value, value >= 0.0, "must be finite and ≥ 0")
}

fn finite(name: &'static str, value: f64) -> Result<()> {
    field(name, value, true, "must be finite")
}

/// The eq. 18 regressors `1, ω, ω², ω³, a², a³` at `w` rad/s ([`calibration::design_row`]).
pub(crate) fn regressors(w: f64, radius_m: f64, g_m_s2: f64) -> [f64; UNKNOWNS] {
    calibration::design_row(w, identify::Geometry { radius_m, g_m_s2 })
}

impl Problem {
    pub(crate) fn new(inputs: &PlanInputs) -> Result<Self> {
        let c = &inputs.centrifuge;
        positive("centrifuge.radius_m", c.radius_m)?;
        field(
            "centrifuge.g_m_s2",
            c.g_m_s2,
            units::GRAVITY_RANGE_M_S2.contains(&c.g_m_s2),
            // The words of `units::GRAVITY_RANGE_M_S2` (a test checks they agree).
            GRAVITY_REQUIREMENT,
        )?;
        positive("centrifuge.min_rate_deg_s", c.min_rate_deg_s)?;
        positive("centrifuge.max_rate_deg_s", c.max_rate_deg_s)?;
        let mut max_rate = c.max_rate_deg_s;
        let mut binding = "centrifuge.max_rate_deg_s";
        if let Some(a) = c.max_acceleration_g {
            positive("centrifuge.max_acceleration_g", a)?;
            let w = (a * c.g_m_s2 / c.radius_m).sqrt().to_degrees();
            if w < max_rate {
                max_rate = w;
                binding = "centrifuge.max_acceleration_g";
            }
        }
        if max_rate < c.min_rate_deg_s {
            return Err(PlanningError::RateRange {
                min_rate_deg_s: c.min_rate_deg_s,
                max_rate_deg_s: max_rate,
                binding,
            });
        }
        let p = &inputs.piga;
        for (name, v) in [
            ("piga.k0_rad_s", p.k0_rad_s),
            ("piga.k2_rad_s_g2", p.k2_rad_s_g2),
            ("piga.k3_rad_s_g3", p.k3_rad_s_g3),
        ] {
            finite(name, v)?;
        }
        field(
            "piga.k1_rad_s_g",
            p.k1_rad_s_g,
            p.k1_rad_s_g != 0.0,
            "must be finite and non-zero",
        )?;
        non_negative("piga.k1_u_rad_s_g", p.k1_u_rad_s_g)?;
        match p.noise {
            NoiseSpec::PerRevolution { sigma_rad_s } => {
                positive("piga.noise.sigma_rad_s", sigma_rad_s)?;
            }
            NoiseSpec::Density { sigma_1s_rad_s } => {
                positive("piga.noise.sigma_1s_rad_s", sigma_1s_rad_s)?;
            }
        }
        let pr = &inputs.probe;
        positive("probe.noise_um", pr.noise_um)?;
        positive("probe.sample_rate_hz", pr.sample_rate_hz)?;
        positive("probe.pivot_to_probe_mm", pr.pivot_to_probe_mm)?;
        non_negative("probe.probe_to_piga_mm", pr.probe_to_piga_mm)?;
        finite("c_r.expected_m_s2", inputs.c_r.expected_m_s2)?;
        if let Some(u) = inputs.c_r.u_m_s2 {
            non_negative("c_r.u_m_s2", u)?;
        }
        let t = &inputs.type_b;
        non_negative("type_b.radius_u_m", t.radius_u_m)?;
        non_negative("type_b.g_u_m_s2", t.g_u_m_s2)?;
        non_negative("type_b.rate_u_relative", t.rate_u_relative)?;
        non_negative("type_b.pivot_to_probe_u_mm", t.pivot_to_probe_u_mm)?;
        non_negative("type_b.probe_to_piga_u_mm", t.probe_to_piga_u_mm)?;
        non_negative("type_b.probe_gain_u_relative", t.probe_gain_u_relative)?;
        let s = &inputs.schedule;
        positive("schedule.budget_s", s.budget_s)?;
        non_negative("schedule.settling_s", s.settling_s)?;
        field(
            "schedule.min_revolutions",
            f64::from(s.min_revolutions),
            s.min_revolutions >= 1,
            "must be ≥ 1",
        )?;
        if s.points < UNKNOWNS + 1 {
            return Err(PlanningError::TooFewPoints {
                points: s.points,
                need: UNKNOWNS + 1,
            });
        }
        let tg = &inputs.target;
        positive("target.u95_k2_rad_s_g2", tg.u95_k2_rad_s_g2)?;
        positive("target.tolerance_k2_rad_s_g2", tg.tolerance_k2_rad_s_g2)?;
        positive("target.bias_fraction", tg.bias_fraction)?;

        let mut rates_deg_s: Vec<f64> = match &c.candidates {
            Candidates::Grid {
                from_deg_s,
                to_deg_s,
                count,
            } => {
                positive("centrifuge.candidates.from_deg_s", *from_deg_s)?;
                field(
                    "centrifuge.candidates.to_deg_s",
                    *to_deg_s,
                    *to_deg_s > *from_deg_s,
                    "must be finite and above from_deg_s",
                )?;
                field(
                    "centrifuge.candidates.count",
                    *count as f64,
                    (2..=100_000).contains(count),
                    "must lie in 2…100000",
                )?;
                (0..*count)
                    .map(|i| from_deg_s + (to_deg_s - from_deg_s) * i as f64 / (*count - 1) as f64)
                    .collect()
            }
            Candidates::List(list) => {
                for &r in list {
                    positive("centrifuge.candidates", r)?;
                }
                list.clone()
            }
        };
        // A rate a hair above the maximum through rounding of the grid still counts.
        let slack = 1e-9 * max_rate;
        rates_deg_s.retain(|&r| r >= c.min_rate_deg_s - slack && r <= max_rate + slack);
        rates_deg_s.sort_by(f64::total_cmp);
        rates_deg_s.dedup();
        let need = if s.allow_repeats { UNKNOWNS } else { s.points };
        if rates_deg_s.len() < need {
            return Err(PlanningError::TooFewCandidates {
                in_range: rates_deg_s.len(),
                need,
                min_rate_deg_s: c.min_rate_deg_s,
                max_rate_deg_s: max_rate,
                reason: if s.allow_repeats {
                    "six distinct rates for the six unknowns of eq. 18"
                } else {
                    "one distinct rate per point, as schedule.allow_repeats is false"
                },
            });
        }
        let rates_rad_s: Vec<f64> = rates_deg_s
            .iter()
            .map(|&r| units::deg_s_to_rad_s(r))
            .collect();
        let raw: Vec<[f64; UNKNOWNS]> = rates_rad_s
            .iter()
            .map(|&w| regressors(w, c.radius_m, c.g_m_s2))
            .collect();
        let grid = Grid::new(&rates_rad_s, &raw, |tau| p.noise.info_per_s(tau));
        let fastest = grid.tau_s.iter().copied().fold(f64::INFINITY, f64::min);
        field(
            "schedule.budget_s",
            s.budget_s,
            s.budget_s / fastest <= MAX_REVOLUTIONS,
            "must allow at most 1e9 revolutions at the fastest candidate",
        )?;
        Ok(Problem {
            inputs: inputs.clone(),
            rates_rad_s,
            grid,
            max_rate_deg_s: max_rate,
        })
    }
}

#[cfg(test)]
mod gravity_tests {
    #[test]
    fn the_gravity_requirement_states_the_shared_range() {
        let range = units::GRAVITY_RANGE_M_S2;
        let words = format!(
            "{}…{} m/s²",
            units::Compact(*range.start()),
            units::Compact(*range.end())
        );
        assert!(super::GRAVITY_REQUIREMENT.contains(&words), "{words}");
    }
}
