//! Calendar dates as the records keep them: ISO 8601 `YYYY-MM-DD` (proleptic Gregorian),
//! counted as days since 1970-01-01 for the drift fits, and a certificate's `measured` span
//! (`2026-11-19 to 2026-11-20`) read as its first and last day.

use std::fmt;

use crate::error::{RecordsError, Result};

/// Days in a mean Gregorian year: the drift rates are per year of 365.2425 days.
pub const DAYS_PER_YEAR: f64 = 365.2425;

/// A calendar date (years 1–9999).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Date {
    /// Days since 1970-01-01 (negative before).
    days: i64,
}

/// The words between a span's first and last day that are understood (as the DCC reads them).
const SEPARATORS: [&str; 5] = [" to ", " – ", " — ", " - ", "/"];

impl Date {
    /// The date `year-month-day`, if it is a day of the calendar.
    pub fn from_ymd(year: i64, month: u32, day: u32) -> Option<Self> {
        let leap = year % 4 == 0 && (year % 100 != 0 || year % 400 == 0);
        let days_in_month = match month {
            1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
            4 | 6 | 9 | 11 => 30,
            2 if leap => 29,
            2 => 28,
            _ => return None,
        };
        if !(1..=9999).contains(&year) || !(1..=days_in_month).contains(&day) {
            return None;
        }
        // Howard Hinnant's days_from_civil.
        let y = if month <= 2 { year - 1 } else { year };
        let era = y.div_euclid(400);
        let yoe = y - era * 400;
        let m = i64::from(month);
        let doy = (153 * (if m > 2 { m - 3 } else { m + 9 }) + 2) / 5 + i64::from(day) - 1;
        let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
        Some(Self {
            days: era * 146_097 + doe - 719_468,
        })
    }

    /// The date `days` days after 1970-01-01.
    pub const fn from_days(days: i64) -> Self {
        Self { days }
    }

    /// Days since 1970-01-01.
    pub const fn days(self) -> i64 {
        self.days
    }

    /// (year, month, day).
    pub fn ymd(self) -> (i64, u32, u32) {
        // Howard Hinnant's civil_from_days.
        let z = self.days + 719_468;
        let era = z.div_euclid(146_097);
        let doe = z - era * 146_097;
        let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
        let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
        let mp = (5 * doy + 2) / 153;
        let day = doy - (153 * mp + 2) / 5 + 1;
        let month = if mp < 10 { mp + 3 } else { mp - 9 };
        let year = yoe + era * 400 + i64::from(month <= 2);
        (
            year,
            u32::try_from(month).unwrap_or(1),
            u32::try_from(day).unwrap_or(1),
        )
    }

    /// `YYYY-MM-DD`, else `None`.
    pub fn parse(text: &str) -> Option<Self> {
        let b = text.trim().as_bytes();
        if b.len() != 10 || b[4] != b'-' || b[7] != b'-' {
            return None;
        }
        let num = |r: std::ops::Range<usize>| -> Option<i64> {
            b[r].iter().try_fold(0_i64, |n, c| {
                c.is_ascii_digit().then(|| n * 10 + i64::from(c - b'0'))
            })
        };
        Self::from_ymd(
            num(0..4)?,
            u32::try_from(num(5..7)?).ok()?,
            u32::try_from(num(8..10)?).ok()?,
        )
    }

    /// The date of a field, or an error naming it.
    ///
    /// # Errors
    /// [`RecordsError::Date`] when `text` is not `YYYY-MM-DD`.
    pub fn parse_field(field: &str, text: &str) -> Result<Self> {
        Self::parse(text).ok_or_else(|| RecordsError::Date {
            field: field.to_owned(),
            value: text.chars().take(60).collect(),
        })
    }

    /// A certificate's `measured`: one day, or a span's first and last day.
    ///
    /// # Errors
    /// [`RecordsError::Date`] naming `field` when neither form is found.
    pub fn parse_span(field: &str, text: &str) -> Result<(Self, Self)> {
        if let Some(d) = Self::parse(text) {
            return Ok((d, d));
        }
        for sep in SEPARATORS {
            if let Some((a, b)) = text.split_once(sep)
                && let (Some(first), Some(last)) = (Self::parse(a), Self::parse(b))
                && first <= last
            {
                return Ok((first, last));
            }
        }
        Err(RecordsError::Date {
            field: field.to_owned(),
            value: text.chars().take(60).collect(),
        })
    }

    /// Years (of [`DAYS_PER_YEAR`]) from `origin` to `self`.
    pub fn years_since(self, origin: Self) -> f64 {
        #[allow(clippy::cast_precision_loss)] // days within ±10⁷
        let d = (self.days - origin.days) as f64;
        d / DAYS_PER_YEAR
    }

    /// The date `years` years (of [`DAYS_PER_YEAR`]) after `self`, to the nearest day.
    pub fn plus_years(self, years: f64) -> Self {
        #[allow(clippy::cast_possible_truncation)] // a finite interval of years
        let d = (years * DAYS_PER_YEAR).round() as i64;
        Self {
            days: self.days + d,
        }
    }
}

impl fmt::Display for Date {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (y, m, d) = self.ymd();
        write!(f, "{y:04}-{m:02}-{d:02}")
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for Date {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn days_round_trip_and_known_days() {
        assert_eq!(Date::parse("1970-01-01").map(Date::days), Some(0));
        assert_eq!(Date::parse("2000-03-01").map(Date::days), Some(11_017));
        for days in [-700_000, -1, 0, 59, 60, 11_016, 20_000, 2_900_000] {
            let d = Date::from_days(days);
            assert_eq!(Date::parse(&d.to_string()), Some(d), "{d}");
        }
        assert_eq!(Date::parse("2027-02-29"), None);
        assert_eq!(
            Date::parse("2028-02-29").map(|d| d.to_string()).as_deref(),
            Some("2028-02-29")
        );
        assert_eq!(Date::parse("2026-13-01"), None);
    }

    #[test]
    fn spans() {
        let (a, b) = Date::parse_span("measured", "2026-11-19 to 2026-11-20").unwrap();
        assert_eq!(
            (a.to_string(), b.to_string()),
            ("2026-11-19".into(), "2026-11-20".into())
        );
        assert!(matches!(
            Date::parse_span("certificate.dates.measured", "last week"),
            Err(RecordsError::Date { field, .. }) if field == "certificate.dates.measured"
        ));
    }
}
