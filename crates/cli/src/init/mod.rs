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
mod orientation;
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
    /// The lab profile (`lab.ron`, docs/PROFILE.md): with it the whole study is written —
    /// the centrifuge's geometry, g, the Type B inputs and the certificate section come from
    /// it, and only what neither the files nor the profile tell is asked.
    #[arg(long)]
    profile: Option<PathBuf>,
    /// The profile's centrifuge used (default: the profile's only one; with several and
    /// none named, the study asks).
    #[arg(long, requires = "profile")]
    centrifuge: Option<String>,
}

impl Init {
    pub(crate) fn run(&self) -> anyhow::Result<()> {
        let profile = self.profile.as_deref().map(read_profile).transpose()?;
        let centrifuge = match (&profile, &self.centrifuge) {
            (None, _) => None,
            (Some(p), Some(name)) => Some(
                p.centrifuges
                    .iter()
                    .position(|c| &c.name == name)
                    .ok_or_else(|| {
                        anyhow::anyhow!(
                            "--centrifuge {name}: the profile has no such centrifuge (it has {})",
                            p.centrifuges
                                .iter()
                                .map(|c| c.name.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        )
                    })?,
            ),
            (Some(p), None) => (p.centrifuges.len() == 1).then_some(0),
        };
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
        let mut plan = plan(&findings, &self.name, &base, &shown, &mut problems);
        if let Some(orientations) = orientation_lines(&plan) {
            console.write_str(&orientations)?;
        }
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
        if let (Some(config), Some(file)) = (profile, &self.profile) {
            plan.profile = Some(config::ProfilePlan {
                file: file.clone(),
                config,
                centrifuge,
            });
        }
        let text = config::render(&plan, &relative);
        write_whole(&out, text.as_bytes()).with_context(|| format!("writing {}", out.display()))?;
        let left = config::placeholders(&text);
        let mut summary = format!("\nwrote {}\n", out.display());
        if !left.is_empty() {
            let _ = writeln!(
                summary,
                "{} value{} to fill in (marked {PLACEHOLDER}, each with its question), then \
                 `centrifuge-cal check {}`:",
                left.len(),
                if left.len() == 1 { "" } else { "s" },
                out.display()
            );
            for l in &left {
                let _ = writeln!(summary, "  {}", l.words());
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

/// `path` relative to `folder` (with `..` where it lies beside it), exactly as the file
/// system names it: a backslash, a quote or a non-ASCII letter in a name is kept (the study
/// writes it as a RON string that reads back to the same name).
fn relative_to(path: &Path, folder: &Path) -> String {
    use std::path::Component;
    let (p, f): (Vec<Component<'_>>, Vec<Component<'_>>) =
        (path.components().collect(), folder.components().collect());
    let common = p.iter().zip(&f).take_while(|(a, b)| a == b).count();
    // Only the root in common: the absolute path says more than `../../..`.
    if common <= 1 && path.is_absolute() {
        return path.to_string_lossy().into_owned();
    }
    let mut out = std::path::PathBuf::new();
    for _ in common..f.len() {
        out.push("..");
    }
    for c in &p[common..] {
        out.push(c.as_os_str());
    }
    out.to_string_lossy().into_owned()
}

/// The lab profile at `path`, read with the study's size cap and validated: every problem
/// at once, each naming the profile's field.
fn read_profile(path: &Path) -> anyhow::Result<pipeline::ProfileConfig> {
    let text = edge_io::read_text_capped(path, pipeline::MAX_STUDY_BYTES)?;
    let profile = pipeline::Profile::from_ron(&text, path)?;
    profile.validate().map_err(|e| match &e {
        pipeline::PipelineError::Several { errors } => anyhow::anyhow!(
            "the lab profile {} has {} problems:\n{}",
            path.display(),
            errors.len(),
            crate::problems::render(&crate::problems::each(&e)).trim_end()
        ),
        _ => anyhow::Error::new(e),
    })?;
    Ok(profile.config().clone())
}

/// The mountings init read from the PIGA files' names, with the evidence, when the files
/// hold both.
fn orientation_lines(plan: &config::Plan<'_>) -> Option<String> {
    if !plan.units.is_empty() {
        let names: Vec<String> = plan.units.iter().map(|u| u.label.clone()).collect();
        return Some(format!(
            "\n{} PIGA tables that name no mounting: {} units calibrated in one run ({}), \
             each from its table, the probe phases measured once\n",
            plan.units.len(),
            plan.units.len(),
            names.join(", ")
        ));
    }
    plan.mountings.as_ref().map(|m| {
        format!(
            "\nIA in and IA out: {m}: a two-orientation section (eq. 23); the calibration takes \
             the IA-in data\n"
        )
    })
}

/// The table of what was found in each file.
fn table(findings: &[Finding], shown: &dyn Fn(&Path) -> String) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "{:<32} {:<29} {:<10} {:>5} {:>5} {:<12} {:<30} {:>7}",
        "file", "kind", "delimiter", "comma", "skip", "rate deg/s", "angle reference", "to fill"
    );
    for f in findings {
        let name = shown(&f.path);
        let mut kind = f.kind.map_or("not understood", Kind::words).to_owned();
        if matches!(f.kind, Some(Kind::PigaTable | Kind::PigaRecording))
            && let Some((o, _)) = orientation::orientation(Path::new(&name))
        {
            kind = format!("{kind}, {}", o.words());
        }
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
            "{name:<32} {kind:<29} {delimiter:<10} {comma:>5} {skip:>5} {rate:<12} {angle:<30} {left:>7}"
        );
    }
    t
}

/// The phases, the calibration and the two mountings from the files; problems found across
/// files (one rate twice, formats that differ within a set, PIGA data that fits no study)
/// are added to `problems`.
fn plan<'a>(
    findings: &'a [Finding],
    name: &Option<String>,
    base: &Path,
    shown: &dyn Fn(&Path) -> String,
    problems: &mut BTreeMap<String, Vec<String>>,
) -> config::Plan<'a> {
    use orientation::Orientation;
    let mut phases: BTreeMap<String, Vec<&Finding>> = BTreeMap::new();
    // PIGA data by the mounting its name states (`None`: it states none).
    let mut piga: BTreeMap<Option<Orientation>, Vec<&Finding>> = BTreeMap::new();
    let mut tables: BTreeMap<Option<Orientation>, Vec<&Finding>> = BTreeMap::new();
    let mut evidence: BTreeMap<Orientation, String> = BTreeMap::new();
    for f in findings.iter().filter(|f| f.problems.is_empty()) {
        let mut mounting = || {
            orientation::orientation(Path::new(&shown(&f.path))).map(|(o, words)| {
                let key = o;
                evidence
                    .entry(key)
                    .or_insert_with(|| format!("{} (`{words}`)", shown(&f.path)));
                key
            })
        };
        match f.kind {
            Some(Kind::Probe) => phases.entry(phase_key(f, base)).or_default().push(f),
            Some(Kind::PigaRecording) => piga.entry(mounting()).or_default().push(f),
            Some(Kind::PigaTable) => tables.entry(mounting()).or_default().push(f),
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
    if !tables.is_empty() && !piga.is_empty() {
        for t in tables.values().flatten() {
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
    // Several PIGA tables whose names state no mounting, and no raw recordings: several
    // units calibrated in one run, one table each (a `units` list).
    let units = match tables.get(&None) {
        Some(list) if list.len() > 1 && tables.len() == 1 && piga.is_empty() => {
            let list = tables.remove(&None).unwrap_or_default();
            unit_labels(&list, shown)
                .into_iter()
                .zip(list)
                .map(|((label, evidence), f)| config::Unit {
                    label,
                    evidence,
                    data: config::PigaData::Table(f),
                })
                .collect()
        }
        _ => Vec::new(),
    };
    // The PIGA's data: one set (a table, or recordings), or one per mounting.
    let keys: Vec<Option<Orientation>> = tables.keys().chain(piga.keys()).copied().collect();
    let both = keys.contains(&Some(Orientation::In)) && keys.contains(&Some(Orientation::Out));
    let mut data: BTreeMap<Option<Orientation>, config::PigaData<'a>> = BTreeMap::new();
    for (key, list) in &tables {
        if list.len() > 1 {
            for t in list {
                problems.entry(shown(&t.path)).or_default().push(format!(
                    "one of {} PIGA tables{}: the study takes one per mounting (name it with \
                     `init FILES`, or name the mountings `ia_in` and `ia_out`)",
                    list.len(),
                    key.map_or_else(String::new, |k| format!(" for {}", k.words()))
                ));
            }
        } else {
            data.insert(*key, config::PigaData::Table(list[0]));
        }
    }
    for (key, list) in piga {
        let mut files = list;
        check_set(&mut files, shown, problems);
        data.insert(
            key,
            config::PigaData::Recordings(config::Group {
                name: "calibration".to_owned(),
                files,
            }),
        );
    }
    let mut mountings = None;
    let (calibration, two_orientation) = if both {
        if let Some(d) = data.get(&None) {
            for f in piga_files(d) {
                problems.entry(shown(&f.path)).or_default().push(
                    "PIGA data whose name states no mounting, beside data named IA in and IA \
                     out: name it `ia_in` or `ia_out`, or leave it out"
                        .to_owned(),
                );
            }
        }
        let ia_in = data.remove(&Some(Orientation::In));
        let ia_out = data.remove(&Some(Orientation::Out));
        mountings = Some(format!(
            "{} and {}",
            evidence.get(&Orientation::In).cloned().unwrap_or_default(),
            evidence.get(&Orientation::Out).cloned().unwrap_or_default()
        ));
        match (ia_in, ia_out) {
            (Some(i), Some(o)) => {
                // The calibration (probe method) reads the IA-in data too.
                let calibration = match &i {
                    config::PigaData::Table(t) => config::PigaData::Table(t),
                    config::PigaData::Recordings(g) => {
                        config::PigaData::Recordings(config::Group {
                            name: g.name.clone(),
                            files: g.files.clone(),
                        })
                    }
                };
                (Some(calibration), Some((i, o)))
            }
            _ => (None, None),
        }
    } else {
        if data.len() > 1 {
            for f in data.values().flat_map(piga_files) {
                problems.entry(shown(&f.path)).or_default().push(
                    "PIGA data of several sets, not named as the two mountings (`ia_in` and \
                     `ia_out`): the study takes one set (name it with `init FILES`)"
                        .to_owned(),
                );
            }
        }
        if let Some(d) = data.get(&Some(Orientation::Out)) {
            for f in piga_files(d) {
                problems.entry(shown(&f.path)).or_default().push(
                    "PIGA data named IA out without IA-in data: the probe method calibrates the \
                     IA-in mounting; add the IA-in data (a two-orientation study) or pass the \
                     files without this one"
                        .to_owned(),
                );
            }
        }
        let one = data.into_values().next();
        (one, None)
    };
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
        calibration,
        two_orientation,
        profile: None,
        mountings,
        units,
    }
}

/// Each unit's label from its table's name (`piga_A.csv` → `A`: the name without its
/// extension and a leading `piga_`, letters, digits, `_` and `-` kept, anything else `_`),
/// made unique without regard to case (`_2`, `_3`…), with the evidence in words.
fn unit_labels(tables: &[&Finding], shown: &dyn Fn(&Path) -> String) -> Vec<(String, String)> {
    let mut labels: Vec<(String, String)> = Vec::new();
    for f in tables {
        let stem = f
            .path
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        let lower = stem.to_ascii_lowercase();
        let bare = ["piga_", "piga-", "piga"]
            .iter()
            .find_map(|p| {
                lower
                    .starts_with(p)
                    .then(|| stem[p.len()..].to_owned())
                    .filter(|r| !r.is_empty())
            })
            .unwrap_or_else(|| stem.clone());
        let mut label: String = bare
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .take(60)
            .collect();
        if label.is_empty() {
            label = "unit".to_owned();
        }
        let base = label.clone();
        let mut n = 2;
        while labels.iter().any(|(l, _)| l.eq_ignore_ascii_case(&label)) {
            label = format!("{base}_{n}");
            n += 1;
        }
        labels.push((label, format!("from the table's name, {}", shown(&f.path))));
    }
    labels
}

/// The files of a set of PIGA data.
fn piga_files<'a>(d: &config::PigaData<'a>) -> Vec<&'a Finding> {
    match d {
        config::PigaData::Table(t) => vec![*t],
        config::PigaData::Recordings(g) => g.files.clone(),
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
