//! The README's path from a fresh clone to a calibration of one's own files, run as written
//! on fixture files: the commands of its "Your own data" block (at most five), with the
//! lab's folder replaced by a copy of the simulated campaign's probe recordings and PIGA
//! table (fixtures/campaign, truth in its truth.json) and the placeholders filled as a user
//! would.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::init::{Scratch, fill_in};

/// The folder the README's example names.
const LAB: &str = "~/lab/spindle";

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The commands of the README's "Your own data" code block, comments removed.
fn readme_commands() -> Vec<String> {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let section = readme
        .split("\n## ")
        .find(|s| s.starts_with("Your own data"))
        .expect("README has a section `## Your own data`");
    let block = section
        .split("```sh\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .expect("a sh code block");
    block
        .lines()
        .map(|l| l.split(" #").next().unwrap_or("").trim().to_owned())
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .collect()
}

#[test]
fn the_readme_path_calibrates_fixture_files() {
    let commands = readme_commands();
    assert!(commands.len() <= 5, "{commands:?}");
    assert!(commands[0].starts_with("git clone"), "{commands:?}");
    assert_eq!(commands[1], "cargo install --path crates/cli");
    let tmp = Scratch::new("cli-init-readme");
    let lab = tmp.0.join("spindle");
    std::fs::create_dir_all(&lab).unwrap();
    let fixture = root().join("fixtures/campaign");
    for entry in std::fs::read_dir(&fixture).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        // The probe recordings and the PIGA table (not also the raw PIGA recordings).
        if name.starts_with("probe_") || name == "piga.csv" {
            std::fs::copy(&path, lab.join(path.file_name().unwrap())).unwrap();
        }
    }
    // `git clone` and `cargo install` made the binary this test runs; the others run here.
    for command in &commands[2..] {
        let line = command.replace(LAB, lab.to_str().unwrap());
        let mut words = line.split_whitespace();
        assert_eq!(words.next(), Some("centrifuge-cal"), "{line}");
        let out = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
            .args(words)
            .current_dir(&tmp.0)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{line}:\n{}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        if line.contains(" init ") {
            // The user's edit: the placeholders, from the lab's own records.
            let config = lab.join("study.ron");
            let text = std::fs::read_to_string(&config).unwrap();
            std::fs::write(&config, fill_in(&text)).unwrap();
        }
    }
    let results = std::fs::read_to_string(lab.join("results/results.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&results).unwrap();
    let truth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(fixture.join("truth.json")).unwrap())
            .unwrap();
    let fit = &json["phases"][0];
    let (c, s) = (
        fit["c_r_m_s2"].as_f64().unwrap(),
        fit["c_r_sigma_m_s2"].as_f64().unwrap(),
    );
    let c_true = truth["c_r_m_s2"].as_f64().unwrap();
    assert!(
        (c - c_true).abs() < 3.0 * s,
        "C_r {c:e} ± {s:e}, truth {c_true:e}"
    );
    assert!(json["calibration"]["coefficients"]["k2"]["value"].is_number());
}
