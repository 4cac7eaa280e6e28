//! The study's figures as SVG (through [`crate::svgplot`]: decimal coordinates, light grids,
//! tick labels as a person writes them).

use crate::error::{ReportError, Result};
use crate::svgplot::{Figure, Panel, Series};
use pipeline::model_name;
use pipeline::{ModelFit, PhaseResults};
use units::{deg_s_to_rad_s, um_to_m};

fn plot_error(message: impl ToString) -> ReportError {
    ReportError::Plot {
        what: "radius_error.svg",
        message: message.to_string(),
    }
}

/// Evaluates a fitted radius-error model at a rate, µm.
fn model_um(fit: &ModelFit, rate_deg_s: f64) -> f64 {
    let w = deg_s_to_rad_s(rate_deg_s);
    fit.offset_um + fit.linear_um_s.unwrap_or(0.0) * w + fit.c_r_m_s2 * w * w / um_to_m(1.0)
}

/// Radius error against rate with the fitted curve: the paper's Fig. 5. The measured points
/// carry error bars of ± their standard error where the phase has one; the fit is a smooth
/// curve (decimal coordinates).
///
/// Returns the SVG document as text.
pub fn radius_error_svg(phase: &PhaseResults, title: &str) -> Result<String> {
    if phase.points.is_empty() {
        return Err(plot_error("the phase has no points"));
    }
    let max_rate = phase
        .points
        .iter()
        .map(|p| p.rate_deg_s)
        .fold(0.0_f64, f64::max);
    let x_max = max_rate * 1.05;
    let curve: Vec<(f64, f64)> = (0..=400)
        .map(|i| {
            let x = x_max * f64::from(i) / 400.0;
            (x, model_um(&phase.fit, x))
        })
        .collect();
    let with_sigma: Vec<(f64, f64, f64)> = phase
        .points
        .iter()
        .filter_map(|p| {
            p.radius_error_sigma_um
                .map(|s| (p.rate_deg_s, p.radius_error_um, s))
        })
        .collect();
    let measured = if with_sigma.len() == phase.points.len() {
        Series::ErrorBars {
            points: with_sigma,
            color: "#c0392b",
            label: Some("radius error from the probe, ± its standard error".to_owned()),
        }
    } else {
        Series::Points {
            points: phase
                .points
                .iter()
                .map(|p| (p.rate_deg_s, p.radius_error_um))
                .collect(),
            color: "#c0392b",
            radius: 3.5,
            label: Some("radius error from the probe".to_owned()),
        }
    };
    let fit = Series::Line {
        points: curve,
        color: "#1f4e9c",
        width: 2.0,
        label: Some(format!(
            "fit {}, C_r = {} m·s²",
            model_name(phase.fit.model),
            crate::format::significant(phase.fit.c_r_m_s2, 5)
        )),
    };
    let series = vec![fit, measured];
    let y_range = Panel::fit_y(&series, 0.08, 1e-3);
    let figure = Figure {
        width: 800.0,
        title: title.to_owned(),
        columns: 1,
        panel_height: 480.0,
        panels: vec![Panel {
            title: None,
            x_label: "rate (deg/s)".to_owned(),
            y_label: "radius error (µm)".to_owned(),
            x_range: (0.0, x_max),
            y_range,
            x_step: None,
            series,
            legend: true,
            zero_line: false,
        }],
    };
    Ok(figure.render())
}

/// The most samples of one revolution drawn per panel: enough to show the signal's shape and
/// noise, few enough to keep the figure small.
const MAX_SAMPLES_DRAWN: usize = 240;

/// Each recording's probe signal over one revolution with its fitted eq. 20 curve, one panel
/// per rate: the paper's Fig. 4. The samples are drawn as light dots (at most
/// `MAX_SAMPLES_DRAWN` (240) per panel, evenly chosen), the fit over them as a dark curve, with a
/// legend. `None` when the phase has no recordings.
pub fn probe_signals_svg(phase: &PhaseResults, title: &str) -> Result<Option<String>> {
    let traces: Vec<_> = phase
        .traces
        .iter()
        .filter_map(|t| t.fit_um.as_ref().map(|fit| (t, fit)))
        .collect();
    if traces.is_empty() {
        return Ok(None);
    }
    let columns = match traces.len() {
        1 => 1,
        2..=4 => 2,
        5..=9 => 3,
        _ => 4,
    };
    let mut panels = Vec::with_capacity(traces.len());
    for (n, (trace, fit)) in traces.iter().enumerate() {
        let curve: Vec<(f64, f64)> = (0..=180)
            .map(|d| {
                let deg = 2.0 * f64::from(d);
                (deg, fit.evaluate(deg.to_radians()))
            })
            .collect();
        let total = trace.gap_um.len();
        let stride = total.div_ceil(MAX_SAMPLES_DRAWN).max(1);
        let samples: Vec<(f64, f64)> = trace
            .angle_deg
            .iter()
            .zip(&trace.gap_um)
            .step_by(stride)
            .map(|(&x, &y)| (x, y))
            .collect();
        let first = n == 0;
        let series = vec![
            Series::Points {
                points: samples,
                color: "#9db4cf",
                radius: 1.4,
                label: first.then(|| {
                    if stride > 1 {
                        format!("samples (every {stride}th of {total})")
                    } else {
                        "samples".to_owned()
                    }
                }),
            },
            Series::Line {
                points: curve,
                color: "#b03a2e",
                width: 1.6,
                label: first.then(|| "fit (eq. 20)".to_owned()),
            },
        ];
        let y_range = Panel::fit_y(&series, 0.08, 1e-3);
        panels.push(Panel {
            title: Some(format!("{} deg/s", crate::format::rate(trace.rate_deg_s))),
            x_label: "spindle angle (deg)".to_owned(),
            y_label: "gap (µm)".to_owned(),
            x_range: (0.0, 360.0),
            y_range,
            x_step: Some(90.0),
            series,
            legend: first,
            zero_line: false,
        });
    }
    let figure = Figure {
        width: 330.0 * columns as f64,
        title: title.to_owned(),
        columns,
        panel_height: 250.0,
        panels,
    };
    Ok(Some(figure.render()))
}

/// The calibration's residuals (output − fitted eq. 18) against rate, with error bars of ±
/// each point's standard uncertainty for a weighted fit, else ± the fit's residual standard
/// deviation (the noise every point was weighted with).
pub fn calibration_residuals_svg(
    calibration: &pipeline::CalibrationResults,
    title: &str,
) -> Result<String> {
    let sd = calibration.residual_sd_rad_s;
    let rows = &calibration.residuals;
    if rows.is_empty() {
        return Err(ReportError::Plot {
            what: "calibration_residuals.svg",
            message: "the calibration has no points".to_owned(),
        });
    }
    let bar = |r: &pipeline::CalibrationRow| r.u_rad_s.unwrap_or(sd);
    let x_max = rows.iter().map(|r| r.rate_deg_s).fold(0.0_f64, f64::max) * 1.05;
    let y_max = rows
        .iter()
        .map(|r| r.residual_rad_s.abs() + bar(r))
        .fold(0.0_f64, f64::max)
        .max(f64::MIN_POSITIVE)
        * 1.25;
    let series = vec![Series::ErrorBars {
        points: rows
            .iter()
            .map(|r| (r.rate_deg_s, r.residual_rad_s, bar(r)))
            .collect(),
        color: "#1f4e9c",
        label: Some(if calibration.weighted {
            "residual ± the point's standard uncertainty".to_owned()
        } else {
            format!(
                "residual ± residual SD ({} rad/s)",
                crate::format::significant(sd, 2)
            )
        }),
    }];
    let figure = Figure {
        width: 800.0,
        title: title.to_owned(),
        columns: 1,
        panel_height: 440.0,
        panels: vec![Panel {
            title: None,
            x_label: "rate (deg/s)".to_owned(),
            y_label: "residual (rad/s)".to_owned(),
            x_range: (0.0, x_max),
            y_range: (-y_max, y_max),
            x_step: None,
            series,
            legend: true,
            zero_line: true,
        }],
    };
    Ok(figure.render())
}
