//! What the DCC is written from, as plain values: the study's results, the software, and the
//! files the study read (from `report::Provenance`, which this crate cannot depend on: the
//! report writes the DCC).

use pipeline::StudyResults;

/// The software that computed the results and wrote the certificate.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Software {
    /// Its name (`centrifuge-cal`).
    pub name: String,
    /// Its release (`0.1.0`).
    pub release: String,
    /// The source's commit, or `unknown`.
    pub commit: String,
}

/// A file the study read, as its provenance record states it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputFile {
    /// The path as the study read it.
    pub path: String,
    /// Its size in bytes.
    pub bytes: u64,
    /// SHA-256 of its contents, 64 lowercase hexadecimal digits.
    pub sha256: String,
    /// What it is to the study: `configuration`, `expected_values`, or a data file's role
    /// (`probe_recording`, `piga_table`, `piga_recording`).
    pub role: String,
    /// The configuration field naming it (`calibration.table`; none for the configuration).
    pub field: Option<String>,
}

/// Everything a DCC is written from.
#[derive(Debug, Clone, Copy)]
pub struct DccInput<'a> {
    /// The study's results; their certificate section is what the DCC states.
    pub results: &'a StudyResults,
    /// The software.
    pub software: &'a Software,
    /// The files the study read, with their digests; `None` when no provenance was
    /// recorded (the DCC says so).
    pub files: Option<&'a [InputFile]>,
}
