//! Study configuration: `StudyConfig::from_ron` and `Inputs::new` never panic on any text,
//! with a data source that refuses every file.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use recording::{Recording, RecordingError, RecordingFormat, Table, TableFormat};

/// A data source that refuses every file (the fuzz target reads no files).
struct Refuse;

impl pipeline::DataSource for Refuse {
    fn recording(&self, path: &Path, _: &RecordingFormat) -> Result<Recording, RecordingError> {
        Err(RecordingError::Empty {
            path: path.to_owned(),
        })
    }

    fn table(&self, path: &Path, _: &TableFormat) -> Result<Table, RecordingError> {
        Err(RecordingError::Empty {
            path: path.to_owned(),
        })
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = Path::new("fuzz.ron");
    let Ok(config) = pipeline::StudyConfig::from_ron(text, path) else {
        return;
    };
    let _ = pipeline::Inputs::new(config, path, &Refuse);
});
