//! The least-squares solver on small arbitrary designs: no panic, and an `Ok` fit holds only
//! finite numbers (coefficients, standard errors, covariance, residuals, residual SD).
#![no_main]

use libfuzzer_sys::fuzz_target;
use nalgebra::DMatrix;

fuzz_target!(|data: &[u8]| {
    let Some((&shape, rest)) = data.split_first() else {
        return;
    };
    let n = usize::from(shape & 3) + 1; // 1..=4 unknowns
    let m = n + usize::from((shape >> 2) & 7); // n..=n+7 observations
    // Each number is 8 bytes read as an f64 (any bit pattern, NaN and ∞ included), so the
    // fuzzer reaches huge, tiny, subnormal and non-finite entries.
    let mut numbers = rest
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])));
    let mut take = || numbers.next().unwrap_or(0.0);
    let design = DMatrix::from_fn(m, n, |_, _| take());
    let y: Vec<f64> = (0..m).map(|_| take()).collect();
    if let Ok(fit) = identify::lstsq(&design, &y) {
        assert!(fit.coefficients.iter().all(|v| v.is_finite()), "{fit:?}");
        assert!(fit.std_errors.iter().all(|v| v.is_finite()), "{fit:?}");
        assert!(fit.covariance.iter().all(|v| v.is_finite()), "{fit:?}");
        assert!(fit.residuals.iter().all(|v| v.is_finite()), "{fit:?}");
        assert!(fit.residual_sd.is_finite(), "{fit:?}");
    }
});
