//! What lies where on the laid-out pages: the items outside a rectangle (text running past
//! the printable area) and each page's text in reading order.

use typst::layout::{Abs, Frame, FrameItem, Point, Transform};
use typst_layout::PagedDocument;

/// A rectangle on the page, as distances from its edges in points (1/72 inch).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Area {
    /// From the left edge.
    pub left_pt: f64,
    /// From the top edge.
    pub top_pt: f64,
    /// From the right edge.
    pub right_pt: f64,
    /// From the bottom edge.
    pub bottom_pt: f64,
}

impl Area {
    /// The same distance `mm` millimetres from each edge.
    #[must_use]
    pub fn inset_mm(left: f64, top: f64, right: f64, bottom: f64) -> Self {
        let pt = |mm: f64| mm / 25.4 * 72.0;
        Self {
            left_pt: pt(left),
            top_pt: pt(top),
            right_pt: pt(right),
            bottom_pt: pt(bottom),
        }
    }
}

/// An item that reaches outside an [`Area`].
#[derive(Debug, Clone, PartialEq)]
pub struct Stray {
    /// The page, 1-based.
    pub page: usize,
    /// What it is: the text of a glyph run, or `shape` / `image`.
    pub what: String,
    /// Its bounding box on the page, points from the top-left corner: x0, y0, x1, y1.
    pub bbox_pt: [f64; 4],
}

/// The bounding box of `(min, max)` under `ts`, as [x0, y0, x1, y1] in points.
fn transformed(ts: Transform, min: Point, max: Point) -> Option<[f64; 4]> {
    let corners = [
        Point::new(min.x, min.y),
        Point::new(max.x, min.y),
        Point::new(min.x, max.y),
        Point::new(max.x, max.y),
    ];
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for c in corners {
        let p = c.transform(ts);
        let (x, y) = (p.x.to_pt(), p.y.to_pt());
        if !x.is_finite() || !y.is_finite() {
            return None;
        }
        b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
    }
    Some(b)
}

/// Every leaf item of `frame` with its bounding box on the page.
fn visit(frame: &Frame, ts: Transform, out: &mut Vec<(String, [f64; 4], f64)>) {
    for (pos, item) in frame.items() {
        let here = ts.pre_concat(Transform::translate(pos.x, pos.y));
        match item {
            FrameItem::Group(g) => visit(&g.frame, here.pre_concat(g.transform), out),
            FrameItem::Text(t) => {
                let r = t.bbox();
                // glyphs without outline (spaces) give no box: the advance's extent
                let (min, max) = if r.min.x.to_pt().is_finite() {
                    (r.min, r.max)
                } else {
                    (Point::zero(), Point::new(t.width(), Abs::zero()))
                };
                if let Some(b) = transformed(here, min, max) {
                    let baseline = Point::zero().transform(here).y.to_pt();
                    out.push((t.text.to_string(), b, baseline));
                }
            }
            FrameItem::Shape(s, _) => {
                let r = s.bbox(true);
                if let Some(b) = transformed(here, r.min, r.max) {
                    out.push(("shape".to_owned(), b, f64::NAN));
                }
            }
            FrameItem::Image(_, size, _) => {
                if let Some(b) = transformed(here, Point::zero(), size.to_point()) {
                    out.push(("image".to_owned(), b, f64::NAN));
                }
            }
            FrameItem::Link(..) | FrameItem::Tag(_) => {}
        }
    }
}

/// The items of `doc` outside `area`, with a tolerance of 1 pt: a line's glyphs may rise a
/// little above the top edge of its box (an ascender's or an apex's overshoot over the cap
/// height typst aligns to), which is not text running past the area.
pub(crate) fn outside(doc: &PagedDocument, area: Area) -> Vec<Stray> {
    const TOLERANCE_PT: f64 = 1.0;
    let mut strays = Vec::new();
    for (n, page) in doc.pages().iter().enumerate() {
        let size = page.frame.size();
        let (w, h) = (size.x.to_pt(), size.y.to_pt());
        let (x0, y0) = (area.left_pt - TOLERANCE_PT, area.top_pt - TOLERANCE_PT);
        let (x1, y1) = (
            w - area.right_pt + TOLERANCE_PT,
            h - area.bottom_pt + TOLERANCE_PT,
        );
        let mut items = Vec::new();
        visit(&page.frame, Transform::identity(), &mut items);
        for (what, b, _) in items {
            // an empty shape (a zero-size line's box) has no extent to stray
            if b[0] < x0 || b[1] < y0 || b[2] > x1 || b[3] > y1 {
                strays.push(Stray {
                    page: n + 1,
                    what,
                    bbox_pt: b,
                });
            }
        }
    }
    strays
}

/// Each page's glyph runs in frame order; with `body`, only those whose baseline lies between
/// its top and bottom (the page's running head and foot left out).
pub(crate) fn laid_out_texts(doc: &PagedDocument, body: Option<Area>) -> Vec<String> {
    doc.pages()
        .iter()
        .map(|page| {
            let mut items = Vec::new();
            visit(&page.frame, Transform::identity(), &mut items);
            let h = page.frame.size().y.to_pt();
            let inside = |y: f64| body.is_none_or(|a| y >= a.top_pt && y <= h - a.bottom_pt);
            items
                .into_iter()
                .filter(|(_, _, baseline)| baseline.is_finite() && inside(*baseline))
                .map(|(text, _, _)| text)
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect()
}

/// Each page's glyph runs, grouped into lines by baseline (within 1 pt), lines top to
/// bottom, runs left to right.
pub(crate) fn page_texts(doc: &PagedDocument) -> Vec<String> {
    doc.pages()
        .iter()
        .map(|page| {
            let mut items = Vec::new();
            visit(&page.frame, Transform::identity(), &mut items);
            let mut runs: Vec<(f64, f64, String)> = items
                .into_iter()
                .filter(|(_, _, baseline)| baseline.is_finite())
                .map(|(text, b, baseline)| (baseline, b[0], text))
                .collect();
            runs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
            let mut lines: Vec<(f64, Vec<(f64, String)>)> = Vec::new();
            for (baseline, x, text) in runs {
                match lines.last_mut() {
                    Some((y, line)) if (baseline - *y).abs() <= 1.0 => line.push((x, text)),
                    _ => lines.push((baseline, vec![(x, text)])),
                }
            }
            lines
                .into_iter()
                .map(|(_, mut line)| {
                    line.sort_by(|a, b| a.0.total_cmp(&b.0));
                    line.into_iter()
                        .map(|(_, t)| t)
                        .collect::<Vec<_>>()
                        .join(" ")
                })
                .collect::<Vec<_>>()
                .join("\n")
        })
        .collect()
}
