//! The recording crate's decimal parser against the standard library's: the same value, bit
//! for bit, on every input; the fast path, where it answers, the same as well.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (full, fast) = recording::number_paths(data);
    let trimmed = data.trim_ascii();
    let std = std::str::from_utf8(trimmed)
        .ok()
        .and_then(|s| s.parse::<f64>().ok());
    let bits = |v: Option<f64>| v.map(|x| if x.is_nan() { u64::MAX } else { x.to_bits() });
    assert_eq!(bits(full), bits(std), "parser vs std on {trimmed:?}");
    if fast.is_some() {
        assert_eq!(bits(fast), bits(std), "fast path vs std on {trimmed:?}");
    }
});
