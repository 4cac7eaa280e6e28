//! Figures drawn as SVG with plotters' SVG backend (no system fonts needed).

use plotters::prelude::*;

use crate::error::{ReportError, Result};
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

/// Radius error against rate with the fitted curve(s): the paper's Fig. 5.
///
/// Returns the SVG document as text.
pub fn radius_error_svg(phase: &PhaseResults, title: &str) -> Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 520)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let max_rate = phase
            .points
            .iter()
            .map(|p| p.rate_deg_s)
            .fold(0.0_f64, f64::max);
        let x_max = max_rate * 1.05;
        let samples: Vec<f64> = (0..=200).map(|i| x_max * f64::from(i) / 200.0).collect();
        let mut values: Vec<f64> = phase.points.iter().map(|p| p.radius_error_um).collect();
        values.extend(samples.iter().map(|&x| model_um(&phase.fit, x)));
        let (lo, hi) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        let pad = ((hi - lo) * 0.1).max(1e-3);
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 20))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..x_max, (lo - pad)..(hi + pad))
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .x_desc("rate (deg/s)")
            .y_desc("radius error (µm)")
            .draw()
            .map_err(plot_error)?;
        let fit_label = format!(
            "fit {}, C_r = {:.4e} m·s²",
            model_name(phase.fit.model),
            phase.fit.c_r_m_s2
        );
        chart
            .draw_series(LineSeries::new(
                samples.iter().map(|&x| (x, model_um(&phase.fit, x))),
                BLUE.stroke_width(2),
            ))
            .map_err(plot_error)?
            .label(fit_label)
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
        chart
            .draw_series(
                phase
                    .points
                    .iter()
                    .map(|p| Circle::new((p.rate_deg_s, p.radius_error_um), 5, RED.filled())),
            )
            .map_err(plot_error)?
            .label("radius error from the probe")
            .legend(|(x, y)| Circle::new((x + 10, y), 5, RED.filled()));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(plot_error)?;
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}

/// Each recording's probe signal over one revolution with its fitted eq. 20 curve, one panel
/// per rate: the paper's Fig. 4. `None` when the phase has no recordings.
pub fn probe_signals_svg(phase: &PhaseResults, title: &str) -> Result<Option<String>> {
    let traces: Vec<_> = phase
        .traces
        .iter()
        .filter_map(|t| t.fit_um.as_ref().map(|fit| (t, fit)))
        .collect();
    if traces.is_empty() {
        return Ok(None);
    }
    let err = |message: String| ReportError::Plot {
        what: "probe_signals.svg",
        message,
    };
    let columns = if traces.len() > 1 { 2 } else { 1 };
    let rows = traces.len().div_ceil(columns);
    let size = (520 * columns as u32, 60 + 300 * rows as u32);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let root = root
            .titled(title, ("sans-serif", 20))
            .map_err(|e| err(e.to_string()))?;
        let panels = root.split_evenly((rows, columns));
        for (panel, (trace, fit)) in panels.iter().zip(&traces) {
            let curve: Vec<(f64, f64)> = (0..=360)
                .map(|d| {
                    let deg = f64::from(d);
                    (deg, fit.evaluate(deg.to_radians()))
                })
                .collect();
            let values = trace.gap_um.iter().chain(curve.iter().map(|(_, y)| y));
            let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
            let pad = ((hi - lo) * 0.08).max(1e-3);
            let mut chart = ChartBuilder::on(panel)
                .caption(format!("{} deg/s", trace.rate_deg_s), ("sans-serif", 15))
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(60)
                .build_cartesian_2d(0.0..360.0, (lo - pad)..(hi + pad))
                .map_err(|e| err(e.to_string()))?;
            chart
                .configure_mesh()
                .x_desc("spindle angle (deg)")
                .y_desc("gap (µm)")
                .x_labels(7)
                .draw()
                .map_err(|e| err(e.to_string()))?;
            chart
                .draw_series(LineSeries::new(curve, BLUE.stroke_width(1)))
                .map_err(|e| err(e.to_string()))?;
            chart
                .draw_series(
                    trace
                        .angle_deg
                        .iter()
                        .zip(&trace.gap_um)
                        .map(|(&x, &y)| Circle::new((x, y), 2, RED.mix(0.6).filled())),
                )
                .map_err(|e| err(e.to_string()))?;
        }
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(Some(svg))
}

/// The calibration's residuals (output − fitted eq. 18) against rate, with error bars of ±
/// each point's standard uncertainty for a weighted fit, else ± the fit's residual standard
/// deviation (the noise every point was weighted with).
pub fn calibration_residuals_svg(
    calibration: &pipeline::CalibrationResults,
    title: &str,
) -> Result<String> {
    let err = |message: String| ReportError::Plot {
        what: "calibration_residuals.svg",
        message,
    };
    let sd = calibration.residual_sd_rad_s;
    let rows = &calibration.residuals;
    let bar = |r: &pipeline::CalibrationRow| r.u_rad_s.unwrap_or(sd);
    let x_max = rows.iter().map(|r| r.rate_deg_s).fold(0.0_f64, f64::max) * 1.05;
    let y_max = rows
        .iter()
        .map(|r| r.residual_rad_s.abs() + bar(r))
        .fold(0.0_f64, f64::max)
        .max(f64::MIN_POSITIVE)
        * 1.15;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 480)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 20))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(80)
            .build_cartesian_2d(0.0..x_max, -y_max..y_max)
            .map_err(|e| err(e.to_string()))?;
        let (x_step, y_step) = (
            crate::format::nice_step(x_max, 10.0),
            crate::format::nice_step(2.0 * y_max, 10.0),
        );
        chart
            .configure_mesh()
            .x_desc("rate (deg/s)")
            .y_desc("residual (rad/s)")
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(200, 200, 200))
            .x_label_formatter(&|v| crate::format::tick(*v, x_step))
            .y_label_formatter(&|v| crate::format::tick(*v, y_step))
            .draw()
            .map_err(|e| err(e.to_string()))?;
        chart
            .draw_series(rows.iter().map(|r| {
                ErrorBar::new_vertical(
                    r.rate_deg_s,
                    r.residual_rad_s - bar(r),
                    r.residual_rad_s,
                    r.residual_rad_s + bar(r),
                    BLUE.filled(),
                    8,
                )
            }))
            .map_err(|e| err(e.to_string()))?
            .label(if calibration.weighted {
                "residual ± the point's standard uncertainty".to_owned()
            } else {
                format!("residual ± residual SD ({sd:.2e} rad/s)")
            })
            .legend(|(x, y)| Circle::new((x + 10, y), 4, BLUE.filled()));
        chart
            .draw_series(LineSeries::new(
                [(0.0, 0.0), (x_max, 0.0)],
                BLACK.stroke_width(1),
            ))
            .map_err(|e| err(e.to_string()))?;
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| err(e.to_string()))?;
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(svg)
}
