//! The calibration's measurement model `Y = f(X)` (eq. 17–19).
//!
//! The fit's coefficients are taken at the nominal R, g and rates. Scaling R, g or the rates
//! multiplies each column of the design by a number, `X' = X·D`, so the coefficients become
//! `D⁻¹·β` exactly; with the lever heights, the probe gain and C_r this gives k0…k3 and Δk2
//! as functions of every input quantity. `pipeline`'s tests check that the model at the
//! nominal inputs equals `identify::identify_compensated`'s result.

use crate::TERMS;

/// The model's input quantities, by index.
pub mod input {
    /// Working radius R, m.
    pub const RADIUS: usize = 0;
    /// Gravity g, m/s².
    pub const G: usize = 1;
    /// Rate scale s common to every rate, 1 (nominal 1).
    pub const RATE_SCALE: usize = 2;
    /// Pivot-to-probe height, mm.
    pub const PIVOT_TO_PROBE: usize = 3;
    /// Probe-to-PIGA height, mm.
    pub const PROBE_TO_PIGA: usize = 4;
    /// Probe gain, 1 (nominal 1).
    pub const PROBE_GAIN: usize = 5;
    /// C_r of the compensating phase, m·s².
    pub const C_R: usize = 6;
    /// k1 when given, rad/(s·g) (ignored when k1 is fitted).
    pub const K1_GIVEN: usize = 7;
    /// The first of the six eq. 18 coefficients (order `1, ω, ω², ω³, a², a³`).
    pub const FIRST_COEFFICIENT: usize = 8;
    /// Number of input quantities.
    pub const COUNT: usize = FIRST_COEFFICIENT + crate::TERMS;
    /// Names of the inputs before the coefficients, in order, as a budget shows them.
    pub const NAMES: [&str; FIRST_COEFFICIENT] = [
        "R (working radius)",
        "g (gravity)",
        "rate scale (common to every rate)",
        "pivot-to-probe height",
        "probe-to-PIGA height",
        "probe gain",
        "C_r of the compensating phase",
        "k1 (given)",
    ];
    /// Units of the inputs before the coefficients, in [`NAMES`]' order, as a budget shows
    /// them.
    pub const UNITS: [&str; FIRST_COEFFICIENT] = [
        "m",
        "m/s²",
        "1 (relative)",
        "mm",
        "mm",
        "1 (relative)",
        "m·s²",
        "rad/(s·g)",
    ];
}

/// The model's outputs, by index.
pub mod output {
    /// k0, rad/s.
    pub const K0: usize = 0;
    /// k1, rad/(s·g).
    pub const K1: usize = 1;
    /// k2 compensated, rad/(s·g²).
    pub const K2: usize = 2;
    /// k3, rad/(s·g³).
    pub const K3: usize = 3;
    /// The apparent k2 (uncompensated), rad/(s·g²).
    pub const K2_UNCOMPENSATED: usize = 4;
    /// Δk2 = k1·C_r·g/R², rad/(s·g²).
    pub const DELTA_K2: usize = 5;
    /// Names of the outputs, in order.
    pub const NAMES: [&str; 6] = ["k0", "k1", "k2", "k3", "k2_uncompensated", "delta_k2"];
    /// Units of the outputs, in [`NAMES`]' order.
    pub const UNITS: [&str; 6] = [
        "rad/s",
        "rad/(s·g)",
        "rad/(s·g²)",
        "rad/(s·g³)",
        "rad/(s·g²)",
        "rad/(s·g²)",
    ];
}

/// The nominal values the model scales from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nominal {
    /// Working radius R, m.
    pub radius_m: f64,
    /// Gravity g, m/s².
    pub g_m_s2: f64,
    /// Pivot-to-probe height, mm.
    pub pivot_to_probe_mm: f64,
    /// Probe-to-PIGA height, mm.
    pub probe_to_piga_mm: f64,
}

/// Where the model's k1 comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum K1Mode {
    /// From the fit's ω² coefficient, `c₂·g/R`.
    Fitted,
    /// The input [`input::K1_GIVEN`].
    Given,
}

/// The calibration as a function of its input quantities ([`input`]: R, g, the rate scale,
/// the lever heights, the probe gain, C_r, k1 given, then the six coefficients of the eq. 18
/// fit at the nominal R, g and rates). Outputs ([`output`]): k0, k1, k2 (compensated), k3,
/// k2 uncompensated, Δk2.
#[derive(Debug, Clone, Copy)]
pub struct CalibrationModel {
    k1_fitted: bool,
    /// `R₀/g₀`, s² (computed once: the same numbers as per trial, without the divisions).
    radius_over_g_s2: f64,
    /// The nominal lever ratio `(h_p + h_a)/h_p`, 1.
    lever0: f64,
}

impl CalibrationModel {
    /// The model around `nominal`.
    #[must_use]
    pub fn new(nominal: Nominal, k1: K1Mode) -> Self {
        let n = nominal;
        Self {
            k1_fitted: k1 == K1Mode::Fitted,
            radius_over_g_s2: n.radius_m / n.g_m_s2,
            lever0: harmonics::lever_ratio(n.pivot_to_probe_mm, n.probe_to_piga_mm),
        }
    }

    /// Number of input quantities.
    #[must_use]
    pub const fn inputs(&self) -> usize {
        input::COUNT
    }

    /// Evaluates the six outputs at the inputs `x` (at least [`input::COUNT`] values; `out`
    /// at least six).
    pub fn evaluate(&self, x: &[f64], out: &mut [f64]) {
        let inputs: [f64; input::COUNT] = std::array::from_fn(|i| x[i]);
        out[..output::NAMES.len()].copy_from_slice(&self.outputs(&inputs));
    }

    /// The six outputs at the fourteen inputs (one trial).
    #[inline(always)]
    fn outputs(&self, x: &[f64; input::COUNT]) -> [f64; 6] {
        let (radius, g, s) = (x[0], x[1], x[2]);
        let (h_p, h_a, gain, c_r, k1_given) = (x[3], x[4], x[5], x[6], x[7]);
        let mut beta = [0.0; TERMS];
        beta.copy_from_slice(&x[input::FIRST_COEFFICIENT..input::COUNT]);
        // X' = X·D with D = diag(1, s, s², s³, ρ², ρ³), ρ = (R s²/g)/(R₀/g₀): β' = D⁻¹β.
        let rho = (radius * s * s / g) / self.radius_over_g_s2;
        let d = [1.0, s, s * s, s * s * s, rho * rho, rho * rho * rho];
        for (b, d) in beta.iter_mut().zip(d) {
            *b /= d;
        }
        let k1 = if self.k1_fitted {
            beta[2] * g / radius
        } else {
            k1_given
        };
        let lever = harmonics::lever_ratio(h_p, h_a);
        let c_r_true = c_r * gain * (lever / self.lever0) / (s * s);
        let delta_k2 = identify::delta_k2_rad_s_g2(k1, c_r_true, radius, g);
        [beta[0], k1, beta[4] - delta_k2, beta[5], beta[4], delta_k2]
    }
}

/// The Monte Carlo method and the GUM framework evaluate the model directly: it never fails,
/// and a non-finite output (a drawn R or g of zero) is a failed trial.
impl uncertainty::MeasurementModel for CalibrationModel {
    fn output_names(&self) -> Vec<String> {
        output::NAMES.iter().map(|&name| name.to_owned()).collect()
    }

    fn evaluate(&self, x: &[f64], y: &mut [f64]) -> Result<(), uncertainty::ModelError> {
        CalibrationModel::evaluate(self, x, y);
        Ok(())
    }

    fn input_count(&self) -> Option<usize> {
        Some(self.inputs())
    }

    /// The trials' columns evaluated in one loop, without a copy of each trial's inputs.
    fn evaluate_trials(
        &self,
        x: &[f64],
        stride: usize,
        len: usize,
        y: &mut [f64],
    ) -> Option<(usize, uncertainty::ModelError)> {
        const N: usize = input::COUNT;
        let columns: [&[f64]; N] =
            std::array::from_fn(|i| x.get(i * stride..i * stride + len).unwrap_or(&[]));
        if columns.iter().any(|c| c.len() != len) {
            y.fill(f64::NAN);
            return Some((
                0,
                uncertainty::ModelError::Failed {
                    reason: "fewer input columns than the model's fourteen inputs",
                },
            ));
        }
        for (t, out) in y
            .chunks_exact_mut(output::NAMES.len())
            .take(len)
            .enumerate()
        {
            let inputs: [f64; N] = std::array::from_fn(|i| columns[i][t]);
            out.copy_from_slice(&self.outputs(&inputs));
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use uncertainty::MeasurementModel as _;

    fn model() -> CalibrationModel {
        CalibrationModel::new(
            Nominal {
                radius_m: 2.5,
                g_m_s2: 9.8,
                pivot_to_probe_mm: 700.0,
                probe_to_piga_mm: 510.0,
            },
            K1Mode::Fitted,
        )
    }

    #[test]
    fn trials_by_columns_equal_trial_by_trial() {
        let model = model();
        let (len, stride) = (5, 7);
        let base = [
            2.5, 9.8, 1.0, 700.0, 510.0, 1.0, 1.6e-6, 0.0, 1e-5, 2e-6, 0.14, -3e-9, 5e-7, 2e-8,
        ];
        // Trial t perturbs every input by a different relative amount.
        let x: Vec<f64> = (0..model.inputs())
            .flat_map(|i| {
                (0..stride)
                    .map(move |t| base[i] * (1.0 + 1e-4 * (t as f64 - 2.0) * (i as f64 + 1.0)))
            })
            .collect();
        let mut by_columns = vec![0.0; len * 6];
        assert!(
            model
                .evaluate_trials(&x, stride, len, &mut by_columns)
                .is_none()
        );
        for t in 0..len {
            let xt: Vec<f64> = (0..model.inputs()).map(|i| x[i * stride + t]).collect();
            let mut y = [0.0; 6];
            CalibrationModel::evaluate(&model, &xt, &mut y);
            assert_eq!(&by_columns[t * 6..t * 6 + 6], &y[..], "trial {t}");
        }
        // Too few columns: every trial fails, nothing panics.
        let mut y = vec![0.0; len * 6];
        assert!(
            model
                .evaluate_trials(&x[..3 * stride], stride, len, &mut y)
                .is_some()
        );
        assert!(y.iter().all(|v| v.is_nan()));
    }

    #[test]
    fn at_the_nominal_inputs_delta_k2_is_eq_19() {
        let model = CalibrationModel::new(
            Nominal {
                radius_m: 2.5,
                g_m_s2: 9.8,
                pivot_to_probe_mm: 700.0,
                probe_to_piga_mm: 510.0,
            },
            K1Mode::Given,
        );
        let mut x = [0.0; input::COUNT];
        x[input::RADIUS] = 2.5;
        x[input::G] = 9.8;
        x[input::RATE_SCALE] = 1.0;
        x[input::PIVOT_TO_PROBE] = 700.0;
        x[input::PROBE_TO_PIGA] = 510.0;
        x[input::PROBE_GAIN] = 1.0;
        x[input::C_R] = 1.6e-6;
        x[input::K1_GIVEN] = 0.56;
        x[input::FIRST_COEFFICIENT + crate::A2_TERM] = 5e-7;
        let mut y = [0.0; 6];
        model.evaluate(&x, &mut y);
        let delta = 0.56 * 1.6e-6 * 9.8 / (2.5 * 2.5);
        assert!((y[output::DELTA_K2] / delta - 1.0).abs() < 1e-15);
        assert_eq!(y[output::K2_UNCOMPENSATED], 5e-7);
        assert_eq!(y[output::K2], 5e-7 - y[output::DELTA_K2]);
        // A probe gain 1 % high means the true C_r, and Δk2, are 1 % larger.
        x[input::PROBE_GAIN] = 1.01;
        model.evaluate(&x, &mut y);
        assert!((y[output::DELTA_K2] / (1.01 * delta) - 1.0).abs() < 1e-14);
    }
}
