//! The mountings section's validation: every unknown term or preset, missing radius, bad
//! angle uncertainty and unreadable table at once; the probe phase compensated; then, with
//! the tables read, whether the mountings separate the chosen terms — refused before
//! anything runs, naming the mounting that would separate them (`check` says the same).

use std::path::Path;

use ::calibration::{ArmStretch, JointSpec, MountingData, Nuisances, separability};
use accel_model::{AccelKind, Mounting, MountingPreset, Term};

use crate::config::{ArmStretchName, MountingConfig, MountingsConfig};
use crate::error::{InvalidReason, PipelineError, Result};
use crate::inputs::{Check, Core, DataSource, InputFile, PhaseNames};
use crate::piga_data::{self, PigaTableRows};
use crate::resolved::Resolved;

/// One mounting, validated, with its table read.
#[derive(Debug, Clone)]
pub(crate) struct MountingSet {
    /// `mountings.list[i]`.
    pub(crate) field: String,
    pub(crate) mounting: Mounting,
    /// Whether the fixture's angular uncertainty was stated.
    pub(crate) angle_u_stated: bool,
    pub(crate) nuisances: Nuisances,
    pub(crate) table: PigaTableRows,
}

/// The validated mountings section.
#[derive(Debug, Clone)]
pub(crate) struct MountingsInputs {
    pub(crate) kind: AccelKind,
    pub(crate) terms: Vec<Term>,
    pub(crate) omega3: bool,
    pub(crate) arm_stretch: ArmStretch,
    /// The probe phase compensated, and how it was chosen (`None`: not compensated).
    pub(crate) phase: Option<(usize, &'static str)>,
    /// The vertical Earth rate, rad/s, and whether the site and spin were stated.
    pub(crate) earth_rate_vertical_rad_s: f64,
    pub(crate) earth_rate_stated: bool,
    pub(crate) sets: Vec<MountingSet>,
    /// The separability of the chosen terms by these mountings (full rank here).
    pub(crate) separability: ::calibration::Separability,
    /// The `uncertainty` section's radius, g and rate-scale inputs (`None`: no section).
    pub(crate) type_b: Option<::calibration::MountingsTypeB>,
}

impl MountingsInputs {
    /// Every table the section read, with its digest, in the configuration's order.
    pub(crate) fn input_files(&self) -> impl Iterator<Item = InputFile<'_>> {
        self.sets.iter().map(|s| InputFile {
            path: &s.table.file,
            role: crate::inputs::InputRole::PigaTable,
            field: s.table.field.clone(),
            digest: s.table.digest.as_ref(),
        })
    }

    /// The joint fit's declaration (with the probe's compensation when given).
    pub(crate) fn spec(
        &self,
        g_m_s2: f64,
        probe: Option<::calibration::ProbeCompensation>,
    ) -> JointSpec {
        JointSpec {
            kind: self.kind,
            terms: self.terms.clone(),
            omega3: self.omega3,
            arm_stretch: self.arm_stretch,
            g_m_s2,
            earth_rate_vertical_rad_s: self.earth_rate_vertical_rad_s,
            probe,
        }
    }

    /// The mountings' data for the joint fit (rates in rad/s).
    pub(crate) fn data<'a>(&'a self, rates_rad_s: &'a [Vec<f64>]) -> Vec<MountingData<'a>> {
        self.sets
            .iter()
            .zip(rates_rad_s)
            .map(|(s, rates)| MountingData {
                field: s.field.clone(),
                mounting: s.mounting.clone(),
                nuisances: s.nuisances,
                rates_rad_s: rates,
                outputs: &s.table.outputs_rad_s,
                sigma: s.table.sigma_rad_s.as_deref(),
            })
            .collect()
    }

    /// Each mounting's rates in rad/s.
    pub(crate) fn rates_rad_s(&self) -> Vec<Vec<f64>> {
        self.sets
            .iter()
            .map(|s| {
                s.table
                    .rates_deg_s
                    .iter()
                    .map(|&r| units::deg_s_to_rad_s(r))
                    .collect()
            })
            .collect()
    }
}

fn problem(check: &Check<'_>, field: String, problem: String) -> PipelineError {
    PipelineError::InvalidMountings {
        path: check.path.to_owned(),
        field,
        problem,
    }
}

/// The preset of a tag, or an error listing the tags.
fn preset(tag: &str) -> std::result::Result<MountingPreset, String> {
    MountingPreset::from_tag(tag).ok_or_else(|| {
        let known: Vec<&str> = MountingPreset::ALL.iter().map(|p| p.tag()).collect();
        format!(
            "no mounting is called “{}”: the presets are {}",
            edge_io::visible(tag),
            known.join(", ")
        )
    })
}

/// Validates the section and reads its tables; every problem at once, in the file's
/// order, then the separability of the chosen terms by the mountings (refused when rank
/// deficient, naming the mounting that separates them). Without `compensate_with`, a
/// compensated fit uses the study's compensating phase (`resolved`); data paths are relative
/// to the configuration's folder, and g and the lever are the study's (`core`).
pub(crate) fn validate(
    check: &Check<'_>,
    config: &MountingsConfig,
    resolved: &Resolved<'_>,
    names: &PhaseNames<'_>,
    core: &Core,
    load: &dyn DataSource,
) -> Result<MountingsInputs> {
    let (base, g_m_s2, lever) = (core.base(), core.g_m_s2, &core.lever);
    let mut errors = Vec::new();
    // the terms: k0 and k1 always, each tag known
    let mut terms = vec![Term::K0, Term::K1];
    for (i, tag) in config.terms.iter().enumerate() {
        match Term::from_tag(tag.trim()) {
            Some(t) => terms.push(t),
            None => {
                let known: Vec<&str> = Term::ALL.iter().map(|t| t.tag()).collect();
                errors.push(problem(
                    check,
                    format!("mountings.terms[{i}]"),
                    format!(
                        "no term is called “{}”: the model's terms are {}",
                        edge_io::visible(tag),
                        known.join(", ")
                    ),
                ));
            }
        }
    }
    terms.sort();
    terms.dedup();
    if config.list.is_empty() {
        errors.push(problem(
            check,
            "mountings.list".to_owned(),
            "no mounting: list each mounting with its preset (or angles), radius and table"
                .to_owned(),
        ));
    }
    // the probe phase
    let phase = if config.compensate {
        let chosen = match &config.compensate_with {
            Some(name) => names
                .index(check, "mountings.compensate_with", name)
                .map(|p| (p, "compensate_with")),
            None => Ok((resolved.compensation.index, resolved.compensation.chosen_by)),
        };
        match chosen {
            Ok(p) => Some(p),
            Err(e) => {
                errors.push(e);
                None
            }
        }
    } else {
        None
    };
    let (earth_rate_vertical_rad_s, earth_rate_stated) =
        match (config.latitude_deg, config.spin_seen_from_above) {
            (Some(lat), _) if !(lat.is_finite() && lat.abs() <= 90.0) => {
                errors.push(check.invalid(
                    "mountings.latitude_deg".to_owned(),
                    lat,
                    InvalidReason::NotALatitude,
                ));
                (0.0, false)
            }
            (Some(lat), Some(spin)) => (
                ::calibration::AxialEarthRate::stated(lat, spin.spin()).value_rad_s,
                true,
            ),
            _ => (0.0, false),
        };
    let mut sets = Vec::with_capacity(config.list.len());
    for (i, m) in config.list.iter().enumerate() {
        if let Some(set) = mounting(check, config, i, m, base, load, &mut errors) {
            sets.push(set);
        }
    }
    let type_b = match resolved.type_b_of_section(check) {
        Ok(t) => t.map(|t| {
            let v = t.values;
            // the lever ratio ρ = (h₁ + h₂)/h₁ of eq. 22: u(ρ)/ρ = √((h₂·u₁/h₁)² + u₂²)/(h₁ + h₂)
            let (h1, h2) = (lever.pivot_to_probe_mm, lever.probe_to_piga_mm);
            let lever_u_relative =
                (h2 * v.pivot_to_probe_u_mm / h1).hypot(v.probe_to_piga_u_mm) / (h1 + h2);
            ::calibration::MountingsTypeB {
                radius_u_m: v.radius_u_m,
                g_u_m_s2: v.g_u_m_s2,
                rate_u_relative: v.rate_u_relative,
                probe_scale_u_relative: lever_u_relative.hypot(v.probe_gain_u_relative),
            }
        }),
        Err(e) => {
            errors.push(e);
            None
        }
    };
    PipelineError::from_list(errors)?;
    let arm_stretch = match config.arm_stretch {
        ArmStretchName::Auto => ArmStretch::Auto,
        ArmStretchName::Fit => ArmStretch::Fit,
        ArmStretchName::Off => ArmStretch::Off,
    };
    let mut inputs = MountingsInputs {
        kind: config.kind,
        terms,
        omega3: config.omega3,
        arm_stretch,
        phase,
        earth_rate_vertical_rad_s,
        earth_rate_stated,
        sets,
        separability: ::calibration::Separability {
            labels: Vec::new(),
            rank: 0,
            condition_number: 0.0,
            confounded: Vec::new(),
            poorly: Vec::new(),
            inflation: Vec::new(),
        },
        type_b,
    };
    // before anything runs: can these mountings separate the chosen terms?
    let rates = inputs.rates_rad_s();
    let data = inputs.data(&rates);
    let spec = inputs.spec(g_m_s2, None);
    let fail = |e: ::calibration::MountingsError| PipelineError::Mountings {
        path: check.path.to_owned(),
        source: Box::new(e),
    };
    let arm = matches!(arm_stretch, ArmStretch::Fit)
        || (matches!(arm_stretch, ArmStretch::Auto)
            && ::calibration::separability(&spec, &data, true)
                .map_err(fail)?
                .full_rank());
    let analysis = separability(&spec, &data, arm).map_err(fail)?;
    if !analysis.full_rank() {
        return Err(fail(::calibration::MountingsError::NotSeparable(Box::new(
            analysis,
        ))));
    }
    inputs.separability = analysis;
    Ok(inputs)
}

/// One mounting: its preset or angles, radius, angle uncertainty, nuisances and table.
/// Problems go to `errors`; `None` when it cannot be used.
fn mounting(
    check: &Check<'_>,
    config: &MountingsConfig,
    i: usize,
    m: &MountingConfig,
    base: &Path,
    load: &dyn DataSource,
    errors: &mut Vec<PipelineError>,
) -> Option<MountingSet> {
    let field = format!("mountings.list[{i}]");
    let before = errors.len();
    let label = m.label.clone();
    let axes = match (&m.preset, &m.angles) {
        (Some(tag), None) => match preset(tag.trim()) {
            Ok(p) => Some((p.label().to_owned(), p.axes())),
            Err(why) => {
                errors.push(problem(check, format!("{field}.preset"), why));
                None
            }
        },
        (None, Some(a)) => match a.axes() {
            Ok(axes) => Some((format!("mounting {}", i + 1), axes)),
            Err(e) => {
                errors.push(problem(check, format!("{field}.angles"), e.to_string()));
                None
            }
        },
        _ => {
            errors.push(problem(
                check,
                field.clone(),
                "state exactly one of `preset` (ia_in, ia_out, …) and `angles` (azimuth_deg, \
                 elevation_deg, roll_deg)"
                    .to_owned(),
            ));
            None
        }
    };
    let radius_m = match m.radius_m {
        None => {
            errors.push(PipelineError::MissingField {
                path: check.path.to_owned(),
                field: format!("{field}.radius_m"),
                hint: "the static radius of this mounting (proof mass to the spindle axis), m"
                    .to_owned(),
            });
            None
        }
        Some(r) if !(r.is_finite() && r > 0.0) => {
            errors.push(check.invalid(format!("{field}.radius_m"), r, InvalidReason::NotPositive));
            None
        }
        Some(r) => Some(r),
    };
    let angle_u_deg = match m.angle_u_deg {
        Some(u) if !(u.is_finite() && u >= 0.0) => {
            errors.push(check.invalid(format!("{field}.angle_u_deg"), u, InvalidReason::Negative));
            0.0
        }
        Some(u) => u,
        None => 0.0,
    };
    let table = match &m.table {
        None => {
            errors.push(PipelineError::MissingField {
                path: check.path.to_owned(),
                field: format!("{field}.table"),
                hint: "this mounting's table: rates in deg/s and mean outputs".to_owned(),
            });
            None
        }
        Some(t) if t.format.is_some() && !matches!(config.kind, AccelKind::Piga) => {
            errors.push(problem(
                check,
                format!("{field}.table.format"),
                format!(
                    "a `format` block converts a PIGA's output to rad/s; a pendulous \
                     accelerometer's table is read by its column names (`rate_column`, \
                     `output_column`, `sigma_column`), its outputs taken in {} as written",
                    config.kind.output_unit()
                ),
            ));
            None
        }
        Some(t) => {
            match piga_data::load_piga_table(t, &format!("{field}.table"), base, check.path, load) {
                Ok(rows) => Some(rows),
                Err(e) => {
                    errors.push(e);
                    None
                }
            }
        }
    };
    let reference = i == 0;
    for (key, stated) in [("own_bias", m.own_bias), ("own_scale", m.own_scale)] {
        if reference && stated == Some(true) {
            errors.push(problem(
                check,
                format!("{field}.{key}"),
                "the first mounting is the reference: its bias is k0 and its scale factor \
                 k1; give the other mountings their own"
                    .to_owned(),
            ));
        }
    }
    if errors.len() > before {
        return None;
    }
    let (words, axes) = axes?;
    let nuisances = Nuisances {
        own_bias: !reference && m.own_bias.unwrap_or(true),
        own_scale: !reference && m.own_scale.unwrap_or(false),
        tilt_rate: m.tilt_rate.unwrap_or(true),
    };
    Some(MountingSet {
        field,
        mounting: Mounting {
            label: label.unwrap_or(words),
            axes,
            radius_m: radius_m?,
            angle_u_deg,
        },
        angle_u_stated: m.angle_u_deg.is_some(),
        nuisances,
        table: table?,
    })
}
