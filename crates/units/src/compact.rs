//! How an error message writes a number.

/// A number as an error message shows it: the shortest text that reads back to the same
/// `f64` (at most 17 significant digits), in plain notation between 1e-5 and 1e16 and in
/// exponent notation outside (`1e300`, never a 301-digit expansion); `NaN`, `inf`, `-inf` as
/// Rust writes them.
///
/// ```
/// use units::Compact;
/// assert_eq!(Compact(0.56).to_string(), "0.56");
/// assert_eq!(Compact(1e300).to_string(), "1e300");
/// assert_eq!(Compact(-2.5e-160).to_string(), "-2.5e-160");
/// assert_eq!(Compact(f64::NEG_INFINITY).to_string(), "-inf");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compact(pub f64);

impl std::fmt::Display for Compact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        let magnitude = x.abs();
        if !x.is_finite() || x == 0.0 || (1e-5..1e16).contains(&magnitude) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// Named quantities as an error message lists them: `k1 = 0.56, radius_m = 1e-160`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompactList<'a>(pub &'a [(&'static str, f64)]);

impl std::fmt::Display for CompactList<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, (name, value)) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{name} = {}", Compact(*value))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compact_numbers_are_short_and_exact() {
        for x in [
            1e300,
            -1e-300,
            1.7976931348623157e308,
            5e-324,
            0.1 + 0.2,
            123456.789,
            1e15,
        ] {
            let text = Compact(x).to_string();
            assert!(text.len() <= 24, "{text}");
            assert_eq!(text.parse::<f64>().unwrap(), x);
        }
        assert_eq!(Compact(0.0).to_string(), "0");
        assert_eq!(Compact(f64::NAN).to_string(), "NaN");
        assert_eq!(
            CompactList(&[("k1", 0.56), ("radius_m", 1e-160)]).to_string(),
            "k1 = 0.56, radius_m = 1e-160"
        );
    }
}
