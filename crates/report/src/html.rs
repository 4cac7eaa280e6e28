//! The HTML pieces of the certificate: its style sheet, the `@page` rule that puts the
//! certificate id and "Page x of y" on every printed page, CSS strings, an inline SVG that
//! scales to its box, and a table row.

use std::fmt::Write as _;

use pipeline::CertificateResults;

use crate::format::esc;

/// A CSS string literal holding `text`.
pub(crate) fn css_string(text: &str) -> String {
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' | '\\' => {
                out.push('\\');
                out.push(c);
            }
            '\n' | '\r' => out.push(' '),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// An SVG document made to scale to its container's width.
pub(crate) fn inline_svg(svg: &str) -> String {
    // plotters writes `<svg width="W" height="H" viewBox="0 0 W H" …>`; the width and
    // height are dropped so that CSS sizes it, the viewBox keeps its aspect.
    let svg = svg
        .trim_start_matches(|c| c != '<')
        .trim_start_matches("<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
        .trim_start();
    let Some(end) = svg.find('>') else {
        return svg.to_owned();
    };
    let (open, rest) = svg.split_at(end);
    let mut attrs = String::new();
    let mut width = None;
    let mut height = None;
    for part in open.trim_start_matches("<svg").split_whitespace() {
        if let Some(w) = part.strip_prefix("width=\"") {
            width = Some(w.trim_end_matches('"').to_owned());
        } else if let Some(h) = part.strip_prefix("height=\"") {
            height = Some(h.trim_end_matches('"').to_owned());
        } else {
            attrs.push(' ');
            attrs.push_str(part);
        }
    }
    if !attrs.contains("viewBox")
        && let (Some(w), Some(h)) = (width, height)
    {
        let _ = write!(attrs, " viewBox=\"0 0 {w} {h}\"");
    }
    format!("<svg class=\"figure\"{attrs}{rest}")
}

pub(crate) const STYLE: &str = r#"
* { box-sizing: border-box; }
html { font-family: "DejaVu Sans", "Liberation Sans", Arial, sans-serif; font-size: 9.5pt; color: #111; }
body { margin: 0; }
h1 { font-size: 17pt; margin: 0 0 1mm 0; }
h2 { font-size: 11.5pt; margin: 6mm 0 2mm 0; border-bottom: 0.4pt solid #444; padding-bottom: 0.8mm; break-after: avoid; }
h3 { font-size: 10pt; margin: 4mm 0 1.5mm 0; break-after: avoid; }
p { margin: 1.2mm 0; line-height: 1.35; }
table { border-collapse: collapse; width: 100%; margin: 1.5mm 0 2mm 0; break-inside: auto; }
tr { break-inside: avoid; }
th, td { border: 0.4pt solid #999; padding: 0.9mm 1.4mm; text-align: left; vertical-align: top; }
th { background: #eef0f3; font-weight: 600; }
td.num, th.num { text-align: right; white-space: nowrap; font-variant-numeric: tabular-nums; }
table.ident th { width: 38mm; }
.masthead { display: flex; justify-content: space-between; align-items: flex-start; border-bottom: 1.2pt solid #111; padding-bottom: 2mm; margin-bottom: 3mm; }
.masthead .lab { text-align: right; font-size: 9pt; }
.id { font-size: 11pt; font-weight: 700; }
.note { font-size: 8.5pt; color: #333; }
.warning { border-left: 2pt solid #b35900; padding-left: 2mm; margin: 1.2mm 0; font-size: 8.5pt; }
.verdict-pass { color: #0a5d1a; font-weight: 700; }
.verdict-conditional { color: #8a5a00; font-weight: 700; }
.verdict-fail { color: #a00; font-weight: 700; }
.hash { font-family: "DejaVu Sans Mono", "Liberation Mono", monospace; font-size: 6.6pt; white-space: nowrap; }
td.path { word-break: break-all; font-size: 8pt; }
svg.figure { width: 100%; height: auto; display: block; break-inside: avoid; }
.figure-box { break-inside: avoid; margin: 2mm 0; }
.signature { margin-top: 8mm; display: flex; gap: 12mm; }
.signature div { flex: 1; border-top: 0.4pt solid #111; padding-top: 1mm; font-size: 8.5pt; }
.details { break-before: page; }
code { font-family: "DejaVu Sans Mono", "Liberation Mono", monospace; font-size: 0.92em; }
section.check, .closing { break-inside: avoid; }
td.unit, th.unit, td.nowrap { white-space: nowrap; }
table.budget td:first-child { min-width: 38mm; }
table.check td:first-child { min-width: 68mm; }
.end { text-align: center; margin-top: 6mm; font-weight: 700; letter-spacing: 0.05em; }
"#;

/// The `@page` rule: A4, the laboratory and certificate id at the top of every page, "page x
/// of y" at the bottom.
pub(crate) fn page_style(info: &CertificateResults) -> String {
    format!(
        "@page {{ size: A4; margin: 20mm 16mm 18mm 16mm;\n  \
         @top-left {{ content: {lab}; font-size: 8pt; color: #444; }}\n  \
         @top-right {{ content: {id}; font-size: 8pt; font-weight: 700; }}\n  \
         @bottom-left {{ content: {title}; font-size: 8pt; color: #444; }}\n  \
         @bottom-right {{ content: \"Page \" counter(page) \" of \" counter(pages); font-size: 8pt; }}\n}}\n",
        lab = css_string(&info.laboratory.name),
        id = css_string(&format!("Certificate {}", info.id)),
        title = css_string(&format!(
            "{} {} serial {}",
            info.item.manufacturer, info.item.model, info.item.serial
        )),
    )
}

/// Escaped text with the symbols a person reads: `C_r` and `C_a` with their subscripts, and
/// a configuration name between backticks (`` `lever.probe_direction` ``) set as code.
pub(crate) fn symbols(text: &str) -> String {
    let escaped = esc(text)
        .replace("C_r", "C<sub>r</sub>")
        .replace("C_a", "C<sub>a</sub>");
    let mut out = String::with_capacity(escaped.len());
    let mut parts = escaped.split('`');
    if let Some(first) = parts.next() {
        out.push_str(first);
    }
    let rest: Vec<&str> = parts.collect();
    if rest.len().is_multiple_of(2) {
        // an even number of backticks: every other part is a name
        for (n, part) in rest.iter().enumerate() {
            if n.is_multiple_of(2) {
                let _ = write!(out, "<code>{part}</code>");
            } else {
                out.push_str(part);
            }
        }
    } else {
        for part in rest {
            out.push('`');
            out.push_str(part);
        }
    }
    out
}

pub(crate) fn row(out: &mut String, th: &str, td: &str) {
    let _ = writeln!(out, "<tr><th>{}</th><td>{}</td></tr>", esc(th), td);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_escaped() {
        assert_eq!(esc("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
        assert_eq!(css_string("Lab \"A\" \\ B"), "\"Lab \\\"A\\\" \\\\ B\"");
    }

    #[test]
    fn symbols_are_set_for_a_reader() {
        assert_eq!(
            symbols("C_r of phase `spindle` & C_a"),
            "C<sub>r</sub> of phase <code>spindle</code> &amp; C<sub>a</sub>"
        );
        // an unbalanced backtick is left as it is
        assert_eq!(symbols("a ` b"), "a ` b");
        assert_eq!(symbols("`a` and `b`"), "<code>a</code> and <code>b</code>");
    }

    #[test]
    fn an_svg_scales_to_its_box() {
        let svg = "<svg width=\"800\" height=\"480\" xmlns=\"http://www.w3.org/2000/svg\">\n<rect/></svg>";
        let inline = inline_svg(svg);
        assert!(
            inline.starts_with("<svg class=\"figure\" xmlns="),
            "{inline}"
        );
        assert!(inline.contains("viewBox=\"0 0 800 480\""), "{inline}");
        assert!(!inline.contains("width=\"800\""));
    }
}
