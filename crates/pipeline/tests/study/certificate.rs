//! The certificate section: every missing required field named at once, a traceability
//! statement for each non-zero Type B input, and no certificate without a calibration.

use pipeline::{Inputs, PipelineError, StudyConfig};

use crate::{chain, root};

/// The campaign study with its certificate section replaced by `certificate` (validation
/// fails before any data file is read).
fn campaign_with_certificate(certificate: &str) -> Result<Inputs, PipelineError> {
    let path = root().join("fixtures/studies/campaign.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    let start = text
        .find("    certificate: (")
        .expect("a certificate section");
    let text = format!("{}{certificate}\n)\n", &text[..start]);
    let config = StudyConfig::from_ron(&text, &path)?;
    Inputs::new(config, &path, &pipeline::Files)
}

#[test]
fn every_missing_certificate_field_is_named_at_once() {
    let e = campaign_with_certificate(
        "    certificate: (id: \"CC-1\", item: (model: \"PIGA-16\", serial: \" \"), \
         traceability: [(input: radius, statement: \"laser tracker\")], \
         limits: [(coefficient: k2, unit: micro, upper: 20.0)]),",
    )
    .unwrap_err();
    let PipelineError::Several { errors } = &e else {
        panic!("expected every missing field at once, got {e}");
    };
    let fields: Vec<String> = errors
        .iter()
        .map(|e| match e {
            PipelineError::MissingField { field, .. } => field.clone(),
            other => panic!("not a missing field: {other}"),
        })
        .collect();
    for field in [
        "certificate.laboratory.name",
        "certificate.laboratory.address",
        "certificate.location",
        "certificate.customer.name",
        "certificate.item.description",
        "certificate.item.manufacturer",
        // blank is missing
        "certificate.item.serial",
        "certificate.item.condition",
        "certificate.equipment",
        "certificate.dates.received",
        "certificate.dates.measured",
        "certificate.dates.issued",
        "certificate.operator",
        "certificate.conditions",
        "certificate.procedure",
        // the campaign's non-zero Type B inputs other than R need their traceability
        "certificate.traceability (input: g)",
        "certificate.traceability (input: rate_scale)",
        "certificate.traceability (input: pivot_to_probe)",
        "certificate.traceability (input: probe_to_piga)",
        "certificate.traceability (input: probe_gain)",
        "certificate.decision_rule",
        "certificate.authorisation.name",
        "certificate.authorisation.role",
    ] {
        assert!(
            fields.iter().any(|f| f == field),
            "{field} not in {fields:?}"
        );
    }
    // given ones are not named
    for given in [
        "certificate.id",
        "certificate.item.model",
        "certificate.traceability (input: radius)",
    ] {
        assert!(
            !fields.iter().any(|f| f == given),
            "{given} named: {fields:?}"
        );
    }
    let text = chain(&e);
    assert!(
        text.contains("`uncertainty.probe_gain_u_relative` is not zero"),
        "{text}"
    );
    assert!(!text.contains("CertificateConfig"), "{text}");
}

#[test]
fn a_certificate_needs_a_calibration() {
    let text = crate::paper_text();
    let end = text.rfind(')').unwrap();
    let text = format!("{}    certificate: (id: \"CC-1\"),\n)\n", &text[..end]);
    let path = root().join("fixtures/studies/paper-2025.ron");
    let config = StudyConfig::from_ron(&text, &path).unwrap();
    let e = Inputs::new(config, &path, &pipeline::Files).unwrap_err();
    let text = chain(&e);
    assert!(
        text.contains("field `certificate`") && text.contains("needs a `calibration` section"),
        "{text}"
    );
}

#[test]
fn an_unknown_certificate_key_names_its_place() {
    let e =
        campaign_with_certificate("    certificate: (id: \"CC-1\", serial: \"x\"),").unwrap_err();
    let text = chain(&e);
    assert!(
        text.contains("unknown field `serial` in `certificate`"),
        "{text}"
    );
}

/// The campaign study with `fields` added to its certificate section and `country` to its
/// laboratory.
fn campaign_with(fields: &str, country: &str) -> Result<Inputs, PipelineError> {
    let path = root().join("fixtures/studies/campaign.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    let text = text
        .replacen(
            "        authorisation: (",
            &format!("        {fields}\n        authorisation: ("),
            1,
        )
        .replacen(
            "            accreditation: ",
            &format!("            country: {country},\n            accreditation: "),
            1,
        );
    let config = StudyConfig::from_ron(&text, &path)?;
    Inputs::new(config, &path, &pipeline::Files)
}

#[test]
fn the_previous_certificate_and_the_country_are_checked_and_recorded() {
    let e = campaign_with(
        "previous_certificate: (id: \" \", sha256: \"0123abcd\"),",
        "\"de\"",
    )
    .unwrap_err();
    let PipelineError::Several { errors } = &e else {
        panic!("expected every problem at once, got {e}");
    };
    let text = chain(&e);
    for field in [
        "certificate.previous_certificate.id",
        "certificate.previous_certificate.sha256",
        "certificate.laboratory.country",
    ] {
        assert!(text.contains(&format!("`{field}`")), "{field}: {text}");
    }
    assert_eq!(errors.len(), 3, "{text}");
    assert!(text.contains("64 hexadecimal digits"), "{text}");
    assert!(text.contains("two capital letters"), "{text}");

    let sha = "AB".repeat(32);
    let inputs = campaign_with(
        &format!("previous_certificate: (id: \"CC-2025-0031\", sha256: \"{sha}\"),"),
        "\"DE\"",
    )
    .unwrap();
    let results = pipeline::run(&inputs).unwrap();
    let cert = results.certificate.unwrap();
    let previous = cert.previous_certificate.unwrap();
    assert_eq!(previous.id, "CC-2025-0031");
    assert_eq!(
        previous.sha256.unwrap(),
        "ab".repeat(32),
        "recorded in lower case"
    );
    assert_eq!(cert.laboratory.country.as_deref(), Some("DE"));
}
