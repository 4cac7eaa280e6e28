//! NIST StRD parser: no panic on any text; a dataset it accepts is solved without a panic
//! and an `Ok` fit is finite.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(dataset) = identify::strd::parse(text) else {
        return;
    };
    if let Ok(accuracy) = dataset.check(&identify::LstsqOptions::default()) {
        let fit = &accuracy.fit;
        assert!(fit.coefficients.iter().chain(&fit.std_errors).all(|v| v.is_finite()));
        assert!(fit.residual_sd.is_finite());
    }
});
