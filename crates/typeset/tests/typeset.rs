//! The typesetter on small templates: data enters as data, the sandbox serves nothing but the
//! template, its assets and the data, a template error is a typed error with its place, the
//! PDF declares PDF/A-2b, the PNG and SVG pages are the same document's, and a line running
//! past the page's margin is found.

use typeset::{Area, Asset, Template, TypesetError};

const PAGE: &str = r#"#set page(paper: "a4", margin: 20mm)
#set document(title: "test", date: datetime(year: 2026, month: 1, day: 2))
#set text(font: "Libertinus Serif", size: 10pt)
#let data = json("/data.json")
"#;

fn template(body: &str) -> String {
    format!("{PAGE}{body}")
}

fn compile(body: &str, data: &str) -> typeset::Result<typeset::Document> {
    let source = template(body);
    typeset::compile(
        &Template {
            name: "test.typ",
            source: &source,
            assets: &[],
        },
        data.as_bytes(),
    )
}

#[test]
fn text_from_the_data_is_shown_as_written_never_run() {
    let hostile = r##"#read("/etc/passwd") $x$ *bold* ] \ `raw` <label> @ref"##;
    let data = serde_json::json!({ "name": hostile }).to_string();
    let doc = compile("Name: #data.name", &data).unwrap();
    let text = doc.page_texts().join("\n");
    assert!(text.contains(hostile), "{text}");
    // nothing was read: the markup in the data was never evaluated
    assert!(doc.denied().is_empty(), "{:?}", doc.denied());
}

#[test]
fn the_sandbox_serves_no_file_of_the_machine() {
    for call in [
        r#"#read("/etc/passwd")"#,
        r#"#read("../../../../etc/passwd")"#,
        r#"#image("/etc/hostname")"#,
        r#"#import "@preview/example:0.1.0": *"#,
    ] {
        let err = compile(call, "{}").unwrap_err();
        let TypesetError::Compile {
            template,
            diagnostics,
            ..
        } = &err
        else {
            panic!("{call}: {err}");
        };
        assert_eq!(template, "test.typ");
        // the error names the line of the template (after the 4 lines of PAGE)
        assert_eq!(diagnostics[0].line.map(|l| l.0), Some(5), "{call}: {err}");
        assert!(err.to_string().contains("test.typ:5:"), "{err}");
    }
}

#[test]
fn an_asset_is_served_at_its_path_and_only_it() {
    let svg = br#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="50"><rect width="100" height="50" fill="blue"/></svg>"#;
    let source = template(r#"#image("/figure.svg", width: 50mm)"#);
    let assets = [Asset {
        path: "/figure.svg",
        bytes: svg,
    }];
    let doc = typeset::compile(
        &Template {
            name: "test.typ",
            source: &source,
            assets: &assets,
        },
        b"{}",
    )
    .unwrap();
    assert!(doc.denied().is_empty());
    assert_eq!(doc.page_count(), 1);
    // an asset path outside the project's root is refused up front
    let bad = [Asset {
        path: "../x.svg",
        bytes: svg,
    }];
    let err = typeset::compile(
        &Template {
            name: "test.typ",
            source: &source,
            assets: &bad,
        },
        b"{}",
    );
    assert!(
        matches!(
            err,
            Err(TypesetError::AssetPath { .. }) | Err(TypesetError::Compile { .. })
        ),
        "{err:?}"
    );
}

#[test]
fn a_template_error_is_typed_with_its_place() {
    let err = compile("#let x = \n#data.missing.field", "{}").unwrap_err();
    let text = err.to_string();
    assert!(
        text.starts_with("the template test.typ could not be typeset"),
        "{text}"
    );
    assert!(text.contains("test.typ:"), "{text}");
    // data that is not JSON: the error is about the data file
    let err = compile("#data", "{not json").unwrap_err();
    assert!(err.to_string().contains("json"), "{err}");
}

#[test]
fn the_clock_is_not_read() {
    let err = compile("#datetime.today().display()", "{}").unwrap_err();
    assert!(matches!(err, TypesetError::Compile { .. }), "{err}");
}

#[test]
fn the_pdf_declares_pdf_a_2b_and_the_pages_render() {
    let doc = compile(
        "= Heading\nSome text, µg/g², ν#sub[eff], 10⁻⁶, ±, ×, −.",
        "{}",
    )
    .unwrap();
    let pdf = doc.pdf().unwrap();
    assert!(pdf.starts_with(b"%PDF-1.7"), "{:?}", &pdf[..8]);
    let text = String::from_utf8_lossy(&pdf);
    assert!(
        text.contains("<pdfaid:part>2</pdfaid:part>"),
        "no PDF/A part in the XMP"
    );
    assert!(text.contains("<pdfaid:conformance>B</pdfaid:conformance>"));
    // the same bytes every time: no clock, no random identifier
    assert_eq!(pdf, doc.pdf().unwrap());
    let png = doc.png_pages(36.0).unwrap();
    assert_eq!(png.len(), 1);
    assert!(png[0].starts_with(b"\x89PNG\r\n\x1a\n"));
    let svg = doc.svg_pages();
    assert_eq!(svg.len(), 1);
    assert!(svg[0].starts_with("<svg"));
    // A4 in points
    let (w, h) = doc.page_size_pt(0).unwrap();
    assert!(
        (w - 595.28).abs() < 0.01 && (h - 841.89).abs() < 0.01,
        "{w} × {h}"
    );
}

#[test]
fn a_line_past_the_margin_is_found() {
    let inside = compile("A short line.", "{}").unwrap();
    let strays = inside.outside(Area::inset_mm(20.0, 20.0, 20.0, 20.0));
    assert!(strays.is_empty(), "{strays:?}");
    // an unbreakable run wider than the text area
    let wide = compile("#box(width: 400mm)[Wide]", "{}").unwrap();
    let _ = wide;
    let long = "W".repeat(200);
    let doc = compile(&format!("Start {long}"), "{}").unwrap();
    let strays = doc.outside(Area::inset_mm(20.0, 20.0, 20.0, 20.0));
    assert!(strays.iter().any(|s| s.what.contains("WWWW")), "{strays:?}");
}
