//! What `init` reads, and how much (issue 32): the folder walk and the bounded read of each
//! file. The walk keeps to regular files (a FIFO, a device or a socket is skipped and
//! named, never opened), follows a link to a folder only when the folder lies inside a
//! folder given (never out of it, never round a loop: a visited set by device and inode),
//! and stops past [`MAX_DATA_FILES`] data files or [`MAX_ENTRIES`] entries. Each file is then
//! opened as a regular file only (checked on the open handle, without blocking) and read up
//! to a cap: [`TEXT_PREFIX_BYTES`] of a text file (its format and rate are guessed from
//! that prefix), a whole TDMS or MAT file up to [`BINARY_MAX_BYTES`] once its first bytes
//! carry the format's signature.

use std::collections::HashSet;
use std::io::Read as _;
use std::path::{Path, PathBuf};

use anyhow::bail;

/// Most data files (by extension) `init` examines in one run.
pub(crate) const MAX_DATA_FILES: usize = 10_000;

/// Most folder entries `init` looks at in one run (data files or not): a folder given by
/// mistake (a home folder, `/usr`) stops early with a message instead of a long walk.
pub(crate) const MAX_ENTRIES: usize = 200_000;

/// Deepest folder nesting followed below a folder given.
pub(crate) const MAX_DEPTH: usize = 32;

/// Bytes of a text file `init` reads: the format and the rate are guessed from at most this
/// much of it, cut at its last whole line (64 MiB: over a million lines of a recording).
pub(crate) const TEXT_PREFIX_BYTES: u64 = 64 << 20;

/// Largest TDMS or MAT file `init` reads (whole: the channels of a binary file are spread
/// through it). A larger one is named with the cap, its format left for the study file.
pub(crate) const BINARY_MAX_BYTES: u64 = 1 << 30;

/// The first bytes of a binary file examined for its signature before the rest is read.
const SIGNATURE_BYTES: usize = 128;

/// A path the walk did not read, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Skipped {
    /// The path.
    pub(crate) path: PathBuf,
    /// Why, in words.
    pub(crate) why: String,
}

/// What the walk found.
#[derive(Debug, Default)]
pub(crate) struct Walked {
    /// The data files (by extension), sorted.
    pub(crate) files: Vec<PathBuf>,
    /// The names of regular files skipped for their extension, sorted.
    pub(crate) other_names: Vec<String>,
    /// What was not read for another reason (not a regular file, a link out of the folder or
    /// round a loop, too deep), in the order found.
    pub(crate) not_read: Vec<Skipped>,
}

/// A folder's identity: device and inode (Unix); elsewhere its canonical path.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
enum Identity {
    #[cfg(unix)]
    Inode(u64, u64),
    #[cfg_attr(unix, allow(dead_code))]
    Path(PathBuf),
}

fn identity(path: &Path, metadata: &std::fs::Metadata) -> Identity {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt as _;
        let _ = path;
        Identity::Inode(metadata.dev(), metadata.ino())
    }
    #[cfg(not(unix))]
    {
        let _ = metadata;
        Identity::Path(path.canonicalize().unwrap_or_else(|_| path.to_path_buf()))
    }
}

/// What a file-system entry is, in words, when it is neither a regular file nor a folder.
fn kind_words(metadata: &std::fs::Metadata) -> &'static str {
    edge_io::kind_of(metadata)
}

/// The files named, folders expanded (recursively, hidden entries left out), sorted, with
/// what was skipped and why (see the module's documentation).
///
/// # Errors
/// A path given that does not exist; a folder that cannot be listed; more than
/// [`MAX_DATA_FILES`] data files or [`MAX_ENTRIES`] entries.
pub(crate) fn collect(inputs: &[PathBuf], extensions: &[&str]) -> anyhow::Result<Walked> {
    let mut walked = Walked::default();
    let mut visited: HashSet<Identity> = HashSet::new();
    // Folders given, resolved: a link to a folder is followed only into one of them.
    let mut roots: Vec<PathBuf> = Vec::new();
    let mut stack: Vec<(PathBuf, usize)> = Vec::new();
    for input in inputs {
        let metadata = std::fs::metadata(input)
            .map_err(|_| anyhow::anyhow!("{}: no such file or folder", input.display()))?;
        if metadata.is_dir() {
            if visited.insert(identity(input, &metadata)) {
                roots.push(input.canonicalize().unwrap_or_else(|_| input.clone()));
                stack.push((input.clone(), 0));
            }
        } else if metadata.is_file() {
            walked.files.push(input.clone());
        } else {
            walked.not_read.push(Skipped {
                path: input.clone(),
                why: format!("{}, not a regular file: not opened", kind_words(&metadata)),
            });
        }
    }
    let has_data_extension = |path: &Path| {
        path.extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .is_some_and(|e| extensions.contains(&e.as_str()))
    };
    let mut entries_seen = 0_usize;
    // Depth first, each folder's entries in name order, so the skipped list reads in order.
    while let Some((dir, depth)) = stack.pop() {
        let listing = std::fs::read_dir(&dir)
            .map_err(|e| anyhow::anyhow!("reading the folder {}: {e}", dir.display()))?;
        let mut paths: Vec<PathBuf> = Vec::new();
        for entry in listing {
            let entry =
                entry.map_err(|e| anyhow::anyhow!("reading the folder {}: {e}", dir.display()))?;
            entries_seen += 1;
            if entries_seen > MAX_ENTRIES {
                bail!(
                    "more than {MAX_ENTRIES} entries under {}: init looks at no more in one \
                     run; give the folder that holds the lab's recordings, or the files \
                     themselves",
                    inputs_text(inputs)
                );
            }
            paths.push(entry.path());
        }
        paths.sort();
        let mut subfolders = Vec::new();
        for path in paths {
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            if name.as_deref().is_some_and(|n| n.starts_with('.')) {
                continue;
            }
            let link = std::fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_symlink());
            let metadata = match std::fs::metadata(&path) {
                Ok(m) => m,
                Err(e) => {
                    walked.not_read.push(Skipped {
                        path,
                        why: if link {
                            "a link to nothing (its target does not exist)".to_owned()
                        } else {
                            format!("cannot be examined: {e}")
                        },
                    });
                    continue;
                }
            };
            if metadata.is_dir() {
                let id = identity(&path, &metadata);
                if link {
                    let target = path.canonicalize().unwrap_or_else(|_| path.clone());
                    if !roots.iter().any(|r| target.starts_with(r)) {
                        walked.not_read.push(Skipped {
                            path,
                            why: format!(
                                "a link to the folder {}, outside the folder given: not followed",
                                target.display()
                            ),
                        });
                        continue;
                    }
                }
                if visited.contains(&id) {
                    walked.not_read.push(Skipped {
                        path,
                        why: "a link back to a folder already read (a loop): not followed"
                            .to_owned(),
                    });
                    continue;
                }
                if depth + 1 > MAX_DEPTH {
                    walked.not_read.push(Skipped {
                        path,
                        why: format!("more than {MAX_DEPTH} folders deep: not read"),
                    });
                    continue;
                }
                visited.insert(id);
                subfolders.push((path, depth + 1));
            } else if !has_data_extension(&path) {
                if let Some(n) = name {
                    walked.other_names.push(n);
                }
            } else if metadata.is_file() {
                walked.files.push(path);
                if walked.files.len() > MAX_DATA_FILES {
                    bail!(
                        "more than {MAX_DATA_FILES} data files under {}: init examines no more \
                         in one run; give a folder of one campaign, or the files themselves",
                        inputs_text(inputs)
                    );
                }
            } else {
                walked.not_read.push(Skipped {
                    path,
                    why: format!("{}, not a regular file: not opened", kind_words(&metadata)),
                });
            }
        }
        // Popped in name order.
        stack.extend(subfolders.into_iter().rev());
    }
    walked.files.sort();
    walked.other_names.sort();
    Ok(walked)
}

fn inputs_text(inputs: &[PathBuf]) -> String {
    inputs
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// A file's bytes as `init` reads them.
#[derive(Debug)]
pub(crate) struct Bounded {
    /// The bytes read: the whole file, or a text file's first [`TEXT_PREFIX_BYTES`] cut at
    /// the last line end, or a binary file's first bytes when it has no signature or is too
    /// large.
    pub(crate) bytes: Vec<u8>,
    /// The file's size when only a prefix was read.
    pub(crate) prefix_of: Option<u64>,
    /// Why the file is not understood from its bytes (too large), if so.
    pub(crate) problem: Option<String>,
}

/// Reads the file at `path` within the caps: a regular file only, opened without blocking
/// (`edge_io::open_regular`).
///
/// # Errors
/// What stops the file from being read, in words (without its path: the table names it).
pub(crate) fn read_bounded(path: &Path) -> Result<Bounded, String> {
    let (file, metadata) = edge_io::open_regular(path).map_err(|e| match e {
        edge_io::EdgeIoError::NotAFile { kind, .. } => {
            format!("{kind}, not a regular file: not read")
        }
        other => format!("cannot be read: {}", std::io::Error::from(other)),
    })?;
    let size = metadata.len();
    let binary = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .is_some_and(|e| e == "tdms" || e == "mat");
    let read_error = |e: std::io::Error| format!("cannot be read: {e}");
    if binary {
        // The signature first: a file without it gets the reader's own words for that from
        // its first bytes, whatever its size (a 2 GB sparse `.tdms` is not read).
        let mut file = file;
        let mut bytes = Vec::with_capacity(SIGNATURE_BYTES);
        (&mut file)
            .take(SIGNATURE_BYTES as u64)
            .read_to_end(&mut bytes)
            .map_err(read_error)?;
        if !signature_ok(path, &bytes) {
            return Ok(Bounded {
                bytes,
                prefix_of: Some(size),
                problem: None,
            });
        }
        if size > BINARY_MAX_BYTES {
            return Ok(Bounded {
                bytes,
                prefix_of: Some(size),
                problem: Some(format!(
                    "{size} bytes ({}), above the {} init reads of a TDMS or MAT file: write \
                     its format in the study file by hand (docs/YOUR-DATA.md)",
                    gib(size),
                    gib(BINARY_MAX_BYTES)
                )),
            });
        }
        bytes.reserve(usize::try_from(size).unwrap_or(0));
        file.take(BINARY_MAX_BYTES)
            .read_to_end(&mut bytes)
            .map_err(read_error)?;
        return Ok(Bounded {
            bytes,
            prefix_of: None,
            problem: None,
        });
    }
    let cap = TEXT_PREFIX_BYTES;
    let mut bytes = Vec::with_capacity(usize::try_from(size.min(cap)).unwrap_or(0));
    file.take(cap + 1)
        .read_to_end(&mut bytes)
        .map_err(read_error)?;
    if bytes.len() as u64 <= cap {
        return Ok(Bounded {
            bytes,
            prefix_of: None,
            problem: None,
        });
    }
    // Longer than the cap: its whole lines within the cap.
    let end = bytes[..cap as usize]
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    bytes.truncate(end);
    Ok(Bounded {
        bytes,
        prefix_of: Some(size.max(cap + 1)),
        problem: None,
    })
}

/// Whether a binary file's first bytes carry its format's signature: `TDSm` for TDMS; for
/// MAT, the 128-byte header's version 0x0100 and endian mark `IM` or `MI`.
fn signature_ok(path: &Path, head: &[u8]) -> bool {
    let tdms = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("tdms"));
    if tdms {
        head.starts_with(b"TDSm")
    } else {
        head.len() >= 128 && matches!(&head[126..128], b"IM" | b"MI")
    }
}

/// A size in GiB (or MiB below one), for a message.
fn gib(bytes: u64) -> String {
    if bytes >= 1 << 30 {
        format!("{:.1} GiB", bytes as f64 / f64::from(1_u32 << 30))
    } else {
        format!("{} MiB", bytes >> 20)
    }
}

/// The first words of every configuration `init` writes (`config::render`): `--force`
/// replaces only a file that starts with them.
pub(crate) const WRITTEN_BY_INIT: &str = "// Study configuration written by `centrifuge-cal init`";

/// Refuses an output path `init` must not write: one of the files it read (with or without
/// `--force`), anything but a regular file, or (with `--force`) a file `init` did not write.
///
/// # Errors
/// The reason, naming the path, with the way out.
pub(crate) fn check_output(out: &Path, inputs: &[PathBuf], force: bool) -> anyhow::Result<()> {
    let Ok(metadata) = std::fs::metadata(out) else {
        return Ok(());
    };
    let same = |p: &PathBuf| {
        std::fs::metadata(p).is_ok_and(|m| identity(p, &m) == identity(out, &metadata))
    };
    if let Some(input) = inputs.iter().find(|p| same(p)) {
        let also = if input == out {
            String::new()
        } else {
            format!(" ({})", input.display())
        };
        bail!(
            "{} is one of the files init reads{also}: nothing written (--out names the \
             configuration to write; name a new file)",
            out.display()
        );
    }
    if !metadata.is_file() {
        bail!(
            "{} is {}: nothing written (--out names the configuration file to write)",
            out.display(),
            kind_words(&metadata)
        );
    }
    if !force {
        bail!(
            "{} exists: nothing written (--force overwrites it, or --out names another file)",
            out.display()
        );
    }
    let mut head = Vec::new();
    let read = edge_io::open_regular(out)
        .ok()
        .and_then(|(f, _)| f.take(256).read_to_end(&mut head).ok());
    if read.is_none() || !head.starts_with(WRITTEN_BY_INIT.as_bytes()) {
        bail!(
            "{} was not written by init (it does not start with init's first line): nothing \
             written; --force replaces only a configuration init wrote, so name another file \
             with --out",
            out.display()
        );
    }
    Ok(())
}
