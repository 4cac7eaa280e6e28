//! Figures drawn as SVG with plotters' SVG backend (no system fonts needed).

use plotters::prelude::*;

use crate::config::model_name;
use crate::error::{PipelineError, Result};
use crate::results::{ModelFit, PhaseResults};
use crate::units::{deg_s_to_rad_s, um_to_m};

fn plot_error(message: impl ToString) -> PipelineError {
    PipelineError::Plot {
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
