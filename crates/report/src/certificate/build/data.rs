//! GUM against Monte Carlo, and the data the results come from.

use pipeline::{CalibrationResults, StudyResults, TwoOrientationResults};

use super::super::model::{DataUsed, Section, Text};
use super::text::{mounting_label, rich, runs, t, table};
use crate::format;
use crate::headline::headlines;

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

pub(super) fn gum_against_mc(c: &CalibrationResults) -> Section {
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
    section(
        "GUM against Monte Carlo (JCGM 101 §8)",
        mc.trials,
        mc.seed,
        "",
        rows,
    )
}

pub(super) fn gum_against_mc_two_orientation(s: &TwoOrientationResults) -> Section {
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
    section(
        "GUM against Monte Carlo, two-orientation method (JCGM 101 §8)",
        mc.trials,
        mc.seed,
        " Each mounting's k0 and k1 are stated with their GUM interval.",
        rows,
    )
}

/// A section comparing the GUM's intervals with Monte Carlo's: its heading, the trials and
/// the seed with what validation means (and `more`), and a row per coefficient.
fn section(heading: &str, trials: u64, seed: u64, more: &str, rows: Vec<Vec<Text>>) -> Section {
    Section {
        heading: heading.to_owned(),
        intro: rich(&format!(
            "{trials} trials (adaptive, JCGM 101 §7.9), seed {seed}. The GUM interval is \
             validated when both its ends lie within the numerical tolerance δ of the Monte \
             Carlo interval's.{more}"
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

pub(super) fn data_used(results: &StudyResults, c: &CalibrationResults) -> DataUsed {
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
