//! `centrifuge-cal init DIR|FILES`: a commented study configuration written from a lab's
//! files. Each file's format (delimiter, decimal mark, metadata lines, columns and units, the
//! angle reference) and rate are guessed from the file and commented with the evidence;
//! what the files cannot tell is left as a placeholder that `check` and `study` refuse. A
//! file that cannot be understood, or two files at one rate, stop it before anything is
//! written, each problem named with its file.

mod binary;
mod columns;
pub(crate) mod config;
mod file;
mod rate;
mod setting;
mod sniff;
mod table;
mod walk;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};

use crate::console::Console;
pub(crate) use file::PLACEHOLDER;
use file::{Finding, Kind};
use sniff::{Delim, Layout};

/// File extensions `init` reads in a folder.
const DATA_EXTENSIONS: [&str; 8] = ["csv", "txt", "dat", "tsv", "asc", "prn", "tdms", "mat"];

/// Write a commented study configuration from a lab's files.
#[derive(Debug, clap::Args)]
pub(crate) struct Init {
    /// A folder holding the lab's files (probe recordings, the PIGA table or PIGA output
    /// recordings; subfolders too), or the files themselves.
    #[arg(required = true, value_name = "DIR|FILES")]
    inputs: Vec<PathBuf>,
    /// The configuration written. Default: study.ron in the folder given (or the first
    /// file's folder).
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Overwrite an existing configuration.
    #[arg(long)]
    force: bool,
    /// The study's name. Default: the folder's name.
    #[arg(long)]
    name: Option<String>,
}

impl Init {
    pub(crate) fn run(&self) -> anyhow::Result<()> {
        let walked = walk::collect(&self.inputs, &DATA_EXTENSIONS)?;
        let (paths, skipped) = (&walked.files, &walked.other_names);
        let base = match &self.inputs[..] {
            [one] if one.is_dir() => one.clone(),
            _ => self.inputs[0]
                .parent()
                .map_or_else(|| PathBuf::from("."), Path::to_path_buf),
        };
        let out = self.out.clone().unwrap_or_else(|| base.join("study.ron"));
        if paths.is_empty() {
            bail!(
                "no data file in {}: looked for {} (found {})",
                self.inputs
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", "),
                DATA_EXTENSIONS.map(|e| format!(".{e}")).join(" "),
                if skipped.is_empty() && walked.not_read.is_empty() {
                    "nothing".to_owned()
                } else {
                    skipped
                        .iter()
                        .cloned()
                        .chain(
                            walked
                                .not_read
                                .iter()
                                .map(|s| format!("{} ({})", s.path.display(), s.why)),
                        )
                        .collect::<Vec<_>>()
                        .join(", ")
                }
            );
        }
        let findings: Vec<Finding> = paths.iter().map(|path| read_and_understand(path)).collect();
        let mut console = Console::stdout();
        let shown = |p: &Path| -> String {
            p.strip_prefix(&base)
                .map_or_else(|_| p.display().to_string(), |r| r.display().to_string())
        };
        if !walked.not_read.is_empty() {
            let mut text = String::from("not read:\n");
            for s in &walked.not_read {
                let _ = writeln!(text, "  {}: {}", shown(&s.path), s.why);
            }
            text.push('\n');
            console.write_str(&text)?;
        }
        console.write_str(&table(&findings, &shown))?;
        let mut problems: BTreeMap<String, Vec<String>> = BTreeMap::new();
        for f in &findings {
            for p in &f.problems {
                problems.entry(shown(&f.path)).or_default().push(p.clone());
            }
        }
        let plan = plan(&findings, &self.name, &base, &shown, &mut problems);
        if !problems.is_empty() {
            let mut text = String::from("\nnothing written; what stops it, file by file:\n");
            for (file, list) in &problems {
                for p in list {
                    let _ = writeln!(text, "  {file}: {p}");
                }
            }
            console.write_str(&text)?;
            let count: usize = problems.values().map(Vec::len).sum();
            bail!(
                "{count} problem{} in {} file{} (listed above)",
                if count == 1 { "" } else { "s" },
                problems.len(),
                if problems.len() == 1 { "" } else { "s" }
            );
        }
        let read: Vec<PathBuf> = paths.iter().chain(&self.inputs).cloned().collect();
        walk::check_output(&out, &read, self.force)?;
        let folder = out
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let folder = folder.canonicalize().unwrap_or(folder);
        let relative = |p: &Path| -> String {
            let abs = p.canonicalize().unwrap_or_else(|_| p.to_path_buf());
            relative_to(&abs, &folder)
        };
        let text = config::render(&plan, &relative);
        write_whole(&out, text.as_bytes()).with_context(|| format!("writing {}", out.display()))?;
        let left = config::placeholders(&text);
        let mut summary = format!("\nwrote {}\n", out.display());
        if !left.is_empty() {
            let _ = writeln!(
                summary,
                "{} value{} to fill in (marked {PLACEHOLDER}), then `centrifuge-cal check {}`:",
                left.len(),
                if left.len() == 1 { "" } else { "s" },
                out.display()
            );
            for (line, code) in &left {
                let _ = writeln!(summary, "  line {line}: {code}");
            }
        }
        console.write_str(&summary)?;
        Ok(())
    }
}

/// One file read within `init`'s caps ([`walk::read_bounded`]) and understood; a text file
/// longer than the cap is understood from its first whole lines, and its rate's evidence
/// says so.
fn read_and_understand(path: &Path) -> Finding {
    let bounded = match walk::read_bounded(path) {
        Ok(b) => b,
        Err(problem) => {
            let mut f = Finding::new(path);
            f.problems = vec![problem];
            return f;
        }
    };
    if let Some(problem) = bounded.problem {
        let mut f = Finding::new(path);
        f.problems = vec![problem];
        return f;
    }
    let bytes = bounded.bytes;
    let mut f = understand(path, &bytes, &|layout, name| {
        read_column(&bytes, path, layout, name)
    });
    if let (Some(size), Some(rate)) = (bounded.prefix_of, f.rate.as_mut()) {
        let _ = write!(
            rate.evidence,
            " (from the file's first {} MiB of {} MiB)",
            bytes.len() >> 20,
            size >> 20
        );
    }
    f
}

/// A whole column of a text file, read by the recording crate's table reader with the
/// sniffed layout.
fn read_column(bytes: &[u8], path: &Path, layout: &Layout, name: &str) -> Result<Vec<f64>, String> {
    let format = recording::TableFormat {
        columns: vec![recording::TableColumn::required(name)],
        delimiter: match layout.delimiter {
            Delim::Char(c) => c,
            Delim::Whitespace => ' ',
        },
        flexible: true,
        whitespace: layout.delimiter == Delim::Whitespace,
        decimal_comma: layout.decimal_comma,
        skip_lines: layout.skip_lines,
        allow_non_finite: true,
        label: None,
        hint_keys: &[],
    };
    let table = recording::parse_table(bytes, path, &format).map_err(|e| e.to_string())?;
    Ok(table.column(name).map(<[f64]>::to_vec).unwrap_or_default())
}

/// Writes a file whole: into a temporary file beside it, then renamed over it, so a failed
/// write leaves the previous file (or none).
fn write_whole(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let staged = path.with_file_name(format!(".{name}.{}.partial", std::process::id()));
    let written = std::fs::write(&staged, bytes).and_then(|()| std::fs::rename(&staged, path));
    if written.is_err() {
        let _ = std::fs::remove_file(&staged);
    }
    written
}

/// `path` relative to `folder` when it lies below it, else absolute.
fn relative_to(path: &Path, folder: &Path) -> String {
    path.strip_prefix(folder)
        .unwrap_or(path)
        .to_string_lossy()
        .replace('\\', "/")
}

/// The table of what was found in each file.
fn table(findings: &[Finding], shown: &dyn Fn(&Path) -> String) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "{:<32} {:<22} {:<10} {:>5} {:>5} {:<12} {:<30} {:>7}",
        "file", "kind", "delimiter", "comma", "skip", "rate deg/s", "angle reference", "to fill"
    );
    for f in findings {
        let name = shown(&f.path);
        let kind = f.kind.map_or("not understood", Kind::words);
        let (delimiter, comma, skip) = f.layout.as_ref().map_or_else(
            || ("—".to_owned(), "—".to_owned(), "—".to_owned()),
            |l| {
                (
                    l.delimiter.to_string(),
                    if l.decimal_comma { "yes" } else { "no" }.to_owned(),
                    l.skip_lines.to_string(),
                )
            },
        );
        let rate = f.rate.as_ref().map_or_else(
            || {
                if matches!(f.kind, Some(Kind::PigaTable) | None) {
                    "—".to_owned()
                } else {
                    "unknown".to_owned()
                }
            },
            |r| format!("{}", r.deg_s),
        );
        let angle = if f.angle_words.is_empty() {
            "—"
        } else {
            &f.angle_words
        };
        let left = f.placeholders().count()
            + usize::from(f.rate.is_none() && f.kind.is_some_and(|k| k != Kind::PigaTable));
        let _ = writeln!(
            t,
            "{name:<32} {kind:<22} {delimiter:<10} {comma:>5} {skip:>5} {rate:<12} {angle:<30} {left:>7}"
        );
    }
    t
}

/// The phases and the calibration from the files; problems found across files (one rate
/// twice, formats that differ within a set, several tables) are added to `problems`.
fn plan<'a>(
    findings: &'a [Finding],
    name: &Option<String>,
    base: &Path,
    shown: &dyn Fn(&Path) -> String,
    problems: &mut BTreeMap<String, Vec<String>>,
) -> config::Plan<'a> {
    let mut phases: BTreeMap<String, Vec<&Finding>> = BTreeMap::new();
    let mut piga = Vec::new();
    let mut tables = Vec::new();
    for f in findings.iter().filter(|f| f.problems.is_empty()) {
        match f.kind {
            Some(Kind::Probe) => phases.entry(phase_key(f, base)).or_default().push(f),
            Some(Kind::PigaRecording) => piga.push(f),
            Some(Kind::PigaTable) => tables.push(f),
            None => {}
        }
    }
    if phases.is_empty() && !findings.iter().all(|f| !f.problems.is_empty()) {
        problems.entry("(all files)".to_owned()).or_default().push(
            "no probe recording among the files: a study needs at least one phase of probe \
             recordings (time and gap columns)"
                .to_owned(),
        );
    }
    if tables.len() > 1 {
        for t in &tables {
            problems.entry(shown(&t.path)).or_default().push(format!(
                "one of {} PIGA tables: the study takes one (name it with `init FILES`)",
                tables.len()
            ));
        }
    }
    if !tables.is_empty() && !piga.is_empty() {
        for t in &tables {
            problems.entry(shown(&t.path)).or_default().push(
                "a PIGA table beside raw PIGA output recordings: the study takes one of them"
                    .to_owned(),
            );
        }
    }
    let mut groups = Vec::new();
    for (key, mut files) in phases {
        check_set(&mut files, shown, problems);
        groups.push(config::Group { name: key, files });
    }
    if groups.len() == 1 && groups[0].name.is_empty() {
        groups[0].name = "spindle".to_owned();
    }
    for (i, g) in groups.iter_mut().enumerate() {
        if g.name.is_empty() {
            g.name = format!("phase_{}", i + 1);
        }
    }
    let piga = (!piga.is_empty()).then(|| {
        check_set(&mut piga, shown, problems);
        config::Group {
            name: "calibration".to_owned(),
            files: piga,
        }
    });
    let study_name = name.clone().unwrap_or_else(|| {
        base.canonicalize()
            .ok()
            .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| "study".to_owned())
    });
    config::Plan {
        name: study_name,
        source: format!("{} file(s) in {}", findings.len(), base.display()),
        phases: groups,
        table: tables.first().copied(),
        piga,
    }
}

/// Files of one set sorted by rate; two at one rate, or formats that differ, are problems.
fn check_set(
    files: &mut [&Finding],
    shown: &dyn Fn(&Path) -> String,
    problems: &mut BTreeMap<String, Vec<String>>,
) {
    files.sort_by(|a, b| {
        let r = |f: &Finding| f.rate.as_ref().map_or(f64::INFINITY, |r| r.deg_s);
        r(a).total_cmp(&r(b)).then_with(|| a.path.cmp(&b.path))
    });
    for pair in files.windows(2) {
        if let (Some(a), Some(b)) = (&pair[0].rate, &pair[1].rate)
            && (a.deg_s - b.deg_s).abs() <= 1e-9 * a.deg_s.abs().max(1.0)
        {
            for (this, other) in [(pair[0], pair[1]), (pair[1], pair[0])] {
                problems.entry(shown(&this.path)).or_default().push(format!(
                    "claims the rate {} deg/s, as {} does: one rate point has two recordings \
                     (keep one, or pass the others with `init FILES` to a second study)",
                    a.deg_s,
                    shown(&other.path)
                ));
            }
        }
    }
    let first = files[0];
    for f in &files[1..] {
        if f.format_ron() != first.format_ron() {
            problems.entry(shown(&f.path)).or_default().push(format!(
                "its format {} differs from {}'s {}: one set of files must share a format",
                f.format_ron(),
                shown(&first.path),
                first.format_ron()
            ));
        }
    }
}

/// The phase a probe recording belongs to: its subfolder and its name without the rate and
/// digits (`pre/probe_020deg_s.csv` → `pre_probe`).
fn phase_key(f: &Finding, base: &Path) -> String {
    let folder = f
        .path
        .parent()
        .and_then(|p| p.strip_prefix(base).ok())
        .map(|p| p.to_string_lossy().replace(['/', '\\'], "_"))
        .unwrap_or_default();
    let stem = f
        .path
        .file_stem()
        .map(|s| s.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    let without_rate = match rate::rate_from_name(&stem) {
        Some((_, text)) => stem.replacen(&text.to_lowercase(), "", 1),
        None => stem,
    };
    let letters: String = without_rate
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .filter(|c| !c.is_ascii_digit())
        .collect();
    let mut key = format!("{folder}_{letters}");
    while key.contains("__") {
        key = key.replace("__", "_");
    }
    let key = key.trim_matches('_');
    // A generic stem (`probe`, `f`, `run`) names no phase.
    let generic = [
        "",
        "probe",
        "f",
        "run",
        "file",
        "data",
        "rec",
        "recording",
        "gap",
    ];
    if generic.contains(&key) {
        String::new()
    } else {
        key.strip_suffix("_probe").unwrap_or(key).to_owned()
    }
}

/// Understands one file from its bytes: a `.tdms` or `.mat` file by its channels
/// ([`binary`]), any other as delimited text ([`file`]).
fn understand(path: &Path, bytes: &[u8], read_column: &file::ColumnReader<'_>) -> Finding {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if matches!(extension.as_deref(), Some("tdms" | "mat")) {
        let mut f = Finding::new(path);
        binary::understand(&mut f, bytes, extension.as_deref() == Some("tdms"));
        return f;
    }
    file::understand(path, bytes, read_column)
}
