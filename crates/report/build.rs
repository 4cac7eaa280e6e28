//! Records the commit the crate is built from as `CENTRIFUGE_CAL_COMMIT` (a certificate
//! names the software's version and commit). An environment variable of that name wins (a
//! build from a source archive has no git); without either, the certificate says `unknown`.

use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    if !out.status.success() {
        return None;
    }
    let text = String::from_utf8(out.stdout).ok()?;
    let text = text.trim();
    (!text.is_empty()).then(|| text.to_owned())
}

fn main() {
    println!("cargo:rerun-if-env-changed=CENTRIFUGE_CAL_COMMIT");
    // rebuild when HEAD moves: HEAD itself, the branch it names, and packed refs (only paths
    // that exist: a missing one would rerun this script on every build)
    for path in [
        git(&["rev-parse", "--git-path", "HEAD"]),
        git(&["symbolic-ref", "-q", "HEAD"]).and_then(|r| git(&["rev-parse", "--git-path", &r])),
        git(&["rev-parse", "--git-path", "packed-refs"]),
    ]
    .into_iter()
    .flatten()
    .filter(|p| std::path::Path::new(p).exists())
    {
        println!("cargo:rerun-if-changed={path}");
    }
    let commit = std::env::var("CENTRIFUGE_CAL_COMMIT")
        .ok()
        .filter(|c| !c.is_empty())
        .or_else(|| git(&["rev-parse", "HEAD"]))
        .unwrap_or_else(|| "unknown".to_owned());
    println!("cargo:rustc-env=CENTRIFUGE_CAL_COMMIT={commit}");
}
