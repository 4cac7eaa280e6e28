//! Where a command finds its defaults: the source checkout (the paper's study, the expected
//! values, the NIST datasets) and the folder its default outputs go into.

use std::path::{Path, PathBuf};

use anyhow::Context as _;

/// The defaults of one way of running the command line.
///
/// `cargo xtask` runs inside a checkout: the defaults live in the workspace and outputs go
/// into the workspace's `target/`. The installed `centrifuge-cal` takes the paper's study and
/// the expected values from the checkout it was built from (when that is still there), and
/// writes default outputs under `target/` in the current directory.
#[derive(Debug, Clone)]
pub struct Places {
    program: &'static str,
    checkout: Option<PathBuf>,
    output_root: PathBuf,
}

/// The checkout this crate was built from, if it still holds the fixtures.
fn built_from() -> Option<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    root.join("fixtures/studies/paper-2025.ron")
        .is_file()
        .then(|| root.canonicalize().unwrap_or(root))
}

impl Places {
    /// `cargo xtask` in the checkout at `workspace_root`.
    #[must_use]
    pub fn xtask(workspace_root: PathBuf) -> Self {
        Self {
            program: "cargo xtask",
            output_root: workspace_root.join("target"),
            checkout: Some(workspace_root),
        }
    }

    /// The installed `centrifuge-cal` (and the Python package's console script): defaults
    /// from the checkout it was built from, outputs under `target/` of the current directory.
    #[must_use]
    pub fn installed() -> Self {
        Self {
            program: "centrifuge-cal",
            checkout: built_from(),
            output_root: PathBuf::from("target"),
        }
    }

    /// The program's name as a user types it (`cargo xtask` or `centrifuge-cal`).
    #[must_use]
    pub fn program(&self) -> &'static str {
        self.program
    }

    /// The paper's study configuration.
    pub(crate) fn paper_study(&self) -> anyhow::Result<PathBuf> {
        self.checkout
            .as_ref()
            .map(|root| root.join("fixtures/studies/paper-2025.ron"))
            .filter(|p| p.is_file())
            .context(
                "no --config given, and the paper's study (fixtures/studies/paper-2025.ron of \
                 the source checkout) is not where this program was built; give --config FILE",
            )
    }

    /// The expected values of a fixture study: `fixtures/expected/<same file name>` when the
    /// configuration is one of the checkout's `fixtures/studies/` (a lab's own study of the
    /// same file name is not compared with a fixture's values).
    pub(crate) fn expected_for(&self, config: &Path) -> Option<PathBuf> {
        let root = self.checkout.as_ref()?;
        let studies = root.join("fixtures/studies").canonicalize().ok()?;
        let folder = config.canonicalize().ok()?.parent()?.to_path_buf();
        if folder != studies {
            return None;
        }
        let candidate = root.join("fixtures/expected").join(config.file_name()?);
        candidate.is_file().then_some(candidate)
    }

    /// The NIST StRD datasets beside the checkout (`../shared/reference/nist-strd`).
    pub(crate) fn nist_strd(&self) -> Option<PathBuf> {
        self.checkout
            .as_ref()
            .map(|root| root.join("../shared/reference/nist-strd"))
    }

    /// A default output directory: `target/NAME` (see [`Places`]).
    pub(crate) fn output(&self, name: &str) -> PathBuf {
        self.output_root.join(name)
    }
}
