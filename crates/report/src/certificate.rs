//! The calibration certificate: one self-contained HTML file (inline CSS and SVG, nothing
//! fetched), laid out for A4 printing with the certificate id and "page x of y" on every
//! page (CSS paged media margin boxes, which Chromium's print-to-PDF honours).
//!
//! Its contents follow ISO/IEC 17025:2017 §7.8.2.1 (identification of the laboratory, the
//! customer, the item, the method, the dates, the results with units, the statement that
//! they relate only to the item, the authorisation, a clear end) and §7.8.4.1 (measurement
//! uncertainty in the measurand's unit, the conditions, the traceability of each input,
//! statements of conformity with the decision rule of ILAC-G8:09/2019).

use std::fmt::Write as _;

use pipeline::{CalibrationResults, Coefficient, MonteCarloOutput, StudyResults};
use serde::Deserialize;

use crate::error::{ReportError, Result};
use crate::format;
use crate::format::esc;
use crate::provenance::{FileRecord, Provenance};

/// A party named on a certificate: the laboratory or the customer.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Party {
    /// Name.
    pub name: String,
    /// Postal address, one line.
    pub address: String,
}

/// The laboratory issuing the certificate.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Laboratory {
    /// Name.
    pub name: String,
    /// Postal address, one line.
    pub address: String,
    /// Accreditation body and number, if accredited.
    #[serde(default)]
    pub accreditation: Option<String>,
}

/// The item calibrated.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Item {
    /// What it is (`pendulous integrating gyroscopic accelerometer`).
    pub description: String,
    /// Its manufacturer.
    pub manufacturer: String,
    /// Its model.
    pub model: String,
    /// Its serial number.
    pub serial: String,
    /// Its condition on receipt.
    pub condition: String,
}

/// An instrument used in the calibration.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Equipment {
    /// Its role (`centrifuge`, `displacement probe`, `data acquisition`).
    pub role: String,
    /// Make and model.
    pub description: String,
    /// Its identity (serial or asset number).
    pub identity: String,
    /// When its calibration falls due (ISO date).
    pub calibration_due: String,
}

/// The dates of a calibration (ISO 8601, `2026-11-20`).
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Dates {
    /// Receipt of the item.
    pub received: String,
    /// The measurement (a day, or a span `2026-11-20 to 2026-11-21`).
    pub measured: String,
    /// Issue of the certificate.
    pub issued: String,
}

/// An environmental condition during the measurement.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Condition {
    /// The quantity (`ambient temperature`).
    pub quantity: String,
    /// Its value as measured, with unit and range (`20.3 °C to 20.9 °C`).
    pub value: String,
}

/// How one Type B input of the budget is traceable.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Traceability {
    /// The budget's input quantity, as the budget names it (`R (working radius)`).
    pub input: String,
    /// Where its value and uncertainty come from (a certificate number, a standard).
    pub statement: String,
}

/// A coefficient a specification limit applies to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CoefficientName {
    /// Bias.
    K0,
    /// Scale factor.
    K1,
    /// Second-order coefficient.
    K2,
    /// Third-order coefficient.
    K3,
}

/// The unit a specification limit is given in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LimitUnit {
    /// The coefficient's own unit: rad/s, rad/(s·g), rad/(s·g²), rad/(s·g³).
    Native,
    /// Relative to k1, in µg, µg/g² or µg/g³ (k0, k2, k3).
    Micro,
}

/// A specification limit of one coefficient.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Limit {
    /// The coefficient.
    pub coefficient: CoefficientName,
    /// The unit of `lower` and `upper`.
    pub unit: LimitUnit,
    /// Lower tolerance limit, if any.
    #[serde(default)]
    pub lower: Option<f64>,
    /// Upper tolerance limit, if any.
    #[serde(default)]
    pub upper: Option<f64>,
}

/// The decision rule of the statements of conformity (ILAC-G8:09/2019 §4.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DecisionRule {
    /// Binary statement, simple acceptance (guard band w = 0): pass or fail on the value.
    SimpleAcceptance,
    /// Non-binary statement with a guard band w = U: pass, conditional pass, conditional
    /// fail or fail.
    GuardBand,
}

/// Who authorises the certificate.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Authorisation {
    /// Name.
    pub name: String,
    /// Role (`head of the inertial laboratory`).
    pub role: String,
}

/// What a certificate states beside the study's results (ISO/IEC 17025:2017 §7.8.2.1 and
/// §7.8.4.1).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CertificateInfo {
    /// The certificate's unique identification, printed on every page.
    pub id: String,
    /// The issuing laboratory.
    pub laboratory: Laboratory,
    /// Where the calibration was performed (the laboratory's premises, or a site).
    pub location: String,
    /// The customer.
    pub customer: Party,
    /// The item calibrated.
    pub item: Item,
    /// The equipment used (centrifuge, probe, data acquisition).
    pub equipment: Vec<Equipment>,
    /// Receipt, measurement and issue.
    pub dates: Dates,
    /// Who performed the calibration.
    pub operator: String,
    /// Environmental conditions during the measurement.
    pub conditions: Vec<Condition>,
    /// The procedure followed (its reference and title).
    pub procedure: String,
    /// Departures from the procedure, or `none`.
    #[serde(default)]
    pub deviations: Option<String>,
    /// How each Type B input of the budget is traceable.
    pub traceability: Vec<Traceability>,
    /// Specification limits for coefficients (none: no statement of conformity).
    #[serde(default)]
    pub limits: Vec<Limit>,
    /// The decision rule for the limits.
    #[serde(default)]
    pub decision_rule: Option<DecisionRule>,
    /// Who authorises the certificate.
    pub authorisation: Authorisation,
}

/// The software that produced a certificate.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Software {
    /// Name and version (`centrifuge-cal 0.1.0`).
    pub version: String,
    /// The source's commit, or `unknown`.
    pub commit: String,
}

impl Software {
    /// This build: the workspace version and the commit it was built from (the build
    /// environment's `CENTRIFUGE_CAL_COMMIT`, else `unknown`).
    pub fn this_build() -> Self {
        Self {
            version: format!("{} {}", crate::TOOL, env!("CARGO_PKG_VERSION")),
            commit: option_env!("CENTRIFUGE_CAL_COMMIT")
                .unwrap_or("unknown")
                .to_owned(),
        }
    }
}

/// How a coefficient's headline interval was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum HeadlineMethod {
    /// JCGM 100, validated by the Monte Carlo method (JCGM 101 §8).
    Gum,
    /// JCGM 101: the GUM interval is not validated, or its validation is borderline.
    MonteCarlo {
        /// The §8 comparison lies within the Monte Carlo's own numerical tolerance of its
        /// threshold (`|max(d_low, d_high) − δ| ≤ δ/2`): either verdict could come out of
        /// another run, so the Monte Carlo interval, valid either way, is reported.
        borderline: bool,
    },
}

/// A coefficient's headline: the value and the 95 % interval a certificate states.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Headline {
    /// The estimate.
    pub value: f64,
    /// Lower end of the 95 % coverage interval.
    pub low: f64,
    /// Upper end.
    pub high: f64,
    /// The GUM coefficient (k, ν_eff, U95).
    pub gum: Coefficient,
    /// Which method gives the interval.
    pub method: HeadlineMethod,
}

impl Headline {
    /// The headline of a coefficient from its GUM result and its Monte Carlo one
    /// (JCGM 101 §8): the GUM interval when validated clearly, else the Monte Carlo one.
    pub(crate) fn of(gum: &Coefficient, mc: &MonteCarloOutput) -> Self {
        let d = mc.d_low.max(mc.d_high);
        let borderline = (d - mc.tolerance).abs() <= 0.5 * mc.tolerance;
        let method = if mc.gum_agrees && !borderline {
            HeadlineMethod::Gum
        } else {
            HeadlineMethod::MonteCarlo { borderline }
        };
        match method {
            HeadlineMethod::Gum => Self {
                value: gum.value,
                low: gum.value - gum.u95,
                high: gum.value + gum.u95,
                gum: *gum,
                method,
            },
            HeadlineMethod::MonteCarlo { .. } => Self {
                value: gum.value,
                low: mc.low95,
                high: mc.high95,
                gum: *gum,
                method,
            },
        }
    }

    /// The interval's half-widths below and above the value, scaled by `scale`.
    pub(crate) fn widths(&self, scale: f64) -> (f64, f64) {
        (
            (self.value - self.low) * scale.abs(),
            (self.high - self.value) * scale.abs(),
        )
    }

    /// The method in words.
    pub(crate) fn method_words(&self) -> &'static str {
        match self.method {
            HeadlineMethod::Gum => "GUM (JCGM 100), validated by Monte Carlo",
            HeadlineMethod::MonteCarlo { borderline: false } => {
                "Monte Carlo (JCGM 101): the GUM interval is not validated (§8)"
            }
            HeadlineMethod::MonteCarlo { borderline: true } => {
                "Monte Carlo (JCGM 101): the GUM validation is borderline (§8)"
            }
        }
    }
}

/// The four headlines of a calibration, k0 … k3.
pub(crate) fn headlines(c: &CalibrationResults) -> [Headline; 4] {
    let (g, m) = (&c.coefficients, &c.monte_carlo);
    [
        Headline::of(&g.k0, &m.k0),
        Headline::of(&g.k1, &m.k1),
        Headline::of(&g.k2, &m.k2),
        Headline::of(&g.k3, &m.k3),
    ]
}

/// A statement of conformity (ILAC-G8:09/2019 §4.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Verdict {
    /// Within the acceptance zone.
    Pass,
    /// Within the tolerance, but the interval reaches beyond it.
    ConditionalPass,
    /// Outside the tolerance, but the interval reaches into it.
    ConditionalFail,
    /// Outside the tolerance by more than the interval.
    Fail,
}

impl Verdict {
    fn words(self) -> &'static str {
        match self {
            Self::Pass => "pass",
            Self::ConditionalPass => "conditional pass",
            Self::ConditionalFail => "conditional fail",
            Self::Fail => "fail",
        }
    }
}

/// The verdict for a value with interval half-widths `(below, above)` against limits.
pub(crate) fn verdict(
    value: f64,
    (below, above): (f64, f64),
    lower: Option<f64>,
    upper: Option<f64>,
    rule: DecisionRule,
) -> Verdict {
    let upper_verdict = |tu: f64| match rule {
        DecisionRule::SimpleAcceptance if value <= tu => Verdict::Pass,
        DecisionRule::SimpleAcceptance => Verdict::Fail,
        DecisionRule::GuardBand if value + above <= tu => Verdict::Pass,
        DecisionRule::GuardBand if value <= tu => Verdict::ConditionalPass,
        DecisionRule::GuardBand if value - below <= tu => Verdict::ConditionalFail,
        DecisionRule::GuardBand => Verdict::Fail,
    };
    let lower_verdict = |tl: f64| match rule {
        DecisionRule::SimpleAcceptance if value >= tl => Verdict::Pass,
        DecisionRule::SimpleAcceptance => Verdict::Fail,
        DecisionRule::GuardBand if value - below >= tl => Verdict::Pass,
        DecisionRule::GuardBand if value >= tl => Verdict::ConditionalPass,
        DecisionRule::GuardBand if value + above >= tl => Verdict::ConditionalFail,
        DecisionRule::GuardBand => Verdict::Fail,
    };
    upper
        .map_or(Verdict::Pass, upper_verdict)
        .max(lower.map_or(Verdict::Pass, lower_verdict))
}

/// A CSS string literal holding `text`.
fn css_string(text: &str) -> String {
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' | '\\' => {
                out.push('\\');
                out.push(c);
            }
            '\n' | '\r' => out.push(' '),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// An SVG document made to scale to its container's width.
fn inline_svg(svg: &str) -> String {
    // plotters writes `<svg width="W" height="H" viewBox="0 0 W H" …>`; the width and
    // height are dropped so that CSS sizes it, the viewBox keeps its aspect.
    let svg = svg
        .trim_start_matches(|c| c != '<')
        .trim_start_matches("<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
        .trim_start();
    let Some(end) = svg.find('>') else {
        return svg.to_owned();
    };
    let (open, rest) = svg.split_at(end);
    let mut attrs = String::new();
    let mut width = None;
    let mut height = None;
    for part in open.trim_start_matches("<svg").split_whitespace() {
        if let Some(w) = part.strip_prefix("width=\"") {
            width = Some(w.trim_end_matches('"').to_owned());
        } else if let Some(h) = part.strip_prefix("height=\"") {
            height = Some(h.trim_end_matches('"').to_owned());
        } else {
            attrs.push(' ');
            attrs.push_str(part);
        }
    }
    if !attrs.contains("viewBox")
        && let (Some(w), Some(h)) = (width, height)
    {
        let _ = write!(attrs, " viewBox=\"0 0 {w} {h}\"");
    }
    format!("<svg class=\"figure\"{attrs}{rest}")
}

const UNITS: [&str; 4] = ["rad/s", "rad/(s·g)", "rad/(s·g²)", "rad/(s·g³)"];
const MICRO_UNITS: [&str; 4] = ["µg", "", "µg/g²", "µg/g³"];
const NAMES: [&str; 4] = ["k0", "k1", "k2", "k3"];

const STYLE: &str = r#"
* { box-sizing: border-box; }
html { font-family: "DejaVu Sans", "Liberation Sans", Arial, sans-serif; font-size: 9.5pt; color: #111; }
body { margin: 0; }
h1 { font-size: 17pt; margin: 0 0 1mm 0; }
h2 { font-size: 11.5pt; margin: 6mm 0 2mm 0; border-bottom: 0.4pt solid #444; padding-bottom: 0.8mm; break-after: avoid; }
h3 { font-size: 10pt; margin: 4mm 0 1.5mm 0; break-after: avoid; }
p { margin: 1.2mm 0; line-height: 1.35; }
table { border-collapse: collapse; width: 100%; margin: 1.5mm 0 2mm 0; break-inside: auto; }
tr { break-inside: avoid; }
th, td { border: 0.4pt solid #999; padding: 0.9mm 1.4mm; text-align: left; vertical-align: top; }
th { background: #eef0f3; font-weight: 600; }
td.num, th.num { text-align: right; white-space: nowrap; font-variant-numeric: tabular-nums; }
table.ident th { width: 38mm; }
.masthead { display: flex; justify-content: space-between; align-items: flex-start; border-bottom: 1.2pt solid #111; padding-bottom: 2mm; margin-bottom: 3mm; }
.masthead .lab { text-align: right; font-size: 9pt; }
.id { font-size: 11pt; font-weight: 700; }
.note { font-size: 8.5pt; color: #333; }
.warning { border-left: 2pt solid #b35900; padding-left: 2mm; margin: 1.2mm 0; font-size: 8.5pt; }
.verdict-pass { color: #0a5d1a; font-weight: 700; }
.verdict-conditional { color: #8a5a00; font-weight: 700; }
.verdict-fail { color: #a00; font-weight: 700; }
.hash { font-family: "DejaVu Sans Mono", "Liberation Mono", monospace; font-size: 6.6pt; white-space: nowrap; }
td.path { word-break: break-all; font-size: 8pt; }
svg.figure { width: 100%; height: auto; display: block; break-inside: avoid; }
.figure-box { break-inside: avoid; margin: 2mm 0; }
.signature { margin-top: 8mm; display: flex; gap: 12mm; }
.signature div { flex: 1; border-top: 0.4pt solid #111; padding-top: 1mm; font-size: 8.5pt; }
.details { break-before: page; }
.end { text-align: center; margin-top: 6mm; font-weight: 700; letter-spacing: 0.05em; }
"#;

/// The `@page` rule: A4, the laboratory and certificate id at the top of every page, "page x
/// of y" at the bottom.
fn page_style(info: &CertificateInfo) -> String {
    format!(
        "@page {{ size: A4; margin: 20mm 16mm 18mm 16mm;\n  \
         @top-left {{ content: {lab}; font-size: 8pt; color: #444; }}\n  \
         @top-right {{ content: {id}; font-size: 8pt; font-weight: 700; }}\n  \
         @bottom-left {{ content: {title}; font-size: 8pt; color: #444; }}\n  \
         @bottom-right {{ content: \"Page \" counter(page) \" of \" counter(pages); font-size: 8pt; }}\n}}\n",
        lab = css_string(&info.laboratory.name),
        id = css_string(&format!("Certificate {}", info.id)),
        title = css_string(&format!(
            "{} {} serial {}",
            info.item.manufacturer, info.item.model, info.item.serial
        )),
    )
}

fn row(out: &mut String, th: &str, td: &str) {
    let _ = writeln!(out, "<tr><th>{}</th><td>{}</td></tr>", esc(th), td);
}

/// The headline interval of a coefficient in a unit: `value`, `U` (symmetric) or `+a / -b`.
fn interval_cells(h: &Headline, scale: f64) -> (String, String) {
    let (below, above) = h.widths(scale);
    let a = format::interval(h.value * scale, below, above);
    let suffix = if a.scale.is_empty() {
        String::new()
    } else {
        format!(" {}", a.scale)
    };
    let u = if a.minus.is_empty() {
        format!("{}{suffix}", a.plus)
    } else {
        format!("+{}{suffix} / -{}{suffix}", a.plus, a.minus)
    };
    (format!("{}{suffix}", a.value), u)
}

/// The scale from a coefficient's own unit to µg, µg/g², µg/g³ (relative to k1).
fn micro_scale(k1: f64) -> f64 {
    1e6 / k1
}

fn results_table(out: &mut String, c: &CalibrationResults, heads: &[Headline; 4]) {
    let _ = writeln!(
        out,
        "<table class=\"results\"><thead><tr><th>coefficient</th><th class=\"num\">value</th>\
         <th class=\"num\">expanded uncertainty U</th><th class=\"num\">k</th><th class=\"num\">ν<sub>eff</sub></th>\
         <th>unit</th><th>coverage interval from</th></tr></thead><tbody>"
    );
    for (n, h) in heads.iter().enumerate() {
        let (value, u) = interval_cells(h, 1.0);
        let (k, nu) = match h.method {
            HeadlineMethod::Gum => (format::coverage_factor(h.gum.k), format::dof(h.gum.dof)),
            HeadlineMethod::MonteCarlo { .. } => ("—".to_owned(), "—".to_owned()),
        };
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td class=\"num\">{value}</td><td class=\"num\">{u}</td><td class=\"num\">{k}</td>\
             <td class=\"num\">{nu}</td><td>{}</td><td>{}</td></tr>",
            NAMES[n],
            UNITS[n],
            esc(h.method_words())
        );
    }
    let k1 = c.coefficients.k1.value;
    for n in [0, 2, 3] {
        let h = &heads[n];
        let (value, u) = interval_cells(h, micro_scale(k1));
        let (k, nu) = match h.method {
            HeadlineMethod::Gum => (format::coverage_factor(h.gum.k), format::dof(h.gum.dof)),
            HeadlineMethod::MonteCarlo { .. } => ("—".to_owned(), "—".to_owned()),
        };
        let _ = writeln!(
            out,
            "<tr><td>{}/k1</td><td class=\"num\">{value}</td><td class=\"num\">{u}</td><td class=\"num\">{k}</td>\
             <td class=\"num\">{nu}</td><td>{}</td><td>{}</td></tr>",
            NAMES[n],
            MICRO_UNITS[n],
            esc(h.method_words())
        );
    }
    let _ = writeln!(out, "</tbody></table>");
    let _ = writeln!(
        out,
        "<p class=\"note\">The expanded uncertainty U is the standard uncertainty multiplied by \
         the coverage factor k, for a coverage probability of approximately 95 %; k is Student's \
         t at the effective degrees of freedom ν<sub>eff</sub> (Welch–Satterthwaite). Where the \
         Monte Carlo method of JCGM 101 does not validate the GUM interval (§8), the probabilistically \
         symmetric 95 % interval of the Monte Carlo method is stated instead, as +/− widths about \
         the estimate. The values relative to k1 use k1 = {} rad/(s·g) and g = {} m/s² (1 g).</p>",
        format::significant(k1, 7),
        format::significant(c.g_m_s2, 6),
    );
}

fn compensation_block(out: &mut String, c: &CalibrationResults, k2: &Headline) {
    let k = k2.gum.k;
    let cr = format::pair(c.c_r_m_s2.value, k * c.c_r_m_s2.u);
    let dk2 = format::pair(c.delta_k2.value, k * c.delta_k2.u);
    let micro = micro_scale(c.coefficients.k1.value);
    let dk2_micro = format::pair(c.delta_k2.value * micro, k * c.delta_k2.u * micro.abs());
    let _ = writeln!(
        out,
        "<table class=\"ident\"><tbody>\
         <tr><th>C<sub>r</sub> of the spindle</th><td class=\"num\">{} m·s²</td><td>phase “{}”, U = k·u with k = {}</td></tr>\
         <tr><th>Δk2 = k1·C<sub>r</sub>·g/R²</th><td class=\"num\">{} rad/(s·g²) = {} µg/g²</td>\
         <td>removed from the fitted a² coefficient (eq. 19); U from the same inputs as k2 (C<sub>r</sub>, probe gain, lever, rate scale, R, g, k1), k = {}</td></tr>\
         </tbody></table>",
        cr.joined(),
        esc(&c.compensate_with),
        format::coverage_factor(k),
        dk2.joined(),
        dk2_micro.joined(),
        format::coverage_factor(k),
    );
}

fn conformity(
    out: &mut String,
    info: &CertificateInfo,
    c: &CalibrationResults,
    heads: &[Headline; 4],
) {
    if info.limits.is_empty() {
        return;
    }
    let rule = info.decision_rule.unwrap_or(DecisionRule::GuardBand);
    let _ = writeln!(out, "<h3>Statements of conformity</h3>");
    let _ = writeln!(
        out,
        "<p>Decision rule (ILAC-G8:09/2019 §4.2): {}</p>",
        match rule {
            DecisionRule::SimpleAcceptance =>
                "binary statement with simple acceptance (guard band w = 0): pass when the \
                 measured value lies within the tolerance limits, fail otherwise. The risk of a \
                 false acceptance reaches 50 % for a value on a limit.",
            DecisionRule::GuardBand =>
                "non-binary statement with a guard band w = U: pass when the whole 95 % interval \
                 lies within the tolerance limits; conditional pass when the value lies within \
                 them but the interval does not; conditional fail when the value lies outside \
                 but the interval reaches within; fail when the whole interval lies outside.",
        }
    );
    let _ = writeln!(
        out,
        "<table><thead><tr><th>coefficient</th><th class=\"num\">value</th><th class=\"num\">U</th>\
         <th class=\"num\">lower limit</th><th class=\"num\">upper limit</th><th>unit</th><th>statement</th></tr></thead><tbody>"
    );
    let k1 = c.coefficients.k1.value;
    for l in &info.limits {
        let n = l.coefficient as usize;
        let h = &heads[n];
        let (scale, unit) = match l.unit {
            LimitUnit::Native => (1.0, UNITS[n]),
            LimitUnit::Micro => (micro_scale(k1), MICRO_UNITS[n]),
        };
        let v = verdict(h.value * scale, h.widths(scale), l.lower, l.upper, rule);
        let (value, u) = interval_cells(h, scale);
        let class = match v {
            Verdict::Pass => "verdict-pass",
            Verdict::ConditionalPass | Verdict::ConditionalFail => "verdict-conditional",
            Verdict::Fail => "verdict-fail",
        };
        let limit = |x: Option<f64>| x.map_or_else(|| "—".to_owned(), format::plain);
        let _ = writeln!(
            out,
            "<tr><td>{}{}</td><td class=\"num\">{value}</td><td class=\"num\">{u}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{}</td><td>{unit}</td><td class=\"{class}\">{}</td></tr>",
            NAMES[n],
            if matches!(l.unit, LimitUnit::Micro) {
                "/k1"
            } else {
                ""
            },
            limit(l.lower),
            limit(l.upper),
            v.words(),
        );
    }
    let _ = writeln!(out, "</tbody></table>");
}

fn budget(out: &mut String, c: &CalibrationResults) {
    let _ = writeln!(out, "<h3>Uncertainty budget of k2 (JCGM 100)</h3>");
    let _ = writeln!(
        out,
        "<table><thead><tr><th>input quantity</th><th>type</th><th class=\"num\">value</th>\
         <th class=\"num\">standard uncertainty</th><th class=\"num\">sensitivity</th>\
         <th class=\"num\">contribution (rad/(s·g²))</th><th class=\"num\">share of u²</th><th class=\"num\">ν</th></tr></thead><tbody>"
    );
    for l in &c.budget.k2 {
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{}</td><td class=\"num\">{} %</td><td class=\"num\">{}</td></tr>",
            esc(&l.quantity),
            esc(&l.evaluation),
            l.value
                .map_or_else(|| "—".to_owned(), |v| format::significant(v, 6)),
            format::significant(l.u, 2),
            format::significant(l.sensitivity, 3),
            format::significant(l.contribution, 2),
            format::percent(l.percent),
            format::dof(l.dof),
        );
    }
    let k2 = &c.coefficients.k2;
    let _ = writeln!(
        out,
        "<tr><th colspan=\"5\">combined standard uncertainty u(k2), effective degrees of freedom</th>\
         <td class=\"num\">{}</td><td class=\"num\">100 %</td><td class=\"num\">{}</td></tr></tbody></table>",
        format::significant(k2.u, 2),
        format::dof(k2.dof)
    );
}

fn gum_against_mc(out: &mut String, c: &CalibrationResults) {
    let mc = &c.monte_carlo;
    let _ = writeln!(out, "<h3>GUM against Monte Carlo (JCGM 101 §8)</h3>");
    let _ = writeln!(
        out,
        "<p>{} trials (adaptive, JCGM 101 §7.9), seed {}. The GUM interval is validated when both \
         its ends lie within the numerical tolerance δ of the Monte Carlo interval's.</p>",
        mc.trials, mc.seed
    );
    let _ = writeln!(
        out,
        "<table><thead><tr><th>coefficient</th><th class=\"num\">GUM 95 % interval</th>\
         <th class=\"num\">Monte Carlo 95 % interval</th><th class=\"num\">largest end difference</th>\
         <th class=\"num\">δ</th><th>verdict</th><th>unit</th></tr></thead><tbody>"
    );
    let heads = headlines(c);
    for (n, (g, m)) in [
        (&c.coefficients.k0, &mc.k0),
        (&c.coefficients.k1, &mc.k1),
        (&c.coefficients.k2, &mc.k2),
        (&c.coefficients.k3, &mc.k3),
    ]
    .into_iter()
    .enumerate()
    {
        let digits = 7;
        let verdict = match heads[n].method {
            HeadlineMethod::Gum => "validated",
            HeadlineMethod::MonteCarlo { borderline: true } => "borderline (Monte Carlo stated)",
            HeadlineMethod::MonteCarlo { borderline: false } => {
                "not validated (Monte Carlo stated)"
            }
        };
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td class=\"num\">[{}, {}]</td><td class=\"num\">[{}, {}]</td>\
             <td class=\"num\">{}</td><td class=\"num\">{}</td><td>{verdict}</td><td>{}</td></tr>",
            NAMES[n],
            format::significant(g.value - g.u95, digits),
            format::significant(g.value + g.u95, digits),
            format::significant(m.low95, digits),
            format::significant(m.high95, digits),
            format::significant(m.d_low.max(m.d_high), 2),
            format::significant(m.tolerance, 2),
            UNITS[n],
        );
    }
    let _ = writeln!(out, "</tbody></table>");
}

fn data_used(out: &mut String, results: &StudyResults, c: &CalibrationResults) {
    let _ = writeln!(out, "<h3>Data used</h3>");
    let phase = results.phase(&c.compensate_with);
    if let Some(p) = phase {
        let revolutions: usize = p.points.iter().filter_map(|q| q.revolutions).sum();
        let rates: Vec<String> = p
            .points
            .iter()
            .map(|q| format::rate(q.rate_deg_s))
            .collect();
        let _ = writeln!(
            out,
            "<p>Spindle (phase “{}”): {} rates, {} deg/s{}; C<sub>r</sub> from the fit {} with {} degrees of freedom.</p>",
            esc(&p.name),
            p.points.len(),
            rates.join(", "),
            if revolutions > 0 {
                format!("; {revolutions} whole revolutions of probe recording")
            } else {
                String::new()
            },
            esc(pipeline::model_name(p.fit.model)),
            p.fit.dof,
        );
    }
    let _ = writeln!(
        out,
        "<p>PIGA: {} points at {} distinct rates, {} residual degrees of freedom; residual \
         standard deviation {} rad/s; {}.</p>",
        c.points,
        c.distinct_rates,
        c.dof,
        format::significant(c.residual_sd_rad_s, 2),
        if c.weighted {
            "weighted by each point's standard uncertainty"
        } else {
            "unweighted"
        }
    );
    if !c.recordings.is_empty() {
        let _ = writeln!(
            out,
            "<table><thead><tr><th class=\"num\">rate (deg/s)</th><th>spindle angle from</th>\
             <th class=\"num\">revolutions</th><th class=\"num\">dropped</th><th class=\"num\">mean output (rad/s)</th>\
             <th class=\"num\">u (rad/s)</th></tr></thead><tbody>"
        );
        for r in &c.recordings {
            let _ = writeln!(
                out,
                "<tr><td class=\"num\">{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>\
                 <td class=\"num\">{}</td><td class=\"num\">{}</td></tr>",
                format::rate(r.rate_deg_s),
                esc(&r.angle_source.replace('_', " ")),
                r.revolutions,
                r.dropped_revolutions,
                format::significant(r.output_rad_s, 9),
                format::significant(r.u_rad_s, 2),
            );
        }
        let _ = writeln!(out, "</tbody></table>");
    }
    let warnings: Vec<String> = results
        .warnings
        .iter()
        .map(|w| format!("{} ({})", w.message, w.location))
        .chain(c.warnings.iter().cloned())
        .collect();
    if warnings.is_empty() {
        let _ = writeln!(out, "<p>No warnings were raised.</p>");
    } else {
        let _ = writeln!(out, "<p>Warnings raised by the evaluation:</p>");
        for w in warnings {
            let _ = writeln!(out, "<p class=\"warning\">{}</p>", esc(&w));
        }
    }
}

fn files(out: &mut String, provenance: &Provenance, software: &Software) {
    let _ = writeln!(out, "<h3>Input files and software</h3>");
    let _ = writeln!(
        out,
        "<table><thead><tr><th>file</th><th class=\"num\">bytes</th><th>SHA-256</th></tr></thead><tbody>"
    );
    let record = |out: &mut String, what: &str, f: &FileRecord| {
        let _ = writeln!(
            out,
            "<tr><td class=\"path\">{}{}</td><td class=\"num\">{}</td><td class=\"hash\">{}</td></tr>",
            esc(what),
            esc(&f.path),
            f.bytes,
            esc(&f.sha256)
        );
    };
    record(out, "study: ", &provenance.config);
    for f in &provenance.inputs {
        record(out, "", f);
    }
    if let Some(e) = &provenance.expected {
        record(out, "expected values: ", e);
    }
    let _ = writeln!(out, "</tbody></table>");
    let _ = writeln!(
        out,
        "<p>Software: {}, commit <span class=\"hash\">{}</span>.</p>",
        esc(&software.version),
        esc(&software.commit)
    );
}

/// Renders the calibration certificate of a study with a calibration section: the HTML
/// text, self-contained (inline CSS and SVG; nothing is fetched), for A4 printing.
///
/// # Errors
/// [`ReportError::NoCalibration`] when the results hold no calibration;
/// [`ReportError::Plot`] when the residual figure cannot be drawn.
pub fn certificate_html(
    results: &StudyResults,
    info: &CertificateInfo,
    provenance: &Provenance,
    software: &Software,
) -> Result<String> {
    let c = results
        .calibration
        .as_ref()
        .ok_or(ReportError::NoCalibration)?;
    let heads = headlines(c);
    let mut out = String::new();
    let _ = writeln!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>Calibration certificate {}</title>\n<style>\n{}{STYLE}</style>\n</head>\n<body>",
        esc(&info.id),
        page_style(info)
    );
    // Identification
    let _ = writeln!(
        out,
        "<div class=\"masthead\"><div><h1>Calibration certificate</h1><div class=\"id\">{}</div></div>\
         <div class=\"lab\"><strong>{}</strong><br>{}{}</div></div>",
        esc(&info.id),
        esc(&info.laboratory.name),
        esc(&info.laboratory.address),
        info.laboratory
            .accreditation
            .as_ref()
            .map_or_else(String::new, |a| format!("<br>{}", esc(a)))
    );
    let _ = writeln!(out, "<table class=\"ident\"><tbody>");
    let item = &info.item;
    row(
        &mut out,
        "Item",
        &format!(
            "{}, {} {}, serial number <strong>{}</strong>",
            esc(&item.description),
            esc(&item.manufacturer),
            esc(&item.model),
            esc(&item.serial)
        ),
    );
    row(&mut out, "Condition on receipt", &esc(&item.condition));
    row(
        &mut out,
        "Customer",
        &format!(
            "{}, {}",
            esc(&info.customer.name),
            esc(&info.customer.address)
        ),
    );
    row(&mut out, "Place of calibration", &esc(&info.location));
    row(
        &mut out,
        "Dates",
        &format!(
            "received {}; measured {}; issued {}",
            esc(&info.dates.received),
            esc(&info.dates.measured),
            esc(&info.dates.issued)
        ),
    );
    row(&mut out, "Procedure", &esc(&info.procedure));
    row(&mut out, "Performed by", &esc(&info.operator));
    let _ = writeln!(out, "</tbody></table>");

    // Results
    let _ = writeln!(out, "<h2>Results</h2>");
    let _ = writeln!(
        out,
        "<p>The PIGA's coefficients of eq. 18, k2 compensated for the spindle's pseudo-second-order \
         term Δk2. Model of the mean output rate: ω<sub>out</sub> = k0 + k1·a + k2·a² + k3·a³ \
         with a the specific force along the input axis in g.</p>"
    );
    results_table(&mut out, c, &heads);
    compensation_block(&mut out, c, &heads[2]);
    conformity(&mut out, info, c, &heads);
    let _ = writeln!(
        out,
        "<p>The results relate only to the item calibrated, as received, under the conditions \
         stated. This certificate shall not be reproduced except in full without the written \
         approval of the laboratory.</p>"
    );
    let _ = writeln!(
        out,
        "<div class=\"signature\"><div>Authorised by {}, {}<br>Date {}</div><div>Signature</div></div>",
        esc(&info.authorisation.name),
        esc(&info.authorisation.role),
        esc(&info.dates.issued)
    );

    // Details
    let _ = writeln!(out, "<section class=\"details\">");
    let _ = writeln!(out, "<h2>Method</h2>");
    let _ = writeln!(
        out,
        "<p>The PIGA is mounted on the centrifuge arm at the working radius R = {} m and \
         calibrated at the rates listed below; at each rate its mean output rate over whole spindle \
         revolutions is measured. The centrifuge's dynamic imbalance makes the working radius grow \
         as C<sub>r</sub>·ω², which adds k1·C<sub>r</sub>·ω⁴/g to the output (eq. 17): indistinguishable \
         by least squares from k2·a², it would appear as a pseudo-second-order term \
         Δk2 = k1·C<sub>r</sub>·g/R² (eq. 19). C<sub>r</sub> is measured by a displacement probe \
         on the spindle (first harmonic of the gap per revolution, eq. 20–22) and the term removed. \
         The coefficients are the least-squares solution of eq. 18 (columns 1, ω, ω², ω³, a², a³), \
         through QR with column scaling; the terms in ω and ω³ are nuisance terms of the set-up. \
         Uncertainties are evaluated by the GUM (JCGM 100) through the whole measurement model and \
         checked by the Monte Carlo method (JCGM 101).</p>",
        format::significant(results.inputs.radius_m, 6)
    );
    if let Some(d) = &info.deviations {
        let _ = writeln!(out, "<p>Departures from the procedure: {}.</p>", esc(d));
    }
    let _ = writeln!(out, "<h2>Conditions and equipment</h2>");
    if !info.conditions.is_empty() {
        let _ = writeln!(out, "<table class=\"ident\"><tbody>");
        for cnd in &info.conditions {
            row(&mut out, &cnd.quantity, &esc(&cnd.value));
        }
        let _ = writeln!(out, "</tbody></table>");
    }
    let _ = writeln!(
        out,
        "<table><thead><tr><th>role</th><th>instrument</th><th>identity</th><th>calibration due</th></tr></thead><tbody>"
    );
    for e in &info.equipment {
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(&e.role),
            esc(&e.description),
            esc(&e.identity),
            esc(&e.calibration_due)
        );
    }
    let _ = writeln!(out, "</tbody></table>");
    let _ = writeln!(out, "<h3>Traceability of the Type B inputs</h3>");
    let _ = writeln!(
        out,
        "<table><thead><tr><th>input quantity</th><th class=\"num\">standard uncertainty</th><th>traceability</th></tr></thead><tbody>"
    );
    for t in &info.traceability {
        let u = c
            .budget
            .k2
            .iter()
            .find(|l| l.quantity == t.input)
            .map_or_else(|| "—".to_owned(), |l| format::significant(l.u, 2));
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td class=\"num\">{u}</td><td>{}</td></tr>",
            esc(&t.input),
            esc(&t.statement)
        );
    }
    let _ = writeln!(out, "</tbody></table>");

    let _ = writeln!(out, "<h2>Evaluation</h2>");
    budget(&mut out, c);
    let svg = crate::plot::calibration_residuals_svg(
        c,
        "PIGA output residuals (eq. 18) with their standard uncertainties",
    )?;
    let _ = writeln!(
        out,
        "<div class=\"figure-box\"><h3>Residuals</h3>{}</div>",
        inline_svg(&svg)
    );
    gum_against_mc(&mut out, c);
    data_used(&mut out, results, c);
    files(&mut out, provenance, software);
    let _ = writeln!(
        out,
        "<p class=\"end\">End of certificate {}</p>\n</section>\n</body>\n</html>",
        esc(&info.id)
    );
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_acceptance_is_binary() {
        let r = DecisionRule::SimpleAcceptance;
        assert_eq!(verdict(0.9, (0.5, 0.5), None, Some(1.0), r), Verdict::Pass);
        assert_eq!(verdict(1.1, (0.5, 0.5), None, Some(1.0), r), Verdict::Fail);
        assert_eq!(
            verdict(-1.1, (0.5, 0.5), Some(-1.0), None, r),
            Verdict::Fail
        );
    }

    #[test]
    fn a_guard_band_of_u_gives_four_statements() {
        let r = DecisionRule::GuardBand;
        let lim = (Some(-1.0), Some(1.0));
        let v = |x: f64| verdict(x, (0.2, 0.2), lim.0, lim.1, r);
        assert_eq!(v(0.7), Verdict::Pass);
        assert_eq!(v(0.9), Verdict::ConditionalPass);
        assert_eq!(v(1.1), Verdict::ConditionalFail);
        assert_eq!(v(1.3), Verdict::Fail);
        assert_eq!(v(-0.9), Verdict::ConditionalPass);
        assert_eq!(v(-1.3), Verdict::Fail);
        // an asymmetric interval: the width towards the limit decides
        assert_eq!(verdict(0.9, (0.5, 0.05), None, Some(1.0), r), Verdict::Pass);
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(esc("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
        assert_eq!(css_string("Lab \"A\" \\ B"), "\"Lab \\\"A\\\" \\\\ B\"");
    }

    #[test]
    fn an_svg_scales_to_its_box() {
        let svg = "<svg width=\"800\" height=\"480\" xmlns=\"http://www.w3.org/2000/svg\">\n<rect/></svg>";
        let inline = inline_svg(svg);
        assert!(
            inline.starts_with("<svg class=\"figure\" xmlns="),
            "{inline}"
        );
        assert!(inline.contains("viewBox=\"0 0 800 480\""), "{inline}");
        assert!(!inline.contains("width=\"800\""));
    }

    fn gum() -> Coefficient {
        Coefficient {
            value: 1.0,
            u: 0.1,
            u95: 0.196,
            k: 1.96,
            dof: pipeline::DegreesOfFreedom::Finite(50.0),
        }
    }

    fn mc(gum_agrees: bool, d: f64, tolerance: f64) -> MonteCarloOutput {
        MonteCarloOutput {
            mean: 1.0,
            u: 0.1,
            low95: 0.79,
            high95: 1.22,
            gum_agrees,
            tolerance,
            d_low: d,
            d_high: 0.5 * d,
            heavy_tailed: false,
        }
    }

    #[test]
    fn the_headline_follows_jcgm_101_section_8() {
        // validated clearly: the GUM interval
        let h = Headline::of(&gum(), &mc(true, 1e-4, 1e-3));
        assert_eq!(h.method, HeadlineMethod::Gum);
        assert!((h.low - 0.804).abs() < 1e-12 && (h.high - 1.196).abs() < 1e-12);
        // not validated: the Monte Carlo interval, and the words say so
        let h = Headline::of(&gum(), &mc(false, 5e-3, 1e-3));
        assert_eq!(h.method, HeadlineMethod::MonteCarlo { borderline: false });
        assert_eq!((h.low, h.high), (0.79, 1.22));
        assert!(h.method_words().contains("not validated"));
        // within δ/2 of the threshold, on either side: borderline, the Monte Carlo interval
        // stated whichever verdict this run gave
        for (agrees, d) in [(true, 0.9e-3), (false, 1.1e-3)] {
            let h = Headline::of(&gum(), &mc(agrees, d, 1e-3));
            assert_eq!(h.method, HeadlineMethod::MonteCarlo { borderline: true });
            assert_eq!((h.low, h.high), (0.79, 1.22));
            assert!(h.method_words().contains("borderline"));
        }
    }
}
