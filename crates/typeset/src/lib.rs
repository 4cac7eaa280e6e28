//! Typesetting a document from a template and its data, in process: PDF/A-2b for archiving,
//! and SVG and PNG pages of the same laid-out document for a screen and for tests.
//!
//! The engine is typst, used as a library. The template is typst markup; its data is a JSON
//! file the template reads with `json("/data.json")` ([`DATA_PATH`]), so that text from a
//! user reaches the page as a string value and is never parsed as markup. The compilation
//! runs in a sandbox: it can read the template, the assets given with it (a figure as SVG
//! bytes) and the data file, and nothing else (no file system, no packages, no network); its
//! fonts are the ones typst bundles (typst-assets); it has no clock (`datetime.today()` is an
//! error), so the same template and data always give the same bytes. A compilation error of
//! the template is a [`TypesetError`] with its line and column, never a panic.
//!
//! [`Document::outside`] lists every glyph, line and image that lies outside a rectangle of
//! the page (a table running past the printable area), for tests.
//!
//! This crate computes nothing of a study and knows nothing of certificates: the report crate
//! builds the certificate's data and holds its template.

mod error;
mod layout;
mod template;
mod world;

use typst::foundations::Smart;
use typst_layout::PagedDocument;
use typst_pdf::{PdfOptions, PdfStandard, PdfStandards};

pub use error::{Diagnostic, TypesetError};
pub use layout::{Area, Stray};
pub use template::{Asset, DATA_PATH, Template};

use world::Sandbox;

/// Result of the typesetter.
pub type Result<T> = std::result::Result<T, TypesetError>;

/// A laid-out document: its pages, ready for PDF, SVG or PNG.
pub struct Document {
    document: PagedDocument,
    denied: Vec<String>,
}

impl std::fmt::Debug for Document {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Document")
            .field("pages", &self.page_count())
            .field("denied", &self.denied)
            .finish()
    }
}

/// Lays out `template` with `data_json` (the bytes the template reads at [`DATA_PATH`]).
///
/// # Errors
/// [`TypesetError::Compile`] with every error of the template (its line and column), for
/// instance data the template does not expect; [`TypesetError::AssetPath`] for an asset
/// path that is not a valid absolute path.
pub fn compile(template: &Template<'_>, data_json: &[u8]) -> Result<Document> {
    let world = Sandbox::new(template, data_json)?;
    let warned = typst::compile::<PagedDocument>(&world);
    let denied = world.denied();
    let result = warned
        .output
        .map_err(|errors| TypesetError::compile(&world, template, &errors, &denied));
    // typst memoises across compilations; a one-shot document keeps nothing
    typst::comemo::evict(0);
    Ok(Document {
        document: result?,
        denied,
    })
}

/// Lays out `template` with `data_json` and writes it as PDF/A-2b ([`Document::pdf`]).
///
/// # Errors
/// As [`compile`] and [`Document::pdf`].
pub fn render_pdf(template: &Template<'_>, data_json: &[u8]) -> Result<Vec<u8>> {
    compile(template, data_json)?.pdf()
}

impl Document {
    /// The number of pages.
    #[must_use]
    pub fn page_count(&self) -> usize {
        self.document.pages().len()
    }

    /// The paths the template asked for that the sandbox does not serve (each refused), in
    /// the order asked.
    #[must_use]
    pub fn denied(&self) -> &[String] {
        &self.denied
    }

    /// The document as PDF/A-2b (ISO 19005-2, level b): fonts embedded, an sRGB output
    /// intent, XMP metadata declaring the part and conformance, no transparency groups
    /// PDF/A forbids, no JavaScript or external actions; no creation date unless the
    /// template sets one.
    ///
    /// # Errors
    /// [`TypesetError::Pdf`] when the document cannot be written as PDF/A-2b (a character
    /// that no bundled font has, which PDF/A forbids to show as a missing glyph).
    pub fn pdf(&self) -> Result<Vec<u8>> {
        let standards = PdfStandards::new(&[PdfStandard::A_2b])
            .map_err(|e| TypesetError::Pdf(vec![Diagnostic::detached(e.message())]))?;
        let options = PdfOptions {
            ident: Smart::Auto,
            creator: Smart::Custom(None),
            timestamp: None,
            page_ranges: None,
            standards,
            tagged: true,
            pretty: false,
        };
        typst_pdf::pdf(&self.document, &options)
            .map_err(|errors| TypesetError::Pdf(errors.iter().map(Diagnostic::of).collect()))
    }

    /// Each page as an SVG document (fonts as paths, nothing fetched).
    #[must_use]
    pub fn svg_pages(&self) -> Vec<String> {
        let options = typst_svg::SvgOptions::default();
        self.document
            .pages()
            .iter()
            .map(|p| typst_svg::svg(p, &options))
            .collect()
    }

    /// Each page as a PNG image at `dpi` pixels per inch (white background).
    ///
    /// # Errors
    /// [`TypesetError::Png`] naming the page when it cannot be encoded (a page too large
    /// for the resolution asked).
    pub fn png_pages(&self, dpi: f32) -> Result<Vec<Vec<u8>>> {
        let options = typst_render::RenderOptions {
            pixel_per_pt: typst::utils::Scalar::new(f64::from(dpi) / 72.0),
            render_bleed: false,
        };
        self.document
            .pages()
            .iter()
            .enumerate()
            .map(|(n, p)| {
                typst_render::render(p, &options)
                    .encode_png()
                    .map_err(|e| TypesetError::Png {
                        page: n + 1,
                        reason: e.to_string(),
                    })
            })
            .collect()
    }

    /// The size of page `index` (0-based) in points (1/72 inch): width, height.
    #[must_use]
    pub fn page_size_pt(&self, index: usize) -> Option<(f64, f64)> {
        self.document.pages().get(index).map(|p| {
            let s = p.frame.size();
            (s.x.to_pt(), s.y.to_pt())
        })
    }

    /// Every glyph run, shape and image that reaches outside `area` on any page.
    #[must_use]
    pub fn outside(&self, area: Area) -> Vec<Stray> {
        layout::outside(&self.document, area)
    }

    /// The text of each page as laid out: its glyph runs in reading order (top to bottom,
    /// then left to right), a line per baseline, runs on one baseline separated by a space.
    #[must_use]
    pub fn page_texts(&self) -> Vec<String> {
        layout::page_texts(&self.document)
    }

    /// The text of each page in the order it was laid out (a table cell's lines together,
    /// cell after cell), its glyph runs joined by a space.
    #[must_use]
    pub fn laid_out_texts(&self) -> Vec<String> {
        layout::laid_out_texts(&self.document, None)
    }

    /// As [`Document::laid_out_texts`], of the runs whose baseline lies between the top and
    /// the bottom of `body` (the running head and foot left out, so that a table cell broken
    /// across pages reads as one text).
    #[must_use]
    pub fn body_texts(&self, body: Area) -> Vec<String> {
        layout::laid_out_texts(&self.document, Some(body))
    }
}

/// Whether one of the bundled fonts has a glyph for `c`.
#[must_use]
pub fn has_glyph(c: char) -> bool {
    world::FONTS
        .1
        .iter()
        .any(|f| f.info().coverage.contains(u32::from(c)))
}

/// `text` as a page can show it, every character visible for what it is: a control character
/// (C0, DEL, C1), a bidirectional control (U+202A–U+202E, U+2066–U+2069, U+200E, U+200F,
/// U+061C), an invisible format character (U+200B–U+200D, U+2060–U+2064, U+FEFF, U+FFF9–U+FFFB)
/// or a character no bundled font has (which PDF/A forbids to print as a missing glyph) is
/// written as `[U+XXXX]`; a line break or tab is a space. Everything else is kept as it is.
#[must_use]
pub fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    fn hidden(c: char) -> bool {
        matches!(c,
            '\u{0}'..='\u{1f}' | '\u{7f}'..='\u{9f}'
            | '\u{200b}'..='\u{200f}' | '\u{202a}'..='\u{202e}'
            | '\u{2060}'..='\u{2069}' | '\u{061c}' | '\u{feff}' | '\u{fff9}'..='\u{fffb}')
    }
    let plain = |c: char| c == ' ' || (!hidden(c) && (c.is_ascii() || has_glyph(c)));
    if text.chars().all(plain) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 16);
    for c in text.chars() {
        match c {
            '\n' | '\r' | '\t' => out.push(' '),
            c if plain(c) => out.push(c),
            c => {
                use std::fmt::Write as _;
                let _ = write!(out, "[U+{:04X}]", u32::from(c));
            }
        }
    }
    std::borrow::Cow::Owned(out)
}
