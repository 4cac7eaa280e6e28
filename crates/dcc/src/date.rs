//! The certificate's dates as the DCC's `xs:date` needs them: the configuration writes them
//! as text (`dates.measured: "2026-11-19 to 2026-11-20"`); the DCC takes calendar dates of
//! ISO 8601 (`2026-11-19`), a span as its first and last day.

use crate::error::{DccError, Result};

/// A calendar date (proleptic Gregorian, years 1–9999).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Date {
    year: u16,
    month: u8,
    day: u8,
}

impl std::fmt::Display for Date {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:04}-{:02}-{:02}", self.year, self.month, self.day)
    }
}

/// The words between a span's first and last day that are understood.
const SEPARATORS: [&str; 5] = [" to ", " – ", " — ", " - ", "/"];

impl Date {
    /// `YYYY-MM-DD`, a real day of the calendar.
    fn parse_exact(text: &str) -> Option<Self> {
        let bytes = text.as_bytes();
        if bytes.len() != 10 || bytes[4] != b'-' || bytes[7] != b'-' {
            return None;
        }
        let digits = |range: std::ops::Range<usize>| -> Option<u16> {
            bytes[range].iter().try_fold(0_u16, |n, b| {
                b.is_ascii_digit().then(|| n * 10 + u16::from(b - b'0'))
            })
        };
        let year = digits(0..4)?;
        let month = u8::try_from(digits(5..7)?).ok()?;
        let day = u8::try_from(digits(8..10)?).ok()?;
        let leap = year % 4 == 0 && (year % 100 != 0 || year % 400 == 0);
        let days = match month {
            1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
            4 | 6 | 9 | 11 => 30,
            2 if leap => 29,
            2 => 28,
            _ => return None,
        };
        (year >= 1 && (1..=days).contains(&day)).then_some(Self { year, month, day })
    }

    /// The date of field `field` (`certificate.dates.issued`).
    pub(crate) fn parse(field: &str, text: &str) -> Result<Self> {
        Self::parse_exact(text.trim()).ok_or_else(|| DccError::Date {
            field: field.to_owned(),
            value: crate::text::Text::free(field, text)
                .map(|t| t.as_str().to_owned())
                .unwrap_or_default(),
            expected: "a calendar date",
            span: "",
        })
    }

    /// The first and last day of field `field`: one date, or two joined by ` to `, an en or
    /// em dash, ` - ` or ISO 8601's `/`.
    pub(crate) fn parse_span(field: &str, text: &str) -> Result<(Self, Self)> {
        let trimmed = text.trim();
        let span = Self::parse_exact(trimmed).map(|d| (d, d)).or_else(|| {
            SEPARATORS.iter().find_map(|sep| {
                let (a, b) = trimmed.split_once(sep)?;
                Some((Self::parse_exact(a.trim())?, Self::parse_exact(b.trim())?))
            })
        });
        let (begin, end) = span.ok_or_else(|| DccError::Date {
            field: field.to_owned(),
            value: crate::text::Text::free(field, text)
                .map(|t| t.as_str().to_owned())
                .unwrap_or_default(),
            expected: "a calendar date or a span of two",
            span: " to 2026-11-20",
        })?;
        if end < begin {
            return Err(DccError::DateOrder {
                begin: begin.to_string(),
                end: end.to_string(),
            });
        }
        Ok((begin, end))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const F: &str = "certificate.dates.measured";

    #[test]
    fn iso_dates_and_spans_are_read() {
        let (b, e) = Date::parse_span(F, "2026-11-19 to 2026-11-20").unwrap();
        assert_eq!(
            (b.to_string(), e.to_string()),
            ("2026-11-19".into(), "2026-11-20".into())
        );
        for text in [
            "2026-11-19/2026-11-20",
            " 2026-11-19 – 2026-11-20 ",
            "2026-11-19 - 2026-11-20",
        ] {
            assert_eq!(Date::parse_span(F, text).unwrap(), (b, e), "{text}");
        }
        let (b, e) = Date::parse_span(F, "2024-02-29").unwrap();
        assert_eq!(b, e);
        assert_eq!(
            Date::parse("f", "0001-01-01").unwrap().to_string(),
            "0001-01-01"
        );
    }

    #[test]
    fn other_dates_are_refused_naming_the_field() {
        for text in [
            "19 November 2026",
            "2026-13-01",
            "2026-02-29",
            "1900-02-29",
            "2026-04-31",
            "0000-01-01",
            "2026-1-19",
            "2026-11-19 to",
            "",
        ] {
            let e = Date::parse_span(F, text).unwrap_err();
            assert!(
                matches!(&e, DccError::Date { field, .. } if field == F),
                "{text}: {e:?}"
            );
            assert!(e.to_string().contains("2026-11-19 to 2026-11-20"), "{e}");
        }
        assert_eq!(
            Date::parse_span(F, "2026-11-20 to 2026-11-19").unwrap_err(),
            DccError::DateOrder {
                begin: "2026-11-20".into(),
                end: "2026-11-19".into()
            }
        );
        let e = Date::parse("certificate.dates.issued", "24.11.2026\u{1b}").unwrap_err();
        assert!(e.to_string().contains("24.11.2026\\\\u{1b}"), "{e}");
    }
}
