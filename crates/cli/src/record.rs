//! `centrifuge-cal record`: a study's outputs (results.json, certificate.dcc.xml,
//! certificate.pdf) into the records database, or a balancing of a centrifuge; and the one
//! place the command line finds the records database (`--records`, else the documented
//! default). `study --records FILE` records through [`record_dir`].

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use clap::Args;
use records::{Access, BalanceOutcome, Database, Date, InputFile, Outcome, Submission};
use serde::Deserialize;

use crate::console::Console;

/// Largest results.json read (a study's is well under a megabyte).
const RESULTS_MAX_BYTES: u64 = 64 << 20;
/// Largest certificate file read (a DCC or a PDF).
const CERTIFICATE_MAX_BYTES: u64 = 64 << 20;

/// Test hook: when set, a recording writes this file and waits before committing (the
/// tests kill it there and check that the database is as it was).
const PAUSE_BEFORE_COMMIT: &str = "CENTRIFUGE_CAL_TEST_PAUSE_BEFORE_COMMIT";

/// Arguments of `centrifuge-cal record`.
#[derive(Debug, Args)]
pub(crate) struct Record {
    /// A study's output directory (results.json, and certificate.dcc.xml and certificate.pdf
    /// when there).
    #[arg(required_unless_present = "balanced", conflicts_with = "balanced")]
    results_dir: Option<PathBuf>,
    #[command(flatten)]
    records: RecordsFile,
    /// The centrifuge the study's probe phases were measured on. Default: the certificate's
    /// equipment whose role names a centrifuge.
    #[arg(long)]
    centrifuge: Option<String>,
    /// The date of measurement (YYYY-MM-DD): for a study without a certificate, and for
    /// `--balanced`.
    #[arg(long)]
    date: Option<String>,
    /// The identification of the certificate this study's certificate corrects: both remain
    /// recorded, and the history uses this one (ISO/IEC 17025 §7.8.8).
    #[arg(long, value_name = "CERTIFICATE_ID")]
    supersedes: Option<String>,
    /// The lab profile the study ran under, recorded with it.
    #[arg(long)]
    profile: Option<String>,
    /// Record a balancing of the centrifuge (--centrifuge, --date) instead of a study: what
    /// was done, in words. `history --centrifuge` fits the campaigns since the latest one.
    #[arg(long, value_name = "NOTE", requires_all = ["centrifuge", "date"], conflicts_with_all = ["supersedes", "profile"])]
    balanced: Option<String>,
}

/// `--records FILE`, shared by `record`, `history` and `study`.
#[derive(Debug, Args)]
pub(crate) struct RecordsFile {
    /// The records database (SQLite). Default: $CENTRIFUGE_CAL_RECORDS, else
    /// records.sqlite in $XDG_DATA_HOME/centrifuge-cal (~/.local/share/centrifuge-cal).
    #[arg(long, value_name = "FILE")]
    records: Option<PathBuf>,
}

impl RecordsFile {
    /// The database's path and, when it is a default, the words saying which.
    pub(crate) fn resolve(&self) -> anyhow::Result<(PathBuf, Option<&'static str>)> {
        records_path(self.records.as_deref())
    }
}

/// The records database's path: `given` (`--records FILE`), else `$CENTRIFUGE_CAL_RECORDS`,
/// else `records.sqlite` in `$XDG_DATA_HOME/centrifuge-cal` (`~/.local/share/centrifuge-cal`);
/// with, when it is a default, the words saying which. The command line and the Python
/// package find the database through this one function.
///
/// # Errors
/// No path given and none of the variables set.
pub fn records_path(given: Option<&Path>) -> anyhow::Result<(PathBuf, Option<&'static str>)> {
    if let Some(p) = given {
        return Ok((p.to_owned(), None));
    }
    if let Some(p) = std::env::var_os("CENTRIFUGE_CAL_RECORDS").filter(|p| !p.is_empty()) {
        return Ok((PathBuf::from(p), Some("from $CENTRIFUGE_CAL_RECORDS")));
    }
    let data = std::env::var_os("XDG_DATA_HOME")
        .filter(|p| !p.is_empty())
        .map(PathBuf::from)
        .or_else(|| {
            std::env::var_os("HOME")
                .filter(|p| !p.is_empty())
                .map(|h| PathBuf::from(h).join(".local/share"))
        })
        .context("no --records given, and neither $CENTRIFUGE_CAL_RECORDS, $XDG_DATA_HOME nor $HOME is set: give --records FILE")?;
    Ok((
        data.join("centrifuge-cal/records.sqlite"),
        Some("the default: no --records given"),
    ))
}

/// What `record` adds to a study's outputs.
#[derive(Debug, Default)]
pub(crate) struct Extra {
    pub(crate) centrifuge: Option<String>,
    pub(crate) date: Option<Date>,
    pub(crate) supersedes: Option<String>,
    pub(crate) profile: Option<String>,
}

#[derive(Debug, Deserialize)]
struct FileDto {
    path: String,
    bytes: u64,
    sha256: String,
    #[serde(default)]
    role: Option<String>,
    #[serde(default)]
    field: Option<String>,
}

#[derive(Debug, Deserialize)]
struct ProvenanceDto {
    #[serde(default)]
    version: Option<String>,
    config: FileDto,
    #[serde(default)]
    expected: Option<FileDto>,
    #[serde(default)]
    inputs: Vec<FileDto>,
}

fn file(role: &str, f: FileDto) -> InputFile {
    InputFile {
        role: f.role.unwrap_or_else(|| role.to_owned()),
        field: f.field,
        path: f.path,
        bytes: f.bytes,
        sha256: f.sha256,
    }
}

fn parse_date(field: &str, text: Option<&str>) -> anyhow::Result<Option<Date>> {
    text.map(|t| Date::parse_field(field, t))
        .transpose()
        .map_err(anyhow::Error::new)
}

fn optional_file(path: &Path) -> anyhow::Result<Option<Vec<u8>>> {
    if path.is_file() {
        Ok(Some(edge_io::read_bytes_capped(
            path,
            CERTIFICATE_MAX_BYTES,
        )?))
    } else {
        Ok(None)
    }
}

/// One study's outputs as read from its folder, ready to be submitted.
struct Read {
    dir: PathBuf,
    results: pipeline::StudyResults,
    bytes: Vec<u8>,
    inputs: Vec<InputFile>,
    tool_version: Option<String>,
    dcc: Option<Vec<u8>>,
    pdf: Option<Vec<u8>>,
}

/// Reads the study whose outputs are in `dir`.
fn read_study(dir: &Path) -> anyhow::Result<Read> {
    let results_path = dir.join("results.json");
    if !results_path.is_file() {
        anyhow::bail!(
            "{}: no results.json: give the output directory of a study (`centrifuge-cal study --out DIR`)",
            dir.display()
        );
    }
    let bytes = edge_io::read_bytes_capped(&results_path, RESULTS_MAX_BYTES)?;
    let value: serde_json::Value = serde_json::from_slice(&bytes)
        .with_context(|| format!("{}: not a study's results (JSON)", results_path.display()))?;
    let results: pipeline::StudyResults =
        serde_json::from_value(value.clone()).with_context(|| {
            format!(
                "{}: not a study's results as this centrifuge-cal writes them (docs/RESULTS.md)",
                results_path.display()
            )
        })?;
    let provenance = match value.get("provenance") {
        Some(p) => Some(
            ProvenanceDto::deserialize(p)
                .with_context(|| format!("{}: field `provenance`", results_path.display()))?,
        ),
        None => None,
    };
    let (tool_version, inputs) = match provenance {
        Some(p) => {
            let mut inputs = vec![file("configuration", p.config)];
            inputs.extend(p.expected.map(|e| file("expected", e)));
            inputs.extend(p.inputs.into_iter().map(|f| file("input", f)));
            (p.version, inputs)
        }
        None => (None, Vec::new()),
    };
    let dcc = optional_file(&dir.join("certificate.dcc.xml"))?;
    let pdf = optional_file(&dir.join("certificate.pdf"))?;
    Ok(Read {
        dir: dir.to_owned(),
        results,
        bytes,
        inputs,
        tool_version,
        dcc,
        pdf,
    })
}

/// Records the study whose outputs are in `dir` into `db`: one study, or, for a
/// several-unit study's top folder, every unit's (`units/<label>/`) in one transaction,
/// all or none. Each folder recorded with what recording it did.
pub(crate) fn record_dir(
    db: &mut Database,
    dir: &Path,
    extra: &Extra,
) -> anyhow::Result<Vec<(PathBuf, Outcome)>> {
    let top = read_study(dir)?;
    let studies = match &top.results.units {
        None => vec![top],
        Some(units) => {
            if extra.supersedes.is_some() {
                anyhow::bail!(
                    "{}: a several-unit study's folder holds {} certificates, and --supersedes                      names the one certificate a corrected certificate replaces: record the                      corrected unit's own folder (`centrifuge-cal record {}/units/LABEL                      --supersedes …`)",
                    dir.display(),
                    units.len(),
                    dir.display()
                );
            }
            if units.is_empty() {
                anyhow::bail!("{}: a several-unit study without units", dir.display());
            }
            units
                .iter()
                .map(|u| {
                    // a label names a folder inside this one, never a path elsewhere
                    if u.label.is_empty()
                        || !u
                            .label
                            .bytes()
                            .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-')
                    {
                        anyhow::bail!(
                            "{}: field `units`: the label {:?} is not a unit's folder name                              (letters, digits, `_` and `-`)",
                            dir.join("results.json").display(),
                            edge_io::visible(&u.label)
                        );
                    }
                    let unit_dir = dir.join("units").join(&u.label);
                    let read = read_study(&unit_dir).with_context(|| {
                        format!("unit {} of the study in {}", u.label, dir.display())
                    })?;
                    if read.results.units.is_some() {
                        anyhow::bail!(
                            "{}: holds another several-unit study, not unit {}'s results",
                            unit_dir.display(),
                            u.label
                        );
                    }
                    Ok(read)
                })
                .collect::<anyhow::Result<Vec<_>>>()?
        }
    };
    let submissions: Vec<Submission<'_>> = studies
        .iter()
        .map(|s| Submission {
            results: &s.results,
            results_json: &s.bytes,
            inputs: s.inputs.clone(),
            tool_version: s.tool_version.clone(),
            dcc_xml: s.dcc.as_deref(),
            certificate_pdf: s.pdf.as_deref(),
            centrifuge: extra.centrifuge.clone(),
            date: extra.date,
            profile: extra.profile.clone(),
            supersedes: extra.supersedes.clone(),
        })
        .collect();
    let outcomes = match std::env::var_os(PAUSE_BEFORE_COMMIT) {
        Some(marker) => db.record_all_then(&submissions, || {
            let _ = std::fs::write(&marker, b"paused before commit");
            std::thread::sleep(std::time::Duration::from_secs(120));
        }),
        None => db.record_all(&submissions),
    }
    .with_context(|| {
        if studies.len() > 1 {
            format!(
                "recording the {} units of {} (nothing of any was recorded)",
                studies.len(),
                dir.display()
            )
        } else {
            format!("recording {}", dir.display())
        }
    })?;
    Ok(studies
        .iter()
        .map(|s| s.dir.clone())
        .zip(outcomes)
        .collect())
}

/// Prints what a recording did.
pub(crate) fn print_outcome(
    console: &mut Console,
    db_path: &Path,
    default: Option<&str>,
    study: &Path,
    outcome: &Outcome,
) -> anyhow::Result<()> {
    let shown = |s: &str| edge_io::visible(s).into_owned();
    let db = match default {
        Some(words) => format!("{} ({words})", db_path.display()),
        None => db_path.display().to_string(),
    };
    match outcome {
        Outcome::Recorded {
            record,
            certificate,
            supersedes,
            unit,
            centrifuge,
            phases,
        } => {
            writeln!(console, "recorded {} in {db}", study.display())?;
            if let (Some(c), Some(u)) = (certificate, unit) {
                write!(console, "  certificate {} of unit {}", shown(c), shown(u))?;
                match supersedes {
                    Some(old) => writeln!(console, ", superseding {}", shown(old))?,
                    None => writeln!(console)?,
                }
            }
            match centrifuge {
                Some(name) => writeln!(
                    console,
                    "  {phases} probe phase{} on centrifuge {}",
                    if *phases == 1 { "" } else { "s" },
                    shown(name)
                )?,
                None => writeln!(
                    console,
                    "  its {phases} probe phase{} on no centrifuge (none named: --centrifuge NAME)",
                    if *phases == 1 { "" } else { "s" }
                )?,
            }
            writeln!(console, "  record {record}")?;
        }
        Outcome::AlreadyRecorded {
            record,
            recorded_at,
        } => {
            writeln!(
                console,
                "already recorded: {} was recorded in {db} at {recorded_at} (record {record}); nothing written",
                study.display()
            )?;
        }
    }
    Ok(())
}

impl Record {
    pub(crate) fn run(&self) -> anyhow::Result<()> {
        let (path, default) = self.records.resolve()?;
        if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("creating the folder of {}", path.display()))?;
        }
        let mut db = Database::open(&path, Access::CreateIfMissing)?;
        let date = parse_date("--date", self.date.as_deref())?;
        let mut console = Console::stdout();
        if let (Some(note), Some(centrifuge), Some(date)) = (&self.balanced, &self.centrifuge, date)
        {
            let outcome = db.record_balance(centrifuge, date, note)?;
            let shown = |s: &str| edge_io::visible(s).into_owned();
            match outcome {
                BalanceOutcome::Recorded => writeln!(
                    console,
                    "recorded in {}: centrifuge {} balanced on {date} ({})",
                    path.display(),
                    shown(centrifuge),
                    shown(note)
                )?,
                BalanceOutcome::AlreadyRecorded => writeln!(
                    console,
                    "already recorded: centrifuge {} balanced on {date} ({}); nothing written",
                    shown(centrifuge),
                    shown(note)
                )?,
            }
            return Ok(());
        }
        let dir = self
            .results_dir
            .as_deref()
            .context("give a study's output directory")?;
        let extra = Extra {
            centrifuge: self.centrifuge.clone(),
            date,
            supersedes: self.supersedes.clone(),
            profile: self.profile.clone(),
        };
        for (study, outcome) in record_dir(&mut db, dir, &extra)? {
            print_outcome(&mut console, &path, default, &study, &outcome)?;
        }
        Ok(())
    }
}
