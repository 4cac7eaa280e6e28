//! The stated 95 % coverage intervals checked before anything is written (issue 27): an
//! interval that is not finite, does not contain its estimate, or has (almost) no width while
//! the standard uncertainty is not zero cannot be stated, and the study is refused naming the
//! input whose uncertainty contributes most. Such intervals come from implausible inputs (a
//! radius uncertainty of 1e200 m) that no verdict should be read from. Core: used by the
//! study, importing no section.

use std::path::Path;

use crate::error::{DegenerateInterval, PipelineError, Result};
use crate::results::{
    BudgetLine, CalibrationResults, Coefficient, Headline, TwoOrientationResults,
};

/// The configuration field that states an input of a budget, by the budget's name for it.
fn field_of(quantity: &str) -> Option<&'static str> {
    let names = ::calibration::input::NAMES;
    let fields = [
        "uncertainty.radius_u_m",
        "uncertainty.g_u_m_s2",
        "uncertainty.rate_u_relative",
        "uncertainty.pivot_to_probe_u_mm",
        "uncertainty.probe_to_piga_u_mm",
        "uncertainty.probe_gain_u_relative",
        "the compensating phase's C_r fit",
        "calibration.k1.u_rad_s_g",
    ];
    names
        .iter()
        .zip(fields)
        .find(|(n, _)| quantity.starts_with(**n))
        .map(|(_, f)| f)
        .or_else(|| {
            quantity
                .starts_with("R ")
                .then_some("uncertainty.radius_u_m")
        })
}

/// The budget line with the largest contribution, in words with its field.
fn dominant(budget: &[BudgetLine]) -> String {
    budget
        .iter()
        .max_by(|a, b| a.percent.total_cmp(&b.percent))
        .map_or_else(
            || "not known (no budget for this quantity)".to_owned(),
            |l| match field_of(&l.quantity) {
                Some(f) => format!("{} ({f}, {:.0} % of the variance)", l.quantity, l.percent),
                None => format!("{} ({:.0} % of the variance)", l.quantity, l.percent),
            },
        )
}

/// Checks one stated interval.
fn check(
    path: &Path,
    quantity: &str,
    c: &Coefficient,
    h: &Headline,
    budget: &[BudgetLine],
) -> Result<()> {
    let width = h.high95 - h.low95;
    let problem = if !(h.low95.is_finite() && h.high95.is_finite() && h.value.is_finite()) {
        Some("is not finite")
    } else if !(h.low95 <= h.value && h.value <= h.high95) {
        Some("does not contain the estimate")
    } else if c.u > 0.0 && width < 1e-3 * c.u {
        Some("has (almost) no width although the standard uncertainty is not zero")
    } else {
        None
    };
    match problem {
        None => Ok(()),
        Some(problem) => Err(PipelineError::DegenerateInterval {
            path: path.to_owned(),
            interval: Box::new(DegenerateInterval {
                quantity: quantity.to_owned(),
                value: h.value,
                u: c.u,
                low: h.low95,
                high: h.high95,
                problem,
                dominant: dominant(budget),
            }),
        }),
    }
}

/// The calibration's k0 … k3: every stated interval can be stated.
pub(crate) fn check_calibration(path: &Path, c: &CalibrationResults) -> Result<()> {
    let k = &c.coefficients;
    let h = &c.headline;
    let b = &c.budget;
    let mut errors = Vec::new();
    for (name, coefficient, headline, budget) in [
        ("k0 of the calibration", &k.k0, &h.k0, &b.k0),
        ("k1 of the calibration", &k.k1, &h.k1, &b.k1),
        ("k2 of the calibration", &k.k2, &h.k2, &b.k2),
        ("k3 of the calibration", &k.k3, &h.k3, &b.k3),
    ] {
        if let Err(e) = check(path, name, coefficient, headline, budget) {
            errors.push(e);
        }
    }
    PipelineError::from_list(errors)
}

/// The two-orientation calibration's k2, k3, C and each mounting's k0 and k1 (stated by the
/// GUM alone).
pub(crate) fn check_two_orientation(path: &Path, t: &TwoOrientationResults) -> Result<()> {
    let mut errors = Vec::new();
    let mut push = |r: Result<()>| {
        if let Err(e) = r {
            errors.push(e);
        }
    };
    push(check(
        path,
        "k2 of the two-orientation method",
        &t.k2,
        &t.headline.k2,
        &t.budget.k2,
    ));
    push(check(
        path,
        "k3 of the two-orientation method",
        &t.k3,
        &t.headline.k3,
        &[],
    ));
    push(check(
        path,
        "C of the two-orientation method",
        &t.c_m_s2,
        &t.headline.c,
        &t.budget.c,
    ));
    for m in &t.mountings {
        let tag = if m.orientation == "ia_out" {
            "IA out"
        } else {
            "IA in"
        };
        for (name, coefficient) in [("k0", &m.k0), ("k1", &m.k1)] {
            let gum = Headline {
                value: coefficient.value,
                low95: coefficient.value - coefficient.u95,
                high95: coefficient.value + coefficient.u95,
                method: crate::results::HeadlineMethod::Gum,
                borderline: false,
            };
            push(check(
                path,
                &format!("{name} ({tag}) of the two-orientation method"),
                coefficient,
                &gum,
                &[],
            ));
        }
    }
    PipelineError::from_list(errors)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::results::{DegreesOfFreedom, HeadlineMethod, InfiniteDof};

    fn coefficient(value: f64, u: f64) -> Coefficient {
        Coefficient {
            value,
            u,
            u95: 1.96 * u,
            k: 1.96,
            dof: DegreesOfFreedom::Infinite(InfiniteDof::Infinite),
        }
    }

    fn headline(value: f64, low95: f64, high95: f64) -> Headline {
        Headline {
            value,
            low95,
            high95,
            method: HeadlineMethod::MonteCarlo,
            borderline: false,
        }
    }

    fn line(quantity: &str, percent: f64) -> BudgetLine {
        BudgetLine {
            quantity: quantity.to_owned(),
            evaluation: "B".to_owned(),
            value: Some(2.5),
            unit: "m".to_owned(),
            u: 1.0,
            sensitivity: 1.0,
            contribution: 1.0,
            percent,
            dof: DegreesOfFreedom::Infinite(InfiniteDof::Infinite),
            note: None,
        }
    }

    #[test]
    fn a_degenerate_interval_names_the_dominant_input() {
        let path = Path::new("study.ron");
        let budget = [line("g (gravity)", 1.0), line("R (working radius)", 99.0)];
        // the k1 interval of `radius_u_m: 1e200`: it excludes the estimate
        let e = check(
            path,
            "k1 of the calibration",
            &coefficient(0.56, 1e199),
            &headline(0.56, -2.2e-199, 2.3e-199),
            &budget,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("does not contain the estimate"), "{e}");
        assert!(
            e.contains("R (working radius) (uncertainty.radius_u_m, 99 % of the variance)"),
            "{e}"
        );
        // k2's [0, 0] with u > 0
        let e = check(
            path,
            "k2",
            &coefficient(1e-7, 1e-8),
            &headline(0.0, 0.0, 0.0),
            &budget,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("does not contain") || e.contains("no width"),
            "{e}"
        );
        let e = check(
            path,
            "k2",
            &coefficient(0.0, 1e-8),
            &headline(0.0, 0.0, 0.0),
            &[],
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("(almost) no width"), "{e}");
        assert!(e.contains("not known"), "{e}");
        let e = check(
            path,
            "k2",
            &coefficient(0.0, 1.0),
            &headline(0.0, f64::NEG_INFINITY, 1.0),
            &[],
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("is not finite"), "{e}");
        // a sound interval, and an exact quantity (u = 0, zero width)
        check(
            path,
            "k2",
            &coefficient(1.0, 0.1),
            &headline(1.0, 0.8, 1.2),
            &budget,
        )
        .unwrap();
        check(
            path,
            "k2",
            &coefficient(1.0, 0.0),
            &headline(1.0, 1.0, 1.0),
            &budget,
        )
        .unwrap();
    }
}
