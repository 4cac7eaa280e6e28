//! The stated 95 % interval of each coefficient as the study chose it (JCGM 101 §8:
//! `pipeline::Headline`), with the GUM coefficient beside it, in a person's words.

use pipeline::{CalibrationResults, Coefficient, HeadlineMethod};

// The coefficients' names, their units and their units relative to k1: the study's.
pub(crate) use pipeline::{
    COEFFICIENT_NAMES as NAMES, COEFFICIENT_UNITS as UNITS, RELATIVE_UNITS as MICRO_UNITS,
};

/// A coefficient's headline: the value and the 95 % interval a certificate states.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Headline {
    /// The stated interval and its method.
    pub stated: pipeline::Headline,
    /// The GUM coefficient (k, ν_eff, U95).
    pub gum: Coefficient,
}

impl Headline {
    /// The estimate.
    pub(crate) const fn value(&self) -> f64 {
        self.stated.value
    }

    /// The interval's half-widths below and above the value, scaled by `scale`.
    pub(crate) fn widths(&self, scale: f64) -> (f64, f64) {
        self.stated.widths(scale)
    }

    /// Whether the GUM interval is stated.
    pub(crate) fn is_gum(&self) -> bool {
        self.stated.method == HeadlineMethod::Gum
    }

    /// The method in a few words, for the summary's table.
    pub(crate) const fn method_short(&self) -> &'static str {
        match (self.stated.method, self.stated.borderline) {
            (HeadlineMethod::Gum, _) => "GUM",
            (HeadlineMethod::MonteCarlo, false) => "Monte Carlo (GUM not validated)",
            (HeadlineMethod::MonteCarlo, true) => "Monte Carlo (GUM validation borderline)",
        }
    }

    /// The §8 verdict in words, for the comparison table.
    pub(crate) const fn verdict_words(&self) -> &'static str {
        match (self.stated.method, self.stated.borderline) {
            (HeadlineMethod::Gum, _) => "validated",
            (HeadlineMethod::MonteCarlo, true) => "borderline (Monte Carlo stated)",
            (HeadlineMethod::MonteCarlo, false) => "not validated (Monte Carlo stated)",
        }
    }
}

/// The four headlines of a calibration, k0 … k3.
pub(crate) fn headlines(c: &CalibrationResults) -> [Headline; 4] {
    let (h, g) = (&c.headline, &c.coefficients);
    [
        Headline {
            stated: h.k0,
            gum: g.k0,
        },
        Headline {
            stated: h.k1,
            gum: g.k1,
        },
        Headline {
            stated: h.k2,
            gum: g.k2,
        },
        Headline {
            stated: h.k3,
            gum: g.k3,
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use pipeline::MonteCarloOutput;

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

    fn of(gum_agrees: bool, d: f64, tolerance: f64) -> Headline {
        Headline {
            stated: pipeline::Headline::of(&gum(), &mc(gum_agrees, d, tolerance)),
            gum: gum(),
        }
    }

    #[test]
    fn the_headline_follows_jcgm_101_section_8() {
        // validated clearly: the GUM interval
        let h = of(true, 1e-4, 1e-3);
        assert!(h.is_gum());
        assert!((h.stated.low95 - 0.804).abs() < 1e-12 && (h.stated.high95 - 1.196).abs() < 1e-12);
        // not validated: the Monte Carlo interval, and the words say so
        let h = of(false, 5e-3, 1e-3);
        assert!(!h.is_gum() && !h.stated.borderline);
        assert_eq!((h.stated.low95, h.stated.high95), (0.79, 1.22));
        assert!(h.verdict_words().contains("not validated"));
        // within δ/2 of the threshold, on either side: borderline, the Monte Carlo interval
        // stated whichever verdict this run gave
        for (agrees, d) in [(true, 0.9e-3), (false, 1.1e-3)] {
            let h = of(agrees, d, 1e-3);
            assert!(!h.is_gum() && h.stated.borderline);
            assert_eq!((h.stated.low95, h.stated.high95), (0.79, 1.22));
            assert!(h.verdict_words().contains("borderline"));
        }
    }
}
