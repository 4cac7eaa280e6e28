//! A PIGA table's settings in the study file (`calibration.table`): the plain column keys for
//! a table as documented (a delimiter, rates in deg/s, outputs in rad/s), else a `format`
//! block — `recording`'s PIGA-table format, which the study and `identify` read alike — for
//! an export with a decimal comma, lines above the header or other rate units.

use recording::RateUnit;

use super::columns::{Column, Role};
use super::setting::{Setting, quoted, unit_words};
use super::sniff::{Delim, Layout};

/// A rate unit in a reader's words.
fn words(unit: RateUnit) -> &'static str {
    match unit {
        RateUnit::DegS => "deg/s",
        RateUnit::RadS => "rad/s",
        RateUnit::Rpm => "rpm",
        RateUnit::DegH => "deg/h",
    }
}

/// A column's unit: the one its header states, or `documented` when it states none (said
/// in the evidence); `None` (with a problem) for a header stating a unit that is no rate.
fn unit_of(
    problems: &mut Vec<String>,
    c: &Column,
    documented: RateUnit,
) -> Option<(RateUnit, String)> {
    // The unit as init read it from the name (`rate_deg_s`, `Drehrate [°/s]`), in the
    // reader's own words for units.
    let stated = c
        .unit
        .as_deref()
        .and_then(|u| RateUnit::in_header(&format!("[{u}]")));
    match (&c.unit, stated) {
        (_, Some(unit)) => Some((unit, unit_words(c))),
        (None, None) => Some((
            documented,
            format!(
                " (no unit in the header: {} as documented; change `unit` if it is not)",
                words(documented)
            ),
        )),
        (Some(u), None) => {
            problems.push(format!(
                "column `{}`: unit `{u}` is not a rate unit the study reads (deg/s, rad/s, \
                 rpm, deg/h)",
                c.name
            ));
            None
        }
    }
}

/// The table's settings (`calibration.table`) added to `format` (which holds the delimiter,
/// decimal and skip_lines settings), what stops it added to `problems`; whether they go in
/// a `format` block.
pub(super) fn table(
    format: &mut Vec<Setting>,
    problems: &mut Vec<String>,
    columns: &[Column],
    layout: &Layout,
) -> bool {
    let pick = |role: Role| columns.iter().find(|c| c.role == role);
    let (Some(rate), Some(output)) = (pick(Role::Rate), pick(Role::Output)) else {
        return false;
    };
    let sigma = pick(Role::Sigma);
    // A column of text (a repeat, an orientation) labels the rows.
    let label = (0..layout.header.len())
        .find(|&i| {
            layout
                .rows
                .iter()
                .all(|r| r.get(i).is_some_and(Option::is_none))
        })
        .map(|i| layout.header[i].clone());
    let rate_unit = unit_of(problems, rate, RateUnit::DegS);
    let output_unit = unit_of(problems, output, RateUnit::RadS);
    let sigma_unit = sigma.map(|s| unit_of(problems, s, RateUnit::RadS));
    let (Some((rate_unit, rate_why)), Some((output_unit, output_why))) = (rate_unit, output_unit)
    else {
        return false;
    };
    let sigma_unit = match sigma_unit {
        Some(None) => return false,
        Some(Some(u)) => Some(u),
        None => None,
    };
    let block = layout.decimal_comma
        || layout.skip_lines > 0
        || rate_unit != RateUnit::DegS
        || output_unit != RateUnit::RadS
        || sigma_unit
            .as_ref()
            .is_some_and(|(u, _)| *u != RateUnit::RadS);
    format.retain(|s| {
        s.ron.starts_with("delimiter")
            || s.ron.starts_with("decimal")
            || s.ron.starts_with("skip_lines")
    });
    if block {
        // The exported table as it is: `format: (…)`, columns with their units.
        format.push(Setting::new(
            format!(
                "rate: (column: {}, unit: {})",
                quoted(&rate.name),
                rate_unit.key()
            ),
            format!("the rate column{rate_why}"),
        ));
        format.push(Setting::new(
            format!(
                "output: (column: {}, unit: {})",
                quoted(&output.name),
                output_unit.key()
            ),
            format!("the mean-output column{output_why}"),
        ));
        if let (Some(s), Some((unit, why))) = (sigma, &sigma_unit) {
            format.push(Setting::new(
                format!("sigma: (column: {}, unit: {})", quoted(&s.name), unit.key()),
                format!("each output's standard uncertainty{why}: the fit is weighted by it"),
            ));
        }
        if let Some(l) = &label {
            format.push(Setting::new(
                format!("label: {}", quoted(l)),
                "a text column: each row's label (rows of one label are compared)",
            ));
        }
        return true;
    }
    // The plain keys: a delimiter and the column names (rates in deg/s, outputs in rad/s).
    if layout.delimiter == Delim::Whitespace {
        for s in format.iter_mut().filter(|s| s.ron.starts_with("delimiter")) {
            *s = Setting::new(
                "delimiter: ' '",
                "fields separated by blanks (a blank delimiter means runs of blanks)",
            );
        }
    }
    format.push(Setting::new(
        format!("rate_column: {}", quoted(&rate.name)),
        format!("the rate column{rate_why}"),
    ));
    format.push(Setting::new(
        format!("output_column: {}", quoted(&output.name)),
        format!("the mean-output column{output_why}"),
    ));
    if let Some(s) = sigma {
        format.push(Setting::new(
            format!("sigma_column: {}", quoted(&s.name)),
            "each output's standard uncertainty: the fit is weighted by it",
        ));
    }
    if let Some(l) = &label {
        format.push(Setting::new(
            format!("label_column: {}", quoted(l)),
            "a text column: each row's label (rows of one label are compared)",
        ));
    }
    false
}
