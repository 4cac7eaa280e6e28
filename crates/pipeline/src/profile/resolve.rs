//! Resolving a study against a validated lab profile: the study's missing values filled from
//! the profile, each step recording where its values came from.

use std::collections::BTreeMap;
use std::path::Path;

use crate::config::{
    CentrifugeConfig, CertificateConfig, EquipmentConfig, InstrumentConfig, OrientationName,
    ProbeConfig, ProfileConfig, StudyConfig, TraceabilityConfig, TypeBInputName, UncertaintyConfig,
};
use crate::error::{PipelineError, Result};
use crate::results::{ProfileResults, ValueOrigin, ValueSource};

/// A Type B input the profile stated, its traceability statement and its field under
/// `uncertainty.`.
type Statement = (TypeBInputName, String, &'static str);

/// What the study uses of the profile: the profile, the centrifuge it names and, when there
/// are, its probe and data acquisition, each with its index in the profile's list.
struct Found<'p> {
    profile: &'p ProfileConfig,
    ci: usize,
    centrifuge: &'p CentrifugeConfig,
    probe: Option<(usize, &'p ProbeConfig)>,
    daq: Option<(usize, &'p InstrumentConfig)>,
}

impl Found<'_> {
    /// A field of the centrifuge in the profile (`centrifuges[0].radius_m`).
    fn at(&self, field: &str) -> String {
        format!("centrifuges[{}].{field}", self.ci)
    }
}

/// Fills the study's missing values from a validated profile (`p`, read from `source`) and
/// records where each value came from; `study` names the study file in errors.
pub(super) fn resolve(
    config: &mut StudyConfig,
    p: &ProfileConfig,
    source: &Path,
    study: &Path,
) -> Result<(ProfileResults, Vec<PipelineError>)> {
    let file = source.display().to_string();
    let mut errors = Vec::new();
    let found = find(config, p, &file, study, &mut errors)?;
    let mut values = Values {
        list: Vec::new(),
        file: &file,
    };
    fill_geometry(config, &found, &mut values);
    let statements = fill_type_b(config, &found, &mut values);
    fill_two_orientation(config, &found, &mut values);
    if let Some(cert) = config.certificate.as_mut() {
        fill_certificate(cert, &found, &statements, &mut values);
        fill_authorisation(cert, p, &file, study, &mut values, &mut errors);
    }
    let values = values.list;
    Ok((
        ProfileResults {
            file,
            centrifuge: found.centrifuge.name.clone(),
            probe: found.probe.map(|(_, x)| x.name.clone()),
            daq: found.daq.map(|(_, d)| d.name.clone()),
            values,
        },
        errors,
    ))
}

/// The centrifuge the study names (refused when it names none or one the profile does not
/// have), its probe (the study's or the centrifuge's; an unknown one is an error in
/// `errors`) and its data acquisition.
fn find<'p>(
    config: &StudyConfig,
    p: &'p ProfileConfig,
    file: &str,
    study: &Path,
    errors: &mut Vec<PipelineError>,
) -> Result<Found<'p>> {
    let centrifuge_names: Vec<String> = p.centrifuges.iter().map(|c| c.name.clone()).collect();
    let Some(centrifuge_name) = config.centrifuge.clone() else {
        return Err(PipelineError::MissingField {
            path: study.to_owned(),
            field: "centrifuge".to_owned(),
            hint: format!(
                "the centrifuge used, by its name in {file}: one of {}",
                centrifuge_names.join(", ")
            ),
        });
    };
    let Some((ci, centrifuge)) = p
        .centrifuges
        .iter()
        .enumerate()
        .find(|(_, c)| c.name == centrifuge_name)
    else {
        return Err(PipelineError::UnknownKey {
            path: study.to_owned(),
            field: "centrifuge".to_owned(),
            key: centrifuge_name,
            known: centrifuge_names,
        });
    };
    let probe_name = config.probe.clone().or_else(|| centrifuge.probe.clone());
    let probe = match &probe_name {
        None => None,
        Some(name) => match p.probes.iter().enumerate().find(|(_, x)| &x.name == name) {
            Some(found) => Some(found),
            None => {
                errors.push(PipelineError::UnknownKey {
                    path: study.to_owned(),
                    field: "probe".to_owned(),
                    key: name.clone(),
                    known: p.probes.iter().map(|x| x.name.clone()).collect(),
                });
                None
            }
        },
    };
    let daq = centrifuge
        .daq
        .as_ref()
        .and_then(|name| p.daqs.iter().enumerate().find(|(_, d)| &d.name == name));
    Ok(Found {
        profile: p,
        ci,
        centrifuge,
        probe,
        daq,
    })
}

/// The radius, g and the lever's geometry.
fn fill_geometry(config: &mut StudyConfig, found: &Found<'_>, values: &mut Values<'_>) {
    let centrifuge = found.centrifuge;
    values.fill(
        &mut config.radius_m,
        centrifuge.radius_m,
        "radius_m",
        &found.at("radius_m"),
    );
    values.fill(
        &mut config.g_m_s2,
        found.profile.gravity.g_m_s2,
        "g_m_s2",
        "gravity.g_m_s2",
    );
    let lever = &centrifuge.lever;
    values.fill(
        &mut config.lever.pivot_to_probe_mm,
        lever.pivot_to_probe_mm,
        "lever.pivot_to_probe_mm",
        &found.at("lever.pivot_to_probe_mm"),
    );
    values.fill(
        &mut config.lever.probe_to_piga_mm,
        lever.probe_to_piga_mm,
        "lever.probe_to_piga_mm",
        &found.at("lever.probe_to_piga_mm"),
    );
    values.fill(
        &mut config.lever.probe_direction,
        lever.probe_direction,
        "lever.probe_direction",
        &found.at("lever.probe_direction"),
    );
    values.fill(
        &mut config.lever.angle_zero_deg,
        lever.angle_zero_deg,
        "lever.angle_zero_deg",
        &found.at("lever.angle_zero_deg"),
    );
}

/// The Type B inputs: each with its standing statement, the traceability of a non-zero
/// uncertainty and the reason for a zero. What the profile stated, for the certificate's
/// traceability.
fn fill_type_b(
    config: &mut StudyConfig,
    found: &Found<'_>,
    values: &mut Values<'_>,
) -> Vec<Statement> {
    let (p, centrifuge) = (found.profile, found.centrifuge);
    let at = |field: &str| found.at(field);
    let lever = &centrifuge.lever;
    let stated_gain = config.stated_probe_gain();
    let u = config.uncertainty.get_or_insert_with(|| UncertaintyConfig {
        radius_u_m: None,
        g_u_m_s2: None,
        g_source: String::new(),
        rate_u_relative: None,
        pivot_to_probe_u_mm: None,
        probe_to_piga_u_mm: None,
        probe_gain_u_relative: None,
        zero_reasons: BTreeMap::new(),
    });
    let t = &centrifuge.traceability;
    let mut statements: Vec<Statement> = Vec::new();
    let mut type_b = |values: &mut Values<'_>,
                      slot: &mut Option<f64>,
                      stated: Option<f64>,
                      name: &'static str,
                      profile_field: String,
                      input: TypeBInputName,
                      statement: &str| {
        if values.fill(slot, stated, &format!("uncertainty.{name}"), &profile_field) {
            statements.push((input, statement.to_owned(), name));
        }
    };
    type_b(
        values,
        &mut u.radius_u_m,
        centrifuge.radius_u_m,
        "radius_u_m",
        at("radius_u_m"),
        TypeBInputName::Radius,
        &t.radius,
    );
    type_b(
        values,
        &mut u.g_u_m_s2,
        p.gravity.u_m_s2,
        "g_u_m_s2",
        "gravity.u_m_s2".to_owned(),
        TypeBInputName::G,
        &p.gravity.source,
    );
    type_b(
        values,
        &mut u.rate_u_relative,
        centrifuge.rate_u_relative,
        "rate_u_relative",
        at("rate_u_relative"),
        TypeBInputName::RateScale,
        &t.rate_scale,
    );
    type_b(
        values,
        &mut u.pivot_to_probe_u_mm,
        lever.pivot_to_probe_u_mm,
        "pivot_to_probe_u_mm",
        at("lever.pivot_to_probe_u_mm"),
        TypeBInputName::PivotToProbe,
        &t.pivot_to_probe,
    );
    type_b(
        values,
        &mut u.probe_to_piga_u_mm,
        lever.probe_to_piga_u_mm,
        "probe_to_piga_u_mm",
        at("lever.probe_to_piga_u_mm"),
        TypeBInputName::ProbeToPiga,
        &t.probe_to_piga,
    );
    if let Some((pi, probe)) = found.probe {
        if stated_gain.is_none() {
            type_b(
                values,
                &mut u.probe_gain_u_relative,
                probe.gain_u_relative,
                "probe_gain_u_relative",
                format!("probes[{pi}].gain_u_relative"),
                TypeBInputName::ProbeGain,
                &probe.traceability,
            );
        } else {
            // The recordings state the gain's uncertainty (a gap in volts with its
            // sensitivity); the probe's certificate stands behind it.
            statements.push((
                TypeBInputName::ProbeGain,
                probe.traceability.clone(),
                "probe_gain_u_relative",
            ));
        }
    }
    if u.g_source.trim().is_empty() {
        u.g_source.clone_from(&p.gravity.source);
        values.push(
            "uncertainty.g_source",
            ValueSource::Profile,
            "gravity.source",
        );
    } else {
        values.push("uncertainty.g_source", ValueSource::Study, "gravity.source");
    }
    let zero: Vec<(&'static str, String)> = statements
        .iter()
        .filter(|(_, _, name)| {
            let value = match *name {
                "radius_u_m" => u.radius_u_m,
                "g_u_m_s2" => u.g_u_m_s2,
                "rate_u_relative" => u.rate_u_relative,
                "pivot_to_probe_u_mm" => u.pivot_to_probe_u_mm,
                "probe_to_piga_u_mm" => u.probe_to_piga_u_mm,
                _ => u.probe_gain_u_relative,
            };
            value == Some(0.0)
        })
        .map(|(_, statement, name)| (*name, statement.clone()))
        .collect();
    for (name, statement) in zero {
        u.zero_reasons.entry(name.to_owned()).or_insert(statement);
    }
    statements
}

/// Two orientations: the IA-in radius is the centrifuge's, the IA-out one its
/// `radius_ia_out_m` when the profile gives it.
fn fill_two_orientation(config: &mut StudyConfig, found: &Found<'_>, values: &mut Values<'_>) {
    let centrifuge = found.centrifuge;
    let at = |field: &str| found.at(field);
    if let Some(two) = config.two_orientation.as_mut() {
        values.fill(
            &mut two.latitude_deg,
            centrifuge.latitude_deg,
            "two_orientation.latitude_deg",
            &at("latitude_deg"),
        );
        values.fill(
            &mut two.spin_seen_from_above,
            centrifuge.spin_seen_from_above,
            "two_orientation.spin_seen_from_above",
            &at("spin_seen_from_above"),
        );
        for (i, o) in two.orientations.iter_mut().enumerate() {
            let (stated, field) = match o.orientation {
                Some(OrientationName::IaIn) => (centrifuge.radius_m, at("radius_m")),
                Some(OrientationName::IaOut) => (centrifuge.radius_ia_out_m, at("radius_ia_out_m")),
                None => continue,
            };
            values.fill(
                &mut o.radius_m,
                stated,
                &format!("two_orientation.orientations[{i}].radius_m"),
                &field,
            );
        }
    }
}

/// The certificate's laboratory, place, procedure, operator, equipment, traceability,
/// decision rule and limits' source, where the study leaves them out.
fn fill_certificate(
    cert: &mut CertificateConfig,
    found: &Found<'_>,
    statements: &[Statement],
    values: &mut Values<'_>,
) {
    let (p, centrifuge) = (found.profile, found.centrifuge);
    let at = |field: &str| found.at(field);
    let text =
        |values: &mut Values<'_>, slot: &mut String, stated: &str, field: &str, from: &str| {
            if slot.trim().is_empty() {
                stated.clone_into(slot);
                values.push(field, ValueSource::Profile, from);
            } else {
                values.push(field, ValueSource::Study, from);
            }
        };
    if cert.laboratory.name.trim().is_empty() && cert.laboratory.address.trim().is_empty() {
        cert.laboratory.name.clone_from(&p.laboratory.name);
        cert.laboratory.address.clone_from(&p.laboratory.address);
        cert.laboratory
            .accreditation
            .clone_from(&p.laboratory.accreditation);
        cert.laboratory.country.clone_from(&p.laboratory.country);
        values.push("certificate.laboratory", ValueSource::Profile, "laboratory");
    } else {
        values.push("certificate.laboratory", ValueSource::Study, "laboratory");
    }
    text(
        values,
        &mut cert.location,
        &centrifuge.location,
        "certificate.location",
        &at("location"),
    );
    text(
        values,
        &mut cert.procedure,
        &p.procedure,
        "certificate.procedure",
        "procedure",
    );
    if let [only] = p.operators.as_slice() {
        text(
            values,
            &mut cert.operator,
            only,
            "certificate.operator",
            "operators",
        );
    }
    fill_equipment(cert, found, values);
    fill_traceability(cert, found, statements, values);
    // The decision rule and the limits' source apply to limits: without any, a
    // certificate states no conformity.
    let limited = !cert.limits.is_empty();
    if limited && cert.decision_rule.is_none() && p.decision_rule.is_some() {
        cert.decision_rule = p.decision_rule;
        values.push(
            "certificate.decision_rule",
            ValueSource::Profile,
            "decision_rule",
        );
    }
    if limited
        && cert
            .limits_source
            .as_deref()
            .is_none_or(|s| s.trim().is_empty())
        && !p.limits_source.trim().is_empty()
    {
        cert.limits_source = Some(p.limits_source.clone());
        values.push(
            "certificate.limits_source",
            ValueSource::Profile,
            "limits_source",
        );
    }
}

/// The certificate's equipment, when the study lists none: the centrifuge, the probe and the
/// data acquisition it uses, and the gravity survey.
fn fill_equipment(cert: &mut CertificateConfig, found: &Found<'_>, values: &mut Values<'_>) {
    let (p, centrifuge, ci) = (found.profile, found.centrifuge, found.ci);
    if cert.equipment.is_empty() {
        cert.equipment.push(equipment(
            "precision centrifuge",
            &centrifuge.description,
            &centrifuge.identity,
            &centrifuge.calibration_due,
        ));
        if let Some((_, probe)) = found.probe {
            cert.equipment.push(equipment(
                "displacement probe",
                &probe.description,
                &probe.identity,
                &probe.calibration_due,
            ));
        }
        if let Some((_, d)) = found.daq {
            cert.equipment.push(equipment(
                "data acquisition",
                &d.description,
                &d.identity,
                &d.calibration_due,
            ));
        }
        cert.equipment.push(equipment(
            "local gravity (survey)",
            &p.gravity.source,
            &p.gravity.identity,
            &p.gravity.calibration_due,
        ));
        let mut from = vec![format!("centrifuges[{ci}]")];
        if let Some((pi, _)) = found.probe {
            from.push(format!("probes[{pi}]"));
        }
        if let Some((di, _)) = found.daq {
            from.push(format!("daqs[{di}]"));
        }
        from.push("gravity".to_owned());
        values.push(
            "certificate.equipment",
            ValueSource::Profile,
            &from.join(", "),
        );
    } else {
        values.push(
            "certificate.equipment",
            ValueSource::Study,
            &format!("centrifuges[{ci}]"),
        );
    }
}

/// A traceability statement for each Type B input the profile stated and the study's
/// certificate does not.
fn fill_traceability(
    cert: &mut CertificateConfig,
    found: &Found<'_>,
    statements: &[Statement],
    values: &mut Values<'_>,
) {
    for (input, statement, _) in statements {
        if !cert.traceability.iter().any(|t| t.input == *input) {
            cert.traceability.push(TraceabilityConfig {
                input: *input,
                statement: statement.clone(),
            });
            let from = match input {
                TypeBInputName::G => "gravity.source".to_owned(),
                TypeBInputName::ProbeGain => found
                    .probe
                    .map_or_else(String::new, |(pi, _)| format!("probes[{pi}].traceability")),
                other => found.at(&format!("traceability.{}", other.key())),
            };
            values.push(
                &format!("certificate.traceability ({})", input.key()),
                ValueSource::Profile,
                &from,
            );
        }
    }
}

/// Who authorises the certificate: the profile's only signatory when the study names none,
/// or the one it names (with the profile's role unless it states one); an unknown or an
/// ambiguous one is an error in `errors`.
fn fill_authorisation(
    cert: &mut CertificateConfig,
    p: &ProfileConfig,
    file: &str,
    study: &Path,
    values: &mut Values<'_>,
    errors: &mut Vec<PipelineError>,
) {
    let signers: Vec<String> = p.signatories.iter().map(|s| s.name.clone()).collect();
    let a = &mut cert.authorisation;
    if a.name.trim().is_empty() {
        if let [only] = p.signatories.as_slice() {
            a.name.clone_from(&only.name);
            a.role.clone_from(&only.role);
            values.push(
                "certificate.authorisation",
                ValueSource::Profile,
                "signatories[0]",
            );
        } else {
            errors.push(PipelineError::MissingField {
                path: study.to_owned(),
                field: "certificate.authorisation.name".to_owned(),
                hint: format!(
                    "who authorises the certificate: one of {file}'s signatories ({})",
                    signers.join(", ")
                ),
            });
        }
    } else {
        match p.signatories.iter().position(|s| s.name == a.name) {
            Some(si) => {
                // The study names who signs; the role is the profile's unless it states
                // one too.
                let (field, from) = if a.role.trim().is_empty() {
                    a.role.clone_from(&p.signatories[si].role);
                    ("certificate.authorisation.role", ValueSource::Profile)
                } else {
                    ("certificate.authorisation", ValueSource::Study)
                };
                values.push(field, from, &format!("signatories[{si}]"));
            }
            None => errors.push(PipelineError::UnknownKey {
                path: study.to_owned(),
                field: "certificate.authorisation.name".to_owned(),
                key: a.name.clone(),
                known: signers,
            }),
        }
    }
}

/// An instrument as the certificate lists it.
fn equipment(role: &str, description: &str, identity: &str, due: &str) -> EquipmentConfig {
    EquipmentConfig {
        role: role.to_owned(),
        description: description.to_owned(),
        identity: identity.to_owned(),
        calibration_due: due.to_owned(),
    }
}

/// Where each value the profile could give came from.
struct Values<'a> {
    list: Vec<ValueOrigin>,
    file: &'a str,
}

impl Values<'_> {
    fn push(&mut self, field: &str, from: ValueSource, profile_field: &str) {
        self.list.push(ValueOrigin {
            field: field.to_owned(),
            from,
            profile_field: format!("{}: {profile_field}", self.file),
        });
    }

    /// Takes the profile's value when the study gives none; whether it did.
    fn fill<T: Copy>(
        &mut self,
        slot: &mut Option<T>,
        stated: Option<T>,
        field: &str,
        profile_field: &str,
    ) -> bool {
        match (slot.is_some(), stated) {
            (true, _) => {
                self.push(field, ValueSource::Study, profile_field);
                false
            }
            (false, Some(v)) => {
                *slot = Some(v);
                self.push(field, ValueSource::Profile, profile_field);
                true
            }
            (false, None) => false,
        }
    }
}
