//! The lab profile (`lab.ron`, `docs/PROFILE.md`) on values: parsed from text the edge read
//! ([`Profile::from_ron`]), validated (every problem at once, each naming the profile's file
//! and field) and resolved into a study's configuration: what the study leaves out is taken
//! from the profile — the centrifuge's radius and probe geometry, g, the Type B inputs with
//! their traceability, the certificate's laboratory, place, equipment, procedure, operator,
//! decision rule and signatory — and what it states overrides the profile. The results say
//! which value came from where ([`ProfileResults`]). Core: used by the study, importing no
//! section.

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use recording::FileDigest;

use crate::config::{
    CentrifugeConfig, EquipmentConfig, InstrumentConfig, OrientationName, ProbeConfig,
    ProfileConfig, StudyConfig, TraceabilityConfig, TypeBInputName, UncertaintyConfig,
};
use crate::date::Date;
use crate::error::{InvalidReason, PipelineError, Result, UnsupportedReason};
use crate::results::{ProfileResults, ValueOrigin, ValueSource};

/// A lab profile as read, unvalidated, with the file it came from (named in every error) and
/// its size and SHA-256 when the edge read it from disk.
#[derive(Debug, Clone)]
pub struct Profile {
    config: ProfileConfig,
    source: PathBuf,
    digest: Option<FileDigest>,
}

impl Profile {
    /// A profile from its configuration; `source` names it in errors and results.
    #[must_use]
    pub fn new(config: ProfileConfig, source: &Path) -> Self {
        Self {
            config,
            source: source.to_owned(),
            digest: None,
        }
    }

    /// Parses RON text (the study's dialect, a byte-order mark dropped) into a profile,
    /// unvalidated; errors name `path`, the line and column, and the profile's keys.
    ///
    /// # Errors
    /// [`PipelineError::Parse`] for malformed RON, an unknown or a misspelt field.
    pub fn from_ron(text: &str, path: &Path) -> Result<Self> {
        let config = edge_io::from_ron(text, path).map_err(crate::config::parse_error)?;
        Ok(Self::new(config, path))
    }

    /// The profile with the size and SHA-256 of its bytes as the edge read them.
    #[must_use]
    pub fn with_digest(mut self, digest: FileDigest) -> Self {
        self.digest = Some(digest);
        self
    }

    /// The file it came from.
    pub fn source(&self) -> &Path {
        &self.source
    }

    /// Its size and SHA-256 as read (`None` for a profile built from values).
    pub const fn digest(&self) -> Option<&FileDigest> {
        self.digest.as_ref()
    }

    /// What the file says.
    pub const fn config(&self) -> &ProfileConfig {
        &self.config
    }

    /// Validates the profile and fills `config`'s missing values from it (what the study
    /// states overrides the profile); `study` names the study file in errors. What
    /// [`crate::Inputs::with_profile`] does before it validates the study, for a caller that
    /// shows the study as it will run (`check`).
    ///
    /// # Errors
    /// Those of [`Profile::validate`]; a centrifuge, probe or signatory the profile does not
    /// have, or a study without `centrifuge`.
    pub fn apply(&self, config: &mut StudyConfig, study: &Path) -> Result<ProfileResults> {
        self.validate()?;
        let (used, errors) = resolve(config, self, study)?;
        PipelineError::from_list(errors)?;
        Ok(used)
    }

    /// [`Profile::apply`] for showing the study as far as it can be resolved: what the
    /// profile gives is filled in and listed even when some reference of the study (the
    /// signatory it names) is refused; `None` when the profile or the centrifuge is.
    pub fn apply_partly(&self, config: &mut StudyConfig, study: &Path) -> Option<ProfileResults> {
        self.validate().ok()?;
        resolve(config, self, study).ok().map(|(used, _)| used)
    }

    /// Validates the profile: every problem at once, each naming the profile's file and
    /// field.
    ///
    /// # Errors
    /// [`PipelineError::MissingField`], [`PipelineError::InvalidField`],
    /// [`PipelineError::InvalidDate`], [`PipelineError::DuplicateName`],
    /// [`PipelineError::UnknownKey`] (a centrifuge naming a probe the profile does not
    /// have); [`PipelineError::Several`] for more than one.
    pub fn validate(&self) -> Result<()> {
        let mut v = Validation {
            path: &self.source,
            errors: Vec::new(),
        };
        let p = &self.config;
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
                path: self.source.clone(),
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

/// Fills the study's missing values from a validated profile and records where each value
/// came from; `study` names the study file in errors.
fn resolve(
    config: &mut StudyConfig,
    profile: &Profile,
    study: &Path,
) -> Result<(ProfileResults, Vec<PipelineError>)> {
    let p = &profile.config;
    let file = profile.source.display().to_string();
    let mut errors = Vec::new();
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
    let mut values = Values {
        list: Vec::new(),
        file: &file,
    };
    let at = |field: &str| format!("centrifuges[{ci}].{field}");
    values.fill(
        &mut config.radius_m,
        centrifuge.radius_m,
        "radius_m",
        &at("radius_m"),
    );
    values.fill(
        &mut config.g_m_s2,
        p.gravity.g_m_s2,
        "g_m_s2",
        "gravity.g_m_s2",
    );
    let lever = &centrifuge.lever;
    values.fill(
        &mut config.lever.pivot_to_probe_mm,
        lever.pivot_to_probe_mm,
        "lever.pivot_to_probe_mm",
        &at("lever.pivot_to_probe_mm"),
    );
    values.fill(
        &mut config.lever.probe_to_piga_mm,
        lever.probe_to_piga_mm,
        "lever.probe_to_piga_mm",
        &at("lever.probe_to_piga_mm"),
    );
    values.fill(
        &mut config.lever.probe_direction,
        lever.probe_direction,
        "lever.probe_direction",
        &at("lever.probe_direction"),
    );
    values.fill(
        &mut config.lever.angle_zero_deg,
        lever.angle_zero_deg,
        "lever.angle_zero_deg",
        &at("lever.angle_zero_deg"),
    );
    // The Type B inputs: each with its standing statement, the traceability of a non-zero
    // uncertainty and the reason for a zero.
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
    let mut statements: Vec<(TypeBInputName, String, &'static str)> = Vec::new();
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
        &mut values,
        &mut u.radius_u_m,
        centrifuge.radius_u_m,
        "radius_u_m",
        at("radius_u_m"),
        TypeBInputName::Radius,
        &t.radius,
    );
    type_b(
        &mut values,
        &mut u.g_u_m_s2,
        p.gravity.u_m_s2,
        "g_u_m_s2",
        "gravity.u_m_s2".to_owned(),
        TypeBInputName::G,
        &p.gravity.source,
    );
    type_b(
        &mut values,
        &mut u.rate_u_relative,
        centrifuge.rate_u_relative,
        "rate_u_relative",
        at("rate_u_relative"),
        TypeBInputName::RateScale,
        &t.rate_scale,
    );
    type_b(
        &mut values,
        &mut u.pivot_to_probe_u_mm,
        lever.pivot_to_probe_u_mm,
        "pivot_to_probe_u_mm",
        at("lever.pivot_to_probe_u_mm"),
        TypeBInputName::PivotToProbe,
        &t.pivot_to_probe,
    );
    type_b(
        &mut values,
        &mut u.probe_to_piga_u_mm,
        lever.probe_to_piga_u_mm,
        "probe_to_piga_u_mm",
        at("lever.probe_to_piga_u_mm"),
        TypeBInputName::ProbeToPiga,
        &t.probe_to_piga,
    );
    if let Some((pi, probe)) = probe {
        if stated_gain.is_none() {
            type_b(
                &mut values,
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
    // Two orientations: the IA-in radius is the centrifuge's, the IA-out one its
    // `radius_ia_out_m` when the profile gives it.
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
    if let Some(cert) = config.certificate.as_mut() {
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
            &mut values,
            &mut cert.location,
            &centrifuge.location,
            "certificate.location",
            &at("location"),
        );
        text(
            &mut values,
            &mut cert.procedure,
            &p.procedure,
            "certificate.procedure",
            "procedure",
        );
        if let [only] = p.operators.as_slice() {
            text(
                &mut values,
                &mut cert.operator,
                only,
                "certificate.operator",
                "operators",
            );
        }
        if cert.equipment.is_empty() {
            cert.equipment.push(equipment(
                "precision centrifuge",
                &centrifuge.description,
                &centrifuge.identity,
                &centrifuge.calibration_due,
            ));
            if let Some((_, probe)) = probe {
                cert.equipment.push(equipment(
                    "displacement probe",
                    &probe.description,
                    &probe.identity,
                    &probe.calibration_due,
                ));
            }
            if let Some((_, d)) = daq {
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
            if let Some((pi, _)) = probe {
                from.push(format!("probes[{pi}]"));
            }
            if let Some((di, _)) = daq {
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
        for (input, statement, _) in &statements {
            if !cert.traceability.iter().any(|t| t.input == *input) {
                cert.traceability.push(TraceabilityConfig {
                    input: *input,
                    statement: statement.clone(),
                });
                let from = match input {
                    TypeBInputName::G => "gravity.source".to_owned(),
                    TypeBInputName::ProbeGain => probe
                        .map_or_else(String::new, |(pi, _)| format!("probes[{pi}].traceability")),
                    other => at(&format!("traceability.{}", input_key(*other))),
                };
                values.push(
                    &format!("certificate.traceability ({})", input_key(*input)),
                    ValueSource::Profile,
                    &from,
                );
            }
        }
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
    let values = values.list;
    Ok((
        ProfileResults {
            file,
            centrifuge: centrifuge.name.clone(),
            probe: probe.map(|(_, x)| x.name.clone()),
            daq: daq.map(|(_, d)| d.name.clone()),
            values,
        },
        errors,
    ))
}

/// A Type B input as the certificate's traceability names it (`input: radius`).
const fn input_key(input: TypeBInputName) -> &'static str {
    match input {
        TypeBInputName::Radius => "radius",
        TypeBInputName::G => "g",
        TypeBInputName::RateScale => "rate_scale",
        TypeBInputName::PivotToProbe => "pivot_to_probe",
        TypeBInputName::ProbeToPiga => "probe_to_piga",
        TypeBInputName::ProbeGain => "probe_gain",
        TypeBInputName::K1 => "k1",
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
