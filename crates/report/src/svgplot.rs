//! A small SVG plotter for the report's figures: coordinates kept as decimals (a smooth
//! curve stays smooth at any zoom; an integer-pixel backend draws a slowly varying curve as
//! a staircase), light grids, tick labels as a person writes them (`20`, `0.5`, `2×10⁻⁸`),
//! error bars, a legend, and data drawn compactly (one path per series) so that a figure of
//! thousands of samples stays small.

use std::fmt::Write as _;

use crate::format::{esc, nice_step, tick};

/// Something drawn in a panel, in data coordinates.
#[derive(Debug, Clone)]
pub(crate) enum Series {
    /// A polyline.
    Line {
        points: Vec<(f64, f64)>,
        color: &'static str,
        width: f64,
        label: Option<String>,
    },
    /// Filled round markers.
    Points {
        points: Vec<(f64, f64)>,
        color: &'static str,
        radius: f64,
        label: Option<String>,
    },
    /// Markers with vertical error bars `(x, y, half-width)`.
    ErrorBars {
        points: Vec<(f64, f64, f64)>,
        color: &'static str,
        label: Option<String>,
    },
}

impl Series {
    fn label(&self) -> Option<&str> {
        match self {
            Self::Line { label, .. }
            | Self::Points { label, .. }
            | Self::ErrorBars { label, .. } => label.as_deref(),
        }
    }
}

/// One plot: axes with their ranges and labels, and what is drawn on them.
#[derive(Debug, Clone)]
pub(crate) struct Panel {
    pub title: Option<String>,
    pub x_label: String,
    pub y_label: String,
    pub x_range: (f64, f64),
    pub y_range: (f64, f64),
    /// A fixed x tick step (90 for an angle in degrees), else a round one.
    pub x_step: Option<f64>,
    pub series: Vec<Series>,
    /// Draw a legend of the labelled series.
    pub legend: bool,
    /// A horizontal reference line at y = 0.
    pub zero_line: bool,
}

impl Panel {
    /// The y range of everything drawn, padded by `pad` of its span (at least `min_span`).
    pub(crate) fn fit_y(series: &[Series], pad: f64, min_span: f64) -> (f64, f64) {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for s in series {
            match s {
                Series::Line { points, .. } | Series::Points { points, .. } => {
                    for &(_, y) in points {
                        lo = lo.min(y);
                        hi = hi.max(y);
                    }
                }
                Series::ErrorBars { points, .. } => {
                    for &(_, y, e) in points {
                        lo = lo.min(y - e);
                        hi = hi.max(y + e);
                    }
                }
            }
        }
        if !lo.is_finite() || !hi.is_finite() {
            return (-1.0, 1.0);
        }
        let span = (hi - lo).max(min_span);
        let mid = 0.5 * (hi + lo);
        (mid - span * (0.5 + pad), mid + span * (0.5 + pad))
    }
}

/// A figure: a title and panels on a grid.
#[derive(Debug, Clone)]
pub(crate) struct Figure {
    pub width: f64,
    pub title: String,
    pub columns: usize,
    pub panel_height: f64,
    pub panels: Vec<Panel>,
}

/// Ticks of a range: a round step and the multiples of it inside.
fn ticks(lo: f64, hi: f64, n: f64) -> (f64, Vec<f64>) {
    let step = nice_step(hi - lo, n);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    let values = (first..=last).map(|i| i as f64 * step).collect();
    (step, values)
}

/// A decimal coordinate, two decimals at most.
fn c(v: f64) -> String {
    let text = format!("{v:.2}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_owned()
    } else {
        text.to_owned()
    }
}

const FONT: &str = "DejaVu Sans, Liberation Sans, Arial, sans-serif";

impl Figure {
    /// Renders the figure as an SVG document.
    pub(crate) fn render(&self) -> String {
        let columns = self.columns.max(1);
        let rows = self.panels.len().div_ceil(columns);
        let title_h = 34.0;
        let height = title_h + self.panel_height * rows as f64;
        let mut out = String::new();
        let _ = writeln!(
            out,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"{FONT}\">",
            w = c(self.width),
            h = c(height)
        );
        let _ = writeln!(
            out,
            "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n<text x=\"{}\" y=\"22\" text-anchor=\"middle\" font-size=\"16\">{}</text>",
            c(self.width / 2.0),
            esc(&self.title)
        );
        let panel_w = self.width / columns as f64;
        for (i, p) in self.panels.iter().enumerate() {
            let x0 = (i % columns) as f64 * panel_w;
            let y0 = title_h + (i / columns) as f64 * self.panel_height;
            panel(&mut out, p, x0, y0, panel_w, self.panel_height);
        }
        out.push_str("</svg>\n");
        out
    }
}

fn panel(out: &mut String, p: &Panel, x0: f64, y0: f64, w: f64, h: f64) {
    let title_h = if p.title.is_some() { 20.0 } else { 4.0 };
    let (left, right, top, bottom) = (x0 + 74.0, x0 + w - 14.0, y0 + title_h + 6.0, y0 + h - 46.0);
    let (xl, xh) = p.x_range;
    let (yl, yh) = p.y_range;
    let sx = |x: f64| left + (x - xl) / (xh - xl) * (right - left);
    let sy = |y: f64| bottom - (y - yl) / (yh - yl) * (bottom - top);
    if let Some(t) = &p.title {
        let _ = writeln!(
            out,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"13\">{}</text>",
            c((left + right) / 2.0),
            c(y0 + 16.0),
            esc(t)
        );
    }
    // grid and ticks
    let (x_step, x_ticks) = match p.x_step {
        Some(step) => (
            step,
            (0..)
                .map(|i| xl + f64::from(i) * step)
                .take_while(|&x| x <= xh + 1e-9 * step)
                .collect(),
        ),
        None => ticks(xl, xh, (right - left) / 80.0),
    };
    let (y_step, y_ticks) = ticks(yl, yh, (bottom - top) / 38.0);
    let mut grid = String::new();
    for &x in &x_ticks {
        let _ = write!(grid, "M{} {}V{}", c(sx(x)), c(top), c(bottom));
    }
    for &y in &y_ticks {
        let _ = write!(grid, "M{} {}H{}", c(left), c(sy(y)), c(right));
    }
    let _ = writeln!(
        out,
        "<path d=\"{grid}\" stroke=\"#e3e3e3\" stroke-width=\"0.8\" fill=\"none\"/>"
    );
    let _ = writeln!(
        out,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#555\" stroke-width=\"0.8\"/>",
        c(left),
        c(top),
        c(right - left),
        c(bottom - top)
    );
    let mut labels = String::new();
    for &x in &x_ticks {
        let _ = write!(
            labels,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            c(sx(x)),
            c(bottom + 15.0),
            esc(&tick(x, x_step))
        );
    }
    for &y in &y_ticks {
        let _ = write!(
            labels,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>",
            c(left - 5.0),
            c(sy(y) + 4.0),
            esc(&tick(y, y_step))
        );
    }
    let _ = writeln!(out, "<g font-size=\"11\" fill=\"#222\">{labels}</g>");
    let _ = writeln!(
        out,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"12\">{}</text>",
        c((left + right) / 2.0),
        c(bottom + 34.0),
        esc(&p.x_label)
    );
    let (ly, lx) = ((top + bottom) / 2.0, x0 + 16.0);
    let _ = writeln!(
        out,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"12\" transform=\"rotate(-90 {} {})\">{}</text>",
        c(lx),
        c(ly),
        c(lx),
        c(ly),
        esc(&p.y_label)
    );
    let _ = writeln!(
        out,
        "<clipPath id=\"clip{id}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>\n<g clip-path=\"url(#clip{id})\">",
        c(left),
        c(top),
        c(right - left),
        c(bottom - top),
        id = c(x0 * 7.0 + y0)
    );
    if p.zero_line && yl < 0.0 && yh > 0.0 {
        let _ = writeln!(
            out,
            "<path d=\"M{} {}H{}\" stroke=\"#333\" stroke-width=\"1\"/>",
            c(left),
            c(sy(0.0)),
            c(right)
        );
    }
    for s in &p.series {
        match s {
            Series::Line {
                points,
                color,
                width,
                ..
            } => {
                let mut d = String::new();
                for (n, &(x, y)) in points.iter().enumerate() {
                    let _ = write!(
                        d,
                        "{}{} {}",
                        if n == 0 { "M" } else { "L" },
                        c(sx(x)),
                        c(sy(y))
                    );
                }
                let _ = writeln!(
                    out,
                    "<path d=\"{d}\" stroke=\"{color}\" stroke-width=\"{}\" fill=\"none\" stroke-linejoin=\"round\"/>",
                    c(*width)
                );
            }
            Series::Points {
                points,
                color,
                radius,
                ..
            } => {
                // zero-length segments with round caps: a dot each, a few bytes per point
                let mut d = String::new();
                for &(x, y) in points {
                    let _ = write!(d, "M{} {}h0", c(sx(x)), c(sy(y)));
                }
                let _ = writeln!(
                    out,
                    "<path d=\"{d}\" stroke=\"{color}\" stroke-width=\"{}\" stroke-linecap=\"round\" fill=\"none\"/>",
                    c(2.0 * radius)
                );
            }
            Series::ErrorBars { points, color, .. } => {
                let mut bars = String::new();
                let mut dots = String::new();
                for &(x, y, e) in points {
                    let (px, lo, hi) = (sx(x), sy(y - e), sy(y + e));
                    let _ = write!(
                        bars,
                        "M{} {}V{}M{} {}H{}M{} {}H{}",
                        c(px),
                        c(lo),
                        c(hi),
                        c(px - 4.0),
                        c(lo),
                        c(px + 4.0),
                        c(px - 4.0),
                        c(hi),
                        c(px + 4.0)
                    );
                    let _ = write!(dots, "M{} {}h0", c(px), c(sy(y)));
                }
                let _ = writeln!(
                    out,
                    "<path d=\"{bars}\" stroke=\"{color}\" stroke-width=\"1.2\" fill=\"none\"/>\n<path d=\"{dots}\" stroke=\"{color}\" stroke-width=\"7\" stroke-linecap=\"round\" fill=\"none\"/>"
                );
            }
        }
    }
    out.push_str("</g>\n");
    if p.legend {
        legend(out, &p.series, left + 8.0, top + 8.0);
    }
}

fn legend(out: &mut String, series: &[Series], x: f64, y: f64) {
    let entries: Vec<&Series> = series.iter().filter(|s| s.label().is_some()).collect();
    if entries.is_empty() {
        return;
    }
    let width = entries
        .iter()
        .map(|s| s.label().map_or(0, |l| l.chars().count()))
        .max()
        .unwrap_or(0) as f64
        * 6.3
        + 42.0;
    let height = 18.0 * entries.len() as f64 + 8.0;
    let _ = writeln!(
        out,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#fff\" fill-opacity=\"0.9\" stroke=\"#999\" stroke-width=\"0.8\"/>",
        c(x),
        c(y),
        c(width),
        c(height)
    );
    for (n, s) in entries.iter().enumerate() {
        let ly = y + 13.0 + 18.0 * n as f64;
        let sample = match s {
            Series::Line { color, width, .. } => format!(
                "<path d=\"M{} {}h22\" stroke=\"{color}\" stroke-width=\"{}\"/>",
                c(x + 8.0),
                c(ly),
                c(*width)
            ),
            Series::Points { color, radius, .. } => format!(
                "<path d=\"M{} {}h0\" stroke=\"{color}\" stroke-width=\"{}\" stroke-linecap=\"round\"/>",
                c(x + 19.0),
                c(ly),
                c((2.0 * radius).max(5.0))
            ),
            Series::ErrorBars { color, .. } => format!(
                "<path d=\"M{x1} {}V{}\" stroke=\"{color}\" stroke-width=\"1.2\"/><path d=\"M{x1} {}h0\" stroke=\"{color}\" stroke-width=\"7\" stroke-linecap=\"round\"/>",
                c(ly - 7.0),
                c(ly + 7.0),
                c(ly),
                x1 = c(x + 19.0)
            ),
        };
        let _ = writeln!(
            out,
            "{sample}<text x=\"{}\" y=\"{}\" font-size=\"11\">{}</text>",
            c(x + 36.0),
            c(ly + 4.0),
            esc(s.label().unwrap_or(""))
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside() {
        let (step, t) = ticks(0.0, 200.0, 10.0);
        assert_eq!(step, 20.0);
        assert_eq!(t.first(), Some(&0.0));
        assert_eq!(t.last(), Some(&200.0));
        let (step, t) = ticks(-1.1e-8, 1.1e-8, 8.0);
        assert_eq!(step, 5e-9);
        assert_eq!(t.len(), 5);
    }

    #[test]
    fn coordinates_keep_their_decimals() {
        assert_eq!(c(12.345_6), "12.35");
        assert_eq!(c(12.0), "12");
        assert_eq!(c(-0.001), "0");
    }

    #[test]
    fn a_figure_is_an_svg_document_with_its_labels() {
        let fig = Figure {
            width: 600.0,
            title: "a & b".to_owned(),
            columns: 1,
            panel_height: 300.0,
            panels: vec![Panel {
                title: None,
                x_label: "rate (deg/s)".to_owned(),
                y_label: "radius error (µm)".to_owned(),
                x_range: (0.0, 200.0),
                y_range: (-1.0, 1.0),
                x_step: None,
                series: vec![Series::Line {
                    points: vec![(0.0, 0.0), (100.0, 0.5)],
                    color: "#1f4e9c",
                    width: 2.0,
                    label: Some("fit".to_owned()),
                }],
                legend: true,
                zero_line: true,
            }],
        };
        let svg = fig.render();
        assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
        assert!(svg.contains("a &amp; b") && svg.contains(">fit<") && svg.contains(">200<"));
        assert!(svg.trim_end().ends_with("</svg>"));
    }
}
