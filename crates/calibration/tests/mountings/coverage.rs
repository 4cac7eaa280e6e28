//! Simulated five-mounting campaigns of each kind (`simulate::campaign_points`: the exact
//! chain with the spindle's drift along and across the arm, static and ∝ ω², and the arm
//! stretch): every chosen term's `k ± U95` (U95 = t₀.₉₇₅(ν)·u from the fit's covariance, ν
//! its degrees of freedom) covers the truth in 93–97 % of the campaigns. The noise-free
//! outputs are computed once; each campaign draws fresh noise and fits.

use accel_model::{
    AccelKind, ModelCoefficients, MountedSpindle, Mounting, MountingPreset, OutputUnit, Term,
};
use calibration::{
    ArmStretch, JointSpec, MountingData, Nuisances, ProbeCompensation, fit_mountings, separability,
};
use kinematics::EARTH_RATE_RAD_S;
use simulate::{CampaignMounting, MountingCampaign, campaign_points, noisy_outputs};
use uncertainty::{Dof, coverage_factor};

/// Campaigns per kind.
pub(crate) const CAMPAIGNS: u64 = 1000;

const PRESETS: [(MountingPreset, f64); 5] = simulate::FIXTURE_MOUNTINGS;

const LATITUDE_DEG: f64 = simulate::FIXTURE_LATITUDE_DEG;

pub(crate) fn spindle() -> MountedSpindle {
    simulate::fixture_spindle()
}

/// The probe's reading of the same spindle (exact here: the test is of the fit).
pub(crate) const PROBE: ProbeCompensation = ProbeCompensation {
    static_m: 5.6e-6,
    c_r_m_s2: 1.6e-6,
    c_r_u_m_s2: 0.0,
    static_across_m: -1.97e-6,
    c_ry_m_s2: 0.4e-6,
};

pub(crate) fn rates() -> Vec<f64> {
    (0..12)
        .map(|i| (35.0 + 15.0 * f64::from(i)).to_radians())
        .collect()
}

/// A kind's true coefficients, the terms it chooses and its noise per rate point.
pub(crate) fn truth(kind: AccelKind) -> (ModelCoefficients, Vec<Term>, f64) {
    let mut c = ModelCoefficients::zero(kind);
    let (values, sigma): (&[(Term, f64)], f64) = match kind {
        AccelKind::Piga => (&simulate::FIXTURE_PIGA_TRUTH, 1e-9),
        AccelKind::Pendulous { .. } => (&simulate::FIXTURE_PENDULOUS_TRUTH, 2e-6),
    };
    for &(t, v) in values {
        c.set(t, v);
    }
    (c, values.iter().map(|(t, _)| *t).collect(), sigma)
}

pub(crate) fn spec(kind: AccelKind, terms: Vec<Term>) -> JointSpec {
    JointSpec {
        kind,
        terms,
        omega3: true,
        arm_stretch: ArmStretch::Fit,
        g_m_s2: 9.8,
        earth_rate_vertical_rad_s: EARTH_RATE_RAD_S * LATITUDE_DEG.to_radians().sin(),
        probe: Some(PROBE),
    }
}

pub(crate) fn campaign(coefficients: ModelCoefficients) -> MountingCampaign {
    MountingCampaign {
        spindle: spindle(),
        coefficients,
        mountings: PRESETS
            .iter()
            .enumerate()
            .map(|(m, &(p, r))| CampaignMounting {
                axes: p.axes(),
                radius_m: r,
                bias_shift: 3e-6 * m as f64 * coefficients.get(Term::K1),
            })
            .collect(),
        rates_rad_s: rates(),
    }
}

pub(crate) fn data<'a>(rates: &'a [f64], outputs: &'a [Vec<f64>]) -> Vec<MountingData<'a>> {
    PRESETS
        .iter()
        .enumerate()
        .map(|(m, &(p, r))| MountingData {
            field: format!("mountings[{m}]"),
            mounting: Mounting::preset(p, r, 0.0),
            nuisances: if m == 0 {
                Nuisances::REFERENCE
            } else {
                Nuisances::REMOUNTED
            },
            rates_rad_s: rates,
            outputs: &outputs[m],
            sigma: None,
        })
        .collect()
}

#[allow(clippy::print_stderr)] // the coverage per term, shown with --nocapture
fn coverage_of(kind: AccelKind, seed: u64) {
    let (coefficients, terms, sigma) = truth(kind);
    let spec = spec(kind, terms.clone());
    let camp = campaign(coefficients);
    let points = campaign_points(&camp).unwrap();
    let rates = rates();
    let noise_free: Vec<Vec<f64>> = points
        .iter()
        .map(|m| m.iter().map(|p| p.output).collect())
        .collect();
    let s = separability(&spec, &data(&rates, &noise_free), true).unwrap();
    assert!(s.full_rank() && s.poorly.is_empty(), "{s}");
    let mut covered = vec![0_u32; terms.len() + 1];
    for k in 0..CAMPAIGNS {
        let outputs = noisy_outputs(&points, sigma, seed, k).unwrap();
        let fit = fit_mountings(&spec, &data(&rates, &outputs)).unwrap();
        let t95 = coverage_factor(0.95, fit.weighting.group_dof).unwrap();
        assert!(matches!(fit.weighting.group_dof, Dof::Finite(_)));
        for (j, &term) in terms.iter().enumerate() {
            let e = fit.term(term).unwrap();
            if (e.value - coefficients.get(term)).abs() <= t95 * e.u {
                covered[j] += 1;
            }
        }
        let c = fit.arm_stretch.unwrap().unseen_m_s2;
        if (c.0 - camp.spindle.arm_stretch_m_s2).abs() <= t95 * c.1 {
            covered[terms.len()] += 1;
        }
    }
    let names: Vec<&str> = terms
        .iter()
        .map(|t| t.symbol())
        .chain(["arm stretch C"])
        .collect();
    let report: Vec<String> = names
        .iter()
        .zip(&covered)
        .map(|(n, c)| format!("{n} {:.1} %", 100.0 * f64::from(*c) / CAMPAIGNS as f64))
        .collect();
    eprintln!("{}: {}", kind.words(), report.join(", "));
    for (n, &c) in names.iter().zip(&covered) {
        let rate = f64::from(c) / CAMPAIGNS as f64;
        assert!(
            (0.93..=0.97).contains(&rate),
            "{n}: covered in {:.1} % of {CAMPAIGNS} campaigns ({})",
            100.0 * rate,
            report.join(", ")
        );
    }
}

#[test]
fn five_mounting_piga_campaigns_cover_the_truth() {
    coverage_of(AccelKind::Piga, 29);
}

#[test]
fn five_mounting_pendulous_campaigns_cover_the_truth() {
    coverage_of(
        AccelKind::Pendulous {
            unit: OutputUnit::MilliAmpere,
        },
        836,
    );
}
