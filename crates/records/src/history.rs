//! A unit's history and a centrifuge's health, computed from the records on values.

use crate::date::Date;
use crate::drift::{Drift, Observation, Prediction, fit_drift};
use crate::error::{RecordsError, Result};
use crate::interval::{Interval, IntervalRequest, variables_interval};
use crate::stored::{BalanceEvent, Campaign, CentrifugeRecords, StoredCertificate, UnitRecords};
use crate::submission::UnitIdentity;

/// What `history UNIT` is asked for.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct HistoryOptions {
    /// The date to predict at (default: the end of the recommended interval, else one year
    /// after the latest certificate).
    pub at: Option<Date>,
    /// The term (`k2`, `k0 (ia_out)`) and the tolerance and reliability of the interval.
    pub interval: Option<(String, IntervalRequest)>,
}

/// Where the date of the prediction comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(rename_all = "snake_case")
)]
pub enum AtSource {
    /// Given (`--at`).
    Given,
    /// The end of the recommended interval.
    IntervalEnd,
    /// One year after the latest certificate (neither given nor an interval asked for).
    OneYearAfterLatest,
}

/// One certificate's value of a term.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct TermPoint {
    /// The certificate.
    pub certificate: String,
    /// Its date of measurement.
    pub date: Date,
    /// The value certified.
    pub value: f64,
    /// Its standard uncertainty.
    pub u: f64,
    /// Its expanded uncertainty (95 %).
    pub expanded: f64,
}

/// One certified term across the unit's current certificates.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct TermHistory {
    /// `k2`, or `k0 (ia_out)`.
    pub label: String,
    /// Its unit.
    pub unit: String,
    /// Its values, by date.
    pub points: Vec<TermPoint>,
    /// The drift fitted through them (two dates or more).
    pub drift: Option<Drift>,
    /// The value predicted at the history's date.
    pub prediction: Option<Prediction>,
}

/// The recommended interval for one term.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct IntervalRecommendation {
    /// The term.
    pub term: String,
    /// Its unit.
    pub unit: String,
    /// The interval.
    pub interval: Interval,
    /// The latest current certificate's date, from which it counts.
    pub from: Date,
    /// When the next calibration falls due (`None`: nothing limits it).
    pub due: Option<Date>,
    /// The method in words.
    pub method: &'static str,
    /// Its assumptions in words.
    pub assumptions: &'static str,
}

/// A unit's history.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct UnitHistory {
    /// The unit.
    pub unit: UnitIdentity,
    /// Every certificate, superseded ones included (they are not fitted).
    pub certificates: Vec<StoredCertificate>,
    /// Each certified term across the current certificates.
    pub terms: Vec<TermHistory>,
    /// The date of the predictions.
    pub at: Date,
    /// Where it comes from.
    pub at_source: AtSource,
    /// The recommended interval, when asked for.
    pub interval: Option<IntervalRecommendation>,
}

/// The history of a unit from its records.
///
/// # Errors
/// [`RecordsError::UnknownTerm`] for an interval's term the certificates do not certify; the
/// drift fit's and the interval's errors.
pub fn unit_history(records: UnitRecords, options: &HistoryOptions) -> Result<UnitHistory> {
    let current: Vec<&StoredCertificate> = records
        .certificates
        .iter()
        .filter(|c| c.is_current())
        .collect();
    let mut terms: Vec<TermHistory> = Vec::new();
    for c in &current {
        for t in &c.terms {
            let label = t.label();
            let point = TermPoint {
                certificate: c.id.clone(),
                date: c.measured,
                value: t.value,
                u: t.u,
                expanded: t.expanded,
            };
            match terms.iter_mut().find(|h| h.label == label) {
                Some(h) => h.points.push(point),
                None => terms.push(TermHistory {
                    label,
                    unit: t.unit.clone(),
                    points: vec![point],
                    drift: None,
                    prediction: None,
                }),
            }
        }
    }
    for h in &mut terms {
        h.points.sort_by_key(|p| p.date);
        let obs: Vec<Observation> = h
            .points
            .iter()
            .map(|p| Observation {
                date: p.date,
                value: p.value,
                u: p.u,
            })
            .collect();
        h.drift = fit_drift(&h.label, &obs)?;
    }
    let latest = current.iter().map(|c| c.measured).max();
    let interval = match &options.interval {
        None => None,
        Some((term, request)) => {
            let matches: Vec<&TermHistory> = terms
                .iter()
                .filter(|h| h.label == *term || h.label.split(' ').next() == Some(term.as_str()))
                .collect();
            let [h] = matches.as_slice() else {
                return Err(RecordsError::UnknownTerm {
                    term: term.clone(),
                    known: terms.iter().map(|h| h.label.clone()).collect(),
                });
            };
            let last = h.points.last().ok_or_else(|| RecordsError::UnknownTerm {
                term: term.clone(),
                known: Vec::new(),
            })?;
            let (rate, u_rate) = h
                .drift
                .as_ref()
                .map_or((0.0, 0.0), |d| (d.rate_per_year, d.u_rate_per_year));
            let interval = variables_interval(*request, last.u, rate, u_rate)?;
            Some(IntervalRecommendation {
                term: h.label.clone(),
                unit: h.unit.clone(),
                due: interval.years.map(|y| last.date.plus_years(y)),
                interval,
                from: last.date,
                method: crate::interval::METHOD,
                assumptions: crate::interval::ASSUMPTIONS,
            })
        }
    };
    let (at, at_source) = match (options.at, interval.as_ref().and_then(|i| i.due), latest) {
        (Some(d), _, _) => (d, AtSource::Given),
        (None, Some(due), _) => (due, AtSource::IntervalEnd),
        (None, None, Some(l)) => (l.plus_years(1.0), AtSource::OneYearAfterLatest),
        (None, None, None) => (Date::from_days(0), AtSource::OneYearAfterLatest),
    };
    for h in &mut terms {
        let u_last = h.points.last().map_or(0.0, |p| p.u);
        h.prediction = h.drift.as_ref().map(|d| d.predict(at, u_last));
    }
    Ok(UnitHistory {
        unit: records.unit,
        certificates: records.certificates,
        terms,
        at,
        at_source,
        interval,
    })
}

/// What `history --centrifuge` is asked for.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HealthOptions {
    /// The target U95 of k2, rad/(s·g²): Δk2 is compared with a share of it.
    pub target_u95_rad_s_g2: Option<f64>,
    /// The share of the target U95 that Δk2 may reach before a rebalance is advised.
    pub share: f64,
    /// The date of the next campaign (default: the latest campaign plus the mean spacing of
    /// the campaigns since the latest balance).
    pub next: Option<Date>,
}

/// Where the next campaign's date comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(rename_all = "snake_case")
)]
pub enum NextSource {
    /// Given (`--next`).
    Given,
    /// The latest campaign plus the mean spacing of those since the latest balance.
    MeanSpacing,
}

/// The advice before the next campaign.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(rename_all = "snake_case")
)]
pub enum Advice {
    /// The predicted |Δk2| exceeds the share of the target U95: rebalance first.
    Rebalance,
    /// The predicted |Δk2| is below the share, but its 95 % interval reaches above it.
    MayExceed,
    /// The predicted |Δk2| and its 95 % interval stay below the share.
    Fine,
    /// Fewer than two campaigns (on two dates) since the latest balance: no prediction.
    TooFewCampaigns,
    /// No target U95 given: nothing to compare with.
    NoTarget,
}

/// A centrifuge's health.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct CentrifugeHealth {
    /// Its name.
    pub name: String,
    /// Its campaigns by date.
    pub campaigns: Vec<Campaign>,
    /// Its balance events by date.
    pub balances: Vec<BalanceEvent>,
    /// The latest balance: the fits use the campaigns on or after it.
    pub since: Option<Date>,
    /// Campaigns fitted.
    pub fitted: usize,
    /// The drift of C_r, m·s² per year.
    pub c_r_drift: Option<Drift>,
    /// The drift of Δk2, rad/(s·g²) per year.
    pub delta_k2_drift: Option<Drift>,
    /// The next campaign's date.
    pub next: Option<Date>,
    /// Where it comes from.
    pub next_source: NextSource,
    /// Δk2 predicted at the next campaign.
    pub predicted_delta_k2: Option<Prediction>,
    /// The target U95 of k2 given.
    pub target_u95_rad_s_g2: Option<f64>,
    /// The share given.
    pub share: f64,
    /// `share × target`: the |Δk2| that calls for a rebalance.
    pub limit_rad_s_g2: Option<f64>,
    /// The advice.
    pub advice: Advice,
}

/// The health of a centrifuge from its records.
///
/// # Errors
/// [`RecordsError::Invalid`] for a target that is not > 0 or a share outside (0, 1]; the drift
/// fits' errors.
pub fn centrifuge_health(
    records: CentrifugeRecords,
    options: &HealthOptions,
) -> Result<CentrifugeHealth> {
    let share = units::require(
        "--share",
        options.share,
        units::Requirement::AboveAtMost { min: 0.0, max: 1.0 },
    )?;
    let target = options
        .target_u95_rad_s_g2
        .map(|t| units::positive("--target-u95", t))
        .transpose()?;
    let since = records.balances.iter().map(|b| b.date).max();
    let after: Vec<&Campaign> = records
        .campaigns
        .iter()
        .filter(|c| since.is_none_or(|s| c.date >= s))
        .collect();
    let fit = |name: &str, pick: &dyn Fn(&Campaign) -> Option<(f64, f64)>| {
        let obs: Option<Vec<Observation>> = after
            .iter()
            .map(|c| {
                pick(c).map(|(value, u)| Observation {
                    date: c.date,
                    value,
                    u,
                })
            })
            .collect();
        obs.map_or(Ok(None), |o| fit_drift(name, &o))
    };
    let c_r_drift = fit("C_r", &|c| c.c_r_u_m_s2.map(|u| (c.c_r_m_s2, u)))?;
    let delta_k2_drift = fit("Δk2", &|c| {
        c.delta_k2_u_rad_s_g2.map(|u| (c.delta_k2_rad_s_g2, u))
    })?;
    let (next, next_source) = match options.next {
        Some(d) => (Some(d), NextSource::Given),
        None => {
            let dates: Vec<Date> = after.iter().map(|c| c.date).collect();
            let next = match (dates.first(), dates.last()) {
                (Some(first), Some(last)) if dates.len() >= 2 && last > first => {
                    #[allow(clippy::cast_precision_loss)] // a count of campaigns
                    let spacing = (last.days() - first.days()) as f64 / (dates.len() - 1) as f64;
                    #[allow(clippy::cast_possible_truncation)] // days
                    Some(Date::from_days(last.days() + spacing.round() as i64))
                }
                _ => None,
            };
            (next, NextSource::MeanSpacing)
        }
    };
    let u_last = after
        .last()
        .and_then(|c| c.delta_k2_u_rad_s_g2)
        .unwrap_or(0.0);
    let predicted = match (&delta_k2_drift, next) {
        (Some(d), Some(n)) => Some(d.predict(n, u_last)),
        _ => None,
    };
    let limit = target.map(|t| share * t);
    let advice = match (limit, predicted) {
        (None, _) => Advice::NoTarget,
        (Some(_), None) => Advice::TooFewCampaigns,
        (Some(l), Some(p)) if p.value.abs() > l => Advice::Rebalance,
        (Some(l), Some(p)) if p.value.abs() + p.k95 * p.u > l => Advice::MayExceed,
        (Some(_), Some(_)) => Advice::Fine,
    };
    Ok(CentrifugeHealth {
        name: records.name,
        fitted: after.len(),
        campaigns: records.campaigns,
        balances: records.balances,
        since,
        c_r_drift,
        delta_k2_drift,
        next,
        next_source,
        predicted_delta_k2: predicted,
        target_u95_rad_s_g2: target,
        share,
        limit_rad_s_g2: limit,
        advice,
    })
}
