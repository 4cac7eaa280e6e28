//! `OutputSet`: a run leaves exactly the new set of files, or the previous set byte for byte.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use test_support::Scratch;

use edge_io::{EdgeIoError, OUTPUT_RECORD, OutputSet, fault};

const OWNED: &[&str] = &["results.json", "report.md", "probe_*.svg"];

/// Every file of a directory with its bytes (the record of what was written included).
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut files = BTreeMap::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let entry = entry.unwrap();
        let name = entry.file_name().to_string_lossy().into_owned();
        files.insert(name, std::fs::read(entry.path()).unwrap());
    }
    files
}

/// The names of a directory's entries, sorted, without the record of what was written.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != OUTPUT_RECORD)
        .collect();
    names.sort();
    names
}

fn write_set(target: &Path, files: &[(&str, &str)]) -> edge_io::Result<Vec<PathBuf>> {
    let mut set = OutputSet::create(target, OWNED)?;
    let paths = files
        .iter()
        .map(|(name, text)| set.write(name, text.as_bytes()))
        .collect::<edge_io::Result<Vec<_>>>()?;
    set.commit()?;
    Ok(paths)
}

#[test]
fn a_new_directory_gets_exactly_the_set() {
    let scratch = Scratch::new("edge-io-new");
    let target = scratch.0.join("nested/study");
    let paths = write_set(&target, &[("results.json", "{}"), ("report.md", "# r")]).unwrap();
    assert_eq!(
        paths,
        vec![target.join("results.json"), target.join("report.md")]
    );
    assert_eq!(entries(&target), ["report.md", "results.json"]);
    assert_eq!(std::fs::read_to_string(&paths[0]).unwrap(), "{}");
    // the record lists what was written, with the sizes
    let record = std::fs::read_to_string(target.join(OUTPUT_RECORD)).unwrap();
    assert!(
        record.ends_with("\n2\tresults.json\n3\treport.md\n"),
        "{record}"
    );
    // nothing is left beside the target
    assert_eq!(entries(&scratch.0.join("nested")), ["study"]);
}

#[test]
fn a_second_run_replaces_the_set_and_drops_files_it_does_not_write() {
    let scratch = Scratch::new("edge-io-replace");
    let target = scratch.0.join("study");
    write_set(
        &target,
        &[("results.json", "1"), ("probe_signals_pre.svg", "<svg/>")],
    )
    .unwrap();
    write_set(&target, &[("results.json", "2"), ("report.md", "r")]).unwrap();
    let files = snapshot(&target);
    assert_eq!(
        files.keys().collect::<Vec<_>>(),
        [OUTPUT_RECORD, "report.md", "results.json"]
    );
    assert_eq!(files["results.json"], b"2");
    assert_eq!(entries(&scratch.0), ["study"]);
}

#[test]
fn a_failure_at_the_last_file_leaves_the_previous_set_byte_identical() {
    let scratch = Scratch::new("edge-io-fail-last");
    let target = scratch.0.join("study");
    write_set(
        &target,
        &[
            ("results.json", "previous"),
            ("probe_signals_pre.svg", "<svg>previous</svg>"),
        ],
    )
    .unwrap();
    let before = snapshot(&target);

    let mut set = OutputSet::create(&target, OWNED).unwrap();
    set.write("results.json", b"new").unwrap();
    set.write("report.md", b"new").unwrap();
    let e = set
        .write_with("probe_signals_post.svg", |out| {
            out.write_all(b"<svg>half")?;
            Err(std::io::Error::other("disk full"))
        })
        .unwrap_err();
    match &e {
        EdgeIoError::Write { path, source } => {
            assert_eq!(path, &target.join("probe_signals_post.svg"));
            assert_eq!(source.to_string(), "disk full");
        }
        other => panic!("expected Write, got {other:?}"),
    }
    drop(set);
    assert_eq!(snapshot(&target), before);
    assert_eq!(
        entries(&scratch.0),
        ["study"],
        "the staging directory is removed"
    );
}

#[test]
fn the_fault_hook_fails_the_named_file_only_while_armed() {
    let scratch = Scratch::new("edge-io-fault");
    let target = scratch.0.join("study");
    write_set(&target, &[("results.json", "previous")]).unwrap();
    let before = snapshot(&target);
    {
        let _fail = fault::fail_writing("report.md");
        let e = write_set(&target, &[("results.json", "new"), ("report.md", "new")]).unwrap_err();
        assert!(
            matches!(&e, EdgeIoError::Write { path, .. } if path.ends_with("report.md")),
            "{e:?}"
        );
        assert!(e.to_string().contains("report.md"), "{e}");
    }
    assert_eq!(snapshot(&target), before);
    write_set(&target, &[("results.json", "new"), ("report.md", "new")]).unwrap();
    assert_eq!(snapshot(&target)["report.md"], b"new");
}

#[test]
fn a_directory_with_foreign_entries_is_refused_and_left_alone() {
    let scratch = Scratch::new("edge-io-foreign");
    let target = scratch.0.join("home");
    std::fs::create_dir_all(target.join("photos")).unwrap();
    std::fs::write(target.join("notes.txt"), "keep me").unwrap();
    std::fs::write(target.join("results.json"), "old").unwrap();
    match OutputSet::create(&target, OWNED) {
        Err(EdgeIoError::ForeignEntries {
            target: t,
            count,
            example,
            why,
        }) => {
            assert_eq!(t, target);
            // notes.txt and photos by their names; results.json with no record of writing it
            assert_eq!(count, 3);
            assert_eq!(
                (example.as_str(), why),
                ("notes.txt", "not a name this tool writes")
            );
        }
        other => panic!("expected ForeignEntries, got {other:?}"),
    }
    assert_eq!(entries(&target), ["notes.txt", "photos", "results.json"]);
    assert_eq!(entries(&scratch.0), ["home"]);
}

#[test]
fn a_foreign_entry_that_appears_before_commit_stops_the_swap() {
    let scratch = Scratch::new("edge-io-foreign-late");
    let target = scratch.0.join("study");
    write_set(&target, &[("results.json", "previous")]).unwrap();
    let mut set = OutputSet::create(&target, OWNED).unwrap();
    set.write("results.json", b"new").unwrap();
    std::fs::write(target.join("mine.txt"), "x").unwrap();
    assert!(matches!(
        set.commit(),
        Err(EdgeIoError::ForeignEntries { count: 1, .. })
    ));
    assert_eq!(snapshot(&target)["results.json"], b"previous");
    assert_eq!(entries(&scratch.0), ["study"]);
}

#[test]
fn bad_names_are_refused() {
    let scratch = Scratch::new("edge-io-names");
    let target = scratch.0.join("study");
    let mut set = OutputSet::create(&target, OWNED).unwrap();
    set.write("results.json", b"x").unwrap();
    for (name, reason) in [
        ("", "not a file name"),
        ("..", "not a file name"),
        (
            "../results.json",
            "has an empty, `.` or `..` folder or file name",
        ),
        (
            "units//results.json",
            "has an empty, `.` or `..` folder or file name",
        ),
        ("results.json", "written twice"),
        (
            "notes.txt",
            "matches none of the names this output set may write",
        ),
    ] {
        match set.write(name, b"y") {
            Err(EdgeIoError::BadFileName {
                name: n, reason: r, ..
            }) => {
                assert_eq!((n.as_str(), r), (name, reason));
            }
            other => panic!("{name:?}: expected BadFileName, got {other:?}"),
        }
    }
}

#[test]
fn a_file_or_a_root_is_not_an_output_directory() {
    let scratch = Scratch::new("edge-io-not-dir");
    let file = scratch.0.join("results");
    std::fs::write(&file, "a file").unwrap();
    assert!(matches!(
        OutputSet::create(&file, OWNED),
        Err(EdgeIoError::NotADirectory { .. })
    ));
    assert!(matches!(
        OutputSet::create(Path::new("/"), OWNED),
        Err(EdgeIoError::NotADirectory { .. })
    ));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "a file");
}

#[test]
fn a_run_killed_between_the_renames_is_restored_by_the_next() {
    let scratch = Scratch::new("edge-io-recover");
    let target = scratch.0.join("study");
    // As a kill between the two renames leaves it: no target, the previous set as `old`.
    let old = scratch.0.join("study.old-4000000-7");
    write_set(&old, &[("results.json", "previous")]).unwrap();
    // and a staging directory of a process that no longer runs (pids stay below 2^22)
    let stale = scratch.0.join("study.tmp-4000001-0");
    std::fs::create_dir_all(&stale).unwrap();
    std::fs::write(stale.join("results.json"), "half").unwrap();
    // an unrelated sibling is never touched
    std::fs::create_dir_all(scratch.0.join("study.backup")).unwrap();

    let set = OutputSet::create(&target, OWNED).unwrap();
    assert_eq!(
        std::fs::read_to_string(target.join("results.json")).unwrap(),
        "previous"
    );
    drop(set);
    assert_eq!(entries(&scratch.0), ["study", "study.backup"]);
}

#[test]
fn an_old_directory_beside_a_complete_swap_is_removed() {
    let scratch = Scratch::new("edge-io-old-after-swap");
    let target = scratch.0.join("study");
    write_set(&target, &[("results.json", "new")]).unwrap();
    std::fs::create_dir_all(scratch.0.join("study.old-4000000-1")).unwrap();
    write_set(&target, &[("results.json", "newer")]).unwrap();
    assert_eq!(entries(&scratch.0), ["study"]);
    assert_eq!(snapshot(&target)["results.json"], b"newer");
}

#[cfg(unix)]
#[test]
fn a_symlinked_target_replaces_the_directory_behind_the_link() {
    let scratch = Scratch::new("edge-io-symlink");
    let real = scratch.0.join("real");
    write_set(&real, &[("results.json", "1")]).unwrap();
    let link = scratch.0.join("link");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let paths = write_set(&link, &[("results.json", "2")]).unwrap();
    assert_eq!(paths, [link.join("results.json")]);
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(
        std::fs::read_to_string(real.join("results.json")).unwrap(),
        "2"
    );
}

#[test]
fn a_folder_of_files_with_owned_names_but_no_record_is_refused_and_left_alone() {
    // A lab's own recordings, named as a simulation names its outputs (issue 32: simulate
    // onto such a folder replaced 41 files by 16).
    let scratch = Scratch::new("edge-io-lab-folder");
    let target = scratch.0.join("lab");
    std::fs::create_dir_all(&target).unwrap();
    for name in ["probe_a.svg", "results.json"] {
        std::fs::write(target.join(name), "the lab's").unwrap();
    }
    let before = snapshot(&target);
    let e = write_set(&target, &[("results.json", "new")]).unwrap_err();
    match &e {
        EdgeIoError::ForeignEntries {
            count,
            example,
            why,
            ..
        } => {
            assert_eq!(*count, 2);
            assert_eq!(
                (example.as_str(), *why),
                ("probe_a.svg", "no record of what this tool wrote here")
            );
        }
        other => panic!("expected ForeignEntries, got {other:?}"),
    }
    assert!(e.to_string().contains("did not write"), "{e}");
    assert_eq!(snapshot(&target), before);
    assert_eq!(entries(&scratch.0), ["lab"]);
}

#[test]
fn a_file_changed_or_added_since_the_last_run_is_refused() {
    let scratch = Scratch::new("edge-io-changed");
    let target = scratch.0.join("study");
    write_set(&target, &[("results.json", "1"), ("report.md", "r")]).unwrap();
    // edited by hand after the run
    std::fs::write(target.join("report.md"), "my notes").unwrap();
    match write_set(&target, &[("results.json", "2")]) {
        Err(EdgeIoError::ForeignEntries { example, why, .. }) => assert_eq!(
            (example.as_str(), why),
            (
                "report.md",
                "changed since this tool wrote it (its size differs)"
            )
        ),
        other => panic!("expected ForeignEntries, got {other:?}"),
    }
    assert_eq!(snapshot(&target)["report.md"], b"my notes");
    // put back as written, then one with an owned name that the last run did not write
    std::fs::write(target.join("report.md"), "r").unwrap();
    std::fs::write(target.join("probe_x.svg"), "<svg/>").unwrap();
    match write_set(&target, &[("results.json", "2")]) {
        Err(EdgeIoError::ForeignEntries { example, why, .. }) => assert_eq!(
            (example.as_str(), why),
            ("probe_x.svg", "not among the files this tool wrote here")
        ),
        other => panic!("expected ForeignEntries, got {other:?}"),
    }
    std::fs::remove_file(target.join("probe_x.svg")).unwrap();
    write_set(&target, &[("results.json", "2")]).unwrap();
    assert_eq!(entries(&target), ["results.json"]);
}

#[test]
fn an_empty_folder_is_taken() {
    let scratch = Scratch::new("edge-io-empty");
    let target = scratch.0.join("out");
    std::fs::create_dir_all(&target).unwrap();
    write_set(&target, &[("results.json", "1")]).unwrap();
    assert_eq!(entries(&target), ["results.json"]);
}

/// A set may hold folders (`units/A/results.json`): they are written, swapped in and
/// replaced with it, and a file in them the set did not write is refused like one beside
/// them.
#[test]
fn folders_of_a_set_are_written_replaced_and_guarded() {
    let scratch = Scratch::new("edge-io-folders");
    let target = scratch.0.join("study");
    let owned = ["results.json", "units/*/results.json", "units/*/report.md"];
    let mut set = OutputSet::create(&target, &owned).unwrap();
    set.write("results.json", b"top").unwrap();
    set.write("units/A/results.json", b"a").unwrap();
    set.write("units/B/results.json", b"b").unwrap();
    assert!(matches!(
        set.write("units/A/notes.txt", b"x"),
        Err(EdgeIoError::BadFileName { .. })
    ));
    set.commit().unwrap();
    assert_eq!(
        std::fs::read(target.join("units/B/results.json")).unwrap(),
        b"b"
    );
    // written again with one unit fewer: the other unit's folder goes with the old set
    let mut set = OutputSet::create(&target, &owned).unwrap();
    set.write("results.json", b"top2").unwrap();
    set.write("units/A/report.md", b"r").unwrap();
    set.commit().unwrap();
    assert!(!target.join("units/B").exists());
    assert!(!target.join("units/A/results.json").exists());
    assert_eq!(
        std::fs::read(target.join("units/A/report.md")).unwrap(),
        b"r"
    );
    // a lab's own file in a unit's folder: nothing is replaced
    std::fs::write(target.join("units/A/notes.txt"), b"mine").unwrap();
    assert!(matches!(
        OutputSet::create(&target, &owned),
        Err(EdgeIoError::ForeignEntries { count: 1, ref example, .. }) if example == "units/A/notes.txt"
    ));
    // a folder the record does not list is foreign as a whole
    std::fs::remove_file(target.join("units/A/notes.txt")).unwrap();
    std::fs::create_dir(target.join("units/C")).unwrap();
    std::fs::write(target.join("units/C/results.json"), b"c").unwrap();
    assert!(matches!(
        OutputSet::create(&target, &owned),
        Err(EdgeIoError::ForeignEntries { .. })
    ));
}
