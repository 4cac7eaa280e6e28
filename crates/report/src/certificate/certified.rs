//! What the certificate certifies: the method, why, its coefficients with their
//! uncertainties, the other method as a check, and where the coefficients hold.
//!
//! Interim: `pipeline` is to state this itself (`results.certificate.certified`,
//! `/work/tools/CERTIFIED-CONTRACT.md`); until it does, it is read here from the calibration
//! section (the probe method, on the IA-in mounting), with the two-orientation section as the
//! check. [`certified`] is the one place that changes when the field lands.

use pipeline::{
    CalibrationResults, DegreesOfFreedom, HeadlineMethod, StudyResults, TwoOrientationResults,
};

/// The method whose coefficients are certified.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Method {
    /// The paper's eq. 18 on one mounting, k2 compensated with the probe's C_r.
    Probe,
    /// Eq. 23 on both mountings, k2 from the PIGA alone.
    TwoOrientation,
}

/// A certified coefficient (native unit), with its value relative to k1.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Coefficient {
    /// `k0` … `k3`.
    pub name: &'static str,
    /// `ia_in`, `ia_out`, or `None` when shared by the mountings.
    pub mounting: Option<&'static str>,
    pub unit: &'static str,
    pub value: f64,
    /// Standard uncertainty.
    pub u: f64,
    pub low95: f64,
    pub high95: f64,
    /// Expanded uncertainty (the larger half-width of a Monte Carlo interval).
    pub expanded: f64,
    /// Coverage factor of a GUM interval; `None` for a Monte Carlo one.
    pub k: Option<f64>,
    pub dof: DegreesOfFreedom,
    pub interval_method: HeadlineMethod,
    /// The GUM validation is borderline (the Monte Carlo interval is stated for that).
    pub borderline: bool,
    pub relative: Option<Relative>,
}

/// A coefficient relative to k1 (µg, µg/g², µg/g³).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Relative {
    pub unit: &'static str,
    pub value: f64,
    pub u: f64,
    pub low95: f64,
    pub high95: f64,
    pub expanded: f64,
}

/// The other method's k2, as a check of the certified one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Check {
    pub method: Method,
    /// Its k2, rad/(s·g²), with standard and expanded uncertainty.
    pub k2: f64,
    pub u: f64,
    pub expanded: f64,
    /// z of (C − C_r).
    pub z: f64,
    pub agrees: bool,
}

/// Where the coefficients hold: one mounting's rates and specific forces.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Validity {
    pub mounting: &'static str,
    pub mounting_words: &'static str,
    pub radius_m: f64,
    pub rate_low_deg_s: f64,
    pub rate_high_deg_s: f64,
    pub specific_force_low_g: f64,
    pub specific_force_high_g: f64,
    pub points: usize,
}

/// What is certified.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Certified {
    pub method: Method,
    /// Why this method, in a customer's words.
    pub reason: String,
    pub check: Option<Check>,
    /// The certified value is one the study's own check refutes.
    pub refuted_by_check: bool,
    pub coefficients: Vec<Coefficient>,
    pub validity: Vec<Validity>,
}

/// The mounting in words.
pub(crate) fn mounting_words(mounting: &str) -> &'static str {
    match mounting {
        "ia_out" => "input axis away from the spindle axis",
        _ => "input axis towards the spindle axis",
    }
}

const NAMES: [&str; 4] = ["k0", "k1", "k2", "k3"];
const UNITS: [&str; 4] = ["rad/s", "rad/(s·g)", "rad/(s·g²)", "rad/(s·g³)"];
const MICRO_UNITS: [&str; 4] = ["µg", "", "µg/g²", "µg/g³"];

/// What the certificate certifies, from the study's results (interim: the calibration
/// section, by the probe method).
pub(crate) fn certified(results: &StudyResults, c: &CalibrationResults) -> Certified {
    let check = results.two_orientation.as_ref().and_then(two_orientation_check);
    let refuted_by_check = check.is_some_and(|k| !k.agrees);
    let reason = if results.two_orientation.is_some() {
        "The PIGA's IA-in measurement, compensated with the displacement probe's C_r, is the \
         calibration this certificate states; the two-orientation measurement checks it."
            .to_owned()
    } else {
        "The PIGA was measured in one mounting only: the probe method, which compensates \
         the spindle's radius growth measured by the displacement probe, is the one that applies."
            .to_owned()
    };
    Certified {
        method: Method::Probe,
        reason,
        check,
        refuted_by_check,
        coefficients: probe_coefficients(c),
        validity: vec![validity(
            "ia_in",
            results.inputs.radius_m,
            c.g_m_s2,
            &c.residuals
                .iter()
                .map(|r| r.rate_deg_s)
                .collect::<Vec<_>>(),
        )],
    }
}

fn two_orientation_check(s: &TwoOrientationResults) -> Option<Check> {
    let p = s.probe.as_ref()?;
    Some(Check {
        method: Method::TwoOrientation,
        k2: s.k2.value,
        u: s.k2.u,
        expanded: s.headline.k2.widths(1.0).0.max(s.headline.k2.widths(1.0).1),
        z: p.z,
        agrees: p.agrees,
    })
}

fn probe_coefficients(c: &CalibrationResults) -> Vec<Coefficient> {
    let g = &c.coefficients;
    let h = &c.headline;
    let mc = &c.monte_carlo;
    let micro = 1e6 / g.k1.value;
    let conventional = [
        Some(c.conventional.k0_ug),
        None,
        Some(c.conventional.k2_ug_per_g2),
        Some(c.conventional.k3_ug_per_g3),
    ];
    [
        (&g.k0, &h.k0, &mc.k0),
        (&g.k1, &h.k1, &mc.k1),
        (&g.k2, &h.k2, &mc.k2),
        (&g.k3, &h.k3, &mc.k3),
    ]
    .into_iter()
    .enumerate()
    .map(|(n, (gum, head, _))| {
        let gum_stated = head.method == HeadlineMethod::Gum;
        let (below, above) = head.widths(1.0);
        let relative = conventional[n].map(|e| {
            let (b, a) = head.widths(micro);
            Relative {
                unit: MICRO_UNITS[n],
                value: head.value * micro,
                u: e.u,
                low95: head.value * micro - b,
                high95: head.value * micro + a,
                expanded: b.max(a),
            }
        });
        Coefficient {
            name: NAMES[n],
            mounting: (n < 2).then_some("ia_in"),
            unit: UNITS[n],
            value: head.value,
            u: gum.u,
            low95: head.low95,
            high95: head.high95,
            expanded: below.max(above),
            k: gum_stated.then_some(gum.k),
            dof: gum.dof,
            interval_method: head.method,
            borderline: head.borderline,
            relative,
        }
    })
    .collect()
}

/// The validity range of a mounting at `radius_m` from the rates used.
pub(crate) fn validity(mounting: &'static str, radius_m: f64, g_m_s2: f64, rates_deg_s: &[f64]) -> Validity {
    let low = rates_deg_s.iter().copied().fold(f64::INFINITY, f64::min);
    let high = rates_deg_s.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let a = |rate_deg_s: f64| radius_m * rate_deg_s.to_radians().powi(2) / g_m_s2;
    Validity {
        mounting,
        mounting_words: mounting_words(mounting),
        radius_m,
        rate_low_deg_s: low,
        rate_high_deg_s: high,
        specific_force_low_g: a(low),
        specific_force_high_g: a(high),
        points: rates_deg_s.len(),
    }
}
