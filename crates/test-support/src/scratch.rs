//! A scratch directory for a test.

use std::path::{Path, PathBuf};

/// A fresh directory under the system temp directory (`centrifuge-cal-<name>-<process id>`,
/// emptied first), removed with its contents on drop. Tests of one binary run in one process
/// and in parallel: give each its own `name`.
#[derive(Debug)]
pub struct Scratch(pub PathBuf);

impl Scratch {
    /// Creates the directory.
    ///
    /// # Panics
    /// When the directory cannot be created (a test set-up failure).
    #[must_use]
    pub fn new(name: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("centrifuge-cal-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("a scratch directory under the temp directory");
        Self(dir)
    }

    /// The directory.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_directory_exists_until_dropped() {
        let scratch = Scratch::new("test-support-self");
        let dir = scratch.path().to_owned();
        std::fs::write(dir.join("a.txt"), "a").unwrap();
        assert!(dir.join("a.txt").is_file());
        drop(scratch);
        assert!(!dir.exists());
    }
}
