//! The uncertainty of a two-orientation fit: the measurement model of its outputs, its
//! inputs, the GUM and Monte Carlo evaluation, the comparison of C with the probe's C_r and
//! the warnings.

use uncertainty::{
    Dof, GumOptions, GumResult, InputQuantity, McOptions, McResult, MeasurementModel, ModelError,
    UncertaintyError,
};

use super::error::TwoOrientationError;
use super::fit::TwoOrientationFit;
use super::terms::{
    B3_TERM, GAMMA_TERM, K2_TERM, K3_TERM, TWO_ORIENTATION_TERM_NAMES, TWO_ORIENTATION_TERMS,
    Z_LIMIT,
};
use crate::TypeB;

/// The probe's C_r as an input of the two-orientation evaluation, with the lever heights
/// it was carried to the PIGA plane through (eq. 22): the nominal values its Type B inputs
/// (lever heights, gain) scale from, as in [`CalibrationModel`](crate::CalibrationModel).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeCr {
    /// C_r from the probe, m·s².
    pub c_r_m_s2: f64,
    /// Its standard uncertainty, m·s².
    pub u_m_s2: f64,
    /// Its degrees of freedom (`None`: infinite).
    pub dof: Option<f64>,
    /// Height from the tilt pivot to the probe plane, mm (> 0).
    pub pivot_to_probe_mm: f64,
    /// Height from the probe plane to the PIGA plane, mm.
    pub probe_to_piga_mm: f64,
}

/// Names of the outputs of [`TwoOrientationModel`], in order (the last only with a probe).
pub const TWO_ORIENTATION_OUTPUTS: [&str; 9] = [
    "k0 (IA in)",
    "k1 (IA in)",
    "k0 (IA out)",
    "k1 (IA out)",
    "k2",
    "k3",
    "C",
    "Δk2,total",
    "C − C_r",
];

/// Units of [`TWO_ORIENTATION_OUTPUTS`], in its order.
pub const TWO_ORIENTATION_OUTPUT_UNITS: [&str; 9] = [
    "rad/s",
    "rad/(s·g)",
    "rad/s",
    "rad/(s·g)",
    "rad/(s·g²)",
    "rad/(s·g³)",
    "m·s²",
    "rad/(s·g²)",
    "m·s²",
];

/// The input quantities of [`TwoOrientationModel`], by index: the ten coefficients of eq. 23
/// (fitted at the declared radii, g and rates), then the quantities they were fitted at, then
/// with a probe its C_r and the quantities C_r depends on.
pub mod two_orientation_input {
    use super::TWO_ORIENTATION_TERMS;

    /// The first of the ten coefficients, in
    /// [`TWO_ORIENTATION_TERM_NAMES`](crate::TWO_ORIENTATION_TERM_NAMES)' order.
    pub const FIRST_COEFFICIENT: usize = 0;
    /// Gravity g, m/s².
    pub const G: usize = TWO_ORIENTATION_TERMS;
    /// Rate scale common to every rate of both mountings and of the probe phase, 1 (nominal 1).
    pub const RATE_SCALE: usize = G + 1;
    /// The IA-in mounting's radius, m.
    pub const RADIUS_IN: usize = G + 2;
    /// The IA-out mounting's radius, m (independent of the IA-in one).
    pub const RADIUS_OUT: usize = G + 3;
    /// The Earth rate about the spindle axis, signed by the spin, rad/s
    /// ([`AxialEarthRate`](crate::AxialEarthRate)).
    pub const EARTH_RATE: usize = G + 4;
    /// Inputs without a probe.
    pub const COUNT_WITHOUT_PROBE: usize = G + 5;
    /// Pivot-to-probe height, mm.
    pub const PIVOT_TO_PROBE: usize = COUNT_WITHOUT_PROBE;
    /// Probe-to-PIGA height, mm.
    pub const PROBE_TO_PIGA: usize = COUNT_WITHOUT_PROBE + 1;
    /// Probe gain, 1 (nominal 1).
    pub const PROBE_GAIN: usize = COUNT_WITHOUT_PROBE + 2;
    /// The probe's C_r, m·s².
    pub const C_R: usize = COUNT_WITHOUT_PROBE + 3;
    /// Inputs with a probe.
    pub const COUNT_WITH_PROBE: usize = COUNT_WITHOUT_PROBE + 4;
    /// Names of the inputs after the coefficients, in order, as a budget shows them.
    pub const NAMES: [&str; COUNT_WITH_PROBE - G] = [
        "g (gravity)",
        "rate scale (common to every rate)",
        "R of the IA-in mounting (independent of the IA-out one)",
        "R of the IA-out mounting (independent of the IA-in one)",
        "Earth rate about the spindle axis (with k2, a same-sign ω³ term)",
        "pivot-to-probe height",
        "probe-to-PIGA height",
        "probe gain",
        "C_r (probe)",
    ];
    /// Units of the inputs after the coefficients, in [`NAMES`]' order, as a budget shows
    /// them.
    pub const UNITS: [&str; COUNT_WITH_PROBE - G] = [
        "m/s²",
        "1 (relative)",
        "m",
        "m",
        "rad/s",
        "mm",
        "mm",
        "1 (relative)",
        "m·s²",
    ];
}

/// The measurement model of the two-orientation calibration: outputs
/// [`TWO_ORIENTATION_OUTPUTS`] as functions of the ten coefficients of eq. 23 fitted at the
/// declared radii, g and rates (one correlated Type A group), the true g, rate scale and radii
/// of both mountings, and, with a probe, its C_r with its lever heights and gain
/// ([`two_orientation_input`]).
///
/// g and the rate scale scale every column of eq. 23 by a power (`a_s = R_s·ω²/g`): the
/// coefficients follow exactly, as in [`CalibrationModel`](crate::CalibrationModel). A radius
/// scales its mounting's `s·a_s` column (k1,s) exactly; k2 and γ are found from the two
/// mountings' ω⁴ coefficients `e_s = k2·a_s²/ω⁴ + s·γ`, which the data fix whatever the radii:
/// `k2 = (e_in + e_out)/(A_in + A_out)`, `γ = (e_in·A_out − e_out·A_in)/(A_in + A_out)` with
/// `A_s = (R_s·σ²/g)²`. The shared `s·a_s³` column (k3) changes shape when the radii change by
/// different amounts: k3 is rescaled by `(P_in + P_out)/(Q_in + Q_out)` (`P_s`, `Q_s` the
/// column's `(R_s/g)³` at the declared and the true inputs), which leaves a term
/// `k3·D·ω⁶` of the same sign in both mountings, `D = (P_in·Q_out − P_out·Q_in)/(Q_in + Q_out)`;
/// its projection on the design, `k3·D·X⁺ω⁶`
/// ([`TwoOrientationFit::omega6_response`]), is added. What is left is of second order in the
/// radius changes (`docs/theory.md` section 11; tested against refits).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoOrientationModel {
    /// The declared IA-in radius, m.
    pub radius_in_m: f64,
    /// The declared IA-out radius, m.
    pub radius_out_m: f64,
    /// The g the fit used, m/s².
    pub g_m_s2: f64,
    /// The fit's response to a common `ω⁶` ([`TwoOrientationFit::omega6_response`]).
    pub omega6_response: [f64; TWO_ORIENTATION_TERMS],
    /// The fit's response to the Earth rate's term with k2
    /// ([`TwoOrientationFit::earth_rate_response`]).
    pub earth_rate_response: [f64; TWO_ORIENTATION_TERMS],
    /// With a probe: its nominal lever ratio `(h_p + h_a)/h_p` (and `C − C_r` an output).
    pub probe_lever: Option<f64>,
}

impl TwoOrientationModel {
    /// The model of `fit`, with the probe's lever heights when it is compared with a probe.
    #[must_use]
    pub fn new(fit: &TwoOrientationFit, probe: Option<&ProbeCr>) -> Self {
        Self {
            radius_in_m: fit.mountings[0].radius_m,
            radius_out_m: fit.mountings[1].radius_m,
            g_m_s2: fit.g_m_s2,
            omega6_response: fit.omega6_response,
            earth_rate_response: fit.earth_rate_response,
            probe_lever: probe
                .map(|p| harmonics::lever_ratio(p.pivot_to_probe_mm, p.probe_to_piga_mm)),
        }
    }

    /// Whether the probe's C_r is an input (and `C − C_r` an output).
    #[must_use]
    pub const fn with_probe(&self) -> bool {
        self.probe_lever.is_some()
    }

    /// Number of outputs.
    #[must_use]
    pub const fn output_count(&self) -> usize {
        if self.with_probe() { 9 } else { 8 }
    }

    /// Number of inputs.
    #[must_use]
    pub const fn input_count(&self) -> usize {
        if self.with_probe() {
            two_orientation_input::COUNT_WITH_PROBE
        } else {
            two_orientation_input::COUNT_WITHOUT_PROBE
        }
    }

    /// The ten coefficients eq. 23 would have at the true g, rate scale and radii of `x`:
    /// the refit of the same data with the columns those give.
    #[must_use]
    pub fn coefficients_at(&self, x: &[f64]) -> [f64; TWO_ORIENTATION_TERMS] {
        use two_orientation_input as i;
        let mut c = [0.0; TWO_ORIENTATION_TERMS];
        c.copy_from_slice(&x[..TWO_ORIENTATION_TERMS]);
        // the data hold β + k2·Ω_a·X⁺v (TwoOrientationFit::earth_rate_response) where the fit
        // reports β: k2 first (its own response divides it), then the others; at the declared
        // radii and g, before they are changed below (what that leaves is of second order)
        let omega_a = x[i::EARTH_RATE];
        if omega_a != 0.0 {
            let k2 = c[K2_TERM] / (1.0 + omega_a * self.earth_rate_response[K2_TERM]);
            for (cj, r) in c.iter_mut().zip(&self.earth_rate_response) {
                *cj -= k2 * omega_a * r;
            }
        }
        let (g, scale) = (x[i::G], x[i::RATE_SCALE]);
        let s2 = scale * scale;
        // a_s at the true inputs over a_s as fitted, per mounting
        let rho = [
            (x[i::RADIUS_IN] * s2 / g) / (self.radius_in_m / self.g_m_s2),
            (x[i::RADIUS_OUT] * s2 / g) / (self.radius_out_m / self.g_m_s2),
        ];
        let r0 = [
            self.radius_in_m / self.g_m_s2,
            self.radius_out_m / self.g_m_s2,
        ];
        // the ω⁴ coefficient of each mounting (k2·(R/g)² ± γ), fixed by the data
        let a0 = [r0[0] * r0[0], r0[1] * r0[1]];
        let e = [
            c[K2_TERM] * a0[0] + c[GAMMA_TERM],
            c[K2_TERM] * a0[1] - c[GAMMA_TERM],
        ];
        // σ⁴·(R_s/g)² at the true inputs
        let a = [rho[0] * rho[0] * a0[0], rho[1] * rho[1] * a0[1]];
        let k2 = (e[0] + e[1]) / (a[0] + a[1]);
        let gamma = (e[0] * a[1] - e[1] * a[0]) / ((a[0] + a[1]) * s2 * s2);
        // the s·a³ column: (R_s/g)³ as fitted (P) and at the true inputs (Q, with σ⁶)
        let p = [a0[0] * r0[0], a0[1] * r0[1]];
        let q = [rho[0].powi(3) * p[0], rho[1].powi(3) * p[1]];
        let k3 = c[K3_TERM];
        let d = (p[0] * q[1] - p[1] * q[0]) / (q[0] + q[1]);
        let mut out = c;
        for (m, rho) in rho.iter().enumerate() {
            out[3 * m + 1] = c[3 * m + 1] / scale;
            out[3 * m + 2] = c[3 * m + 2] / rho;
        }
        out[B3_TERM] = c[B3_TERM] / (s2 * scale);
        out[K2_TERM] = k2;
        out[K3_TERM] = k3 * (p[0] + p[1]) / (q[0] + q[1]);
        out[GAMMA_TERM] = gamma;
        // the common ω⁶ left by the k3 column's change of shape, as the fit takes it
        for (o, l) in out.iter_mut().zip(&self.omega6_response) {
            *o += k3 * d * l;
        }
        out
    }
}

impl MeasurementModel for TwoOrientationModel {
    fn output_names(&self) -> Vec<String> {
        TWO_ORIENTATION_OUTPUTS[..self.output_count()]
            .iter()
            .map(|s| (*s).to_owned())
            .collect()
    }

    fn input_count(&self) -> Option<usize> {
        Some(TwoOrientationModel::input_count(self))
    }

    fn evaluate(&self, x: &[f64], y: &mut [f64]) -> Result<(), ModelError> {
        use two_orientation_input as i;
        let c = self.coefficients_at(x);
        let (g, scale) = (x[i::G], x[i::RATE_SCALE]);
        let k1_mean = 0.5 * (c[2] + c[5]);
        let c_total = c[GAMMA_TERM] * g / k1_mean;
        let r_in = x[i::RADIUS_IN];
        y[0] = c[0];
        y[1] = c[2];
        y[2] = c[3];
        y[3] = c[5];
        y[4] = c[K2_TERM];
        y[5] = c[K3_TERM];
        y[6] = c_total;
        y[7] = c[GAMMA_TERM] * g * g / (r_in * r_in);
        if let Some(lever0) = self.probe_lever {
            // the probe's C_r as CalibrationModel takes it: its gain, its lever, and the
            // rate scale of the probe phase's rates
            let (h_p, h_a) = (x[i::PIVOT_TO_PROBE], x[i::PROBE_TO_PIGA]);
            let lever = harmonics::lever_ratio(h_p, h_a);
            let c_r = x[i::C_R] * x[i::PROBE_GAIN] * (lever / lever0) / (scale * scale);
            y[8] = c_total - c_r;
        }
        Ok(())
    }
}

/// The inputs of [`TwoOrientationModel`] for a fit ([`two_orientation_input`]): the ten coefficients as
/// one Type A group correlated through the fit's covariance (degrees of freedom
/// [`TwoOrientationFit::coefficients_dof`]: infinite for stated σ the residuals stay within,
/// else `n − 10`);
/// g, the rate scale and each mounting's radius with the Type B standard uncertainties of
/// `type_b` (`radius_u_m` applies to each mounting, the two radii independent); with a probe,
/// its lever heights, gain (`type_b`'s) and C_r (Type A, its own u and degrees of freedom).
///
/// # Errors
/// Those of [`uncertainty::Inputs::with_correlation`] (e.g. a negative or non-finite u).
pub fn two_orientation_inputs(
    fit: &TwoOrientationFit,
    type_b: &TypeB,
    probe: Option<ProbeCr>,
) -> Result<uncertainty::Inputs, UncertaintyError> {
    use two_orientation_input as i;
    let f = &fit.fit;
    let dof = fit.coefficients_dof();
    let name = |k: usize| i::NAMES[k - i::G];
    let mut q: Vec<InputQuantity> = TWO_ORIENTATION_TERM_NAMES
        .iter()
        .enumerate()
        .map(|(j, name)| {
            InputQuantity::type_a(
                format!("fit coefficient {name}"),
                f.coefficients[j],
                f.std_errors[j],
                dof,
            )
        })
        .collect();
    q.push(InputQuantity::normal(
        name(i::G),
        fit.g_m_s2,
        type_b.g_u_m_s2,
    ));
    q.push(InputQuantity::normal(
        name(i::RATE_SCALE),
        1.0,
        type_b.rate_u_relative,
    ));
    q.push(InputQuantity::normal(
        name(i::RADIUS_IN),
        fit.mountings[0].radius_m,
        type_b.radius_u_m,
    ));
    q.push(InputQuantity::normal(
        name(i::RADIUS_OUT),
        fit.mountings[1].radius_m,
        type_b.radius_u_m,
    ));
    let earth = type_b.axial_earth_rate;
    q.push(if earth.half_width_rad_s > 0.0 {
        InputQuantity::rectangular(
            name(i::EARTH_RATE),
            earth.value_rad_s,
            earth.half_width_rad_s,
        )
    } else {
        InputQuantity::normal(name(i::EARTH_RATE), earth.value_rad_s, 0.0)
    });
    if let Some(p) = probe {
        q.push(InputQuantity::normal(
            name(i::PIVOT_TO_PROBE),
            p.pivot_to_probe_mm,
            type_b.pivot_to_probe_u_mm,
        ));
        q.push(InputQuantity::normal(
            name(i::PROBE_TO_PIGA),
            p.probe_to_piga_mm,
            type_b.probe_to_piga_u_mm,
        ));
        q.push(InputQuantity::normal(
            name(i::PROBE_GAIN),
            1.0,
            type_b.probe_gain_u_relative,
        ));
        let d = p.dof.map_or(Dof::Infinite, Dof::Finite);
        q.push(InputQuantity::type_a(name(i::C_R), p.c_r_m_s2, p.u_m_s2, d));
    }
    let m = q.len();
    let mut r = vec![0.0; m * m];
    for i in 0..m {
        r[i * m + i] = 1.0;
    }
    for a in 0..TWO_ORIENTATION_TERMS {
        for b in 0..TWO_ORIENTATION_TERMS {
            let d = f.std_errors[a] * f.std_errors[b];
            if a != b && d > 0.0 {
                r[a * m + b] = (f.covariance[(a, b)] / d).clamp(-1.0, 1.0);
            }
        }
    }
    uncertainty::Inputs::with_correlation(q, &r)
}

/// What the two-orientation evaluation warns about.
#[derive(Debug, Clone, PartialEq)]
pub enum TwoOrientationWarning {
    /// The `s·ω⁴` term cannot be told apart from k2: fitting C widens u(k2) more than
    /// [`K2_INFLATION_LIMIT`](crate::K2_INFLATION_LIMIT) times.
    GammaNotSeparable {
        /// Its variance inflation factor (a diagnostic).
        vif: f64,
        /// u(k2) in the joint fit over u(k2) with C known.
        k2_inflation: f64,
        /// Correlation of the k2 and C estimates.
        correlation: f64,
    },
    /// The PIGA's C and the probe's C_r disagree (|z| > 3): radius growth the probe does not
    /// see (arm stretch), or the probe's declared sign, unit or lever is wrong.
    ProbeDisagrees {
        /// `C − C_r`, m·s².
        difference_m_s2: f64,
        /// Its standard uncertainty, m·s².
        u_m_s2: f64,
        /// `z = (C − C_r)/u`.
        z: f64,
    },
}

/// The two-orientation calibration evaluated: the GUM (with its budget) and, when asked, the
/// Monte Carlo method on [`TwoOrientationModel`], with `C − C_r` and its z when a probe is given.
#[derive(Debug, Clone)]
pub struct TwoOrientationEvaluation {
    /// The model evaluated.
    pub model: TwoOrientationModel,
    /// Its inputs.
    pub inputs: uncertainty::Inputs,
    /// The GUM evaluation (outputs [`TWO_ORIENTATION_OUTPUTS`]).
    pub gum: GumResult,
    /// The Monte Carlo evaluation, when asked for.
    pub monte_carlo: Option<McResult>,
    /// With a probe: `(C − C_r, u, z)`.
    pub probe_difference: Option<(f64, f64, f64)>,
    /// Warnings, in words a reader can act on ([`TwoOrientationWarning`]).
    pub warnings: Vec<TwoOrientationWarning>,
}

/// Evaluates the uncertainty of a two-orientation fit through `uncertainty`'s GUM and
/// (with `mc`) Monte Carlo method on [`TwoOrientationModel`] with the Type B inputs `type_b`
/// (u(R) of each mounting, u(g), the rate scale; with a probe its lever heights and gain),
/// compares C with the probe's C_r when given, and collects the warnings (a non-separable
/// `s·ω⁴` term; |z| > 3).
///
/// # Errors
/// [`TwoOrientationError::Invalid`] for a probe's lever height that is not finite (the
/// pivot-to-probe height > 0); [`TwoOrientationError::Uncertainty`] from the inputs (a negative or
/// non-finite u), the GUM or the Monte Carlo method.
pub fn evaluate_two_orientation(
    fit: &TwoOrientationFit,
    type_b: &TypeB,
    probe: Option<ProbeCr>,
    mc: Option<&McOptions>,
) -> Result<TwoOrientationEvaluation, TwoOrientationError> {
    if let Some(p) = probe {
        for (field, value, ok) in [
            (
                "probe.pivot_to_probe_mm",
                p.pivot_to_probe_mm,
                p.pivot_to_probe_mm.is_finite() && p.pivot_to_probe_mm > 0.0,
            ),
            (
                "probe.probe_to_piga_mm",
                p.probe_to_piga_mm,
                p.probe_to_piga_mm.is_finite(),
            ),
        ] {
            if !ok {
                return Err(TwoOrientationError::Invalid {
                    field: field.to_owned(),
                    value,
                    reason: "the probe's lever heights must be finite, the pivot-to-probe height > 0",
                });
            }
        }
    }
    let model = TwoOrientationModel::new(fit, probe.as_ref());
    let inputs =
        two_orientation_inputs(fit, type_b, probe).map_err(TwoOrientationError::Uncertainty)?;
    let gum = uncertainty::gum(&model, &inputs, &GumOptions::default())
        .map_err(TwoOrientationError::Uncertainty)?;
    let monte_carlo = mc
        .map(|o| uncertainty::monte_carlo(&model, &inputs, o))
        .transpose()
        .map_err(TwoOrientationError::Uncertainty)?;
    let mut warnings = Vec::new();
    if !fit.separable() {
        warnings.push(TwoOrientationWarning::GammaNotSeparable {
            vif: fit.gamma_vif,
            k2_inflation: fit.k2_inflation,
            correlation: fit.k2_gamma_correlation,
        });
    }
    let probe_difference = probe.is_some().then(|| {
        let o = &gum.outputs[8];
        let z = if o.standard_uncertainty > 0.0 {
            o.estimate / o.standard_uncertainty
        } else {
            0.0
        };
        (o.estimate, o.standard_uncertainty, z)
    });
    if let Some((d, u, z)) = probe_difference
        && z.abs() > Z_LIMIT
    {
        warnings.push(TwoOrientationWarning::ProbeDisagrees {
            difference_m_s2: d,
            u_m_s2: u,
            z,
        });
    }
    Ok(TwoOrientationEvaluation {
        model,
        inputs,
        gum,
        monte_carlo,
        probe_difference,
        warnings,
    })
}
