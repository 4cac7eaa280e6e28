//! A unit's history and a centrifuge's health as a person reads them (`centrifuge-cal
//! history`): a text for the terminal and an SVG chart. Computes nothing: the drift, the
//! predictions, the interval and the advice come from `records`.

use std::fmt::Write as _;

use records::{
    Advice, AtSource, CentrifugeHealth, Date, Drift, NextSource, Prediction, UnitHistory,
};

use crate::error::{ReportError, Result};
use crate::format::{pair, significant};
use crate::svgplot::{Figure, Panel, Series};

/// Text from the records written on a terminal: hidden characters shown visibly.
fn shown(text: &str) -> String {
    edge_io::visible(text).into_owned()
}

/// A value ± its expanded uncertainty.
fn pm(value: f64, expanded: f64) -> String {
    pair(value, expanded).joined()
}

/// A signed value ± its expanded uncertainty (`+` written for a positive drift).
fn signed_pm(value: f64, expanded: f64) -> String {
    let text = pm(value, expanded);
    if value > 0.0 {
        if let Some(rest) = text.strip_prefix('(') {
            format!("(+{rest}")
        } else {
            format!("+{text}")
        }
    } else {
        text
    }
}

/// A share or a probability in percent as a person writes it (`20 %`, `99.5 %`).
fn percent(fraction: f64) -> String {
    let text = format!("{:.3}", fraction * 100.0);
    let text = text.trim_end_matches('0').trim_end_matches('.');
    format!("{text} %")
}

/// What the drift was fitted through, and the scale it is written in (`1e6` for µm·s²).
struct Fitted {
    what: &'static str,
    scale: f64,
}

const CERTIFICATES: Fitted = Fitted {
    what: "certificates",
    scale: 1.0,
};

fn drift_line(d: &Drift, unit: &str, fitted: &Fitted) -> String {
    let mut line = format!(
        "drift {} {unit} per year (± U95, k = {}, {} {}): {}",
        signed_pm(
            d.rate_per_year * fitted.scale,
            d.expanded_rate_per_year * fitted.scale
        ),
        significant(d.k95, 3),
        d.points,
        fitted.what,
        if d.significant {
            "significant at 95 %"
        } else {
            "not significant at 95 %"
        }
    );
    if d.scaled_by_scatter {
        let _ = write!(
            line,
            "; the values scatter more than their uncertainties say (Birge ratio {}): u of the drift enlarged by it, k from Student's t with {} degrees of freedom",
            significant(d.birge_ratio.unwrap_or(1.0), 3),
            d.points.saturating_sub(2)
        );
    }
    line
}

fn prediction_line(p: &Prediction, unit: &str, what: &str, reading: &str) -> String {
    format!(
        "{what} on {}: {} {unit} (± U95 of the value; {reading} on that date would read it ± {})",
        p.date,
        pm(p.value, p.k95 * p.u),
        significant(p.k95 * p.u_reading, 2)
    )
}

/// The unit's history as the terminal shows it.
pub fn history_text(h: &UnitHistory) -> String {
    let mut out = String::new();
    let u = &h.unit;
    let _ = writeln!(
        out,
        "unit {} {} (serial {}), {}",
        shown(&u.manufacturer),
        shown(&u.model),
        shown(&u.serial),
        shown(&u.kind)
    );
    let current = h.certificates.iter().filter(|c| c.is_current()).count();
    let _ = writeln!(
        out,
        "{} certificate{} recorded, {current} current",
        h.certificates.len(),
        if h.certificates.len() == 1 { "" } else { "s" }
    );
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "{:<24} {:<10} {:<10} status",
        "certificate", "measured", "issued"
    );
    for c in &h.certificates {
        let status = match (&c.superseded_by, &c.supersedes) {
            (Some(by), _) => format!("superseded by {} (not used)", shown(by)),
            (None, Some(old)) => format!("current, corrects {}", shown(old)),
            (None, None) => "current".to_owned(),
        };
        let _ = writeln!(
            out,
            "{:<24} {:<10} {:<10} {status}",
            shown(&c.id),
            c.measured.to_string(),
            c.issued.to_string()
        );
    }
    for t in &h.terms {
        let _ = writeln!(out);
        let _ = writeln!(out, "{}, {} (value ± U95)", t.label, t.unit);
        for p in &t.points {
            let _ = writeln!(
                out,
                "  {}  {:<24} {}",
                p.date,
                shown(&p.certificate),
                pm(p.value, p.expanded)
            );
        }
        match (&t.drift, &t.prediction) {
            (Some(d), Some(p)) => {
                let _ = writeln!(out, "  {}", drift_line(d, &t.unit, &CERTIFICATES));
                let _ = writeln!(
                    out,
                    "  {}",
                    prediction_line(p, &t.unit, "predicted", "a calibration")
                );
            }
            (Some(d), None) => {
                let _ = writeln!(out, "  {}", drift_line(d, &t.unit, &CERTIFICATES));
            }
            _ => {
                let _ = writeln!(
                    out,
                    "  no drift: certificates on two dates or more are needed"
                );
            }
        }
    }
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "predictions on {}: {}",
        h.at,
        match h.at_source {
            AtSource::Given => "the date given (--at)",
            AtSource::IntervalEnd => "the end of the recommended interval",
            AtSource::OneYearAfterLatest =>
                "one year after the latest certificate (no --at given and no interval asked for)",
        }
    );
    if let Some(i) = &h.interval {
        let iv = &i.interval;
        let _ = writeln!(out);
        let head = format!(
            "recommended interval for {} (tolerance ± {} {} on the deviation from the value certified, reliability {})",
            i.term,
            significant(iv.request.tolerance, 3),
            i.unit,
            percent(iv.request.reliability)
        );
        let verdict = match (iv.attainable, iv.years, i.due) {
            (false, _, _) => format!(
                "none: the tolerance is not held even on the day of calibration (z_R·u₀ = {} ≥ {})",
                significant(iv.z * iv.u0, 3),
                significant(iv.request.tolerance, 3)
            ),
            (true, Some(y), Some(due)) => {
                format!("{} years from {}, due {due}", significant(y, 3), i.from)
            }
            _ => "not limited by the drift: no drift and no uncertainty of it".to_owned(),
        };
        let _ = writeln!(out, "{head}: {verdict}");
        let _ = writeln!(
            out,
            "  from u₀ = {} {unit} (the latest certificate), drift |b| = {} ± {} {unit} per year (standard uncertainties), z_R = {}",
            significant(iv.u0, 3),
            significant(iv.rate_per_year, 3),
            significant(iv.u_rate_per_year, 3),
            significant(iv.z, 4),
            unit = i.unit
        );
        let _ = writeln!(out, "  method: {}", i.method);
        let _ = writeln!(out, "  assumptions: {}", i.assumptions);
    }
    out
}

/// Decimal years (2026.88) of a date, for a chart's axis.
fn year(d: Date) -> f64 {
    let (y, _, _) = d.ymd();
    let start = Date::from_ymd(y, 1, 1).unwrap_or(d);
    #[allow(clippy::cast_precision_loss)] // years and days of the calendar
    let value = y as f64 + (d.days() - start.days()) as f64 / records::DAYS_PER_YEAR;
    value
}

/// A y range that is not empty (one point without a bar spans nothing).
fn open_range((lo, hi): (f64, f64)) -> (f64, f64) {
    if hi > lo {
        (lo, hi)
    } else {
        let half = (0.1 * lo.abs()).max(f64::MIN_POSITIVE * 1e10);
        (lo - half, hi + half)
    }
}

fn x_range(dates: &[Date]) -> (f64, f64) {
    let lo = dates.iter().map(|d| year(*d)).fold(f64::INFINITY, f64::min);
    let hi = dates
        .iter()
        .map(|d| year(*d))
        .fold(f64::NEG_INFINITY, f64::max);
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.08).max(0.25);
    (lo - pad, hi + pad)
}

/// The unit's history as a chart: one panel per certified term, its values with U95 bars,
/// the drift line and the value predicted with the U95 of a calibration on that date.
///
/// # Errors
/// [`ReportError::Plot`] when no certificate is current.
pub fn history_svg(h: &UnitHistory) -> Result<String> {
    if h.terms.is_empty() {
        return Err(ReportError::Plot {
            what: "history.svg",
            message: "the unit has no current certificate".to_owned(),
        });
    }
    let mut dates: Vec<Date> = h
        .terms
        .iter()
        .flat_map(|t| t.points.iter().map(|p| p.date))
        .collect();
    if h.terms.iter().any(|t| t.prediction.is_some()) {
        dates.push(h.at);
    }
    let xr = x_range(&dates);
    let panels = h
        .terms
        .iter()
        .map(|t| {
            let mut series = vec![Series::ErrorBars {
                points: t
                    .points
                    .iter()
                    .map(|p| (year(p.date), p.value, p.expanded))
                    .collect(),
                color: "#1f4e9c",
                label: Some("certified value ± U95".to_owned()),
            }];
            if let (Some(d), Some(p)) = (&t.drift, &t.prediction) {
                let first = t.points.first().map_or(d.origin, |p| p.date);
                let at = |date: Date| d.intercept + d.rate_per_year * date.years_since(d.origin);
                series.push(Series::Line {
                    points: vec![(year(first), at(first)), (year(p.date), at(p.date))],
                    color: "#888",
                    width: 1.2,
                    label: Some("drift (weighted fit)".to_owned()),
                });
                series.push(Series::ErrorBars {
                    points: vec![(year(p.date), p.value, p.k95 * p.u_reading)],
                    color: "#c0392b",
                    label: Some(format!("predicted on {} ± U95", p.date)),
                });
            }
            Panel {
                title: Some(t.label.clone()),
                x_label: "date (year)".to_owned(),
                y_label: t.unit.clone(),
                x_range: xr,
                y_range: open_range(Panel::fit_y(&series, 0.12, 0.0)),
                x_step: None,
                series,
                legend: true,
                zero_line: false,
            }
        })
        .collect::<Vec<_>>();
    let figure = Figure {
        width: 1000.0,
        title: format!(
            "{} {}, serial {}: certified coefficients by date",
            shown(&h.unit.manufacturer),
            shown(&h.unit.model),
            shown(&h.unit.serial)
        ),
        columns: 2,
        panel_height: 330.0,
        panels,
    };
    Ok(figure.render())
}

/// The centrifuge's health as the terminal shows it.
pub fn health_text(h: &CentrifugeHealth) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "centrifuge {}: {} campaign{}, {} balance event{}",
        shown(&h.name),
        h.campaigns.len(),
        if h.campaigns.len() == 1 { "" } else { "s" },
        h.balances.len(),
        if h.balances.len() == 1 { "" } else { "s" }
    );
    let _ = writeln!(
        out,
        "(per campaign the probe phase its calibration compensated with, else its last phase)"
    );
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "{:<10}  {:<22} {:<12} {:>22} {:>12} {:>28}",
        "date", "study", "phase", "C_r µm·s² (± 2σ)", "offset µm", "Δk2 rad/(s·g²) (± 2σ)"
    );
    let mut events = h.balances.iter().peekable();
    for c in &h.campaigns {
        while let Some(b) = events.next_if(|b| b.date <= c.date) {
            let _ = writeln!(out, "{}  balanced: {}", b.date, shown(&b.note));
        }
        let with_u = |v: f64, u: Option<f64>, scale: f64| match u {
            Some(u) => pm(v * scale, 2.0 * u * scale),
            None => significant(v * scale, 4),
        };
        let _ = writeln!(
            out,
            "{:<10}  {:<22} {:<12} {:>22} {:>12} {:>28}",
            c.date.to_string(),
            shown(&c.study),
            shown(&c.phase),
            with_u(c.c_r_m_s2, c.c_r_u_m_s2, 1e6),
            significant(c.offset_um, 4),
            with_u(c.delta_k2_rad_s_g2, c.delta_k2_u_rad_s_g2, 1.0)
        );
    }
    for b in events {
        let _ = writeln!(out, "{}  balanced: {}", b.date, shown(&b.note));
    }
    let _ = writeln!(out);
    match h.since {
        Some(s) => {
            let _ = writeln!(
                out,
                "since the latest balance ({s}): {} campaign{} fitted",
                h.fitted,
                if h.fitted == 1 { "" } else { "s" }
            );
        }
        None => {
            let _ = writeln!(
                out,
                "no balance recorded: all {} campaigns fitted",
                h.fitted
            );
        }
    }
    let campaigns = |scale| Fitted {
        what: "campaigns",
        scale,
    };
    if let Some(d) = &h.c_r_drift {
        let _ = writeln!(out, "C_r {}", drift_line(d, "µm·s²", &campaigns(1e6)));
    }
    if let Some(d) = &h.delta_k2_drift {
        let _ = writeln!(out, "Δk2 {}", drift_line(d, "rad/(s·g²)", &campaigns(1.0)));
    }
    if let Some(next) = h.next {
        let _ = writeln!(
            out,
            "next campaign on {next}: {}",
            match h.next_source {
                NextSource::Given => "the date given (--next)",
                NextSource::MeanSpacing =>
                    "the latest campaign plus the mean spacing of the campaigns fitted (no --next given)",
            }
        );
    }
    if let Some(p) = &h.predicted_delta_k2 {
        let _ = writeln!(
            out,
            "{}",
            prediction_line(p, "rad/(s·g²)", "Δk2 predicted", "a campaign")
        );
    }
    let limit_words = |l: f64, t: f64| {
        format!(
            "{} of the target U95 of k2 ({} rad/(s·g²)): {} rad/(s·g²)",
            percent(h.share),
            significant(t, 3),
            significant(l, 3)
        )
    };
    let _ = writeln!(out);
    match (
        h.advice,
        h.limit_rad_s_g2,
        h.target_u95_rad_s_g2,
        &h.predicted_delta_k2,
    ) {
        (Advice::Rebalance, Some(l), Some(t), Some(p)) => {
            let _ = writeln!(
                out,
                "warning: rebalance before the next campaign. Δk2 predicted on {} is {} rad/(s·g²), above {}. Δk2 is what the probe method removes from k2, so the compensation's error grows with it: beyond this share of the target U95 it puts the calibration's uncertainty at risk.",
                p.date,
                significant(p.value, 3),
                limit_words(l, t)
            );
        }
        (Advice::MayExceed, Some(l), Some(t), Some(p)) => {
            let _ = writeln!(
                out,
                "caution: Δk2 predicted on {} is {} rad/(s·g²), below {}, but its 95 % interval reaches above it; consider rebalancing before the next campaign.",
                p.date,
                significant(p.value, 3),
                limit_words(l, t)
            );
        }
        (Advice::Fine, Some(l), Some(t), Some(p)) => {
            let _ = writeln!(
                out,
                "no rebalance needed: Δk2 predicted on {} is {} rad/(s·g²), and its 95 % interval stays below {}.",
                p.date,
                significant(p.value, 3),
                limit_words(l, t)
            );
        }
        (Advice::TooFewCampaigns, _, _, _) => {
            let _ = writeln!(
                out,
                "no prediction: campaigns on two dates or more since the latest balance are needed, with Δk2's uncertainty."
            );
        }
        _ => {
            let _ = writeln!(
                out,
                "no advice on rebalancing: give --target-u95 (the U95 of k2 the calibration is to meet, rad/(s·g²)) and --share."
            );
        }
    }
    out
}

/// The centrifuge's health as a chart: C_r, the offset and Δk2 by date, the balance events
/// as vertical lines, Δk2's prediction and the limit.
///
/// # Errors
/// [`ReportError::Plot`] when there is no campaign.
pub fn health_svg(h: &CentrifugeHealth) -> Result<String> {
    if h.campaigns.is_empty() {
        return Err(ReportError::Plot {
            what: "centrifuge.svg",
            message: "the centrifuge has no campaign".to_owned(),
        });
    }
    let mut dates: Vec<Date> = h.campaigns.iter().map(|c| c.date).collect();
    dates.extend(h.balances.iter().map(|b| b.date));
    if let Some(p) = &h.predicted_delta_k2 {
        dates.push(p.date);
    }
    let xr = x_range(&dates);
    let panel = |title: &str, unit: &str, mut series: Vec<Series>, extra: Vec<f64>| {
        let mut y = Panel::fit_y(&series, 0.12, 0.0);
        for e in extra {
            y = (y.0.min(e), y.1.max(e));
        }
        let y = open_range(y);
        let first_balance = std::cell::Cell::new(true);
        for b in &h.balances {
            series.push(Series::Line {
                points: vec![(year(b.date), y.0), (year(b.date), y.1)],
                color: "#2e8b57",
                width: 1.5,
                label: first_balance.replace(false).then(|| "balanced".to_owned()),
            });
        }
        Panel {
            title: Some(title.to_owned()),
            x_label: "date (year)".to_owned(),
            y_label: unit.to_owned(),
            x_range: xr,
            y_range: y,
            x_step: None,
            series,
            legend: true,
            zero_line: false,
        }
    };
    let bars = |pick: &dyn Fn(&records::Campaign) -> (f64, Option<f64>)| {
        h.campaigns
            .iter()
            .map(|c| {
                let (v, u) = pick(c);
                (year(c.date), v, 2.0 * u.unwrap_or(0.0))
            })
            .collect::<Vec<_>>()
    };
    let c_r = panel(
        "C_r",
        "µm·s²",
        vec![Series::ErrorBars {
            points: bars(&|c| (c.c_r_m_s2 * 1e6, c.c_r_u_m_s2.map(|u| u * 1e6))),
            color: "#1f4e9c",
            label: Some("C_r ± 2σ".to_owned()),
        }],
        Vec::new(),
    );
    let offset = panel(
        "static offset (the radius error's constant term)",
        "µm",
        vec![Series::Points {
            points: h
                .campaigns
                .iter()
                .map(|c| (year(c.date), c.offset_um))
                .collect(),
            color: "#1f4e9c",
            radius: 3.5,
            label: Some("offset".to_owned()),
        }],
        Vec::new(),
    );
    let mut dk2 = vec![Series::ErrorBars {
        points: bars(&|c| (c.delta_k2_rad_s_g2, c.delta_k2_u_rad_s_g2)),
        color: "#1f4e9c",
        label: Some("Δk2 ± 2σ".to_owned()),
    }];
    let mut extra = Vec::new();
    if let (Some(p), Some(d), Some(since)) = (
        &h.predicted_delta_k2,
        &h.delta_k2_drift,
        h.campaigns
            .iter()
            .map(|c| c.date)
            .find(|date| h.since.is_none_or(|s| *date >= s)),
    ) {
        let at = |date: Date| d.intercept + d.rate_per_year * date.years_since(d.origin);
        dk2.push(Series::Line {
            points: vec![(year(since), at(since)), (year(p.date), at(p.date))],
            color: "#888",
            width: 1.2,
            label: Some("drift since the latest balance (weighted fit)".to_owned()),
        });
    }
    if let Some(p) = &h.predicted_delta_k2 {
        dk2.push(Series::ErrorBars {
            points: vec![(year(p.date), p.value, p.k95 * p.u)],
            color: "#c0392b",
            label: Some(format!("predicted on {} ± U95", p.date)),
        });
    }
    if let Some(l) = h.limit_rad_s_g2 {
        dk2.push(Series::Line {
            points: vec![(xr.0, l), (xr.1, l)],
            color: "#e67e22",
            width: 1.5,
            label: Some(format!("{} of the target U95", percent(h.share))),
        });
        extra.push(l);
    }
    let dk2 = panel("Δk2 = k1·C_r·g/R²", "rad/(s·g²)", dk2, extra);
    let figure = Figure {
        width: 1000.0,
        title: format!("centrifuge {}: health by date", shown(&h.name)),
        columns: 1,
        panel_height: 280.0,
        panels: vec![c_r, offset, dk2],
    };
    Ok(figure.render())
}
