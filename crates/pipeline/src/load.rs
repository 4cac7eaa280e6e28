//! The study's edge: reading a study file and the recordings it names. The only module of
//! this crate that touches the file system.

use std::path::Path;

use crate::config::StudyConfig;
use crate::error::Result;
use crate::inputs::{DataSource, Loaded};
use crate::profile::Profile;
use crate::study::Inputs;

/// The data files of a study, read from disk.
#[derive(Debug, Clone, Copy, Default)]
pub struct Files;

impl DataSource for Files {
    fn recording(
        &self,
        path: &Path,
        format: &recording::RecordingFormat,
    ) -> std::result::Result<recording::Recording, recording::RecordingError> {
        recording::load_recording(path, format)
    }

    fn table(
        &self,
        path: &Path,
        format: &recording::TableFormat,
    ) -> std::result::Result<recording::Table, recording::RecordingError> {
        recording::load_table(path, format)
    }

    /// Reads the file once, hashing its bytes as they are read.
    fn read_recording(
        &self,
        path: &Path,
        format: &recording::RecordingFormat,
    ) -> std::result::Result<Loaded<recording::Recording>, recording::RecordingError> {
        let (value, digest) = recording::load_recording_digested(path, format)?;
        Ok(Loaded {
            value,
            digest: Some(digest),
        })
    }

    /// Reads the file once, hashing its bytes as they are read.
    fn read_table(
        &self,
        path: &Path,
        format: &recording::TableFormat,
    ) -> std::result::Result<Loaded<recording::Table>, recording::RecordingError> {
        let (value, digest) = recording::load_table_digested(path, format)?;
        Ok(Loaded {
            value,
            digest: Some(digest),
        })
    }

    /// Reads the file once, hashing its bytes as they are read.
    fn read_piga_recording(
        &self,
        path: &Path,
        format: &recording::PigaRecordingFormat,
    ) -> std::result::Result<Loaded<recording::PigaRecording>, recording::RecordingError> {
        let (value, digest) = recording::load_piga_recording_digested(path, format)?;
        Ok(Loaded {
            value,
            digest: Some(digest),
        })
    }
}

/// Largest study file read, bytes (16 MiB): a larger file is refused before it is read.
pub const MAX_STUDY_BYTES: u64 = edge_io::CONFIG_MAX_BYTES;

/// Reads a study file, validates it and loads the data files it names from disk, keeping
/// the size and SHA-256 of every file as it was read (the configuration's too:
/// [`Inputs::config_digest`], [`Inputs::input_files`]; and its lab profile's:
/// [`Inputs::profile_file`]).
///
/// # Errors
/// [`PipelineError::File`](crate::PipelineError::File) if the file cannot be read, is above [`MAX_STUDY_BYTES`] or is not
/// UTF-8, and the errors of [`parse_study`].
pub fn load_study(path: &Path) -> Result<Inputs> {
    let bytes = edge_io::read_bytes_capped(path, MAX_STUDY_BYTES)?;
    let digest = recording::FileDigest::of(&bytes);
    let text = edge_io::text_from_bytes(path, bytes)?;
    Ok(parse_study(&text, path)?.with_config_digest(digest))
}

/// Parses and validates study text, loading the lab profile it names and the recordings it
/// names from disk (relative to `path`'s folder); `path` names the source in errors.
pub fn parse_study(text: &str, path: &Path) -> Result<Inputs> {
    let config = StudyConfig::from_ron(text.strip_prefix('\u{feff}').unwrap_or(text), path)?;
    let profile = load_profile(&config, path)?;
    Inputs::with_profile(config, profile.as_ref(), path, &Files)
}

/// The lab profile a study names (`profile: "lab.ron"`, relative to the study file `path`'s
/// folder), read with the study's size cap and RON dialect and kept with its size and
/// SHA-256; `None` when the study names none. Not validated here: [`Inputs::with_profile`]
/// validates it.
///
/// # Errors
/// [`PipelineError::File`](crate::PipelineError::File) if the file cannot be read, is too
/// large or is not UTF-8; [`PipelineError::Parse`](crate::PipelineError::Parse) naming the
/// profile's line and column.
pub fn load_profile(config: &StudyConfig, path: &Path) -> Result<Option<Profile>> {
    let Some(named) = &config.profile else {
        return Ok(None);
    };
    let file = path.parent().unwrap_or_else(|| Path::new(".")).join(named);
    let bytes = edge_io::read_bytes_capped(&file, MAX_STUDY_BYTES)?;
    let digest = recording::FileDigest::of(&bytes);
    let text = edge_io::text_from_bytes(&file, bytes)?;
    Ok(Some(Profile::from_ron(&text, &file)?.with_digest(digest)))
}
