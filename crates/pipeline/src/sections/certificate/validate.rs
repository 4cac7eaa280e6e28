//! The certificate section's validation: every required field, all missing ones at once.

use crate::config::{
    CertificateConfig, CertifyName, DecisionRuleName, LimitUnitName, TypeBInputName,
};
use crate::date::Date;
use crate::error::{PipelineError, Result, UnsupportedReason};
use crate::inputs::Check;
use crate::resolved::Resolved;
use crate::results::{
    Authorisation, CertifyPolicy, Condition, Dates, DecisionRule, Equipment, Item, Laboratory,
    Party, PreviousCertificate, Warning,
};

/// A specification limit, validated.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Limit {
    /// 0 for k0 … 3 for k3.
    pub(crate) index: usize,
    /// Relative to k1 (µg, µg/g², µg/g³).
    pub(crate) relative: bool,
    pub(crate) lower: Option<f64>,
    pub(crate) upper: Option<f64>,
    /// Where it comes from (absent or blank: not stated).
    pub(crate) source: Option<String>,
}

/// The validated certificate section.
#[derive(Debug, Clone)]
pub(crate) struct Certificate {
    pub(crate) id: String,
    pub(crate) laboratory: Laboratory,
    pub(crate) location: String,
    pub(crate) customer: Party,
    pub(crate) item: Item,
    pub(crate) equipment: Vec<Equipment>,
    pub(crate) dates: Dates,
    pub(crate) operator: String,
    pub(crate) conditions: Vec<Condition>,
    pub(crate) procedure: String,
    pub(crate) deviations: Option<String>,
    /// Each input's index in `calibration::input::NAMES` and its statement.
    pub(crate) traceability: Vec<(usize, String)>,
    pub(crate) limits: Vec<Limit>,
    pub(crate) rule: Option<DecisionRule>,
    pub(crate) limits_source: Option<String>,
    pub(crate) authorisation: Authorisation,
    pub(crate) previous_certificate: Option<PreviousCertificate>,
    /// Which method's coefficients to certify.
    pub(crate) certify: CertifyPolicy,
    /// The laboratory's reason for certifying a value the study's check refutes.
    pub(crate) despite_check: Option<String>,
}

impl Certificate {
    /// Equipment past its calibration due date on the last day of the measurement
    /// (`calibration_overdue`), or due dates that cannot be compared with it
    /// (`calibration_due_unchecked`: a measurement date or a due date not written
    /// `YYYY-MM-DD`).
    pub(crate) fn warnings(&self) -> Vec<Warning> {
        let Some(measured) = Date::last_of_span(&self.dates.measured) else {
            return vec![Warning::calibration_due_unchecked(&format!(
                "the measurement date `{}` (certificate.dates.measured) is not written \
                 YYYY-MM-DD or YYYY-MM-DD to YYYY-MM-DD",
                self.dates.measured
            ))];
        };
        let mut warnings = Vec::new();
        let mut unreadable = Vec::new();
        for (i, e) in self.equipment.iter().enumerate() {
            match Date::parse_iso(&e.calibration_due) {
                Some(due) if due < measured => warnings.push(Warning::calibration_overdue(
                    &e.role,
                    &e.identity,
                    &due.to_string(),
                    &measured.to_string(),
                    &format!("certificate.equipment[{i}]"),
                )),
                Some(_) => {}
                None => unreadable.push(format!(
                    "{} {} (`{}`)",
                    e.role, e.identity, e.calibration_due
                )),
            }
        }
        if !unreadable.is_empty() {
            warnings.push(Warning::calibration_due_unchecked(&format!(
                "the calibration due date of {} is not written YYYY-MM-DD",
                unreadable.join(", ")
            )));
        }
        warnings
    }
}

/// The input of the calibration model a traceability statement is about.
pub(crate) const fn input_index(name: TypeBInputName) -> usize {
    use ::calibration::input;
    match name {
        TypeBInputName::Radius => input::RADIUS,
        TypeBInputName::G => input::G,
        TypeBInputName::RateScale => input::RATE_SCALE,
        TypeBInputName::PivotToProbe => input::PIVOT_TO_PROBE,
        TypeBInputName::ProbeToPiga => input::PROBE_TO_PIGA,
        TypeBInputName::ProbeGain => input::PROBE_GAIN,
        TypeBInputName::K1 => input::K1_GIVEN,
    }
}

/// Validates the certificate section `c` with the study's resolved facts (`resolved`: which
/// sections it has, its uncertain Type B inputs): it needs a calibration section; every
/// required text present and not blank, at least one instrument and one condition, a
/// traceability statement for each Type B input with a non-zero uncertainty, a decision
/// rule with limits and at least one end per limit. Every problem at once.
pub(crate) fn validate(
    check: &Check<'_>,
    c: &CertificateConfig,
    resolved: &Resolved<'_>,
) -> Result<Certificate> {
    if !resolved.present.calibration {
        return Err(PipelineError::Unsupported {
            path: check.path.to_owned(),
            field: "certificate".to_owned(),
            reason: UnsupportedReason::CertificateNeedsCalibration,
        });
    }
    let mut n = Need {
        path: check.path,
        errors: section_problems(check, c, resolved),
    };
    let id = n.need("id", &c.id, "the certificate's unique identification");
    let (laboratory, location, customer, item) = n.parties(c);
    let equipment = n.equipment(c);
    let dates = Dates {
        received: n.need("dates.received", &c.dates.received, "receipt of the item"),
        measured: n.need("dates.measured", &c.dates.measured, "the measurement"),
        issued: n.need("dates.issued", &c.dates.issued, "issue of the certificate"),
    };
    let operator = n.need("operator", &c.operator, "who performed the calibration");
    let conditions = n.conditions(c);
    let procedure = n.need(
        "procedure",
        &c.procedure,
        "the procedure's reference and title",
    );
    let traceability = n.traceability(c, resolved);
    let (limits, rule) = n.limits(c);
    let authorisation = Authorisation {
        name: n.need(
            "authorisation.name",
            &c.authorisation.name,
            "who authorises the certificate",
        ),
        role: n.need(
            "authorisation.role",
            &c.authorisation.role,
            "the role of who authorises it",
        ),
    };
    let previous_certificate = n.previous_certificate(c);
    n.formats(c);
    PipelineError::from_list(n.errors)?;
    for (i, l) in limits.iter().enumerate() {
        for (end, v) in [("lower", l.lower), ("upper", l.upper)] {
            if let Some(v) = v {
                check.finite(format!("certificate.limits[{i}].{end}"), v)?;
            }
        }
    }
    Ok(Certificate {
        id,
        laboratory,
        location,
        customer,
        item,
        equipment,
        dates,
        operator,
        conditions,
        procedure,
        deviations: c.deviations.clone(),
        traceability,
        limits,
        rule,
        limits_source: c.limits_source.clone().filter(|s| !s.trim().is_empty()),
        authorisation,
        previous_certificate,
        certify: match c.certify {
            CertifyName::Auto => CertifyPolicy::Auto,
            CertifyName::Probe => CertifyPolicy::Probe,
            CertifyName::TwoOrientation => CertifyPolicy::TwoOrientation,
        },
        despite_check: c.certify_despite_check.clone(),
    })
}

/// The problems of the section as a whole, before its fields: the `uncertainty` section it
/// needs, a hidden character in any of its texts, the `two_orientation` section a
/// two-orientation certificate needs, a blank reason to certify despite the check.
fn section_problems(
    check: &Check<'_>,
    c: &CertificateConfig,
    resolved: &Resolved<'_>,
) -> Vec<PipelineError> {
    let mut errors = Vec::new();
    if !resolved.present.uncertainty {
        errors.push(PipelineError::MissingField {
            path: check.path.to_owned(),
            field: "uncertainty".to_owned(),
            hint: "a certificate states every Type B input of the budget: give the \
                   `uncertainty` section"
                .to_owned(),
        });
    }
    // Every text of the section shows what it says: no control character or bidirectional
    // override (a serial number that reorders itself on the page, an escape sequence on a
    // terminal).
    for (field, text) in texts(c) {
        if let Some(hidden) = edge_io::hidden_char(text) {
            errors.push(PipelineError::HiddenCharacter {
                path: check.path.to_owned(),
                field: format!("certificate.{field}"),
                hidden,
            });
        }
    }
    if c.certify == CertifyName::TwoOrientation && !resolved.present.two_orientation {
        errors.push(PipelineError::MissingField {
            path: check.path.to_owned(),
            field: "two_orientation".to_owned(),
            hint: "`certificate.certify: two_orientation` certifies the two-orientation \
                   method's coefficients: the study needs its `two_orientation` section (IA in \
                   and IA out)"
                .to_owned(),
        });
    }
    if c.certify_despite_check
        .as_ref()
        .is_some_and(|r| r.trim().is_empty())
    {
        errors.push(PipelineError::MissingField {
            path: check.path.to_owned(),
            field: "certificate.certify_despite_check".to_owned(),
            hint: "the laboratory's reason for certifying a value the study's own check \
                   refutes, in words the certificate prints"
                .to_owned(),
        });
    }
    errors
}

/// The section's fields as they are checked: the study file and the problems found so far,
/// in the order of the fields.
struct Need<'a> {
    path: &'a std::path::Path,
    errors: Vec<PipelineError>,
}

impl Need<'_> {
    /// A required text: a problem when it is blank; the text.
    fn need(&mut self, field: &str, value: &str, hint: &str) -> String {
        if value.trim().is_empty() {
            self.errors.push(PipelineError::MissingField {
                path: self.path.to_owned(),
                field: format!("certificate.{field}"),
                hint: hint.to_owned(),
            });
        }
        value.to_owned()
    }

    /// [`Self::need`] for the field `name` of item `i` of the list `list`
    /// (`equipment[0].role`).
    fn need_in(&mut self, (list, i): (&str, usize), name: &str, value: &str, hint: &str) -> String {
        self.need(&format!("{list}[{i}].{name}"), value, hint)
    }

    /// Each of `items` as `each` makes it from its index and itself (checking its fields);
    /// none at all is the missing field `field` (`hint`).
    fn need_each<T, U>(
        &mut self,
        items: &[T],
        field: &str,
        hint: &str,
        mut each: impl FnMut(&mut Self, usize, &T) -> U,
    ) -> Vec<U> {
        let made: Vec<U> = items
            .iter()
            .enumerate()
            .map(|(i, item)| each(self, i, item))
            .collect();
        if made.is_empty() {
            self.need(field, "", hint);
        }
        made
    }

    /// The issuing laboratory, where it calibrated, the customer and the item.
    fn parties(&mut self, c: &CertificateConfig) -> (Laboratory, String, Party, Item) {
        let laboratory = Laboratory {
            name: self.need(
                "laboratory.name",
                &c.laboratory.name,
                "the issuing laboratory",
            ),
            address: self.need(
                "laboratory.address",
                &c.laboratory.address,
                "the laboratory's address",
            ),
            accreditation: c.laboratory.accreditation.clone(),
            country: c.laboratory.country.clone(),
        };
        let location = self.need(
            "location",
            &c.location,
            "where the calibration was performed",
        );
        let customer = Party {
            name: self.need("customer.name", &c.customer.name, "the customer"),
            address: self.need(
                "customer.address",
                &c.customer.address,
                "the customer's address",
            ),
        };
        let item = Item {
            description: self.need("item.description", &c.item.description, "what the item is"),
            manufacturer: self.need(
                "item.manufacturer",
                &c.item.manufacturer,
                "the item's manufacturer",
            ),
            model: self.need("item.model", &c.item.model, "the item's model"),
            serial: self.need("item.serial", &c.item.serial, "the item's serial number"),
            condition: self.need(
                "item.condition",
                &c.item.condition,
                "the item's condition on receipt",
            ),
        };
        (laboratory, location, customer, item)
    }

    /// The instruments used, at least one.
    fn equipment(&mut self, c: &CertificateConfig) -> Vec<Equipment> {
        let none = "the centrifuge, the probe and the data acquisition, each with its identity and calibration due date";
        self.need_each(&c.equipment, "equipment", none, |v, i, e| Equipment {
            role: v.need_in(("equipment", i), "role", &e.role, "the instrument's role"),
            description: v.need_in(
                ("equipment", i),
                "description",
                &e.description,
                "make and model",
            ),
            identity: v.need_in(
                ("equipment", i),
                "identity",
                &e.identity,
                "serial or asset number",
            ),
            calibration_due: v.need_in(
                ("equipment", i),
                "calibration_due",
                &e.calibration_due,
                "when its calibration falls due",
            ),
        })
    }

    /// The environmental conditions, at least one.
    fn conditions(&mut self, c: &CertificateConfig) -> Vec<Condition> {
        self.need_each(
            &c.conditions,
            "conditions",
            "the environmental conditions during the measurement (temperature, humidity)",
            |v, i, cnd| Condition {
                quantity: v.need_in(("conditions", i), "quantity", &cnd.quantity, "the quantity"),
                value: v.need_in(
                    ("conditions", i),
                    "value",
                    &cnd.value,
                    "its value with unit and range",
                ),
            },
        )
    }

    /// The traceability statements, and one for each Type B input with a non-zero
    /// uncertainty.
    fn traceability(
        &mut self,
        c: &CertificateConfig,
        resolved: &Resolved<'_>,
    ) -> Vec<(usize, String)> {
        let mut traceability = Vec::new();
        for (i, t) in c.traceability.iter().enumerate() {
            self.need(
                &format!("traceability[{i}].statement"),
                &t.statement,
                "where the input's value and uncertainty come from",
            );
            traceability.push((input_index(t.input), t.statement.clone()));
        }
        for (name, field) in resolved.uncertain_inputs() {
            if !c.traceability.iter().any(|t| t.input == *name) {
                let key = name.key();
                self.need(
                    &format!("traceability (input: {key})"),
                    "",
                    &format!("{field} is not zero: state where that uncertainty comes from"),
                );
            }
        }
        traceability
    }

    /// The specification limits, each with at least one end, and their decision rule.
    fn limits(&mut self, c: &CertificateConfig) -> (Vec<Limit>, Option<DecisionRule>) {
        let mut limits = Vec::new();
        for (i, l) in c.limits.iter().enumerate() {
            if l.lower.is_none() && l.upper.is_none() {
                self.need(
                    &format!("limits[{i}].lower (or upper)"),
                    "",
                    "a limit needs at least one end",
                );
            }
            limits.push(Limit {
                index: l.coefficient as usize,
                relative: matches!(l.unit, LimitUnitName::Micro),
                lower: l.lower,
                upper: l.upper,
                source: l.source.clone().filter(|s| !s.trim().is_empty()),
            });
        }
        let rule = c.decision_rule.map(|r| match r {
            DecisionRuleName::SimpleAcceptance => DecisionRule::SimpleAcceptance,
            DecisionRuleName::GuardBand => DecisionRule::GuardBand,
        });
        if !limits.is_empty() && rule.is_none() {
            self.need(
                "decision_rule",
                "",
                "limits need a decision rule: `simple_acceptance` or `guard_band` (ILAC-G8:09/2019)",
            );
        }
        (limits, rule)
    }

    /// The certificate this one follows, when it names one.
    fn previous_certificate(&mut self, c: &CertificateConfig) -> Option<PreviousCertificate> {
        c.previous_certificate
            .as_ref()
            .map(|p| PreviousCertificate {
                id: self.need(
                    "previous_certificate.id",
                    &p.id,
                    "the identification of the certificate this one follows",
                ),
                sha256: p.sha256.as_ref().map(|h| h.to_ascii_lowercase()),
            })
    }

    /// The fields with a format: the previous certificate's SHA-256 and the laboratory's
    /// country code.
    fn formats(&mut self, c: &CertificateConfig) {
        if c.previous_certificate
            .as_ref()
            .and_then(|p| p.sha256.as_ref())
            .is_some_and(|h| !(h.len() == 64 && h.bytes().all(|b| b.is_ascii_hexdigit())))
        {
            self.errors.push(PipelineError::Unsupported {
                path: self.path.to_owned(),
                field: "certificate.previous_certificate.sha256".to_owned(),
                reason: UnsupportedReason::NotSha256,
            });
        }
        if let Some(country) = &c.laboratory.country
            && !(country.len() == 2 && country.bytes().all(|b| b.is_ascii_uppercase()))
        {
            self.errors.push(PipelineError::Unsupported {
                path: self.path.to_owned(),
                field: "certificate.laboratory.country".to_owned(),
                reason: UnsupportedReason::NotCountryCode,
            });
        }
    }
}

/// Every text of the certificate section with its field (under `certificate.`).
fn texts(c: &CertificateConfig) -> Vec<(String, &str)> {
    let mut list: Vec<(String, &str)> = vec![
        ("id".into(), &c.id),
        ("laboratory.name".into(), &c.laboratory.name),
        ("laboratory.address".into(), &c.laboratory.address),
        ("location".into(), &c.location),
        ("customer.name".into(), &c.customer.name),
        ("customer.address".into(), &c.customer.address),
        ("item.description".into(), &c.item.description),
        ("item.manufacturer".into(), &c.item.manufacturer),
        ("item.model".into(), &c.item.model),
        ("item.serial".into(), &c.item.serial),
        ("item.condition".into(), &c.item.condition),
        ("dates.received".into(), &c.dates.received),
        ("dates.measured".into(), &c.dates.measured),
        ("dates.issued".into(), &c.dates.issued),
        ("operator".into(), &c.operator),
        ("procedure".into(), &c.procedure),
        ("authorisation.name".into(), &c.authorisation.name),
        ("authorisation.role".into(), &c.authorisation.role),
    ];
    if let Some(a) = &c.laboratory.accreditation {
        list.push(("laboratory.accreditation".into(), a));
    }
    if let Some(d) = &c.deviations {
        list.push(("deviations".into(), d));
    }
    if let Some(r) = &c.certify_despite_check {
        list.push(("certify_despite_check".into(), r));
    }
    if let Some(country) = &c.laboratory.country {
        list.push(("laboratory.country".into(), country));
    }
    if let Some(p) = &c.previous_certificate {
        list.push(("previous_certificate.id".into(), &p.id));
        if let Some(sha) = &p.sha256 {
            list.push(("previous_certificate.sha256".into(), sha));
        }
    }
    for (i, e) in c.equipment.iter().enumerate() {
        list.push((format!("equipment[{i}].role"), &e.role));
        list.push((format!("equipment[{i}].description"), &e.description));
        list.push((format!("equipment[{i}].identity"), &e.identity));
        list.push((
            format!("equipment[{i}].calibration_due"),
            &e.calibration_due,
        ));
    }
    for (i, cnd) in c.conditions.iter().enumerate() {
        list.push((format!("conditions[{i}].quantity"), &cnd.quantity));
        list.push((format!("conditions[{i}].value"), &cnd.value));
    }
    for (i, t) in c.traceability.iter().enumerate() {
        list.push((format!("traceability[{i}].statement"), &t.statement));
    }
    list
}
