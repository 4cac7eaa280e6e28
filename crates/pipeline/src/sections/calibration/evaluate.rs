//! The calibration's evaluation: the eq. 18 fit (weighted, with the Paule–Mandel τ), the
//! measurement model [`CalibrationModel`] and its GUM and Monte Carlo evaluation, all through
//! the `calibration` crate.
//!
//! [`CalibrationModel`] is the same computation as a function of every input quantity —
//! R, g, a common rate scale, the lever heights, the probe gain, the phase's C_r, k1 when
//! given, and the six coefficients of the fit at the nominal R, g and rates. The fit's
//! coefficients are one Type A input group: their covariance from the residuals, ν = n − 6
//! degrees of freedom (JCGM 100 G.4 treats the group as one term; JCGM 101 draws it from a
//! multivariate t). A test checks that the model at the nominal inputs equals
//! `identify_compensated`'s result.

use ::calibration::{CalibrationModel, CalibrationWarning, Weighting};
use identify::CompensatedCalibration;

use super::validate::{CalibrationInputs, K1Choice, TypeB};
use crate::piga_data::PigaPoints;

/// The nominal values the model is linearised around and scales from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Nominal {
    pub(crate) radius_m: f64,
    pub(crate) g_m_s2: f64,
    pub(crate) pivot_to_probe_mm: f64,
    pub(crate) probe_to_piga_mm: f64,
    pub(crate) c_r_m_s2: f64,
}

/// Everything the calibration computes, before it becomes results.
pub(crate) struct Evaluated {
    pub(crate) cal: CompensatedCalibration,
    /// The measurement model (its check against the fit is a unit test).
    #[cfg_attr(not(test), allow(dead_code))]
    pub(crate) model: CalibrationModel,
    pub(crate) vif: [f64; 5],
    /// How much wider u(k0…k3) are than an evenly spread design's (`None`: not computable).
    pub(crate) inflation: Option<::calibration::CoefficientInflation>,
    pub(crate) gum: uncertainty::GumResult,
    pub(crate) mc: uncertainty::McResult,
    pub(crate) validation: uncertainty::Validation,
    /// The inputs of the uncertainty evaluation.
    pub(crate) quantities: Vec<uncertainty::InputQuantity>,
    pub(crate) weighting: Weighting,
    /// The residuals' standard deviation in rad/s (`calibration::Calibrated`).
    pub(crate) residual_sd_rad_s: f64,
    /// What the calibration says of its fit.
    pub(crate) fit_warnings: Vec<CalibrationWarning>,
}

/// Where a calibration failed.
#[derive(Debug)]
pub(crate) enum CalibrationFailure {
    Calibration(::calibration::CalibrationError),
    Uncertainty(uncertainty::UncertaintyError),
}

/// The nominal values and uncertainties the evaluation starts from.
pub(crate) struct Setting<'a> {
    pub(crate) nominal: Nominal,
    pub(crate) type_b: &'a TypeB,
    /// σ(C_r) and the degrees of freedom of the phase's fit (`None`: C_r exact).
    pub(crate) c_r_sigma: Option<(f64, usize)>,
    /// The probe's measuring direction (echoed with C_r).
    pub(crate) probe_direction: harmonics::ProbeDirection,
}

/// The calibration's uncertainty evaluation, set up: the eq. 18 fit, the measurement model,
/// its input quantities (validated, with the fit's correlations) and the Monte Carlo options.
pub(crate) struct Setup {
    pub(crate) cal: CompensatedCalibration,
    pub(crate) model: CalibrationModel,
    pub(crate) vif: [f64; 5],
    pub(crate) inflation: Option<::calibration::CoefficientInflation>,
    pub(crate) quantities: Vec<uncertainty::InputQuantity>,
    pub(crate) set: uncertainty::Inputs,
    pub(crate) options: uncertainty::McOptions,
    pub(crate) weighting: Weighting,
    pub(crate) residual_sd_rad_s: f64,
    pub(crate) fit_warnings: Vec<CalibrationWarning>,
}

/// Fits and builds the measurement model with its input quantities.
pub(crate) fn setup(
    inputs: &CalibrationInputs,
    points: &PigaPoints,
    setting: &Setting<'_>,
) -> std::result::Result<Setup, CalibrationFailure> {
    use uncertainty::McOptions;
    let n = setting.nominal;
    let rates_rad_s: Vec<f64> = points
        .rates_deg_s
        .iter()
        .map(|&r| units::deg_s_to_rad_s(r))
        .collect();
    let sigma_c_r = setting.c_r_sigma.map_or(0.0, |(s, _)| s);
    let geometry = identify::Geometry {
        radius_m: n.radius_m,
        g_m_s2: n.g_m_s2,
    };
    let k1_given = match inputs.k1 {
        K1Choice::Fitted => None,
        K1Choice::Given { k1_rad_s_g, .. } => Some(k1_rad_s_g),
    };
    let compensation = ::calibration::compensation(n.c_r_m_s2, sigma_c_r, k1_given);
    let ::calibration::Calibrated {
        calibration: cal,
        weighting,
        residual_sd_rad_s,
        inflation,
        warnings: fit_warnings,
    } = ::calibration::calibrate_compensated(
        &::calibration::Points {
            rates_rad_s: &rates_rad_s,
            outputs_rad_s: &points.outputs_rad_s,
            sigma_rad_s: points.sigma_rad_s.as_deref(),
        },
        geometry,
        &compensation,
    )
    .map_err(CalibrationFailure::Calibration)?;
    let nominal = ::calibration::Nominal {
        radius_m: n.radius_m,
        g_m_s2: n.g_m_s2,
        pivot_to_probe_mm: n.pivot_to_probe_mm,
        probe_to_piga_mm: n.probe_to_piga_mm,
    };
    let model = CalibrationModel::new(
        nominal,
        match inputs.k1 {
            K1Choice::Fitted => ::calibration::K1Mode::Fitted,
            K1Choice::Given { .. } => ::calibration::K1Mode::Given,
        },
    );
    let vif =
        ::calibration::variance_inflation(&cal, &rates_rad_s, weighting.sigma_used.as_deref());
    let type_b = setting.type_b.values;
    let k1 = match inputs.k1 {
        K1Choice::Fitted => ::calibration::K1Input::Fitted,
        K1Choice::Given {
            k1_rad_s_g,
            u_rad_s_g,
        } => ::calibration::K1Input::Given {
            k1_rad_s_g,
            u_rad_s_g,
        },
    };
    let c_r = ::calibration::CrInput {
        c_r_m_s2: n.c_r_m_s2,
        sigma: setting.c_r_sigma,
    };
    let (quantities, set) = ::calibration::measurement_inputs(
        &nominal,
        &type_b,
        c_r,
        k1,
        &cal.uncompensated.fit,
        weighting.group_dof,
    )
    .map_err(CalibrationFailure::Uncertainty)?;
    let options = McOptions {
        seed: inputs.seed,
        trials: match inputs.trials {
            None => McOptions::default().trials,
            Some(n) => uncertainty::Trials::Fixed(n),
        },
        ..McOptions::default()
    };
    Ok(Setup {
        cal,
        model,
        vif,
        inflation,
        quantities,
        set,
        options,
        weighting,
        residual_sd_rad_s,
        fit_warnings,
    })
}

/// Fits, builds the measurement model and evaluates its uncertainty (GUM and Monte Carlo).
pub(crate) fn evaluate(
    inputs: &CalibrationInputs,
    points: &PigaPoints,
    setting: &Setting<'_>,
) -> std::result::Result<Evaluated, CalibrationFailure> {
    use uncertainty::{GumOptions, gum, monte_carlo, validate};
    let Setup {
        cal,
        model,
        vif,
        inflation,
        quantities,
        set,
        options,
        weighting,
        residual_sd_rad_s,
        fit_warnings,
    } = setup(inputs, points, setting)?;
    let gum_result =
        gum(&model, &set, &GumOptions::default()).map_err(CalibrationFailure::Uncertainty)?;
    let mc = monte_carlo(&model, &set, &options).map_err(CalibrationFailure::Uncertainty)?;
    let validation = validate(&gum_result, &mc, 2).map_err(CalibrationFailure::Uncertainty)?;
    Ok(Evaluated {
        cal,
        model,
        vif,
        inflation,
        gum: gum_result,
        mc,
        validation,
        quantities,
        weighting,
        residual_sd_rad_s,
        fit_warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::piga_data::{self as data, PigaData, PigaTableRows};
    use std::path::{Path, PathBuf};

    /// Outputs of eq. 18 with given coefficients at `n` rates, plus a small deterministic
    /// wiggle so that the fit has residuals.
    fn table(n: usize, k: [f64; 6], nominal: &Nominal) -> (CalibrationInputs, PigaPoints) {
        let rates_deg_s: Vec<f64> = (1..=n).map(|i| 200.0 * i as f64 / n as f64).collect();
        let outputs_rad_s = rates_deg_s
            .iter()
            .enumerate()
            .map(|(i, &r)| {
                let w = units::deg_s_to_rad_s(r);
                let a = nominal.radius_m * w * w / nominal.g_m_s2;
                let wiggle = 1e-9 * ((i * 7919) % 13) as f64 / 13.0;
                k[0] + k[1] * w
                    + k[2] * w * w
                    + k[3] * w.powi(3)
                    + k[4] * a * a
                    + k[5] * a.powi(3)
                    + wiggle
            })
            .collect();
        let rows = PigaTableRows {
            field: "calibration.table".to_owned(),
            file: PathBuf::from("t.csv"),
            lines: (2..n + 2).collect(),
            rates_deg_s,
            outputs_rad_s,
            sigma_rad_s: None,
            labels: None,
            digest: None,
        };
        let inputs = CalibrationInputs {
            data: PigaData::Table(rows),
            phase: 0,
            k1: K1Choice::Fitted,
            seed: 3,
            trials: Some(2000),
            type_b: TypeB::default(),
            type_b_given: false,
        };
        let (points, warnings) = data::points(&inputs.data, Path::new("study.ron")).unwrap();
        assert!(warnings.is_empty());
        (inputs, points)
    }

    #[test]
    fn the_model_at_the_estimates_is_the_certified_fit() {
        let nominal = Nominal {
            radius_m: 2.5,
            g_m_s2: 9.8,
            pivot_to_probe_mm: 700.0,
            probe_to_piga_mm: 510.0,
            c_r_m_s2: 1.6e-6,
        };
        for k1 in [
            K1Choice::Fitted,
            K1Choice::Given {
                k1_rad_s_g: 0.5601,
                u_rad_s_g: 1e-5,
            },
        ] {
            let (inputs, points) = table(
                12,
                [1e-5, 2e-6, 0.56 * 2.5 / 9.8, -3e-9, 5e-7, 2e-8],
                &nominal,
            );
            let inputs = CalibrationInputs { k1, ..inputs };
            let tb = TypeB::default();
            let setting = Setting {
                nominal,
                type_b: &tb,
                c_r_sigma: Some((4e-10, 10)),
                probe_direction: harmonics::ProbeDirection::AgainstO1X1,
            };
            let e = evaluate(&inputs, &points, &setting).unwrap();
            let x: Vec<f64> = e.quantities.iter().map(|q| q.value).collect();
            let mut y = [0.0; 6];
            e.model.evaluate(&x, &mut y);
            let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
            // At the estimates the model is the uncompensated fit with Δk2 removed from the a²
            // coefficient: the same numbers.
            let unc = &e.cal.uncompensated;
            assert_eq!(y[0], unc.bias_rad_s);
            assert_eq!(y[3], unc.k3_rad_s_g3);
            assert_eq!(y[4], unc.k2_apparent_rad_s_g2);
            assert!(rel(y[1], e.cal.k1_used_rad_s_g) < 1e-14, "k1");
            assert!(rel(y[5], e.cal.delta_k2.delta_k2_rad_s_g2) < 1e-14, "Δk2");
            // identify's refit of the compensated outputs agrees far below the uncertainty.
            let se = &unc.fit.std_errors;
            assert!(
                (y[0] - e.cal.compensated.bias_rad_s).abs() < 1e-4 * se[0],
                "k0"
            );
            assert!((y[2] - e.cal.k2_rad_s_g2).abs() < 1e-4 * se[4], "k2");
            assert!(
                (y[3] - e.cal.compensated.k3_rad_s_g3).abs() < 1e-4 * se[5],
                "k3"
            );
            // Scaling every rate by s is the same as fitting the scaled rates.
            let s = 1.001;
            let mut scaled = x.clone();
            scaled[2] = s;
            e.model.evaluate(&scaled, &mut y);
            let rates: Vec<f64> = points
                .rates_deg_s
                .iter()
                .map(|r| units::deg_s_to_rad_s(r * s))
                .collect();
            let geometry = identify::Geometry {
                radius_m: 2.5,
                g_m_s2: 9.8,
            };
            let direct =
                identify::identify_calibration(&rates, &points.outputs_rad_s, geometry).unwrap();
            let se = &direct.fit.std_errors;
            assert!((y[4] - direct.k2_apparent_rad_s_g2).abs() < 1e-4 * se[4]);
            assert!((y[0] - direct.bias_rad_s).abs() < 1e-4 * se[0]);
            assert!(
                (y[4] - unc.k2_apparent_rad_s_g2).abs() > 1e-2 * se[4],
                "the scale matters"
            );
        }
    }
}
