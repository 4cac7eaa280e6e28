//! The Type B inputs of the joint fit (`type_b_contributions`: each mounting's radius and its
//! fixture's three angles) tested by simulation, not only by formula: in each campaign the
//! true radii and the true case axes differ from the declared ones by draws of their stated u
//! (the axes turned about IA, PA and OA by an independent rotation written here, not the
//! library's), the data come from the exact chain at the true values, and the fit uses the
//! declared ones. `k ± t₀.₉₇₅(ν_eff)·u`, u from the fit and the Type B contributions (ν_eff by
//! Welch–Satterthwaite with ν = ∞ for Type B), covers the truth in at least 93 % of 1000
//! campaigns for every chosen term (95–96 % for k0, k2, k_oq, k_io, δ_o, δ_p; more for k1 and
//! k3, below); the fit's u alone does not (the Type B inputs dominate).

use accel_model::{AccelKind, CaseAxes};
use calibration::{MountingsTypeB, fit_mountings, type_b_contributions};
use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};
use simulate::{campaign_points, noisy_outputs};
use uncertainty::{Dof, coverage_factor};

use super::coverage::{CAMPAIGNS, campaign, data, rates, spec, truth};

/// The fixtures' angular uncertainty (each of the three angles), rad: 0.001°.
const ANGLE_U_RAD: f64 = 1.745_329_251_994_33e-5;
/// Each mounting's radius uncertainty, m.
const RADIUS_U_M: f64 = 5e-6;

/// `v` turned by `angle` about the unit vector `k` (Rodrigues).
fn turn(v: [f64; 3], k: [f64; 3], angle: f64) -> [f64; 3] {
    let (s, c) = angle.sin_cos();
    let kxv = [
        k[1] * v[2] - k[2] * v[1],
        k[2] * v[0] - k[0] * v[2],
        k[0] * v[1] - k[1] * v[0],
    ];
    let kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    [0, 1, 2].map(|j| v[j] * c + kxv[j] * s + k[j] * kv * (1.0 - c))
}

/// The axes turned about their own IA, then PA, then OA by `angles`.
fn turned(axes: CaseAxes, angles: [f64; 3]) -> CaseAxes {
    let mut a = axes;
    for (i, angle) in angles.into_iter().enumerate() {
        let k = [a.ia, a.pa, a.oa][i];
        a = CaseAxes {
            ia: turn(a.ia, k, angle),
            pa: turn(a.pa, k, angle),
            oa: turn(a.oa, k, angle),
        };
    }
    a
}

#[test]
#[allow(clippy::print_stderr)] // the coverage per term, shown with --nocapture
fn type_b_of_the_radii_and_the_fixture_angles_covers_the_truth() {
    let kind = AccelKind::Piga;
    let (coefficients, terms, sigma) = truth(kind);
    let spec = spec(kind, terms.clone());
    let declared = campaign(coefficients);
    let rates = rates();
    // the Type B contributions from the declared values and noise-free data (they depend on
    // the design, not on the draws)
    let points = campaign_points(&declared).unwrap();
    let noise_free: Vec<Vec<f64>> = points
        .iter()
        .map(|m| m.iter().map(|p| p.output).collect())
        .collect();
    let mut nominal = data(&rates, &noise_free);
    for d in &mut nominal {
        d.mounting.angle_u_deg = ANGLE_U_RAD.to_degrees();
    }
    let type_b = MountingsTypeB {
        radius_u_m: RADIUS_U_M,
        ..MountingsTypeB::default()
    };
    let contributions = type_b_contributions(&spec, &nominal, &type_b).unwrap();
    assert_eq!(contributions.len(), 5 * 4, "five radii and fifteen angles");
    let type_b_var: Vec<f64> = (0..terms.len())
        .map(|j| {
            contributions
                .iter()
                .map(|c| c.contributions[j].powi(2))
                .sum()
        })
        .collect();

    let normal = Normal::new(0.0, 1.0).unwrap();
    let mut covered = vec![0_u32; terms.len()];
    let mut covered_fit_only = vec![0_u32; terms.len()];
    for k in 0..CAMPAIGNS {
        let mut rng = StdRng::seed_from_u64(units::stream_seed(2911, k, 0));
        let mut truth_campaign = declared.clone();
        for m in &mut truth_campaign.mountings {
            m.radius_m += RADIUS_U_M * normal.sample(&mut rng);
            let angles = [0; 3].map(|_| ANGLE_U_RAD * normal.sample(&mut rng));
            m.axes = turned(m.axes, angles);
        }
        let points = campaign_points(&truth_campaign).unwrap();
        let outputs = noisy_outputs(&points, sigma, 2911, k).unwrap();
        let fit = fit_mountings(&spec, &data(&rates, &outputs)).unwrap();
        let Dof::Finite(nu_fit) = fit.weighting.group_dof else {
            panic!("an unweighted fit has finite ν");
        };
        for (j, &term) in terms.iter().enumerate() {
            let e = fit.term(term).unwrap();
            let u2 = e.u * e.u + type_b_var[j];
            let nu = u2 * u2 / (e.u.powi(4) / nu_fit);
            let t95 = coverage_factor(0.95, Dof::Finite(nu)).unwrap();
            let miss = (e.value - coefficients.get(term)).abs();
            if miss <= t95 * u2.sqrt() {
                covered[j] += 1;
            }
            if miss <= coverage_factor(0.95, fit.weighting.group_dof).unwrap() * e.u {
                covered_fit_only[j] += 1;
            }
        }
    }
    let report: Vec<String> = terms
        .iter()
        .zip(covered.iter().zip(&covered_fit_only))
        .map(|(t, (c, f))| {
            format!(
                "{} {:.1} % (fit's u alone {:.1} %)",
                t.symbol(),
                100.0 * f64::from(*c) / CAMPAIGNS as f64,
                100.0 * f64::from(*f) / CAMPAIGNS as f64
            )
        })
        .collect();
    eprintln!("{}", report.join(", "));
    // Never below 93 %; above 97 % where the fit's own u already holds part of the misfit
    // (k1 97.5 %, k3 100 % here): the fit's u comes from its residuals, and a radius or
    // fixture angle that is not the declared one leaves residuals the model cannot absorb, so
    // adding the Type B contribution counts that part twice. Conservative, and said in
    // docs/MODEL.md.
    for (t, &c) in terms.iter().zip(&covered) {
        let rate = f64::from(c) / CAMPAIGNS as f64;
        assert!(
            rate >= 0.93,
            "{}: {:.1} % ({})",
            t.symbol(),
            100.0 * rate,
            report.join(", ")
        );
    }
    // the Type B inputs matter here: without them k2 would be covered far less often
    let k2 = terms.iter().position(|t| t.symbol() == "k2").unwrap();
    assert!(
        f64::from(covered_fit_only[k2]) / (CAMPAIGNS as f64) < 0.5,
        "{}",
        report.join(", ")
    );
}
