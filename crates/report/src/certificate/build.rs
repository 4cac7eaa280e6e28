//! The one builder of the certificate's data ([`CertificateData`]) from a study's results,
//! its provenance and the software: ISO/IEC 17025:2017 §7.8.2.1 (the laboratory, the
//! customer, the item, the method, the dates, the results with their units, the statement
//! that they relate only to the item, the authorisation, a marked end) and §7.8.4.1 and
//! §7.8.6 (the uncertainty in the measurand's unit, the conditions, the traceability of each
//! input, the statements of conformity with their decision rule and the source of each
//! limit).

use pipeline::{
    CalibrationResults, CertificateResults, DecisionRule, HeadlineMethod, StudyResults,
    TwoOrientationResults, Verdict,
};

use super::certified::{self, Certified, Method};
use super::model::{
    Authorisation, Budget, CalendarDate, CertificateData, Check, Conformity, DataUsed, Field,
    Files, Laboratory, Run, Running, Section, Table, Text,
};
use crate::format;
use crate::headline::headlines;
use crate::provenance::{FileRecord, Provenance, Software};

/// A plain text run.
fn t(text: impl Into<String>) -> Text {
    Text::Plain(text.into())
}

/// Text written by this tool, with its symbols set as a person writes them: `C_r`, `C_a`,
/// `ν_eff`, `ω_out`, `R_in`, `d_c1`, `d_s1` (the gap's first-harmonic coefficients, eq. 20–21)
/// with their subscripts, a name between backticks as code. Never given text from the study
/// file (whose characters are shown as they are).
pub(crate) fn rich(text: &str) -> Text {
    const SUBSCRIPTED: [(&str, &str, &str); 7] = [
        ("C_r", "C", "r"),
        ("C_a", "C", "a"),
        ("ν_eff", "ν", "eff"),
        ("ω_out", "ω", "out"),
        ("R_in", "R", "in"),
        ("d_c1", "d", "c1"),
        ("d_s1", "d", "s1"),
    ];
    let mut runs = Vec::new();
    let mut plain = String::new();
    let parts: Vec<&str> = text.split('`').collect();
    let balanced = parts.len() % 2 == 1;
    for (n, part) in parts.iter().enumerate() {
        if balanced && n % 2 == 1 {
            if !plain.is_empty() {
                runs.push(Run::Plain(std::mem::take(&mut plain)));
            }
            runs.push(Run::Code((*part).to_owned()));
            continue;
        }
        if n > 0 && !balanced {
            plain.push('`');
        }
        let mut rest = *part;
        'scan: while !rest.is_empty() {
            for (symbol, base, sub) in SUBSCRIPTED {
                if let Some(after) = rest.strip_prefix(symbol) {
                    plain.push_str(base);
                    runs.push(Run::Plain(std::mem::take(&mut plain)));
                    runs.push(Run::Sub(sub.to_owned()));
                    rest = after;
                    continue 'scan;
                }
            }
            let c = rest.chars().next().unwrap_or(' ');
            plain.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    if !plain.is_empty() {
        runs.push(Run::Plain(plain));
    }
    match runs.as_slice() {
        [] => t(""),
        [Run::Plain(p)] => t(p.clone()),
        _ => Text::Runs(runs),
    }
}

/// Runs joined into one text.
fn runs(parts: Vec<Text>) -> Text {
    let mut out = Vec::new();
    for p in parts {
        match p {
            Text::Plain(s) if s.is_empty() => {}
            Text::Plain(s) => out.push(Run::Plain(s)),
            Text::Runs(r) => out.extend(r),
        }
    }
    Text::Runs(out)
}

/// A table; the cells of its numeric columns (numbers this tool wrote) have their minus
/// signs set as U+2212 ([`format::typographic_minus`]).
fn table(columns: &[&str], numeric: &[bool], widths: &[u32], rows: Vec<Vec<Text>>) -> Table {
    let rows = rows
        .into_iter()
        .map(|row| {
            row.into_iter()
                .enumerate()
                .map(|(n, cell)| {
                    if numeric.get(n).copied().unwrap_or(false) {
                        minus_signs(cell)
                    } else {
                        cell
                    }
                })
                .collect()
        })
        .collect();
    Table {
        columns: columns.iter().map(|c| rich(c)).collect(),
        numeric: numeric.to_vec(),
        widths: widths.to_vec(),
        rows,
    }
}

/// `text` with the minus signs of its numbers set as U+2212.
fn minus_signs(text: Text) -> Text {
    match text {
        Text::Plain(s) => Text::Plain(format::typographic_minus(&s)),
        Text::Runs(runs) => Text::Runs(
            runs.into_iter()
                .map(|r| match r {
                    Run::Plain(s) => Run::Plain(format::typographic_minus(&s)),
                    other => other,
                })
                .collect(),
        ),
    }
}

/// A value with its standard uncertainty `u` and its 95 % interval (widths `below`,
/// `above`), in one power of ten: value, u, U (or `+a / −b`), as cells.
fn value_u_expanded(value: f64, u: f64, below: f64, above: f64) -> [String; 3] {
    let a = format::interval(value, below, above);
    let scale_exp = a.exponent;
    let suffix = if a.scale.is_empty() {
        String::new()
    } else {
        format!(" {}", a.scale)
    };
    let u_text = format!("{}{suffix}", format::two_digits(u / 10f64.powi(scale_exp)));
    let expanded = if a.minus.is_empty() {
        format!("{}{suffix}", a.plus)
    } else {
        format!("+{}{suffix} / −{}{suffix}", a.plus, a.minus)
    };
    [format!("{}{suffix}", a.value), u_text, expanded]
}

/// The method's name.
const fn method_name(m: Method) -> &'static str {
    match m {
        Method::Probe => "probe method",
        Method::TwoOrientation => "two-orientation method",
    }
}

/// The mounting's short label for a table.
fn mounting_label(m: Option<&str>) -> &'static str {
    match m {
        Some("ia_in") => "IA in",
        Some("ia_out") => "IA out",
        _ => "both",
    }
}

/// The interval's origin, for the results table.
fn interval_from(method: HeadlineMethod, borderline: bool) -> &'static str {
    match (method, borderline) {
        (HeadlineMethod::Gum, _) => "GUM",
        (HeadlineMethod::MonteCarlo, false) => "Monte Carlo (GUM not validated)",
        (HeadlineMethod::MonteCarlo, true) => "Monte Carlo (GUM validation borderline)",
    }
}

/// The certificate's data.
pub(crate) fn build(
    results: &StudyResults,
    c: &CalibrationResults,
    info: &CertificateResults,
    provenance: Option<&Provenance>,
    software: &Software,
) -> CertificateData {
    let cert = certified::certified(results, c, &info.certified);
    let item = &info.item;
    CertificateData {
        id: running(&info.id),
        issued: calendar_date(&info.dates.issued),
        running: Running {
            left: running(&info.laboratory.name),
            right: running(&format!("Certificate {}", info.id)),
            foot: running(&format!(
                "{} {}, serial number {}",
                item.manufacturer, item.model, item.serial
            )),
        },
        // the head of page 1 (a grid, which cannot break across pages): at most 90
        // characters each, the identification table states them in full
        laboratory: Laboratory {
            name: running(&info.laboratory.name),
            address: running(&info.laboratory.address),
            accreditation: info.laboratory.accreditation.as_deref().map(running),
        },
        identification: identification(info, &results.study),
        serial: item.serial.clone(),
        certified: certified_section(&cert),
        results: results_table(&cert),
        results_notes: results_notes(&cert, c),
        compensation: (cert.method == Method::Probe)
            .then(|| compensation(c, &results.inputs.angle_zero)),
        sign_convention: (cert.method == Method::Probe).then(|| {
            t(format!(
                "Probe sign convention: {}.",
                probe_sign_words(c.probe_direction)
            ))
        }),
        check: results.two_orientation.as_ref().map(|s| check(s, &cert, c)),
        conformity: conformity(info),
        scope: "The results relate only to the item calibrated, as received, under the \
                conditions stated. This certificate shall not be reproduced except in full \
                without the written approval of the laboratory."
            .to_owned(),
        // beside the signature (a block kept on one page): at most 90 characters each, the
        // identification table states them in full
        authorisation: Authorisation {
            name: running(&info.authorisation.name),
            role: running(&info.authorisation.role),
            date: info.dates.issued.clone(),
        },
        method: method(results, info, &cert),
        conditions: info
            .conditions
            .iter()
            .map(|x| Field {
                label: x.quantity.clone(),
                value: x.value.clone(),
            })
            .collect(),
        equipment: table(
            &["role", "instrument", "identity", "calibration due"],
            &[false; 4],
            &[3, 5, 3, 2],
            info.equipment
                .iter()
                .map(|e| {
                    vec![
                        t(&e.role),
                        t(&e.description),
                        t(&e.identity),
                        t(&e.calibration_due),
                    ]
                })
                .collect(),
        ),
        traceability: traceability(info),
        budget: match (cert.method, &results.two_orientation) {
            (Method::TwoOrientation, Some(s)) => budget(
                &s.budget.k2,
                &s.k2,
                "Uncertainty budget of the certified k2, two-orientation method (JCGM 100)",
            ),
            _ => budget(
                &c.budget.k2,
                &c.coefficients.k2,
                "Uncertainty budget of the certified k2, probe method (JCGM 100)",
            ),
        },
        figure_caption: rich(if cert.method == Method::Probe {
            "Residuals of the PIGA's mean output about the fitted model (eq. 18), with the \
             standard uncertainty of each point as its error bar."
        } else {
            "Residuals of the PIGA's mean output in the IA-in mounting about the probe \
             method's fit (eq. 18, the check), with the standard uncertainty of each point as \
             its error bar."
        }),
        gum_against_mc: match (cert.method, &results.two_orientation) {
            (Method::TwoOrientation, Some(s)) => gum_against_mc_two_orientation(s),
            _ => gum_against_mc(c),
        },
        data_used: data_used(results, c),
        files: files(provenance, software),
        end: format!("End of certificate {}", info.id),
    }
}

/// `2026-11-24` as a calendar date (`None` for any other text).
fn calendar_date(text: &str) -> Option<CalendarDate> {
    let mut parts = text.trim().split('-');
    let (y, m, d) = (parts.next()?, parts.next()?, parts.next()?);
    if parts.next().is_some() || y.len() != 4 || m.len() != 2 || d.len() != 2 {
        return None;
    }
    let date = CalendarDate {
        year: y.parse().ok()?,
        month: m.parse().ok()?,
        day: d.parse().ok()?,
    };
    ((1..=12).contains(&date.month) && (1..=31).contains(&date.day)).then_some(date)
}

/// A running head's text: at most 90 characters (a longer one is cut, with `…`; the page
/// states it in full).
fn running(text: &str) -> String {
    const MAX: usize = 90;
    if text.chars().count() <= MAX {
        text.to_owned()
    } else {
        let mut cut: String = text.chars().take(MAX - 1).collect();
        cut.push('…');
        cut
    }
}

/// The identification fields; `study` is the study's name, the laboratory's reference of the
/// reduction (results.json holds it).
fn identification(info: &CertificateResults, study: &str) -> Vec<Field> {
    let item = &info.item;
    let field = |label: &str, value: String| Field {
        label: label.to_owned(),
        value,
    };
    let mut fields = vec![
        field("Certificate", info.id.clone()),
        field(
            "Issued by",
            match &info.laboratory.accreditation {
                Some(a) => format!("{}, {}; {a}", info.laboratory.name, info.laboratory.address),
                None => format!("{}, {}", info.laboratory.name, info.laboratory.address),
            },
        ),
        field(
            "Item",
            format!("{}, {} {}", item.description, item.manufacturer, item.model),
        ),
        field("Serial number", item.serial.clone()),
        field("Condition on receipt", item.condition.clone()),
        field(
            "Customer",
            format!("{}, {}", info.customer.name, info.customer.address),
        ),
        field("Place of calibration", info.location.clone()),
        field("Date of receipt", info.dates.received.clone()),
        field("Date(s) of measurement", info.dates.measured.clone()),
        field("Date of issue", info.dates.issued.clone()),
        field("Procedure", info.procedure.clone()),
        field("Study (laboratory reference)", study.to_owned()),
        field("Performed by", info.operator.clone()),
        field(
            "Authorised by",
            format!("{}, {}", info.authorisation.name, info.authorisation.role),
        ),
    ];
    if let Some(p) = &info.previous_certificate {
        fields.push(field(
            "Follows certificate",
            match &p.sha256 {
                Some(h) => format!("{} (SHA-256 of its file {h})", p.id),
                None => p.id.clone(),
            },
        ));
    }
    fields
}

fn certified_section(cert: &Certified) -> super::model::Certified {
    let name = method_name(cert.method);
    let mountings: Vec<&str> = cert
        .validity
        .iter()
        .map(|v| v.mounting_words.as_str())
        .collect();
    let statement = match cert.method {
        Method::Probe => format!(
            "This certificate states the coefficients of the {name} (Liu et al. 2025): the \
             PIGA mounted with its {}, k2 compensated for the spindle's radius growth C_r \
             measured by a displacement probe.",
            mountings.join(" and ")
        ),
        Method::TwoOrientation => format!(
            "This certificate states the coefficients of the {name} (Sun et al. 2022, with \
             the model of Liu et al. 2025): the PIGA measured with its {}, k2 and k3 shared by \
             the two mountings and free of the centrifuge's radius growth.",
            mountings.join(" and with its ")
        ),
    };
    let refuted = cert.refuted_by_check.then(|| {
        let other = cert
            .check
            .map_or("the other method", |k| method_name(k.method));
        rich(&format!(
            "The laboratory certifies a value that its own check refutes: the {other} \
             disagrees with the certified k2 beyond its uncertainty (|z| > 3, see the check \
             below). The certified values are stated because the laboratory chose the {name} \
             explicitly."
        ))
    });
    super::model::Certified {
        method: name.to_owned(),
        statement: rich(&statement),
        reason: t(&cert.reason),
        model: rich(
            "Model of the mean output rate: ω_out = k0 + k1·a + k2·a² + k3·a³, with a the \
             specific force along the input axis in g (a = R·ω²/g at the working radius R and \
             spindle rate ω).",
        ),
        refuted,
        validity: table(
            &[
                "mounting",
                "working radius R",
                "spindle rates",
                "specific force along the input axis",
                "points",
            ],
            &[false, true, true, true, true],
            &[5, 2, 3, 3, 1],
            cert.validity
                .iter()
                .map(|v| {
                    vec![
                        t(format!(
                            "{}: {}",
                            mounting_label(Some(v.mounting.as_str())),
                            v.mounting_words
                        )),
                        t(format!("{} m", format::plain(v.radius_m))),
                        t(format!(
                            "{} to {} deg/s",
                            format::rate(v.rate_low_deg_s),
                            format::rate(v.rate_high_deg_s)
                        )),
                        t(format!(
                            "{} g to {} g",
                            format::significant(v.specific_force_low_g, 3),
                            format::significant(v.specific_force_high_g, 3)
                        )),
                        t(v.points.to_string()),
                    ]
                })
                .collect(),
        ),
    }
}

fn results_table(cert: &Certified) -> Table {
    let several = cert
        .coefficients
        .iter()
        .filter_map(|c| c.mounting.as_deref())
        .any(|m| m == "ia_out");
    let mut rows = Vec::new();
    let row = |name: String, cells: [String; 3], k: String, dof: String, unit: &str, from: &str| {
        let [value, u, expanded] = cells;
        vec![
            rich(&name),
            t(value),
            t(u),
            t(expanded),
            t(k),
            t(dof),
            t(unit),
            t(from),
        ]
    };
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
        rows.push(row(
            label(c, ""),
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
            rows.push(row(
                label(c, "/k1"),
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
    table(
        &[
            "coefficient",
            "value",
            "standard uncertainty u",
            "expanded uncertainty U (95 %)",
            "k",
            "ν_eff",
            "unit",
            "95 % interval from",
        ],
        &[false, true, true, true, true, true, false, false],
        &[9, 12, 11, 14, 5, 6, 9, 12],
        rows,
    )
}

fn results_notes(cert: &Certified, c: &CalibrationResults) -> Vec<Text> {
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

fn compensation(c: &CalibrationResults, angle_zero: &pipeline::AngleZero) -> Table {
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
const fn probe_sign_words(sign: pipeline::ProbeSign) -> &'static str {
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

fn signed(z: f64) -> String {
    format!("{z:+.1}").replacen('-', "−", 1)
}

fn check(s: &TwoOrientationResults, cert: &Certified, c: &CalibrationResults) -> Check {
    let micro = 1e6 / c.coefficients.k1.value;
    let heads = headlines(c);
    let mountings: Vec<String> = s
        .mountings
        .iter()
        .map(|m| {
            format!(
                "{} ({}, R = {} m)",
                mounting_label(Some(&m.orientation)),
                certified::mounting_words(&m.orientation),
                format::plain(m.radius_m)
            )
        })
        .collect();
    let mut rows = Vec::new();
    let mut row =
        |name: &str, cells: [String; 3], k: String, dof: String, unit: &str, from: &str| {
            let [value, u, expanded] = cells;
            rows.push(vec![
                rich(name),
                t(value),
                t(u),
                t(expanded),
                t(k),
                t(dof),
                t(unit),
                t(from),
            ]);
        };
    let headline_cells = |h: &pipeline::Headline, u: f64, scale: f64| {
        let (b, a) = h.widths(scale);
        value_u_expanded(h.value * scale, u * scale.abs(), b, a)
    };
    let k_dof = |h: &pipeline::Headline, gum: &pipeline::Coefficient| {
        if h.method == HeadlineMethod::Gum {
            (format::coverage_factor(gum.k), format::dof(gum.dof))
        } else {
            ("—".to_owned(), "—".to_owned())
        }
    };
    let probe_is_certified = cert.method == Method::Probe;
    // the method not certified is marked so on each of its rows: a check, not certified
    let (probe_tag, two_tag) = if probe_is_certified {
        (
            "k2, probe method (certified)",
            "k2, two-orientation method (a check, not certified)",
        )
    } else {
        (
            "k2, probe method (a check, not certified)",
            "k2, two-orientation method (certified)",
        )
    };
    // k2 by the probe method: the calibration section's (the certified one when the probe
    // method is certified)
    let probe = &heads[2];
    let (k, dof) = k_dof(&probe.stated, &probe.gum);
    let from = interval_from(probe.stated.method, probe.stated.borderline);
    row(
        probe_tag,
        headline_cells(&probe.stated, probe.gum.u, 1.0),
        k.clone(),
        dof.clone(),
        "rad/(s·g²)",
        from,
    );
    row(
        &format!("{probe_tag}, relative to k1"),
        headline_cells(&probe.stated, probe.gum.u, micro),
        k,
        dof,
        "µg/g²",
        from,
    );
    let (k, dof) = k_dof(&s.headline.k2, &s.k2);
    let from = interval_from(s.headline.k2.method, s.headline.k2.borderline);
    row(
        two_tag,
        headline_cells(&s.headline.k2, s.k2.u, 1.0),
        k.clone(),
        dof.clone(),
        "rad/(s·g²)",
        from,
    );
    row(
        &format!("{two_tag}, relative to k1"),
        headline_cells(&s.headline.k2, s.k2.u, micro),
        k,
        dof,
        "µg/g²",
        from,
    );
    let (k, dof) = k_dof(&s.headline.c, &s.c_m_s2);
    row(
        "C, total radius growth (PIGA alone)",
        headline_cells(&s.headline.c, s.c_m_s2.u, 1e6),
        k,
        dof,
        "10⁻⁶ m·s²",
        interval_from(s.headline.c.method, s.headline.c.borderline),
    );
    let mut verdict = rich("No probe phase was compared with the two-orientation fit.");
    let mut disagrees = false;
    if let Some(p) = &s.probe {
        let cr = format::pair(p.c_r_m_s2.value * 1e6, p.c_r_m_s2.u * 1e6);
        row(
            "C_r, spindle growth (probe)",
            [cr.value.clone(), cr.u.clone(), "—".to_owned()],
            "—".to_owned(),
            "—".to_owned(),
            "10⁻⁶ m·s²",
            "probe phase (standard uncertainty only)",
        );
        let d = &p.difference_m_s2;
        let stated = match &s.monte_carlo.difference {
            Some(mc) => pipeline::Headline::of(d, mc),
            None => pipeline::Headline {
                value: d.value,
                low95: d.value - d.u95,
                high95: d.value + d.u95,
                method: HeadlineMethod::Gum,
                borderline: false,
            },
        };
        let (k, dof) = k_dof(&stated, d);
        row(
            "C − C_r, growth the probe misses",
            headline_cells(&stated, d.u, 1e6),
            k,
            dof,
            "10⁻⁶ m·s²",
            interval_from(stated.method, stated.borderline),
        );
        // k2_difference is the two-orientation k2 less the probe method's
        let excess = -p.k2_difference;
        let above = if excess >= 0.0 { "above" } else { "below" };
        let native = format::significant(excess.abs(), 2);
        let relative = format::significant(excess.abs() * micro, 2);
        disagrees = !p.agrees;
        verdict = rich(&if p.agrees {
            format!(
                "z = (C − C_r)/u(C − C_r) = {z}, within ±3: the radius growth the PIGA \
                 measures agrees with the probe's, and the probe method's compensation is \
                 confirmed by the PIGA's own output (the probe method's k2 lies {above} the \
                 two-orientation k2 by {native} rad/(s·g²), {relative} µg/g²).",
                z = signed(p.z)
            )
        } else {
            format!(
                "The two methods disagree: z = (C − C_r)/u(C − C_r) = {z}, beyond ±3. Either \
                 the probe is declared wrongly — the encoder's angle zero relative to the arm, \
                 the probe's sign convention or its gap unit (each changes C_r with no other \
                 sign) — or, those right, the working radius grows in a way the probe does not \
                 see (the arm stretching under centrifugal load, a mount that gives) or the \
                 lever heights are wrong. The probe method's k2 is \
                 compensated with the probe's C_r only and keeps k1·(C − C_r)·g/R²: it lies \
                 {above} the two-orientation k2 by {native} rad/(s·g²) ({relative} µg/g²){which}.",
                z = signed(p.z),
                which = if probe_is_certified {
                    "; it is certified only because the laboratory chose the probe method \
                     explicitly"
                } else {
                    "; the two-orientation k2 is the one certified"
                }
            )
        });
    }
    let heading = if probe_is_certified {
        "Check by the two-orientation method (not certified)"
    } else {
        "Check by the probe method (not certified)"
    };
    Check {
        heading: heading.to_owned(),
        intro: rich(&if probe_is_certified {
            format!(
                "The PIGA was also measured with its input axis turned round — {} — and both \
                 data sets fitted jointly (eq. 23; Sun et al. 2022), as a check, not certified. Turning the input axis \
                 round reverses the sign of the radius growth's term in the output but not that \
                 of k2·a²: the joint fit gives k2 and the total dynamic growth C of the working \
                 radius from the PIGA's own output, without the displacement probe. Sign \
                 convention: the working radius is R + C·ω², C and C_r positive when the radius \
                 grows with the rate; C − C_r > 0 when the PIGA sees more growth than the probe.",
                mountings.join("; ")
            )
        } else {
            format!(
                "The certified coefficients come from both mountings — {} — fitted jointly \
                 (eq. 23; Sun et al. 2022), which gives k2 and the total dynamic growth C of the \
                 working radius from the PIGA's own output. The probe method checks them (its \
                 values below are a check, not certified): the IA-in data alone, fitted by \
                 eq. 18 and compensated for the spindle's radius growth C_r measured by a \
                 displacement probe (Liu et al. 2025). The two agree \
                 when the probe sees all the growth, C − C_r = 0. Sign convention: the working \
                 radius is R + C·ω², C and C_r positive when the radius grows with the rate; \
                 C − C_r > 0 when the PIGA sees more growth than the probe.",
                mountings.join("; ")
            )
        }),
        table: table(
            &[
                "quantity",
                "value",
                "standard uncertainty u",
                "expanded uncertainty U (95 %)",
                "k",
                "ν_eff",
                "unit",
                "95 % interval from",
            ],
            &[false, true, true, true, true, true, false, false],
            &[16, 11, 10, 12, 5, 6, 8, 10],
            rows,
        ),
        verdict,
        disagrees,
    }
}

fn conformity(info: &CertificateResults) -> Option<Conformity> {
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

fn traceability(info: &CertificateResults) -> Table {
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
                    t(input_unit(&x.input).unwrap_or("—")),
                    t(&x.statement),
                ]
            })
            .collect(),
    )
}

/// The unit of a budget's input quantity, by the name the budget gives it (`None` for a name
/// this table does not know: a test checks that every input of the fixtures has one).
pub(crate) fn input_unit(quantity: &str) -> Option<&'static str> {
    Some(match quantity {
        "R (working radius)" => "m",
        "g (gravity)" => "m/s²",
        "rate scale (common to every rate)" | "probe gain" => "1 (relative)",
        "pivot-to-probe height" | "probe-to-PIGA height" => "mm",
        q if q.starts_with("R of the IA-") => "m",
        "C_r of the compensating phase" => "m·s²",
        "k1 (given)" => "rad/(s·g)",
        // Ω·sin L, the Earth rate's component along the spindle axis (two orientations)
        q if q.starts_with("Earth rate about the spindle axis") => "rad/s",
        // the fit's coefficients as one correlated group: its contribution, sensitivity 1
        q if q.starts_with("PIGA mean outputs") => "rad/(s·g²)",
        _ => return None,
    })
}

/// A nominal value as a person writes it: six significant digits at most, trailing zeros
/// dropped (`2.5`, `700`, `1`, `1.60009 × 10⁻⁶`).
fn nominal(x: f64) -> String {
    let text = format::significant(x, 6);
    let (mantissa, scale) = text
        .split_once(' ')
        .map_or((text.as_str(), ""), |(m, rest)| (m, rest));
    let mantissa = if mantissa.contains('.') {
        mantissa.trim_end_matches('0').trim_end_matches('.')
    } else {
        mantissa
    };
    if scale.is_empty() {
        mantissa.to_owned()
    } else {
        format!("{mantissa} {scale}")
    }
}

fn budget(lines: &[pipeline::BudgetLine], k2: &pipeline::Coefficient, heading: &str) -> Budget {
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
                t(input_unit(&l.quantity).unwrap_or("—")),
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

/// Writes the ends of a coefficient's GUM and Monte Carlo intervals in one power of ten (the
/// value's) and to the decimal place of the tolerance δ they are compared against.
struct EndsWriter {
    exponent: i32,
    decimals: usize,
}

impl EndsWriter {
    fn new(value: f64, tolerance: f64) -> Self {
        let exp_of = |x: f64| {
            if x == 0.0 || !x.is_finite() {
                0
            } else {
                // |x| < 1e308: the floor fits an i32
                x.abs().log10().floor() as i32
            }
        };
        let e = exp_of(value);
        let exponent = if (-2..5).contains(&e) { 0 } else { e };
        let place = if tolerance > 0.0 {
            exp_of(tolerance)
        } else {
            exponent - 6
        };
        let decimals = usize::try_from((exponent - place).clamp(0, 12)).unwrap_or(0);
        Self { exponent, decimals }
    }

    fn interval(&self, low: f64, high: f64) -> String {
        let s = 10f64.powi(self.exponent);
        let (a, b) = (
            format::fixed(low / s, self.decimals),
            format::fixed(high / s, self.decimals),
        );
        if self.exponent == 0 {
            format!("[{a}, {b}]")
        } else {
            format!("[{a}, {b}] × {}", format::power_of_ten(self.exponent))
        }
    }
}

fn gum_against_mc(c: &CalibrationResults) -> Section {
    let mc = &c.monte_carlo;
    let heads = headlines(c);
    let rows = [
        (&c.coefficients.k0, &mc.k0),
        (&c.coefficients.k1, &mc.k1),
        (&c.coefficients.k2, &mc.k2),
        (&c.coefficients.k3, &mc.k3),
    ]
    .into_iter()
    .enumerate()
    .map(|(n, (g, m))| {
        let ends = EndsWriter::new(g.value, m.tolerance);
        vec![
            t(crate::headline::NAMES[n]),
            t(ends.interval(g.value - g.u95, g.value + g.u95)),
            t(ends.interval(m.low95, m.high95)),
            t(format::significant(m.d_low.max(m.d_high), 2)),
            t(format::significant(m.tolerance, 2)),
            t(heads[n].verdict_words()),
            t(crate::headline::UNITS[n]),
        ]
    })
    .collect();
    Section {
        heading: "GUM against Monte Carlo (JCGM 101 §8)".to_owned(),
        intro: rich(&format!(
            "{} trials (adaptive, JCGM 101 §7.9), seed {}. The GUM interval is validated when \
             both its ends lie within the numerical tolerance δ of the Monte Carlo interval's.",
            mc.trials, mc.seed
        )),
        table: table(
            &[
                "coefficient",
                "GUM 95 % interval",
                "Monte Carlo 95 % interval",
                "largest end difference",
                "δ",
                "verdict",
                "unit",
            ],
            &[false, true, true, true, true, false, false],
            &[4, 10, 10, 5, 4, 8, 5],
            rows,
        ),
    }
}

fn gum_against_mc_two_orientation(s: &TwoOrientationResults) -> Section {
    let mc = &s.monte_carlo;
    let rows = [
        ("k2", &s.k2, &mc.k2, s.headline.k2, "rad/(s·g²)"),
        ("k3", &s.k3, &mc.k3, s.headline.k3, "rad/(s·g³)"),
        ("C", &s.c_m_s2, &mc.c, s.headline.c, "m·s²"),
    ]
    .into_iter()
    .map(|(name, g, m, head, unit)| {
        let ends = EndsWriter::new(g.value, m.tolerance);
        let h = crate::headline::Headline {
            stated: head,
            gum: *g,
        };
        vec![
            t(name),
            t(ends.interval(g.value - g.u95, g.value + g.u95)),
            t(ends.interval(m.low95, m.high95)),
            t(format::significant(m.d_low.max(m.d_high), 2)),
            t(format::significant(m.tolerance, 2)),
            t(h.verdict_words()),
            t(unit),
        ]
    })
    .collect();
    Section {
        heading: "GUM against Monte Carlo, two-orientation method (JCGM 101 §8)".to_owned(),
        intro: rich(&format!(
            "{} trials (adaptive, JCGM 101 §7.9), seed {}. The GUM interval is validated when \
             both its ends lie within the numerical tolerance δ of the Monte Carlo interval's. \
             Each mounting's k0 and k1 are stated with their GUM interval.",
            mc.trials, mc.seed
        )),
        table: table(
            &[
                "coefficient",
                "GUM 95 % interval",
                "Monte Carlo 95 % interval",
                "largest end difference",
                "δ",
                "verdict",
                "unit",
            ],
            &[false, true, true, true, true, false, false],
            &[4, 10, 10, 5, 4, 8, 5],
            rows,
        ),
    }
}

fn data_used(results: &StudyResults, c: &CalibrationResults) -> DataUsed {
    let mut paragraphs = Vec::new();
    if let Some(p) = results.phase(&c.compensate_with) {
        let revolutions: usize = p.points.iter().filter_map(|q| q.revolutions).sum();
        let rates: Vec<String> = p
            .points
            .iter()
            .map(|q| format::rate(q.rate_deg_s))
            .collect();
        paragraphs.push(runs(vec![
            t("Displacement probe (phase “"),
            t(&p.name),
            rich(&format!(
                "”): {} rates, {} deg/s{}; C_r from the fit of {} with {} degrees of freedom.",
                p.points.len(),
                rates.join(", "),
                if revolutions > 0 {
                    format!("; {revolutions} whole revolutions of probe recording")
                } else {
                    String::new()
                },
                pipeline::model_name(p.fit.model).replace('`', ""),
                p.fit.dof,
            )),
        ]));
    }
    let rates: Vec<String> = {
        let mut r: Vec<f64> = c.residuals.iter().map(|x| x.rate_deg_s).collect();
        r.sort_by(f64::total_cmp);
        r.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        r.iter().map(|x| format::rate(*x)).collect()
    };
    paragraphs.push(runs(vec![
        t("PIGA"),
        c.table
            .as_ref()
            .map_or_else(|| t(""), |x| runs(vec![t(" (table "), t(x), t(")")])),
        rich(&format!(
            ": {} points at {} distinct rates ({} deg/s), {} residual degrees of freedom; \
             residual standard deviation {} rad/s; {}.",
            c.points,
            c.distinct_rates,
            rates.join(", "),
            c.dof,
            format::significant(c.residual_sd_rad_s, 2),
            if c.weighted {
                "weighted by each point's standard uncertainty"
            } else {
                "unweighted"
            }
        )),
    ]));
    let recordings = (!c.recordings.is_empty()).then(|| {
        table(
            &[
                "rate (deg/s)",
                "spindle angle from",
                "revolutions",
                "dropped",
                "mean output (rad/s)",
                "standard uncertainty u (rad/s)",
            ],
            &[true, false, true, true, true, true],
            &[3, 4, 3, 3, 5, 5],
            c.recordings
                .iter()
                .map(|r| {
                    vec![
                        t(format::rate(r.rate_deg_s)),
                        t(angle_source_words(&r.angle_source)),
                        t(r.revolutions.to_string()),
                        t(r.dropped_revolutions.to_string()),
                        t(format::significant(r.output_rad_s, 9)),
                        t(format::significant(r.u_rad_s, 2)),
                    ]
                })
                .collect(),
        )
    });
    if let Some(s) = &results.two_orientation {
        let mountings: Vec<String> = s
            .mountings
            .iter()
            .map(|m| {
                format!(
                    "{} at R = {} m, {} points at {} distinct rates",
                    mounting_label(Some(&m.orientation)),
                    format::plain(m.radius_m),
                    m.points,
                    m.distinct_rates
                )
            })
            .collect();
        paragraphs.push(rich(&format!(
            "Two-orientation fit: {}; the joint fit has {} residual degrees of freedom and a \
             residual standard deviation of {} rad/s.",
            mountings.join("; "),
            s.dof,
            format::significant(s.residual_sd_rad_s, 2)
        )));
    }
    // the disagreement of the probe with the two-orientation fit is the check's verdict,
    // stated there in a customer's words (the warning names the study file's fields)
    let warnings = results
        .warnings
        .iter()
        .filter(|w| w.code != pipeline::WarningCode::ProbeDisagrees)
        .map(|w| rich(&w.message))
        .chain(c.warnings.iter().map(|w| rich(w)))
        .collect();
    DataUsed {
        paragraphs,
        recordings,
        warnings,
    }
}

/// Where a recording's spindle angle comes from, in words.
fn angle_source_words(source: &str) -> String {
    match source {
        "encoder" => "encoder".to_owned(),
        "index_pulse" => "index pulse".to_owned(),
        "declared_rate" => "declared rate".to_owned(),
        other => other.replace('_', " "),
    }
}

fn files(provenance: Option<&Provenance>, software: &Software) -> Files {
    let Some(provenance) = provenance else {
        return Files {
            missing: Some(t(
                "The input files and their SHA-256 digests were not recorded with these results.",
            )),
            table: None,
            software: software.version.clone(),
            commit: software.commit.clone(),
        };
    };
    // a file read by two sections (the IA-in table by the calibration and the two-orientation
    // fit) is listed once
    let mut listed: Vec<(String, String)> = Vec::new();
    let mut rows = Vec::new();
    let mut record = |what: &str, f: &FileRecord| {
        let key = (f.path.clone(), f.sha256.clone());
        if listed.contains(&key) {
            return;
        }
        listed.push(key);
        rows.push(vec![
            t(what),
            t(&f.path),
            t(f.bytes.to_string()),
            t(&f.sha256),
        ]);
    };
    record("study file", &provenance.config);
    if let Some(p) = &provenance.profile {
        record("lab profile", p);
    }
    for f in &provenance.inputs {
        record(role_words(f.role.as_deref()), f);
    }
    if let Some(e) = &provenance.expected {
        record("expected values", e);
    }
    Files {
        missing: None,
        table: Some(table(
            &["file", "path", "bytes", "SHA-256"],
            &[false, false, true, false],
            &[3, 9, 2, 9],
            rows,
        )),
        software: software.version.clone(),
        commit: software.commit.clone(),
    }
}

/// A data file's role in words.
fn role_words(role: Option<&str>) -> &'static str {
    match role {
        Some("probe_recording") => "probe recording",
        Some("piga_table") => "PIGA table",
        Some("piga_recording") => "PIGA recording",
        _ => "data file",
    }
}

fn method(
    results: &StudyResults,
    info: &CertificateResults,
    cert: &Certified,
) -> super::model::Method {
    let mut paragraphs = vec![rich(&format!(
        "The PIGA is mounted on the centrifuge arm at the working radius R = {} m with its \
         input axis towards the spindle axis, and calibrated at the rates stated under “What \
         is certified”; at each rate its mean output rate over whole spindle revolutions is \
         measured (IEEE Std 836). The centrifuge's dynamic imbalance makes the working radius \
         grow as C_r·ω², which adds k1·C_r·ω⁴/g to the output (Liu et al. 2025, eq. 17): \
         indistinguishable by least squares from k2·a², it would appear as a \
         pseudo-second-order term Δk2 = k1·C_r·g/R² (eq. 19). C_r is measured by a \
         displacement probe on the spindle (first harmonic of the gap per revolution, eq. \
         20–22) and the term removed. The coefficients are the least-squares solution of eq. \
         18 (columns 1, ω, ω², ω³, a², a³), through QR with column scaling; the terms in ω \
         and ω³ are nuisance terms of the set-up.",
        format::plain(results.inputs.radius_m)
    ))];
    if results.two_orientation.is_some() {
        paragraphs.push(rich(
            "The two-orientation method (Sun et al. 2022) fits the mean outputs of both \
             mountings (IA in and IA out) jointly (eq. 23): a bias k0, a scale factor k1 and an \
             ω term per mounting; k2, k3, an ω³ term and the radius growth's term γ = k1·C/g \
             shared, γ with the sign of the mounting. C − C_r is compared with its standard \
             uncertainty: |z| = |C − C_r|/u(C − C_r) above 3 is a disagreement.",
        ));
    }
    paragraphs.push(rich(&format!(
        "Uncertainties are evaluated by the GUM (JCGM 100) through the whole measurement \
         model and checked by the Monte Carlo method (JCGM 101); the certified values are \
         those of the {}. Statements of conformity follow ILAC-G8:09/2019.",
        method_name(cert.method)
    )));
    super::model::Method {
        paragraphs,
        deviations: info.deviations.clone(),
        references: [
            "Liu Y., Zhang C., He D., Yu Z., Ren S. (2025), The mechanism of PIGA's \
             pseudo-second-order term generated by spindle dynamic imbalance of centrifuge, \
             Navigation Positioning and Timing, doi:10.19306/j.cnki.2095-8110.2025.01.013 \
             (eq. 17–22).",
            "Sun, Ren, Cao, Huo (2022), Measurement: calibration with the input axis in two \
             orientations on a centrifuge (eq. 23).",
            "IEEE Std 836-2009, Recommended Practice for Precision Centrifuge Testing of Linear \
             Accelerometers.",
            "JCGM 100:2008, Evaluation of measurement data — Guide to the expression of \
             uncertainty in measurement (GUM).",
            "JCGM 101:2008, Evaluation of measurement data — Supplement 1 to the GUM — \
             Propagation of distributions using a Monte Carlo method.",
            "ILAC-G8:09/2019, Guidelines on Decision Rules and Statements of Conformity.",
            "ISO/IEC 17025:2017, General requirements for the competence of testing and \
             calibration laboratories, §7.8.",
        ]
        .into_iter()
        .map(t)
        .collect(),
    }
}
