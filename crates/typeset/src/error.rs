//! The typesetter's errors: a template's compilation errors with their place, a document
//! that cannot be written as PDF/A, an image that cannot be encoded.

use std::fmt;

use typst::World;
use typst::WorldExt as _;
use typst::diag::SourceDiagnostic;

use crate::template::{DATA_PATH, Template};

/// One message of typst, with its place when it has one.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// The file it is about (the template's name, or [`DATA_PATH`]); `None` when it has no
    /// place.
    pub file: Option<String>,
    /// Line and column, 1-based, in that file.
    pub line: Option<(usize, usize)>,
    /// What typst says.
    pub message: String,
    /// Its hints.
    pub hints: Vec<String>,
}

impl Diagnostic {
    pub(crate) fn detached(message: &str) -> Self {
        Self {
            file: None,
            line: None,
            message: message.to_owned(),
            hints: Vec::new(),
        }
    }

    /// A diagnostic without its place (the PDF writer's).
    pub(crate) fn of(d: &SourceDiagnostic) -> Self {
        Self {
            file: None,
            line: None,
            message: d.message.to_string(),
            hints: d.hints.iter().map(|h| h.v.to_string()).collect(),
        }
    }

    /// A diagnostic of the compilation of `template` in `world`, with its line and column.
    fn placed(world: &dyn World, template: &Template<'_>, d: &SourceDiagnostic) -> Self {
        let mut out = Self::of(d);
        let Some(id) = d.span.id() else {
            return out;
        };
        let is_main = id == world.main();
        out.file = Some(if is_main {
            template.name.to_owned()
        } else {
            format!("{:?}", id.get()).trim_matches('"').to_owned()
        });
        if let Some(range) = world.range(d.span) {
            let text = if is_main {
                Some(template.source.to_owned())
            } else {
                world
                    .file(id)
                    .ok()
                    .and_then(|b| std::str::from_utf8(&b).ok().map(str::to_owned))
            };
            out.line = text.map(|t| {
                let before = &t[..range.start.min(t.len())];
                let line = before.matches('\n').count() + 1;
                let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
                (line, column)
            });
        }
        out
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.file, self.line) {
            (Some(file), Some((l, c))) => write!(f, "{file}:{l}:{c}: ")?,
            (Some(file), None) => write!(f, "{file}: ")?,
            _ => {}
        }
        write!(f, "{}", self.message)?;
        for h in &self.hints {
            write!(f, " (hint: {h})")?;
        }
        Ok(())
    }
}

/// The diagnostics, one a line.
struct Lines<'a>(&'a [Diagnostic]);

impl fmt::Display for Lines<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for d in self.0 {
            write!(f, "\n  {d}")?;
        }
        Ok(())
    }
}

/// What went wrong typesetting a document.
#[derive(Debug, thiserror::Error)]
pub enum TypesetError {
    /// The template did not compile with this data.
    #[error(
        "the template {template} could not be typeset{}{}", Lines(diagnostics),
        if denied.is_empty() { String::new() } else {
            format!("\n  it asked for files the typesetter does not serve: {}", denied.join(", "))
        }
    )]
    Compile {
        /// The template's name.
        template: String,
        /// Every error, with its place.
        diagnostics: Vec<Diagnostic>,
        /// The paths it asked for and was refused.
        denied: Vec<String>,
    },
    /// The laid-out document could not be written as PDF/A-2b.
    #[error("the document could not be written as PDF/A-2b{}", Lines(.0))]
    Pdf(Vec<Diagnostic>),
    /// A page could not be encoded as PNG.
    #[error("page {page} could not be encoded as PNG: {reason}")]
    Png {
        /// The page, 1-based.
        page: usize,
        /// Why.
        reason: String,
    },
    /// An asset's path is not one the typesetter can serve.
    #[error(
        "the asset path {path:?} cannot be served: {reason} (hint: an absolute path such as /figure.svg, each once, not {DATA_PATH})"
    )]
    AssetPath {
        /// The path.
        path: String,
        /// Why.
        reason: String,
    },
}

impl TypesetError {
    pub(crate) fn compile(
        world: &dyn World,
        template: &Template<'_>,
        errors: &[SourceDiagnostic],
        denied: &[String],
    ) -> Self {
        Self::Compile {
            template: template.name.to_owned(),
            diagnostics: errors
                .iter()
                .map(|d| Diagnostic::placed(world, template, d))
                .collect(),
            denied: denied.to_vec(),
        }
    }
}
