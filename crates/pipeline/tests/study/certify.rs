//! What a certificate certifies (issue 27): with both mountings the two-orientation method,
//! the probe method as its check; with one mounting the probe method; a value the study's own
//! check refutes only with the laboratory's stated reason; each mounting's range of validity.
//! And what refuses a certificate: hidden characters in its text, an implausible Type B
//! uncertainty.

use pipeline::{
    CertifiedMethod, CertifyPolicy, HeadlineMethod, Inputs, PipelineError, StudyConfig,
    StudyResults,
};

use crate::{chain, root};

/// The fixture study `name` with `edit` applied to its text, run.
fn run_edited(name: &str, edit: impl Fn(String) -> String) -> Result<StudyResults, PipelineError> {
    let path = root().join(format!("fixtures/studies/{name}.ron"));
    let text = edit(std::fs::read_to_string(&path).unwrap());
    let config = StudyConfig::from_ron(&text, &path)?;
    let inputs = Inputs::new(config, &path, &pipeline::Files)?;
    pipeline::run(&inputs)
}

/// `field: …` added to the certificate section.
fn with_certificate_field(text: String, field: &str) -> String {
    text.replacen(
        "    certificate: (\n",
        &format!("    certificate: (\n        {field}\n"),
        1,
    )
}

#[test]
fn both_mountings_certify_the_two_orientation_method_and_check_with_the_probe() {
    let r = run_edited("two_orientation", |t| t).unwrap();
    let cert = r.certificate.as_ref().unwrap();
    let c = &cert.certified;
    let t = r.two_orientation.as_ref().unwrap();
    assert_eq!(c.policy, CertifyPolicy::Auto);
    assert_eq!(c.method, CertifiedMethod::TwoOrientation);
    assert!(!c.refuted_by_check);
    // k0 and k1 of each mounting, then k2 and k3
    let names: Vec<String> = c
        .coefficients
        .iter()
        .map(|k| format!("{} {}", k.name, k.mounting.as_deref().unwrap_or("-")))
        .collect();
    assert_eq!(
        names,
        [
            "k0 ia_in",
            "k1 ia_in",
            "k0 ia_out",
            "k1 ia_out",
            "k2 -",
            "k3 -"
        ]
    );
    let k2 = &c.coefficients[4];
    assert_eq!(k2.value, t.k2.value);
    assert_eq!(
        (k2.low95, k2.high95),
        (t.headline.k2.low95, t.headline.k2.high95)
    );
    // the fixture's arm stretch: the check disagrees, and the reason says the probe's is not
    // certified
    let check = c.check.unwrap();
    assert_eq!(check.method, CertifiedMethod::Probe);
    assert!(!check.agrees && check.z.abs() > 3.0, "{check:?}");
    assert_eq!(
        check.k2,
        r.calibration.as_ref().unwrap().coefficients.k2.value
    );
    assert!(
        c.reason.contains("disagree") && c.reason.contains("not certified"),
        "{}",
        c.reason
    );
    // a covariance of the six, symmetric, with u² on its diagonal
    assert_eq!(c.covariance.len(), 6);
    for (i, k) in c.coefficients.iter().enumerate() {
        let rel = (c.covariance[i][i] - k.u * k.u).abs() / (k.u * k.u);
        assert!(rel < 1e-9, "{}: {rel}", k.name);
        for j in 0..6 {
            assert_eq!(c.covariance[i][j], c.covariance[j][i]);
        }
    }
    // k2 relative to the mountings' mean k1, in µg/g²
    let k1_mean = (t.mountings[0].k1.value + t.mountings[1].k1.value) / 2.0;
    let rel = k2.relative.as_ref().unwrap();
    assert_eq!(rel.unit, "µg/g²");
    assert!((rel.value - k2.value / k1_mean * 1e6).abs() < 1e-12 * rel.value.abs().max(1.0));
    // each mounting's rates and specific force: a = R·ω²/g, negative with the IA out
    assert_eq!(c.validity.len(), 2);
    for (v, m) in c.validity.iter().zip(&t.mountings) {
        assert_eq!(v.mounting, m.orientation);
        let w = v.rate_high_deg_s.to_radians();
        let a = m.radius_m * w * w / t.g_m_s2.value;
        let sign = if m.orientation == "ia_out" { -1.0 } else { 1.0 };
        assert!((v.specific_force_high_g - sign * a).abs() < 1e-12);
        assert!(v.rate_low_deg_s < v.rate_high_deg_s);
        assert_eq!(v.points, m.points);
    }
    assert!(
        c.validity[1]
            .mounting_words
            .contains("away from the spindle axis")
    );
    // the statements of conformity are judged on the certified k2
    if let Some(conformity) = &cert.conformity {
        for s in conformity.statements.iter().filter(|s| s.index == 2) {
            let expected = if s.relative_to_k1 {
                rel.value
            } else {
                k2.value
            };
            assert_eq!(s.value, expected);
        }
    }
}

#[test]
fn one_mounting_certifies_the_probe_method() {
    let r = run_edited("campaign", |t| t).unwrap();
    let c = &r.certificate.as_ref().unwrap().certified;
    let cal = r.calibration.as_ref().unwrap();
    assert_eq!(c.method, CertifiedMethod::Probe);
    assert!(c.check.is_none());
    assert!(c.reason.contains("probe method"), "{}", c.reason);
    assert_eq!(c.coefficients.len(), 4);
    let k2 = &c.coefficients[2];
    assert_eq!(k2.value, cal.coefficients.k2.value);
    assert_eq!(
        (k2.low95, k2.high95),
        (cal.headline.k2.low95, cal.headline.k2.high95)
    );
    // a Monte Carlo interval has no coverage factor; a GUM one has its own
    for (k, h) in c.coefficients.iter().zip([
        cal.headline.k0,
        cal.headline.k1,
        cal.headline.k2,
        cal.headline.k3,
    ]) {
        assert_eq!(k.interval_method, h.method);
        assert_eq!(k.k.is_some(), h.method == HeadlineMethod::Gum, "{}", k.name);
    }
    assert_eq!(c.validity.len(), 1);
    let v = &c.validity[0];
    assert_eq!(v.mounting, "ia_in");
    let rates: Vec<f64> = cal.residuals.iter().map(|p| p.rate_deg_s).collect();
    assert_eq!(
        v.rate_low_deg_s,
        rates.iter().copied().fold(f64::INFINITY, f64::min)
    );
    assert_eq!(v.rate_high_deg_s, rates.iter().copied().fold(0.0, f64::max));
    assert!(v.specific_force_low_g > 0.0 && v.specific_force_high_g > v.specific_force_low_g);
}

#[test]
fn a_refuted_value_is_certified_only_with_the_laboratorys_reason() {
    let probe = |t: String| with_certificate_field(t, "certify: probe,");
    let e = run_edited("two_orientation", probe).unwrap_err();
    let message = chain(&e);
    assert!(
        matches!(e, PipelineError::CertifiesRefutedValue { .. }),
        "{message}"
    );
    assert!(message.contains("field `certificate.certify`"), "{message}");
    assert!(message.contains("certify_despite_check"), "{message}");
    assert!(message.contains("µg/g²"), "{message}");

    let despite = |t: String| {
        with_certificate_field(
            t,
            "certify: probe, certify_despite_check: \"customer contract CC-9 requires the probe method\",",
        )
    };
    let r = run_edited("two_orientation", despite).unwrap();
    let c = &r.certificate.as_ref().unwrap().certified;
    assert_eq!(c.method, CertifiedMethod::Probe);
    assert!(c.refuted_by_check);
    assert_eq!(
        c.despite_check_reason.as_deref(),
        Some("customer contract CC-9 requires the probe method")
    );
    assert!(c.reason.contains("customer contract CC-9"), "{}", c.reason);
    assert_eq!(c.check.unwrap().method, CertifiedMethod::TwoOrientation);
}

#[test]
fn certifying_the_two_orientation_method_needs_its_section() {
    let e = run_edited("campaign", |t| {
        with_certificate_field(t, "certify: two_orientation,")
    })
    .unwrap_err();
    let message = chain(&e);
    assert!(
        message.contains("field `two_orientation` is required"),
        "{message}"
    );
}

#[test]
fn hidden_characters_in_the_certificates_text_are_refused_by_field() {
    let e = run_edited("campaign", |t| {
        t.replacen("serial: \"", "serial: \"SN \\u{202E}evil\\u{202C} ", 1)
            .replacen("operator: \"", "operator: \"\\u{1b}]0;pwned\\u{7}", 1)
    })
    .unwrap_err();
    let message = chain(&e);
    assert!(
        message.contains("field `certificate.item.serial` holds the character U+202E (RIGHT-TO-LEFT OVERRIDE) at character 4"),
        "{message}"
    );
    assert!(
        message.contains(
            "field `certificate.operator` holds the character U+001B (ESC) at character 1"
        ),
        "{message}"
    );
}

#[test]
fn an_implausible_type_b_uncertainty_is_refused_naming_it() {
    let e = run_edited("campaign", |t| {
        t.replacen("radius_u_m: 5.0e-6", "radius_u_m: 1e200", 1)
    })
    .unwrap_err();
    let message = chain(&e);
    assert!(
        message.contains("field `uncertainty.radius_u_m` = 1e200: a standard uncertainty as large as the quantity itself (`radius_m` = 2.5 m)"),
        "{message}"
    );
}
