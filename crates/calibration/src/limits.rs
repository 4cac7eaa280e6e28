//! The χ² limits above which a fit is reported as describing its points worse than their σ.

/// `√(χ²/ν)` of residuals over their σ above which a fit is flagged as lacking: 2 for many
/// degrees of freedom, more for few (`√(max(4, 1 + 6·√(2/ν)))`), so that white noise alone
/// rarely reaches it. Used for the radius-error fit and the eq. 18 fit alike.
#[must_use]
pub fn lack_of_fit_limit(dof: usize) -> f64 {
    (4.0_f64).max(1.0 + 6.0 * (2.0 / dof as f64).sqrt()).sqrt()
}

/// Mean residual of a label, in its standard uncertainties, above which the label is
/// reported as sitting apart, for many rows (fewer widen it by Student's t).
pub const LABEL_OFFSET_LIMIT: f64 = 3.0;

/// The limit for a label of `rows` rows: Student's t at 99.73 % (about 3σ) with `rows − 1`
/// degrees of freedom; infinite for one row (no scatter to measure an offset against).
#[must_use]
pub fn label_offset_limit(rows: usize) -> f64 {
    if rows >= 2 {
        uncertainty::coverage_factor(0.9973, uncertainty::Dof::Finite((rows - 1) as f64))
            .unwrap_or(LABEL_OFFSET_LIMIT)
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_widen_with_few_degrees_of_freedom() {
        assert_eq!(lack_of_fit_limit(1000), 2.0);
        assert!(lack_of_fit_limit(2) > lack_of_fit_limit(20));
        assert!(label_offset_limit(3) > label_offset_limit(100));
        assert!((label_offset_limit(100_000) - 3.0).abs() < 0.01);
        assert_eq!(label_offset_limit(1), f64::INFINITY);
    }
}
