//! What a certificate certifies (issue 27): the probe method's coefficients (eq. 18 on one
//! mounting, k2 compensated with the probe's C_r) or the two-orientation method's (eq. 23,
//! k2 from the PIGA alone), chosen by `certificate.certify`, with the other method as the
//! check. A value the study's own check refutes (|z| > 3) is certified only when the
//! configuration gives the laboratory's reason (`certify_despite_check`).

use std::path::Path;

use crate::error::{PipelineError, Result};
use crate::results::{COEFFICIENT_NAMES as NAMES, COEFFICIENT_UNITS as UNITS, RELATIVE_UNITS};
use crate::results::{
    CalibrationResults, Certified, CertifiedCoefficient, CertifiedMethod, CertifyPolicy,
    Coefficient, Headline, HeadlineMethod, MethodCheck, OutputCovariance, RelativeValue,
    TwoOrientationResults, ValidityRange,
};

/// A mounting in words, as a customer reads it.
pub(crate) const fn mounting_words(orientation: &str) -> &'static str {
    if matches!(orientation.as_bytes(), b"ia_out") {
        "input axis pointing away from the spindle axis"
    } else {
        "input axis pointing towards the spindle axis"
    }
}

/// A mounting's short name on a certificate's row.
const fn mounting_tag(orientation: &str) -> &'static str {
    if matches!(orientation.as_bytes(), b"ia_out") {
        "IA out"
    } else {
        "IA in"
    }
}

/// One coefficient's GUM result and stated interval.
struct Stated<'a> {
    index: usize,
    mounting: Option<&'a str>,
    coefficient: &'a Coefficient,
    headline: Headline,
}

/// The headline of a coefficient stated by the GUM alone (no Monte Carlo output of it).
fn gum_headline(c: &Coefficient) -> Headline {
    Headline {
        value: c.value,
        low95: c.value - c.u95,
        high95: c.value + c.u95,
        method: HeadlineMethod::Gum,
        borderline: false,
    }
}

/// The certified coefficient of `s`, relative to `k1` (its value and its covariance row with
/// `k1` from `cov`: `(var k1, cov(x, k1))`).
fn certified(s: &Stated<'_>, k1: f64, cov: (f64, f64)) -> CertifiedCoefficient {
    let h = s.headline;
    let c = s.coefficient;
    let (expanded, k) = match h.method {
        HeadlineMethod::Gum => (c.u95, Some(c.k)),
        HeadlineMethod::MonteCarlo => ((h.high95 - h.value).max(h.value - h.low95), None),
    };
    let relative = (s.index != 1).then(|| {
        let scale = 1e6 / k1;
        let r = c.value / k1;
        let (var_k1, cov_x_k1) = cov;
        let var =
            c.u * c.u / (k1 * k1) + (r / k1).powi(2) * var_k1 - 2.0 * r / (k1 * k1) * cov_x_k1;
        RelativeValue {
            unit: RELATIVE_UNITS[s.index].to_owned(),
            value: c.value * scale,
            u: var.max(0.0).sqrt() * 1e6,
            low95: h.low95 * scale,
            high95: h.high95 * scale,
            expanded: expanded * scale,
        }
    });
    CertifiedCoefficient {
        name: NAMES[s.index].to_owned(),
        mounting: s.mounting.map(str::to_owned),
        unit: UNITS[s.index].to_owned(),
        value: c.value,
        u: c.u,
        low95: h.low95,
        high95: h.high95,
        expanded,
        k,
        dof: c.dof,
        interval_method: h.method,
        relative,
    }
}

/// The specific force along the input axis at `rate_deg_s` on a mounting at `radius_m`, in g:
/// R·ω²/g, negative with the input axis away from the spindle axis.
fn specific_force_g(orientation: &str, radius_m: f64, rate_deg_s: f64, g_m_s2: f64) -> f64 {
    let w = units::deg_s_to_rad_s(rate_deg_s);
    let a = radius_m * w * w / g_m_s2;
    if orientation == "ia_out" { -a } else { a }
}

fn validity(
    orientation: &str,
    radius_m: f64,
    (low, high): (f64, f64),
    points: usize,
    g_m_s2: f64,
) -> ValidityRange {
    ValidityRange {
        mounting: orientation.to_owned(),
        mounting_words: mounting_words(orientation).to_owned(),
        radius_m,
        rate_low_deg_s: low,
        rate_high_deg_s: high,
        specific_force_low_g: specific_force_g(orientation, radius_m, low, g_m_s2),
        specific_force_high_g: specific_force_g(orientation, radius_m, high, g_m_s2),
        points,
    }
}

/// The probe method's coefficients: the calibration section's (one mounting, IA in).
fn probe_coefficients(c: &CalibrationResults) -> (Vec<CertifiedCoefficient>, Vec<Vec<f64>>) {
    let coefficients = [
        &c.coefficients.k0,
        &c.coefficients.k1,
        &c.coefficients.k2,
        &c.coefficients.k3,
    ];
    let heads = [c.headline.k0, c.headline.k1, c.headline.k2, c.headline.k3];
    let cov = &c.covariance.matrix;
    let k1 = c.coefficients.k1.value;
    let list = (0..4)
        .map(|i| {
            let s = Stated {
                index: i,
                mounting: (i < 2).then_some("ia_in"),
                coefficient: coefficients[i],
                headline: heads[i],
            };
            certified(&s, k1, (cov[1][1], cov[i][1]))
        })
        .collect();
    (list, cov.clone())
}

/// The two-orientation method's coefficients: k0 and k1 of each mounting, k2 and k3 shared;
/// k2 and k3 relative to the mountings' mean k1.
fn two_orientation_coefficients(
    t: &TwoOrientationResults,
) -> (Vec<CertifiedCoefficient>, Vec<Vec<f64>>) {
    let OutputCovariance { matrix: cov, .. } = &t.covariance;
    let mut list = Vec::new();
    for (m, mounting) in t.mountings.iter().enumerate() {
        let (i0, i1) = (2 * m, 2 * m + 1);
        let k1 = mounting.k1.value;
        for (index, coefficient, row) in [(0, &mounting.k0, i0), (1, &mounting.k1, i1)] {
            let s = Stated {
                index,
                mounting: Some(mounting.orientation.as_str()),
                coefficient,
                headline: gum_headline(coefficient),
            };
            list.push(certified(&s, k1, (cov[i1][i1], cov[row][i1])));
        }
    }
    // k̄1 = (k1 in + k1 out)/2, its variance and covariance with k2, k3
    let k1_mean = t.mountings.iter().map(|m| m.k1.value).sum::<f64>() / 2.0;
    let var_mean = (cov[1][1] + cov[3][3] + 2.0 * cov[1][3]) / 4.0;
    for (index, coefficient, headline, row) in
        [(2, &t.k2, t.headline.k2, 4), (3, &t.k3, t.headline.k3, 5)]
    {
        let s = Stated {
            index,
            mounting: None,
            coefficient,
            headline,
        };
        let cov_mean = (cov[row][1] + cov[row][3]) / 2.0;
        list.push(certified(&s, k1_mean, (var_mean, cov_mean)));
    }
    (list, cov.clone())
}

/// What the certificate certifies, by `policy`, from the calibration `c` and, when the study
/// has both mountings, the two-orientation results `two`; `g_m_s2` and `radius_m` are the
/// study's (the calibration section's mounting).
///
/// # Errors
/// [`PipelineError::CertifiesRefutedValue`] when the value to certify is one the study's own
/// check refutes and `despite` gives no reason.
pub(crate) fn certify(
    path: &Path,
    policy: CertifyPolicy,
    despite: Option<&str>,
    c: &CalibrationResults,
    two: Option<&TwoOrientationResults>,
    radius_m: f64,
) -> Result<Certified> {
    let method = match (policy, two) {
        (CertifyPolicy::Probe, _) | (CertifyPolicy::Auto, None) => CertifiedMethod::Probe,
        _ => CertifiedMethod::TwoOrientation,
    };
    let comparison = two.and_then(|t| t.probe.as_ref());
    let probe_check = |t: &TwoOrientationResults| {
        comparison.map(|p| MethodCheck {
            method: CertifiedMethod::TwoOrientation,
            k2: t.k2.value,
            u: t.k2.u,
            expanded: (t.headline.k2.high95 - t.headline.k2.value)
                .max(t.headline.k2.value - t.headline.k2.low95),
            z: p.z,
            agrees: p.agrees,
        })
    };
    let k2_gap_ug = |t: &TwoOrientationResults| {
        (c.coefficients.k2.value - t.k2.value) * 1e6 / c.coefficients.k1.value
    };
    let (check, refuted, reason) = match (method, two) {
        (CertifiedMethod::Probe, None) => (
            None,
            false,
            "One mounting was measured (input axis pointing towards the spindle axis): k2 is \
             found by the probe method, the output's ω⁴ term corrected for the spindle's \
             radius growth measured with a displacement probe."
                .to_owned(),
        ),
        (CertifiedMethod::Probe, Some(t)) => {
            let check = probe_check(t);
            let refuted = check.is_some_and(|k| !k.agrees);
            let z = check.map_or(0.0, |k| k.z);
            if refuted && despite.is_none() {
                return Err(PipelineError::CertifiesRefutedValue {
                    path: path.to_owned(),
                    message: format!(
                        "the probe method's k2 is to be certified, but the study's own check by \
                         the two-orientation method refutes it (z = {z:+.1}: the radius grows by \
                         more or less than the probe measured, and the probe method's k2 is off \
                         by about {gap:+.3} µg/g²). Certify the two-orientation method \
                         (`certify: auto` or `certify: two_orientation`), correct the probe's \
                         declaration (direction, gap unit, angle reference, lever heights), or \
                         give the laboratory's reason in `certify_despite_check`, which the \
                         certificate prints",
                        gap = k2_gap_ug(t),
                    ),
                });
            }
            let reason = if refuted {
                format!(
                    "The laboratory certifies the probe method although the check by the \
                     two-orientation method disagrees with it (z = {z:+.1}); its reason: {}",
                    despite.unwrap_or_default().trim()
                )
            } else if check.is_some() {
                format!(
                    "The laboratory certifies the probe method (k2 corrected for the spindle's \
                     radius growth measured with a displacement probe); the two-orientation \
                     method agrees with it (z = {z:+.1})."
                )
            } else {
                "The laboratory certifies the probe method.".to_owned()
            };
            (check, refuted, reason)
        }
        (CertifiedMethod::TwoOrientation, t) => {
            let t = t.expect("the two-orientation method is chosen only with its results");
            let check = comparison.map(|p| MethodCheck {
                method: CertifiedMethod::Probe,
                k2: c.coefficients.k2.value,
                u: c.coefficients.k2.u,
                expanded: (c.headline.k2.high95 - c.headline.k2.value)
                    .max(c.headline.k2.value - c.headline.k2.low95),
                z: p.z,
                agrees: p.agrees,
            });
            let base = "Both mountings were measured (input axis pointing towards and away from \
                        the spindle axis), so k2 and k3 are found from the accelerometer's own \
                        outputs, whatever the spindle's radius growth; the probe method is \
                        stated as a check.";
            let reason = match check {
                Some(k) if !k.agrees => format!(
                    "{base} The two methods disagree (z = {z:+.1}): the radius grows by more or \
                     less than the probe measured (an arm that stretches under load, or a probe \
                     declared wrongly), so the probe method's k2 would be off by {gap:+.3} µg/g²; \
                     it is not certified.",
                    z = k.z,
                    gap = k2_gap_ug(t),
                ),
                Some(k) => format!("{base} The two methods agree (z = {:+.1}).", k.z),
                None => base.to_owned(),
            };
            (check, false, reason)
        }
    };
    let (coefficients, covariance, validity) = match (method, two) {
        (CertifiedMethod::TwoOrientation, Some(t)) => {
            let (list, cov) = two_orientation_coefficients(t);
            let ranges = t
                .mountings
                .iter()
                .map(|m| {
                    validity(
                        &m.orientation,
                        m.radius_m,
                        (m.rate_low_deg_s, m.rate_high_deg_s),
                        m.points,
                        t.g_m_s2.value,
                    )
                })
                .collect();
            (list, cov, ranges)
        }
        _ => {
            let (list, cov) = probe_coefficients(c);
            let rates = c.residuals.iter().map(|r| r.rate_deg_s);
            let low = rates.clone().fold(f64::INFINITY, f64::min);
            let high = rates.fold(f64::NEG_INFINITY, f64::max);
            let range = validity("ia_in", radius_m, (low, high), c.points, c.g_m_s2);
            (list, cov, vec![range])
        }
    };
    Ok(Certified {
        policy,
        method,
        reason,
        check,
        refuted_by_check: refuted,
        despite_check_reason: refuted.then(|| despite.unwrap_or_default().trim().to_owned()),
        coefficients,
        covariance,
        validity,
    })
}

/// The label of a certified coefficient in a statement of conformity: `k0`, or `k0 (IA in)`
/// when the certificate states it for two mountings.
pub(crate) fn label(c: &CertifiedCoefficient, mountings: usize) -> String {
    match &c.mounting {
        Some(m) if mountings > 1 => format!("{} ({})", c.name, mounting_tag(m)),
        _ => c.name.clone(),
    }
}
