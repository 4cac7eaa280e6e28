//! The joint least-squares fit of eq. 23 to the two data sets: the checks of the data, the
//! fit, and the coefficients and C it gives.

use identify::{Fit, LstsqOptions};

use super::error::TwoOrientationError;
use super::terms::{
    B3_TERM, GAMMA_TERM, K2_INFLATION_LIMIT, K2_TERM, K3_TERM, MIN_RATES_PER_ORIENTATION,
    Orientation, OrientationData, TWO_ORIENTATION_TERMS, distinct, index, two_orientation_terms,
};

/// One mounting's own coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MountingFit {
    /// IA in or out.
    pub orientation: Orientation,
    /// Its static radius, m.
    pub radius_m: f64,
    /// Distinct rates in its data set.
    pub distinct_rates: usize,
    /// `k0,s` (bias with the gravity seen through the tilt), rad/s, and its standard error.
    pub k0_rad_s: (f64, f64),
    /// `b1,s` (the ω nuisance term: tilt, Coriolis, alignment), and its standard error.
    pub b1: (f64, f64),
    /// `k1,s`, rad/(s·g), and its standard error.
    pub k1_rad_s_g: (f64, f64),
}

/// The joint fit of eq. 23.
#[derive(Debug, Clone, PartialEq)]
pub struct TwoOrientationFit {
    /// IA in, then IA out.
    pub mountings: [MountingFit; 2],
    /// `k2` from the PIGA alone, rad/(s·g²), and its standard error.
    pub k2_rad_s_g2: (f64, f64),
    /// `k3`, rad/(s·g³), and its standard error.
    pub k3_rad_s_g3: (f64, f64),
    /// `b3` (ω³ nuisance term), and its standard error.
    pub b3: (f64, f64),
    /// `γ = k1·C/g` (coefficient of `s·ω⁴`), rad·s³, and its standard error.
    pub gamma: (f64, f64),
    /// `C = γ·g/k̄1`, m·s², with `k̄1` the mean of the two `k1,s`, and its standard error
    /// (first order, from the fit's covariance).
    pub c_m_s2: (f64, f64),
    /// `Δk2,total = k̄1·C·g/R_in²` at the IA-in radius, rad/(s·g²), and its standard error.
    pub delta_k2_total_rad_s_g2: (f64, f64),
    /// Variance inflation factor of the `s·ω⁴` column (a diagnostic: about 1e6 on every
    /// ordinary design, where C is well determined).
    pub gamma_vif: f64,
    /// Correlation of the k2 and γ (hence C) estimates in the joint fit.
    pub k2_gamma_correlation: f64,
    /// u(k2) in the joint fit over u(k2) in the same fit with γ known (the `s·ω⁴` column
    /// dropped): `1/√(1 − ρ²)`, ρ = [`TwoOrientationFit::k2_gamma_correlation`]. What fitting C
    /// costs k2; the study warns above [`K2_INFLATION_LIMIT`](crate::K2_INFLATION_LIMIT).
    pub k2_inflation: f64,
    /// Gravity used to form `a_s`, m/s².
    pub g_m_s2: f64,
    /// Residuals `output − fitted`, rad/s, IA in's points then IA out's, each in its data
    /// set's order.
    pub residuals_rad_s: [Vec<f64>; 2],
    /// Birge ratio `√(χ²/ν)` of a weighted fit (`None` unweighted).
    pub birge_ratio: Option<f64>,
    /// The fit's coefficients for a term `ω⁶` of the same sign in both mountings (a column
    /// eq. 23 does not have): the least-squares projection `X⁺·ω⁶` through the same QR (and
    /// weights). [`TwoOrientationModel`](crate::TwoOrientationModel) uses it for what a change of the
    /// radii does to the shared `s·a_s³` column that no rescaling of k3 absorbs
    /// (`docs/theory.md` section 11).
    pub omega6_response: [f64; TWO_ORIENTATION_TERMS],
    /// The fit's coefficients for the term eq. 23 leaves out where k2 meets the Earth rate:
    /// the specific force along the arm is `R·(ω + Ω_a)²/g`, with `Ω_a` the Earth rate about
    /// the spindle axis signed by the spin, so `k2·a_s²` carries `k2·Ω_a·4·R_s²·ω³/g²`, of the
    /// same sign in both mountings (no column of eq. 23 takes it). This is `X⁺·v`,
    /// `v = 4·R_s²·ω³/g²`, through the same QR (and weights): the data hold
    /// `β + k2·Ω_a·X⁺·v` where the fit reports β, and
    /// [`TwoOrientationModel`](crate::TwoOrientationModel) removes it for the `Ω_a` stated
    /// (or takes it as an uncertainty when it is not: issue 31).
    pub earth_rate_response: [f64; TWO_ORIENTATION_TERMS],
    /// The least-squares fit (coefficients in [`TWO_ORIENTATION_TERM_NAMES`](crate::TWO_ORIENTATION_TERM_NAMES)' order; for a weighted
    /// fit the covariance is `(XᵀWX)⁻¹` times the squared Birge ratio when above 1).
    pub fit: Fit,
}

impl TwoOrientationFit {
    /// Degrees of freedom of the fit's coefficients as an input group, by the one-mounting
    /// calibration's policy ([`crate::Weighting::group_dof`]): infinite when the points' σ are
    /// taken as known (a weighted fit whose Birge ratio is at most 1, its covariance
    /// `(XᵀWX)⁻¹` not scaled by the residuals), else the fit's `n − 10`.
    #[must_use]
    pub fn coefficients_dof(&self) -> uncertainty::Dof {
        match self.birge_ratio {
            Some(b) if b <= 1.0 => uncertainty::Dof::Infinite,
            _ => uncertainty::Dof::Finite(self.fit.dof as f64),
        }
    }

    /// Whether the `s·ω⁴` term (C) can be told apart from k2: fitting it widens u(k2) by no
    /// more than [`K2_INFLATION_LIMIT`](crate::K2_INFLATION_LIMIT). (Until issue 20's review
    /// this was "VIF ≤ 1e4", which no ordinary design meets.)
    #[must_use]
    pub fn separable(&self) -> bool {
        self.k2_inflation <= K2_INFLATION_LIMIT
    }

    /// The mounting of an orientation.
    #[must_use]
    pub const fn mounting(&self, o: Orientation) -> &MountingFit {
        &self.mountings[index(o)]
    }
}

/// Checks the data sets and returns them as (IA in, IA out) with their radii.
fn check<'a>(
    data: &[OrientationData<'a>],
    list_field: &str,
) -> Result<[(OrientationData<'a>, f64); 2], TwoOrientationError> {
    let describe = |d: &[OrientationData<'_>]| {
        let words: Vec<&str> = d
            .iter()
            .map(|x| x.orientation.map_or("undeclared", Orientation::label))
            .collect();
        if words.is_empty() {
            "no data set".to_owned()
        } else {
            format!("{} data set(s): {}", d.len(), words.join(", "))
        }
    };
    for d in data {
        if d.orientation.is_none() {
            return Err(TwoOrientationError::MissingOrientation {
                field: d.field.to_owned(),
            });
        }
    }
    if data.len() == 2 && data[0].orientation == data[1].orientation {
        let o = data[0].orientation.unwrap_or(Orientation::IaIn);
        return Err(TwoOrientationError::SameOrientation {
            field: data[1].field.to_owned(),
            first: data[0].field.to_owned(),
            orientation: o.label(),
        });
    }
    if data.len() != 2 {
        return Err(TwoOrientationError::OneOrientationOnly {
            field: list_field.to_owned(),
            got: describe(data),
        });
    }
    let mut out: [Option<(OrientationData<'a>, f64)>; 2] = [None, None];
    for d in data {
        let Some(o) = d.orientation else { continue };
        let Some(r) = d.radius_m else {
            return Err(TwoOrientationError::MissingRadius {
                field: d.field.to_owned(),
            });
        };
        if !(r.is_finite() && r > 0.0) {
            return Err(TwoOrientationError::Invalid {
                field: format!("{}.radius_m", d.field),
                value: r,
                reason: "must be finite and > 0",
            });
        }
        if d.rates_rad_s.len() != d.output_rad_s.len() {
            return Err(TwoOrientationError::Invalid {
                field: format!("{}.output_rad_s", d.field),
                value: d.output_rad_s.len() as f64,
                reason: "must have one output per rate",
            });
        }
        for (i, (&w, &y)) in d.rates_rad_s.iter().zip(d.output_rad_s).enumerate() {
            if !w.is_finite() {
                return Err(TwoOrientationError::Invalid {
                    field: format!("{}.rates[{i}]", d.field),
                    value: w,
                    reason: "a rate must be finite",
                });
            }
            if !y.is_finite() {
                return Err(TwoOrientationError::Invalid {
                    field: format!("{}.outputs[{i}]", d.field),
                    value: y,
                    reason: "an output must be finite",
                });
            }
        }
        if let Some(sig) = d.sigma_rad_s {
            if sig.len() != d.rates_rad_s.len() {
                return Err(TwoOrientationError::Invalid {
                    field: format!("{}.sigma_rad_s", d.field),
                    value: sig.len() as f64,
                    reason: "must have one σ per rate",
                });
            }
            if let Some((i, &s)) = sig
                .iter()
                .enumerate()
                .find(|(_, s)| !(s.is_finite() && **s > 0.0))
            {
                return Err(TwoOrientationError::Invalid {
                    field: format!("{}.sigma_rad_s[{i}]", d.field),
                    value: s,
                    reason: "a σ must be finite and > 0",
                });
            }
        }
        let n = distinct(d.rates_rad_s);
        if n < MIN_RATES_PER_ORIENTATION {
            return Err(TwoOrientationError::TooFewRates {
                field: d.field.to_owned(),
                orientation: o.label(),
                distinct: n,
                need: MIN_RATES_PER_ORIENTATION,
            });
        }
        out[index(o)] = Some((*d, r));
    }
    match out {
        [Some(a), Some(b)] => Ok([a, b]),
        _ => Err(TwoOrientationError::OneOrientationOnly {
            field: list_field.to_owned(),
            got: describe(data),
        }),
    }
}

/// Fits eq. 23 to two data sets, one per orientation, by `identify`'s QR with column scaling
/// (covariance from the residuals; weighted by `1/σᵢ` when both sets give σ, with the
/// Birge-ratio policy of `identify::identify_calibration_weighted`).
///
/// `list_field` names the list of data sets in errors (`two_orientation.orientations`).
///
/// # Errors
/// [`TwoOrientationError::OneOrientationOnly`] unless there are exactly two sets, one per
/// orientation; [`TwoOrientationError::SameOrientation`]; [`TwoOrientationError::MissingOrientation`];
/// [`TwoOrientationError::MissingRadius`]; [`TwoOrientationError::TooFewRates`] for fewer than
/// [`MIN_RATES_PER_ORIENTATION`] distinct rates in a set; [`TwoOrientationError::Invalid`] for a
/// non-finite number, mismatched lengths or a non-positive g or σ;
/// [`TwoOrientationError::Fit`] from the solver (e.g. a rank-deficient design).
pub fn fit_two_orientation(
    data: &[OrientationData<'_>],
    g_m_s2: f64,
    list_field: &str,
) -> Result<TwoOrientationFit, TwoOrientationError> {
    if !(g_m_s2.is_finite() && g_m_s2 > 0.0) {
        return Err(TwoOrientationError::Invalid {
            field: "g_m_s2".to_owned(),
            value: g_m_s2,
            reason: "must be finite and > 0",
        });
    }
    let sets = check(data, list_field)?;
    let weighted = sets.iter().all(|(d, _)| d.sigma_rad_s.is_some());
    let rows: usize = sets.iter().map(|(d, _)| d.rates_rad_s.len()).sum();
    let mut y = Vec::with_capacity(rows);
    let mut weights = Vec::with_capacity(rows);
    let mut omega6 = Vec::with_capacity(rows);
    let mut earth_rate = Vec::with_capacity(rows);
    let mut rates = Vec::with_capacity(rows);
    let mut row_set = Vec::with_capacity(rows);
    for (k, (d, radius)) in sets.iter().enumerate() {
        for (i, (&w, &out)) in d.rates_rad_s.iter().zip(d.output_rad_s).enumerate() {
            let wt = if weighted {
                d.sigma_rad_s.map_or(1.0, |s| 1.0 / s[i])
            } else {
                1.0
            };
            y.push(out * wt);
            weights.push(wt);
            omega6.push(w.powi(6) * wt);
            earth_rate.push(4.0 * radius * radius * w.powi(3) / (g_m_s2 * g_m_s2) * wt);
            rates.push(w);
            row_set.push(k);
        }
    }
    // The design of eq. 23 in double-double (`two_orientation_terms`: each entry a power of ω
    // times a constant, as eq. 18's design and the joint fit over several mountings form
    // theirs, so that eq. 23 is that fit's special case to the last digit), weighted by 1/σᵢ.
    let design = identify::Design::polynomials(&rates, TWO_ORIENTATION_TERMS, |r, j| {
        let (d, radius) = &sets[row_set[r]];
        let o = d.orientation.unwrap_or(Orientation::IaIn);
        two_orientation_terms(o, *radius, g_m_s2)[j]
            .into_iter()
            .collect()
    })
    .and_then(|d| d.scale_rows(&weights))
    .map_err(TwoOrientationError::Fit)?;
    let x = design.to_matrix();
    let mut fit = identify::lstsq_design(&design, &y, &LstsqOptions::default())
        .map_err(TwoOrientationError::Fit)?;
    // the least-squares projection of ω⁶ on the design, X⁺·ω⁶ = (XᵀX)⁻¹·Xᵀ·ω⁶, from the
    // fit's own (XᵀX)⁻¹ (the QR's, refined): no second factorisation on every fit, which the
    // planner's 10⁴ simulated campaigns paid for
    let omega6_response =
        &fit.unscaled_covariance * (x.transpose() * nalgebra::DVector::from_vec(omega6));
    let omega6_response: [f64; TWO_ORIENTATION_TERMS] = std::array::from_fn(|j| omega6_response[j]);
    let earth_rate_response =
        &fit.unscaled_covariance * (x.transpose() * nalgebra::DVector::from_vec(earth_rate));
    let earth_rate_response: [f64; TWO_ORIENTATION_TERMS] =
        std::array::from_fn(|j| earth_rate_response[j]);
    let birge_ratio = weighted.then(|| {
        let chi2: f64 = fit.residuals.iter().map(|e| e * e).sum();
        (chi2 / fit.dof.max(1) as f64).sqrt()
    });
    if let Some(b) = birge_ratio {
        // the σᵢ taken as known: (XᵀWX)⁻¹, enlarged by the Birge ratio when above 1
        let scale = b.max(1.0).powi(2);
        fit.covariance = &fit.unscaled_covariance * scale;
        fit.std_errors = (0..TWO_ORIENTATION_TERMS)
            .map(|j| fit.covariance[(j, j)].sqrt())
            .collect();
    }
    let residuals_all: Vec<f64> = fit
        .residuals
        .iter()
        .zip(&weights)
        .map(|(e, w)| e / w)
        .collect();
    let n_in = sets[0].0.rates_rad_s.len();
    let residuals_rad_s = [
        residuals_all[..n_in].to_vec(),
        residuals_all[n_in..].to_vec(),
    ];

    let c = &fit.coefficients;
    let se = &fit.std_errors;
    let cov = &fit.covariance;
    let pair = |j: usize| (c[j], se[j]);
    let mountings = [0, 1].map(|k| {
        let (d, radius) = &sets[k];
        MountingFit {
            orientation: if k == 0 {
                Orientation::IaIn
            } else {
                Orientation::IaOut
            },
            radius_m: *radius,
            distinct_rates: distinct(d.rates_rad_s),
            k0_rad_s: pair(3 * k),
            b1: pair(3 * k + 1),
            k1_rad_s_g: pair(3 * k + 2),
        }
    });
    // C = γ·g/k̄1, k̄1 = (k1,+ + k1,−)/2: first-order standard error through the gradient
    let k1_mean = 0.5 * (c[2] + c[5]);
    let gamma = c[GAMMA_TERM];
    let c_value = gamma * g_m_s2 / k1_mean;
    let mut grad = [0.0; TWO_ORIENTATION_TERMS];
    grad[GAMMA_TERM] = g_m_s2 / k1_mean;
    grad[2] = -0.5 * c_value / k1_mean;
    grad[5] = -0.5 * c_value / k1_mean;
    let mut var_c = 0.0;
    for a in 0..TWO_ORIENTATION_TERMS {
        for b in 0..TWO_ORIENTATION_TERMS {
            var_c += grad[a] * cov[(a, b)] * grad[b];
        }
    }
    let r_in = sets[0].1;
    let dk2_scale = g_m_s2 * g_m_s2 / (r_in * r_in);
    let gamma_vif = vif(&x, &weights, &fit, GAMMA_TERM);
    // Var(k2 | full) = Var(k2 | γ known) + Cov(k2, γ)²/Var(γ): the ratio is 1/(1 − ρ²)
    let u = &fit.unscaled_covariance;
    let rho =
        u[(K2_TERM, GAMMA_TERM)] / (u[(K2_TERM, K2_TERM)] * u[(GAMMA_TERM, GAMMA_TERM)]).sqrt();
    let k2_gamma_correlation = rho.clamp(-1.0, 1.0);
    let k2_inflation = 1.0
        / (1.0 - k2_gamma_correlation.powi(2))
            .max(f64::MIN_POSITIVE)
            .sqrt();
    let result = TwoOrientationFit {
        mountings,
        k2_rad_s_g2: pair(K2_TERM),
        k3_rad_s_g3: pair(K3_TERM),
        b3: pair(B3_TERM),
        gamma: pair(GAMMA_TERM),
        c_m_s2: (c_value, var_c.max(0.0).sqrt()),
        delta_k2_total_rad_s_g2: (gamma * dk2_scale, se[GAMMA_TERM] * dk2_scale),
        gamma_vif,
        k2_gamma_correlation,
        k2_inflation,
        g_m_s2,
        residuals_rad_s,
        birge_ratio,
        omega6_response,
        earth_rate_response,
        fit,
    };
    Ok(result)
}

/// Variance inflation factor of column `j` (the design rows already weighted): `VIF_j =
/// [(XᵀWX)⁻¹]_jj · Σᵢ (x_ij − x̄_j)²` about the weighted mean, the form of
/// `crate::variance_inflation` (valid with intercept columns; eq. 23 has one per
/// orientation, whose sum is the constant column).
fn vif(x: &nalgebra::DMatrix<f64>, weights: &[f64], fit: &Fit, j: usize) -> f64 {
    let w2: Vec<f64> = weights.iter().map(|w| w * w).collect();
    let total: f64 = w2.iter().sum();
    let raw = |i: usize| x[(i, j)] / weights[i];
    let mean = (0..x.nrows()).map(|i| raw(i) * w2[i]).sum::<f64>() / total;
    let ss: f64 = (0..x.nrows())
        .map(|i| w2[i] * (raw(i) - mean) * (raw(i) - mean))
        .sum();
    fit.unscaled_covariance[(j, j)] * ss
}

#[cfg(test)]
mod separability {
    use super::*;
    use crate::two_orientation_row;
    use identify::lstsq_with;

    /// A joint fit of two noise-free data sets at rates `a` (IA in, radius `ra`) and `b`
    /// (IA out, radius `rb`), °/s.
    fn fit_of(a: &[f64], ra: f64, b: &[f64], rb: f64) -> TwoOrientationFit {
        let rad = |v: &[f64]| v.iter().map(|d| d.to_radians()).collect::<Vec<f64>>();
        let (wa, wb) = (rad(a), rad(b));
        let ya: Vec<f64> = wa
            .iter()
            .map(|w| 0.56 * ra * w * w / 9.8 + 1e-9 * w)
            .collect();
        let yb: Vec<f64> = wb
            .iter()
            .map(|w| -0.56 * rb * w * w / 9.8 - 2e-9 * w)
            .collect();
        let data = [
            OrientationData {
                field: "a",
                orientation: Some(Orientation::IaIn),
                radius_m: Some(ra),
                rates_rad_s: &wa,
                output_rad_s: &ya,
                sigma_rad_s: None,
            },
            OrientationData {
                field: "b",
                orientation: Some(Orientation::IaOut),
                radius_m: Some(rb),
                rates_rad_s: &wb,
                output_rad_s: &yb,
                sigma_rad_s: None,
            },
        ];
        fit_two_orientation(&data, 9.8, "o").expect("a full-rank design")
    }

    fn wide() -> Vec<f64> {
        (0..12).map(|i| 35.0 + 15.0 * f64::from(i)).collect()
    }

    /// The ω⁶ projection from the fit's (XᵀX)⁻¹ is the least-squares solution for ω⁶ through
    /// a QR of its own.
    #[test]
    fn the_omega6_response_is_the_least_squares_projection() {
        let w = wide();
        let f = fit_of(&w, 2.5, &w, 2.54);
        let rad: Vec<f64> = w.iter().map(|d| d.to_radians()).collect();
        let mut x = nalgebra::DMatrix::zeros(2 * rad.len(), TWO_ORIENTATION_TERMS);
        let mut omega6 = Vec::new();
        for (k, o) in [Orientation::IaIn, Orientation::IaOut]
            .into_iter()
            .enumerate()
        {
            let radius = [2.5, 2.54][k];
            for (i, &wi) in rad.iter().enumerate() {
                let row = two_orientation_row(o, radius, 9.8, wi);
                for (j, v) in row.iter().enumerate() {
                    x[(k * rad.len() + i, j)] = *v;
                }
                omega6.push(wi.powi(6));
            }
        }
        let qr = lstsq_with(&x, &omega6, &LstsqOptions::default()).unwrap();
        for j in 0..TWO_ORIENTATION_TERMS {
            let (a, b) = (f.omega6_response[j], qr.coefficients[j]);
            assert!(
                (a - b).abs() <= 1e-7 * b.abs().max(1e-12),
                "term {j}: {a} against {b}"
            );
        }
    }

    #[test]
    fn the_ordinary_design_separates_k2_and_c_though_its_vif_is_large() {
        // the fixture's design: 12 rates 35–200 °/s in both mountings, R 2.50 and 2.54 m
        let f = fit_of(&wide(), 2.5, &wide(), 2.54);
        assert!(f.gamma_vif > 1e6, "{}", f.gamma_vif);
        assert!(f.k2_inflation < 1.5, "{}", f.k2_inflation);
        assert!(f.separable());
        // equal radii and rates: k2 and C come from the sum and the difference of the two
        // mountings' ω⁴ coefficients, uncorrelated whatever the VIF
        let same = fit_of(&wide(), 2.5, &wide(), 2.5);
        assert!(same.k2_gamma_correlation.abs() < 1e-6, "{same:?}");
    }

    #[test]
    fn one_mounting_at_low_rates_only_cannot_separate_them() {
        // IA out measured at 35–60 °/s only: its ω⁴ coefficient is barely known, so k2 and C
        // both rest on IA in's alone
        let f = fit_of(&wide(), 2.5, &[35.0, 40.0, 45.0, 50.0, 55.0, 60.0], 2.54);
        assert!(f.k2_inflation > 5.0, "{}", f.k2_inflation);
        assert!(f.k2_gamma_correlation.abs() > 0.98);
        assert!(!f.separable());
    }

    #[test]
    fn the_inflation_is_u_k2_over_u_k2_with_c_known() {
        // the identity checked against a fit without the s·ω⁴ column, through the same QR
        let a = wide();
        let b = [35.0, 40.0, 45.0, 50.0, 55.0, 60.0];
        let f = fit_of(&a, 2.5, &b, 2.54);
        let mut rows = Vec::new();
        for (o, r, rates) in [
            (Orientation::IaIn, 2.5, &a[..]),
            (Orientation::IaOut, 2.54, &b[..]),
        ] {
            for d in rates {
                let row = two_orientation_row(o, r, 9.8, d.to_radians());
                rows.push(row[..GAMMA_TERM].to_vec());
            }
        }
        let x = nalgebra::DMatrix::from_fn(rows.len(), GAMMA_TERM, |i, j| rows[i][j]);
        let reduced = lstsq_with(&x, &vec![0.0; rows.len()], &LstsqOptions::default()).unwrap();
        let ratio = (f.fit.unscaled_covariance[(K2_TERM, K2_TERM)]
            / reduced.unscaled_covariance[(K2_TERM, K2_TERM)])
            .sqrt();
        assert!(
            (ratio / f.k2_inflation - 1.0).abs() < 1e-6,
            "{ratio} vs {}",
            f.k2_inflation
        );
    }
}
