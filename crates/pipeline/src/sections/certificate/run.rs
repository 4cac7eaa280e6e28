//! The certificate section's run: the statements, each Type B input's standard
//! uncertainty from the calibration's k2 budget, and the statements of conformity.

use std::path::Path;

use super::certified::{certify, label};
use super::validate::Certificate;
use crate::error::Result;
use crate::results::{
    CalibrationResults, CertificateResults, Conformity, ConformityStatement, Traceability,
    TwoOrientationResults, Verdict,
};

/// The certificate's results for the calibration `c` and, when the study has both mountings,
/// the two-orientation results `two`: what is certified (`certificate.certify`), and the
/// conformity of each limited coefficient judged on its stated interval (the §8 headline),
/// in the limit's unit, for every mounting the coefficient is certified for.
///
/// # Errors
/// [`crate::PipelineError::CertifiesRefutedValue`] when the value to certify is one the
/// study's own check refutes and the configuration gives no reason.
pub(crate) fn run(
    path: &Path,
    cert: &Certificate,
    c: &CalibrationResults,
    two: Option<&TwoOrientationResults>,
    radius_m: f64,
) -> Result<CertificateResults> {
    let traceability = cert
        .traceability
        .iter()
        .map(|(index, statement)| {
            let input = ::calibration::input::NAMES[*index];
            Traceability {
                input: input.to_owned(),
                unit: ::calibration::input::UNITS[*index].to_owned(),
                u: c.budget
                    .k2
                    .iter()
                    .find(|l| l.quantity == input)
                    .map(|l| l.u),
                statement: statement.clone(),
            }
        })
        .collect();
    let certified = certify(
        path,
        cert.certify,
        cert.despite_check.as_deref(),
        c,
        two,
        radius_m,
    )?;
    let mountings = certified.validity.len();
    let conformity = cert.rule.map(|rule| Conformity {
        rule,
        limits_source: cert.limits_source.clone(),
        statements: cert
            .limits
            .iter()
            .flat_map(|l| {
                certified
                    .coefficients
                    .iter()
                    .filter(|k| k.name == ["k0", "k1", "k2", "k3"][l.index])
                    .map(move |k| {
                        // k1 relative to itself is 1: its "relative" limit is in parts per
                        // million of nothing; the native unit is kept for it.
                        let relative = k.relative.as_ref().filter(|_| l.relative);
                        let (value, low95, high95, unit) = match relative {
                            Some(r) => (r.value, r.low95, r.high95, r.unit.clone()),
                            None => (k.value, k.low95, k.high95, k.unit.clone()),
                        };
                        let name = label(k, mountings);
                        ConformityStatement {
                            coefficient: if relative.is_some() {
                                name.replacen(&k.name, &format!("{}/k1", k.name), 1)
                            } else {
                                name
                            },
                            index: l.index,
                            relative_to_k1: relative.is_some(),
                            unit,
                            value,
                            low95,
                            high95,
                            lower: l.lower,
                            upper: l.upper,
                            // the limit's own source, else where the certificate's limits
                            // come from (`limits_source`, which a lab profile may state)
                            source: l.source.clone().or_else(|| cert.limits_source.clone()),
                            verdict: Verdict::of(
                                value,
                                (value - low95, high95 - value),
                                l.lower,
                                l.upper,
                                rule,
                            ),
                        }
                    })
            })
            .collect(),
    });
    Ok(CertificateResults {
        id: cert.id.clone(),
        laboratory: cert.laboratory.clone(),
        location: cert.location.clone(),
        customer: cert.customer.clone(),
        item: cert.item.clone(),
        equipment: cert.equipment.clone(),
        dates: cert.dates.clone(),
        operator: cert.operator.clone(),
        conditions: cert.conditions.clone(),
        procedure: cert.procedure.clone(),
        deviations: cert.deviations.clone(),
        traceability,
        conformity,
        authorisation: cert.authorisation.clone(),
        certified,
        previous_certificate: cert.previous_certificate.clone(),
    })
}

#[cfg(test)]
mod tests {
    use crate::results::{DecisionRule, Verdict};

    #[test]
    fn simple_acceptance_is_binary() {
        let r = DecisionRule::SimpleAcceptance;
        assert_eq!(
            Verdict::of(0.9, (0.5, 0.5), None, Some(1.0), r),
            Verdict::Pass
        );
        assert_eq!(
            Verdict::of(1.1, (0.5, 0.5), None, Some(1.0), r),
            Verdict::Fail
        );
        assert_eq!(
            Verdict::of(-1.1, (0.5, 0.5), Some(-1.0), None, r),
            Verdict::Fail
        );
    }

    #[test]
    fn a_guard_band_of_u_gives_four_statements() {
        let r = DecisionRule::GuardBand;
        let v = |x: f64| Verdict::of(x, (0.2, 0.2), Some(-1.0), Some(1.0), r);
        assert_eq!(v(0.7), Verdict::Pass);
        assert_eq!(v(0.9), Verdict::ConditionalPass);
        assert_eq!(v(1.1), Verdict::ConditionalFail);
        assert_eq!(v(1.3), Verdict::Fail);
        assert_eq!(v(-0.9), Verdict::ConditionalPass);
        assert_eq!(v(-1.3), Verdict::Fail);
        // an asymmetric interval: the width towards the limit decides
        assert_eq!(
            Verdict::of(0.9, (0.5, 0.05), None, Some(1.0), r),
            Verdict::Pass
        );
    }
}
