//! `cargo xtask`: the centrifuge-cal command line inside the checkout. It runs the `cli`
//! crate's commands with the workspace's defaults (the paper's study, outputs in `target/`).

// One feature set with the tests' build (crates/workspace-hack).
use workspace_hack as _;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn main() -> ExitCode {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    ExitCode::from(cli::run_with(
        &cli::Places::xtask(root),
        std::env::args_os(),
    ))
}
