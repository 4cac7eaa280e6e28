//! The decimal parser: Clinger's fast path, the standard library's parser otherwise.

/// Exact powers of ten representable in `f64`.
pub(super) const POW10: [f64; 23] = {
    let mut p = [1.0; 23];
    let mut i = 1;
    while i < 23 {
        p[i] = p[i - 1] * 10.0;
        i += 1;
    }
    p
};

/// Parses a decimal number (surrounding blanks allowed). Fast path: up to 19 significant
/// digits with a decimal exponent within ±22 are exact (Clinger's fast path: an exactly
/// representable mantissa times or over an exact power of ten is correctly rounded);
/// everything else (more digits, large exponents, `nan`, `inf`) goes to the standard
/// library's parser. `None` if the field is not a number. With `comma`, the decimal mark
/// is `,` and a `.` is not a number.
pub(super) fn parse_f64(field: &[u8], comma: bool) -> Option<f64> {
    let f = field.trim_ascii();
    let mark = if comma { b',' } else { b'.' };
    if let Some(v) = fast_f64(f, mark) {
        return Some(v);
    }
    if comma {
        if f.contains(&b'.') {
            return None;
        }
        let swapped: Vec<u8> = f
            .iter()
            .map(|&b| if b == b',' { b'.' } else { b })
            .collect();
        return std::str::from_utf8(&swapped).ok()?.parse().ok();
    }
    std::str::from_utf8(f).ok()?.parse().ok()
}

/// A number field as the lab-file readers read it (the one number syntax of the workspace's lab
/// files: a decimal point, or with `decimal_comma` a decimal comma and no point; surrounding
/// blanks allowed; `nan` and `inf` as the standard library reads them). `None` if it is not a
/// number. `centrifuge-cal init` guesses a file's layout with it, so what init takes for a
/// number is what the readers then read.
///
/// ```
/// assert_eq!(recording::parse_number("0,05", true), Some(0.05));
/// assert_eq!(recording::parse_number("0.05", true), None);
/// assert_eq!(recording::parse_number(" -1.5e3 ", false), Some(-1500.0));
/// assert_eq!(recording::parse_number("1,5", false), None);
/// ```
#[must_use]
pub fn parse_number(field: &str, decimal_comma: bool) -> Option<f64> {
    parse_f64(field.as_bytes(), decimal_comma)
}

/// The decimal parser as the fuzz targets and tests see it: `(parse_f64, fast_f64)` of
/// `field` with a decimal point, the full parser and its fast path alone (`None` where the
/// fast path declines). Not part of the crate's interface.
#[doc(hidden)]
pub fn number_paths(field: &[u8]) -> (Option<f64>, Option<f64>) {
    (parse_f64(field, false), fast_f64(field.trim_ascii(), b'.'))
}

/// `fast_prefix` over the whole field.
pub(super) fn fast_f64(s: &[u8], mark: u8) -> Option<f64> {
    fast_prefix(s, mark).and_then(|(v, used)| (used == s.len()).then_some(v))
}

/// The fast path of [`parse_f64`] on the number at the start of `s`: its value and length,
/// or `None` when it is not a plain decimal number the fast path computes exactly. `mark` is
/// the decimal mark (`.` or `,`).
#[inline(always)]
pub(super) fn fast_prefix(s: &[u8], mark: u8) -> Option<(f64, usize)> {
    let mut i = 0;
    let negative = match s.first() {
        Some(b'-') => {
            i = 1;
            true
        }
        Some(b'+') => {
            i = 1;
            false
        }
        _ => false,
    };
    // Integer and fraction digits; leading zeros count too (a field of more than 19 digits
    // goes to the standard parser, which is rare and still correct).
    let int_start = i;
    let mut mantissa: u64 = 0;
    while let Some(four) = four_digits(s, i) {
        mantissa = mantissa.wrapping_mul(10_000).wrapping_add(u64::from(four));
        i += 4;
    }
    while let Some(d) = s.get(i).map(|b| b.wrapping_sub(b'0')).filter(|d| *d <= 9) {
        mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(d));
        i += 1;
    }
    let mut digits = i - int_start;
    let mut exponent: i32 = 0;
    if s.get(i) == Some(&mark) {
        i += 1;
        let frac_start = i;
        while let Some(four) = four_digits(s, i) {
            mantissa = mantissa.wrapping_mul(10_000).wrapping_add(u64::from(four));
            i += 4;
        }
        while let Some(d) = s.get(i).map(|b| b.wrapping_sub(b'0')).filter(|d| *d <= 9) {
            mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(d));
            i += 1;
        }
        digits += i - frac_start;
        exponent = -((i - frac_start) as i32);
    }
    if digits == 0 || digits > 19 {
        return None;
    }
    if i < s.len() && (s[i] == b'e' || s[i] == b'E') {
        i += 1;
        let mut exp_negative = false;
        if i < s.len() && (s[i] == b'-' || s[i] == b'+') {
            exp_negative = s[i] == b'-';
            i += 1;
        }
        let start = i;
        let mut e: i32 = 0;
        while i < s.len() && s[i].is_ascii_digit() && e < 10_000 {
            e = e * 10 + i32::from(s[i] - b'0');
            i += 1;
        }
        if i == start {
            return None;
        }
        exponent += if exp_negative { -e } else { e };
    }
    if mantissa > (1 << 53) || !(-22..=22).contains(&exponent) {
        return None;
    }
    let m = mantissa as f64;
    let v = if exponent < 0 {
        m / POW10[(-exponent) as usize]
    } else {
        m * POW10[exponent as usize]
    };
    Some((if negative { -v } else { v }, i))
}

/// The value of four ASCII digits at `s[i..i + 4]`, if they are all digits (SWAR: one
/// 32-bit word, two multiplications).
#[inline(always)]
pub(super) fn four_digits(s: &[u8], i: usize) -> Option<u32> {
    let bytes: [u8; 4] = s.get(i..i + 4)?.try_into().ok()?;
    let v = u32::from_le_bytes(bytes);
    // Every byte in '0'..='9': high nibble 3, and adding 6 keeps it below 0x40.
    if (v & 0xF0F0_F0F0) | ((v.wrapping_add(0x0606_0606) & 0xF0F0_F0F0) >> 4) != 0x3333_3333 {
        return None;
    }
    let v = v - 0x3030_3030;
    // Byte 0 becomes 10·d0 + d1 and byte 2 becomes 10·d2 + d3 (no byte exceeds 99).
    let v = v.wrapping_mul(10).wrapping_add(v >> 8);
    // (a + c·2¹⁶)·(1 + 100·2¹⁶) holds 100·a + c in bits 16…31.
    let w = u64::from(v & 0x00FF_00FF);
    Some((((w * (1 + (100 << 16))) >> 16) & 0xFFFF) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_parser_agrees_with_std() {
        let cases = [
            "0",
            "-0",
            "1",
            "+1.5",
            "0.001",
            "123456.789",
            "-3.2385",
            "1e-3",
            "2.5E+2",
            "00012.50",
            "1234567890123456789",
            "12345678901234567890",
            "0.1234567890123456789",
            "1e22",
            "1e23",
            "1e-22",
            "1e-23",
            "9007199254740993",
            "4.9e-324",
            "1.7976931348623157e308",
            ".5",
            "5.",
            "nan",
            "NaN",
            "inf",
            "-inf",
            "infinity",
        ];
        for c in cases {
            let want: f64 = c.parse().unwrap();
            let got = parse_f64(c.as_bytes(), false).unwrap();
            assert!(
                got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                "{c}: {got} vs {want}"
            );
        }
        for bad in ["", "-", ".", "e5", "1e", "1.2.3", "12a", "0x10", "1,5"] {
            assert_eq!(parse_f64(bad.as_bytes(), false), None, "{bad:?}");
        }
    }

    #[test]
    fn fast_parser_is_exact_on_random_decimals() {
        // A deterministic walk over mantissas and exponents.
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let digits = (x % 17) as u32 + 1;
            let m = (x >> 8) % 10u64.pow(digits);
            let e = (x >> 40) % 30;
            let s = format!("{m}e-{e}");
            let want: f64 = s.parse().unwrap();
            assert_eq!(
                parse_f64(s.as_bytes(), false).unwrap().to_bits(),
                want.to_bits(),
                "{s}"
            );
            let comma = s.replace('.', ",");
            assert_eq!(
                parse_f64(comma.as_bytes(), true).unwrap().to_bits(),
                want.to_bits(),
                "{comma}"
            );
        }
    }

    #[test]
    fn decimal_comma() {
        for (text, want) in [
            ("1,5", 1.5),
            ("-0,001", -0.001),
            ("12345678901234567890,5", 12345678901234567890.5),
            ("2,5e-3", 2.5e-3),
            ("7", 7.0),
        ] {
            assert_eq!(parse_f64(text.as_bytes(), true), Some(want), "{text}");
        }
        assert_eq!(parse_f64(b"1.5", true), None);
        assert_eq!(parse_f64(b"1,5", false), None);
    }
}
