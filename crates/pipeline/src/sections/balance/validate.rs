//! The balance section's validation.

use std::collections::HashMap;

use balance::{CorrectionPlane, TrialMass};

use crate::config::{BalanceConfig, SecondProbeConfig, TrialMassConfig, TwoPlaneConfig};
use crate::error::{PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, probe_direction, sorted_names};
use crate::resolved::{PhaseShape, Resolved};

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
    resolved: &Resolved<'_>,
    names: &HashMap<&str, usize>,
    first_probe_to_piga_mm: f64,
) -> Result<BalanceInputs> {
    let known = Phases {
        check,
        resolved,
        names,
    };
    let initial = known.phase("balance.initial", &b.initial)?;
    let trial = trial(&known, "balance", b.trial.as_deref(), b.trial_mass.as_ref())?;
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
        .map(|name| known.phase("balance.check", name))
        .transpose()?;
    if let Some(k) = b.angular_stiffness_n_m_rad {
        check.positive("balance.angular_stiffness_n_m_rad", k)?;
    }
    let two_plane = b
        .two_plane
        .as_ref()
        .map(|t| two_plane(&known, b, t, trial.is_some()))
        .transpose()?;
    let used: Vec<usize> = [Some(initial), trial.map(|t| t.0), check_phase]
        .into_iter()
        .chain([two_plane.as_ref().and_then(|t| t.trial.map(|x| x.0))])
        .flatten()
        .collect();
    let second = b
        .second_probe
        .as_ref()
        .map(|q| second_probe(&known, q, &used, first_probe_to_piga_mm))
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

/// The study's phases as the balance section names them.
struct Phases<'a> {
    check: &'a Check<'a>,
    resolved: &'a Resolved<'a>,
    names: &'a HashMap<&'a str, usize>,
}

impl Phases<'_> {
    /// The index of the phase `name` (named by `field`): a known phase of first harmonics
    /// with enough rates for the phasor fit.
    fn phase(&self, field: &str, name: &str) -> Result<usize> {
        let check = self.check;
        let Some(&i) = self.names.get(name) else {
            return Err(PipelineError::UnknownPhase {
                path: check.path.to_owned(),
                field: field.to_owned(),
                name: name.to_owned(),
                known: sorted_names(self.names),
            });
        };
        let count = match self.resolved.phase_shape(i) {
            PhaseShape::FirstHarmonic { points } => points,
            PhaseShape::Recordings { files } => files,
            PhaseShape::RadiusError | PhaseShape::RadiusChange { .. } => {
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
    }

    fn unsupported(&self, field: &str, reason: UnsupportedReason) -> PipelineError {
        PipelineError::Unsupported {
            path: self.check.path.to_owned(),
            field: field.to_owned(),
            reason,
        }
    }
}

/// A trial run and its mass under `at` (`balance` or `balance.two_plane`): both or neither,
/// the phase known, the mass, its radius positive and its azimuth and height finite.
fn trial(
    known: &Phases<'_>,
    at: &str,
    name: Option<&str>,
    mass: Option<&TrialMassConfig>,
) -> Result<Option<(usize, TrialMass)>> {
    let check = known.check;
    match (name, mass) {
        (Some(name), Some(m)) => {
            let i = known.phase(&format!("{at}.trial"), name)?;
            check.positive(&format!("{at}.trial_mass.mass_kg"), m.mass_kg)?;
            check.positive(&format!("{at}.trial_mass.radius_m"), m.radius_m)?;
            check.finite(format!("{at}.trial_mass.azimuth_deg"), m.azimuth_deg)?;
            if let Some(h) = m.height_m {
                check.finite(format!("{at}.trial_mass.height_m"), h)?;
            }
            Ok(Some((
                i,
                balance::TrialMass {
                    mass_kg: m.mass_kg,
                    radius_m: m.radius_m,
                    azimuth_deg: m.azimuth_deg,
                },
            )))
        }
        (None, None) => Ok(None),
        (Some(_), None) | (None, Some(_)) => Err(known.unsupported(
            &if name.is_some() {
                format!("{at}.trial_mass")
            } else {
                format!("{at}.trial")
            },
            UnsupportedReason::TrialNeedsTrialMass,
        )),
    }
}

/// The two-plane correction: with a second probe, two planes at different finite heights,
/// each trial mass in its plane, plane B's radius and trial, and a method (both trials, or
/// both stiffnesses).
fn two_plane(
    known: &Phases<'_>,
    b: &BalanceConfig,
    t: &TwoPlaneConfig,
    trial_a: bool,
) -> Result<TwoPlaneInputs> {
    let check = known.check;
    if b.second_probe.is_none() {
        return Err(known.unsupported(
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
            return Err(known.unsupported(field, UnsupportedReason::TrialOutOfPlane));
        }
    }
    if za == zb {
        return Err(known.unsupported(
            "balance.two_plane.heights_m",
            UnsupportedReason::PlanesAtOneHeight,
        ));
    }
    let radius_b = t.radius_b_m.unwrap_or(b.correction_radius_m);
    check.positive("balance.two_plane.radius_b_m", radius_b)?;
    // (plane B's trial mass is in its plane, checked above: its height is finite)
    let trial_b = trial(
        known,
        "balance.two_plane",
        t.trial.as_deref(),
        t.trial_mass.as_ref(),
    )?;
    let influence = trial_b.is_some() && trial_a;
    let stiffness = b.radial_stiffness_n_m.is_some() && b.angular_stiffness_n_m_rad.is_some();
    if !influence && !stiffness {
        return Err(known.unsupported("balance.two_plane", UnsupportedReason::TwoPlaneNeedsMethod));
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
}

/// The second probe: at another height than the first, each of the first probe's phases
/// the section `used` paired with another phase of the second probe's data.
fn second_probe(
    known: &Phases<'_>,
    q: &SecondProbeConfig,
    used: &[usize],
    first_probe_to_piga_mm: f64,
) -> Result<SecondProbeInputs> {
    let field = "balance.second_probe.probe_to_piga_mm";
    known.check.finite(field.to_owned(), q.probe_to_piga_mm)?;
    if q.probe_to_piga_mm == first_probe_to_piga_mm {
        return Err(known.unsupported(field, UnsupportedReason::SecondProbeAtFirstHeight));
    }
    let mut of = HashMap::new();
    for (key, value) in &q.phases {
        let first = known.phase(&format!("balance.second_probe.phases[{key:?}]"), key)?;
        let second = known.phase(&format!("balance.second_probe.phases[{key:?}]"), value)?;
        of.insert(first, second);
    }
    // The second probe's data is another phase than any the first probe gives.
    if let Some((key, _)) = q.phases.iter().find(|(_, value)| {
        known
            .names
            .get(value.as_str())
            .is_some_and(|i| used.contains(i))
    }) {
        return Err(known.unsupported(
            &format!("balance.second_probe.phases[{key:?}]"),
            UnsupportedReason::SecondProbePhaseIsFirst,
        ));
    }
    for i in used {
        if !of.contains_key(i) {
            return Err(known.unsupported(
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
}
