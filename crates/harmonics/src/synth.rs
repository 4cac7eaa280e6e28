//! Deterministic synthetic probe recordings with known coefficients, for tests, benchmarks
//! and fixtures.

use std::f64::consts::TAU;

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
    /// Standard deviation of white Gaussian noise added to the gap.
    pub noise_std: f64,
    /// Amplitude `A` of the non-uniform part of the angle, rad.
    pub wobble_rad: f64,
    /// Seed of the noise.
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
    pub fn generate(&self) -> SyntheticSamples {
        let mut rng = SplitMix64(self.seed);
        let mut time_s = Vec::with_capacity(self.samples);
        let mut gap = Vec::with_capacity(self.samples);
        let mut angle_rad = Vec::with_capacity(self.samples);
        for i in 0..self.samples {
            let t = self.start_time_s + i as f64 / self.sample_rate_hz;
            let theta = self.angle_at(t);
            let drift = self.coefficients.drift_per_s.unwrap_or(0.0) * (t - self.start_time_s);
            let noise = if self.noise_std > 0.0 {
                self.noise_std * rng.normal()
            } else {
                0.0
            };
            time_s.push(t);
            gap.push(self.coefficients.evaluate(theta) + drift + noise);
            angle_rad.push(theta.rem_euclid(TAU));
        }
        SyntheticSamples {
            time_s,
            gap,
            angle_rad,
        }
    }
}

/// SplitMix64 generator with Box–Muller normals: small, deterministic, dependency-free.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1].
    fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 1.0) / (1_u64 << 53) as f64
    }

    fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (TAU * v).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normals_have_unit_variance() {
        let mut g = SplitMix64(7);
        let n = 200_000;
        let xs: Vec<f64> = (0..n).map(|_| g.normal()).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        assert!(mean.abs() < 0.01, "mean {mean}");
        assert!((var - 1.0).abs() < 0.01, "variance {var}");
    }
}
