//! Atomic output directories: stage a set of files beside the target, then swap it in.

use std::ffi::{OsStr, OsString};
use std::fs;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::error::{EdgeIoError, Result};
use crate::fault;

/// The hidden file of a committed output set listing the files it wrote and their sizes
/// (see [`OutputSet`]): the proof that a later run may replace them.
pub const OUTPUT_RECORD: &str = ".centrifuge-cal-written";

/// The first line of [`OUTPUT_RECORD`].
const RECORD_HEADER: &str = "# centrifuge-cal wrote these files (bytes, name); it replaces a folder only if it holds just these";

/// Largest record read, bytes: a record is a line per file written.
const RECORD_MAX_BYTES: u64 = 16 << 20;

/// Numbers the staging and old directories of this process.
static SEQUENCE: AtomicUsize = AtomicUsize::new(0);

/// A set of output files written into a directory all at once: after a run the directory
/// holds either exactly the new set (files of an earlier run that this one does not write are
/// gone) or, if anything failed, the previous set untouched byte for byte.
///
/// # How the swap works
/// For a target directory `<dir>`:
///
/// 1. [`OutputSet::create`] creates the target's parent if needed and makes a staging
///    directory beside the target, `<dir>.tmp-<pid>-<n>` (same file system, so renames are
///    atomic). It refuses a target that holds entries whose names the caller does not own
///    (see below), so that pointing `--out` at a home directory cannot delete it.
/// 2. [`OutputSet::write`] and [`OutputSet::write_with`] create each file in the staging
///    directory, write it and flush it to disk (`fsync`). The target is not touched.
/// 3. [`OutputSet::commit`] syncs the staging directory, then: if `<dir>` does not exist,
///    renames the staging directory to `<dir>`; otherwise renames `<dir>` to
///    `<dir>.old-<pid>-<n>`, renames the staging directory to `<dir>` (putting the old one
///    back if that fails), syncs the parent and removes the old directory.
/// 4. Dropping a set that was not committed (an error, a panic) removes the staging
///    directory.
///
/// A process killed before step 3 leaves the target untouched and a stale
/// `<dir>.tmp-<pid>-<n>`; one killed between the two renames of step 3 leaves no `<dir>` but
/// a complete `<dir>.old-<pid>-<n>`. The next [`OutputSet::create`] for the same target
/// tidies both: it renames an old directory back to `<dir>` when `<dir>` is missing, removes
/// it when `<dir>` exists (the swap had completed), and removes staging directories of
/// processes that no longer run (on Linux, where `/proc` tells; elsewhere they are left).
/// Two processes writing the same target at the same time are not supported.
///
/// # Owned names, and the record of what was written
/// The caller lists the file names it writes as patterns in which `*` stands for any run of
/// characters but `/` (e.g. `"results.json"`, `"probe_signals_*.svg"`,
/// `"units/*/results.json"` for a file in a folder of the set). Every file written must
/// match one. A folder of the set is replaced with it: it is the set's when the record lists
/// files in it, and each of its entries is checked as the target's own.
///
/// A name is not proof of authorship: a lab's own `probe_020deg_s.csv` matches a
/// simulation's pattern (issue 32: `simulate --out` onto a folder of real recordings
/// replaced 41 files by 16). So each committed set also holds [`OUTPUT_RECORD`], a hidden
/// file listing every file the set wrote with its size, and an existing target is replaced
/// only if every entry it holds is listed there with the same size and matches an owned
/// pattern. A target holding anything else — a file the record does not list, one whose
/// size changed since it was written, a folder or a link, or any entry at all when there is
/// no record — is [`EdgeIoError::ForeignEntries`] and nothing is replaced. An empty folder
/// is taken.
#[derive(Debug)]
pub struct OutputSet {
    /// The target as the caller gave it; returned paths are under it.
    target: PathBuf,
    /// The target with symbolic links and `.`/`..` resolved: where the swap happens.
    resolved: PathBuf,
    /// The staging directory beside `resolved`.
    staging: PathBuf,
    /// Patterns of the names this set may write and replace.
    owned: Vec<String>,
    /// The names written so far, with their sizes.
    names: Vec<(String, u64)>,
    /// Whether the staging directory has become the target.
    committed: bool,
}

impl OutputSet {
    /// Prepares to write a new set of files into `target`, tidying what an interrupted
    /// earlier run left beside it (see the type's documentation).
    ///
    /// # Errors
    /// [`EdgeIoError::NotADirectory`] when `target` exists and is not a directory or names
    /// none; [`EdgeIoError::ForeignEntries`] when it holds entries that match no pattern of
    /// `owned`; [`EdgeIoError::Write`] when the parent or the staging directory cannot be
    /// created; [`EdgeIoError::Replace`] when an interrupted run's directory cannot be put
    /// back.
    pub fn create(target: &Path, owned: &[&str]) -> Result<Self> {
        let resolved = resolve(target)?;
        let owned: Vec<String> = owned.iter().map(|&p| p.to_owned()).collect();
        recover(&resolved, target)?;
        check_replaceable(&resolved, target, &owned)?;
        let staging = loop {
            let candidate = sibling(&resolved, "tmp");
            match fs::create_dir(&candidate) {
                Ok(()) => break candidate,
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {}
                Err(source) => {
                    return Err(EdgeIoError::Write {
                        path: candidate,
                        source,
                    });
                }
            }
        };
        Ok(Self {
            target: target.to_owned(),
            resolved,
            staging,
            owned,
            names: Vec::new(),
            committed: false,
        })
    }

    /// The output directory, as given to [`OutputSet::create`].
    #[must_use]
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Stages a file with the given contents; returns the path it will have once the set is
    /// committed (`target/name`).
    ///
    /// # Errors
    /// As [`OutputSet::write_with`].
    pub fn write(&mut self, name: &str, contents: &[u8]) -> Result<PathBuf> {
        self.write_with(name, |out| out.write_all(contents))
    }

    /// Stages a file whose contents `contents` writes into a buffered writer; returns the
    /// path it will have once the set is committed (`target/name`).
    ///
    /// # Errors
    /// [`EdgeIoError::BadFileName`] for a name that is empty, `.` or `..`, has a path
    /// separator other than `/` between folder names (`units/A/results.json` is a file in a
    /// folder of the set, created with it), was written already or matches no owned
    /// pattern; [`EdgeIoError::Write`]
    /// naming `target/name` when the file cannot be created, written (including an error
    /// `contents` returns) or synced.
    pub fn write_with<F>(&mut self, name: &str, contents: F) -> Result<PathBuf>
    where
        F: FnOnce(&mut dyn Write) -> io::Result<()>,
    {
        self.check_name(name)?;
        let destination = self.target.join(name);
        let error = |source| EdgeIoError::Write {
            path: destination.clone(),
            source,
        };
        let staged = self.staging.join(name);
        if let Some(folder) = staged.parent().filter(|p| *p != self.staging) {
            fs::create_dir_all(folder).map_err(error)?;
        }
        let file = fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&staged)
            .map_err(error)?;
        let mut out = BufWriter::with_capacity(1 << 16, file);
        contents(&mut out).map_err(error)?;
        if fault::armed_for(name) {
            return Err(error(io::Error::other(
                "failure injected by edge_io::fault",
            )));
        }
        let file = out.into_inner().map_err(|e| error(e.into_error()))?;
        file.sync_all().map_err(error)?;
        let bytes = file.metadata().map_err(error)?.len();
        self.names.push((name.to_owned(), bytes));
        Ok(destination)
    }

    /// Moves the staged files into place: afterwards the target holds exactly the files
    /// written to this set.
    ///
    /// # Errors
    /// [`EdgeIoError::Write`] when the staging directory cannot be synced;
    /// [`EdgeIoError::NotADirectory`] or [`EdgeIoError::ForeignEntries`] when the target
    /// changed since [`OutputSet::create`]; [`EdgeIoError::Replace`] when a rename fails. In
    /// every case the previous target is left as it was and the staging directory is removed.
    pub fn commit(mut self) -> Result<()> {
        let mut record = format!("{RECORD_HEADER}\n");
        for (name, bytes) in &self.names {
            record.push_str(&format!("{bytes}\t{name}\n"));
        }
        let record_path = self.staging.join(OUTPUT_RECORD);
        fs::write(&record_path, record)
            .and_then(|()| fs::File::open(&record_path)?.sync_all())
            .map_err(|source| EdgeIoError::Write {
                path: self.target.join(OUTPUT_RECORD),
                source,
            })?;
        sync_dir(&self.staging).map_err(|source| EdgeIoError::Write {
            path: self.target.clone(),
            source,
        })?;
        let replace = |source| EdgeIoError::Replace {
            target: self.target.clone(),
            source,
        };
        let old = match fs::symlink_metadata(&self.resolved) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => None,
            Err(e) => return Err(replace(e)),
            Ok(metadata) => {
                if !metadata.is_dir() {
                    return Err(EdgeIoError::NotADirectory {
                        target: self.target.clone(),
                    });
                }
                check_replaceable(&self.resolved, &self.target, &self.owned)?;
                let old = sibling(&self.resolved, "old");
                fs::rename(&self.resolved, &old).map_err(replace)?;
                Some(old)
            }
        };
        if let Err(e) = fs::rename(&self.staging, &self.resolved) {
            if let Some(old) = &old {
                // Put the previous set back; if even that fails, the next `create` does.
                let _ = fs::rename(old, &self.resolved);
            }
            return Err(replace(e));
        }
        self.committed = true;
        // The new set is in place: a failure from here on loses nothing. An old directory
        // that cannot be removed now is removed by the next run's `create`.
        let _ = sync_dir(parent_of(&self.resolved));
        if let Some(old) = old {
            let _ = fs::remove_dir_all(old);
        }
        Ok(())
    }

    fn check_name(&self, name: &str) -> Result<()> {
        let reason = if name.is_empty() || name == "." || name == ".." {
            Some("not a file name")
        } else if name
            .split('/')
            .any(|c| c.chars().any(std::path::is_separator))
        {
            Some("has a path separator other than `/`")
        } else if name
            .split('/')
            .any(|c| c.is_empty() || c == "." || c == "..")
        {
            Some("has an empty, `.` or `..` folder or file name")
        } else if self.names.iter().any(|(n, _)| n == name) {
            Some("written twice")
        } else if !self.owned.iter().any(|p| matches_pattern(p, name)) {
            Some("matches none of the names this output set may write")
        } else {
            None
        };
        reason.map_or(Ok(()), |reason| {
            Err(EdgeIoError::BadFileName {
                target: self.target.clone(),
                name: name.to_owned(),
                reason,
            })
        })
    }
}

impl Drop for OutputSet {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.staging);
        }
    }
}

/// Whether `name` matches `pattern`, in which each `*` stands for any run of characters
/// other than `/` (a name in a folder of the set is `folder/name`).
fn matches_pattern(pattern: &str, name: &str) -> bool {
    match pattern.split_once('*') {
        None => pattern == name,
        Some((prefix, rest)) => {
            let Some(name) = name.strip_prefix(prefix) else {
                return false;
            };
            let mut end = 0;
            loop {
                if matches_pattern(rest, &name[end..]) {
                    return true;
                }
                match name[end..].chars().next() {
                    None | Some('/') => return false,
                    Some(c) => end += c.len_utf8(),
                }
            }
        }
    }
}

/// The target with links and `.`/`..` resolved when it exists; otherwise its parent (created
/// if needed) joined with its name.
fn resolve(target: &Path) -> Result<PathBuf> {
    let not_a_directory = || EdgeIoError::NotADirectory {
        target: target.to_owned(),
    };
    let resolved = match fs::symlink_metadata(target) {
        Ok(_) => fs::canonicalize(target).map_err(|source| EdgeIoError::Write {
            path: target.to_owned(),
            source,
        })?,
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            let name = target.file_name().ok_or_else(not_a_directory)?;
            let parent = parent_of(target);
            fs::create_dir_all(parent).map_err(|source| EdgeIoError::Write {
                path: parent.to_owned(),
                source,
            })?;
            parent.join(name)
        }
        Err(source) => {
            return Err(EdgeIoError::Write {
                path: target.to_owned(),
                source,
            });
        }
    };
    if resolved.file_name().is_none() || (resolved.exists() && !resolved.is_dir()) {
        return Err(not_a_directory());
    }
    Ok(resolved)
}

/// The folder holding `path` (`.` for a bare name).
fn parent_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// A fresh `<dir>.<kind>-<pid>-<n>` beside `dir`.
fn sibling(dir: &Path, kind: &str) -> PathBuf {
    let mut name = dir.file_name().unwrap_or(OsStr::new("out")).to_os_string();
    name.push(format!(
        ".{kind}-{}-{}",
        std::process::id(),
        SEQUENCE.fetch_add(1, Ordering::Relaxed)
    ));
    dir.with_file_name(name)
}

/// The kind (`"old"` or `"tmp"`) and process id of a sibling name made by [`sibling`].
fn parse_sibling<'a>(dir_name: &str, entry: &'a OsStr) -> Option<(&'a str, u32)> {
    let rest = entry.to_str()?.strip_prefix(dir_name)?.strip_prefix('.')?;
    let (kind, numbers) = rest.split_once('-')?;
    let (pid, n) = numbers.split_once('-')?;
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    (matches!(kind, "old" | "tmp") && digits(pid) && digits(n)).then_some(())?;
    Some((kind, pid.parse().ok()?))
}

/// Whether the process that made a staging directory has ended (only Linux can tell).
fn process_gone(pid: u32) -> bool {
    if pid == std::process::id() {
        return false;
    }
    if cfg!(target_os = "linux") {
        !Path::new("/proc").join(pid.to_string()).exists()
    } else {
        false
    }
}

/// Tidies what interrupted runs left beside `resolved` (see [`OutputSet`]).
fn recover(resolved: &Path, target: &Path) -> Result<()> {
    let Some(dir_name) = resolved.file_name().and_then(OsStr::to_str) else {
        return Ok(());
    };
    let Ok(entries) = fs::read_dir(parent_of(resolved)) else {
        return Ok(());
    };
    let mut old: Vec<PathBuf> = Vec::new();
    let mut stale: Vec<PathBuf> = Vec::new();
    for entry in entries.flatten() {
        let name: OsString = entry.file_name();
        match parse_sibling(dir_name, &name) {
            Some(("old", _)) => old.push(entry.path()),
            Some((_, pid)) if process_gone(pid) => stale.push(entry.path()),
            _ => {}
        }
    }
    old.sort();
    if fs::symlink_metadata(resolved).is_err()
        && let Some(latest) = old.pop()
    {
        fs::rename(&latest, resolved).map_err(|source| EdgeIoError::Replace {
            target: target.to_owned(),
            source,
        })?;
    }
    for leftover in old.iter().chain(&stale) {
        let _ = fs::remove_dir_all(leftover);
    }
    Ok(())
}

/// The files an earlier set recorded in `dir` ([`OUTPUT_RECORD`]), name → size; `None`
/// when there is no record (or it cannot be read as one).
fn read_record(dir: &Path) -> Option<std::collections::HashMap<String, u64>> {
    let bytes = crate::text::read_bytes_capped(&dir.join(OUTPUT_RECORD), RECORD_MAX_BYTES).ok()?;
    let text = String::from_utf8(bytes).ok()?;
    let mut lines = text.lines();
    (lines.next()? == RECORD_HEADER).then_some(())?;
    lines
        .map(|line| {
            let (bytes, name) = line.split_once('\t')?;
            Some((name.to_owned(), bytes.parse().ok()?))
        })
        .collect()
}

/// Refuses a target that holds an entry an earlier set did not write (see [`OutputSet`]).
fn check_replaceable(resolved: &Path, target: &Path, owned: &[String]) -> Result<()> {
    let record = read_record(resolved);
    let mut foreign: Vec<(String, &'static str)> = Vec::new();
    scan(resolved, "", target, record.as_ref(), owned, &mut foreign)?;
    foreign.sort();
    match foreign.first() {
        None => Ok(()),
        Some((example, why)) => Err(EdgeIoError::ForeignEntries {
            target: target.to_owned(),
            count: foreign.len(),
            example: example.clone(),
            why,
        }),
    }
}

/// The entries of `dir` (at `prefix`, `""` or `units/A/`, within the target) that an earlier
/// set did not write, into `foreign`: a folder is its own only when the record lists files
/// under it, and then every entry in it is checked in turn.
fn scan(
    dir: &Path,
    prefix: &str,
    target: &Path,
    record: Option<&std::collections::HashMap<String, u64>>,
    owned: &[String],
    foreign: &mut Vec<(String, &'static str)>,
) -> Result<()> {
    let entries = match fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(()),
        Err(source) => {
            return Err(EdgeIoError::Replace {
                target: target.to_owned(),
                source,
            });
        }
    };
    for entry in entries {
        let entry = entry.map_err(|source| EdgeIoError::Replace {
            target: target.to_owned(),
            source,
        })?;
        let name = entry.file_name();
        let text = format!("{prefix}{}", name.to_string_lossy());
        if prefix.is_empty() && text == OUTPUT_RECORD && record.is_some() {
            continue;
        }
        let folder = format!("{text}/");
        let is_dir = entry.metadata().is_ok_and(|m| m.is_dir());
        if is_dir
            && name.to_str().is_some()
            && record.is_some_and(|r| r.keys().any(|k| k.starts_with(&folder)))
        {
            scan(&entry.path(), &folder, target, record, owned, foreign)?;
            continue;
        }
        let why = match (record, name.to_str()) {
            (_, None) => Some("a name that is not UTF-8"),
            (_, Some(_)) if !owned.iter().any(|p| matches_pattern(p, &text)) => {
                Some("not a name this tool writes")
            }
            (None, _) => Some("no record of what this tool wrote here"),
            (Some(record), Some(_)) => match (record.get(&text), entry.metadata()) {
                (None, _) => Some("not among the files this tool wrote here"),
                (Some(_), Ok(m)) if !m.is_file() => Some("not a regular file"),
                (Some(&bytes), Ok(m)) if m.len() != bytes => {
                    Some("changed since this tool wrote it (its size differs)")
                }
                (Some(_), Ok(_)) => None,
                (Some(_), Err(_)) => Some("cannot be examined"),
            },
        };
        if let Some(why) = why {
            foreign.push((text, why));
        }
    }
    Ok(())
}

/// Flushes a directory's entries to disk (a no-op where directories cannot be opened).
fn sync_dir(dir: &Path) -> io::Result<()> {
    if cfg!(unix) {
        fs::File::open(dir)?.sync_all()
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_match_folders_and_names() {
        assert!(matches_pattern(
            "units/*/results.json",
            "units/A/results.json"
        ));
        assert!(!matches_pattern(
            "units/*/results.json",
            "units/A/B/results.json"
        ));
        assert!(matches_pattern(
            "units/*/probe_signals_*.svg",
            "units/A-2/probe_signals_pre.svg"
        ));
        assert!(!matches_pattern(
            "units/*/results.json",
            "units//results.json.x"
        ));
        assert!(!matches_pattern("probe_*.svg", "probe_x/y.svg"));
    }

    #[test]
    fn patterns_have_one_wildcard() {
        assert!(matches_pattern("results.json", "results.json"));
        assert!(!matches_pattern("results.json", "results.json.bak"));
        assert!(matches_pattern(
            "probe_*.svg",
            "probe_signals_pre_balance.svg"
        ));
        assert!(matches_pattern("probe_*.svg", "probe_.svg"));
        assert!(!matches_pattern("probe_*.svg", "probe.svg"));
        assert!(!matches_pattern("a*a", "a"));
    }

    #[test]
    fn sibling_names_round_trip() {
        let s = sibling(Path::new("/x/study"), "tmp");
        let (kind, pid) = parse_sibling("study", s.file_name().unwrap()).unwrap();
        assert_eq!((kind, pid), ("tmp", std::process::id()));
        assert_eq!(
            parse_sibling("study", OsStr::new("study.old-12-3")),
            Some(("old", 12))
        );
        assert_eq!(parse_sibling("study", OsStr::new("study.bak-12-3")), None);
        assert_eq!(parse_sibling("study", OsStr::new("study.old-12")), None);
        assert_eq!(parse_sibling("study", OsStr::new("studyx.old-12-3")), None);
        assert_eq!(parse_sibling("study", OsStr::new("study.old-1a-3")), None);
    }
}
