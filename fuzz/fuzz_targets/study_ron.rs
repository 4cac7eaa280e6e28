//! Study configuration: `StudyConfig::from_ron` and `Inputs::new` never panic on any text,
//! with recordings "loaded" by a loader that refuses every file.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = Path::new("fuzz.ron");
    let Ok(config) = pipeline::StudyConfig::from_ron(text, path) else {
        return;
    };
    let refuse = |file: &Path, _: &recording::RecordingFormat| {
        Err(recording::RecordingError::Empty {
            path: file.to_owned(),
        })
    };
    let _ = pipeline::Inputs::new(config, path, &refuse);
});
