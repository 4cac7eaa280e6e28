//! What produced a `results.json`: the tool, its version, and the configuration and input
//! files with their sizes and SHA-256 digests.

use std::io::Read as _;
use std::path::Path;

use serde::Serialize;
use sha2::{Digest as _, Sha256};

use crate::error::Result;
use pipeline::Inputs;

/// The tool named in every provenance record.
pub const TOOL: &str = "centrifuge-cal";

/// The `provenance` object of `results.json` (see `docs/RESULTS.md`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Provenance {
    /// Always [`TOOL`].
    pub tool: String,
    /// The tool's version (the workspace version).
    pub version: String,
    /// The study configuration, with its path as the tool was given it.
    pub config: FileRecord,
    /// The expected-values file whose published values the report shows, if any.
    pub expected: Option<FileRecord>,
    /// The input files the study read (probe recordings), in the configuration's order
    /// (pre-balance, then post-balance), each with its path as the study read it: the
    /// configuration's folder joined with the path the configuration gives.
    pub inputs: Vec<FileRecord>,
}

/// A file as it was when a study read it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct FileRecord {
    /// The path.
    pub path: String,
    /// Its size in bytes.
    pub bytes: u64,
    /// SHA-256 of its contents, 64 lowercase hexadecimal digits.
    pub sha256: String,
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
        })
    }
}

impl Provenance {
    /// The provenance of a study run from `study` (its configuration file and the recordings
    /// it read), with the expected-values file at `expected` if the report shows one.
    ///
    /// # Errors
    /// [`ReportError::File`](crate::ReportError::File) naming a file that cannot be read.
    pub fn of_study(study: &Inputs, expected: Option<&Path>) -> Result<Self> {
        Ok(Self {
            tool: TOOL.to_owned(),
            version: env!("CARGO_PKG_VERSION").to_owned(),
            config: FileRecord::of(study.source())?,
            expected: expected.map(FileRecord::of).transpose()?,
            inputs: study
                .recording_files()
                .map(FileRecord::of)
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
