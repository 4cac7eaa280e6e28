//! The certificate's tables: the results with their stated intervals, C_r and Δk2, the
//! statements of conformity, the k2 budget, GUM against Monte Carlo, the data used and the
//! input files with their digests.

use std::fmt::Write as _;

use pipeline::{
    AngleZero, CalibrationResults, CertificateResults, Certified, DecisionRule, HeadlineMethod,
    StudyResults, Verdict,
};

use crate::format;
use crate::format::esc;
use crate::headline::{Headline, MICRO_UNITS, NAMES, UNITS, headlines, micro_scale};
use crate::html::symbols;
use crate::provenance::{FileRecord, Provenance, Software};

/// The headline interval of a coefficient in a unit: `value`, `U` (symmetric) or `+a / -b`.
pub(crate) fn interval_cells(h: &Headline, scale: f64) -> (String, String) {
    let (below, above) = h.widths(scale);
    cells(h.value() * scale, below, above)
}

/// A value with interval half-widths `below` and `above`: `value`, `U` (symmetric) or
/// `+a / -b`.
fn cells(value: f64, below: f64, above: f64) -> (String, String) {
    let a = format::interval(value, below, above);
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

/// k and ν_eff of a GUM interval; a dash for a Monte Carlo one.
pub(crate) fn k_and_dof(h: &Headline) -> (String, String) {
    if h.is_gum() {
        (format::coverage_factor(h.gum.k), format::dof(h.gum.dof))
    } else {
        ("—".to_owned(), "—".to_owned())
    }
}

pub(crate) fn results_table(out: &mut String, c: &CalibrationResults, heads: &[Headline; 4]) {
    let _ = writeln!(
        out,
        "<table class=\"results\"><thead><tr><th>coefficient</th><th class=\"num\">value</th>\
         <th class=\"num\">expanded uncertainty U</th><th class=\"num\">k</th><th class=\"num\">ν<sub>eff</sub></th>\
         <th>unit</th><th>coverage interval from</th></tr></thead><tbody>"
    );
    for (n, h) in heads.iter().enumerate() {
        let (value, u) = interval_cells(h, 1.0);
        let (k, nu) = k_and_dof(h);
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
        let (k, nu) = k_and_dof(h);
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
        format::plain(c.g_m_s2),
    );
}

pub(crate) fn compensation_block(
    out: &mut String,
    c: &CalibrationResults,
    angle_zero: &AngleZero,
    k2: &Headline,
) {
    let k = k2.gum.k;
    let cr = format::pair(c.c_r_combined_m_s2.value, k * c.c_r_combined_m_s2.u);
    let dk2 = format::pair(c.delta_k2.value, k * c.delta_k2.u);
    let micro = micro_scale(c.coefficients.k1.value);
    let dk2_micro = format::pair(c.delta_k2.value * micro, k * c.delta_k2.u * micro.abs());
    let _ = writeln!(
        out,
        "<table class=\"ident\"><tbody>\
         <tr><th>C<sub>r</sub> of the spindle</th><td class=\"num\">{} m·s²</td><td>phase “{}”; U = k·u with k = {}, u from the fit, the probe gain, the lever heights and the rate scale (the inputs that carry C<sub>r</sub> into Δk2)</td></tr>\
         <tr><th>Probe sign convention</th><td colspan=\"2\">{}</td></tr>\
         <tr><th>Angle zero of the probe analysis</th><td colspan=\"2\">{}</td></tr>\
         <tr><th>Δk2 = k1·C<sub>r</sub>·g/R²</th><td class=\"num\">{} rad/(s·g²) = {} µg/g²</td>\
         <td>removed from the fitted a² coefficient (eq. 19); U from the same inputs as k2 (C<sub>r</sub>, probe gain, lever, rate scale, R, g, k1), k = {}</td></tr>\
         </tbody></table>",
        cr.joined(),
        esc(&c.compensate_with),
        format::coverage_factor(k),
        esc(c.probe_direction.words()),
        symbols(&angle_zero.words()),
        dk2.joined(),
        dk2_micro.joined(),
        format::coverage_factor(k),
    );
}

pub(crate) fn conformity(out: &mut String, info: &CertificateResults) {
    let Some(conformity) = &info.conformity else {
        return;
    };
    let _ = writeln!(out, "<h3>Statements of conformity</h3>");
    let _ = writeln!(
        out,
        "<p>Decision rule (ILAC-G8:09/2019 §4.2): {}</p>",
        match conformity.rule {
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
    for st in &conformity.statements {
        let (value, u) = cells(st.value, st.value - st.low95, st.high95 - st.value);
        let class = match st.verdict {
            Verdict::Pass => "verdict-pass",
            Verdict::ConditionalPass | Verdict::ConditionalFail => "verdict-conditional",
            Verdict::Fail => "verdict-fail",
        };
        let limit = |x: Option<f64>| x.map_or_else(|| "—".to_owned(), format::plain);
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td class=\"num\">{value}</td><td class=\"num\">{u}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{}</td><td>{}</td><td class=\"{class}\">{}</td></tr>",
            esc(&st.coefficient),
            limit(st.lower),
            limit(st.upper),
            esc(&st.unit),
            st.verdict.words(),
        );
    }
    let _ = writeln!(out, "</tbody></table>");
}

/// The unit of a budget's input quantity, by the name the budget gives it (`None` for a name
/// this table does not know: a test checks that every input of the fixtures has one).
pub(crate) fn input_unit(quantity: &str) -> Option<&'static str> {
    Some(match quantity {
        "R (working radius)" => "m",
        "g (gravity)" => "m/s²",
        "rate scale (common to every rate)" | "probe gain" => "1 (relative)",
        "pivot-to-probe height" | "probe-to-PIGA height" => "mm",
        "C_r of the compensating phase" => "m·s²",
        "k1 (given)" => "rad/(s·g)",
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

pub(crate) fn budget(out: &mut String, c: &CalibrationResults) {
    let _ = writeln!(out, "<h3>Uncertainty budget of k2 (JCGM 100)</h3>");
    let _ = writeln!(
        out,
        "<table class=\"budget\"><thead><tr><th>input quantity</th><th>type</th><th class=\"num\">value</th>\
         <th class=\"num\">standard uncertainty u</th><th class=\"unit\">unit</th>\
         <th class=\"num\">sensitivity c<br>(rad/(s·g²) per unit)</th>\
         <th class=\"num\">contribution |c|·u<br>(rad/(s·g²))</th><th class=\"num\">share of u²</th><th class=\"num\">ν</th></tr></thead><tbody>"
    );
    for l in &c.budget.k2 {
        let _ = writeln!(
            out,
            "<tr><td>{}{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"unit\">{}</td>\
             <td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{} %</td><td class=\"num\">{}</td></tr>",
            symbols(&l.quantity),
            l.note.as_ref().map_or_else(String::new, |n| format!(
                "<br><span class=\"note\">{}</span>",
                symbols(n)
            )),
            esc(&l.evaluation),
            l.value.map_or_else(|| "—".to_owned(), nominal),
            format::significant(l.u, 2),
            input_unit(&l.quantity).unwrap_or("—"),
            format::significant(l.sensitivity, 3),
            format::significant(l.contribution, 2),
            format::percent(l.percent),
            format::dof(l.dof),
        );
    }
    let k2 = &c.coefficients.k2;
    let _ = writeln!(
        out,
        "<tr><th colspan=\"6\">combined standard uncertainty u(k2), effective degrees of freedom</th>\
         <td class=\"num\">{}</td><td class=\"num\">100 %</td><td class=\"num\">{}</td></tr></tbody></table>",
        format::significant(k2.u, 2),
        format::dof(k2.dof)
    );
}

pub(crate) fn gum_against_mc(out: &mut String, c: &CalibrationResults) {
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
        let ends = EndsWriter::new(g.value, m.tolerance);
        let verdict = heads[n].verdict_words();
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"nowrap\">{verdict}</td><td class=\"unit\">{}</td></tr>",
            NAMES[n],
            ends.interval(g.value - g.u95, g.value + g.u95),
            ends.interval(m.low95, m.high95),
            format::significant(m.d_low.max(m.d_high), 2),
            format::significant(m.tolerance, 2),
            UNITS[n],
        );
    }
    let _ = writeln!(out, "</tbody></table>");
}

/// Writes the ends of a coefficient's GUM and Monte Carlo intervals in one power of ten (the
/// value's) and to the decimal place of the tolerance δ they are compared against, so that
/// their difference can be read and no digit below it is printed.
struct EndsWriter {
    /// The power of ten (0: none).
    exponent: i32,
    /// Decimals after the point of the scaled ends.
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

pub(crate) fn data_used(out: &mut String, results: &StudyResults, c: &CalibrationResults) {
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
            "<p>Spindle (phase “{}”): {} rates, {} deg/s{}; C<sub>r</sub> from the fit of {} with {} degrees of freedom.</p>",
            esc(&p.name),
            p.points.len(),
            rates.join(", "),
            if revolutions > 0 {
                format!("; {revolutions} whole revolutions of probe recording")
            } else {
                String::new()
            },
            symbols(pipeline::model_name(p.fit.model)),
            p.fit.dof,
        );
    }
    let _ = writeln!(
        out,
        "<p>PIGA{}: {} points at {} distinct rates, {} residual degrees of freedom; residual \
         standard deviation {} rad/s; {}.</p>",
        c.table
            .as_ref()
            .map_or_else(String::new, |t| format!(" (table {})", esc(t))),
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
    if let Some(s) = &results.two_orientation {
        let mountings: Vec<String> = s
            .mountings
            .iter()
            .map(|m| {
                format!(
                    "{} at R = {} m, {} points at {} distinct rates",
                    if m.orientation == "ia_in" {
                        "IA in"
                    } else {
                        "IA out"
                    },
                    format::plain(m.radius_m),
                    m.points,
                    m.distinct_rates
                )
            })
            .collect();
        let _ = writeln!(
            out,
            "<p>Check by the two-orientation method: {}; the joint fit has {} residual degrees \
             of freedom and a residual standard deviation of {} rad/s.</p>",
            mountings.join("; "),
            s.dof,
            format::significant(s.residual_sd_rad_s, 2)
        );
    }
    let warnings: Vec<String> = results
        .warnings
        .iter()
        .map(|w| {
            format!(
                "{} <span class=\"note\">(study field {})</span>",
                symbols(&w.message),
                symbols(&format!("`{}`", w.location))
            )
        })
        .chain(c.warnings.iter().map(|w| symbols(w)))
        .collect();
    if warnings.is_empty() {
        let _ = writeln!(out, "<p>No warnings were raised.</p>");
    } else {
        let _ = writeln!(out, "<p>Warnings raised by the evaluation:</p>");
        for w in warnings {
            let _ = writeln!(out, "<p class=\"warning\">{w}</p>");
        }
    }
}

pub(crate) fn files<'a>(out: &mut String, provenance: Option<&'a Provenance>, software: &Software) {
    let _ = writeln!(out, "<h3>Input files and software</h3>");
    let Some(provenance) = provenance else {
        let _ = writeln!(
            out,
            "<p class=\"warning\">The input files and their SHA-256 digests were not recorded \
             with these results.</p>\n<p>Software: {}, commit <span class=\"hash\">{}</span>.</p>",
            esc(&software.version),
            esc(&software.commit)
        );
        return;
    };
    let _ = writeln!(
        out,
        "<table><thead><tr><th>file</th><th class=\"num\">bytes</th><th>SHA-256</th></tr></thead><tbody>"
    );
    // a file read by two sections (the IA-in table by the calibration and the two-orientation
    // fit) is listed once
    let mut listed: Vec<(&str, &str)> = Vec::new();
    let mut record = |out: &mut String, what: &str, f: &'a FileRecord| {
        if listed.contains(&(f.path.as_str(), f.sha256.as_str())) {
            return;
        }
        listed.push((f.path.as_str(), f.sha256.as_str()));
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

/// The certified coefficients (`results.certificate.certified`) when another method than the
/// probe method is certified: what is certified, why, and each coefficient with its stated
/// 95 % interval, in its unit and relative to k1.
pub(crate) fn certified_table(out: &mut String, k: &Certified) {
    let _ = writeln!(
        out,
        "<p><strong>Certified: {}.</strong> {}</p>",
        esc(k.method.words()),
        esc(&k.reason)
    );
    let _ = writeln!(
        out,
        "<table class=\"results\"><thead><tr><th>coefficient</th><th class=\"num\">value</th>\
         <th class=\"num\">expanded uncertainty U</th><th class=\"num\">k</th><th class=\"num\">ν<sub>eff</sub></th>\
         <th>unit</th><th>coverage interval from</th></tr></thead><tbody>"
    );
    for q in &k.coefficients {
        let mounting = match q.mounting.as_deref() {
            Some("ia_in") => " (input axis towards the spindle axis)".to_owned(),
            Some("ia_out") => " (input axis away from the spindle axis)".to_owned(),
            Some(m) => format!(" ({m})"),
            None => String::new(),
        };
        let name = format!("{}{mounting}", q.name);
        let (kk, nu) = match q.k {
            Some(f) => (format::coverage_factor(f), format::dof(q.dof)),
            None => ("—".to_owned(), "—".to_owned()),
        };
        let method = match q.interval_method {
            HeadlineMethod::Gum => "GUM (JCGM 100)",
            HeadlineMethod::MonteCarlo => "Monte Carlo (JCGM 101)",
        };
        let (value, u) = cells(q.value, q.value - q.low95, q.high95 - q.value);
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td class=\"num\">{value}</td><td class=\"num\">{u}</td><td class=\"num\">{kk}</td>\
             <td class=\"num\">{nu}</td><td>{}</td><td>{method}</td></tr>",
            esc(&name),
            esc(&q.unit)
        );
        if let Some(r) = &q.relative {
            let (value, u) = cells(r.value, r.value - r.low95, r.high95 - r.value);
            let _ = writeln!(
                out,
                "<tr><td>{}/k1{}</td><td class=\"num\">{value}</td><td class=\"num\">{u}</td><td class=\"num\">{kk}</td>\
                 <td class=\"num\">{nu}</td><td>{}</td><td>{method}</td></tr>",
                esc(&q.name),
                esc(&mounting),
                esc(&r.unit)
            );
        }
    }
    let _ = writeln!(out, "</tbody></table>");
}
