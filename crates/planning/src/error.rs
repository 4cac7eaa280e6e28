//! The crate's error type.

/// Everything that can make a plan fail. Each variant names the field or the constraint
/// concerned and, for an infeasible plan, by how much it misses.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PlanningError {
    /// A field is not finite or outside its range.
    #[error("{field} = {}: {requirement}", units::Compact(*value))]
    InvalidField {
        /// The field's path in the plan, e.g. `piga.noise.sigma_rad_s`.
        field: &'static str,
        /// The value given.
        value: f64,
        /// What the field must satisfy.
        requirement: &'static str,
    },
    /// The highest rate the centrifuge allows lies below the lowest rate asked for.
    #[error(
        "the maximum rate {} deg/s (from {binding}) is below the minimum rate {} deg/s, by {} \
         deg/s",
        units::Compact(*max_rate_deg_s),
        units::Compact(*min_rate_deg_s),
        units::Compact(min_rate_deg_s - max_rate_deg_s)
    )]
    RateRange {
        /// `centrifuge.min_rate_deg_s`.
        min_rate_deg_s: f64,
        /// The effective maximum rate.
        max_rate_deg_s: f64,
        /// Which field sets the maximum (`centrifuge.max_rate_deg_s` or
        /// `centrifuge.max_acceleration_g`).
        binding: &'static str,
    },
    /// Fewer candidate rates inside the allowed range than the design has unknowns (or, without
    /// repeated rates, than points).
    #[error(
        "{in_range} candidate rates lie within {}…{} deg/s, {need} are needed ({reason}): {} \
         short",
        units::Compact(*min_rate_deg_s),
        units::Compact(*max_rate_deg_s),
        need - in_range
    )]
    TooFewCandidates {
        /// Candidates within the allowed range.
        in_range: usize,
        /// Candidates needed.
        need: usize,
        /// The lowest allowed rate, deg/s.
        min_rate_deg_s: f64,
        /// The highest allowed rate, deg/s.
        max_rate_deg_s: f64,
        /// Why that many are needed.
        reason: &'static str,
    },
    /// Fewer rate points than the eq. 18 design has unknowns, plus one residual degree of
    /// freedom.
    #[error(
        "schedule.points = {points}: the eq. 18 design has 6 unknowns and its Type A \
         evaluation needs a residual degree of freedom, so at least {need} points ({} short)",
        need - points
    )]
    TooFewPoints {
        /// Points asked for.
        points: usize,
        /// Least number of points.
        need: usize,
    },
    /// The settling time and the minimum revolutions alone exceed the time budget.
    #[error(
        "schedule.budget_s = {} s is shorter than the {:.1} s that settling ({:.1} s) and the \
         minimum revolutions ({:.1} s) of {points} points need, by {:.1} s",
        units::Compact(*budget_s),
        units::Compact(*needed_s),
        units::Compact(*settling_s),
        units::Compact(*minimum_s),
        units::Compact(needed_s - budget_s)
    )]
    BudgetTooShort {
        /// The budget, s.
        budget_s: f64,
        /// The least time of any plan with this many points, s.
        needed_s: f64,
        /// Of which settling, s.
        settling_s: f64,
        /// Of which the minimum revolutions at the fastest candidates, s.
        minimum_s: f64,
        /// Points.
        points: usize,
    },
    /// A two-orientation plan's remount, settling and minimum revolutions alone exceed the
    /// time budget.
    #[error(
        "schedule.budget_s = {} s is shorter than the {:.1} s that turning the PIGA round \
         (two_orientation.remount_s = {} s), settling ({:.1} s) and the minimum revolutions \
         ({:.1} s) of {points} points in two mountings need, by {:.1} s",
        units::Compact(*budget_s),
        units::Compact(*needed_s),
        units::Compact(*remount_s),
        units::Compact(*settling_s),
        units::Compact(*minimum_s),
        units::Compact(needed_s - budget_s)
    )]
    TwoOrientationBudgetTooShort {
        /// The budget, s.
        budget_s: f64,
        /// The least time of any two-orientation plan with this many points, s.
        needed_s: f64,
        /// Of which the remount, s.
        remount_s: f64,
        /// Of which settling, s.
        settling_s: f64,
        /// Of which the minimum revolutions at the fastest candidates, s.
        minimum_s: f64,
        /// Points in both mountings.
        points: usize,
    },
    /// The best plan within the budget misses the target U95(k2).
    #[error(
        "target.u95_k2_rad_s_g2 = {target:.4e} rad/(s·g²) is not reached: the best plan within \
         schedule.budget_s = {} s gives U95(k2) = {achieved:.4e} ({:.1} % above the target); {}",
        units::Compact(*budget_s),
        units::Compact(100.0 * (achieved / target - 1.0)),
        match needed_budget_s {
            Some(t) => format!("about {:.0} s of centrifuge time would reach it", units::Compact(*t)),
            None => format!(
                "no budget reaches it: the Type B inputs alone give U95 = {type_b_floor:.4e}"
            ),
        }
    )]
    TargetUnreachable {
        /// The target U95(k2), rad/(s·g²).
        target: f64,
        /// The best U95(k2) within the budget.
        achieved: f64,
        /// The budget, s.
        budget_s: f64,
        /// An estimate of the budget that reaches the target (`None`: none does).
        needed_budget_s: Option<f64>,
        /// The expanded uncertainty of the Type B inputs alone (infinite centrifuge time).
        type_b_floor: f64,
    },
    /// A design's information matrix is singular (it cannot separate the eq. 18 terms).
    #[error(
        "the design of rates {} deg/s cannot separate the six eq. 18 terms",
        units::CompactSeries(rates_deg_s)
    )]
    Singular {
        /// The rates, deg/s.
        rates_deg_s: Vec<f64>,
    },
    /// A number of simulated campaigns below the least that estimates a spread.
    #[error("campaigns = {campaigns}: at least {need} simulated campaigns are needed")]
    TooFewCampaigns {
        /// Asked for.
        campaigns: usize,
        /// Least.
        need: usize,
    },
    /// More simulated campaigns than [`crate::MAX_CAMPAIGNS`]: refused before any is run,
    /// with what they would cost.
    #[error(
        "campaigns = {campaigns}: at most {max} simulated campaigns are run (about {} s of \
         CPU at the measured cost of {} ms per 1000 campaigns of this kind of plan; ask for at \
         most {max})",
        units::Compact((*campaigns as f64 * seconds_per_campaign).round()),
        units::Compact((1e6 * seconds_per_campaign).round())
    )]
    TooManyCampaigns {
        /// Asked for.
        campaigns: usize,
        /// Most.
        max: usize,
        /// The measured CPU time of one campaign of this kind of plan, s (docs/PERFORMANCE.md).
        seconds_per_campaign: f64,
    },
    /// The noise-free outputs given to the simulation do not match the plan's points.
    #[error("{got} noise-free outputs for a plan of {expected} points")]
    OutputCount {
        /// Given.
        got: usize,
        /// Points of the plan.
        expected: usize,
    },
    /// A result would hold a non-finite number (inputs at the edge of overflow).
    #[error("the plan's {field} is not finite (inputs too large or too small)")]
    NonFinite {
        /// The result's field.
        field: &'static str,
    },
    /// A two-orientation plan was asked for a plan file without `two_orientation`.
    #[error(
        "the plan file has no `two_orientation` section: add one with the radius of each \
         mounting (`ia_in: (radius_m: …), ia_out: (radius_m: …)`) to plan both orientations"
    )]
    MissingTwoOrientations,
    /// The two-orientation joint fit failed.
    #[error("the two-orientation fit")]
    TwoOrientation(#[source] calibration::TwoOrientationError),
    /// The least-squares solver failed.
    #[error("least squares")]
    Identify(#[source] identify::IdentifyError),
    /// The uncertainty evaluation failed.
    #[error("uncertainty evaluation")]
    Uncertainty(#[source] uncertainty::UncertaintyError),
}

/// The crate's result type.
pub type Result<T> = std::result::Result<T, PlanningError>;
