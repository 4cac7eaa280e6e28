//! The coverage interval from the model values: the order statistics of JCGM 101 §7.7,
//! found by selection (Floyd–Rivest bracketing for large batches).

/// Index `(r, r + q)` (0-based) of the probabilistically symmetric 100p % coverage interval
/// among `count` sorted values (JCGM 101 §7.7.1 and §7.7.2, with 1-based `r`).
pub(super) fn coverage_indices(count: usize, p: f64) -> (usize, usize) {
    let q = ((p * count as f64) + 0.5).floor() as usize;
    let q = q.min(count - 1);
    // r = (M − q)/2 when that is an integer, (M − q + 1)/2 otherwise: ⌈(M − q)/2⌉, at least 1.
    let r = (count - q).div_ceil(2).max(1);
    (r - 1, (r + q - 1).min(count - 1))
}

/// The coverage interval of `values` (reordered in place by selection).
pub(super) fn coverage_interval(values: &mut [f64], p: f64) -> (f64, f64) {
    let (lo, hi) = coverage_indices(values.len(), p);
    order_statistics(values, lo, hi)
}

/// The order statistics of 0-based ranks `lo ≤ hi` of `values` in the order of
/// [`f64::total_cmp`], by selection (`values` is reordered).
pub(super) fn select_two(values: &mut [f64], lo: usize, hi: usize) -> (f64, f64) {
    let (_, low, upper) = values.select_nth_unstable_by(lo, f64::total_cmp);
    let low = *low;
    let high = if hi == lo {
        low
    } else {
        *upper.select_nth_unstable_by(hi - lo - 1, f64::total_cmp).1
    };
    (low, high)
}

/// Fewest values for which [`order_statistics`] brackets the ranks from a sample; fewer are
/// selected directly.
const BRACKET_MIN: usize = 65_536;

/// The order statistics of 0-based ranks `lo ≤ hi` of `values` (in the order of
/// [`f64::total_cmp`]; `values` may be reordered): the same numbers as two selections, at
/// the cost of about one pass for large slices.
///
/// Floyd and Rivest's bracketing: the ranks' neighbourhoods in an evenly strided sample of
/// about `n^(2/3)` values give two brackets that hold the wanted order statistics with
/// overwhelming probability; one pass counts the values below each bracket and gathers those
/// inside, and the order statistic is selected among the gathered few. A bracket that missed
/// (its count says so, exactly) falls back to selecting over all values, so the result never
/// depends on the sample.
///
/// # References
/// R. W. Floyd, R. L. Rivest, "Expected time bounds for selection", Commun. ACM 18 (1975).
fn order_statistics(values: &mut [f64], lo: usize, hi: usize) -> (f64, f64) {
    let n = values.len();
    if n < BRACKET_MIN || hi < lo {
        return select_two(values, lo, hi);
    }
    let stride = (n as f64).cbrt().ceil() as usize;
    let mut sample: Vec<f64> = values.iter().step_by(stride).copied().collect();
    let s = sample.len();
    // Sample ranks k·s/n ± 4 standard deviations of a sample rank (and 2 for rounding).
    let bracket = |k: usize, sample: &mut [f64]| -> (f64, f64) {
        let q = k as f64 / n as f64;
        let centre = q * s as f64;
        let margin = 4.0 * (s as f64 * q * (1.0 - q)).sqrt() + 2.0;
        let a = centre - margin;
        let b = centre + margin;
        let low = if a < 0.0 {
            f64::NEG_INFINITY
        } else {
            *sample.select_nth_unstable_by(a as usize, f64::total_cmp).1
        };
        let high = if b >= (s - 1) as f64 {
            f64::INFINITY
        } else {
            *sample
                .select_nth_unstable_by(b.ceil() as usize, f64::total_cmp)
                .1
        };
        (low, high)
    };
    let (a1, b1) = bracket(lo, &mut sample);
    let (a2, b2) = bracket(hi, &mut sample);
    within_brackets(values, lo, hi, [a1, b1, a2, b2])
}

/// The order statistics of ranks `lo ≤ hi`, as [`select_two`] gives them, found among the
/// values inside the brackets `[a1, b1]` and `[a2, b2]` when they hold them (one counting
/// pass tells), by selection over all values otherwise.
pub(super) fn within_brackets(
    values: &mut [f64],
    lo: usize,
    hi: usize,
    brackets: [f64; 4],
) -> (f64, f64) {
    let [a1, b1, a2, b2] = brackets;
    // The passes compare with `<` and `<=`, which order the values as `total_cmp` does when
    // none is NaN (counted, and failed trials are left out before) and no bound is a zero
    // (−0 = +0 to `<`).
    if [a1, b1, a2, b2].iter().any(|&b| b == 0.0 || b.is_nan()) || b1 >= a2 {
        return select_two(values, lo, hi);
    }
    // First pass, counts only (vectorised): values below and up to each bracket's ends.
    let mut counts = [0usize; 5];
    for &v in values.iter() {
        counts[0] += usize::from(v < a1);
        counts[1] += usize::from(v <= b1);
        counts[2] += usize::from(v < a2);
        counts[3] += usize::from(v <= b2);
        counts[4] += usize::from(v.is_nan());
    }
    let [below, upto_first, below_second, upto_second, nan] = counts;
    if nan > 0 || !((below..upto_first).contains(&lo) && (below_second..upto_second).contains(&hi))
    {
        return select_two(values, lo, hi);
    }
    // Second pass: gather the few values inside the brackets.
    let mut first = Vec::with_capacity(upto_first - below);
    let mut second = Vec::with_capacity(upto_second - below_second);
    for &v in values.iter() {
        // Non-short-circuit operators: one branch, rarely taken, instead of a chain.
        let in_first = (v >= a1) & (v <= b1);
        let in_second = (v >= a2) & (v <= b2);
        if in_first | in_second {
            if in_first {
                first.push(v);
            } else {
                second.push(v);
            }
        }
    }
    let low = *first.select_nth_unstable_by(lo - below, f64::total_cmp).1;
    let high = *second
        .select_nth_unstable_by(hi - below_second, f64::total_cmp)
        .1;
    (low, high)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng as _;
    use rand_distr::StandardNormal;

    #[test]
    fn coverage_indices_follow_jcgm_101_7_7() {
        // M = 10⁴, p = 0.95: q = 9500, r = 250: [y_(250), y_(9750)] (1-based).
        assert_eq!(coverage_indices(10_000, 0.95), (249, 9749));
        // M = 10⁴ + 1: q = int(9500.95 + ½) = 9501, (M − q)/2 = 250: [y_(250), y_(9751)].
        assert_eq!(coverage_indices(10_001, 0.95), (249, 9750));
        // M = 10⁴ + 2: q = int(9501.9 + ½) = 9502, (M − q)/2 = 250.
        assert_eq!(coverage_indices(10_002, 0.95), (249, 9751));
        // M = 10⁴ + 3: q = int(9502.85 + ½) = 9503, (M − q)/2 = 250.
        assert_eq!(coverage_indices(10_003, 0.95), (249, 9752));
        // M = 10⁴ + 10: q = 9510 (pM = 9509.5 → int(9510)), (M − q)/2 = 250.
        assert_eq!(coverage_indices(10_010, 0.95), (249, 9759));
        // M = 10⁴ + 20: q = int(9519 + ½) = 9519, (M − q)/2 = 250.5 → r = 251.
        assert_eq!(coverage_indices(10_020, 0.95), (250, 9769));
    }

    #[test]
    fn coverage_interval_selects_order_statistics() {
        let mut v: Vec<f64> = (1..=10_000).rev().map(f64::from).collect();
        assert_eq!(coverage_interval(&mut v, 0.95), (250.0, 9750.0));
    }

    #[test]
    fn bracketed_order_statistics_equal_selection() {
        // Normal draws, heavy ties (rounded), signed zeros and a sorted, a reversed and a
        // constant run: the bracketing gives exactly the selected values.
        let mut rng = super::super::draw::stream(7, 0, 0);
        let normal: Vec<f64> = (0..50_000).map(|_| rng.sample(StandardNormal)).collect();
        let ties: Vec<f64> = normal.iter().map(|v| (v * 4.0).round() / 4.0).collect();
        let zeros: Vec<f64> = (0..10_000)
            .map(|i| if i % 2 == 0 { 0.0 } else { -0.0 })
            .collect();
        let sorted: Vec<f64> = (0..20_000).map(f64::from).collect();
        let reversed: Vec<f64> = sorted.iter().rev().copied().collect();
        let constant = vec![1.5; 8192];
        for (case, values) in [normal, ties, zeros, sorted, reversed, constant]
            .into_iter()
            .enumerate()
        {
            for p in [0.5, 0.9, 0.95, 0.99, 0.9999] {
                let (lo, hi) = coverage_indices(values.len(), p);
                let mut a = values.clone();
                let mut b = values.clone();
                let got = order_statistics(&mut a, lo, hi);
                let want = select_two(&mut b, lo, hi);
                let bits = |(x, y): (f64, f64)| (x.to_bits(), y.to_bits());
                assert_eq!(bits(got), bits(want), "case {case}, p = {p}");
                // Given brackets: ones that hold the limits, and ones that miss (fallback).
                let (w0, w1) = want;
                for brackets in [
                    [w0 - 1.0, w0 + 0.5, w1 - 0.5, w1 + 1.0],
                    [w0 + 0.25, w0 + 0.5, w1 - 0.5, w1 - 0.25],
                    [-1e300, -1e299, 1e299, 1e300],
                ] {
                    let mut c = values.clone();
                    let got = within_brackets(&mut c, lo, hi, brackets);
                    assert_eq!(bits(got), bits(want), "case {case}, p = {p}, {brackets:?}");
                }
            }
        }
    }
}
