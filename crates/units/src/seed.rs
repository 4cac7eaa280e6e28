//! The one seeding convention of the workspace: a user's seed and the labels of a stream
//! (a purpose, a rate, a batch, a chunk, a campaign) give that stream's own seed.
//!
//! [`stream_seed`] mixes them through the SplitMix64 finaliser (Steele, Lea & Flood 2014), so
//! neighbouring labels give unrelated seeds and a stream does not depend on how many others
//! are drawn, or in which order or thread. The generator (`StdRng` in `simulate`,
//! xoshiro256++ in `uncertainty`) is seeded with `seed_from_u64(stream_seed(…))`. Not a
//! sum: `seed + n` makes the streams of two neighbouring seeds overlap.

/// The seed of the stream labelled `(a, b)` under the user's `seed`.
///
/// ```
/// let s = units::stream_seed(42, 0, 0);
/// assert_eq!(s, units::stream_seed(42, 0, 0)); // a fixed function of its inputs
/// assert_ne!(s, units::stream_seed(42, 0, 1));
/// assert_ne!(s, units::stream_seed(43, 0, 0));
/// ```
#[must_use]
pub const fn stream_seed(seed: u64, a: u64, b: u64) -> u64 {
    let mut z =
        seed ^ a.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ b.wrapping_mul(0xD1B5_4A32_D192_ED03);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbouring_labels_differ_in_about_half_their_bits() {
        // A finaliser, not a sum: seed + 1 and label + 1 do not give related seeds.
        for (x, y) in [
            (stream_seed(7, 0, 0), stream_seed(7, 0, 1)),
            (stream_seed(7, 0, 0), stream_seed(7, 1, 0)),
            (stream_seed(7, 0, 0), stream_seed(8, 0, 0)),
        ] {
            let differing = (x ^ y).count_ones();
            assert!((16..=48).contains(&differing), "{differing} bits differ");
        }
    }
}
