//! The certificate section's run: the statements, each Type B input's standard
//! uncertainty from the calibration's k2 budget, and the statements of conformity.

use super::validate::Certificate;
use crate::results::{
    CalibrationResults, CertificateResults, Conformity, ConformityStatement, Traceability, Verdict,
};

const NAMES: [&str; 4] = ["k0", "k1", "k2", "k3"];
const UNITS: [&str; 4] = ["rad/s", "rad/(s·g)", "rad/(s·g²)", "rad/(s·g³)"];
const MICRO_UNITS: [&str; 4] = ["µg", "µg/g", "µg/g²", "µg/g³"];

/// The certificate's results for the calibration `c`: the conformity of each limited
/// coefficient is judged on its stated interval (the §8 headline), in the limit's unit.
pub(crate) fn run(cert: &Certificate, c: &CalibrationResults) -> CertificateResults {
    let traceability = cert
        .traceability
        .iter()
        .map(|(index, statement)| {
            let input = ::calibration::input::NAMES[*index];
            Traceability {
                input: input.to_owned(),
                u: c.budget
                    .k2
                    .iter()
                    .find(|l| l.quantity == input)
                    .map(|l| l.u),
                statement: statement.clone(),
            }
        })
        .collect();
    let heads = [
        &c.headline.k0,
        &c.headline.k1,
        &c.headline.k2,
        &c.headline.k3,
    ];
    let micro = 1e6 / c.coefficients.k1.value;
    let conformity = cert.rule.map(|rule| Conformity {
        rule,
        statements: cert
            .limits
            .iter()
            .map(|l| {
                let h = heads[l.index];
                // k1 relative to itself is 1: its "relative" limit is in parts per million of
                // nothing; the native unit is kept for it.
                let relative = l.relative && l.index != 1;
                let scale = if relative { micro } else { 1.0 };
                let value = h.value * scale;
                let (below, above) = h.widths(scale);
                ConformityStatement {
                    coefficient: if relative {
                        format!("{}/k1", NAMES[l.index])
                    } else {
                        NAMES[l.index].to_owned()
                    },
                    index: l.index,
                    relative_to_k1: relative,
                    unit: if relative {
                        MICRO_UNITS[l.index]
                    } else {
                        UNITS[l.index]
                    }
                    .to_owned(),
                    value,
                    low95: value - below,
                    high95: value + above,
                    lower: l.lower,
                    upper: l.upper,
                    source: l.source.clone(),
                    verdict: Verdict::of(value, (below, above), l.lower, l.upper, rule),
                }
            })
            .collect(),
    });
    CertificateResults {
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
    }
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
