//! The certificate's data as the template reads it (`/data.json`): every number already
//! written as a person reads it (rounded to its uncertainty, powers of ten as `× 10⁻⁶`), every
//! sentence in the reader's words. The template lays it out and adds no number of its own.
//!
//! Strings that come from the study file or the input files (names, addresses, serial
//! numbers, file paths) are data: the template shows them as text and never evaluates them;
//! every string is made [`typeset::printable`] before it is serialised.

use serde::Serialize;

/// Text as the page shows it: a plain string (written as one JSON string), or runs of
/// plain, subscript, code and bold text (an array of one-key objects: `{"t": …}`,
/// `{"sub": …}`, `{"code": …}`, `{"b": …}`). Every run is shown as the text it holds.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(untagged)]
pub enum Text {
    /// One plain run.
    Plain(String),
    /// Runs.
    Runs(Vec<Run>),
}

/// A run of text.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub enum Run {
    /// Plain.
    #[serde(rename = "t")]
    Plain(String),
    /// A subscript (`r` of C_r).
    #[serde(rename = "sub")]
    Sub(String),
    /// A name set as code.
    #[serde(rename = "code")]
    Code(String),
    /// Bold.
    #[serde(rename = "b")]
    Bold(String),
    /// A note in small type on a line of its own.
    #[serde(rename = "note")]
    Note(String),
}

/// The whole certificate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CertificateData {
    /// The certificate's identification.
    pub id: String,
    /// The date of issue as a calendar date, the PDF's document date (PDF/A requires one);
    /// absent when the study states it otherwise than as ISO 8601 (`2026-11-24`).
    pub issued: Option<CalendarDate>,
    /// The head and foot of every page.
    pub running: Running,
    /// The issuing laboratory.
    pub laboratory: Laboratory,
    /// The identification table: label and value.
    pub identification: Vec<Field>,
    /// The item's serial number (shown in bold in the identification).
    pub serial: String,
    /// What is certified: the method, why, and where the coefficients hold.
    pub certified: Certified,
    /// The certified coefficients.
    pub results: Table,
    /// The notes under the results: what U, k and ν_eff are, what the relative values use.
    pub results_notes: Vec<Text>,
    /// The compensation of the probe method (C_r and Δk2), when the probe method is
    /// certified.
    pub compensation: Option<Table>,
    /// The probe's sign convention, in words.
    pub sign_convention: Option<Text>,
    /// The other method's check.
    pub check: Option<Check>,
    /// The statements of conformity.
    pub conformity: Option<Conformity>,
    /// That the results relate only to the item calibrated.
    pub scope: String,
    /// Who authorises the certificate.
    pub authorisation: Authorisation,
    /// The method in paragraphs, departures from the procedure, and the references.
    pub method: Method,
    /// Environmental conditions: quantity and value.
    pub conditions: Vec<Field>,
    /// The equipment.
    pub equipment: Table,
    /// The traceability of each Type B input.
    pub traceability: Table,
    /// The uncertainty budget of the certified k2.
    pub budget: Budget,
    /// The residual figure's caption (the figure is the asset `/residuals.svg`).
    pub figure_caption: Text,
    /// GUM against Monte Carlo.
    pub gum_against_mc: Section,
    /// The data used: paragraphs, the recordings' table, the warnings.
    pub data_used: DataUsed,
    /// The input files with their SHA-256 and the software.
    pub files: Files,
    /// The marked end.
    pub end: String,
}

/// A calendar date.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct CalendarDate {
    /// The year.
    pub year: i32,
    /// The month, 1 to 12.
    pub month: u8,
    /// The day, 1 to 31.
    pub day: u8,
}

/// The running head and foot.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Running {
    /// Top left: the laboratory.
    pub left: String,
    /// Top right: `Certificate <id>`.
    pub right: String,
    /// Bottom left: the item.
    pub foot: String,
}

/// The laboratory.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Laboratory {
    /// Name.
    pub name: String,
    /// Address.
    pub address: String,
    /// Accreditation, when stated.
    pub accreditation: Option<String>,
}

/// A label and its value.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Field {
    /// The label (the tool's words, or a condition's quantity).
    pub label: String,
    /// The value.
    pub value: String,
}

/// A table: its column headings and rows of cells; `numeric` marks the columns set right.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Table {
    /// Column headings.
    pub columns: Vec<Text>,
    /// Which columns hold numbers (set right).
    pub numeric: Vec<bool>,
    /// Relative widths of the columns (fractions of the text width).
    pub widths: Vec<u32>,
    /// The rows.
    pub rows: Vec<Vec<Text>>,
}

/// What is certified.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Certified {
    /// The method's name: `probe method` or `two-orientation method`.
    pub method: String,
    /// One sentence: which method's values are certified, on which mounting(s).
    pub statement: Text,
    /// Why this method.
    pub reason: Text,
    /// The model of the output the coefficients belong to.
    pub model: Text,
    /// The marked statement when the certified value is one the study's own check refutes.
    pub refuted: Option<Text>,
    /// The validity range: one row per mounting used in the fit.
    pub validity: Table,
}

/// The check by the other method.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Check {
    /// Its heading.
    pub heading: String,
    /// What the check does, in words.
    pub intro: Text,
    /// Its quantities.
    pub table: Table,
    /// The verdict in words.
    pub verdict: Text,
    /// Whether the methods disagree (the verdict is marked).
    pub disagrees: bool,
}

/// The statements of conformity.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Conformity {
    /// The decision rule in words.
    pub rule: Text,
    /// One row per limit.
    pub table: Table,
    /// The verdict of each row: `pass`, `conditional`, `fail` (for its colour).
    pub verdicts: Vec<String>,
}

/// Who authorises the certificate.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Authorisation {
    /// Name.
    pub name: String,
    /// Role.
    pub role: String,
    /// Date of issue.
    pub date: String,
}

/// The method.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Method {
    /// Paragraphs.
    pub paragraphs: Vec<Text>,
    /// Departures from the procedure, as stated.
    pub deviations: Option<String>,
    /// The references.
    pub references: Vec<Text>,
}

/// The uncertainty budget.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Budget {
    /// Its heading.
    pub heading: String,
    /// The inputs.
    pub table: Table,
    /// The combined standard uncertainty and effective degrees of freedom, as the last
    /// row's cells: label, u, share, ν.
    pub total: Vec<Text>,
}

/// A heading, a paragraph and a table.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Section {
    /// The heading.
    pub heading: String,
    /// The paragraph.
    pub intro: Text,
    /// The table.
    pub table: Table,
}

/// The data used.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct DataUsed {
    /// Paragraphs.
    pub paragraphs: Vec<Text>,
    /// The raw recordings, one row each (absent for a table).
    pub recordings: Option<Table>,
    /// The warnings raised by the evaluation.
    pub warnings: Vec<Text>,
}

/// The input files and the software.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Files {
    /// Said when the files were not recorded.
    pub missing: Option<Text>,
    /// One row per file: what, path, bytes, SHA-256.
    pub table: Option<Table>,
    /// The software's version.
    pub software: String,
    /// The commit it was built from.
    pub commit: String,
}
