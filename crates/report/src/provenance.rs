//! What produced a `results.json`: the tool, its version, and the configuration, every data
//! file and the expected values, each with its size and SHA-256 as it was read — the study's
//! data source hashes each file as it reads it (`pipeline::Files`), `pipeline::load_study`
//! the configuration and [`Expected::load_recorded`](crate::Expected::load_recorded) the
//! expected values, so the record is of the bytes the numbers came from, read once.

use std::io::Read as _;
use std::path::Path;

use serde::{Deserialize, Serialize};
use sha2::{Digest as _, Sha256};

use crate::error::Result;
use pipeline::{FileDigest, Inputs};

/// The tool named in every provenance record.
pub const TOOL: &str = "centrifuge-cal";

/// The `provenance` object of `results.json` (see `docs/RESULTS.md`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Provenance {
    /// Always [`TOOL`].
    pub tool: String,
    /// The tool's version (the workspace version).
    pub version: String,
    /// The study configuration, with its path as the tool was given it.
    pub config: FileRecord,
    /// The lab profile the study named (`docs/PROFILE.md`), with its path as read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub profile: Option<FileRecord>,
    /// The expected-values file whose published values the report shows, if any.
    pub expected: Option<FileRecord>,
    /// Every data file the study read, in the configuration's order: the phases' probe
    /// recordings, then the calibration's PIGA table or raw PIGA output recordings; each with
    /// its path as the study read it (the configuration's folder joined with the path the
    /// configuration gives), its role and the configuration field naming it.
    pub inputs: Vec<FileRecord>,
}

/// A file as it was when a study read it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileRecord {
    /// The path.
    pub path: String,
    /// Its size in bytes.
    pub bytes: u64,
    /// SHA-256 of its contents, 64 lowercase hexadecimal digits.
    pub sha256: String,
    /// What the file is to the study (`probe_recording`, `piga_table`, `piga_recording`;
    /// data files only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub role: Option<String>,
    /// The configuration field naming it (`calibration.recordings.files[3]`; data files
    /// only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub field: Option<String>,
}

impl FileRecord {
    /// Reads the file at `path` once, in blocks, for its size and SHA-256.
    ///
    /// # Errors
    /// [`ReportError::File`](crate::ReportError::File) naming `path` when it cannot be read.
    pub fn of(path: &Path) -> Result<Self> {
        let read_error = |source| edge_io::EdgeIoError::Read {
            path: path.to_owned(),
            source,
        };
        let mut file = std::fs::File::open(path).map_err(read_error)?;
        let mut hasher = Sha256::new();
        let mut buffer = vec![0_u8; 1 << 16];
        let mut bytes = 0_u64;
        loop {
            let n = match file.read(&mut buffer) {
                Ok(0) => break,
                Ok(n) => n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(read_error(e).into()),
            };
            hasher.update(&buffer[..n]);
            bytes += n as u64;
        }
        Ok(Self {
            path: path.display().to_string(),
            bytes,
            sha256: hex(&hasher.finalize()),
            role: None,
            field: None,
        })
    }

    /// The record of the file at `path` from the size and SHA-256 taken as it was read.
    #[must_use]
    pub fn read(path: &Path, digest: &FileDigest) -> Self {
        Self {
            path: path.display().to_string(),
            bytes: digest.bytes,
            sha256: digest.sha256.clone(),
            role: None,
            field: None,
        }
    }

    /// [`FileRecord::read`] when the digest was kept as the file was read; otherwise (a
    /// study whose data source keeps no digest, such as data held in memory) the file at
    /// `path` is read here.
    fn kept_or_read(path: &Path, digest: Option<&FileDigest>) -> Result<Self> {
        digest.map_or_else(|| Self::of(path), |d| Ok(Self::read(path, d)))
    }
}

impl Provenance {
    /// The provenance of a study run from `study`: its configuration file and every data
    /// file it read ([`Inputs::input_files`]), with the sizes and digests taken as they were
    /// read, and the record of the expected-values file if the report shows one
    /// ([`Expected::load_recorded`](crate::Expected::load_recorded)).
    ///
    /// Nothing is read again when the study was loaded from files
    /// ([`pipeline::load_study`]); only a file whose digest the study's data source did not
    /// keep (data held in memory) is read here.
    ///
    /// # Errors
    /// [`ReportError::File`](crate::ReportError::File) naming a file that must be read here
    /// and cannot be.
    pub fn of_study(study: &Inputs, expected: Option<&FileRecord>) -> Result<Self> {
        Ok(Self {
            tool: TOOL.to_owned(),
            version: env!("CARGO_PKG_VERSION").to_owned(),
            config: FileRecord::kept_or_read(study.source(), study.config_digest())?,
            profile: study
                .profile_file()
                .map(|(path, digest)| FileRecord::kept_or_read(path, digest))
                .transpose()?,
            expected: expected.cloned(),
            inputs: study
                .input_files()
                .into_iter()
                .map(|f| {
                    Ok(FileRecord {
                        role: Some(f.role.code().to_owned()),
                        field: Some(f.field),
                        ..FileRecord::kept_or_read(f.path, f.digest)?
                    })
                })
                .collect::<Result<_>>()?,
        })
    }
}

/// The software that produced a certificate.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Software {
    /// Name and version (`centrifuge-cal 0.1.0`).
    pub version: String,
    /// The source's commit, or `unknown`.
    pub commit: String,
}

impl Software {
    /// This build: the workspace version and the commit it was built from (the build
    /// environment's `CENTRIFUGE_CAL_COMMIT`, else `unknown`).
    pub fn this_build() -> Self {
        Self {
            version: format!("{} {}", crate::TOOL, env!("CARGO_PKG_VERSION")),
            commit: option_env!("CENTRIFUGE_CAL_COMMIT")
                .unwrap_or("unknown")
                .to_owned(),
        }
    }
}

/// Lowercase hexadecimal digits of `bytes`.
fn hex(bytes: &[u8]) -> String {
    use std::fmt::Write as _;
    bytes
        .iter()
        .fold(String::with_capacity(2 * bytes.len()), |mut s, b| {
            // writing to a String cannot fail
            let _ = write!(s, "{b:02x}");
            s
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sha256_of_a_known_text() {
        let path = std::env::temp_dir().join(format!("report-sha-{}.txt", std::process::id()));
        std::fs::write(&path, "abc").unwrap();
        let record = FileRecord::of(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(record.path, path.display().to_string());
        assert_eq!(record.bytes, 3);
        // FIPS 180-2, appendix B.1
        assert_eq!(
            record.sha256,
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }
}
