//! Deterministic synthetic probe recordings with known coefficients, for tests, benchmarks
//! and fixtures (feature `synthetic`).

use std::f64::consts::TAU;

use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};

use crate::analysis::Coefficients;

/// A recipe for a synthetic recording: the gap follows eq. 20 with the given coefficients at
/// the spindle's true angle, plus optional drift and Gaussian noise.
///
/// The true angle is `θ(t) = θ₀ + ω t + A sin(ω t / 3)`; with a wobble `A ≠ 0` the spindle
/// does not turn uniformly, so only the encoder angle (returned with the samples) describes
/// it. The wobble must keep the angle increasing: `A/3 < 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticRecording {
    /// Spindle rate `ω`, rad/s.
    pub rate_rad_s: f64,
    /// Sample rate, Hz.
    pub sample_rate_hz: f64,
    /// Number of samples.
    pub samples: usize,
    /// Time of the first sample, s.
    pub start_time_s: f64,
    /// Angle `θ₀` of the first sample from O1X1, rad.
    pub start_angle_rad: f64,
    /// The coefficients of eq. 20 (`drift_per_s` adds `drift·(t − start_time_s)`).
    pub coefficients: Coefficients,
    /// Standard deviation of white Gaussian noise added to the gap, in the gap's unit (finite
    /// and not negative; zero adds none).
    pub noise_std: f64,
    /// Amplitude `A` of the non-uniform part of the angle, rad.
    pub wobble_rad: f64,
    /// Seed of the noise (`rand`'s `StdRng::seed_from_u64`).
    pub seed: u64,
}

/// The samples of a synthetic recording.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticSamples {
    /// Sample times, s.
    pub time_s: Vec<f64>,
    /// Gap of each sample.
    pub gap: Vec<f64>,
    /// Encoder angle of each sample, rad, wrapped into `[0, 2π)`.
    pub angle_rad: Vec<f64>,
}

impl SyntheticRecording {
    /// The true (unwrapped) spindle angle at time `t`.
    pub fn angle_at(&self, t_s: f64) -> f64 {
        let wt = self.rate_rad_s * (t_s - self.start_time_s);
        self.start_angle_rad + wt + self.wobble_rad * (wt / 3.0).sin()
    }

    /// Generates the samples.
    ///
    /// # Panics
    /// When `noise_std` is negative or not finite.
    pub fn generate(&self) -> SyntheticSamples {
        assert!(
            self.noise_std.is_finite() && self.noise_std >= 0.0,
            "noise_std must be finite and not negative, got {}",
            self.noise_std
        );
        let mut rng = StdRng::seed_from_u64(self.seed);
        // Without noise, no draws at all.
        let noise = (self.noise_std > 0.0).then(|| {
            Normal::new(0.0, self.noise_std).expect("a finite standard deviation is accepted")
        });
        let mut time_s = Vec::with_capacity(self.samples);
        let mut gap = Vec::with_capacity(self.samples);
        let mut angle_rad = Vec::with_capacity(self.samples);
        for i in 0..self.samples {
            let t = self.start_time_s + i as f64 / self.sample_rate_hz;
            let theta = self.angle_at(t);
            let drift = self.coefficients.drift_per_s.unwrap_or(0.0) * (t - self.start_time_s);
            let e = noise.map_or(0.0, |n| n.sample(&mut rng));
            time_s.push(t);
            gap.push(self.coefficients.evaluate(theta) + drift + e);
            angle_rad.push(theta.rem_euclid(TAU));
        }
        SyntheticSamples {
            time_s,
            gap,
            angle_rad,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn recording(noise_std: f64, seed: u64) -> SyntheticRecording {
        SyntheticRecording {
            rate_rad_s: 1.0,
            sample_rate_hz: 100.0,
            samples: 200_000,
            start_time_s: 0.0,
            start_angle_rad: 0.0,
            coefficients: Coefficients {
                l0: 5.0,
                c: vec![0.0],
                s: vec![0.0],
                drift_per_s: None,
            },
            noise_std,
            wobble_rad: 0.0,
            seed,
        }
    }

    #[test]
    fn noise_has_the_given_standard_deviation() {
        let rec = recording(0.5, 7);
        let gap = rec.generate().gap;
        let n = gap.len() as f64;
        let mean = gap.iter().sum::<f64>() / n;
        let var = gap.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
        // standard errors: 0.5/√n ≈ 1.1e-3 for the mean, 0.25·√(2/n) ≈ 7.9e-4 for the variance
        assert!((mean - 5.0).abs() < 0.01, "mean {mean}");
        assert!((var - 0.25).abs() < 0.01, "variance {var}");
    }

    #[test]
    fn same_seed_same_samples_and_no_noise_is_exact() {
        let a = recording(0.5, 7);
        assert_eq!(a.generate(), a.generate());
        assert_ne!(a.generate().gap, recording(0.5, 8).generate().gap);
        assert!(recording(0.0, 7).generate().gap.iter().all(|&g| g == 5.0));
    }
}
