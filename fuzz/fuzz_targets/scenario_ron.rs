//! Simulation scenario: `Scenario::parse` never panics on any text, and what it accepts
//! passes its own check again.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(loaded) = simulate::Scenario::parse(text, Path::new("fuzz.ron")) {
        assert!(loaded.scenario.check(&loaded.path).is_ok());
    }
});
