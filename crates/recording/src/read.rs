//! A probe recording from a file, whichever its kind: delimited text through the table
//! parser, `.tdms` and `.mat` through the binary readers. Above both `lab` and `binary`, so
//! neither needs the other.

use std::path::Path;

use crate::digest::FileDigest;
use crate::error::{RecordingError, Result};
use crate::lab::format::RecordingFormat;
use crate::lab::probe::Recording;
use crate::text::parser::{load_table, parse_table};

/// Reads a probe recording from a file, streaming it through one reused buffer of about a
/// megabyte (see [`load_table`](crate::load_table); a line longer than 16 MiB is
/// [`RecordingError::LineTooLong`]). The samples' lines are kept in a compact row → line
/// table ([`Recording::line_of_sample`]).
///
/// A `.tdms` or `.mat` file is read by the TDMS or MAT reader with the format's names and
/// units ([`crate::load_tdms`], [`crate::load_mat`]; its `group` and `waveform_time`;
/// delimiter, decimal mark and skipped lines do not apply).
pub fn load_recording(path: &Path, format: &RecordingFormat) -> Result<Recording> {
    if let Some(kind) = crate::binary::format_of(path) {
        return crate::binary::with_source(path, |source| {
            crate::binary::read_with_format(path, source, kind, format)
        });
    }
    text_only(path, format)?;
    let table = load_table(path, &format.table_format()?)?;
    Recording::from_table(table, format)
}

/// [`load_recording`], with the size and SHA-256 of the bytes it read, taken as it read them
/// (a text file is read once; a TDMS or MAT file is parsed from the open file by positioned
/// reads, then the same open file is hashed piece by piece, so memory stays bounded by the
/// samples and a file without the format's signature is refused before it is hashed).
pub fn load_recording_digested(
    path: &Path,
    format: &RecordingFormat,
) -> Result<(Recording, FileDigest)> {
    if let Some(kind) = crate::binary::format_of(path) {
        return crate::binary::with_source(path, |source| {
            let rec = crate::binary::read_with_format(path, source, kind, format)?;
            Ok((rec, source.digest()?))
        });
    }
    text_only(path, format)?;
    let (table, digest) = crate::text::parser::load_table_digested(path, &format.table_format()?)?;
    Ok((Recording::from_table(table, format)?, digest))
}

/// Parses a probe recording held in memory; `path` names it in errors, and its extension
/// chooses the reader as for [`load_recording`].
pub fn parse_recording(text: &[u8], path: &Path, format: &RecordingFormat) -> Result<Recording> {
    if let Some(kind) = crate::binary::format_of(path) {
        return crate::binary::read_with_format(
            path,
            &crate::binary::Source::Bytes(text),
            kind,
            format,
        );
    }
    text_only(path, format)?;
    let table = parse_table(text, path, &format.table_format()?)?;
    Recording::from_table(table, format)
}

/// Refuses the settings of binary files for a text file.
pub(crate) fn text_only(path: &Path, format: &RecordingFormat) -> Result<()> {
    let binary_only = [
        ("group", format.group.is_some(), "TDMS and MAT files"),
        ("waveform_time", format.waveform_time, "TDMS files"),
    ];
    for (setting, given, applies_to) in binary_only {
        if given {
            return Err(RecordingError::SettingNotForFile {
                path: path.to_path_buf(),
                setting,
                applies_to,
            });
        }
    }
    Ok(())
}
