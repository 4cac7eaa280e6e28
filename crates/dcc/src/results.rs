//! The DCC's measurement results: the methods, the software, the equipment and the
//! conditions of the calibration; the certified coefficients k0…k3 and their values
//! relative to k1 as `si:real` with their stated 95 % intervals; the coefficients together
//! with their covariance as `si:realListXMLList`; what is certified and why, the check by
//! the other method, each mounting's range of validity, the statements of conformity and
//! the files the results were computed from, with their SHA-256.

use pipeline::{
    CertificateResults, CertifiedMethod, DecisionRule, DegreesOfFreedom, ValidityRange, Verdict,
};

use crate::certified::{Certified, CertifiedCoefficient, Interval, Stated};
use crate::error::Result;
use crate::input::{InputFile, Software};
use crate::number::{self, COVERAGE_PROBABILITY_P};
use crate::si::{self, CorrelatedList, Uncertainty, unit};
use crate::text::Text;
use crate::xml::Xml;

// The coefficients' names, their native units as the printed certificate writes them, and
// the units of the values relative to k1: the study's.
use pipeline::{
    COEFFICIENT_NAMES as NAMES, COEFFICIENT_UNITS as NATIVE_UNITS, RELATIVE_UNITS as MICRO_UNITS,
};

/// What the coefficients are.
const WHAT: [&str; 4] = [
    "bias",
    "scale factor",
    "second-order coefficient",
    "third-order coefficient",
];
/// The paper.
const LIU: &str = "Liu Y. et al., The mechanism of PIGA's pseudo-second-order term generated \
                   by spindle dynamic imbalance of centrifuge, Navigation Positioning and \
                   Timing, 2025(1)";
/// The term each multiplies.
const TERMS: [&str; 4] = ["the constant term", "a/g", "(a/g)²", "(a/g)³"];

/// `dcc:measurementResults` of certificate `cert` certifying `certified`, computed by
/// `software` from `files`.
pub(crate) fn measurement_results(
    x: &mut Xml,
    cert: &CertificateResults,
    certified: &Certified<'_>,
    software: &Software,
    files: Option<&[InputFile]>,
) -> Result<()> {
    x.el("dcc:measurementResults", |x| {
        x.el("dcc:measurementResult", |x| {
            x.own_content("dcc:name", "Coefficients of the PIGA's model")?;
            x.own_content(
                "dcc:description",
                &format!(
                    "The model of the PIGA's output rate in the specific force a along its input \
                     axis (IEEE Std 836): ω = k0 + k1·(a/g) + k2·(a/g)² + k3·(a/g)³, with \
                     g = {} m/s² (1 g). k1, k2 and k3 are in rad/(s·g), rad/(s·g²) and \
                     rad/(s·g³): the coefficients of powers of the number a/g, each written \
                     here as a rate (rad/s). The values relative to k1 (k0/k1 in µg, k2/k1 in \
                     µg/g², k3/k1 in µg/g³) are written in parts per million (1 µg = 1 ppm of \
                     1 g). Every interval is for a coverage probability of 95 %.",
                    certified.g_m_s2
                ),
            )?;
            used_methods(x, cert, certified)?;
            x.el("dcc:usedSoftware", |x| {
                crate::admin::software_element(x, software)
            })?;
            equipment(x, cert)?;
            conditions(x, cert)?;
            x.el("dcc:results", |x| {
                for c in &certified.coefficients {
                    coefficient(x, c, certified)?;
                }
                covariance(x, certified)
            })?;
            x.el("dcc:measurementMetaData", |x| {
                what_is_certified(x, certified)?;
                for v in certified.validity {
                    validity(x, v)?;
                }
                conformity(x, cert)?;
                input_files(x, files)
            })
        })
    })
}

/// The label of a coefficient: its name, with its mounting (`k0_ia_in`) when the certificate
/// states two.
fn label(c: &CertifiedCoefficient, certified: &Certified<'_>) -> Result<Text> {
    let mountings = certified.validity.len();
    match &c.mounting {
        Some(m) if mountings > 1 => Text::identification(
            "a certified coefficient's mounting",
            &format!("{}_{m}", NAMES[c.power]),
        ),
        _ => Ok(Text::own(NAMES[c.power])),
    }
}

/// A mounting in words, as the study states it.
fn mounting_words<'a>(certified: &'a Certified<'_>, mounting: &'a str) -> &'a str {
    certified
        .validity
        .iter()
        .find(|v| v.mounting == mounting)
        .map_or(mounting, |v| v.mounting_words.as_str())
}

fn used_methods(x: &mut Xml, cert: &CertificateResults, certified: &Certified<'_>) -> Result<()> {
    x.el("dcc:usedMethods", |x| {
        x.el_with("dcc:usedMethod", &[("id", "method-calibration")], |x| {
            match certified.method {
                CertifiedMethod::Probe => {
                    x.own_content(
                        "dcc:name",
                        "Calibration on a precision centrifuge, compensated for the spindle's \
                         dynamic radius error (probe method)",
                    )?;
                    x.own_content(
                        "dcc:description",
                        "The PIGA's mean output rate at each spindle rate is fitted by least \
                         squares with the terms 1, ω, ω², ω³, (a/g)² and (a/g)³ (eq. 18 of Liu \
                         et al. 2025); the spindle's dynamic radius growth C_r·ω², measured by a \
                         displacement probe, adds k1·C_r·g/R² to the fitted second-order \
                         coefficient (eq. 19), which is removed from it.",
                    )?;
                    x.own("dcc:norm", "IEEE Std 836-2009")?;
                    x.own("dcc:reference", LIU)?;
                }
                CertifiedMethod::TwoOrientation => {
                    x.own_content(
                        "dcc:name",
                        "Calibration on a precision centrifuge in two mountings, the input axis \
                         pointing towards and away from the spindle axis (two-orientation method)",
                    )?;
                    x.own_content(
                        "dcc:description",
                        "The PIGA's mean output rates in both mountings are fitted together \
                         (eq. 23): the terms linear in the specific force change sign with the \
                         mounting while k2·(a/g)² does not, so k2 and k3 come from the PIGA's own \
                         outputs whatever the arm's radius growth; k0 and k1 are each mounting's.",
                    )?;
                    x.own("dcc:norm", "IEEE Std 836-2009")?;
                    x.own(
                        "dcc:reference",
                        "Sun, Ren, Cao and Huo, Measurement, 2022 (the two mountings)",
                    )?;
                    x.own("dcc:reference", LIU)?;
                }
            }
            x.el("dcc:usedMethodQuantities", |x| {
                x.el("dcc:usedMethodQuantity", |x| {
                    x.own_content(
                        "dcc:name",
                        "g: the unit of the specific force in the model (1 g)",
                    )?;
                    si::real(
                        x,
                        &Text::own("g"),
                        "g",
                        certified.g_m_s2,
                        unit::METRE_PER_S2,
                        Uncertainty::None,
                    )
                })
            })
        })?;
        x.el_with("dcc:usedMethod", &[("id", "method-procedure")], |x| {
            x.own_content("dcc:name", "The laboratory's procedure")?;
            x.content(
                "dcc:description",
                &Text::free("certificate.procedure", &cert.procedure)?,
            )
        })?;
        x.el_with("dcc:usedMethod", &[("id", "method-gum")], |x| {
            x.own_content(
                "dcc:name",
                "Uncertainty: the law of propagation of uncertainty (GUM)",
            )?;
            x.own_content(
                "dcc:description",
                "Sensitivities through the calibration's measurement model, effective degrees of \
                 freedom by Welch–Satterthwaite, the coverage factor k from Student's t.",
            )?;
            x.own("dcc:norm", "JCGM 100:2008")
        })?;
        x.el_with("dcc:usedMethod", &[("id", "method-monte-carlo")], |x| {
            x.own_content("dcc:name", "Uncertainty: the Monte Carlo method")?;
            x.own_content(
                "dcc:description",
                "The adaptive Monte Carlo method validates the GUM's interval (§8); where it \
                 does not, its probabilistically symmetric 95 % interval is stated.",
            )?;
            x.own("dcc:norm", "JCGM 101:2008")
        })?;
        x.el_with("dcc:usedMethod", &[("id", "method-region")], |x| {
            x.own_content("dcc:name", "Coverage region of the coefficients together")?;
            x.own_content(
                "dcc:description",
                "The hyper-ellipsoid of the coefficients' covariance matrix, for 95 % coverage \
                 of a multivariate normal distribution (k² the 95 % quantile of χ² with as many \
                 degrees of freedom as coefficients).",
            )?;
            x.own("dcc:norm", "JCGM 102:2011")
        })?;
        x.el_with("dcc:usedMethod", &[("id", "method-conformity")], |x| {
            x.own_content(
                "dcc:name",
                "Statements of conformity and their decision rule",
            )?;
            x.own("dcc:norm", "ILAC-G8:09/2019")
        })
    })
}

fn equipment(x: &mut Xml, cert: &CertificateResults) -> Result<()> {
    x.el("dcc:measuringEquipments", |x| {
        for (i, e) in cert.equipment.iter().enumerate() {
            x.el("dcc:measuringEquipment", |x| {
                x.content(
                    "dcc:name",
                    &Text::free(&format!("certificate.equipment[{i}].role"), &e.role)?,
                )?;
                x.content(
                    "dcc:description",
                    &Text::free(
                        &format!("certificate.equipment[{i}].description"),
                        &format!("{}; calibration due {}", e.description, e.calibration_due),
                    )?,
                )?;
                x.el("dcc:identifications", |x| {
                    x.el("dcc:identification", |x| {
                        x.own("dcc:issuer", "calibrationLaboratory")?;
                        x.leaf(
                            "dcc:value",
                            &Text::identification(
                                &format!("certificate.equipment[{i}].identity"),
                                &e.identity,
                            )?,
                        )?;
                        x.own_content("dcc:name", "serial or asset number")
                    })
                })
            })?;
        }
        Ok(())
    })
}

fn conditions(x: &mut Xml, cert: &CertificateResults) -> Result<()> {
    if cert.conditions.is_empty() {
        return Ok(());
    }
    x.el("dcc:influenceConditions", |x| {
        for (i, c) in cert.conditions.iter().enumerate() {
            x.el("dcc:influenceCondition", |x| {
                x.content(
                    "dcc:name",
                    &Text::free(
                        &format!("certificate.conditions[{i}].quantity"),
                        &c.quantity,
                    )?,
                )?;
                x.el("dcc:data", |x| {
                    x.content(
                        "dcc:text",
                        &Text::free(&format!("certificate.conditions[{i}].value"), &c.value)?,
                    )
                })
            })?;
        }
        Ok(())
    })
}

/// Effective degrees of freedom in words, by the one formatter (`DegreesOfFreedom`'s display,
/// as the certificate's page and the terminal write them): `ν_eff = 12`, `ν_eff = 3.4`,
/// `ν_eff > 1000`, `ν_eff = ∞`.
fn dof_words(dof: DegreesOfFreedom) -> String {
    match dof {
        DegreesOfFreedom::Finite(n) if n > 1000.0 => format!("ν_eff {dof}"),
        _ => format!("ν_eff = {dof}"),
    }
}

/// The uncertainty of `s` as its interval states it.
fn uncertainty_of(s: &Stated, interval: Interval) -> Uncertainty {
    match interval {
        Interval::Gum { k } => Uncertainty::Expanded {
            expanded: s.expanded,
            k,
        },
        Interval::MonteCarlo => Uncertainty::Interval {
            u: s.u,
            low: s.low95,
            high: s.high95,
        },
    }
}

/// One `dcc:result` per coefficient: its value in its unit and, but for k1, relative to k1.
fn coefficient(x: &mut Xml, c: &CertifiedCoefficient, certified: &Certified<'_>) -> Result<()> {
    let label = label(c, certified)?;
    let name = NAMES[c.power];
    let interval_words = match c.interval {
        Interval::Gum { k } => format!(
            "the GUM interval (JCGM 100), validated by the Monte Carlo method; k = {k:.2} for \
             {}",
            dof_words(c.dof)
        ),
        Interval::MonteCarlo => "the Monte Carlo method's interval (JCGM 101): the GUM \
                                 interval is not validated, or its validation is borderline \
                                 (§8); it may be asymmetric about the value"
            .to_owned(),
    };
    let mounting_words = match &c.mounting {
        Some(m) if certified.validity.len() > 1 => {
            format!(" ({})", mounting_words(certified, m))
        }
        _ => String::new(),
    };
    x.el_with("dcc:result", &[("id", label.as_str())], |x| {
        x.content(
            "dcc:name",
            &Text::free(
                "certified coefficient",
                &format!("{name}, {}{mounting_words}", WHAT[c.power]),
            )?,
        )?;
        x.own_content(
            "dcc:description",
            &format!(
                "In {} (the coefficient of {}, written as rad/s). Stated interval: {}.",
                NATIVE_UNITS[c.power], TERMS[c.power], interval_words
            ),
        )?;
        x.el("dcc:data", |x| {
            x.el_with(
                "dcc:quantity",
                &[("id", &format!("{}-value", label.as_str()))],
                |x| {
                    x.content("dcc:name", &label)?;
                    si::real(
                        x,
                        &label,
                        name,
                        c.native.value,
                        unit::RAD_PER_S,
                        uncertainty_of(&c.native, c.interval),
                    )
                },
            )?;
            if let Some(r) = &c.relative {
                let relative_label = Text::own(format!("{}/k1", label.as_str()));
                x.el_with(
                    "dcc:quantity",
                    &[("id", &format!("{}-relative", label.as_str()))],
                    |x| {
                        x.own_content(
                            "dcc:name",
                            &format!(
                                "{}, relative to k1, in {} (written in ppm)",
                                relative_label.as_str(),
                                MICRO_UNITS[c.power]
                            ),
                        )?;
                        si::real(
                            x,
                            &relative_label,
                            &format!("{name}/k1"),
                            r.value,
                            unit::PPM,
                            uncertainty_of(r, c.interval),
                        )
                    },
                )?;
            }
            Ok(())
        })
    })
}

/// The certified coefficients as one list with their standard uncertainties and, when the
/// study gives it, their covariance and its 95 % coverage region.
fn covariance(x: &mut Xml, certified: &Certified<'_>) -> Result<()> {
    let labels = certified
        .coefficients
        .iter()
        .map(|c| label(c, certified).map(|l| l.as_str().to_owned()))
        .collect::<Result<Vec<_>>>()?;
    let values: Vec<f64> = certified
        .coefficients
        .iter()
        .map(|c| c.native.value)
        .collect();
    let u: Vec<f64> = certified.coefficients.iter().map(|c| c.native.u).collect();
    let units = vec![unit::RAD_PER_S; labels.len()];
    let k = number::ellipsoid_coverage_factor(labels.len(), COVERAGE_PROBABILITY_P);
    x.el_with("dcc:result", &[("id", "coefficients")], |x| {
        x.own_content(
            "dcc:name",
            "The coefficients together, with their standard uncertainties and covariance",
        )?;
        x.own_content(
            "dcc:description",
            match certified.covariance {
                Some(_) => {
                    "The covariance matrix (in (rad/s)²) and the hyper-ellipsoidal region of \
                     95 % coverage for the coefficients together (JCGM 102). The standard \
                     uncertainty of a coefficient stated by the Monte Carlo method is that \
                     method's."
                }
                None => {
                    "Standard uncertainties only: the study records no covariance of the \
                     certified coefficients. The standard uncertainty of a coefficient \
                     stated by the Monte Carlo method is that method's."
                }
            },
        )?;
        x.el("dcc:data", |x| {
            x.el("dcc:quantity", |x| {
                si::correlated_list(
                    x,
                    &CorrelatedList {
                        labels: &labels,
                        values: &values,
                        units: &units,
                        u: &u,
                        covariance: certified.covariance.map(|m| (m, k)),
                    },
                )
            })
        })
    })
}

/// What is certified and why; with the other method run, its k2 as a check.
fn what_is_certified(x: &mut Xml, certified: &Certified<'_>) -> Result<()> {
    let method = certified.method.words();
    x.el_with("dcc:metaData", &[("id", "certified-method")], |x| {
        x.own_content("dcc:name", "What is certified")?;
        x.own_content(
            "dcc:description",
            &format!("The coefficients of {method} are certified."),
        )?;
        x.content(
            "dcc:declaration",
            &Text::free("the certificate's reason", certified.reason)?,
        )
    })?;
    if let Some(despite) = certified
        .despite_check
        .filter(|_| certified.refuted_by_check)
    {
        x.el_with("dcc:metaData", &[("id", "certified-despite-check")], |x| {
            x.own_content(
                "dcc:name",
                "Certified although the study's own check refutes it",
            )?;
            x.content(
                "dcc:declaration",
                &Text::free("certificate.certify_despite_check", despite)?,
            )
        })?;
    }
    let Some(check) = certified.check else {
        return Ok(());
    };
    let other = check.method.words();
    x.el_with("dcc:metaData", &[("id", "check")], |x| {
        x.content("dcc:name", &Text::own(format!("Check of k2 by {other}")))?;
        x.own_content(
            "dcc:description",
            &format!(
                "k2 by {other} (in rad/(s·g²), written as rad/s), with its standard and \
                 expanded (95 %) uncertainty, and z, the difference of the two methods' radius \
                 growths over its standard uncertainty: the methods {} (|z| {} 3).",
                if check.agrees { "agree" } else { "disagree" },
                if check.agrees { "≤" } else { ">" },
            ),
        )?;
        x.el("dcc:data", |x| {
            let label = Text::own("k2");
            x.el("dcc:quantity", |x| {
                x.own_content(
                    "dcc:name",
                    "k2 by the other method, with its standard uncertainty",
                )?;
                x.el("si:real", |x| {
                    x.leaf("si:label", &label)?;
                    x.leaf("si:value", &number::decimal("k2 of the check", check.k2)?)?;
                    x.own("si:unit", unit::RAD_PER_S)?;
                    x.el("si:measurementUncertaintyUnivariate", |x| {
                        x.el("si:standardMU", |x| {
                            x.leaf(
                                "si:valueStandardMU",
                                &number::uncertainty("u of k2 of the check", check.u)?,
                            )
                        })
                    })
                })
            })?;
            x.el("dcc:quantity", |x| {
                x.own_content("dcc:name", "its expanded uncertainty U (95 %)")?;
                si::real(
                    x,
                    &Text::own("U(k2)"),
                    "U of k2 of the check",
                    check.expanded,
                    unit::RAD_PER_S,
                    Uncertainty::None,
                )
            })?;
            x.el("dcc:quantity", |x| {
                x.own_content(
                    "dcc:name",
                    "z of the difference of the two methods' radius growths",
                )?;
                si::real(
                    x,
                    &Text::own("z"),
                    "z of the check",
                    check.z,
                    unit::ONE,
                    Uncertainty::None,
                )
            })
        })
    })
}

/// Where the coefficients hold, for one mounting: its radius, the rates fitted and the
/// specific force along the input axis they give.
fn validity(x: &mut Xml, v: &ValidityRange) -> Result<()> {
    let mounting = Text::identification("a range of validity's mounting", &v.mounting)?;
    let id = format!("validity-{}", mounting.as_str());
    x.el_with("dcc:metaData", &[("id", &id)], |x| {
        x.content(
            "dcc:name",
            &Text::free(
                "a range of validity's mounting",
                &format!("Range of validity, {}", v.mounting_words),
            )?,
        )?;
        x.own_content(
            "dcc:description",
            &format!(
                "The coefficients hold over the rates fitted in this mounting ({} points) and \
                 the specific force along the input axis they give, R·ω²/g in units of g \
                 (negative with the input axis pointing away from the spindle axis).",
                v.points
            ),
        )?;
        x.el("dcc:data", |x| {
            let quantities: [(&str, &str, f64, &str); 5] = [
                (
                    "radius",
                    "the mounting's static radius R",
                    v.radius_m,
                    unit::METRE,
                ),
                (
                    "rate_low",
                    "the lowest rate",
                    v.rate_low_deg_s,
                    unit::DEGREE_PER_S,
                ),
                (
                    "rate_high",
                    "the highest rate",
                    v.rate_high_deg_s,
                    unit::DEGREE_PER_S,
                ),
                (
                    "specific_force_low",
                    "the specific force at the lowest rate (g)",
                    v.specific_force_low_g,
                    unit::ONE,
                ),
                (
                    "specific_force_high",
                    "the specific force at the highest rate (g)",
                    v.specific_force_high_g,
                    unit::ONE,
                ),
            ];
            for (label, name, value, unit) in quantities {
                x.el("dcc:quantity", |x| {
                    x.own_content("dcc:name", name)?;
                    si::real(x, &Text::own(label), name, value, unit, Uncertainty::None)
                })?;
            }
            Ok(())
        })
    })
}

/// The statements of conformity (ILAC-G8:09/2019), one per limit.
fn conformity(x: &mut Xml, cert: &CertificateResults) -> Result<()> {
    let Some(conformity) = &cert.conformity else {
        return Ok(());
    };
    let rule = match conformity.rule {
        DecisionRule::SimpleAcceptance => {
            "binary statement with simple acceptance (guard band w = 0)"
        }
        DecisionRule::GuardBand => "non-binary statement with a guard band w = U",
    };
    for (i, s) in conformity.statements.iter().enumerate() {
        let (unit, unit_words) = if s.relative_to_k1 {
            (unit::PPM, format!("{} (written in ppm)", s.unit))
        } else {
            (unit::RAD_PER_S, format!("{} (written as rad/s)", s.unit))
        };
        let coefficient = Text::free(
            &format!("certificate.conformity.statements[{i}].coefficient"),
            &s.coefficient,
        )?;
        let id = format!("conformity-{}", i + 1);
        x.el_with("dcc:metaData", &[("id", &id)], |x| {
            x.content(
                "dcc:name",
                &Text::free(
                    "statement of conformity",
                    &format!("Statement of conformity of {}", coefficient.as_str()),
                )?,
            )?;
            x.content(
                "dcc:description",
                &Text::free(
                    "statement of conformity",
                    &format!(
                        "Decision rule: {rule}. The value and its stated 95 % interval against \
                         the tolerance limits, in {unit_words}."
                    ),
                )?,
            )?;
            x.own("dcc:norm", "ILAC-G8:09/2019")?;
            x.own(
                "dcc:conformity",
                match s.verdict {
                    Verdict::Pass => "pass",
                    Verdict::ConditionalPass => "conditionalPass",
                    Verdict::ConditionalFail => "conditionalFail",
                    Verdict::Fail => "fail",
                },
            )?;
            x.el("dcc:data", |x| {
                let quantity = |x: &mut Xml, what: &str, value: f64, u: Uncertainty| {
                    x.el("dcc:quantity", |x| {
                        x.own_content("dcc:name", what)?;
                        si::real(
                            x,
                            &coefficient,
                            &format!("{what} of {}", coefficient.as_str()),
                            value,
                            unit,
                            u,
                        )
                    })
                };
                quantity(x, "value", s.value, Uncertainty::None)?;
                quantity(
                    x,
                    "lower end of the stated 95 % interval",
                    s.low95,
                    Uncertainty::None,
                )?;
                quantity(
                    x,
                    "upper end of the stated 95 % interval",
                    s.high95,
                    Uncertainty::None,
                )?;
                if let Some(l) = s.lower {
                    quantity(x, "lower tolerance limit", l, Uncertainty::None)?;
                }
                if let Some(u) = s.upper {
                    quantity(x, "upper tolerance limit", u, Uncertainty::None)?;
                }
                Ok(())
            })
        })?;
    }
    Ok(())
}

/// What a file is to the study, in words.
fn role_words(role: &str) -> &str {
    match role {
        "configuration" => "the study's configuration",
        "expected_values" => "the expected values shown beside the results",
        "probe_recording" => "a displacement-probe recording",
        "piga_table" => "the PIGA's table of mean outputs",
        "piga_recording" => "a raw PIGA output recording",
        other => other,
    }
}

/// Every file the results were computed from, with its size and SHA-256.
fn input_files(x: &mut Xml, files: Option<&[InputFile]>) -> Result<()> {
    let Some(files) = files else {
        return x.el_with("dcc:metaData", &[("id", "input-files")], |x| {
            x.own_content("dcc:name", "Input files")?;
            x.own_content(
                "dcc:declaration",
                "No record of the input files was kept with these results: their digests \
                 cannot be stated.",
            )
        });
    };
    for (i, f) in files.iter().enumerate() {
        let field = format!("input file {}", i + 1);
        let sha = Text::identification(&format!("{field}: SHA-256"), &f.sha256)?;
        let id = format!("input-file-{}", i + 1);
        x.el_with("dcc:metaData", &[("id", &id)], |x| {
            x.content(
                "dcc:name",
                &Text::free(
                    &field,
                    &format!("Input file {}: {}", i + 1, role_words(&f.role)),
                )?,
            )?;
            x.content(
                "dcc:description",
                &Text::free(&field, &format!("{} ({} bytes)", f.path, f.bytes))?,
            )?;
            x.el("dcc:data", |x| {
                x.el("dcc:quantity", |x| {
                    x.own_content("dcc:name", "SHA-256 of the file's contents")?;
                    x.leaf("dcc:charsXMLList", &sha)
                })
            })
        })?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use pipeline::InfiniteDof;

    /// The DCC writes ν_eff as the certificate's page does (`DegreesOfFreedom`'s display).
    #[test]
    fn dof_words_are_the_pages() {
        assert_eq!(dof_words(DegreesOfFreedom::Finite(12.0)), "ν_eff = 12");
        assert_eq!(dof_words(DegreesOfFreedom::Finite(3.4)), "ν_eff = 3.4");
        assert_eq!(dof_words(DegreesOfFreedom::Finite(5000.0)), "ν_eff > 1000");
        assert_eq!(
            dof_words(DegreesOfFreedom::Infinite(InfiniteDof::Infinite)),
            "ν_eff = ∞"
        );
    }
}
