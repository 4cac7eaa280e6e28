//! The candidates of a search: their scaled design rows, seconds per revolution and weight
//! per second (a leaf: used by the inputs' validation and by the exchange search alike).

use nalgebra::SVector;

/// The candidates of a search: their design rows, each column divided by its largest
/// magnitude over the candidates, with `N` coefficients, their seconds per revolution and
/// their weight per second of recording.
#[derive(Debug, Clone)]
pub(crate) struct Grid<const N: usize> {
    /// Scaled design rows: the row is `x·scale`.
    pub(crate) x: Vec<SVector<f64, N>>,
    /// Column scales (a column of zeros: 1).
    pub(crate) scale: [f64; N],
    /// Seconds per revolution of each candidate.
    pub(crate) tau_s: Vec<f64>,
    /// Weight (1/variance of the mean output) per second of recording of each candidate,
    /// 1/(rad/s)².
    pub(crate) info_per_s: Vec<f64>,
}

impl<const N: usize> Grid<N> {
    /// The candidates at `rates_rad_s` with design rows `rows`, and the weight per second of
    /// recording a revolution of `τ` seconds gives (`info_per_s(τ)`, the PIGA's noise).
    pub(crate) fn new(
        rates_rad_s: &[f64],
        rows: &[[f64; N]],
        info_per_s: impl Fn(f64) -> f64,
    ) -> Self {
        let mut scale = [0.0_f64; N];
        for r in rows {
            for (s, v) in scale.iter_mut().zip(r) {
                *s = s.max(v.abs());
            }
        }
        for s in &mut scale {
            if *s == 0.0 {
                *s = 1.0;
            }
        }
        let x = rows
            .iter()
            .map(|r| SVector::from_fn(|j, _| r[j] / scale[j]))
            .collect();
        let tau_s: Vec<f64> = rates_rad_s
            .iter()
            .map(|w| std::f64::consts::TAU / w)
            .collect();
        let info_per_s = tau_s.iter().map(|&t| info_per_s(t)).collect();
        Grid {
            x,
            scale,
            tau_s,
            info_per_s,
        }
    }
}
