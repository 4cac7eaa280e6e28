//! The study's resolved facts: what the study settles once, before its sections validate,
//! from the parts of the configuration that several sections depend on — the phase whose C_r
//! compensates (the calibration's `compensate_with`, else the first phase), the probe gain
//! each phase's recordings state, the gap unit each states and what each was given as, the
//! Type B inputs at the
//! compensating phase, which Type B inputs are uncertain, and which sections the study has.
//! Each section validates its own part of the configuration with these beside it, and reads
//! no other section's part. Core: used by sections, importing none.

use crate::config::{
    K1Config, PhaseConfig, Points, StudyConfig, TypeBInputName, UncertaintyConfig,
};
use crate::error::{PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, PhaseNames};
use crate::type_b::TypeB;

/// The probe phase whose C_r compensates a calibration, and how it was chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Compensation {
    /// Its index in `phases`.
    pub(crate) index: usize,
    /// How it was chosen: `calibration.compensate_with`, or `first phase` (the study has no
    /// calibration section).
    pub(crate) chosen_by: &'static str,
}

/// Which of the study's sections another section's validation depends on are present.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Present {
    pub(crate) calibration: bool,
    pub(crate) uncertainty: bool,
    pub(crate) two_orientation: bool,
}

/// What a phase was given as, for the sections that name a phase (the balance advisor needs
/// first harmonics, the counterweight a change of radius error).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum PhaseShape {
    /// First-harmonic coefficients, `points` rates.
    FirstHarmonic { points: usize },
    /// Probe recordings, `files` of them.
    Recordings { files: usize },
    /// Radius errors.
    RadiusError,
    /// A change of radius error between two rates.
    RadiusChange {
        from_rate_deg_s: f64,
        to_rate_deg_s: f64,
        change_um: f64,
    },
}

impl PhaseShape {
    fn of(phase: &PhaseConfig) -> Self {
        match &phase.points {
            Points::FirstHarmonic(p) => Self::FirstHarmonic { points: p.len() },
            Points::Recordings(set) => Self::Recordings {
                files: set.files.len(),
            },
            Points::RadiusError(_) => Self::RadiusError,
            &Points::RadiusChange {
                from_rate_deg_s,
                to_rate_deg_s,
                change_um,
            } => Self::RadiusChange {
                from_rate_deg_s,
                to_rate_deg_s,
                change_um,
            },
        }
    }
}

/// What the study resolves once and hands every section beside its own configuration.
#[derive(Debug, Clone)]
pub(crate) struct Resolved<'a> {
    /// The phase that compensates, unless a section names its own.
    pub(crate) compensation: Compensation,
    pub(crate) present: Present,
    /// The `uncertainty` section (read only here and in `crate::type_b`).
    uncertainty: Option<&'a UncertaintyConfig>,
    /// Per phase: the probe gain's relative u its recordings state, with the field.
    stated_gains: Vec<Option<(f64, String)>>,
    /// Per phase: the field stating its gap unit, and what it states.
    gap_units: Vec<(String, String)>,
    /// Per phase: what it was given as.
    shapes: Vec<PhaseShape>,
    /// The Type B inputs at the compensating phase (`None`: the study has no calibration
    /// section, or states no Type B input).
    type_b: Option<TypeB>,
    /// The Type B inputs with a non-zero standard uncertainty, each with the field that
    /// gives it.
    uncertain_inputs: Vec<(TypeBInputName, String)>,
}

impl<'a> Resolved<'a> {
    /// Resolves the study's shared facts: with a calibration section, its Type B inputs
    /// (`crate::type_b`; their problems first) and then its compensating phase (known, and not
    /// a second probe's).
    ///
    /// # Errors
    /// The Type B inputs' problems; an unknown `calibration.compensate_with`, or one naming a
    /// phase of the second probe's data.
    pub(crate) fn new(
        check: &Check<'_>,
        config: &'a StudyConfig,
        names: &PhaseNames<'_>,
    ) -> Result<Self> {
        let (compensation, type_b) = match &config.calibration {
            Some(c) => {
                let type_b = crate::type_b::type_b(
                    check,
                    config.uncertainty.as_ref(),
                    config.stated_probe_gain(),
                )?;
                let index =
                    names.index(check, "calibration.compensate_with", &c.compensate_with)?;
                if names.second_probe.contains(&index) {
                    return Err(PipelineError::Unsupported {
                        path: check.path.to_owned(),
                        field: "calibration.compensate_with".to_owned(),
                        reason: UnsupportedReason::SecondProbeData,
                    });
                }
                let compensation = Compensation {
                    index,
                    chosen_by: "calibration.compensate_with",
                };
                (compensation, type_b)
            }
            None => {
                let compensation = Compensation {
                    index: 0,
                    chosen_by: "first phase",
                };
                (compensation, None)
            }
        };
        Ok(Self {
            compensation,
            present: Present {
                calibration: config.calibration.is_some(),
                uncertainty: config.uncertainty.is_some(),
                two_orientation: config.two_orientation.is_some(),
            },
            uncertainty: config.uncertainty.as_ref(),
            stated_gains: config
                .phases
                .iter()
                .enumerate()
                .map(|(i, p)| p.stated_probe_gain(i))
                .collect(),
            gap_units: config
                .phases
                .iter()
                .enumerate()
                .map(|(i, p)| gap_unit(p, i))
                .collect(),
            shapes: config.phases.iter().map(PhaseShape::of).collect(),
            type_b,
            uncertain_inputs: uncertain_inputs(config),
        })
    }

    /// The Type B inputs of the compensating phase, as the calibration carries them.
    pub(crate) fn type_b(&self) -> Option<TypeB> {
        self.type_b.clone()
    }

    /// The Type B inputs with the probe gain stated by phase `phase`'s recordings (the
    /// compensating phase's: those resolved once; another phase: read by the same rule,
    /// `crate::type_b`).
    ///
    /// # Errors
    /// Those of `crate::type_b::type_b`.
    pub(crate) fn type_b_at(&self, check: &Check<'_>, phase: usize) -> Result<Option<TypeB>> {
        if self.present.calibration && phase == self.compensation.index {
            return Ok(self.type_b.clone());
        }
        let stated = self.stated_gains.get(phase).cloned().flatten();
        crate::type_b::type_b(check, self.uncertainty, stated)
    }

    /// The Type B inputs the `uncertainty` section states, with no probe gain stated by a
    /// phase's recordings (`None`: the study has no `uncertainty` section).
    ///
    /// # Errors
    /// Those of `crate::type_b::type_b`.
    pub(crate) fn type_b_of_section(&self, check: &Check<'_>) -> Result<Option<TypeB>> {
        crate::type_b::type_b(check, self.uncertainty, None)
    }

    /// The field that states the gap unit of phase `phase`, and what it states.
    pub(crate) fn gap_unit(&self, phase: usize) -> (String, String) {
        self.gap_units.get(phase).cloned().unwrap_or_else(|| {
            (
                format!("phases[{phase}].points (change_um)"),
                "a change given in µm".to_owned(),
            )
        })
    }

    /// What phase `phase` (an index of a known phase) was given as.
    pub(crate) fn phase_shape(&self, phase: usize) -> PhaseShape {
        self.shapes[phase]
    }

    /// The Type B inputs of the study with a non-zero standard uncertainty, each with the
    /// field that gives it.
    pub(crate) fn uncertain_inputs(&self) -> &[(TypeBInputName, String)] {
        &self.uncertain_inputs
    }
}

/// The field that states the gap unit of `phase` (at `index`), and what it states: a
/// recordings phase's `format.gap.unit`, or the µm of given coefficients.
fn gap_unit(phase: &PhaseConfig, index: usize) -> (String, String) {
    use recording::GapUnit;
    let key = format!("phases[{index}].points");
    match &phase.points {
        Points::Recordings(set) => (
            format!("{key}.format.gap.unit"),
            match set.format.gap.unit {
                GapUnit::Nm => "nm",
                GapUnit::Um => "um",
                GapUnit::Mm => "mm",
                GapUnit::M => "m",
                GapUnit::Volts { .. } => "volts, converted to µm by the probe's sensitivity",
            }
            .to_owned(),
        ),
        Points::FirstHarmonic(_) => (
            format!("{key} (dc1_um, ds1_um)"),
            "coefficients given in µm".to_owned(),
        ),
        Points::RadiusError(_) => (
            format!("{key} (radius_error_um)"),
            "radius errors given in µm".to_owned(),
        ),
        Points::RadiusChange { .. } => (
            format!("{key} (change_um)"),
            "a change given in µm".to_owned(),
        ),
    }
}

/// The Type B inputs of a study with a non-zero standard uncertainty, each with the field
/// that gives it: the `uncertainty` section's, the probe gain stated by the compensating
/// phase's recordings, a given k1's.
fn uncertain_inputs(config: &StudyConfig) -> Vec<(TypeBInputName, String)> {
    let mut list = Vec::new();
    if let Some(u) = &config.uncertainty {
        for (name, field, value) in [
            (
                TypeBInputName::Radius,
                "uncertainty.radius_u_m",
                u.radius_u_m,
            ),
            (TypeBInputName::G, "uncertainty.g_u_m_s2", u.g_u_m_s2),
            (
                TypeBInputName::RateScale,
                "uncertainty.rate_u_relative",
                u.rate_u_relative,
            ),
            (
                TypeBInputName::PivotToProbe,
                "uncertainty.pivot_to_probe_u_mm",
                u.pivot_to_probe_u_mm,
            ),
            (
                TypeBInputName::ProbeToPiga,
                "uncertainty.probe_to_piga_u_mm",
                u.probe_to_piga_u_mm,
            ),
            (
                TypeBInputName::ProbeGain,
                "uncertainty.probe_gain_u_relative",
                u.probe_gain_u_relative,
            ),
        ] {
            if value.is_some_and(|v| v > 0.0) {
                list.push((name, format!("`{field}`")));
            }
        }
    }
    if let Some((gain, _)) = config.stated_probe_gain()
        && gain > 0.0
        && !list.iter().any(|(n, _)| *n == TypeBInputName::ProbeGain)
    {
        list.push((
            TypeBInputName::ProbeGain,
            "the recordings' stated probe sensitivity".to_owned(),
        ));
    }
    if let Some(c) = &config.calibration
        && let K1Config::Given { u_rad_s_g, .. } = c.k1
        && u_rad_s_g > 0.0
    {
        list.push((TypeBInputName::K1, "`calibration.k1.u_rad_s_g`".to_owned()));
    }
    list
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;
    use std::path::Path;

    use super::*;

    /// A study of two phases (a radius change, then first harmonics) with `sections`.
    fn config(sections: &str) -> StudyConfig {
        let text = format!(
            r#"(
            name: "t", radius_m: 2.5, g_m_s2: 9.8, k1_rad_s_g: 0.56,
            lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0),
            phases: [
                (name: "before", points: radius_change(from_rate_deg_s: 10.0,
                                                       to_rate_deg_s: 200.0, change_um: 20.0)),
                (name: "after", points: first_harmonic([
                    (rate_deg_s: 10.0, dc1_um: 1.0, ds1_um: 0.0),
                    (rate_deg_s: 20.0, dc1_um: 1.0, ds1_um: 0.0),
                ])),
            ],
            {sections}
        )"#
        );
        StudyConfig::from_ron(&text, Path::new("t.ron")).unwrap()
    }

    fn names(second_probe: Vec<usize>) -> PhaseNames<'static> {
        PhaseNames {
            names: HashMap::from([("before", 0), ("after", 1)]),
            second_probe,
        }
    }

    const UNCERTAINTY: &str = "uncertainty: (radius_u_m: 5.0e-6, g_u_m_s2: 0.0, \
        zero_reasons: {\"g_u_m_s2\": \"measured\"}, rate_u_relative: 1.0e-6, \
        pivot_to_probe_u_mm: 0.5, probe_to_piga_u_mm: 0.5, probe_gain_u_relative: 2.0e-3),";

    #[test]
    fn without_a_calibration_the_first_phase_compensates_and_no_type_b_is_read() {
        let config = config(UNCERTAINTY);
        let check = Check {
            path: Path::new("t.ron"),
        };
        let r = Resolved::new(&check, &config, &names(Vec::new())).unwrap();
        assert_eq!(r.compensation.index, 0);
        assert_eq!(r.compensation.chosen_by, "first phase");
        assert_eq!(r.type_b(), None);
        assert_eq!(
            r.present,
            Present {
                calibration: false,
                uncertainty: true,
                two_orientation: false,
            }
        );
        // another phase's Type B is read by the same rule, on demand
        let t = r.type_b_at(&check, 1).unwrap().unwrap();
        assert_eq!(t.values.radius_u_m, 5.0e-6);
        assert!(t.from_section);
        assert_eq!(
            r.phase_shape(0),
            PhaseShape::RadiusChange {
                from_rate_deg_s: 10.0,
                to_rate_deg_s: 200.0,
                change_um: 20.0,
            }
        );
        assert_eq!(r.phase_shape(1), PhaseShape::FirstHarmonic { points: 2 });
        assert_eq!(
            r.gap_unit(1),
            (
                "phases[1].points (dc1_um, ds1_um)".to_owned(),
                "coefficients given in µm".to_owned()
            )
        );
        // the non-zero inputs, each with its field; g is 0
        let uncertain: Vec<&str> = r
            .uncertain_inputs()
            .iter()
            .map(|(_, f)| f.as_str())
            .collect();
        assert_eq!(
            uncertain,
            [
                "`uncertainty.radius_u_m`",
                "`uncertainty.rate_u_relative`",
                "`uncertainty.pivot_to_probe_u_mm`",
                "`uncertainty.probe_to_piga_u_mm`",
                "`uncertainty.probe_gain_u_relative`",
            ]
        );
    }

    #[test]
    fn the_calibration_names_the_compensating_phase_once() {
        let calibration = format!(
            "calibration: (table: (file: \"piga.csv\"), compensate_with: \"after\"), {UNCERTAINTY}"
        );
        let config = config(&calibration);
        let check = Check {
            path: Path::new("t.ron"),
        };
        let r = Resolved::new(&check, &config, &names(Vec::new())).unwrap();
        assert_eq!(r.compensation.index, 1);
        assert_eq!(r.compensation.chosen_by, "calibration.compensate_with");
        assert!(r.present.calibration);
        let t = r.type_b().expect("the calibration's Type B, resolved once");
        assert_eq!(r.type_b_at(&check, 1).unwrap(), Some(t));
        // an unknown phase, and a second probe's, are the calibration's field's errors
        let unknown = config_with_phase("nowhere");
        let e = Resolved::new(&check, &unknown, &names(Vec::new())).unwrap_err();
        assert!(
            matches!(&e, PipelineError::UnknownPhase { field, .. } if field == "calibration.compensate_with"),
            "{e}"
        );
        let e = Resolved::new(&check, &config, &names(vec![1])).unwrap_err();
        assert!(
            matches!(&e, PipelineError::Unsupported { field, reason: UnsupportedReason::SecondProbeData, .. }
                if field == "calibration.compensate_with"),
            "{e}"
        );
    }

    fn config_with_phase(name: &str) -> StudyConfig {
        config(&format!(
            "calibration: (table: (file: \"piga.csv\"), compensate_with: \"{name}\"), {UNCERTAINTY}"
        ))
    }
}
