//! `identify` reads a PIGA table with the study's table options: the German export of
//! fixtures/recordings/piga-table-de (metadata lines, `;`, decimal comma, units in the
//! header) gives the same coefficients as the same numbers written plainly.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn identify(args: &[&str]) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .arg("identify")
        .args(args)
        .args(["--radius-m", "2.5", "--g", "9.8", "--json"])
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn a_decimal_comma_table_reads_as_the_study_reads_it() {
    let german = root().join("fixtures/recordings/piga-table-de/piga_export_utf8.csv");
    let read = identify(&[
        german.to_str().unwrap(),
        "--delimiter",
        ";",
        "--decimal",
        "comma",
        "--skip-lines",
        "5",
        "--rate-column",
        "Drehrate [°/s]",
        "--output-column",
        "Ausgang [rad/s]",
    ]);
    // The same rows with decimal points, commas between fields, no metadata.
    let text = std::fs::read_to_string(&german).unwrap();
    let mut plain = String::from("rate_deg_s,output_rad_s\n");
    for line in text.lines().skip(6).filter(|l| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split(';').collect();
        plain += &format!("{},{}\n", f[0].replace(',', "."), f[1].replace(',', "."));
    }
    let dir = std::env::temp_dir().join(format!("cli-identify-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let plain_path = dir.join("plain.csv");
    std::fs::write(&plain_path, plain).unwrap();
    let reference = identify(&[plain_path.to_str().unwrap()]);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(read["coefficients"], reference["coefficients"], "{read:#}");
    assert!(read["coefficients"].is_object(), "{read:#}");
    // A comma delimiter with a decimal comma is refused, naming the clash.
    let out = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(["identify", german.to_str().unwrap(), "--decimal", "comma"])
        .args(["--radius-m", "2.5", "--g", "9.8"])
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(1));
}

/// `identify` run in the repository's root (so the file is named relatively in its output).
fn identify_in_root(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .current_dir(root())
        .arg("identify")
        .args(args)
        .args(["--radius-m", "2.5", "--g", "9.8"])
        .output()
        .expect("runs")
}

const GERMAN: &str = "fixtures/recordings/piga-table-de/piga_export_utf8.csv";

/// Each reader error's hint names identify's own options (`--skip-lines`, `--decimal comma`,
/// `--rate-column`, `--rate-unit`), never a key of a study's `format` block.
#[test]
fn reading_errors_hint_at_identifys_own_options() {
    let cases: [(&[&str], &str); 5] = [
        (&[], "--skip-lines N"),
        // The lines skipped, the fields still read at commas: the header is one name that
        // splits at `;`, and the hint names the delimiter, not metadata lines.
        (&["--skip-lines", "5"], "--delimiter ';'"),
        (&["--delimiter", ";", "--skip-lines", "5"], "--rate-column"),
        (
            &[
                "--delimiter",
                ";",
                "--skip-lines",
                "5",
                "--rate-column",
                "Drehrate [°/s]",
                "--output-column",
                "Ausgang [rad/s]",
            ],
            "--decimal comma",
        ),
        (
            &[
                "--delimiter",
                ";",
                "--skip-lines",
                "5",
                "--decimal",
                "comma",
                "--rate-column",
                "Drehrate [°/s]",
                "--rate-unit",
                "rpm",
                "--output-column",
                "Ausgang [rad/s]",
            ],
            "--rate-unit deg_s",
        ),
    ];
    let mut all = String::new();
    for (args, option) in cases {
        let mut line = vec![GERMAN];
        line.extend_from_slice(args);
        let out = identify_in_root(&line);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(stderr.contains(option), "{args:?}: {stderr}");
        // No key of a study file: `set `decimal: comma``, `set `skip_lines``, `unit: rpm`.
        assert!(!stderr.contains("set `"), "{stderr}");
        assert!(!stderr.contains("skip_lines"), "{stderr}");
        all += &format!("$ identify {} …\n{stderr}\n", args.join(" "));
    }
    insta::assert_snapshot!("identify_reading_errors", all);
}

/// The human output of identify on the German export (rates in °/s, a label column): g
/// stated, U95 beside each u.
#[test]
fn identify_human_output_of_an_export() {
    let out = identify_in_root(&[
        GERMAN,
        "--delimiter",
        ";",
        "--skip-lines",
        "5",
        "--decimal",
        "comma",
        "--rate-column",
        "Drehrate [°/s]",
        "--output-column",
        "Ausgang [rad/s]",
        "--label-column",
        "Lage",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(text.contains("g = 9.8 m/s² (given with --g)"), "{text}");
    assert!(text.contains(" u ") && text.contains("U95"), "{text}");
    insta::assert_snapshot!("identify_export", text);
}

/// A radius that shrinks with ω² has a negative C_r; `--c-r-m-s2 -4e-8` is read as that
/// number (clap would take `-4e-8` for a flag), and the compensation uses it.
#[test]
fn a_negative_c_r_is_read_as_a_number() {
    let table = root().join("fixtures/campaign/piga.csv");
    let table = table.to_str().unwrap();
    let with = |c_r: &str| identify(&[table, "--c-r-m-s2", c_r, "--c-r-sigma-m-s2", "1e-9"]);
    let negative = with("-4e-8");
    let positive = with("4e-8");
    assert_ne!(
        negative, positive,
        "the sign of C_r reaches the compensation"
    );
    assert!(negative.to_string().contains("-4e-8") || negative.to_string().contains("-4.0e-8"));
}
