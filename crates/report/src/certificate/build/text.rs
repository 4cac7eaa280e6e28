//! The certificate's words and cells: text runs with their symbols set, tables, a value
//! with its uncertainties in one power of ten, and the short labels every part uses.

use pipeline::HeadlineMethod;

use super::super::certified::Method;
use super::super::model::{CalendarDate, Run, Table, Text};
use crate::format;

/// A plain text run.
pub(super) fn t(text: impl Into<String>) -> Text {
    Text::Plain(text.into())
}

/// Text written by this tool, with its symbols set as a person writes them: `C_r`, `C_a`,
/// `ν_eff`, `ω_out`, `R_in`, `d_c1`, `d_s1` (the gap's first-harmonic coefficients, eq. 20–21)
/// with their subscripts, a name between backticks as code. Never given text from the study
/// file (whose characters are shown as they are).
pub(super) fn rich(text: &str) -> Text {
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
pub(super) fn runs(parts: Vec<Text>) -> Text {
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
pub(super) fn table(
    columns: &[&str],
    numeric: &[bool],
    widths: &[u32],
    rows: Vec<Vec<Text>>,
) -> Table {
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

/// A table of values with their 95 % intervals (the results, the check): `first` names
/// what each row is, then the value, u, U, k, ν_eff, the unit and where the interval comes
/// from; rows by [`interval_row`].
pub(super) fn interval_table(first: &str, widths: &[u32], rows: Vec<Vec<Text>>) -> Table {
    table(
        &[
            first,
            "value",
            "standard uncertainty u",
            "expanded uncertainty U (95 %)",
            "k",
            "ν_eff",
            "unit",
            "95 % interval from",
        ],
        &[false, true, true, true, true, true, false, false],
        widths,
        rows,
    )
}

/// A row of an [`interval_table`]: the quantity, its value, u and U as cells, k,
/// ν_eff, the unit and where the interval comes from.
pub(super) fn interval_row(
    name: &str,
    cells: [String; 3],
    k: String,
    dof: String,
    unit: &str,
    from: &str,
) -> Vec<Text> {
    let [value, u, expanded] = cells;
    vec![
        rich(name),
        t(value),
        t(u),
        t(expanded),
        t(k),
        t(dof),
        t(unit),
        t(from),
    ]
}

/// A value with its standard uncertainty `u` and its 95 % interval (widths `below`,
/// `above`), in one power of ten: value, u, U (or `+a / −b`), as cells.
pub(super) fn value_u_expanded(value: f64, u: f64, below: f64, above: f64) -> [String; 3] {
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
pub(super) const fn method_name(m: Method) -> &'static str {
    match m {
        Method::Probe => "probe method",
        Method::TwoOrientation => "two-orientation method",
    }
}

/// The mounting's short label for a table.
pub(super) fn mounting_label(m: Option<&str>) -> &'static str {
    match m {
        Some("ia_in") => "IA in",
        Some("ia_out") => "IA out",
        _ => "both",
    }
}

/// The interval's origin, for the results table.
pub(super) fn interval_from(method: HeadlineMethod, borderline: bool) -> &'static str {
    match (method, borderline) {
        (HeadlineMethod::Gum, _) => "GUM",
        (HeadlineMethod::MonteCarlo, false) => "Monte Carlo (GUM not validated)",
        (HeadlineMethod::MonteCarlo, true) => "Monte Carlo (GUM validation borderline)",
    }
}

pub(super) fn signed(z: f64) -> String {
    format!("{z:+.1}").replacen('-', "−", 1)
}

/// A nominal value as a person writes it: six significant digits at most, trailing zeros
/// dropped (`2.5`, `700`, `1`, `1.60009 × 10⁻⁶`).
pub(super) fn nominal(x: f64) -> String {
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

/// A running head's text: at most 90 characters (a longer one is cut, with `…`; the page
/// states it in full).
pub(super) fn running(text: &str) -> String {
    const MAX: usize = 90;
    if text.chars().count() <= MAX {
        text.to_owned()
    } else {
        let mut cut: String = text.chars().take(MAX - 1).collect();
        cut.push('…');
        cut
    }
}

/// `2026-11-24` as a calendar date (`None` for any other text).
pub(super) fn calendar_date(text: &str) -> Option<CalendarDate> {
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
