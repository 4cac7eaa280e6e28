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
/// // A precision rounds in plain notation and keeps the exponent outside it.
/// assert_eq!(format!("{:.1}", Compact(3599.96)), "3600.0");
/// assert_eq!(format!("{:.1}", Compact(1e300)), "1.0e300");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compact(pub f64);

impl std::fmt::Display for Compact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        let magnitude = x.abs();
        let plain = !x.is_finite() || x == 0.0 || (1e-5..1e16).contains(&magnitude);
        match (f.precision(), plain) {
            (None, true) => write!(f, "{x}"),
            (None, false) => write!(f, "{x:e}"),
            (Some(p), true) => write!(f, "{x:.p$}"),
            (Some(p), false) => write!(f, "{x:.p$e}"),
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

/// A list of numbers as an error message or warning shows it: every value when there are at
/// most [`CompactSeries::SHOWN`], else the first few and the last, with the count, so that a
/// table of 10⁵ rates gives one short line, not 257 kB.
///
/// ```
/// use units::CompactSeries;
/// assert_eq!(CompactSeries(&[10.0, 20.5]).to_string(), "[10, 20.5]");
/// let many: Vec<f64> = (1..=100_000).map(f64::from).collect();
/// assert_eq!(CompactSeries(&many).to_string(), "[1, 2, 3, 4, 5, 6, …, 100000] (100000 values)");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompactSeries<'a>(pub &'a [f64]);

impl CompactSeries<'_> {
    /// Most values written in full.
    pub const SHOWN: usize = 8;
}

impl std::fmt::Display for CompactSeries<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let values = self.0;
        f.write_str("[")?;
        if values.len() <= Self::SHOWN {
            for (i, x) in values.iter().enumerate() {
                if i > 0 {
                    f.write_str(", ")?;
                }
                write!(f, "{}", Compact(*x))?;
            }
            return f.write_str("]");
        }
        for x in &values[..Self::SHOWN - 2] {
            write!(f, "{}, ", Compact(*x))?;
        }
        write!(
            f,
            "…, {}] ({} values)",
            Compact(values[values.len() - 1]),
            values.len()
        )
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
