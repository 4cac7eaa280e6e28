//! The simulator's noise: one independent random stream per (seed, purpose, rate), the
//! purposes that keep the probe's, the PIGA's and each mounting's draws apart, and the white
//! noise on a PIGA table's mean outputs.

use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};

use crate::mounting::Orientation;

/// Stream tags that keep the random streams of the probe and the PIGA independent of each
/// other; each rate has its own streams, keyed by its value, so that adding, removing or
/// reordering rates leaves the noise of the others unchanged.
pub(super) const PROBE_STREAM: u64 = 1;
pub(super) const PIGA_STREAM: u64 = 2;
pub(super) const PIGA_RECORDING_STREAM: u64 = 3;
pub(super) const SECOND_PROBE_STREAM: u64 = 4;
/// The mountings' tables and raw recordings: one stream each per orientation.
pub(super) const MOUNTING_STREAM: [u64; 2] = [5, 6];
pub(super) const MOUNTING_RECORDING_STREAM: [u64; 2] = [7, 8];

/// Index of an orientation in the mounting stream tables.
pub(super) const fn orientation_index(o: Orientation) -> usize {
    match o {
        Orientation::IaIn => 0,
        Orientation::IaOut => 1,
    }
}

/// White noise on the PIGA's per-rate mean output: N(0, σ²), one independent stream per rate
/// drawn from the seed (the simulator's one noise model for PIGA tables).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputNoise {
    /// Standard deviation, rad/s (0: noise-free; must be finite and ≥ 0).
    pub sigma_rad_s: f64,
    /// Seed of the streams.
    pub seed: u64,
}

impl OutputNoise {
    /// `output_rad_s` plus this rate's draw.
    pub(super) fn added_to(&self, output_rad_s: f64, rate_deg_s: f64) -> f64 {
        self.added_to_stream(PIGA_STREAM, output_rad_s, rate_deg_s)
    }

    /// `output_rad_s` plus this rate's draw from the stream `purpose`.
    pub(super) fn added_to_stream(&self, purpose: u64, output_rad_s: f64, rate_deg_s: f64) -> f64 {
        let mut rng = stream(self.seed, purpose, rate_deg_s.to_bits());
        output_rad_s + normal(self.sigma_rad_s).map_or(0.0, |d| d.sample(&mut rng))
    }
}

/// An independent random stream per (seed, purpose, key): the workspace's one seeding
/// convention, [`units::stream_seed`].
pub(super) fn stream(seed: u64, purpose: u64, key: u64) -> StdRng {
    StdRng::seed_from_u64(units::stream_seed(seed, purpose, key))
}

/// N(0, σ²), or `None` (no draws at all) when σ is 0.
pub(super) fn normal(sigma: f64) -> Option<Normal<f64>> {
    // σ was validated finite and ≥ 0, so `Normal::new` cannot fail
    (sigma > 0.0)
        .then(|| Normal::new(0.0, sigma).ok())
        .flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_distinct_and_repeatable() {
        use rand::Rng;
        let a: u64 = stream(7, PROBE_STREAM, 0).random();
        let b: u64 = stream(7, PROBE_STREAM, 1).random();
        let c: u64 = stream(7, PIGA_STREAM, 0).random();
        let a2: u64 = stream(7, PROBE_STREAM, 0).random();
        assert_eq!(a, a2);
        assert_ne!(a, b);
        assert_ne!(a, c);
    }
}
