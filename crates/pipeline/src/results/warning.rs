//! A diagnostic of results.json: the numbers were computed, but something may make them
//! wrong. Every code is a [`WarningCode`] and every warning is built by one constructor per
//! code, which holds its words.

use serde::{Deserialize, Serialize};

use super::declarations::{AngleZero, ProbeSign};

/// What a warning is about: a short stable code, `snake_case` in results.json.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum WarningCode {
    /// A recording without an encoder or index pulse: its angle comes from the declared rate.
    AngleFromRate,
    /// A recording's measured mean rate differs from the declared one.
    RateDiffers,
    /// A recording's first harmonic varies from revolution to revolution beyond white noise.
    RevolutionSpread,
    /// A recording's mean gap drifts and the fit has no drift term.
    DriftNotFitted,
    /// Revolutions of a recording were dropped for gaps or non-finite samples.
    DroppedRevolutions,
    /// A raw PIGA recording's per-revolution outputs scatter beyond white noise.
    OutputSpread,
    /// A probe signal implausible for its gap column's declared unit (a mean gap below a
    /// micrometre, a first harmonic below a probe's own noise): C_r wrong by the unit's factor.
    ImplausibleGapUnit,
    /// Revolutions of a recording fit far worse than the others (a glitch or dropout).
    ResidualOutlier,
    /// A recording's residuals alternate in sign from sample to sample.
    AlternatingResiduals,
    /// Another diagnostic of a recording (one this version does not name).
    Recording,
    /// The radius-error residuals exceed their white-noise σ.
    LackOfFit,
    /// A phase holds the second probe's data, read through the first probe's lever.
    SecondProbePhase,
    /// The calibration's raw recordings have no scatter: the eq. 18 fit is unweighted.
    CalibrationUnweighted,
    /// The eq. 18 residuals exceed the points' standard uncertainties.
    CalibrationLackOfFit,
    /// The rows of one label sit apart from the fit.
    LabelOffset,
    /// Calibration rates lie outside the rates at which the compensating phase measured C_r.
    RateOutsidePhase,
    /// A balance correction's mass is known no better than its own size.
    CorrectionUncertain,
    /// One probe's C_r through the cone of eq. 22 differs from the two probes' at the PIGA
    /// plane.
    #[serde(rename = "cone_c_r")]
    ConeCr,
    /// The two-orientation fit's s·ω⁴ term (C) is hard to tell apart from k2: fitting it
    /// widens u(k2) more than 3 times.
    #[serde(rename = "omega4_not_separable")]
    Omega4NotSeparable,
    /// The PIGA's total radius growth C and the probe's C_r disagree (|z| > 3).
    ProbeDisagrees,
    /// The two-orientation design's rates make u(k2) or u(C) more than 3 times what the same
    /// number of points per mounting, evenly spread, would give.
    TwoOrientationRatesBunched,
    /// A section of the study file written under a former name, read as the new one.
    DeprecatedKey,
    /// An instrument of the certificate was past its calibration due date on the
    /// measurement date.
    CalibrationOverdue,
    /// A calibration due date or the measurement date is not written `YYYY-MM-DD`, so the
    /// two cannot be compared.
    CalibrationDueUnchecked,
    /// The mountings separate a chosen term only poorly (its u inflated), or cannot see the
    /// arm stretch, which then hides in the even terms.
    MountingsPoorlySeparated,
    /// The joint fit over the mountings took a value the study does not state (an angle
    /// uncertainty, the vertical Earth rate) or leaves an input out of its U95.
    MountingsAssumed,
}

impl WarningCode {
    /// The code as results.json writes it (`lack_of_fit`): stable, for scripts and the report.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::AngleFromRate => "angle_from_rate",
            Self::RateDiffers => "rate_differs",
            Self::RevolutionSpread => "revolution_spread",
            Self::DriftNotFitted => "drift_not_fitted",
            Self::DroppedRevolutions => "dropped_revolutions",
            Self::OutputSpread => "output_spread",
            Self::ImplausibleGapUnit => "implausible_gap_unit",
            Self::ResidualOutlier => "residual_outlier",
            Self::AlternatingResiduals => "alternating_residuals",
            Self::Recording => "recording",
            Self::LackOfFit => "lack_of_fit",
            Self::SecondProbePhase => "second_probe_phase",
            Self::CalibrationUnweighted => "calibration_unweighted",
            Self::CalibrationLackOfFit => "calibration_lack_of_fit",
            Self::LabelOffset => "label_offset",
            Self::RateOutsidePhase => "rate_outside_phase",
            Self::CorrectionUncertain => "correction_uncertain",
            Self::ConeCr => "cone_c_r",
            Self::CalibrationOverdue => "calibration_overdue",
            Self::CalibrationDueUnchecked => "calibration_due_unchecked",
            Self::Omega4NotSeparable => "omega4_not_separable",
            Self::ProbeDisagrees => "probe_disagrees",
            Self::DeprecatedKey => "deprecated_key",
            Self::TwoOrientationRatesBunched => "two_orientation_rates_bunched",
            Self::MountingsPoorlySeparated => "mountings_poorly_separated",
            Self::MountingsAssumed => "mountings_assumed",
        }
    }

    /// What the code means, in a few words.
    #[must_use]
    pub fn title(self) -> &'static str {
        match self {
            Self::AngleFromRate => "angle taken from the declared rate",
            Self::RateDiffers => "measured rate differs from the declared one",
            Self::RevolutionSpread => "first harmonic varies between revolutions",
            Self::DriftNotFitted => "gap drifts, drift not fitted",
            Self::DroppedRevolutions => "revolutions dropped",
            Self::OutputSpread => "PIGA output varies between revolutions",
            Self::ImplausibleGapUnit => "probe signal implausible for its declared unit",
            Self::ResidualOutlier => "revolutions that fit far worse than the others",
            Self::AlternatingResiduals => "residuals alternate from sample to sample",
            Self::Recording => "recording diagnostic",
            Self::LackOfFit => "radius-error fit worse than the noise",
            Self::SecondProbePhase => "phase read with the first probe's lever",
            Self::CalibrationUnweighted => "calibration fit unweighted",
            Self::CalibrationLackOfFit => "calibration fit worse than the points' σ",
            Self::LabelOffset => "a label's rows sit apart",
            Self::RateOutsidePhase => "calibration rate outside the compensating phase's rates",
            Self::CorrectionUncertain => "correction mass uncertain",
            Self::ConeCr => "cone C_r differs from the two-probe C_r",
            Self::Omega4NotSeparable => "ω⁴ term hard to separate in the two-orientation fit",
            Self::ProbeDisagrees => "the PIGA's radius growth and the probe's disagree",
            Self::DeprecatedKey => "a section under a former name",
            Self::CalibrationOverdue => "equipment past its calibration due date",
            Self::CalibrationDueUnchecked => "calibration due dates not compared",
            Self::TwoOrientationRatesBunched => "two-orientation rates too bunched for k2 and C",
            Self::MountingsPoorlySeparated => "a term the mountings separate poorly",
            Self::MountingsAssumed => "the joint fit over the mountings took a value not stated",
        }
    }
}

/// The code as results.json writes it ([`WarningCode::as_str`]).
impl std::fmt::Display for WarningCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A code equals the text results.json holds for it (`code == "lack_of_fit"`).
impl PartialEq<&str> for WarningCode {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

/// A diagnostic: the numbers were computed, but something may make them wrong.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Warning {
    /// What it is about.
    pub code: WarningCode,
    /// What was seen and what to do, in plain words.
    pub message: String,
    /// The configuration field, and the file when it concerns a recording.
    #[serde(rename = "where")]
    pub location: String,
}

impl std::fmt::Display for Warning {
    /// `where: message`, as a person reads it.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.location, self.message)
    }
}

impl Warning {
    /// A recording's diagnostic, at `location` (the field and the file).
    #[must_use]
    pub fn recording(d: &recording::Diagnostic, location: String) -> Self {
        use recording::Diagnostic as D;
        let code = match d {
            D::AngleFromRate { .. } => WarningCode::AngleFromRate,
            D::RateDiffers { .. } => WarningCode::RateDiffers,
            D::RevolutionSpread { .. } => WarningCode::RevolutionSpread,
            D::DriftNotFitted { .. } => WarningCode::DriftNotFitted,
            D::DroppedRevolutions { .. } => WarningCode::DroppedRevolutions,
            D::OutputSpread { .. } => WarningCode::OutputSpread,
            D::ImplausibleGap { .. } => WarningCode::ImplausibleGapUnit,
            D::ResidualOutlier { .. } => WarningCode::ResidualOutlier,
            D::AlternatingResiduals { .. } => WarningCode::AlternatingResiduals,
            _ => WarningCode::Recording,
        };
        Self {
            code,
            message: d.to_string(),
            location,
        }
    }

    /// `lack_of_fit`: the radius-error residuals are `ratio` × their white-noise σ
    /// (`√(χ²/dof)`), in the phase `section`.
    #[must_use]
    pub fn lack_of_fit(ratio: f64, dof: usize, section: &str) -> Self {
        Self {
            code: WarningCode::LackOfFit,
            message: format!(
                "the radius-error residuals are {ratio:.1}× their white-noise σ (√(χ²/dof), {dof} \
                 degrees of freedom): a + C_r·ω² does not describe the points within their \
                 noise; look for drift (`drift: true`), a rate error or a pickup not synchronous \
                 with the spindle (see the other warnings), or another `radius_model`. σ(C_r) \
                 comes from the residuals and includes the scatter, not a bias"
            ),
            location: format!("{section}.points"),
        }
    }

    /// `second_probe_phase`: phase `name` (at `key`) holds the second probe's data.
    #[must_use]
    pub fn second_probe_phase(name: &str, key: &str) -> Self {
        Self {
            code: WarningCode::SecondProbePhase,
            message: format!(
                "phase `{name}` holds the second probe's data: its radius-error fit here reads \
                 it with the first probe's lever and direction, so its C_r and Δk2 are not \
                 the PIGA plane's; `balance.two_plane` gives C_r at the PIGA plane from both \
                 probes"
            ),
            location: key.to_owned(),
        }
    }

    /// `calibration_unweighted`: a raw recording's mean output has no scatter, so the
    /// recordings at `location` (`calibration.recordings`) are fitted unweighted.
    #[must_use]
    pub fn calibration_unweighted(location: &str) -> Self {
        Self {
            code: WarningCode::CalibrationUnweighted,
            message: "a recording's mean output has no scatter across revolutions \
                      (noise-free data?): the fit of these recordings is unweighted"
                .into(),
            location: location.into(),
        }
    }

    /// `calibration_unweighted`: one orientation's points carry standard uncertainties (raw
    /// recordings, or a table's σ column) and the other's do not, so the joint fit is
    /// unweighted and the given σ are not used.
    #[must_use]
    pub fn two_orientation_unweighted(with_sigma: &str, without_sigma: &str) -> Self {
        Self {
            code: WarningCode::CalibrationUnweighted,
            message: format!(
                "{with_sigma} gives each point's standard uncertainty but {without_sigma} does \
                 not: the two-orientation fit is unweighted, its uncertainties come from the \
                 residuals, and the given ones are not used (state a table's σ by `sigma_column` or \
                 `output_sigma_rad_s`)"
            ),
            location: without_sigma.into(),
        }
    }

    /// `calibration_lack_of_fit`: the eq. 18 residuals exceed the points' σ, in the
    /// calibration's own words (`calibration::CalibrationWarning::LackOfFit`, which
    /// `centrifuge-cal identify` prints too).
    #[must_use]
    pub fn calibration_lack_of_fit(warning: &::calibration::CalibrationWarning) -> Self {
        Self {
            code: WarningCode::CalibrationLackOfFit,
            message: warning.to_string(),
            location: "calibration".into(),
        }
    }

    /// `label_offset`: the `rows` rows labelled `label` sit `z` standard uncertainties from
    /// the fit on average (mean residual `mean_residual_rad_s`).
    #[must_use]
    pub fn label_offset(rows: usize, label: &str, z: f64, mean_residual_rad_s: f64) -> Self {
        Self {
            code: WarningCode::LabelOffset,
            message: format!(
                "the {rows} rows labelled `{label}` sit {z:+.1} standard uncertainties from the fit \
                 on average (mean residual {mean_residual_rad_s:+.3e} rad/s, against the scatter \
                 within the label): that repeat or orientation differs from the others (a bias, a \
                 set-up change) and one eq. 18 model does not describe them all"
            ),
            location: "calibration.table".into(),
        }
    }

    /// `rate_outside_phase`: calibration rates `outside` lie outside `low`–`high` deg/s, the
    /// rates at which `phase` measured C_r.
    #[must_use]
    pub fn rate_outside_phase(outside: &[f64], low: f64, high: f64, phase: &str) -> Self {
        Self {
            code: WarningCode::RateOutsidePhase,
            message: format!(
                "{} calibration rate(s) ({}) lie outside {}–{} deg/s, the rates at which \
                 phase `{phase}` measured C_r: there the compensation extrapolates C_r·ω², which \
                 no probe measurement checks",
                outside.len(),
                // A long list is summarised (issue 32: 1e5 rates made one 257 kB line).
                units::CompactSeries(outside)
                    .to_string()
                    .trim_start_matches('[')
                    .replacen(']', "", 1),
                units::Compact(low),
                units::Compact(high),
            ),
            location: "calibration".into(),
        }
    }

    /// `correction_uncertain`: a correction of `mass_kg` with a standard uncertainty
    /// `mass_u_kg` as large as itself, at `location`.
    #[must_use]
    pub fn correction_uncertain(mass_kg: f64, mass_u_kg: f64, location: String) -> Self {
        Self {
            code: WarningCode::CorrectionUncertain,
            message: format!(
                "the correction's mass {mass_kg:.4} kg has a standard uncertainty of \
                 {mass_u_kg:.4} kg, as large as itself: the trial run(s) did not move the spindle \
                 clearly enough (near-parallel or small responses) — use a larger trial mass, or \
                 another trial azimuth or plane"
            ),
            location,
        }
    }

    /// `cone_c_r`: phase `phase`'s C_r through the cone (`cone`) against both probes'
    /// (`two_plane ± u`) at the PIGA plane.
    #[must_use]
    pub fn cone_c_r(phase: &str, cone: f64, two_plane: f64, u: f64) -> Self {
        Self {
            code: WarningCode::ConeCr,
            message: format!(
                "phase `{phase}`'s C_r read by one probe through the cone of eq. 22 is {cone:.4e} \
                 m·s²; both probes give {two_plane:.4e} ± {u:.1e} m·s² at the PIGA plane: the \
                 spindle does not move as a cone about the assumed pivot, and a calibration or \
                 mechanism section that uses the phase's C_r is off by the difference"
            ),
            location: "balance.two_plane".into(),
        }
    }

    /// `omega4_not_separable`: fitting the two-orientation fit's s·ω⁴ term (C) widens u(k2)
    /// `k2_inflation` times (above `limit`) over a fit with C known, the k2 and C estimates
    /// correlated at `correlation`; `vif` is the column's variance inflation factor.
    #[must_use]
    pub fn omega4_not_separable(k2_inflation: f64, correlation: f64, limit: f64, vif: f64) -> Self {
        Self {
            code: WarningCode::Omega4NotSeparable,
            message: format!(
                "k2 and the radius growth C are hard to tell apart in the two-orientation fit: \
                 fitting C (the ω⁴ term that changes sign with the orientation) makes u(k2) \
                 {k2_inflation:.1} times what it would be with C known (warned above {limit}); \
                 their estimates are correlated at {correlation:+.3} (variance inflation factor of \
                 the ω⁴ term {vif:.1e}). Both are stated with uncertainties that carry this, but \
                 k2 from the PIGA alone is far less precise than the design could give: measure \
                 both orientations over the same wide band of rates, with comparable noise"
            ),
            location: "two_orientation.orientations".into(),
        }
    }

    /// `two_orientation_rates_bunched`: u(k2) and u(C) are `k2` and `c` times the spread reference
    /// design's (rates from `low_deg_s` to `top_deg_s` in both mountings); `limit` the limit.
    #[must_use]
    pub fn two_orientation_rates_bunched(
        k2: f64,
        c: f64,
        (low_deg_s, top_deg_s): (f64, f64),
        limit: f64,
    ) -> Self {
        let times = |f: f64| {
            if f < 10.0 {
                format!("{f:.1}")
            } else {
                format!("{f:.0}")
            }
        };
        Self {
            code: WarningCode::TwoOrientationRatesBunched,
            message: format!(
                "the two orientations' rates cannot separate k2 and the radius growth C well: \
                 u(k2) is {} times and u(C) {} times what the same number of rates per \
                 orientation, spread evenly from {} to {} deg/s in both, would give (warned above \
                 {limit}). Both are stated with uncertainties that carry this, but the design \
                 wastes centrifuge time: spread each orientation's rates over 10–100 % of the top \
                 rate (`centrifuge-cal plan` with `two_orientation` chooses them)",
                times(k2),
                times(c),
                times(low_deg_s),
                times(top_deg_s),
            ),
            location: "two_orientation.orientations".into(),
        }
    }

    /// `deprecated_key`: the section `old` of the study file now has the name `new`.
    #[must_use]
    pub fn deprecated_key(old: &str, new: &str) -> Self {
        Self {
            code: WarningCode::DeprecatedKey,
            message: format!(
                "the section `{old}` is now called `{new}`: it was read as `{new}`; rename it \
                 in the study file (the old name will be refused in a later version)"
            ),
            location: old.into(),
        }
    }

    /// `mountings_poorly_separated`: what the separability analysis of the mountings says
    /// (`message`, in words), at `location`.
    #[must_use]
    pub fn mountings_poorly_separated(message: String, location: &str) -> Self {
        Self {
            code: WarningCode::MountingsPoorlySeparated,
            message,
            location: location.into(),
        }
    }

    /// `mountings_assumed`: a value the joint fit took or left out (`message`, in words), at
    /// `location`.
    #[must_use]
    pub fn mountings_assumed(message: String, location: &str) -> Self {
        Self {
            code: WarningCode::MountingsAssumed,
            message,
            location: location.into(),
        }
    }

    /// `calibration_overdue`: the instrument `role` `identity` was due for calibration on
    /// `due`, before the measurement's last day `measured`.
    #[must_use]
    pub fn calibration_overdue(
        role: &str,
        identity: &str,
        due: &str,
        measured: &str,
        location: &str,
    ) -> Self {
        Self {
            code: WarningCode::CalibrationOverdue,
            message: format!(
                "the {role} {identity} was due for calibration on {due}, before the \
                 measurement ({measured}): its calibration had expired when it was used, so the \
                 certificate's traceability through it does not hold (calibrate it, or state the \
                 departure from the procedure)"
            ),
            location: location.into(),
        }
    }

    /// `calibration_due_unchecked`: `what` cannot be compared (a date not written
    /// `YYYY-MM-DD`).
    #[must_use]
    pub fn calibration_due_unchecked(what: &str) -> Self {
        Self {
            code: WarningCode::CalibrationDueUnchecked,
            message: format!(
                "the equipment's calibration due dates were not compared with the measurement \
                 date: {what}"
            ),
            location: "certificate.equipment".into(),
        }
    }

    /// `probe_disagrees`: the PIGA's C and the probe's C_r (`c_r`, m·s²) differ by
    /// `difference ± u` m·s² (`z`). The message names the probe's three declarations that
    /// show exactly so — the angle zero, the probe direction and the gap unit, each with the
    /// field that states it and what it says now — before radius growth the probe does not
    /// see.
    #[must_use]
    pub fn probe_disagrees(
        declared: &ProbeDeclared,
        c_r: f64,
        difference: f64,
        u: f64,
        z: f64,
    ) -> Self {
        let c = c_r + difference;
        let ratio = c_r / c;
        let ratio_text = if ratio.is_finite() {
            format!("; C_r/C = {}", units::Compact(round_to(ratio, 3)))
        } else {
            String::new()
        };
        // an encoder zero off by φ makes C_r cos φ times its value for an imbalance along
        // the arm
        let offset_hint = if ratio.is_finite() && ratio > 0.0 && ratio < 1.0 {
            format!(
                " (C_r/C = {} would then be φ ≈ {}°)",
                units::Compact(round_to(ratio, 3)),
                ratio.acos().to_degrees().round()
            )
        } else {
            String::new()
        };
        let angle = if declared.angle_zero.stated {
            format!(
                "now {}°",
                units::Compact(declared.angle_zero.angle_zero_deg)
            )
        } else {
            "not stated, so 0° is taken".to_owned()
        };
        Self {
            code: WarningCode::ProbeDisagrees,
            message: format!(
                "the radius growth C the PIGA measures in its two orientations differs from the \
                 probe's C_r of phase `{phase}` by {difference:+.3e} ± {u:.1e} m·s² (C − C_r; \
                 z = {z:+.1}, beyond ±3{ratio_text}). A wrong declaration of the probe shows \
                 exactly so, with no other sign; check these three first: (1) the angle zero, \
                 `lever.angle_zero_deg` ({angle}): what the encoder reads when the arm's PIGA \
                 end points at the probe; an encoder zero off by φ turns the probe's first \
                 harmonic by φ, which makes C_r cos φ times its value when the imbalance lies \
                 along the arm{offset_hint}, more or less otherwise; (2) the probe direction, \
                 `lever.probe_direction` \
                 ({direction}: {direction_words}): the other way round turns C_r's sign (C_r/C \
                 near −1); (3) the gap unit, `{gap_field}` ({gap_unit}): a column in mm read \
                 as µm makes C_r 1000 times too small. If all three are right, the radius grows \
                 in a way the probe does not see (the arm stretching under centrifugal load, a \
                 mount that gives, or wrong lever heights `lever.pivot_to_probe_mm`, \
                 `lever.probe_to_piga_mm`), and a k2 compensated with the probe keeps that \
                 part of the error: state the two-orientation k2",
                phase = declared.phase,
                direction = declared.direction.name(),
                direction_words = declared.direction.words(),
                gap_field = declared.gap_field,
                gap_unit = declared.gap_unit,
            ),
            location: "two_orientation.compare_with".into(),
        }
    }
}

/// `x` rounded to `digits` significant digits (a ratio as a person reads it).
fn round_to(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

/// What the probe phase a two-orientation study compares with declares: the declarations
/// a disagreement of C and C_r names first.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeDeclared {
    /// The phase's name.
    pub phase: String,
    /// The angle zero (`lever.angle_zero_deg`).
    pub angle_zero: AngleZero,
    /// The probe's measuring direction (`lever.probe_direction`).
    pub direction: ProbeSign,
    /// The field that states the phase's gap unit (`phases[0].points.format.gap.unit`).
    pub gap_field: String,
    /// What it states (`um`, `mm`, or the unit of given coefficients).
    pub gap_unit: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_snake_case_in_json() {
        let code = |c: WarningCode| serde_json::to_string(&c).unwrap();
        assert_eq!(code(WarningCode::LackOfFit), "\"lack_of_fit\"");
        assert_eq!(code(WarningCode::ConeCr), "\"cone_c_r\"");
        assert_eq!(
            code(WarningCode::CalibrationLackOfFit),
            "\"calibration_lack_of_fit\""
        );
        let back: WarningCode = serde_json::from_str("\"rate_outside_phase\"").unwrap();
        assert_eq!(back, WarningCode::RateOutsidePhase);
    }

    #[test]
    fn display_has_no_rust_names() {
        let w = Warning::second_probe_phase("after_b", "phases[2]");
        let text = w.to_string();
        assert!(text.starts_with("phases[2]: phase `after_b`"), "{text}");
        // The code as a person sees it is the one results.json holds, never the Rust name.
        for c in [
            WarningCode::ConeCr,
            WarningCode::LackOfFit,
            WarningCode::AngleFromRate,
        ] {
            assert_eq!(format!("\"{c}\""), serde_json::to_string(&c).unwrap());
            assert!(!c.title().is_empty());
        }
    }

    #[test]
    fn a_long_list_of_rates_is_summarised() {
        // Issue 32: 1e5 calibration rates made one 257 kB warning line.
        let rates: Vec<f64> = (0..100_000).map(|i| 250.0 + f64::from(i) * 0.5).collect();
        let w = Warning::rate_outside_phase(&rates, 10.0, 200.1234, "spindle");
        assert!(w.message.len() < 400, "{} bytes", w.message.len());
        assert!(
            w.message.starts_with(
                "100000 calibration rate(s) (250, 250.5, 251, 251.5, 252, 252.5, …, 50249.5 \
                 (100000 values)) lie outside 10–200.1234 deg/s"
            ),
            "{}",
            w.message
        );
        // A short list is written whole.
        let w = Warning::rate_outside_phase(&[210.0, 220.5], 10.0, 200.0, "spindle");
        assert!(
            w.message
                .starts_with("2 calibration rate(s) (210, 220.5) lie"),
            "{}",
            w.message
        );
    }
}
