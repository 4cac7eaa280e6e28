//! Hostile inputs on `init`, `check`, `study` and `simulate` (issue 32): links round a loop
//! or out of the folder, a FIFO and `/dev/zero` named as data, sparse files of 2 GB, a
//! folder past the file-count cap, outputs onto a lab's own files. Each command runs as a
//! child process under a watchdog ([`run_within`]): a command that blocks or runs away fails
//! its test after the limit (and is killed) instead of hanging CI.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use test_support::Scratch;
use test_support::hostile::{mkfifo, sparse_file};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs the CLI with `args`, killed (and the test failed) if it has not ended within
/// `limit`. Its output goes to files, so a full pipe cannot stall it.
fn run_within(limit: Duration, args: &[&str]) -> Output {
    static RUN: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = RUN.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let scratch = Scratch::new(&format!("cli-hostile-run-{n}"));
    let (out_path, err_path) = (scratch.0.join("stdout"), scratch.0.join("stderr"));
    let mut child = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap())
        .spawn()
        .expect("runs");
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "centrifuge-cal {} did not end within {limit:?}: killed (stderr: {})",
                args.join(" "),
                std::fs::read_to_string(&err_path).unwrap_or_default()
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Output {
        status,
        stdout: std::fs::read(&out_path).unwrap(),
        stderr: std::fs::read(&err_path).unwrap(),
    }
}

const LIMIT: Duration = Duration::from_secs(60);

fn text(out: &Output) -> (String, String) {
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Every file of a folder with its bytes.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap_or_default(),
            )
        })
        .collect()
}

/// Three of the small campaign's probe recordings copied into `dir`.
fn lab_recordings(dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    let from = root().join("fixtures/recordings/pre-balance-small");
    for rate in ["020.0000", "040.0000", "080.1234"] {
        let name = format!("probe_{rate}deg_s.csv");
        std::fs::copy(from.join(&name), dir.join(&name)).unwrap();
    }
}

#[cfg(unix)]
#[test]
fn init_follows_no_link_round_a_loop_or_out_of_the_folder() {
    let scratch = Scratch::new("cli-hostile-links");
    let lab = scratch.0.join("L");
    lab_recordings(&lab);
    std::fs::create_dir_all(lab.join("sub")).unwrap();
    std::os::unix::fs::symlink(".", lab.join("self")).unwrap();
    std::os::unix::fs::symlink("..", lab.join("sub/up")).unwrap();
    // a folder outside, with a data file that must not be read
    let outside = scratch.0.join("elsewhere");
    lab_recordings(&outside);
    std::os::unix::fs::symlink(&outside, lab.join("out")).unwrap();
    let out = run_within(LIMIT, &["init", lab.to_str().unwrap()]);
    let (stdout, stderr) = text(&out);
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(
        stdout.contains("  self: a link back to a folder already read (a loop): not followed"),
        "{stdout}"
    );
    assert!(
        stdout.contains("  sub/up: a link back to a folder already read (a loop): not followed"),
        "{stdout}"
    );
    assert!(
        stdout.contains(&format!(
            "  out: a link to the folder {}, outside the folder given: not followed",
            outside.canonicalize().unwrap().display()
        )),
        "{stdout}"
    );
    // the three recordings once each, nothing through the links
    assert_eq!(stdout.matches("probe recording").count(), 3, "{stdout}");
    assert!(!stdout.contains("self/probe"), "{stdout}");
}

#[cfg(unix)]
#[test]
fn init_skips_a_fifo_and_a_device_named_as_data_without_blocking() {
    let scratch = Scratch::new("cli-hostile-fifo-init");
    let lab = scratch.0.join("L");
    lab_recordings(&lab);
    mkfifo(&lab.join("fifo.csv"));
    std::os::unix::fs::symlink("/dev/zero", lab.join("zero.csv")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", lab.join("zero.tdms")).unwrap();
    let out = run_within(LIMIT, &["init", lab.to_str().unwrap()]);
    let (stdout, stderr) = text(&out);
    assert!(out.status.success(), "{stdout}\n{stderr}");
    for line in [
        "  fifo.csv: a named pipe (FIFO), not a regular file: not opened",
        "  zero.csv: a character device, not a regular file: not opened",
        "  zero.tdms: a character device, not a regular file: not opened",
    ] {
        assert!(stdout.contains(line), "{line}\n{stdout}");
    }
    assert!(lab.join("study.ron").is_file());
    // Named on the command line, the FIFO is skipped the same way.
    let fifo = lab.join("fifo.csv");
    let out = run_within(LIMIT, &["init", fifo.to_str().unwrap()]);
    let (stdout, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(1), "{stdout}\n{stderr}");
    assert!(
        stderr.contains("fifo.csv (a named pipe (FIFO), not a regular file: not opened)"),
        "{stderr}"
    );
}

#[test]
fn init_refuses_sparse_2_gb_files_from_their_first_bytes() {
    let scratch = Scratch::new("cli-hostile-sparse-init");
    let lab = scratch.0.join("L");
    lab_recordings(&lab);
    sparse_file(&lab.join("huge.tdms"), b"", 2 << 30);
    sparse_file(&lab.join("huge.mat"), b"", 2 << 30);
    sparse_file(&lab.join("huge.csv"), b"", 2 << 30);
    let start = Instant::now();
    let out = run_within(LIMIT, &["init", lab.to_str().unwrap()]);
    let elapsed = start.elapsed();
    let (stdout, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(1), "{stdout}\n{stderr}");
    assert!(
        stdout.contains(
            "  huge.tdms: cannot be read as an NI TDMS file: not a TDMS file (no TDMS signature at byte 0)"
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains("  huge.mat: cannot be read as a MATLAB file"),
        "{stdout}"
    );
    // A text file is read up to the cap (64 MiB of zeros here), never whole.
    assert!(stdout.contains("  huge.csv: unknown shape"), "{stdout}");
    assert!(!lab.join("study.ron").exists());
    // Before issue 32: 2.1 GB of memory and 8.7 s per file. A generous bound for a loaded
    // machine; the watchdog stops a whole read.
    assert!(elapsed < Duration::from_secs(30), "{elapsed:?}");
}

#[test]
fn init_stops_past_the_file_count_cap_with_a_message() {
    let scratch = Scratch::new("cli-hostile-many");
    let lab = scratch.0.join("L");
    std::fs::create_dir_all(&lab).unwrap();
    for i in 0..=10_000 {
        std::fs::File::create(lab.join(format!("f{i:05}.csv"))).unwrap();
    }
    let out = run_within(LIMIT, &["init", lab.to_str().unwrap()]);
    let (stdout, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(1), "{stdout}\n{stderr}");
    assert!(
        stderr.contains("more than 10000 data files under")
            && stderr.contains("init examines no more in one run"),
        "{stderr}"
    );
    assert!(stdout.is_empty(), "nothing examined: {stdout}");
}

#[test]
fn init_never_writes_over_one_of_its_inputs_or_a_file_it_did_not_write() {
    let scratch = Scratch::new("cli-hostile-init-out");
    let lab = scratch.0.join("L");
    lab_recordings(&lab);
    let before = snapshot(&lab);
    let input = lab.join("probe_020.0000deg_s.csv");
    let out = run_within(
        LIMIT,
        &[
            "init",
            lab.to_str().unwrap(),
            "--force",
            "--out",
            input.to_str().unwrap(),
        ],
    );
    let (stdout, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(1), "{stdout}\n{stderr}");
    assert!(
        stderr.contains("is one of the files init reads: nothing written"),
        "{stderr}"
    );
    assert_eq!(snapshot(&lab), before, "the recordings untouched");
    // A configuration the lab wrote by hand is not init's to replace, even with --force.
    std::fs::write(lab.join("study.ron"), "(name: \"ours\")").unwrap();
    let out = run_within(LIMIT, &["init", lab.to_str().unwrap(), "--force"]);
    let (stdout, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(1), "{stdout}\n{stderr}");
    assert!(stderr.contains("was not written by init"), "{stderr}");
    assert_eq!(
        std::fs::read_to_string(lab.join("study.ron")).unwrap(),
        "(name: \"ours\")"
    );
    // One init wrote is replaced with --force.
    std::fs::remove_file(lab.join("study.ron")).unwrap();
    for args in [
        vec!["init", lab.to_str().unwrap()],
        vec!["init", lab.to_str().unwrap(), "--force"],
    ] {
        let out = run_within(LIMIT, &args);
        assert!(out.status.success(), "{:?}", text(&out));
    }
}

/// The small recordings study copied into `dir` with its recordings beside it, the one at
/// 40 deg/s replaced by `replace` (called with its path).
fn study_with(dir: &Path, replace: impl FnOnce(&Path)) -> PathBuf {
    let recordings = dir.join("recordings/pre-balance-small");
    std::fs::create_dir_all(&recordings).unwrap();
    let from = root().join("fixtures/recordings/pre-balance-small");
    for e in std::fs::read_dir(&from).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), recordings.join(e.file_name())).unwrap();
    }
    let target = recordings.join("probe_040.0000deg_s.csv");
    std::fs::remove_file(&target).unwrap();
    replace(&target);
    let studies = dir.join("studies");
    std::fs::create_dir_all(&studies).unwrap();
    let config = studies.join("recordings-small.ron");
    std::fs::copy(
        root().join("fixtures/studies/recordings-small.ron"),
        &config,
    )
    .unwrap();
    config
}

#[cfg(unix)]
#[test]
fn check_and_study_refuse_a_fifo_or_a_device_recording_without_blocking() {
    for (name, make) in [
        ("fifo", (|p: &Path| mkfifo(p)) as fn(&Path)),
        ("zero", |p: &Path| {
            std::os::unix::fs::symlink("/dev/zero", p).unwrap()
        }),
    ] {
        let scratch = Scratch::new(&format!("cli-hostile-study-{name}"));
        let config = study_with(&scratch.0, make);
        let kind = if name == "fifo" {
            "is a named pipe (FIFO), not a regular file"
        } else {
            "is a character device, not a regular file"
        };
        let out = run_within(LIMIT, &["check", config.to_str().unwrap()]);
        let (stdout, stderr) = text(&out);
        assert_eq!(out.status.code(), Some(1), "{stdout}\n{stderr}");
        assert!(
            stdout.contains("probe_040.0000deg_s.csv") && stdout.contains(kind),
            "{name}: {stdout}"
        );
        let target = scratch.0.join("out");
        let out = run_within(
            LIMIT,
            &[
                "study",
                "--config",
                config.to_str().unwrap(),
                "--out",
                target.to_str().unwrap(),
            ],
        );
        let (stdout, stderr) = text(&out);
        assert_eq!(out.status.code(), Some(1), "{stdout}\n{stderr}");
        assert!(
            stderr.contains("probe_040.0000deg_s.csv") && stderr.contains(kind),
            "{name}: {stderr}"
        );
        assert!(!target.exists(), "nothing written");
    }
}

#[test]
fn simulate_onto_a_folder_of_a_labs_recordings_is_refused_and_changes_nothing() {
    let scratch = Scratch::new("cli-hostile-simulate");
    let lab = scratch.0.join("lab");
    // A lab's own files, named as simulate names its outputs.
    lab_recordings(&lab);
    std::fs::write(lab.join("piga.csv"), "rate_deg_s,output_rad_s\n10,0.004\n").unwrap();
    std::fs::write(lab.join("piga_020deg_s.csv"), "time_s,output_deg\n0,0\n").unwrap();
    let before = snapshot(&lab);
    let scenario = root().join("fixtures/scenarios/pre-balance-small.ron");
    let out = run_within(
        LIMIT,
        &[
            "simulate",
            "--config",
            scenario.to_str().unwrap(),
            "--out",
            lab.to_str().unwrap(),
        ],
    );
    let (stdout, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(1), "{stdout}\n{stderr}");
    assert!(
        stderr.contains("holds 5 entries this tool did not write")
            && stderr.contains("no record of what this tool wrote here"),
        "{stderr}"
    );
    assert_eq!(snapshot(&lab), before, "the lab's files, byte for byte");
    // Its own output it replaces, run after run.
    let sim = scratch.0.join("sim");
    for _ in 0..2 {
        let out = run_within(
            LIMIT,
            &[
                "simulate",
                "--config",
                scenario.to_str().unwrap(),
                "--out",
                sim.to_str().unwrap(),
            ],
        );
        assert!(out.status.success(), "{:?}", text(&out));
    }
}
