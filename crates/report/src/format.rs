//! Numbers as a person writes them on a certificate or in a summary: an uncertainty with two
//! significant digits and its value rounded to the same place (JCGM 100 §7.2.6), powers of
//! ten as `× 10⁻⁶` rather than `e-6`, effective degrees of freedom above 1000 as `> 1000`,
//! and never a `-0` or `-0.00`.

use pipeline::DegreesOfFreedom;

/// The exponent of ten of `x`'s leading digit (0 for zero or a non-finite number).
fn exponent(x: f64) -> i32 {
    if x == 0.0 || !x.is_finite() {
        0
    } else {
        // |x| < 1e308, so the floor fits an i32
        x.abs().log10().floor() as i32
    }
}

/// `text` without a minus sign in front of a zero (`-0`, `-0.00`, `-0.0e0`).
fn no_negative_zero(text: String) -> String {
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| matches!(c, '0' | '.')) => rest.to_owned(),
        _ => text,
    }
}

/// `x` with `decimals` digits after the point, never `-0.00`.
pub(crate) fn fixed(x: f64, decimals: usize) -> String {
    no_negative_zero(format!("{x:.decimals$}"))
}

/// Superscript digits for an exponent: `-6` → `⁻⁶`.
pub(crate) fn superscript(n: i32) -> String {
    n.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            '9' => '⁹',
            other => other,
        })
        .collect()
}

/// `10⁻⁸` for -8.
pub(crate) fn power_of_ten(n: i32) -> String {
    format!("10{}", superscript(n))
}

/// How many decimals an uncertainty `u` (in the unit it is written in) needs for two
/// significant digits; zero for an uncertainty of 10 or more.
fn decimals_for(u: f64) -> usize {
    let e = exponent(u);
    usize::try_from(1 - e).unwrap_or(0)
}

/// A value and its uncertainty written together as a person writes them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Pair {
    /// The value, rounded to the uncertainty's last digit.
    pub value: String,
    /// The uncertainty, two significant digits.
    pub u: String,
    /// The common power of ten (`× 10⁻⁶`), empty when none is needed.
    pub scale: String,
}

impl Pair {
    /// `(2.3456 ± 0.0012) × 10⁻⁶` or `4.12 ± 0.56`.
    pub(crate) fn joined(&self) -> String {
        if self.scale.is_empty() {
            format!("{} ± {}", self.value, self.u)
        } else {
            format!("({} ± {}) {}", self.value, self.u, self.scale)
        }
    }
}

/// A value with its (expanded or standard) uncertainty `u`, both scaled by one power of ten
/// chosen by the larger of the two (engineering steps of three are not used: a certificate writes
/// `× 10⁻⁶` or `× 10⁻⁷` as the value needs). Numbers between 0.01 and 10 000 are written
/// without a power of ten.
pub(crate) fn pair(value: f64, u: f64) -> Pair {
    let e = exponent(value.abs().max(u));
    let scale_exp = if (-2..5).contains(&e) { 0 } else { e };
    let s = 10f64.powi(scale_exp);
    let (v, uu) = (value / s, u / s);
    let decimals = if uu > 0.0 { decimals_for(uu) } else { 4 };
    Pair {
        value: fixed(v, decimals),
        u: fixed(uu, decimals),
        scale: if scale_exp == 0 {
            String::new()
        } else {
            format!("× {}", power_of_ten(scale_exp))
        },
    }
}

/// A value with an asymmetric interval: `below` and `above` are the widths to its ends.
/// Written `2.3457 +0.0012/-0.0010 × 10⁻⁶` parts: (value, plus, minus, scale).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Asymmetric {
    /// The value, rounded to the smaller width's second digit.
    pub value: String,
    /// The width above.
    pub plus: String,
    /// The width below.
    pub minus: String,
    /// The common power of ten, empty when none is needed.
    pub scale: String,
    /// Its exponent (0 when none is needed).
    pub exponent: i32,
}

/// A value and an interval about it; symmetric intervals (widths within 5 %) are written as
/// `value ± U` in `Asymmetric::plus`, with `minus` empty.
pub(crate) fn interval(value: f64, below: f64, above: f64) -> Asymmetric {
    let symmetric = (below - above).abs() <= 0.05 * below.max(above);
    let e = exponent(value.abs().max(below).max(above));
    let scale_exp = if (-2..5).contains(&e) { 0 } else { e };
    let s = 10f64.powi(scale_exp);
    let smallest = if symmetric {
        below.max(above)
    } else {
        below.min(above)
    } / s;
    let decimals = if smallest > 0.0 {
        decimals_for(smallest)
    } else {
        4
    };
    Asymmetric {
        value: fixed(value / s, decimals),
        plus: fixed(above.max(if symmetric { below } else { 0.0 }) / s, decimals),
        minus: if symmetric {
            String::new()
        } else {
            fixed(below / s, decimals)
        },
        scale: if scale_exp == 0 {
            String::new()
        } else {
            format!("× {}", power_of_ten(scale_exp))
        },
        exponent: scale_exp,
    }
}

/// `x` with two significant digits and no power of ten (`0.00033`, `12`, `0.87`).
pub(crate) fn two_digits(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return plain(x);
    }
    fixed(x, decimals_for(x))
}

impl Asymmetric {
    /// `(2.3457 ± 0.0012) × 10⁻⁶`, `0.945 ± 0.16`, `(2.3457 +0.0012/-0.0010) × 10⁻⁶`.
    pub(crate) fn joined(&self) -> String {
        let inner = if self.minus.is_empty() {
            format!("{} ± {}", self.value, self.plus)
        } else {
            format!("{} +{}/-{}", self.value, self.plus, self.minus)
        };
        if self.scale.is_empty() {
            inner
        } else {
            format!("({inner}) {}", self.scale)
        }
    }
}

/// A number alone with `digits` significant digits: plain between 0.01 and 10 000, else as
/// `1.23 × 10⁻⁸`.
pub(crate) fn significant(x: f64, digits: usize) -> String {
    if x == 0.0 {
        return "0".to_owned();
    }
    let e = exponent(x);
    let digits = digits.max(1);
    if (-2..5).contains(&e) {
        let decimals = usize::try_from(i32::try_from(digits).unwrap_or(3) - 1 - e).unwrap_or(0);
        fixed(x, decimals)
    } else {
        let mantissa = x / 10f64.powi(e);
        // rounding may carry the mantissa to 10
        let m = fixed(mantissa, digits - 1);
        if m.trim_start_matches('-').starts_with("10") {
            format!(
                "{} × {}",
                fixed(mantissa / 10.0, digits - 1),
                power_of_ten(e + 1)
            )
        } else {
            format!("{m} × {}", power_of_ten(e))
        }
    }
}

/// `text` with each hyphen-minus that starts a number (at the start, or after a space, `(`,
/// `[`, `/`, `±` or `×`, and followed by a digit or a point) set as the minus sign U+2212, as
/// a typeset page writes it. Hyphens inside words, dates and identifiers (`SN-12`,
/// `2026-11-28`) are left. Only for numbers this tool wrote: never for text from a study file.
pub(crate) fn typographic_minus(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 4);
    let mut prev: Option<char> = None;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        let starts_number = c == '-'
            && prev.is_none_or(|p| p.is_whitespace() || matches!(p, '(' | '[' | '/' | '±' | '×'))
            && chars
                .peek()
                .is_some_and(|n| n.is_ascii_digit() || *n == '.');
        out.push(if starts_number { '\u{2212}' } else { c });
        prev = Some(c);
    }
    out
}

/// A number as given, in its shortest exact form (`20`, `-0.5`, `1e-7`), never `-0`.
pub(crate) fn plain(x: f64) -> String {
    no_negative_zero(format!("{x}"))
}

/// Effective degrees of freedom as a person writes them, by the one formatter
/// (`uncertainty::Dof`'s `Display`): a whole number up to 1000, `> 1000` above, one decimal
/// for a fraction below 10, `∞` for infinitely many.
pub(crate) fn dof(d: DegreesOfFreedom) -> String {
    d.to_string()
}

/// A share of a variance in percent: one decimal, `< 0.1` for a positive share below it,
/// `0` for none (never `-0.00`).
pub(crate) fn percent(p: f64) -> String {
    if p <= 0.0 {
        "0".to_owned()
    } else if p < 0.05 {
        "< 0.1".to_owned()
    } else {
        fixed(p, 1)
    }
}

/// A coverage factor: three significant digits (`2.00`, `2.09`, `12.7`).
pub(crate) fn coverage_factor(k: f64) -> String {
    significant(k, 3)
}

/// A rate in deg/s: at most six decimals, trailing zeros dropped (`20`, `19.999871`).
pub(crate) fn rate(rate_deg_s: f64) -> String {
    let text = fixed(rate_deg_s, 6);
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    }
}

/// A round step for about `n` ticks over `range` (1, 2 or 5 times a power of ten).
pub(crate) fn nice_step(range: f64, n: f64) -> f64 {
    let raw = (range / n).abs();
    if raw == 0.0 || !raw.is_finite() {
        return 1.0;
    }
    let p = 10f64.powi(exponent(raw));
    let m = raw / p;
    let nice = if m <= 1.0 {
        1.0
    } else if m <= 2.0 {
        2.0
    } else if m <= 5.0 {
        5.0
    } else {
        10.0
    };
    nice * p
}

/// An axis tick label: `20` not `20.0`, `0.5`, `2.5 × 10⁻⁸` written `2.5e-8` → with a
/// superscript exponent.
pub(crate) fn tick(x: f64, step: f64) -> String {
    if x.abs() < step.abs() * 1e-9 {
        return "0".to_owned();
    }
    let e = exponent(step);
    if (-3..6).contains(&exponent(x)) && e >= -3 {
        let decimals = usize::try_from(-e).unwrap_or(0);
        let text = fixed(x, decimals);
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            text
        }
    } else {
        let ex = exponent(x);
        let mantissa = x / 10f64.powi(ex);
        let digits = usize::try_from(ex - e).unwrap_or(0);
        let m = fixed(mantissa, digits);
        let m = if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            m
        };
        if m == "1" {
            power_of_ten(ex)
        } else if m == "-1" {
            format!("-{}", power_of_ten(ex))
        } else {
            format!("{m}×{}", power_of_ten(ex))
        }
    }
}

/// Escapes text for HTML.
pub(crate) fn esc(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Text from a file or a configuration written into Markdown (`report.md`) as text, never as
/// markup: `&`, `<` and `>` become HTML entities (no raw HTML reaches a renderer), the
/// characters that start code, emphasis, links, images or table cells within a line (`\\`,
/// `` ` ``, `*`, `[`, `]`, `|`) are escaped with a backslash, and hidden characters (controls,
/// line breaks, bidirectional overrides) are written visibly. The text is always inline (a
/// table cell or a sentence), so what matters only at a line's start needs nothing.
pub(crate) fn md_text(text: &str) -> String {
    let shown = edge_io::visible(text);
    let mut out = String::with_capacity(shown.len() + 8);
    for c in shown.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '\\' | '`' | '*' | '[' | ']' | '|' => {
                out.push('\\');
                out.push(c);
            }
            c => out.push(c),
        }
    }
    out
}

/// A Markdown table's head: the row of column names as given (`| rate | output |`), then the
/// `|---|` row under it, one `|---` a column.
pub(crate) fn table_head(out: &mut String, head: &str) {
    use std::fmt::Write as _;
    let _ = writeln!(out, "{head}");
    let _ = writeln!(out, "{}|", "|---".repeat(head.matches(" | ").count() + 1));
}

#[cfg(test)]
mod tests {
    use super::*;
    use pipeline::InfiniteDof;

    #[test]
    fn minus_signs_of_numbers_only() {
        assert_eq!(
            typographic_minus("-0.0967 g to 2.36 g"),
            "\u{2212}0.0967 g to 2.36 g"
        );
        assert_eq!(
            typographic_minus("(-1.5 ± 0.2) × 10⁻⁶ [-3, -.5]"),
            "(\u{2212}1.5 ± 0.2) × 10⁻⁶ [\u{2212}3, \u{2212}.5]"
        );
        assert_eq!(typographic_minus("+0.1 / -0.2"), "+0.1 / \u{2212}0.2");
        // identifiers, dates, words and a lone dash stay as they are
        for kept in ["SN-12", "2026-11-28", "IA-in", "-", "—", "a - b", "x-1"] {
            assert_eq!(typographic_minus(kept), kept);
        }
    }

    #[test]
    fn markdown_text_is_never_markup() {
        let t = md_text("<img src=x onerror=alert(1)> `code` [a](javascript:x) | *b* \u{1b}[31m");
        assert!(!t.contains('<') && !t.contains('>'), "{t}");
        assert!(t.contains("&lt;img"), "{t}");
        assert!(t.contains("\\`code\\`"), "{t}");
        assert!(t.contains("\\[a\\](javascript:x)"), "{t}");
        assert!(t.contains("\\|") && t.contains("\\*b\\*"), "{t}");
        assert!(!t.contains('\u{1b}'), "{t}");
        assert_eq!(md_text("SN 1604"), "SN 1604");
    }

    #[test]
    fn a_value_is_rounded_to_its_uncertainty() {
        assert_eq!(pair(4.123_456, 0.5612).joined(), "4.12 ± 0.56");
        assert_eq!(
            pair(2.345_678e-6, 1.234e-9).joined(),
            "(2.3457 ± 0.0012) × 10⁻⁶"
        );
        assert_eq!(pair(-0.000_4, 0.02).joined(), "0.000 ± 0.020");
        assert_eq!(pair(1234.6, 56.0).joined(), "1235 ± 56");
        assert_eq!(pair(0.501, 0.0012).joined(), "0.5010 ± 0.0012");
    }

    #[test]
    fn an_asymmetric_interval_keeps_both_widths() {
        assert_eq!(
            interval(5.29e-7, 0.87e-7, 0.87e-7).joined(),
            "(5.29 ± 0.87) × 10⁻⁷"
        );
        assert_eq!(
            interval(5.29e-7, 0.60e-7, 0.90e-7).joined(),
            "(5.29 +0.90/-0.60) × 10⁻⁷"
        );
        assert_eq!(interval(0.946, 0.16, 0.16).joined(), "0.95 ± 0.16");
    }

    #[test]
    fn no_negative_zero_anywhere() {
        assert_eq!(fixed(-0.0001, 2), "0.00");
        assert_eq!(fixed(-0.0, 0), "0");
        assert_eq!(fixed(-0.1, 2), "-0.10");
        assert_eq!(percent(-1e-9), "0");
        assert_eq!(percent(0.01), "< 0.1");
        assert_eq!(percent(12.345), "12.3");
    }

    #[test]
    fn degrees_of_freedom_as_a_person_writes_them() {
        assert_eq!(dof(DegreesOfFreedom::Finite(79_552_918.2)), "> 1000");
        assert_eq!(dof(DegreesOfFreedom::Finite(14.2)), "14");
        assert_eq!(dof(DegreesOfFreedom::Finite(3.46)), "3.5");
        assert_eq!(dof(DegreesOfFreedom::Infinite(InfiniteDof::Infinite)), "∞");
    }

    #[test]
    fn significant_digits_and_powers_of_ten() {
        assert_eq!(significant(1.6e-6, 3), "1.60 × 10⁻⁶");
        assert_eq!(significant(9.996e-6, 3), "1.00 × 10⁻⁵");
        assert_eq!(significant(2.0, 3), "2.00");
        assert_eq!(significant(123.4, 3), "123");
        assert_eq!(coverage_factor(2.093), "2.09");
        assert_eq!(rate(20.0), "20");
        assert_eq!(rate(19.999_871_4), "19.999871");
    }

    #[test]
    fn tick_labels() {
        assert_eq!(tick(20.0, 20.0), "20");
        assert_eq!(tick(0.5, 0.1), "0.5");
        assert_eq!(tick(1e-8, 1e-8), "10⁻⁸");
        assert_eq!(tick(2e-8, 1e-8), "2×10⁻⁸");
        assert_eq!(tick(-2.5e-8, 5e-9), "-2.5×10⁻⁸");
        assert_eq!(tick(1e-20, 1e-8), "0");
    }
}
