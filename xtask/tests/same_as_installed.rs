//! `cargo xtask` is a thin wrapper: the `centrifuge-cal` binary built from crates/cli (what
//! `cargo install --path crates/cli` installs) gives the same study, byte for byte apart from
//! the output paths it prints.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The `centrifuge-cal` binary, built as `cargo build` builds it beside this test's own.
fn centrifuge_cal() -> PathBuf {
    let status = Command::new(env!("CARGO"))
        .args([
            "build",
            "--quiet",
            "--package",
            "cli",
            "--bin",
            "centrifuge-cal",
        ])
        .current_dir(root())
        .status()
        .expect("cargo runs");
    assert!(status.success(), "cargo build of centrifuge-cal failed");
    let xtask = PathBuf::from(env!("CARGO_BIN_EXE_xtask"));
    let binary = xtask.with_file_name(format!("centrifuge-cal{}", std::env::consts::EXE_SUFFIX));
    assert!(binary.is_file(), "{} not built", binary.display());
    binary
}

/// Runs `program ARGS --out DIR` and returns (stdout without the `wrote` lines, results.json).
fn study(program: &Path, args: &[&str], out: &Path) -> (String, serde_json::Value) {
    let run = Command::new(program)
        .args(args)
        .arg("--out")
        .arg(out)
        .current_dir(root())
        .output()
        .expect("runs");
    assert!(
        run.status.success(),
        "{}: {}",
        program.display(),
        String::from_utf8_lossy(&run.stderr)
    );
    let stdout = String::from_utf8(run.stdout)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with("wrote "))
        .collect::<Vec<_>>()
        .join("\n");
    let json = std::fs::read_to_string(out.join("results.json")).unwrap();
    (stdout, serde_json::from_str(&json).unwrap())
}

#[test]
fn the_installed_binary_reproduces_cargo_xtask_study() {
    let binary = centrifuge_cal();
    let tmp = std::env::temp_dir().join(format!("xtask-same-{}", std::process::id()));
    for args in [
        &["study"][..],
        &["study", "--config", "fixtures/studies/recordings-small.ron"][..],
    ] {
        let (xtask_out, xtask_json) = study(
            Path::new(env!("CARGO_BIN_EXE_xtask")),
            args,
            &tmp.join("xtask"),
        );
        let (cli_out, cli_json) = study(&binary, args, &tmp.join("cli"));
        assert!(xtask_out.contains("C_r"), "{xtask_out}");
        assert_eq!(xtask_out, cli_out, "{args:?}");
        assert_eq!(xtask_json, cli_json, "{args:?}");
    }
    std::fs::remove_dir_all(&tmp).unwrap();
}
