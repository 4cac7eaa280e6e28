//! The study's edge: reading a study file and the recordings it names. The only module of
//! this crate that touches the file system.

use std::path::Path;

use crate::config::StudyConfig;
use crate::error::{PipelineError, Result};
use crate::inputs::Inputs;

/// Largest study file read, bytes (16 MiB): a larger file is refused before it is read.
pub const MAX_STUDY_BYTES: u64 = 16 << 20;

/// Reads a study file, validates it and loads the recordings it names from disk.
///
/// # Errors
/// [`PipelineError::Io`] if the file cannot be read, [`PipelineError::TooLarge`] above
/// [`MAX_STUDY_BYTES`], and the errors of [`parse_study`].
pub fn load_study(path: &Path) -> Result<Inputs> {
    let text = read_text(path)?;
    parse_study(&text, path)
}

/// Parses and validates study text, loading the recordings it names from disk (relative to
/// `path`'s folder); `path` names the source in errors.
pub fn parse_study(text: &str, path: &Path) -> Result<Inputs> {
    let config = StudyConfig::from_ron(text.strip_prefix('\u{feff}').unwrap_or(text), path)?;
    Inputs::new(config, path, &|file, format| {
        recording::load_recording(file, format)
    })
}

/// A text file of at most [`MAX_STUDY_BYTES`], read without reading past the limit.
fn read_text(path: &Path) -> Result<String> {
    use std::io::Read as _;
    let io = |source| PipelineError::Io {
        path: path.to_owned(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(MAX_STUDY_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > MAX_STUDY_BYTES {
        return Err(PipelineError::TooLarge {
            path: path.to_owned(),
            max_bytes: MAX_STUDY_BYTES,
        });
    }
    String::from_utf8(bytes).map_err(|e| PipelineError::NotUtf8 {
        path: path.to_owned(),
        byte: e.utf8_error().valid_up_to(),
    })
}
