//! D-SI quantities (PTB's `https://ptb.de/si`, v2.2.1): `si:real` with its univariate
//! uncertainty, and `si:realListXMLList` with a covariance matrix.
//!
//! # Units
//! The PIGA model is written in the specific force along the input axis in units of g
//! (IEEE Std 836): `ω_out = k0 + k1·(a/g) + k2·(a/g)² + k3·(a/g)³`, so k1, k2 and k3 are in
//! rad/(s·g), rad/(s·g²) and rad/(s·g³). g is not a unit of the SI; D-SI has none for it. The
//! DCC states the g-normalised quantities: `a/g` is a number (D-SI `\one`), so every kₙ is a
//! rate, `\radian\second\tothe{-1}`, its name saying which power of `a/g` it multiplies and
//! the g used stated beside it (a `usedMethodQuantity` in m/s²). The numbers are those of
//! results.json and the printed certificate, unconverted. The values relative to k1 (µg,
//! µg/g², µg/g³) are numbers in g-units (`k0/k1` in g, `k2/k1` in 1/g, …), written in parts
//! per million (`\ppm`: 1 µg/g² = 1 ppm of the g-normalised `k2/k1`).

use crate::error::Result;
use crate::number::{self, COVERAGE_PROBABILITY};
use crate::text::Text;
use crate::xml::Xml;

/// D-SI unit strings.
pub(crate) mod unit {
    /// rad/s: every kₙ (of the g-normalised specific force).
    pub(crate) const RAD_PER_S: &str = r"\radian\second\tothe{-1}";
    /// (rad/s)²: the covariance of two coefficients.
    pub(crate) const RAD_PER_S_SQUARED: &str = r"\radian\tothe{2}\second\tothe{-2}";
    /// Parts per million: the values relative to k1 (µg, µg/g², µg/g³).
    pub(crate) const PPM: &str = r"\ppm";
    /// m/s²: g.
    pub(crate) const METRE_PER_S2: &str = r"\metre\second\tothe{-2}";
    /// deg/s: the rates.
    pub(crate) const DEGREE_PER_S: &str = r"\degree\second\tothe{-1}";
    /// A number: the specific force in units of g, a count.
    pub(crate) const ONE: &str = r"\one";
    /// m: a radius.
    pub(crate) const METRE: &str = r"\metre";
}

/// A value's univariate uncertainty as stated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Uncertainty {
    /// No uncertainty stated (a limit, a nominal value).
    None,
    /// `U = k·u` for 95 % coverage (a GUM interval).
    Expanded {
        /// U.
        expanded: f64,
        /// k.
        k: f64,
    },
    /// A 95 % coverage interval (the Monte Carlo method's) with the standard uncertainty.
    Interval {
        /// u.
        u: f64,
        /// Lower end.
        low: f64,
        /// Upper end.
        high: f64,
    },
}

/// `si:real`: `label`, `value` in `unit`, its uncertainty. `quantity` names it in errors.
pub(crate) fn real(
    x: &mut Xml,
    label: &Text,
    quantity: &str,
    value: f64,
    unit: &str,
    uncertainty: Uncertainty,
) -> Result<()> {
    x.el("si:real", |x| {
        x.leaf("si:label", label)?;
        x.leaf("si:value", &number::decimal(quantity, value)?)?;
        x.own("si:unit", unit)?;
        match uncertainty {
            Uncertainty::None => Ok(()),
            Uncertainty::Expanded { expanded, k } => {
                x.el("si:measurementUncertaintyUnivariate", |x| {
                    x.el("si:expandedMU", |x| {
                        x.leaf(
                            "si:valueExpandedMU",
                            &number::uncertainty(&format!("U of {quantity}"), expanded)?,
                        )?;
                        x.leaf(
                            "si:coverageFactor",
                            &number::coverage_factor(&format!("k of {quantity}"), k)?,
                        )?;
                        x.own("si:coverageProbability", COVERAGE_PROBABILITY)?;
                        x.own("si:distribution", "normal")
                    })
                })
            }
            Uncertainty::Interval { u, low, high } => {
                x.el("si:measurementUncertaintyUnivariate", |x| {
                    x.el("si:coverageIntervalMU", |x| {
                        x.leaf(
                            "si:valueStandardMU",
                            &number::uncertainty(&format!("u of {quantity}"), u)?,
                        )?;
                        x.leaf(
                            "si:intervalMin",
                            &number::decimal(&format!("lower end of {quantity}"), low)?,
                        )?;
                        x.leaf(
                            "si:intervalMax",
                            &number::decimal(&format!("upper end of {quantity}"), high)?,
                        )?;
                        x.own("si:coverageProbability", COVERAGE_PROBABILITY)
                    })
                })
            }
        }
    })
}

/// A list of correlated real quantities with their standard uncertainties and covariance.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CorrelatedList<'a> {
    /// One label per value (no white space in a label: the list is space-separated).
    pub(crate) labels: &'a [String],
    pub(crate) values: &'a [f64],
    pub(crate) units: &'a [&'static str],
    /// Standard uncertainties.
    pub(crate) u: &'a [f64],
    /// The covariance matrix (symmetric, n×n, units the products of the values' units),
    /// with the coverage factor of its 95 % region; none when unknown.
    pub(crate) covariance: Option<(&'a [Vec<f64>], f64)>,
}

/// `si:realListXMLList` of `list`, with `si:standardMUXMLList` and, when the covariance is
/// known, `si:measurementUncertaintyMultivariateXMLList` holding the hyper-ellipsoidal 95 %
/// coverage region.
pub(crate) fn correlated_list(x: &mut Xml, list: &CorrelatedList<'_>) -> Result<()> {
    let joined =
        |items: Vec<Text>| Text::own(items.iter().map(Text::as_str).collect::<Vec<_>>().join(" "));
    x.el("si:realListXMLList", |x| {
        x.leaf("si:labelXMLList", &Text::own(list.labels.join(" ")))?;
        let values = list
            .labels
            .iter()
            .zip(list.values)
            .map(|(l, v)| number::decimal(l, *v))
            .collect::<Result<Vec<_>>>()?;
        x.leaf("si:valueXMLList", &joined(values))?;
        x.own("si:unitXMLList", &list.units.join(" "))?;
        let u = list
            .labels
            .iter()
            .zip(list.u)
            .map(|(l, u)| number::uncertainty(&format!("u of {l}"), *u))
            .collect::<Result<Vec<_>>>()?;
        x.el("si:measurementUncertaintyUnivariateXMLList", |x| {
            x.el("si:standardMUXMLList", |x| {
                x.leaf("si:valueStandardMUXMLList", &joined(u))
            })
        })?;
        let Some((matrix, k)) = list.covariance else {
            return Ok(());
        };
        let n = list.labels.len();
        if matrix.len() != n || matrix.iter().any(|row| row.len() != n) {
            return Err(crate::error::DccError::CovarianceShape { n });
        }
        x.el("si:measurementUncertaintyMultivariateXMLList", |x| {
            x.el("si:ellipsoidalRegionMUXMLList", |x| {
                x.el("si:covarianceMatrixXMLList", |x| {
                    for (j, label_j) in list.labels.iter().enumerate() {
                        x.el("si:columnXMLList", |x| {
                            for (i, label_i) in list.labels.iter().enumerate() {
                                let value = matrix[i][j];
                                x.el("si:covarianceXMLList", |x| {
                                    x.leaf(
                                        "si:valueXMLList",
                                        &number::decimal(
                                            &format!("covariance of {label_i} and {label_j}"),
                                            value,
                                        )?,
                                    )?;
                                    x.own(
                                        "si:unitXMLList",
                                        &product_unit(list.units[i], list.units[j]),
                                    )
                                })?;
                            }
                            Ok(())
                        })?;
                    }
                    Ok(())
                })?;
                x.leaf(
                    "si:coverageFactorXMLList",
                    &number::coverage_factor("the coverage factor of the coefficients' region", k)?,
                )?;
                x.own("si:coverageProbabilityXMLList", COVERAGE_PROBABILITY)?;
                x.own("si:distributionXMLList", "normal")
            })
        })
    })
}

/// The unit of a product of quantities in units `a` and `b` (the units this crate writes).
fn product_unit(a: &str, b: &str) -> String {
    if a == unit::RAD_PER_S && b == unit::RAD_PER_S {
        unit::RAD_PER_S_SQUARED.to_owned()
    } else {
        format!("{a}{b}")
    }
}
