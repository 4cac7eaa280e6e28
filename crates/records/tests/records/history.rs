//! The history from the records: the interval's worked example of docs/RECORDS.md against a
//! hand calculation, and the centrifuge's warning before the campaign whose Δk2 would exceed
//! the share of the target U95.

use std::path::Path;

use approx::assert_relative_eq;
use records::{
    Advice, Database, Date, HealthOptions, IntervalRequest, centrifuge_health, variables_interval,
};

use crate::common::{campaign, json, submission, variant};

#[test]
fn the_worked_example_of_the_interval_equals_a_hand_calculation() {
    // docs/RECORDS.md, "Worked example": k2 drifts by b = 0.30 µg/g² per year with
    // u_b = 0.05 µg/g² per year; the latest certificate states u₀ = 0.08 µg/g²; the tolerance
    // is ±1.0 µg/g² about the value certified, the reliability target 95 %.
    let (b, ub, u0, l) = (0.30_f64, 0.05_f64, 0.08_f64, 1.0_f64);
    let interval = variables_interval(
        IntervalRequest {
            tolerance: l,
            reliability: 0.95,
        },
        u0,
        b,
        ub,
    )
    .unwrap();
    // By hand: z = Φ⁻¹(0.95) = 1.644854 (a normal table); square |b|T + z√(u₀² + u_b²T²) = L
    // into A·T² + B·T + C = 0 and take the smaller root with the textbook formula.
    let z = 1.644_853_626_951_472_2_f64;
    assert_relative_eq!(interval.z, z, max_relative = 1e-12);
    let a = b * b - z * z * ub * ub; // 0.09 − 0.0067640 = 0.0832360
    let bb = -2.0 * l * b; // −0.6
    let c = l * l - z * z * u0 * u0; // 1 − 0.0173157 = 0.9826843
    let t = (-bb - (bb * bb - 4.0 * a * c).sqrt()) / (2.0 * a);
    assert_relative_eq!(interval.years.unwrap(), t, max_relative = 1e-12);
    // at the end of the interval the deviation and its one-sided 95 % bound reach L
    assert_relative_eq!(
        b * t + z * (u0 * u0 + ub * ub * t * t).sqrt(),
        l,
        max_relative = 1e-12
    );
    // the document states the same number
    let doc = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/RECORDS.md"),
    )
    .unwrap();
    let stated = format!("T = {t:.2} years");
    assert!(doc.contains(&stated), "docs/RECORDS.md states `{stated}`");
}

/// Records campaigns every four months whose C_r grows linearly (a spindle going out of
/// balance), and asks for the health after each: the warning must come exactly before the
/// first campaign whose Δk2 exceeds the share of the target U95.
#[test]
fn the_centrifuge_warns_before_the_campaign_whose_delta_k2_would_exceed_the_share() {
    let base = campaign();
    let c_r0 = base.phases[0].fit.c_r_m_s2;
    let dk2_per_c_r = base.phases[0].fit.delta_k2_rad_s_g2 / c_r0;
    let u_dk2 = base.phases[0].fit.delta_k2_sigma_rad_s_g2.unwrap();
    // C_r grows by 30 % of its first value per campaign; small noise (well within σ).
    let noise = [0.3, -0.5, 0.2, -0.1, 0.4, -0.3, 0.1, 0.0];
    let c_r = |n: usize| c_r0 * (1.0 + 0.3 * n as f64) + noise[n] * u_dk2 / dk2_per_c_r;
    // the share of the target U95 of k2: the limit is crossed between campaigns 4 and 5
    let limit = (1.0 + 0.3 * 4.5) * c_r0 * dk2_per_c_r;
    let share = 0.25;
    let target = limit / share;
    let first_over = (0..noise.len())
        .find(|&n| c_r(n) * dk2_per_c_r > limit)
        .unwrap();
    assert_eq!(
        first_over, 5,
        "the simulation crosses the limit at campaign 5"
    );

    let mut db = Database::in_memory().unwrap();
    let start = Date::parse("2026-01-15").unwrap();
    let mut warned_before = None;
    for n in 0..noise.len() {
        let date = Date::from_days(start.days() + 120 * n as i64).to_string();
        let r = variant(&format!("CC-{n}"), &date, None, Some(c_r(n)));
        let bytes = json(&r);
        db.record(&submission(&r, &bytes)).unwrap();
        let health = centrifuge_health(
            db.centrifuge_records("CF-2 (asset 1021)").unwrap(),
            &HealthOptions {
                target_u95_rad_s_g2: Some(target),
                share,
                next: None,
            },
        )
        .unwrap();
        assert_eq!(health.campaigns.len(), n + 1);
        if n == 0 {
            assert_eq!(health.advice, Advice::TooFewCampaigns);
            continue;
        }
        // the next campaign is predicted 120 days on (the mean spacing)
        assert_eq!(
            health.next.unwrap().days() - start.days(),
            120 * (n as i64 + 1)
        );
        let d = health.delta_k2_drift.as_ref().unwrap();
        assert!(
            d.significant,
            "campaign {n}: the drift of Δk2 is significant"
        );
        if health.advice == Advice::Rebalance && warned_before.is_none() {
            warned_before = Some(n + 1);
        }
        if n + 1 < first_over {
            assert_ne!(
                health.advice,
                Advice::Rebalance,
                "no warning before campaign {n}"
            );
        }
    }
    assert_eq!(
        warned_before,
        Some(first_over),
        "warned after the campaign before the first one over the limit"
    );

    // a balancing starts the fit again
    db.record_balance(
        "CF-2 (asset 1021)",
        Date::from_days(start.days() + 120 * 8),
        "trial weight, 12 g at 40°",
    )
    .unwrap();
    let health = centrifuge_health(
        db.centrifuge_records("CF-2 (asset 1021)").unwrap(),
        &HealthOptions {
            target_u95_rad_s_g2: Some(target),
            share,
            next: None,
        },
    )
    .unwrap();
    assert_eq!(health.fitted, 0);
    assert_eq!(health.advice, Advice::TooFewCampaigns);
}
