//! Means over whole revolutions by the uniform rule.

use core::f64::consts::TAU;

use crate::error::{KinematicsError, Result};

/// The uniform N-point rule over one revolution, `t_j = j·T/N`, `T = 2π/|ω|`.
///
/// For a trigonometric polynomial in the spindle angle `ωt`, of degree K, the rule returns the
/// mean over the revolution exactly (up to rounding) as soon as N > K, because
/// `Σ_j exp(i k 2π j/N) = 0` unless N divides k. Requiring N > 2K, as [`Self::new`] does, also
/// makes the samples determine the polynomial (Nyquist), so the rule remains exact for the
/// product of two such quantities of degree K.
///
/// ```
/// use approx::assert_relative_eq;
/// use kinematics::RevolutionQuadrature;
/// let w = 2.0; // rad/s
/// let q = RevolutionQuadrature::new(7, 3).unwrap();
/// // mean of (1 + cos ωt)³ over a revolution = 1 + 3/2 = 2.5
/// let m = q.mean(w, |t| (1.0 + (w * t).cos()).powi(3));
/// assert_relative_eq!(m, 2.5, max_relative = 1e-14);
/// assert!(RevolutionQuadrature::new(6, 3).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RevolutionQuadrature {
    points: usize,
}

impl RevolutionQuadrature {
    /// The smallest rule accepted for content up to `highest_harmonic`: `N = 2K + 1`.
    #[must_use]
    pub const fn minimal(highest_harmonic: usize) -> Self {
        Self {
            points: 2 * highest_harmonic + 1,
        }
    }

    /// A rule with `points` nodes, checked against the harmonic content to be averaged.
    ///
    /// # Errors
    /// [`KinematicsError::TooFewQuadraturePoints`] unless `points > 2 * highest_harmonic`.
    pub const fn new(points: usize, highest_harmonic: usize) -> Result<Self> {
        let need = 2 * highest_harmonic + 1;
        if points < need {
            return Err(KinematicsError::TooFewQuadraturePoints {
                points,
                highest_harmonic,
                need,
            });
        }
        Ok(Self { points })
    }

    /// Number of nodes per revolution.
    #[must_use]
    pub const fn points(&self) -> usize {
        self.points
    }

    /// The node times over the first revolution at `rate_rad_s`, in seconds. At zero rate (or
    /// a rate so small that its period overflows) the motion does not depend on time within
    /// double precision and the single node `t = 0` is returned.
    pub fn sample_times_s(&self, rate_rad_s: f64) -> impl Iterator<Item = f64> + use<> {
        let step = TAU / rate_rad_s.abs() / self.points as f64;
        let (n, step) = if step.is_finite() {
            (self.points, step)
        } else {
            (1, 0.0)
        };
        (0..n).map(move |j| j as f64 * step)
    }

    /// Mean of `f(t)` over one revolution at `rate_rad_s`.
    pub fn mean<F: FnMut(f64) -> f64>(&self, rate_rad_s: f64, mut f: F) -> f64 {
        self.mean_array(rate_rad_s, |t| [f(t)])[0]
    }

    /// Component-wise mean of a vector-valued `f(t)` over one revolution.
    pub fn mean_array<const M: usize, F: FnMut(f64) -> [f64; M]>(
        &self,
        rate_rad_s: f64,
        mut f: F,
    ) -> [f64; M] {
        let mut sum = [0.0; M];
        let mut n = 0usize;
        for t in self.sample_times_s(rate_rad_s) {
            for (s, v) in sum.iter_mut().zip(f(t)) {
                *s += v;
            }
            n += 1;
        }
        sum.map(|s| s / n as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn exact_up_to_the_declared_harmonic() {
        let w = -1.7; // negative rates are fine
        for k in 0..6usize {
            let q = RevolutionQuadrature::minimal(k);
            // a trigonometric polynomial of degree k with known mean 0.3
            let m = q.mean(w, |t| {
                0.3 + (1..=k)
                    .map(|i| (i as f64 * w * t + 0.2 * i as f64).cos())
                    .sum::<f64>()
            });
            assert!((m - 0.3).abs() < 1e-14, "k = {k}: {m}");
        }
    }

    #[test]
    fn too_few_points_is_a_typed_error() {
        assert_eq!(
            RevolutionQuadrature::new(4, 2),
            Err(KinematicsError::TooFewQuadraturePoints {
                points: 4,
                highest_harmonic: 2,
                need: 5
            })
        );
    }

    #[test]
    fn zero_rate_is_a_single_node() {
        let q = RevolutionQuadrature::minimal(3);
        assert_eq!(q.sample_times_s(0.0).collect::<Vec<_>>(), vec![0.0]);
        assert_relative_eq!(q.mean(0.0, |_| 4.0), 4.0);
    }

    #[test]
    fn a_subnormal_rate_is_taken_as_zero_not_nan() {
        let q = RevolutionQuadrature::minimal(1);
        let times: Vec<f64> = q.sample_times_s(1e-318).collect();
        assert_eq!(times, vec![0.0]);
        assert!(q.mean(1e-318, |t| t + 1.0).is_finite());
    }
}
