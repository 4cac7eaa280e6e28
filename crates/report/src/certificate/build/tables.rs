//! The certificate's tables of results: the coefficients, the compensation, conformity,
//! traceability and the uncertainty budget.

use pipeline::{CalibrationResults, CertificateResults, DecisionRule, Verdict};

use super::super::certified::{self, Certified};
use super::super::model::{Budget, Conformity, Run, Table, Text};
use super::text::{
    interval_from, interval_row, interval_table, mounting_label, nominal, rich, runs, t, table,
    value_u_expanded,
};
use crate::format;

pub(super) fn results_table(cert: &Certified) -> Table {
    let several = cert
        .coefficients
        .iter()
        .filter_map(|c| c.mounting.as_deref())
        .any(|m| m == "ia_out");
    let mut rows = Vec::new();
    let label = |c: &certified::Coefficient, suffix: &str| {
        if several && c.mounting.is_some() {
            format!(
                "{}{suffix} ({})",
                c.name,
                mounting_label(c.mounting.as_deref())
            )
        } else {
            format!("{}{suffix}", c.name)
        }
    };
    for c in &cert.coefficients {
        rows.push(interval_row(
            &label(c, ""),
            value_u_expanded(c.value, c.u, c.value - c.low95, c.high95 - c.value),
            c.k.map_or_else(|| "—".to_owned(), format::coverage_factor),
            if c.k.is_some() {
                format::dof(c.dof)
            } else {
                "—".to_owned()
            },
            &c.unit,
            interval_from(c.interval_method, c.borderline),
        ));
    }
    for c in &cert.coefficients {
        if let Some(r) = &c.relative {
            rows.push(interval_row(
                &label(c, "/k1"),
                value_u_expanded(r.value, r.u, r.value - r.low95, r.high95 - r.value),
                c.k.map_or_else(|| "—".to_owned(), format::coverage_factor),
                if c.k.is_some() {
                    format::dof(c.dof)
                } else {
                    "—".to_owned()
                },
                &r.unit,
                interval_from(c.interval_method, c.borderline),
            ));
        }
    }
    interval_table("coefficient", &[9, 12, 11, 14, 5, 6, 9, 12], rows)
}

pub(super) fn results_notes(cert: &Certified, c: &CalibrationResults) -> Vec<Text> {
    let k1 = cert
        .coefficients
        .iter()
        .find(|x| x.name == "k1")
        .map_or(c.coefficients.k1.value, |x| x.value);
    vec![
        rich(
            "u is the standard uncertainty; U is the expanded uncertainty for a coverage \
             probability of approximately 95 %: U = k·u with the coverage factor k of that \
             quantity, Student's t at its effective degrees of freedom ν_eff (Welch–Satterthwaite, \
             JCGM 100). Where the Monte Carlo method (JCGM 101) does not validate the GUM \
             interval, or the validation is borderline, the Monte Carlo method's probabilistically \
             symmetric 95 % interval is stated instead, as +/− widths about the value; it has no \
             coverage factor.",
        ),
        rich(&if cert.validity.len() > 1 {
            format!(
                "Each mounting's k0 relative to k1 uses that mounting's k1; k2 and k3 relative \
                 to k1 use the mean of the two mountings' k1; g = {} m/s² (1 g).",
                format::plain(c.g_m_s2)
            )
        } else {
            format!(
                "The values relative to k1 use k1 = {} rad/(s·g) and g = {} m/s² (1 g).",
                format::significant(k1, 7),
                format::plain(c.g_m_s2)
            )
        }),
    ]
}

pub(super) fn compensation(c: &CalibrationResults, angle_zero: &pipeline::AngleZero) -> Table {
    let micro = 1e6 / c.coefficients.k1.value;
    let cr = format::pair(c.c_r_combined_m_s2.value, c.c_r_combined_m_s2.u);
    let dk2 = format::pair(c.delta_k2.value, c.delta_k2.u);
    let dk2_micro = format::pair(c.delta_k2.value * micro, c.delta_k2.u * micro.abs());
    let with_scale = |p: &format::Pair, x: &str| {
        if p.scale.is_empty() {
            x.to_owned()
        } else {
            format!("{x} {}", p.scale)
        }
    };
    table(
        &[
            "quantity",
            "value",
            "standard uncertainty u",
            "unit",
            "what it is",
        ],
        &[false, true, true, false, false],
        &[6, 5, 5, 4, 14],
        vec![
            vec![
                rich("C_r, the spindle's radius growth"),
                t(with_scale(&cr, &cr.value)),
                t(with_scale(&cr, &cr.u)),
                t("m·s²"),
                runs(vec![
                    rich("from the displacement probe (phase “"),
                    t(&c.compensate_with),
                    rich(
                        "”); u from the fit, the probe gain, the lever heights and the rate scale",
                    ),
                ]),
            ],
            vec![
                rich("Δk2 = k1·C_r·g/R²"),
                t(with_scale(&dk2, &dk2.value)),
                t(with_scale(&dk2, &dk2.u)),
                t("rad/(s·g²)"),
                rich(&format!(
                    "the pseudo-second-order term removed from the fitted a² coefficient \
                     (eq. 19): {} µg/g² relative to k1, standard uncertainty u = {} µg/g²",
                    with_scale(&dk2_micro, &dk2_micro.value),
                    with_scale(&dk2_micro, &dk2_micro.u)
                )),
            ],
            vec![
                t("angle zero of the probe analysis"),
                t(angle_zero_value(angle_zero)),
                t("—"),
                t("deg"),
                t(angle_zero_words(angle_zero)),
            ],
        ],
    )
}

/// The encoder's reading at the angle zero, as the compensation table states it.
fn angle_zero_value(a: &pipeline::AngleZero) -> String {
    if a.measured_angles {
        format::plain(a.angle_zero_deg)
    } else {
        "—".to_owned()
    }
}

/// The angle zero of the probe analysis in a customer's words (eq. 20–21).
fn angle_zero_words(a: &pipeline::AngleZero) -> String {
    let at = "when the arm's accelerometer end points at the probe";
    match (a.measured_angles, a.stated) {
        (false, _) => "not used: no probe recording measures its angle".to_owned(),
        (true, false) => format!(
            "not stated by the laboratory: the encoder is taken to read 0° {at}; an encoder \
             zero elsewhere would change C_r with no other sign"
        ),
        (true, true) => format!("the encoder's reading {at}, as the laboratory states it"),
    }
}

/// The probe's sign convention in the words a person checks at the machine (no axis name of
/// the paper's figure).
pub(super) const fn probe_sign_words(sign: pipeline::ProbeSign) -> &'static str {
    match sign {
        pipeline::ProbeSign::AgainstO1X1 => {
            "the probe's gap closes (its reading falls) when the spindle moves towards the \
             accelerometer"
        }
        pipeline::ProbeSign::AlongO1X1 => {
            "the probe's reading rises when the spindle moves towards the accelerometer"
        }
    }
}

pub(super) fn conformity(info: &CertificateResults) -> Option<Conformity> {
    let conformity = info.conformity.as_ref()?;
    let rule = match conformity.rule {
        DecisionRule::SimpleAcceptance => {
            "Decision rule (ILAC-G8:09/2019 §4.2): binary statement with simple acceptance \
             (guard band w = 0): pass when the measured value lies within the tolerance \
             limits, fail otherwise. The risk of a false acceptance reaches 50 % for a value on \
             a limit."
        }
        DecisionRule::GuardBand => {
            "Decision rule (ILAC-G8:09/2019 §4.2): non-binary statement with a guard band \
             w = U: pass when the whole 95 % interval lies within the tolerance limits; \
             conditional pass when the value lies within them but the interval does not; \
             conditional fail when the value lies outside but the interval reaches within; \
             fail when the whole interval lies outside."
        }
    };
    let limit = |x: Option<f64>| x.map_or_else(|| "—".to_owned(), format::plain);
    let mut verdicts = Vec::new();
    let rows = conformity
        .statements
        .iter()
        .map(|st| {
            let a = format::interval(st.value, st.value - st.low95, st.high95 - st.value);
            let suffix = if a.scale.is_empty() {
                String::new()
            } else {
                format!(" {}", a.scale)
            };
            let expanded = if a.minus.is_empty() {
                format!("{}{suffix}", a.plus)
            } else {
                format!("+{}{suffix} / −{}{suffix}", a.plus, a.minus)
            };
            verdicts.push(
                match st.verdict {
                    Verdict::Pass => "pass",
                    Verdict::ConditionalPass | Verdict::ConditionalFail => "conditional",
                    Verdict::Fail => "fail",
                }
                .to_owned(),
            );
            vec![
                t(&st.coefficient),
                t(format!("{}{suffix}", a.value)),
                t(expanded),
                t(limit(st.lower)),
                t(limit(st.upper)),
                t(&st.unit),
                st.source.as_ref().map_or_else(|| t("not stated"), t),
                t(st.verdict.words()),
            ]
        })
        .collect();
    Some(Conformity {
        rule: rich(rule),
        table: table(
            &[
                "coefficient",
                "value",
                "expanded uncertainty U (95 %)",
                "lower limit",
                "upper limit",
                "unit",
                "limit from",
                "statement",
            ],
            &[false, true, true, true, true, false, false, false],
            &[5, 5, 7, 4, 4, 4, 8, 5],
            rows,
        ),
        verdicts,
    })
}

pub(super) fn traceability(info: &CertificateResults) -> Table {
    table(
        &[
            "input quantity",
            "standard uncertainty u",
            "unit",
            "traceability",
        ],
        &[false, true, false, false],
        &[5, 3, 2, 9],
        info.traceability
            .iter()
            .map(|x| {
                vec![
                    rich(&x.input),
                    t(x.u.map_or_else(|| "—".to_owned(), |u| format::significant(u, 2))),
                    t(unit_or_dash(&x.unit)),
                    t(&x.statement),
                ]
            })
            .collect(),
    )
}

/// A unit as results.json records it, or a dash for one written before units were recorded.
fn unit_or_dash(unit: &str) -> &str {
    if unit.is_empty() { "—" } else { unit }
}

pub(super) fn budget(
    lines: &[pipeline::BudgetLine],
    k2: &pipeline::Coefficient,
    heading: &str,
) -> Budget {
    let rows = lines
        .iter()
        .map(|l| {
            let quantity = match &l.note {
                Some(n) => runs(vec![
                    rich(&l.quantity),
                    Text::Runs(vec![Run::Note(n.clone())]),
                ]),
                None => rich(&l.quantity),
            };
            vec![
                quantity,
                t(&l.evaluation),
                t(l.value.map_or_else(|| "—".to_owned(), nominal)),
                t(format::significant(l.u, 2)),
                t(unit_or_dash(&l.unit)),
                t(format::significant(l.sensitivity, 3)),
                t(format::significant(l.contribution, 2)),
                t(format!("{} %", format::percent(l.percent))),
                t(format::dof(l.dof)),
            ]
        })
        .collect();
    Budget {
        heading: heading.to_owned(),
        table: table(
            &[
                "input quantity",
                "type",
                "value",
                "standard uncertainty u",
                "unit",
                "sensitivity c (rad/(s·g²) per unit)",
                "contribution |c|·u (rad/(s·g²))",
                "share of u²",
                "ν",
            ],
            &[false, false, true, true, false, true, true, true, true],
            &[14, 3, 7, 7, 6, 8, 8, 5, 4],
            rows,
        ),
        total: vec![
            rich("combined standard uncertainty u(k2) and effective degrees of freedom ν_eff"),
            t(format::significant(k2.u, 2)),
            t("100 %"),
            t(format::dof(k2.dof)),
        ],
    }
}
