//! `cargo xtask` is a thin wrapper: the `centrifuge-cal` binary built from crates/cli (what
//! `cargo install --path crates/cli` installs) gives the same study, byte for byte apart from
//! the output paths it prints.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The `centrifuge-cal` binary from crates/cli. `cargo test --workspace` has already built it
/// beside this test's xtask binary (cli's own tests need it); that one is used when it is newer
/// than the cli library xtask links and than every source file of crates/cli. Otherwise (this
/// test run on its own after an edit) it is built here, as `cargo build` builds it. Building it
/// here always would rebuild every workspace crate: a plain `cargo build -p cli` resolves the
/// crates' features without the tests' dev-dependency features, which costs CI minutes.
fn centrifuge_cal() -> PathBuf {
    let xtask = PathBuf::from(env!("CARGO_BIN_EXE_xtask"));
    let binary = xtask.with_file_name(format!("centrifuge-cal{}", std::env::consts::EXE_SUFFIX));
    if is_fresh(&binary, &xtask) {
        return binary;
    }
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
    assert!(binary.is_file(), "{} not built", binary.display());
    binary
}

/// Whether `binary` was built after the newest cli library in `xtask`'s `deps/` and after
/// every file under crates/cli/src.
fn is_fresh(binary: &Path, xtask: &Path) -> bool {
    let modified = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified()).ok();
    let Some(built) = modified(binary) else {
        return false;
    };
    let mut inputs = Vec::new();
    if let Some(dir) = xtask.parent() {
        let deps = dir.join("deps");
        if let Ok(entries) = std::fs::read_dir(&deps) {
            for e in entries.flatten() {
                let name = e.file_name().to_string_lossy().into_owned();
                if name.starts_with("libcli-") && name.ends_with(".rlib") {
                    inputs.push(e.path());
                }
            }
        }
    }
    if inputs.is_empty() {
        return false;
    }
    let mut stack = vec![root().join("crates/cli/src")];
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            return false;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else {
                inputs.push(p);
            }
        }
    }
    inputs
        .iter()
        .all(|p| modified(p).is_some_and(|m| m <= built))
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
