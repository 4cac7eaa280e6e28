//! The lab profile's validation: every field checked, every problem kept, each naming the
//! profile's file and field.

use std::collections::HashMap;
use std::path::Path;

use crate::config::{CentrifugeConfig, InstrumentConfig, ProbeConfig, ProfileConfig};
use crate::date::Date;
use crate::error::{InvalidReason, PipelineError, Result, UnsupportedReason};

/// Validates the profile `p` read from `path`: every problem at once, each naming the
/// profile's file and field.
pub(super) fn validate(p: &ProfileConfig, path: &Path) -> Result<()> {
    let mut v = Validation {
        path,
        errors: Vec::new(),
    };
    v.text(
        "laboratory.name",
        &p.laboratory.name,
        "the laboratory's name",
    );
    v.text(
        "laboratory.address",
        &p.laboratory.address,
        "the laboratory's postal address, one line",
    );
    if let Some(a) = &p.laboratory.accreditation {
        v.text(
            "laboratory.accreditation",
            a,
            "the accreditation body and number (or leave the field out)",
        );
    }
    if let Some(country) = &p.laboratory.country
        && !(country.len() == 2 && country.bytes().all(|b| b.is_ascii_uppercase()))
    {
        v.errors.push(PipelineError::Unsupported {
            path: path.to_owned(),
            field: "laboratory.country".to_owned(),
            reason: UnsupportedReason::NotCountryCode,
        });
    }
    if p.signatories.is_empty() {
        v.missing(
            "signatories",
            "who may authorise a certificate: `[(name: \"…\", role: \"…\")]`",
        );
    }
    let mut names = HashMap::new();
    for (i, s) in p.signatories.iter().enumerate() {
        v.text(&format!("signatories[{i}].name"), &s.name, "their name");
        v.text(&format!("signatories[{i}].role"), &s.role, "their role");
        v.unique("signatories", i, &s.name, &mut names);
    }
    for (i, o) in p.operators.iter().enumerate() {
        v.text(&format!("operators[{i}]"), o, "the operator's name");
    }
    v.text(
        "procedure",
        &p.procedure,
        "the procedure followed: its reference and title",
    );
    for (i, c) in p.conditions.iter().enumerate() {
        v.text(
            &format!("conditions[{i}]"),
            c,
            "a condition recorded during a calibration (`ambient temperature`)",
        );
    }
    if p.centrifuges.is_empty() {
        v.missing("centrifuges", "at least one centrifuge");
    }
    let mut names = HashMap::new();
    for (i, c) in p.centrifuges.iter().enumerate() {
        v.centrifuge(i, c, p);
        v.unique("centrifuges", i, &c.name, &mut names);
    }
    let mut names = HashMap::new();
    for (i, probe) in p.probes.iter().enumerate() {
        v.probe(i, probe);
        v.unique("probes", i, &probe.name, &mut names);
    }
    let mut names = HashMap::new();
    for (i, d) in p.daqs.iter().enumerate() {
        v.instrument(&format!("daqs[{i}]"), d);
        v.unique("daqs", i, &d.name, &mut names);
    }
    let g = &p.gravity;
    v.positive(
        "gravity.g_m_s2",
        g.g_m_s2,
        "local gravity at the centrifuges, m/s²",
    );
    v.non_negative(
        "gravity.u_m_s2",
        g.u_m_s2,
        "the standard uncertainty of g, m/s²",
    );
    v.plausible(
        "gravity.u_m_s2",
        g.u_m_s2,
        "gravity.g_m_s2",
        g.g_m_s2,
        "m/s²",
    );
    v.text(
        "gravity.source",
        &g.source,
        "where g comes from: the survey, its report and the point it refers to",
    );
    v.text(
        "gravity.identity",
        &g.identity,
        "the survey's report number",
    );
    v.date("gravity.calibration_due", &g.calibration_due);
    if p.decision_rule.is_some() || !p.limits_source.is_empty() {
        v.text(
            "limits_source",
            &p.limits_source,
            "where the limits a certificate states come from (a customer's specification, a data sheet)",
        );
    }
    PipelineError::from_list(v.errors)
}

/// The validation's state: the profile's file and the problems found so far.
struct Validation<'a> {
    path: &'a Path,
    errors: Vec<PipelineError>,
}

impl Validation<'_> {
    fn missing(&mut self, field: &str, hint: &str) {
        self.errors.push(PipelineError::MissingField {
            path: self.path.to_owned(),
            field: field.to_owned(),
            hint: hint.to_owned(),
        });
    }

    /// A required text: not blank, and showing what it says (no control character or
    /// bidirectional override: it reaches the certificate).
    fn text(&mut self, field: &str, value: &str, hint: &str) {
        if value.trim().is_empty() {
            self.missing(field, hint);
        } else if let Some(hidden) = edge_io::hidden_char(value) {
            self.errors.push(PipelineError::HiddenCharacter {
                path: self.path.to_owned(),
                field: field.to_owned(),
                hidden,
            });
        }
    }

    fn number(&mut self, field: &str, value: Option<f64>, hint: &str, reason: InvalidReason) {
        match value {
            None => self.missing(field, hint),
            Some(x) => {
                let ok = match reason {
                    InvalidReason::NotPositive => x.is_finite() && x > 0.0,
                    InvalidReason::NotFinite => x.is_finite(),
                    _ => x.is_finite() && x >= 0.0,
                };
                if !ok {
                    self.errors.push(PipelineError::InvalidField {
                        path: self.path.to_owned(),
                        field: field.to_owned(),
                        value: x,
                        reason,
                    });
                }
            }
        }
    }

    /// A standard uncertainty as large as its quantity: a unit slip, never a statement.
    fn plausible(
        &mut self,
        field: &str,
        u: Option<f64>,
        quantity_field: &str,
        quantity: Option<f64>,
        unit: &'static str,
    ) {
        if let (Some(u), Some(q)) = (u, quantity)
            && u.is_finite()
            && q.is_finite()
            && q > 0.0
            && u >= q
        {
            self.errors.push(PipelineError::ImplausibleUncertainty {
                path: self.path.to_owned(),
                field: field.to_owned(),
                u,
                quantity_field: quantity_field.to_owned(),
                quantity: q,
                unit,
            });
        }
    }

    fn positive(&mut self, field: &str, value: Option<f64>, hint: &str) {
        self.number(field, value, hint, InvalidReason::NotPositive);
    }

    fn non_negative(&mut self, field: &str, value: Option<f64>, hint: &str) {
        self.number(field, value, hint, InvalidReason::Negative);
    }

    fn date(&mut self, field: &str, value: &str) {
        if value.trim().is_empty() {
            self.missing(field, "when its calibration falls due, YYYY-MM-DD");
        } else if Date::parse_iso(value).is_none() {
            self.errors.push(PipelineError::InvalidDate {
                path: self.path.to_owned(),
                field: field.to_owned(),
                value: value.to_owned(),
                hint: Date::iso_hint(value).map_or_else(
                    || "write the date as YYYY-MM-DD (ISO 8601), e.g. 2027-03-31".to_owned(),
                    |d| format!("write it as YYYY-MM-DD (ISO 8601): \"{d}\""),
                ),
            });
        }
    }

    fn unique<'n>(
        &mut self,
        list: &str,
        i: usize,
        name: &'n str,
        seen: &mut HashMap<&'n str, usize>,
    ) {
        if name.trim().is_empty() {
            return;
        }
        if let Some(first) = seen.insert(name, i) {
            self.errors.push(PipelineError::DuplicateName {
                path: self.path.to_owned(),
                field: format!("{list}[{i}].name"),
                first: format!("{list}[{first}].name"),
                name: name.to_owned(),
            });
        }
    }

    fn instrument(&mut self, at: &str, d: &InstrumentConfig) {
        self.text(&format!("{at}.name"), &d.name, "the name studies give it");
        self.text(
            &format!("{at}.description"),
            &d.description,
            "make and model",
        );
        self.text(
            &format!("{at}.identity"),
            &d.identity,
            "serial or asset number",
        );
        self.date(&format!("{at}.calibration_due"), &d.calibration_due);
    }

    fn probe(&mut self, i: usize, p: &ProbeConfig) {
        let at = format!("probes[{i}]");
        self.text(&format!("{at}.name"), &p.name, "the name studies give it");
        self.text(
            &format!("{at}.description"),
            &p.description,
            "make and model",
        );
        self.text(
            &format!("{at}.identity"),
            &p.identity,
            "serial or asset number",
        );
        self.date(&format!("{at}.calibration_due"), &p.calibration_due);
        self.non_negative(
            &format!("{at}.gain_u_relative"),
            p.gain_u_relative,
            "the relative standard uncertainty of the probe's gain, from its calibration certificate",
        );
        self.plausible(
            &format!("{at}.gain_u_relative"),
            p.gain_u_relative,
            "the gain itself",
            Some(1.0),
            "relative",
        );
        self.text(
            &format!("{at}.traceability"),
            &p.traceability,
            "where the gain's uncertainty comes from (its calibration certificate), or why it is negligible",
        );
    }

    fn centrifuge(&mut self, i: usize, c: &CentrifugeConfig, p: &ProfileConfig) {
        let at = format!("centrifuges[{i}]");
        let f = |field: &str| format!("{at}.{field}");
        self.text(
            &f("name"),
            &c.name,
            "the name studies give it (`centrifuge: \"CF-1\"`)",
        );
        self.text(&f("description"), &c.description, "make and model");
        self.text(&f("identity"), &c.identity, "serial or asset number");
        self.date(&f("calibration_due"), &c.calibration_due);
        self.text(
            &f("location"),
            &c.location,
            "where it stands: the certificate's place of calibration",
        );
        self.positive(
            &f("radius_m"),
            c.radius_m,
            "the static radius with the PIGA mounted input axis in: its centre of mass to the spindle axis, m",
        );
        self.non_negative(
            &f("radius_u_m"),
            c.radius_u_m,
            "the radius' standard uncertainty, m",
        );
        if c.radius_ia_out_m.is_some() {
            self.positive(&f("radius_ia_out_m"), c.radius_ia_out_m, "");
        }
        if let Some(lat) = c.latitude_deg
            && !(lat.is_finite() && lat.abs() <= 90.0)
        {
            self.errors.push(PipelineError::InvalidField {
                path: self.path.to_owned(),
                field: f("latitude_deg"),
                value: lat,
                reason: InvalidReason::NotALatitude,
            });
        }
        self.non_negative(
            &f("rate_u_relative"),
            c.rate_u_relative,
            "the relative standard uncertainty of the rate (a scale error common to every rate)",
        );
        let l = &c.lever;
        self.positive(
            &f("lever.pivot_to_probe_mm"),
            l.pivot_to_probe_mm,
            "the height from the spindle's tilt pivot to the probe plane, mm",
        );
        self.non_negative(
            &f("lever.probe_to_piga_mm"),
            l.probe_to_piga_mm,
            "the height from the probe plane to the PIGA's centre-of-mass plane, mm",
        );
        self.non_negative(
            &f("lever.pivot_to_probe_u_mm"),
            l.pivot_to_probe_u_mm,
            "its standard uncertainty, mm",
        );
        self.non_negative(
            &f("lever.probe_to_piga_u_mm"),
            l.probe_to_piga_u_mm,
            "its standard uncertainty, mm",
        );
        self.plausible(
            &f("radius_u_m"),
            c.radius_u_m,
            &f("radius_m"),
            c.radius_m,
            "m",
        );
        self.plausible(
            &f("rate_u_relative"),
            c.rate_u_relative,
            "the rate itself",
            Some(1.0),
            "relative",
        );
        self.plausible(
            &f("lever.pivot_to_probe_u_mm"),
            l.pivot_to_probe_u_mm,
            &f("lever.pivot_to_probe_mm"),
            l.pivot_to_probe_mm,
            "mm",
        );
        if let Some(deg) = l.angle_zero_deg {
            // optional: a study states it when the centrifuge's encoder zero is not fixed
            self.number(
                &f("lever.angle_zero_deg"),
                Some(deg),
                "",
                InvalidReason::NotFinite,
            );
        }
        if l.probe_direction.is_none() {
            self.missing(
                &f("lever.probe_direction"),
                "which way the probe measures: against_o1_x1 when its reading falls as the \
                 spindle moves towards the PIGA, along_o1_x1 when it rises (docs/PROFILE.md)",
            );
        }
        for (name, list, field) in [
            (
                c.probe.as_deref(),
                p.probes.iter().map(|x| x.name.clone()).collect::<Vec<_>>(),
                "probe",
            ),
            (
                c.daq.as_deref(),
                p.daqs.iter().map(|x| x.name.clone()).collect(),
                "daq",
            ),
        ] {
            if let Some(name) = name
                && !list.iter().any(|n| n == name)
            {
                self.errors.push(PipelineError::UnknownKey {
                    path: self.path.to_owned(),
                    field: f(field),
                    key: name.to_owned(),
                    known: list,
                });
            }
        }
        let t = &c.traceability;
        for (key, value, what) in [
            ("radius", &t.radius, "the radius"),
            ("rate_scale", &t.rate_scale, "the rate scale"),
            (
                "pivot_to_probe",
                &t.pivot_to_probe,
                "the pivot-to-probe height",
            ),
            (
                "probe_to_piga",
                &t.probe_to_piga,
                "the probe-to-PIGA height",
            ),
        ] {
            self.text(
                &f(&format!("traceability.{key}")),
                value,
                &format!(
                    "where {what}'s value and uncertainty come from (a certificate), or why its \
                     uncertainty is negligible"
                ),
            );
        }
    }
}
