//! The balance section's validation.

use std::collections::HashMap;

use balance::{CorrectionPlane, TrialMass};

use crate::config::{BalanceConfig, PhaseConfig, Points};
use crate::error::{PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, probe_direction, sorted_names};

/// The validated balance section.
#[derive(Debug, Clone)]
pub(crate) struct BalanceInputs {
    /// Index of the initial phase.
    pub(crate) initial: usize,
    /// Index of the trial phase and its trial mass.
    pub(crate) trial: Option<(usize, TrialMass)>,
    pub(crate) radial_stiffness_n_m: Option<f64>,
    pub(crate) plane: CorrectionPlane,
    pub(crate) rotor_mass_kg: Option<f64>,
    /// Index of the check phase.
    pub(crate) check: Option<usize>,
    /// The second probe, when there is one.
    pub(crate) second: Option<SecondProbeInputs>,
    pub(crate) angular_stiffness_n_m_rad: Option<f64>,
    /// The two-plane correction, when configured (with a second probe).
    pub(crate) two_plane: Option<TwoPlaneInputs>,
}

/// The validated second probe.
#[derive(Debug, Clone)]
pub(crate) struct SecondProbeInputs {
    pub(crate) probe_to_piga_mm: f64,
    pub(crate) probe_direction: harmonics::ProbeDirection,
    /// Phase index (first probe) → phase index of the same run seen by the second probe.
    pub(crate) phase_of: std::collections::HashMap<usize, usize>,
}

/// The validated two-plane section.
#[derive(Debug, Clone)]
pub(crate) struct TwoPlaneInputs {
    /// Planes A and B.
    pub(crate) planes: [balance::HeightPlane; 2],
    /// The trial run in plane B and its mass.
    pub(crate) trial: Option<(usize, TrialMass)>,
}

impl BalanceInputs {
    /// The phases holding the second probe's data.
    pub(crate) fn second_probe_phases(&self) -> Vec<usize> {
        self.second
            .as_ref()
            .map(|s| s.phase_of.values().copied().collect())
            .unwrap_or_default()
    }
}

/// The phases a balance section's second probe names (read with the first probe's lever,
/// their C_r is not the PIGA plane's; docs/BALANCING.md), before it is validated.
pub(crate) fn second_probe_phases(
    config: Option<&BalanceConfig>,
    names: &HashMap<&str, usize>,
) -> Vec<usize> {
    config
        .iter()
        .flat_map(|b| b.second_probe.iter())
        .flat_map(|q| q.phases.values())
        .filter_map(|name| names.get(name.as_str()).copied())
        .collect()
}

/// The balance section: known phases with first harmonics and enough rates, a trial mass
/// with its phase, positive lengths and masses.
pub(crate) fn validate(
    check: &Check<'_>,
    b: &BalanceConfig,
    phases: &[PhaseConfig],
    names: &HashMap<&str, usize>,
    first_probe_to_piga_mm: f64,
) -> Result<BalanceInputs> {
    let phase = |field: &str, name: &str| -> Result<usize> {
        let Some(&i) = names.get(name) else {
            return Err(PipelineError::UnknownPhase {
                path: check.path.to_owned(),
                field: field.to_owned(),
                name: name.to_owned(),
                known: sorted_names(names),
            });
        };
        let count = match &phases[i].points {
            Points::FirstHarmonic(p) => p.len(),
            Points::Recordings(set) => set.files.len(),
            Points::RadiusError(_) | Points::RadiusChange { .. } => {
                return Err(PipelineError::Unsupported {
                    path: check.path.to_owned(),
                    field: field.to_owned(),
                    reason: UnsupportedReason::BalanceNeedsFirstHarmonic,
                });
            }
        };
        if count < balance::MIN_RATES {
            return Err(PipelineError::TooFewPoints {
                path: check.path.to_owned(),
                field: format!("phases[{i}].points"),
                got: count,
                need: balance::MIN_RATES,
                model: "the balance advisor's static/dynamic phasor fit",
            });
        }
        Ok(i)
    };
    let initial = phase("balance.initial", &b.initial)?;
    let trial = match (&b.trial, &b.trial_mass) {
        (Some(name), Some(m)) => {
            let i = phase("balance.trial", name)?;
            check.positive("balance.trial_mass.mass_kg", m.mass_kg)?;
            check.positive("balance.trial_mass.radius_m", m.radius_m)?;
            check.finite("balance.trial_mass.azimuth_deg".to_owned(), m.azimuth_deg)?;
            if let Some(h) = m.height_m {
                check.finite("balance.trial_mass.height_m".to_owned(), h)?;
            }
            Some((
                i,
                balance::TrialMass {
                    mass_kg: m.mass_kg,
                    radius_m: m.radius_m,
                    azimuth_deg: m.azimuth_deg,
                },
            ))
        }
        (None, None) => None,
        (Some(_), None) | (None, Some(_)) => {
            return Err(PipelineError::Unsupported {
                path: check.path.to_owned(),
                field: if b.trial.is_some() {
                    "balance.trial_mass"
                } else {
                    "balance.trial"
                }
                .to_owned(),
                reason: UnsupportedReason::TrialNeedsTrialMass,
            });
        }
    };
    if let Some(k) = b.radial_stiffness_n_m {
        check.positive("balance.radial_stiffness_n_m", k)?;
    }
    if trial.is_none() && b.radial_stiffness_n_m.is_none() {
        return Err(PipelineError::Unsupported {
            path: check.path.to_owned(),
            field: "balance".to_owned(),
            reason: UnsupportedReason::BalanceNeedsMethod,
        });
    }
    check.positive("balance.correction_radius_m", b.correction_radius_m)?;
    for (i, &a) in b.fixed_azimuths_deg.iter().enumerate() {
        check.finite(format!("balance.fixed_azimuths_deg[{i}]"), a)?;
    }
    if let Some(m) = b.rotor_mass_kg {
        check.positive("balance.rotor_mass_kg", m)?;
    }
    let check_phase = b
        .check
        .as_deref()
        .map(|name| phase("balance.check", name))
        .transpose()?;
    if let Some(k) = b.angular_stiffness_n_m_rad {
        check.positive("balance.angular_stiffness_n_m_rad", k)?;
    }
    let unsupported = |field: &str, reason| PipelineError::Unsupported {
        path: check.path.to_owned(),
        field: field.to_owned(),
        reason,
    };
    let two_plane = b
        .two_plane
        .as_ref()
        .map(|t| {
            if b.second_probe.is_none() {
                return Err(unsupported(
                    "balance.two_plane",
                    UnsupportedReason::TwoPlaneNeedsSecondProbe,
                ));
            }
            let (za, zb) = t.heights_m;
            check.finite("balance.two_plane.heights_m.0".to_owned(), za)?;
            check.finite("balance.two_plane.heights_m.1".to_owned(), zb)?;
            // A trial mass goes in its correction plane: the influence coefficients
            // hold for masses at that height only.
            for (field, mass, plane) in [
                ("balance.trial_mass.height_m", b.trial_mass.as_ref(), za),
                (
                    "balance.two_plane.trial_mass.height_m",
                    t.trial_mass.as_ref(),
                    zb,
                ),
            ] {
                if let Some(h) = mass.and_then(|m| m.height_m)
                    && h != plane
                {
                    return Err(unsupported(field, UnsupportedReason::TrialOutOfPlane));
                }
            }
            if za == zb {
                return Err(unsupported(
                    "balance.two_plane.heights_m",
                    UnsupportedReason::PlanesAtOneHeight,
                ));
            }
            let radius_b = t.radius_b_m.unwrap_or(b.correction_radius_m);
            check.positive("balance.two_plane.radius_b_m", radius_b)?;
            let trial_b = match (&t.trial, &t.trial_mass) {
                (Some(name), Some(m)) => {
                    let i = phase("balance.two_plane.trial", name)?;
                    check.positive("balance.two_plane.trial_mass.mass_kg", m.mass_kg)?;
                    check.positive("balance.two_plane.trial_mass.radius_m", m.radius_m)?;
                    check.finite(
                        "balance.two_plane.trial_mass.azimuth_deg".to_owned(),
                        m.azimuth_deg,
                    )?;
                    Some((
                        i,
                        balance::TrialMass {
                            mass_kg: m.mass_kg,
                            radius_m: m.radius_m,
                            azimuth_deg: m.azimuth_deg,
                        },
                    ))
                }
                (None, None) => None,
                (Some(_), None) | (None, Some(_)) => {
                    return Err(unsupported(
                        if t.trial.is_some() {
                            "balance.two_plane.trial_mass"
                        } else {
                            "balance.two_plane.trial"
                        },
                        UnsupportedReason::TrialNeedsTrialMass,
                    ));
                }
            };
            let influence = trial_b.is_some() && trial.is_some();
            let stiffness =
                b.radial_stiffness_n_m.is_some() && b.angular_stiffness_n_m_rad.is_some();
            if !influence && !stiffness {
                return Err(unsupported(
                    "balance.two_plane",
                    UnsupportedReason::TwoPlaneNeedsMethod,
                ));
            }
            let plane = |height_m: f64, radius_m: f64| balance::HeightPlane {
                height_m,
                plane: balance::CorrectionPlane {
                    radius_m,
                    fixed_azimuths_deg: b.fixed_azimuths_deg.clone(),
                },
            };
            Ok(TwoPlaneInputs {
                planes: [plane(za, b.correction_radius_m), plane(zb, radius_b)],
                trial: trial_b,
            })
        })
        .transpose()?;
    let second = b
        .second_probe
        .as_ref()
        .map(|q| {
            let field = "balance.second_probe.probe_to_piga_mm";
            check.finite(field.to_owned(), q.probe_to_piga_mm)?;
            if q.probe_to_piga_mm == first_probe_to_piga_mm {
                return Err(unsupported(
                    field,
                    UnsupportedReason::SecondProbeAtFirstHeight,
                ));
            }
            let mut of = HashMap::new();
            for (key, value) in &q.phases {
                let first = phase(&format!("balance.second_probe.phases[{key:?}]"), key)?;
                let second = phase(&format!("balance.second_probe.phases[{key:?}]"), value)?;
                of.insert(first, second);
            }
            let used: Vec<usize> = [Some(initial), trial.map(|t| t.0), check_phase]
                .into_iter()
                .chain([two_plane.as_ref().and_then(|t| t.trial.map(|x| x.0))])
                .flatten()
                .collect();
            // The second probe's data is another phase than any the first probe gives.
            if let Some((key, _)) = q
                .phases
                .iter()
                .find(|(_, value)| names.get(value.as_str()).is_some_and(|i| used.contains(i)))
            {
                return Err(unsupported(
                    &format!("balance.second_probe.phases[{key:?}]"),
                    UnsupportedReason::SecondProbePhaseIsFirst,
                ));
            }
            for i in used {
                if !of.contains_key(&i) {
                    return Err(unsupported(
                        "balance.second_probe.phases",
                        UnsupportedReason::SecondProbeNeedsPhase,
                    ));
                }
            }
            Ok(SecondProbeInputs {
                probe_to_piga_mm: q.probe_to_piga_mm,
                probe_direction: probe_direction(q.probe_direction),
                phase_of: of,
            })
        })
        .transpose()?;
    Ok(BalanceInputs {
        second,
        angular_stiffness_n_m_rad: b.angular_stiffness_n_m_rad,
        two_plane,
        initial,
        trial,
        radial_stiffness_n_m: b.radial_stiffness_n_m,
        plane: balance::CorrectionPlane {
            radius_m: b.correction_radius_m,
            fixed_azimuths_deg: b.fixed_azimuths_deg.clone(),
        },
        rotor_mass_kg: b.rotor_mass_kg,
        check: check_phase,
    })
}
