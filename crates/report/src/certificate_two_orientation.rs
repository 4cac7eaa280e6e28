//! The certificate's check by the two-orientation method (a study with both a `two_orientation`
//! and a `certificate` section, `docs/CERTIFICATE.md`): k2 from the PIGA alone beside the
//! certified k2 of the probe method, in rad/(s·g²) and relative to k1, and the PIGA's total
//! radius growth C against the probe's C_r, with z and what it means in words.

use std::fmt::Write as _;

use pipeline::{Coefficient, TwoOrientationResults};

use crate::certificate_tables::{interval_cells, k_and_dof};
use crate::format;
use crate::format::esc;
use crate::headline::{Headline, micro_scale};

/// The unit the radius growths C, C_r and C − C_r are written in (one power of ten for all
/// three, so that the difference reads at a glance).
const GROWTH_UNIT: &str = "10⁻⁶ m·s²";

/// A row of the check's table: a quantity (HTML), its value and U, k and ν_eff, its unit and
/// where its interval comes from (HTML).
fn row(
    out: &mut String,
    quantity: &str,
    cells: (String, String),
    k_nu: (String, String),
    unit: &str,
    from: &str,
) {
    let (value, u) = cells;
    let (k, nu) = k_nu;
    let _ = writeln!(
        out,
        "<tr><td>{quantity}</td><td class=\"num\">{value}</td><td class=\"num\">{u}</td>\
         <td class=\"num\">{k}</td><td class=\"num\">{nu}</td><td class=\"unit\">{unit}</td><td>{from}</td></tr>"
    );
}

/// The mounting's words: `IA in: towards the spindle axis, R = 2.5 m`.
fn mounting_words(orientation: &str, radius_m: f64) -> String {
    let which = if orientation == "ia_in" {
        "IA in: towards the spindle axis"
    } else {
        "IA out: away from it"
    };
    format!("{which}, R = {} m", format::plain(radius_m))
}

/// Appends the check: `certified_k2` is the results table's k2 headline and `k1` the
/// certified k1 (the relative values use it, as the results table does).
pub(crate) fn certificate_block(
    out: &mut String,
    s: &TwoOrientationResults,
    certified_k2: &Headline,
    k1: f64,
    probe_certified: bool,
) {
    let _ = writeln!(out, "<section class=\"check\">");
    let _ = writeln!(out, "<h3>Check by the two-orientation method</h3>");
    let mountings: Vec<String> = s
        .mountings
        .iter()
        .map(|m| mounting_words(&m.orientation, m.radius_m))
        .collect();
    let _ = writeln!(
        out,
        "<p>The PIGA was also measured with its input axis turned round ({}) and both data sets \
         fitted jointly (eq. 23). Turning the input axis round reverses the sign of the radius \
         growth's term in the output but not that of k2·a²: the joint fit gives k2 and the total \
         dynamic growth C of the working radius from the PIGA's own output, without the \
         displacement probe. Sign convention: the working radius is R + C·ω², C and C<sub>r</sub> \
         positive when the radius grows with the rate; C − C<sub>r</sub> &gt; 0 when the PIGA \
         sees more growth than the probe.</p>",
        mountings.join("; ")
    );
    let _ = writeln!(
        out,
        "<table class=\"check\"><thead><tr><th>quantity</th><th class=\"num\">value</th>\
         <th class=\"num\">expanded uncertainty U</th><th class=\"num\">k</th><th class=\"num\">ν<sub>eff</sub></th>\
         <th class=\"unit\">unit</th><th>coverage interval from</th></tr></thead><tbody>"
    );
    let two = Headline {
        stated: s.headline.k2,
        gum: s.k2,
    };
    let c = Headline {
        stated: s.headline.c,
        gum: s.c_m_s2,
    };
    let micro = micro_scale(k1);
    for (name, h, scale, unit) in [
        (
            if probe_certified {
                "k2, probe method (certified above)"
            } else {
                "k2, probe method (a check, not certified)"
            },
            certified_k2,
            1.0,
            "rad/(s·g²)",
        ),
        ("k2, two-orientation method", &two, 1.0, "rad/(s·g²)"),
        (
            if probe_certified {
                "k2/k1, probe method (certified above)"
            } else {
                "k2/k1, probe method (a check, not certified)"
            },
            certified_k2,
            micro,
            "µg/g²",
        ),
        ("k2/k1, two-orientation method", &two, micro, "µg/g²"),
        ("C, total radius growth (PIGA alone)", &c, 1e6, GROWTH_UNIT),
    ] {
        row(
            out,
            &esc(name),
            interval_cells(h, scale),
            k_and_dof(h),
            unit,
            h.method_short(),
        );
    }
    if let Some(p) = &s.probe {
        let cr = format::pair(p.c_r_m_s2.value * 1e6, p.c_r_m_s2.u * 1e6);
        let scaled = |x: &str| {
            if cr.scale.is_empty() {
                x.to_owned()
            } else {
                format!("{x} {}", cr.scale)
            }
        };
        row(
            out,
            "C<sub>r</sub>, spindle growth (probe)",
            (scaled(&cr.value), "—".to_owned()),
            ("—".to_owned(), "—".to_owned()),
            GROWTH_UNIT,
            &format!(
                "u = {} (standard uncertainty; phase “{}”)",
                scaled(&cr.u),
                esc(&p.phase)
            ),
        );
        let d = &p.difference_m_s2;
        // the Monte Carlo's §8 rule when it evaluated the difference, else the GUM alone
        let (diff, from) = match &s.monte_carlo.difference {
            Some(mc) => {
                let h = Headline {
                    stated: pipeline::Headline::of(d, mc),
                    gum: *d,
                };
                (h, h.method_short())
            }
            None => (gum_only(d), "GUM"),
        };
        row(
            out,
            "C − C<sub>r</sub>, growth the probe misses",
            interval_cells(&diff, 1e6),
            k_and_dof(&diff),
            GROWTH_UNIT,
            from,
        );
    }
    let _ = writeln!(out, "</tbody></table>");
    if let Some(p) = &s.probe {
        // k2_difference is the two-orientation k2 less the probe method's
        let excess = -p.k2_difference;
        let excess_native = format::significant(excess.abs(), 2);
        let excess_micro = format::significant(excess.abs() * micro, 2);
        let above = if excess >= 0.0 { "above" } else { "below" };
        if !p.agrees {
            let _ = writeln!(
                out,
                "<p class=\"warning\"><strong>The two methods disagree</strong>: z = (C − C<sub>r</sub>)/u(C − C<sub>r</sub>) \
                 = {z}, beyond ±3. Either the probe is declared wrongly — the encoder's angle zero \
                 relative to the arm, the probe's sign convention or its gap unit (each changes \
                 C<sub>r</sub> with no other sign) — or, those right, the working radius grows in a \
                 way the probe does not see (the arm stretching under centrifugal load, a mount \
                 that gives) or the lever heights are wrong. The probe method's k2 is \
                 compensated with the probe's C<sub>r</sub> only and keeps k1·(C − C<sub>r</sub>)·g/R²: \
                 it lies {above} the two-orientation k2 by {excess_native} rad/(s·g²) \
                 ({excess_micro} µg/g²){certified}.</p>",
                z = signed(p.z),
                certified = if probe_certified {
                    "; it is certified only because the study says so \
                     (certificate.certify_despite_check)"
                } else {
                    "; the two-orientation k2 is the one certified"
                },
            );
        } else {
            let _ = writeln!(
                out,
                "<p>z = (C − C<sub>r</sub>)/u(C − C<sub>r</sub>) = {z}, within ±3: the radius growth \
                 the PIGA measures agrees with the probe's, and the probe method's compensation is \
                 confirmed by the PIGA's own output (the probe method's k2 lies {above} the \
                 two-orientation k2 by {excess_native} rad/(s·g²), {excess_micro} µg/g²).</p>",
                z = signed(p.z),
            );
        }
    }
    let _ = writeln!(out, "</section>");
}

/// A GUM headline of a coefficient that has no Monte Carlo counterpart.
fn gum_only(c: &Coefficient) -> Headline {
    Headline {
        stated: pipeline::Headline {
            value: c.value,
            low95: c.value - c.u95,
            high95: c.value + c.u95,
            method: pipeline::HeadlineMethod::Gum,
            borderline: false,
        },
        gum: *c,
    }
}

/// `+7.9`, `−0.4` (a true minus sign).
fn signed(z: f64) -> String {
    let text = format!("{z:+.1}");
    text.replacen('-', "−", 1)
}
