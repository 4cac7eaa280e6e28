//! Files held in memory as a study's data source.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use pipeline::DataSource;
use recording::{Recording, RecordingError, RecordingFormat, Table, TableFormat};

/// Files held in memory (path → bytes), parsed as the study asks: the study runs without
/// reading the disk. A path the study names that is not held is a panic (a test set-up
/// error). Keeps no digest (`pipeline::Loaded::digest` is `None`).
#[derive(Debug, Clone, Default)]
pub struct MemoryFiles(pub HashMap<PathBuf, Vec<u8>>);

impl MemoryFiles {
    fn bytes(&self, path: &Path) -> &[u8] {
        self.0
            .get(path)
            .unwrap_or_else(|| panic!("the study asks for {path:?}, which is not held in memory"))
    }
}

impl DataSource for MemoryFiles {
    fn recording(
        &self,
        path: &Path,
        format: &RecordingFormat,
    ) -> Result<Recording, RecordingError> {
        recording::parse_recording(self.bytes(path), path, format)
    }

    fn table(&self, path: &Path, format: &TableFormat) -> Result<Table, RecordingError> {
        recording::parse_table(self.bytes(path), path, format)
    }
}
