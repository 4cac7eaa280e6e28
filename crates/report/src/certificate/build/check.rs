//! The check of the certified k2 by the other method: both k2, C and C_r with their
//! intervals, and the verdict in a customer's words.

use pipeline::{CalibrationResults, HeadlineMethod, TwoOrientationResults};

use super::super::certified::{self, Certified, Method};
use super::super::model::{Check, Text};
use super::text::{
    interval_from, interval_row, interval_table, mounting_label, rich, signed, value_u_expanded,
};
use crate::format;
use crate::headline::{MICRO_UNITS, UNITS, headlines};

pub(super) fn check(s: &TwoOrientationResults, cert: &Certified, c: &CalibrationResults) -> Check {
    let micro = 1e6 / c.coefficients.k1.value;
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
    let probe_is_certified = cert.method == Method::Probe;
    let mut rows = Vec::new();
    k2_rows(&mut rows, s, c, micro, probe_is_certified);
    let (verdict, disagrees) = match &s.probe {
        Some(p) => probe_rows(&mut rows, s, p, micro, probe_is_certified),
        None => (
            rich("No probe phase was compared with the two-orientation fit."),
            false,
        ),
    };
    let heading = if probe_is_certified {
        "Check by the two-orientation method (not certified)"
    } else {
        "Check by the probe method (not certified)"
    };
    Check {
        heading: heading.to_owned(),
        intro: intro(probe_is_certified, &mountings),
        table: interval_table("quantity", &[16, 11, 10, 12, 5, 6, 8, 10], rows),
        verdict,
        disagrees,
    }
}

/// A headline's value, u and U (or its interval's widths) as cells, scaled by `scale`.
fn headline_cells(h: &pipeline::Headline, u: f64, scale: f64) -> [String; 3] {
    let (b, a) = h.widths(scale);
    value_u_expanded(h.value * scale, u * scale.abs(), b, a)
}

/// k and ν_eff of a headline stated by the GUM (`—` for a Monte Carlo interval).
fn k_dof(h: &pipeline::Headline, gum: &pipeline::Coefficient) -> (String, String) {
    if h.method == HeadlineMethod::Gum {
        (format::coverage_factor(gum.k), format::dof(gum.dof))
    } else {
        ("—".to_owned(), "—".to_owned())
    }
}

/// k2 by both methods, native and relative to k1, the method not certified marked so on each
/// of its rows (a check, not certified), and C.
fn k2_rows(
    rows: &mut Vec<Vec<Text>>,
    s: &TwoOrientationResults,
    c: &CalibrationResults,
    micro: f64,
    probe_is_certified: bool,
) {
    let heads = headlines(c);
    let mut row = |name: &str, cells, k, dof, unit: &str, from: &str| {
        rows.push(interval_row(name, cells, k, dof, unit, from));
    };
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
        UNITS[2],
        from,
    );
    row(
        &format!("{probe_tag}, relative to k1"),
        headline_cells(&probe.stated, probe.gum.u, micro),
        k,
        dof,
        MICRO_UNITS[2],
        from,
    );
    let (k, dof) = k_dof(&s.headline.k2, &s.k2);
    let from = interval_from(s.headline.k2.method, s.headline.k2.borderline);
    row(
        two_tag,
        headline_cells(&s.headline.k2, s.k2.u, 1.0),
        k.clone(),
        dof.clone(),
        UNITS[2],
        from,
    );
    row(
        &format!("{two_tag}, relative to k1"),
        headline_cells(&s.headline.k2, s.k2.u, micro),
        k,
        dof,
        MICRO_UNITS[2],
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
}

/// The probe's C_r and C − C_r, and the verdict of the comparison in a customer's words
/// (whether the methods disagree).
fn probe_rows(
    rows: &mut Vec<Vec<Text>>,
    s: &TwoOrientationResults,
    p: &pipeline::ProbeComparison,
    micro: f64,
    probe_is_certified: bool,
) -> (Text, bool) {
    let cr = format::pair(p.c_r_m_s2.value * 1e6, p.c_r_m_s2.u * 1e6);
    rows.push(interval_row(
        "C_r, spindle growth (probe)",
        [cr.value.clone(), cr.u.clone(), "—".to_owned()],
        "—".to_owned(),
        "—".to_owned(),
        "10⁻⁶ m·s²",
        "probe phase (standard uncertainty only)",
    ));
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
    rows.push(interval_row(
        "C − C_r, growth the probe misses",
        headline_cells(&stated, d.u, 1e6),
        k,
        dof,
        "10⁻⁶ m·s²",
        interval_from(stated.method, stated.borderline),
    ));
    // k2_difference is the two-orientation k2 less the probe method's
    let excess = -p.k2_difference;
    let above = if excess >= 0.0 { "above" } else { "below" };
    let native = format::significant(excess.abs(), 2);
    let relative = format::significant(excess.abs() * micro, 2);
    let verdict = rich(&if p.agrees {
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
    (verdict, !p.agrees)
}

/// What the check is, for the method certified.
fn intro(probe_is_certified: bool, mountings: &[String]) -> Text {
    rich(&if probe_is_certified {
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
    })
}
