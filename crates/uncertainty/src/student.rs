//! Quantiles of Student's t distribution, for the coverage factor (JCGM 100 G.3, G.6.4).
//!
//! The upper tail of t with ν degrees of freedom is `Q(t) = ½·I_x(ν/2, ½)` with
//! `x = ν/(ν + t²)` (the regularised incomplete beta function, evaluated by its continued
//! fraction with the modified Lentz method). The quantile solves `Q(t) = α` by Newton's method
//! on `t`, kept inside a bisection bracket. For ν above [`EXPANSION_DOF`] the continued
//! fraction needs O(√ν) terms, and the Cornish–Fisher expansion of the quantile in `1/ν`
//! around the normal quantile (Abramowitz & Stegun 26.7.5, four terms, truncation below
//! 1e-20 there) is used instead. The normal quantile solves `½·erfc(z/√2) = α` the same way,
//! with `erfc` from the regularised incomplete gamma function `Q(½, x²)`.
//!
//! Accuracy: better than 1e-13 relative against closed forms (ν = 1, 2, 4) and the tables
//! (unit tests below).

use crate::error::{Result, UncertaintyError};
use crate::kind::Dof;
use units::Requirement;

/// Above this many degrees of freedom the quantile comes from the Cornish–Fisher expansion.
const EXPANSION_DOF: f64 = 1e5;
const MAX_ITER: usize = 200;
const CF_MAX_TERMS: usize = 100_000;
const TINY: f64 = 1e-300;

/// The quantile of Student's t distribution with `dof` degrees of freedom at cumulative
/// probability `probability` (`Dof::Infinite`: the standard normal quantile).
///
/// Errors: `probability` outside `(0, 1)`, or a quantile too large for `f64` (ν far below 1).
pub fn student_t_quantile(probability: f64, dof: Dof) -> Result<f64> {
    if !(probability > 0.0 && probability < 1.0) {
        return Err(UncertaintyError::InvalidOption {
            name: "probability",
            value: probability,
            requirement: Requirement::OpenUnitInterval,
        });
    }
    if let Dof::Finite(nu) = dof
        && !(nu.is_finite() && nu > 0.0)
    {
        return Err(UncertaintyError::InvalidOption {
            name: "dof",
            value: nu,
            requirement: Requirement::Positive,
        });
    }
    if probability == 0.5 {
        return Ok(0.0);
    }
    // Solve for the upper tail α ≤ ½ and restore the sign.
    let (alpha, sign) = if probability > 0.5 {
        (1.0 - probability, 1.0)
    } else {
        (probability, -1.0)
    };
    let t = match dof {
        Dof::Infinite => normal_upper_quantile(alpha),
        Dof::Finite(nu) if nu > EXPANSION_DOF => cornish_fisher(normal_upper_quantile(alpha), nu),
        Dof::Finite(nu) => t_upper_quantile(alpha, nu),
    };
    if t.is_finite() {
        Ok(sign * t)
    } else {
        Err(UncertaintyError::QuantileOverflow { probability, dof })
    }
}

/// The coverage factor `k = t_{(1+p)/2}(ν)` for a symmetric coverage interval of probability
/// `p` (JCGM 100 G.3.4): 12.706 for ν = 1 and p = 0.95, 1.95996 for ν = ∞.
pub fn coverage_factor(coverage_probability: f64, dof: Dof) -> Result<f64> {
    if !(coverage_probability > 0.0 && coverage_probability < 1.0) {
        return Err(UncertaintyError::InvalidOption {
            name: "coverage_probability",
            value: coverage_probability,
            requirement: Requirement::OpenUnitInterval,
        });
    }
    student_t_quantile(0.5 + 0.5 * coverage_probability, dof)
}

/// `ln Γ(x)` for `x > 0` (Lanczos, g = 7, nine terms; about 1e-15 relative).
pub(crate) fn ln_gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Γ(x)Γ(1−x) = π / sin(πx).
        return (std::f64::consts::PI / (std::f64::consts::PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + G + 0.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Continued fraction of the incomplete beta function (modified Lentz), valid and fast for
/// `x < (a+1)/(a+b+2)`.
fn beta_cf(a: f64, b: f64, x: f64) -> f64 {
    let (qab, qap, qam) = (a + b, a + 1.0, a - 1.0);
    let mut c = 1.0;
    let mut d = 1.0 - qab * x / qap;
    if d.abs() < TINY {
        d = TINY;
    }
    d = 1.0 / d;
    let mut h = d;
    for m in 1..CF_MAX_TERMS {
        let m = m as f64;
        let m2 = 2.0 * m;
        let aa = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1.0 + aa * d;
        if d.abs() < TINY {
            d = TINY;
        }
        c = 1.0 + aa / c;
        if c.abs() < TINY {
            c = TINY;
        }
        d = 1.0 / d;
        h *= d * c;
        let aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1.0 + aa * d;
        if d.abs() < TINY {
            d = TINY;
        }
        c = 1.0 + aa / c;
        if c.abs() < TINY {
            c = TINY;
        }
        d = 1.0 / d;
        let del = d * c;
        h *= del;
        if (del - 1.0).abs() < 1e-16 {
            break;
        }
    }
    h
}

/// Stirling's correction `δ(x) = ln Γ(x) − [(x − ½)·ln x − x + ½·ln 2π]` for `x ≥ 10`
/// (seven terms of the asymptotic series; the eighth is below 1e-16 there).
fn stirling_correction(x: f64) -> f64 {
    let r = 1.0 / (x * x);
    (1.0 / 12.0
        - r * (1.0 / 360.0
            - r * (1.0 / 1260.0
                - r * (1.0 / 1680.0 - r * (1.0 / 1188.0 - r * (691.0 / 360_360.0 - r / 156.0))))))
        / x
}

/// `ln B(a, b) = ln Γ(a) + ln Γ(b) − ln Γ(a + b)`. When the larger argument is at least 10,
/// `ln Γ(a) − ln Γ(a + b)` is taken from Stirling's series term by term, so that two large
/// logarithms do not cancel (they would cost 1e-11 at a = 5·10⁴).
fn ln_beta(a: f64, b: f64) -> f64 {
    let (small, large) = if a < b { (a, b) } else { (b, a) };
    if large < 10.0 {
        return ln_gamma(a) + ln_gamma(b) - ln_gamma(a + b);
    }
    let sum = small + large;
    // ln Γ(L) − ln Γ(L + s) = −(L − ½)·ln(1 + s/L) − s·ln(L + s) + s + δ(L) − δ(L + s)
    let diff = -(large - 0.5) * (small / large).ln_1p() - small * sum.ln()
        + small
        + stirling_correction(large)
        - stirling_correction(sum);
    let ln_gamma_small = if small >= 10.0 {
        (small - 0.5) * small.ln() - small
            + 0.5 * (2.0 * std::f64::consts::PI).ln()
            + stirling_correction(small)
    } else {
        ln_gamma(small)
    };
    ln_gamma_small + diff
}

/// The regularised incomplete beta function `I_x(a, b)`, given `x`, `y = 1 − x` and their
/// logarithms, each computed without cancellation by the caller.
fn incomplete_beta(a: f64, b: f64, (x, ln_x): (f64, f64), (y, ln_y): (f64, f64)) -> f64 {
    if x <= 0.0 && ln_x == f64::NEG_INFINITY {
        return 0.0;
    }
    if y <= 0.0 && ln_y == f64::NEG_INFINITY {
        return 1.0;
    }
    let front = (a * ln_x + b * ln_y - ln_beta(a, b)).exp();
    if x < (a + 1.0) / (a + b + 2.0) {
        front * beta_cf(a, b, x) / a
    } else {
        1.0 - front * beta_cf(b, a, y) / b
    }
}

/// Upper tail `P(T > t)` of Student's t with ν degrees of freedom, `t ≥ 0`, with
/// `x = ν/(ν + t²) = 1/(1 + s²)` and `1 − x = s²/(1 + s²)` for `s = t/√ν`, their logarithms
/// formed without overflow for any finite `t`.
fn t_upper_tail(t: f64, nu: f64) -> f64 {
    let ln_s = t.ln() - 0.5 * nu.ln();
    let ln_x = if ln_s < 300.0 {
        -(2.0 * ln_s).exp().ln_1p()
    } else {
        -2.0 * ln_s
    };
    let ln_y = if ln_s <= 0.0 {
        2.0 * ln_s - (2.0 * ln_s).exp().ln_1p()
    } else {
        -(-2.0 * ln_s).exp().ln_1p()
    };
    0.5 * incomplete_beta(0.5 * nu, 0.5, (ln_x.exp(), ln_x), (ln_y.exp(), ln_y))
}

/// Density of Student's t with ν degrees of freedom.
fn t_density(t: f64, nu: f64, ln_norm: f64) -> f64 {
    (ln_norm - 0.5 * (nu + 1.0) * (t * t / nu).ln_1p()).exp()
}

/// Solves `f(t) = α` for a decreasing tail function `f` on `t ≥ 0`, given its density
/// (`−f'`): Newton's method inside a bisection bracket.
fn solve_tail(
    alpha: f64,
    tail: impl Fn(f64) -> f64,
    density: impl Fn(f64) -> f64,
    start: f64,
) -> f64 {
    let (mut lo, mut hi) = (0.0_f64, start.max(1.0));
    while tail(hi) > alpha {
        lo = hi;
        hi *= 2.0;
        if !hi.is_finite() {
            return f64::INFINITY;
        }
    }
    let mut t = start.clamp(lo, hi);
    for _ in 0..MAX_ITER {
        let f = tail(t) - alpha;
        if f > 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let step = f / density(t);
        let mut next = t + step;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - t).abs() <= 1e-15 * next.abs() || hi - lo <= 1e-15 * hi {
            return next;
        }
        t = next;
    }
    t
}

/// Upper α quantile of Student's t with ν degrees of freedom (α ≤ ½).
fn t_upper_quantile(alpha: f64, nu: f64) -> f64 {
    let ln_norm =
        ln_gamma(0.5 * (nu + 1.0)) - ln_gamma(0.5 * nu) - 0.5 * (nu * std::f64::consts::PI).ln();
    let start = if nu >= 3.0 {
        cornish_fisher(normal_upper_quantile(alpha), nu)
    } else {
        1.0
    };
    solve_tail(
        alpha,
        |t| t_upper_tail(t, nu),
        |t| t_density(t, nu, ln_norm),
        start,
    )
}

/// Cornish–Fisher expansion of the t quantile around the normal quantile `z`
/// (Abramowitz & Stegun 26.7.5).
fn cornish_fisher(z: f64, nu: f64) -> f64 {
    let z2 = z * z;
    let g1 = (z2 + 1.0) * z / 4.0;
    let g2 = ((5.0 * z2 + 16.0) * z2 + 3.0) * z / 96.0;
    let g3 = (((3.0 * z2 + 19.0) * z2 + 17.0) * z2 - 15.0) * z / 384.0;
    let g4 = ((((79.0 * z2 + 776.0) * z2 + 1482.0) * z2 - 1920.0) * z2 - 945.0) * z / 92160.0;
    z + (g1 + (g2 + (g3 + g4 / nu) / nu) / nu) / nu
}

/// Regularised upper incomplete gamma `Q(a, x)` (series below `a + 1`, continued fraction
/// above), as in Numerical Recipes' `gammq`.
fn upper_incomplete_gamma(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let ln_front = a * x.ln() - x - ln_gamma(a);
    if x < a + 1.0 {
        let (mut ap, mut del) = (a, 1.0 / a);
        let mut sum = del;
        for _ in 0..CF_MAX_TERMS {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-17 {
                break;
            }
        }
        1.0 - sum * ln_front.exp()
    } else {
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / TINY;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..CF_MAX_TERMS {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < TINY {
                d = TINY;
            }
            c = b + an / c;
            if c.abs() < TINY {
                c = TINY;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-16 {
                break;
            }
        }
        ln_front.exp() * h
    }
}

/// Upper α quantile of the standard normal distribution (α ≤ ½).
fn normal_upper_quantile(alpha: f64) -> f64 {
    let tail = |z: f64| 0.5 * upper_incomplete_gamma(0.5, 0.5 * z * z);
    let density = |z: f64| (-0.5 * z * z).exp() / (2.0 * std::f64::consts::PI).sqrt();
    // Start from the logistic-like approximation z ≈ √(−2 ln α) corrected (A&S 26.2.23 form).
    let s = (-2.0 * alpha.ln()).sqrt();
    let start = s
        - (2.515_517 + 0.802_853 * s + 0.010_328 * s * s)
            / (1.0 + 1.432_788 * s + 0.189_269 * s * s + 0.001_308 * s * s * s);
    solve_tail(alpha, tail, density, start.max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn k95(nu: f64) -> f64 {
        coverage_factor(0.95, Dof::Finite(nu)).unwrap()
    }

    #[test]
    fn ln_gamma_matches_known_values() {
        assert_relative_eq!(ln_gamma(0.5), 0.572_364_942_924_700_1, max_relative = 1e-14);
        assert_relative_eq!(ln_gamma(1.0), 0.0, epsilon = 1e-15);
        assert_relative_eq!(ln_gamma(10.0), 362_880f64.ln(), max_relative = 1e-14);
        assert_relative_eq!(ln_gamma(0.1), 2.252_712_651_734_206, max_relative = 1e-14);
        // ln B through Stirling's series against the direct sum where both are accurate.
        for (a, b) in [(10.0, 0.5), (12.5, 3.0), (40.0, 15.0), (0.5, 25.0)] {
            let direct = ln_gamma(a) + ln_gamma(b) - ln_gamma(a + b);
            assert_relative_eq!(ln_beta(a, b), direct, max_relative = 1e-13);
        }
    }

    #[test]
    fn closed_forms_for_one_two_and_four_dof() {
        // ν = 1 (Cauchy): t = tan(π(p − ½)); ν = 2: t = (2p − 1)/√(2p(1 − p)).
        for p in [0.6, 0.9, 0.975, 0.995, 0.9995] {
            let cauchy = (std::f64::consts::PI * (p - 0.5)).tan();
            assert_relative_eq!(
                student_t_quantile(p, Dof::Finite(1.0)).unwrap(),
                cauchy,
                max_relative = 1e-13
            );
            let two = (2.0 * p - 1.0) / (2.0 * p * (1.0 - p)).sqrt();
            assert_relative_eq!(
                student_t_quantile(p, Dof::Finite(2.0)).unwrap(),
                two,
                max_relative = 1e-13
            );
            // ν = 4: with α = 4p(1−p) and q = cos(⅓ arccos √α)/√α, t = sign·2√(q − 1).
            let a = 4.0 * p * (1.0 - p);
            let q = ((a.sqrt()).acos() / 3.0).cos() / a.sqrt();
            let four = 2.0 * (q - 1.0).sqrt();
            assert_relative_eq!(
                student_t_quantile(p, Dof::Finite(4.0)).unwrap(),
                four,
                max_relative = 1e-13
            );
        }
    }

    #[test]
    fn tabulated_coverage_factors() {
        // JCGM 100 Table G.2 and standard t tables (two-sided 95 %).
        for (nu, t) in [
            (1.0, 12.706),
            (2.0, 4.303),
            (3.0, 3.182),
            (5.0, 2.571),
            (10.0, 2.228),
            (20.0, 2.086),
            (30.0, 2.042),
            (100.0, 1.984),
        ] {
            assert!((k95(nu) - t).abs() < 5e-4, "ν = {nu}: {} vs {t}", k95(nu));
        }
        // More digits (R's qt(0.975, ν)).
        assert_relative_eq!(k95(5.0), 2.570_581_835_636_315, max_relative = 1e-13);
        assert_relative_eq!(k95(10.0), 2.228_138_851_986_274, max_relative = 1e-13);
        assert_relative_eq!(k95(30.0), 2.042_272_456_301_238, max_relative = 1e-13);
        assert_relative_eq!(k95(100.0), 1.983_971_518_523_552, max_relative = 1e-13);
        // Non-integer ν lies between its neighbours.
        assert!(k95(5.5) < k95(5.0) && k95(5.5) > k95(6.0));
    }

    #[test]
    fn normal_quantiles() {
        let z = |p| student_t_quantile(p, Dof::Infinite).unwrap();
        assert_relative_eq!(z(0.975), 1.959_963_984_540_054, max_relative = 1e-14);
        assert_relative_eq!(z(0.995), 2.575_829_303_548_901, max_relative = 1e-14);
        assert_relative_eq!(z(0.841_344_746_068_542_9), 1.0, max_relative = 1e-12);
        assert_relative_eq!(z(0.025), -1.959_963_984_540_054, max_relative = 1e-14);
        assert_relative_eq!(z(1e-10), -6.361_340_902_404_056, max_relative = 1e-13);
    }

    #[test]
    fn expansion_and_continued_fraction_agree_where_they_meet() {
        // The expansion takes over above 1e5; at 300 its truncation is still below 1e-11, so
        // agreement there checks its four coefficients, and at 1e5 the switch is seamless.
        for nu in [300.0, 3000.0, EXPANSION_DOF] {
            let cf = t_upper_quantile(0.025, nu);
            let ex = cornish_fisher(normal_upper_quantile(0.025), nu);
            assert_relative_eq!(cf, ex, max_relative = 1e-11);
        }
        assert!(k95(1e12) > 1.959_963_984_540_054 && k95(1e12) < 1.959_963_984_543);
    }

    #[test]
    fn invalid_arguments_are_errors() {
        assert!(matches!(
            coverage_factor(1.0, Dof::Infinite),
            Err(UncertaintyError::InvalidOption {
                name: "coverage_probability",
                ..
            })
        ));
        assert!(matches!(
            student_t_quantile(0.975, Dof::Finite(0.0)),
            Err(UncertaintyError::InvalidOption { name: "dof", .. })
        ));
        assert!(matches!(
            student_t_quantile(0.975, Dof::Finite(1e-4)),
            Err(UncertaintyError::QuantileOverflow { .. })
        ));
    }
}
