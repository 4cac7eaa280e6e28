//! First-harmonic phasors in the spindle frame and their static/dynamic fit (eq. 1–4, 20–22).

use harmonics::{LeverGeometry, ProbeDirection};
use identify::{Design, LstsqOptions, lstsq_design};
use nalgebra::DMatrix;

use crate::error::{BalanceError, Result, finite_result};

/// A vector in the spindle's horizontal plane, `x` along `O2X2` (the arm towards the PIGA),
/// `y` along `O2Y2`, with the 2×2 covariance of its components. Read as the complex number
/// `x + i·y`; its azimuth is measured from `O2X2` towards `O2Y2`.
///
/// The unit is the one of the quantity it stands for and is named where it is used
/// (`static_probe_um`, `dynamic_piga_um_s2`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Phasor {
    /// Component along `O2X2`.
    pub x: f64,
    /// Component along `O2Y2`.
    pub y: f64,
    /// Covariance `[[var x, cov xy], [cov xy, var y]]`.
    pub covariance: [[f64; 2]; 2],
}

impl Phasor {
    /// An exact phasor (zero covariance).
    #[must_use]
    pub const fn exact(x: f64, y: f64) -> Self {
        Self {
            x,
            y,
            covariance: [[0.0; 2]; 2],
        }
    }

    /// `√(x² + y²)`.
    #[must_use]
    pub fn magnitude(&self) -> f64 {
        self.x.hypot(self.y)
    }

    /// Azimuth from `O2X2` towards `O2Y2`, degrees in (−180, 180].
    #[must_use]
    pub fn azimuth_deg(&self) -> f64 {
        self.y.atan2(self.x).to_degrees()
    }

    /// Standard uncertainty of the magnitude (first order: the variance along the phasor's
    /// direction). For a zero phasor, the RMS of the two principal standard deviations.
    #[must_use]
    pub fn magnitude_sigma(&self) -> f64 {
        let m = self.magnitude();
        if m == 0.0 {
            return (0.5 * (self.covariance[0][0] + self.covariance[1][1]))
                .max(0.0)
                .sqrt();
        }
        quadratic(&self.covariance, self.x / m, self.y / m).sqrt()
    }

    /// Standard uncertainty of the azimuth, degrees (first order: the standard deviation
    /// across the phasor divided by its magnitude; 180 for a zero phasor).
    #[must_use]
    pub fn azimuth_sigma_deg(&self) -> f64 {
        let m = self.magnitude();
        if m == 0.0 {
            return 180.0;
        }
        let across = quadratic(&self.covariance, -self.y / m, self.x / m).sqrt();
        (across / m).min(std::f64::consts::PI).to_degrees()
    }

    /// The largest standard deviation over all directions (square root of the largest
    /// eigenvalue of the covariance).
    #[must_use]
    pub fn max_sigma(&self) -> f64 {
        let [[a, b], [_, d]] = self.covariance;
        let mean = 0.5 * (a + d);
        let half = (0.5 * (a - d)).hypot(b);
        (mean + half).max(0.0).sqrt()
    }

    /// The phasor times a real factor.
    #[must_use]
    pub fn scaled(&self, k: f64) -> Self {
        let c = self.covariance;
        Self {
            x: k * self.x,
            y: k * self.y,
            covariance: [
                [k * k * c[0][0], k * k * c[0][1]],
                [k * k * c[1][0], k * k * c[1][1]],
            ],
        }
    }

    /// `self + other` for independent phasors (the covariances add).
    #[must_use]
    pub fn plus(&self, other: &Self) -> Self {
        self.plus_independent(other)
    }

    /// The complex product `c·self`, with `c` taken as exact.
    #[must_use]
    pub(crate) fn times(&self, c: Complex) -> Self {
        let (x, y) = c.mul(Complex::new(self.x, self.y)).parts();
        Self {
            x,
            y,
            covariance: c.propagate(&self.covariance),
        }
    }

    /// `self + other` for independent phasors.
    #[must_use]
    pub(crate) fn plus_independent(&self, other: &Self) -> Self {
        let mut covariance = self.covariance;
        for (row, other_row) in covariance.iter_mut().zip(&other.covariance) {
            for (v, w) in row.iter_mut().zip(other_row) {
                *v += w;
            }
        }
        Self {
            x: self.x + other.x,
            y: self.y + other.y,
            covariance,
        }
    }

    pub(crate) fn value(&self) -> Complex {
        Complex::new(self.x, self.y)
    }

    pub(crate) fn is_finite(&self) -> bool {
        self.x.is_finite()
            && self.y.is_finite()
            && self.covariance.iter().flatten().all(|v| v.is_finite())
    }
}

/// `uᵀ·C·u`.
fn quadratic(c: &[[f64; 2]; 2], u0: f64, u1: f64) -> f64 {
    (u0 * (c[0][0] * u0 + c[0][1] * u1) + u1 * (c[1][0] * u0 + c[1][1] * u1)).max(0.0)
}

/// A complex number (the crate's few complex operations, without a dependency).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Complex {
    pub(crate) re: f64,
    pub(crate) im: f64,
}

impl Complex {
    pub(crate) const fn new(re: f64, im: f64) -> Self {
        Self { re, im }
    }
    pub(crate) fn from_polar(r: f64, theta_rad: f64) -> Self {
        let (s, c) = theta_rad.sin_cos();
        Self::new(r * c, r * s)
    }
    pub(crate) fn parts(self) -> (f64, f64) {
        (self.re, self.im)
    }
    pub(crate) fn abs(self) -> f64 {
        self.re.hypot(self.im)
    }
    pub(crate) fn add(self, o: Self) -> Self {
        Self::new(self.re + o.re, self.im + o.im)
    }
    pub(crate) fn sub(self, o: Self) -> Self {
        Self::new(self.re - o.re, self.im - o.im)
    }
    pub(crate) fn mul(self, o: Self) -> Self {
        Self::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    /// `self / o`; the caller makes sure that `o` is not zero.
    pub(crate) fn div(self, o: Self) -> Self {
        // Smith's algorithm: no overflow for large components
        if o.re.abs() >= o.im.abs() {
            let r = o.im / o.re;
            let d = o.re + o.im * r;
            Self::new((self.re + self.im * r) / d, (self.im - self.re * r) / d)
        } else {
            let r = o.re / o.im;
            let d = o.re * r + o.im;
            Self::new((self.re * r + self.im) / d, (self.im * r - self.re) / d)
        }
    }
    pub(crate) fn neg(self) -> Self {
        Self::new(-self.re, -self.im)
    }
    /// The covariance of `self·z` for a 2-vector `z` of covariance `c`: `M·C·Mᵀ` with
    /// `M = [[re, −im], [im, re]]`.
    pub(crate) fn propagate(self, c: &[[f64; 2]; 2]) -> [[f64; 2]; 2] {
        let m = [[self.re, -self.im], [self.im, self.re]];
        let mut out = [[0.0; 2]; 2];
        for (i, row) in out.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (0..2)
                    .flat_map(|k| (0..2).map(move |l| (k, l)))
                    .map(|(k, l)| m[i][k] * c[k][l] * m[j][l])
                    .sum();
            }
        }
        out
    }
}

/// One rate point of a probe phase: the first-harmonic coefficients of the gap (eq. 21) and,
/// when known, the standard error of each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbePoint {
    /// Spindle rate ω, rad/s.
    pub rate_rad_s: f64,
    /// `d_c1`, µm.
    pub dc1_um: f64,
    /// `d_s1`, µm.
    pub ds1_um: f64,
    /// Standard error of `d_c1` and of `d_s1` (taken equal and independent: the white-noise
    /// standard error of a Fourier coefficient), µm. `None`: unknown, estimated from the
    /// scatter of the fit.
    pub sigma_um: Option<f64>,
}

/// A probe phase: its points, where its fields live (for errors), and the probe's geometry.
#[derive(Debug, Clone, Copy)]
pub struct ProbePhase<'a> {
    /// Path of the phase in the caller's configuration, e.g. `balance.initial`; errors name
    /// `<field>.points[i].dc1_um`.
    pub field: &'a str,
    /// The rate points (at least 3 distinct rates).
    pub points: &'a [ProbePoint],
    /// Lever heights and probe direction (eq. 21–22).
    pub lever: LeverGeometry,
}

/// The optional lack-of-fit check: the same phase fitted with a term linear in ω,
/// `d1(ω) = S + B·ω + D·ω²`, which the imbalance model does not have.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LackOfFit {
    /// The linear phasor `B` at the probe plane, µm·s.
    pub linear_probe_um_s: Phasor,
    /// `|B|` in units of its own standard uncertainty along its direction (above about 3, the
    /// model `S + D·ω²` misses something: a resonance nearby, a speed-dependent run-out).
    pub linear_significance: f64,
}

/// The static and dynamic first-harmonic phasors of one probe phase (eq. 1–4 through eq. 22).
///
/// The phase's first harmonic, as a drift of the spindle axis in `O2` at the probe plane, is
/// fitted as `d1(ω) = S + D·ω²`: `S` the static (rate-independent, eq. 3–4) part in µm,
/// `D` the dynamic (∝ ω², eq. 1–2) part in µm·s². The PIGA-plane forms are these times the
/// lever ratio (the cone assumption of eq. 22, one probe). The `x` component of the dynamic
/// phasor at the PIGA plane is `C_r` (in µm·s²).
#[derive(Debug, Clone, PartialEq)]
pub struct PhasorFit {
    /// Static phasor `S` at the probe plane, µm.
    pub static_probe_um: Phasor,
    /// Dynamic phasor `D` at the probe plane, µm·s² (µm per (rad/s)²).
    pub dynamic_probe_um_s2: Phasor,
    /// `S` carried to the PIGA plane (× lever ratio), µm.
    pub static_piga_um: Phasor,
    /// `D` carried to the PIGA plane (× lever ratio), µm·s².
    pub dynamic_piga_um_s2: Phasor,
    /// Covariance of `(S_x, S_y, D_x, D_y)` at the probe plane.
    pub covariance_probe: [[f64; 4]; 4],
    /// `(h_probe + h_piga)/h_probe`.
    pub lever_ratio: f64,
    /// The measured drift phasors at the probe plane, per point, in the order given, µm.
    pub measured_probe_um: Vec<(f64, Phasor)>,
    /// Residual degrees of freedom, `2·(n − 2)`.
    pub dof: usize,
    /// `√(χ²/dof)` when the points carried standard errors, else `None`. The covariance is
    /// enlarged by it when it exceeds 1, never shrunk.
    pub reduced_chi: Option<f64>,
    /// Residual standard deviation of the drift components, µm.
    pub residual_sd_um: f64,
    /// The three-term check, when there are at least 4 rates.
    pub lack_of_fit: Option<LackOfFit>,
}

/// Minimum number of distinct rates of a phase.
pub const MIN_RATES: usize = 3;

/// Fits the static and dynamic phasors of a probe phase (complex least squares over the
/// rates, with covariance).
///
/// The gap's first harmonic is turned into the drift of the axis in `O2` at the probe plane,
/// with the encoder zero convention of eq. 21 (ωt = 0 when `O2X2` lies along `O1X1`): against
/// `O1X1` (the paper's probe), `x = −d_c1`, `y = d_s1`; along `O1X1`, `x = d_c1`,
/// `y = −d_s1`. Then `x + i·y = S + D·ω²` is fitted by least squares (the two components
/// share the design `[1, ω²]`), weighted by `1/σ²` when every point has a σ.
///
/// # Errors
/// [`BalanceError::TooFewRates`] for fewer than [`MIN_RATES`] points;
/// [`BalanceError::InvalidField`] for a non-finite coefficient or a rate that is not > 0, a
/// σ that is not > 0; [`BalanceError::DuplicateRate`]; [`BalanceError::Geometry`] for a bad
/// lever; [`BalanceError::Fit`] if the solver refuses.
pub fn fit_phasors(phase: &ProbePhase<'_>) -> Result<PhasorFit> {
    let field = phase.field;
    let points = phase.points;
    if points.len() < MIN_RATES {
        return Err(BalanceError::TooFewRates {
            field: format!("{field}.points"),
            got: points.len(),
            need: MIN_RATES,
        });
    }
    let ratio = phase
        .lever
        .lever_ratio()
        .map_err(|source| BalanceError::Geometry {
            field: format!("{field}.lever"),
            source,
        })?;
    for (i, p) in points.iter().enumerate() {
        let at = |name: &str| format!("{field}.points[{i}].{name}");
        units::positive(at("rate_rad_s"), p.rate_rad_s)?;
        units::finite(at("dc1_um"), p.dc1_um)?;
        units::finite(at("ds1_um"), p.ds1_um)?;
        if let Some(s) = p.sigma_um {
            units::positive(at("sigma_um"), s)?;
        }
        if points[..i].iter().any(|q| q.rate_rad_s == p.rate_rad_s) {
            return Err(BalanceError::DuplicateRate {
                field: format!("{field}.points[{i}].rate_rad_s"),
                rate_rad_s: p.rate_rad_s,
            });
        }
    }
    let weighted = points.iter().all(|p| p.sigma_um.is_some());
    let sign = match phase.lever.probe_direction {
        ProbeDirection::AgainstO1X1 => -1.0,
        ProbeDirection::AlongO1X1 => 1.0,
    };
    let measured: Vec<(f64, Complex)> = points
        .iter()
        .map(|p| {
            (
                p.rate_rad_s,
                Complex::new(sign * p.dc1_um, -sign * p.ds1_um),
            )
        })
        .collect();
    let weights: Vec<f64> = points
        .iter()
        .map(|p| match (weighted, p.sigma_um) {
            (true, Some(s)) => 1.0 / s,
            _ => 1.0,
        })
        .collect();

    let two = fit_components(field, &measured, &weights, &[0, 2])?;
    let n = points.len();
    let dof = 2 * (n - 2);
    let chi2: f64 = two.residual_sum_squares;
    let (scale2, reduced_chi) = if weighted {
        let r = (chi2 / dof as f64).sqrt();
        ((r * r).max(1.0), Some(r))
    } else {
        (chi2 / dof as f64, None)
    };
    let u = &two.unscaled;
    let mut covariance_probe = [[0.0; 4]; 4];
    // order (S_x, S_y, D_x, D_y): the two components are independent with the same (XᵀWX)⁻¹
    for (a, b) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
        covariance_probe[2 * a][2 * b] = scale2 * u[a][b];
        covariance_probe[2 * a + 1][2 * b + 1] = scale2 * u[a][b];
    }
    let phasor = |k: usize| Phasor {
        x: two.coefficients[k].re,
        y: two.coefficients[k].im,
        covariance: [
            [covariance_probe[2 * k][2 * k], 0.0],
            [0.0, covariance_probe[2 * k + 1][2 * k + 1]],
        ],
    };
    let static_probe_um = phasor(0);
    let dynamic_probe_um_s2 = phasor(1);

    let lack_of_fit = if n >= 4 {
        let three = fit_components(field, &measured, &weights, &[0, 1, 2])?;
        let dof3 = 2 * (n - 3);
        let s2 = if weighted {
            (three.residual_sum_squares / dof3 as f64).max(1.0)
        } else {
            three.residual_sum_squares / dof3 as f64
        };
        let var = s2 * three.unscaled[1][1];
        let b = Phasor {
            x: three.coefficients[1].re,
            y: three.coefficients[1].im,
            covariance: [[var, 0.0], [0.0, var]],
        };
        let significance = if var > 0.0 {
            b.magnitude() / var.sqrt()
        } else {
            f64::INFINITY
        };
        // an exact fit (noise-free data) has no scale to judge B by: leave the check out
        significance.is_finite().then_some(LackOfFit {
            linear_probe_um_s: b,
            linear_significance: significance,
        })
    } else {
        None
    };

    let residual_sd_um = if weighted {
        two.unweighted_rss / dof as f64
    } else {
        chi2 / dof as f64
    }
    .sqrt();
    let fit = PhasorFit {
        static_piga_um: static_probe_um.scaled(ratio),
        dynamic_piga_um_s2: dynamic_probe_um_s2.scaled(ratio),
        static_probe_um,
        dynamic_probe_um_s2,
        covariance_probe,
        lever_ratio: ratio,
        measured_probe_um: measured
            .iter()
            .zip(points)
            .map(|(&(w, z), p)| {
                let v = p.sigma_um.map_or(0.0, |s| s * s);
                (
                    w,
                    Phasor {
                        x: z.re,
                        y: z.im,
                        covariance: [[v, 0.0], [0.0, v]],
                    },
                )
            })
            .collect(),
        dof,
        reduced_chi,
        residual_sd_um,
        lack_of_fit,
    };
    let all_finite = fit.static_piga_um.is_finite()
        && fit.dynamic_piga_um_s2.is_finite()
        && fit.residual_sd_um.is_finite()
        && fit.reduced_chi.is_none_or(f64::is_finite);
    finite_result(field, if all_finite { 0.0 } else { f64::NAN })?;
    Ok(fit)
}

/// Both components fitted on one (weighted) design.
struct ComponentFit {
    coefficients: Vec<Complex>,
    /// `(XᵀWX)⁻¹`.
    unscaled: Vec<Vec<f64>>,
    /// Weighted residual sum of squares over both components.
    residual_sum_squares: f64,
    /// Unweighted residual sum of squares over both components.
    unweighted_rss: f64,
}

fn fit_components(
    field: &str,
    measured: &[(f64, Complex)],
    weights: &[f64],
    exponents: &[u32],
) -> Result<ComponentFit> {
    let n = measured.len();
    let x = DMatrix::from_fn(n, exponents.len(), |i, j| {
        weights[i] * measured[i].0.powi(exponents[j] as i32)
    });
    let design = Design::from_matrix(&x);
    let options = LstsqOptions::default();
    let solve = |y: Vec<f64>| {
        lstsq_design(&design, &y, &options).map_err(|source| BalanceError::Fit {
            field: field.to_owned(),
            source,
        })
    };
    let re = solve(
        measured
            .iter()
            .zip(weights)
            .map(|(m, w)| w * m.1.re)
            .collect(),
    )?;
    let im = solve(
        measured
            .iter()
            .zip(weights)
            .map(|(m, w)| w * m.1.im)
            .collect(),
    )?;
    let coefficients = re
        .coefficients
        .iter()
        .zip(&im.coefficients)
        .map(|(&a, &b)| Complex::new(a, b))
        .collect();
    let p = exponents.len();
    let unscaled = (0..p)
        .map(|i| (0..p).map(|j| re.unscaled_covariance[(i, j)]).collect())
        .collect();
    let rss = |f: &identify::Fit| f.residuals.iter().map(|r| r * r).sum::<f64>();
    let unweighted = |f: &identify::Fit| {
        f.residuals
            .iter()
            .zip(weights)
            .map(|(r, w)| (r / w) * (r / w))
            .sum::<f64>()
    };
    Ok(ComponentFit {
        coefficients,
        unscaled,
        residual_sum_squares: rss(&re) + rss(&im),
        unweighted_rss: unweighted(&re) + unweighted(&im),
    })
}
