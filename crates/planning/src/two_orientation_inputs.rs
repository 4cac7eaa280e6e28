//! What a two-orientation plan adds to a plan file (issue 20): the two mountings, the time to
//! turn the PIGA round, the rate grid the operator types, and the lack-of-fit reserve.

use crate::error::{PlanningError, Result};

/// The PIGA recorded with its input axis towards the spindle (IA in) and away from it
/// (IA out), one joint fit of eq. 23 (`calibration::fit_two_orientation`): k2 and the total radius
/// growth C from the PIGA alone.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct TwoOrientationPlanInputs {
    /// The IA-in mounting (the paper's, eq. 10).
    pub ia_in: MountingPlan,
    /// The IA-out mounting (the PIGA turned 180° about an axis parallel to the spindle).
    pub ia_out: MountingPlan,
    /// Time to stop, turn the PIGA round and remount it, s (default 0). Counted once in the
    /// budget.
    #[cfg_attr(feature = "serde", serde(default))]
    pub remount_s: f64,
    /// The rates the planner may choose (default: a round grid of 5 deg/s).
    #[cfg_attr(feature = "serde", serde(default))]
    pub rates: RateGrid,
    /// Points kept aside so the model can be tested (default: two more rates per
    /// orientation and 10 % of the recording time spread over every point).
    #[cfg_attr(feature = "serde", serde(default))]
    pub reserve: LackOfFitReserve,
    /// Arm stretch C_a expected, m·s² (default 0): the radius at the PIGA grows by C_a·ω²
    /// beyond the spindle's motion, which the probe does not see. The probe method's k2 is
    /// off by k1·C_a·g/R²; the two-orientation k2 is not.
    #[cfg_attr(feature = "serde", serde(default))]
    pub arm_stretch_m_s2: f64,
}

/// One mounting of the PIGA.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct MountingPlan {
    /// Static radius of this mounting (PIGA centre of mass to the spindle axis), m.
    pub radius_m: f64,
    /// Expected change of the bias k0 in this mounting, rad/s (default 0; it does not change
    /// u(k2), each mounting has its own bias in the fit).
    #[cfg_attr(feature = "serde", serde(default))]
    pub bias_shift_rad_s: f64,
}

/// The rates a two-orientation plan chooses from.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum RateGrid {
    /// Whole multiples of `step_deg_s` within the allowed range (the default, 5 deg/s): rates
    /// an operator types.
    Round {
        /// Grid step, deg/s (> 0).
        step_deg_s: f64,
    },
    /// The plan file's `centrifuge.candidates` as they are (the unrounded optimum).
    Candidates,
}

impl Default for RateGrid {
    fn default() -> Self {
        Self::Round {
            step_deg_s: DEFAULT_STEP_DEG_S,
        }
    }
}

/// The round grid's default step, deg/s.
pub const DEFAULT_STEP_DEG_S: f64 = 5.0;

/// Points kept aside for a lack-of-fit test: the c-optimal design of k2 puts its time on a
/// few support rates, which cannot show whether the model fits between them.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct LackOfFitReserve {
    /// Distinct rates added to each orientation beyond the six the fit needs, placed in the
    /// widest gaps between the chosen rates (default 2; 0 with `time_fraction: 0` turns the
    /// reserve off).
    pub extra_rates_per_orientation: usize,
    /// Share of the recording time given in equal parts to every point before the rest is
    /// allocated for the smallest u(k2) (default 0.1; 0 ≤ f < 1).
    pub time_fraction: f64,
}

impl Default for LackOfFitReserve {
    fn default() -> Self {
        Self {
            extra_rates_per_orientation: 2,
            time_fraction: 0.1,
        }
    }
}

impl LackOfFitReserve {
    /// No reserve.
    pub const OFF: Self = Self {
        extra_rates_per_orientation: 0,
        time_fraction: 0.0,
    };

    /// Whether the reserve is off.
    #[must_use]
    pub fn is_off(&self) -> bool {
        self.extra_rates_per_orientation == 0 && self.time_fraction == 0.0
    }
}

/// The most rates a reserve may add per orientation.
const MAX_EXTRA_RATES: usize = 50;

fn invalid(field: &'static str, value: f64, requirement: &'static str) -> PlanningError {
    PlanningError::InvalidField {
        field,
        value,
        requirement,
    }
}

impl TwoOrientationPlanInputs {
    /// Checks the fields; the error names the plan file's field.
    ///
    /// # Errors
    /// [`PlanningError::InvalidField`].
    pub fn validate(&self) -> Result<()> {
        for (field, m) in [
            ("two_orientation.ia_in.radius_m", &self.ia_in),
            ("two_orientation.ia_out.radius_m", &self.ia_out),
        ] {
            if !(m.radius_m.is_finite() && m.radius_m > 0.0) {
                return Err(invalid(field, m.radius_m, "must be finite and > 0"));
            }
        }
        for (field, v) in [
            (
                "two_orientation.ia_in.bias_shift_rad_s",
                self.ia_in.bias_shift_rad_s,
            ),
            (
                "two_orientation.ia_out.bias_shift_rad_s",
                self.ia_out.bias_shift_rad_s,
            ),
            ("two_orientation.arm_stretch_m_s2", self.arm_stretch_m_s2),
        ] {
            if !v.is_finite() {
                return Err(invalid(field, v, "must be finite"));
            }
        }
        if !(self.remount_s.is_finite() && self.remount_s >= 0.0) {
            return Err(invalid(
                "two_orientation.remount_s",
                self.remount_s,
                "must be finite and ≥ 0",
            ));
        }
        if let RateGrid::Round { step_deg_s } = self.rates
            && !(step_deg_s.is_finite() && step_deg_s > 0.0)
        {
            return Err(invalid(
                "two_orientation.rates.step_deg_s",
                step_deg_s,
                "must be finite and > 0",
            ));
        }
        let r = &self.reserve;
        if !(r.time_fraction.is_finite() && (0.0..1.0).contains(&r.time_fraction)) {
            return Err(invalid(
                "two_orientation.reserve.time_fraction",
                r.time_fraction,
                "must lie in 0 ≤ f < 1",
            ));
        }
        if r.extra_rates_per_orientation > MAX_EXTRA_RATES {
            return Err(invalid(
                "two_orientation.reserve.extra_rates_per_orientation",
                r.extra_rates_per_orientation as f64,
                "must be at most 50",
            ));
        }
        Ok(())
    }
}

/// The whole multiples of `step` within `min…max`, deg/s.
pub(crate) fn round_grid(step_deg_s: f64, min_deg_s: f64, max_deg_s: f64) -> Vec<f64> {
    let slack = 1e-9 * max_deg_s;
    let first = ((min_deg_s - slack) / step_deg_s).ceil().max(1.0) as u64;
    let last = ((max_deg_s + slack) / step_deg_s).floor() as u64;
    (first..=last.max(first.saturating_sub(1)))
        .map(|k| k as f64 * step_deg_s)
        .filter(|r| *r <= max_deg_s + slack)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_round_grid_holds_whole_multiples_within_the_range() {
        assert_eq!(round_grid(5.0, 10.0, 200.1234).len(), 39);
        assert_eq!(round_grid(5.0, 10.0, 200.1234)[0], 10.0);
        assert_eq!(round_grid(5.0, 12.0, 31.0), vec![15.0, 20.0, 25.0, 30.0]);
        assert!(round_grid(50.0, 10.0, 40.0).is_empty());
    }
}
