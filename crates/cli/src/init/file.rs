//! One lab file understood: what it is (a probe recording, a PIGA table, a raw PIGA output
//! recording), its format as the study file writes it, its rate, and for each guess the
//! evidence; or what could not be understood and what is needed. Works on the file's bytes.

use std::path::{Path, PathBuf};

use super::columns::{Column, Role, angle_unit, is_voltage, length_unit, time_unit};
use super::rate::{pulse_rate_deg_s, rate_from_name, slope_deg_s, unwrap_rad};
pub(crate) use super::setting::{PLACEHOLDER, Setting, quoted};
use super::sniff::{Delim, Layout, sniff};

/// What a file is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Probe gap against time: a phase's recording.
    Probe,
    /// PIGA mean outputs against rate: the calibration's table.
    PigaTable,
    /// PIGA output angle against time: one of the calibration's recordings.
    PigaRecording,
}

impl Kind {
    /// The kind in words.
    pub(crate) fn words(self) -> &'static str {
        match self {
            Self::Probe => "probe recording",
            Self::PigaTable => "PIGA table",
            Self::PigaRecording => "PIGA output recording",
        }
    }
}

/// A file's rate, deg/s, with its evidence.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Rate {
    /// The rate written in the study file, deg/s.
    pub(crate) deg_s: f64,
    /// Where it comes from.
    pub(crate) evidence: String,
    /// Measured from the data (encoder or index pulse), deg/s.
    pub(crate) measured: Option<f64>,
}

/// What `init` found in one file.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Finding {
    /// The file, as given or found in the folder.
    pub(crate) path: PathBuf,
    /// What the file is, if recognised.
    pub(crate) kind: Option<Kind>,
    /// The text layout, for text files.
    pub(crate) layout: Option<Layout>,
    /// The format's settings in the study file's order (delimiter, decimal, skip_lines,
    /// columns, angle), each with its evidence.
    pub(crate) format: Vec<Setting>,
    /// The angle reference in words (for the table).
    pub(crate) angle_words: String,
    /// The rate, when one applies and could be found.
    pub(crate) rate: Option<Rate>,
    /// What stops this file from being used (then no configuration is written).
    pub(crate) problems: Vec<String>,
    /// A PIGA table whose settings go in a `format` block (decimal comma, lines above the
    /// header, units other than deg/s and rad/s) rather than the plain column keys.
    pub(crate) table_block: bool,
}

impl Finding {
    pub(crate) fn new(path: &Path) -> Self {
        Self {
            path: path.to_path_buf(),
            kind: None,
            layout: None,
            format: Vec::new(),
            angle_words: String::new(),
            rate: None,
            problems: Vec::new(),
            table_block: false,
        }
    }

    /// The format block, `(key: value, ...)`, as one line.
    pub(crate) fn format_ron(&self) -> String {
        let parts: Vec<&str> = self.format.iter().map(|s| s.ron.as_str()).collect();
        format!("({})", parts.join(", "))
    }

    /// The settings that are placeholders.
    pub(crate) fn placeholders(&self) -> impl Iterator<Item = &Setting> {
        self.format.iter().filter(|s| s.is_placeholder())
    }
}

/// Every value of column `index` of the file's data rows, read in full by the sniffed
/// layout (`None`: a field that is not a number).
pub(crate) type ColumnReader<'a> = dyn Fn(&Layout, &str) -> Result<Vec<f64>, String> + 'a;

/// Understands one delimited-text file from its bytes; `read_column` reads a whole column by
/// header name with the sniffed layout (the recording crate's table reader, at the edge).
/// TDMS and MAT files go to [`super::binary`] instead ([`super::understand`] chooses).
pub(crate) fn understand(path: &Path, bytes: &[u8], read_column: &ColumnReader<'_>) -> Finding {
    let mut f = Finding::new(path);
    let layout = match sniff(bytes) {
        Ok(l) => l,
        Err(e) => {
            f.problems.push(format!("unknown shape: the file {e}"));
            return f;
        }
    };
    let columns: Vec<Column> = layout.header.iter().map(|n| Column::of(n)).collect();
    let find = |role: Role| columns.iter().position(|c| c.role == role);
    let (time, gap, output, rate) = (
        find(Role::Time),
        find(Role::Gap),
        find(Role::Output),
        find(Role::Rate),
    );
    f.kind = match (time, gap, output, rate) {
        (Some(_), _, Some(_), _) => Some(Kind::PigaRecording),
        (Some(_), Some(_), None, _) => Some(Kind::Probe),
        (None, _, Some(_), Some(_)) => Some(Kind::PigaTable),
        _ => None,
    };
    let Some(kind) = f.kind else {
        f.problems.push(format!(
            "unknown shape: the header `{}` names no time and gap columns (a probe \
             recording), no time and output columns (a PIGA output recording) and no rate \
             and output columns (a PIGA table); name them, e.g. `time [s]`, `gap [um]`, \
             `angle [deg]`",
            layout.header.join(&layout.delimiter_text())
        ));
        f.layout = Some(layout);
        return f;
    };
    f.format.push(Setting::new(
        format!("delimiter: {}", layout.delimiter.ron()),
        format!(
            "every data line splits into {} fields at a {}",
            layout.header.len(),
            layout.delimiter
        ),
    ));
    if layout.decimal_comma {
        f.format.push(Setting::new(
            "decimal: comma",
            "numbers are written like `0,05` (decimal comma)",
        ));
    }
    if layout.skip_lines > 0 {
        let shown: Vec<&str> = layout.metadata.iter().take(2).map(String::as_str).collect();
        f.format.push(Setting::new(
            format!("skip_lines: {}", layout.skip_lines),
            format!(
                "{} lines above the header{}",
                layout.skip_lines,
                if shown.is_empty() {
                    String::new()
                } else {
                    format!(" (instrument metadata: `{}`…)", shown.join("`, `"))
                }
            ),
        ));
    }
    match kind {
        Kind::PigaTable => {
            f.table_block = super::table::table(&mut f.format, &mut f.problems, &columns, &layout);
        }
        Kind::Probe | Kind::PigaRecording => {
            recording(&mut f, kind, &columns, &layout, read_column);
        }
    }
    f.layout = Some(layout);
    f
}

impl Layout {
    fn delimiter_text(&self) -> String {
        match self.delimiter {
            Delim::Char('\t') => "\\t".to_owned(),
            Delim::Char(c) => c.to_string(),
            Delim::Whitespace => " ".to_owned(),
        }
    }
}

/// A probe or PIGA output recording's settings: time, gap or output, the angle reference;
/// and its rate.
fn recording(
    f: &mut Finding,
    kind: Kind,
    columns: &[Column],
    layout: &Layout,
    read_column: &ColumnReader<'_>,
) {
    let read = |name: &str| read_column(layout, name);
    let Some(time_s) = time_setting(f, columns, &read) else {
        return;
    };
    signals(f, kind, columns, &layout.header, &read, time_s.as_deref());
}

/// One whole column (or channel) by name.
pub(crate) type Read<'a> = dyn Fn(&str) -> Result<Vec<f64>, String> + 'a;

/// The time column's setting; its values in seconds when its unit is known (`None` when
/// there is no time column: `Some(None)` when the times cannot be had).
pub(crate) fn time_setting(
    f: &mut Finding,
    columns: &[Column],
    read: &Read<'_>,
) -> Option<Option<Vec<f64>>> {
    let pick = |role: Role| columns.iter().find(|c| c.role == role);
    let time = pick(Role::Time)?;
    let time_unit = time.unit.as_deref().and_then(time_unit);
    let time_values = read(&time.name);
    let epoch = time_values
        .as_ref()
        .ok()
        .and_then(|v| v.first())
        .is_some_and(|&t| t > 1.0e8);
    match (time_unit, &time.unit) {
        (Some(u), _) => f.format.push(Setting::new(
            format!("time: (column: {}, unit: {u})", quoted(&time.name)),
            format!(
                "the header's `{}`{}",
                time.name,
                if epoch {
                    " (epoch time: seconds since 1970, only differences matter)"
                } else {
                    ""
                }
            ),
        )),
        (None, unit) => f.format.push(Setting::new(
            format!(
                "time: (column: {}, unit: {PLACEHOLDER})",
                quoted(&time.name)
            ),
            format!(
                "the header's `{}` {}: write s, ms, us or ns",
                time.name,
                unit.as_ref().map_or_else(
                    || "has no unit".to_owned(),
                    |u| format!("has the unit `{u}`, which is not a time unit")
                )
            ),
        )),
    }
    let seconds = time_unit.map(|u| match u {
        "ms" => 1e-3,
        "us" => 1e-6,
        "ns" => 1e-9,
        _ => 1.0,
    });
    let time_s: Option<Vec<f64>> = match (&time_values, seconds) {
        (Ok(v), Some(scale)) => Some(v.iter().map(|t| t * scale).collect()),
        _ => None,
    };
    if let Err(e) = &time_values {
        f.problems
            .push(format!("the time column cannot be read: {e}"));
    }
    Some(time_s)
}

/// The gap (or output) and angle settings and the rate, given the times in seconds.
pub(crate) fn signals(
    f: &mut Finding,
    kind: Kind,
    columns: &[Column],
    header: &[String],
    read: &Read<'_>,
    time_s: Option<&[f64]>,
) {
    let pick = |role: Role| columns.iter().find(|c| c.role == role);
    // gap or output
    match kind {
        Kind::Probe => {
            let gap = pick(Role::Gap).expect("a probe recording has a gap column");
            match gap.unit.as_deref() {
                Some(u) if length_unit(u).is_some() => f.format.push(Setting::new(
                    format!(
                        "gap: (column: {}, unit: {})",
                        quoted(&gap.name),
                        length_unit(u).unwrap_or(PLACEHOLDER)
                    ),
                    format!("the header's `{}`", gap.name),
                )),
                Some(u) if is_voltage(u) => {
                    f.format.push(Setting::new(
                        format!(
                            "gap: (column: {}, unit: volts(sensitivity: {PLACEHOLDER}, \
                             sensitivity_unit: um_per_v, u_sensitivity: {PLACEHOLDER}))",
                            quoted(&gap.name)
                        ),
                        format!(
                            "the header's `{}` is in volts{}: give the probe's sensitivity and \
                             its standard uncertainty from the probe's calibration certificate \
                             (sensitivity_unit um_per_v, mm_per_v or v_per_mm; the uncertainty \
                             in the same unit is the study's probe-gain input; \
                             docs/YOUR-DATA.md)",
                            gap.name,
                            if u.trim().eq_ignore_ascii_case("mv") {
                                " (millivolts: the values are read as written, so give the \
                                 sensitivity per millivolt where per volt is asked)"
                            } else {
                                ""
                            }
                        ),
                    ));
                }
                other => f.format.push(Setting::new(
                    format!("gap: (column: {}, unit: {PLACEHOLDER})", quoted(&gap.name)),
                    format!(
                        "the header's `{}` {}: write nm, um, mm or m",
                        gap.name,
                        other.map_or_else(
                            || "has no unit".to_owned(),
                            |u| format!("has the unit `{u}`, which is not a length")
                        )
                    ),
                )),
            }
        }
        Kind::PigaRecording | Kind::PigaTable => {
            let output = pick(Role::Output).expect("a PIGA recording has an output column");
            let values = read(&output.name).unwrap_or_default();
            let (unit, evidence) = angle_from(output, &values);
            f.format.push(Setting::new(
                format!("output: (column: {}, unit: {unit})", quoted(&output.name)),
                evidence,
            ));
        }
    }
    // the spindle angle
    let angle_column = columns
        .iter()
        .find(|c| matches!(c.role, Role::Angle | Role::Index));
    let named_rate = f
        .path
        .file_stem()
        .and_then(|s| rate_from_name(&s.to_string_lossy()));
    let mut measured: Option<(f64, String)> = None;
    match angle_column {
        Some(c) => {
            let values = match read(&c.name) {
                Ok(v) => v,
                Err(e) => {
                    f.problems
                        .push(format!("column `{}` cannot be read: {e}", c.name));
                    Vec::new()
                }
            };
            let binary = !values.is_empty() && values.iter().all(|&v| v == 0.0 || v == 1.0);
            if c.role == Role::Index || binary {
                f.format.push(Setting::new(
                    format!("angle: index_pulse(column: {})", quoted(&c.name)),
                    format!(
                        "`{}` holds only 0 and 1: a once-per-revolution pulse, angle 0 at \
                         each rising edge",
                        c.name
                    ),
                ));
                f.angle_words = format!("index pulse `{}`", c.name);
                if let Some(t) = time_s
                    && let Some((rate, turns)) = pulse_rate_deg_s(t, &values)
                {
                    measured = Some((
                        rate,
                        format!("measured from {turns} revolutions between index pulses"),
                    ));
                }
            } else {
                let (unit, evidence) = angle_from(c, &values);
                f.format.push(Setting::new(
                    format!("angle: encoder(column: {}, unit: {unit})", quoted(&c.name)),
                    evidence,
                ));
                f.angle_words = format!("encoder `{}` in {}", c.name, unit_name(&unit));
                if let (Some(t), Some((per_unit, turn))) = (time_s, rad_per_unit(&unit)) {
                    let rad = unwrap_rad(&values, per_unit, turn);
                    if let Some(rate) = slope_deg_s(t, &rad) {
                        measured = Some((
                            rate.abs(),
                            format!("measured from the encoder over {} samples", t.len()),
                        ));
                    }
                }
            }
        }
        None => {
            // Nothing measures the angle: it comes from the declared rate, and the start angle
            // (where the spindle was at the first sample) is not known.
            f.format.push(Setting::new(
                format!("angle: rate(start_angle_deg: {PLACEHOLDER})"),
                format!(
                    "no encoder or index-pulse column (columns: {}): the angle is taken \
                     from the declared rate, and the spindle's angle at the first sample \
                     from O1X1 must be given (a wrong one turns β and biases C_r)",
                    header.join(", ")
                ),
            ));
            f.angle_words = "none: from the declared rate".to_owned();
        }
    }
    f.rate = match (named_rate, measured) {
        (Some((named, text)), Some((m, how))) => {
            if ((m - named) / named).abs() > 0.02 {
                f.problems.push(format!(
                    "the name says {named} deg/s (`{text}`) but the angle reference gives \
                     {m:.4} deg/s ({how}): the file belongs to another rate point, or a \
                     unit is wrong"
                ));
            }
            Some(Rate {
                deg_s: named,
                evidence: format!("from the file name (`{text}`); {how}: {m:.4} deg/s"),
                measured: Some(m),
            })
        }
        (Some((named, text)), None) => Some(Rate {
            deg_s: named,
            evidence: format!("from the file name (`{text}`)"),
            measured: None,
        }),
        (None, Some((m, how))) => Some(Rate {
            deg_s: round_significant(m, 6),
            evidence: format!("{how} (no rate in the file name)"),
            measured: Some(m),
        }),
        (None, None) => None,
    };
}

/// The rate rounded to `digits` significant digits.
fn round_significant(v: f64, digits: i32) -> f64 {
    if v == 0.0 {
        return 0.0;
    }
    let scale = 10f64.powi(digits - 1 - v.abs().log10().floor() as i32);
    (v * scale).round() / scale
}

/// An angle unit in words.
fn unit_name(unit: &str) -> String {
    match unit {
        "deg" => "degrees".to_owned(),
        "rad" => "radians".to_owned(),
        u if u.starts_with("counts") => u
            .replace("counts(per_rev: ", "counts (")
            .replace(')', " per revolution)"),
        u => u.to_owned(),
    }
}

/// Radians per unit and the unit's wrap (a turn) of a RON angle unit.
fn rad_per_unit(unit: &str) -> Option<(f64, f64)> {
    match unit {
        "deg" => Some((1f64.to_radians(), 360.0)),
        "rad" => Some((1.0, std::f64::consts::TAU)),
        u => {
            let n: f64 = u
                .strip_prefix("counts(per_rev: ")?
                .strip_suffix(')')?
                .parse()
                .ok()?;
            Some((std::f64::consts::TAU / n, n))
        }
    }
}

/// An angle column's unit (RON) and the evidence: the header's unit, else the values' range.
fn angle_from(c: &Column, values: &[f64]) -> (String, String) {
    let (min, max) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let integers = !values.is_empty() && values.iter().all(|v| v.fract() == 0.0);
    let from_header = c.unit.as_deref().and_then(angle_unit);
    let counts = |why: String| -> (String, String) {
        match counts_per_rev(values) {
            Some((n, how)) => (format!("counts(per_rev: {n})"), format!("{why}; {how}")),
            None => (
                format!("counts(per_rev: {PLACEHOLDER})"),
                format!(
                    "{why}; the counter does not wrap in the file, so its counts per \
                     revolution are not known: give them"
                ),
            ),
        }
    };
    match from_header {
        Some("deg") => ("deg".into(), format!("the header's `{}`", c.name)),
        Some("rad") => ("rad".into(), format!("the header's `{}`", c.name)),
        Some(_) => counts(format!("the header's `{}` counts", c.name)),
        None if values.is_empty() => (
            PLACEHOLDER.into(),
            format!(
                "`{}` has no unit and no values: write deg, rad or counts(per_rev: N)",
                c.name
            ),
        ),
        None if integers && max > 360.0 => counts(format!(
            "`{}` has no unit and holds whole numbers up to {max}: encoder counts",
            c.name
        )),
        None if min >= -0.01 && max <= std::f64::consts::TAU + 0.01 && max > 3.0 => (
            "rad".into(),
            format!(
                "`{}` has no unit; its values stay within 0…{max:.3}, one turn in radians \
                 (check: degrees would span 0…360)",
                c.name
            ),
        ),
        None if min >= -360.01 && max <= 360.01 && max > 10.0 => (
            "deg".into(),
            format!(
                "`{}` has no unit; its values stay within {min:.1}…{max:.1}: degrees",
                c.name
            ),
        ),
        None => (
            PLACEHOLDER.into(),
            format!(
                "`{}` has no unit and its values ({min}…{max}) do not say which: write deg, \
                 rad or counts(per_rev: N)",
                c.name
            ),
        ),
    }
}

/// A counter's length from its wraps: the drop at each wrap plus one step, rounded to a
/// whole count and agreeing across wraps.
fn counts_per_rev(values: &[f64]) -> Option<(u64, String)> {
    let (min, max) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let span = max - min;
    let mut steps: Vec<f64> = values
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|s| *s > 0.0)
        .collect();
    if steps.is_empty() {
        return None;
    }
    steps.sort_by(f64::total_cmp);
    let typical = steps[steps.len() / 2];
    let wraps: Vec<f64> = values
        .windows(2)
        .filter(|w| w[1] - w[0] < -span / 2.0)
        .map(|w| w[0] - w[1] + typical)
        .collect();
    if wraps.is_empty() {
        return None;
    }
    let mean = wraps.iter().sum::<f64>() / wraps.len() as f64;
    // The counter's length is a whole number; a power of two within a step is the likely one.
    let power = 2f64.powi(mean.log2().round() as i32);
    let n = if (power - mean).abs() <= typical {
        power
    } else {
        mean.round()
    };
    let agree = wraps.iter().all(|w| (w - n).abs() <= 1.5 * typical);
    (agree && n >= 2.0).then(|| {
        (
            n as u64,
            format!(
                "the counter wraps {} time(s), each time after about {n} counts: {n} per \
                 revolution",
                wraps.len()
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reader(_: &str) -> impl Fn(&Layout, &str) -> Result<Vec<f64>, String> {
        |l: &Layout, name: &str| {
            let i = l.header.iter().position(|h| h == name).ok_or("no column")?;
            Ok(l.rows.iter().filter_map(|r| r[i]).collect())
        }
    }

    #[test]
    fn a_wrapping_counter_gives_its_length() {
        let v: Vec<f64> = (0..100).map(|k| f64::from((k * 100) % 4096)).collect();
        let (n, _) = counts_per_rev(&v).unwrap();
        assert_eq!(n, 4096);
    }

    #[test]
    fn a_probe_file_with_units_in_the_header() {
        let mut text = String::from("Time (ms)\tGap [um]\tAngle [deg]\n");
        for k in 0..400 {
            let t = f64::from(k) * 5.0;
            text += &format!(
                "{t}\t{}\t{}\n",
                1.0 + f64::from(k % 7) * 0.01,
                (t * 0.12) % 360.0
            );
        }
        let f = understand(
            Path::new("spin_120deg_s.txt"),
            text.as_bytes(),
            &reader(&text),
        );
        assert!(f.problems.is_empty(), "{:?}", f.problems);
        assert_eq!(f.kind, Some(Kind::Probe));
        assert_eq!(
            f.format_ron(),
            "(delimiter: '\\t', time: (column: \"Time (ms)\", unit: ms), gap: (column: \"Gap [um]\", unit: um), angle: encoder(column: \"Angle [deg]\", unit: deg))"
        );
        let rate = f.rate.unwrap();
        assert_eq!(rate.deg_s, 120.0);
        assert!((rate.measured.unwrap() - 120.0).abs() < 1e-6);
    }

    #[test]
    fn a_header_without_units_leaves_placeholders() {
        let mut text = String::from("time,gap\n");
        for k in 0..50 {
            text += &format!("{},{}\n", f64::from(k) * 0.01, 1.0);
        }
        let f = understand(Path::new("x.csv"), text.as_bytes(), &reader(&text));
        let missing: Vec<&str> = f.placeholders().map(|s| s.ron.as_str()).collect();
        assert_eq!(missing.len(), 3, "{missing:?}");
        assert!(f.rate.is_none());
    }
}
