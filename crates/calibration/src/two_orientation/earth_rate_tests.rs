//! The Earth rate about the spindle axis meets k2 in a term eq. 23 has no column for (issue 31):
//! the specific force along the arm is `R·(ω + Ω_a)²/g`, so `k2·a²` carries
//! `4·k2·R²·Ω_a·ω³/g²`, the same sign in both mountings. On a PIGA with k2 = 3e-5 rad/(s·g²)
//! (sixty times the fixtures') the fit that ignores it moves k2 by 0.85 u; the model
//! ([`TwoOrientationModel`]) given Ω_a removes it, and the GUM with Ω_a unknown covers it.
//! Each campaign is compared with the same campaign (the same noise) on a site without an
//! Earth rate, so that what is measured is the term alone, not the noise's own draw.

use super::evaluate::{TwoOrientationModel, two_orientation_input};
use super::fit::{TwoOrientationFit, fit_two_orientation};
use super::refit_tests::{twelve_rates_rad_s, xorshift_noise};
use super::terms::{K2_TERM, Orientation, OrientationData};
use crate::{AxialEarthRate, Spin, TypeB};
use uncertainty::MeasurementModel as _;

const R: [f64; 2] = [2.5, 2.54];
const G: f64 = 9.8;
const K1: f64 = 0.56;
const K2: f64 = 3e-5;
const K3: f64 = 2e-8;
const C_M_S2: f64 = 2.08e-6;
const NOISE_RAD_S: f64 = 1e-9;
const LATITUDE_DEG: f64 = 39.9;

/// Both mountings' outputs with the Earth rate of `spin` at the latitude in the specific
/// force (every power of it; `None`: no Earth rate), the same deterministic noise, 12 rates
/// 35–200 deg/s.
fn fit_of(spin: Option<Spin>) -> TwoOrientationFit {
    let omega_a = spin.map_or(0.0, |s| AxialEarthRate::stated(LATITUDE_DEG, s).value_rad_s);
    let rates = twelve_rates_rad_s();
    let mut noise = xorshift_noise(0x9e37_79b9_7f4a_7c15, NOISE_RAD_S);
    let gamma = K1 * C_M_S2 / G;
    let outputs = [
        (Orientation::IaIn, 0, 1e-5),
        (Orientation::IaOut, 1, 1.4e-5),
    ]
    .map(|(o, k, k0)| {
        let s = o.sign();
        rates
            .iter()
            .map(|&w| {
                // the specific force along the input axis, in g: s·R(ω + Ω_a)²/g
                let a = s * R[k] * (w + omega_a).powi(2) / G;
                k0 + K1 * a
                    + K2 * a * a
                    + K3 * a.powi(3)
                    + s * (2e-9 * w - 3e-9 * w.powi(3) + gamma * w.powi(4))
                    + noise()
            })
            .collect::<Vec<f64>>()
    });
    let data = [Orientation::IaIn, Orientation::IaOut].map(|o| {
        let k = usize::from(o == Orientation::IaOut);
        OrientationData {
            field: "o",
            orientation: Some(o),
            radius_m: Some(R[k]),
            rates_rad_s: &rates,
            output_rad_s: &outputs[k],
            sigma_rad_s: None,
        }
    });
    fit_two_orientation(&data, G, "o").expect("a full-rank design")
}

/// k2 from the model at the fit's own g, rates and radii and the Earth rate `omega_a`.
fn k2_at(fit: &TwoOrientationFit, omega_a: f64) -> f64 {
    use two_orientation_input as i;
    let model = TwoOrientationModel::new(fit, None);
    let mut x = fit.fit.coefficients.clone();
    x.resize(i::COUNT_WITHOUT_PROBE, 0.0);
    x[i::G] = G;
    x[i::RATE_SCALE] = 1.0;
    x[i::RADIUS_IN] = R[0];
    x[i::RADIUS_OUT] = R[1];
    x[i::EARTH_RATE] = omega_a;
    let mut y = vec![0.0; model.output_count()];
    model.evaluate(&x, &mut y).expect("finite inputs");
    y[4]
}

#[test]
fn ignoring_the_earth_rate_moves_a_large_k2_by_most_of_a_u_and_stating_it_removes_the_move() {
    let without = fit_of(None);
    let reference = k2_at(&without, 0.0);
    for spin in [Spin::CounterclockwiseFromAbove, Spin::ClockwiseFromAbove] {
        let fit = fit_of(Some(spin));
        let u = fit.fit.std_errors[K2_TERM];
        let omega_a = AxialEarthRate::stated(LATITUDE_DEG, spin).value_rad_s;
        let ignored = (k2_at(&fit, 0.0) - reference) / u;
        let stated = (k2_at(&fit, omega_a) - reference) / u;
        assert!(
            ignored.abs() > 0.5,
            "{spin:?}: ignored moves k2 by {ignored} u"
        );
        assert!(stated.abs() < 0.01, "{spin:?}: stated leaves {stated} u");
        // the spin the Earth's way raises the fitted k2, the other way lowers it
        assert_eq!(ignored.signum(), omega_a.signum(), "{spin:?}");
    }
}

#[test]
fn an_unknown_earth_rate_widens_u_k2_to_cover_what_it_may_do() {
    let reference = k2_at(&fit_of(None), 0.0);
    let fit = fit_of(Some(Spin::CounterclockwiseFromAbove));
    let k2_u = |earth: AxialEarthRate| {
        let type_b = TypeB {
            axial_earth_rate: earth,
            ..TypeB::default()
        };
        let e = super::evaluate_two_orientation(&fit, &type_b, None, None).expect("evaluates");
        let k2 = e.gum.output("k2").expect("k2 is an output");
        (k2.estimate, k2.standard_uncertainty)
    };
    let (stated, u_stated) = k2_u(AxialEarthRate::stated(
        LATITUDE_DEG,
        Spin::CounterclockwiseFromAbove,
    ));
    let (unknown, u_unknown) = k2_u(AxialEarthRate::not_stated());
    assert!(
        (stated - reference).abs() < 0.01 * u_stated,
        "{stated} vs {reference}"
    );
    // the rectangular ±Ω adds (k2·Ω·X⁺v)²/3 to u²: most of a u on this PIGA
    assert!(u_unknown > 1.1 * u_stated, "{u_unknown} vs {u_stated}");
    // what the term did lies within the unknown case's 95 % interval about its estimate
    assert!(
        (unknown - reference).abs() < 1.65 * u_unknown,
        "{unknown} ± {u_unknown} vs {reference}"
    );
    // and the default TypeB has no such input at all: the fit as it was
    let (plain, _) = k2_u(AxialEarthRate::default());
    let fitted = fit.fit.coefficients[K2_TERM];
    assert!(
        (plain - fitted).abs() <= 1e-12 * fitted.abs(),
        "{plain} vs {fitted}"
    );
}
