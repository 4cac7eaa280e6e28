//! What a document is typeset from: a template, the assets it may read, and where it reads
//! its data.

/// The path at which the template reads its data: `json("/data.json")`.
pub const DATA_PATH: &str = "/data.json";

/// A file the template may read besides its data (an image), at a virtual path of its own.
#[derive(Debug, Clone, Copy)]
pub struct Asset<'a> {
    /// The path the template names it by (`/residuals.svg`).
    pub path: &'a str,
    /// Its contents.
    pub bytes: &'a [u8],
}

/// A template: typst markup and the assets it may read.
#[derive(Debug, Clone, Copy)]
pub struct Template<'a> {
    /// Its name, as errors give it (`certificate.typ`).
    pub name: &'a str,
    /// Its markup.
    pub source: &'a str,
    /// The files it may read besides its data.
    pub assets: &'a [Asset<'a>],
}
