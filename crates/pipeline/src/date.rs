//! Calendar dates as the lab profile writes them: ISO 8601 `YYYY-MM-DD`, nothing else (a
//! `31.03.2027` or `03/31/2027` is refused with the ISO form as hint, rather than guessed).

use std::fmt;

/// A day of the Gregorian calendar.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Date {
    year: i32,
    month: u32,
    day: u32,
}

impl fmt::Display for Date {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04}-{:02}-{:02}", self.year, self.month, self.day)
    }
}

const fn days_in_month(year: i32, month: u32) -> u32 {
    match month {
        2 if (year % 4 == 0 && year % 100 != 0) || year % 400 == 0 => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

impl Date {
    fn new(year: i32, month: u32, day: u32) -> Option<Self> {
        ((1..=12).contains(&month) && day >= 1 && day <= days_in_month(year, month))
            .then_some(Self { year, month, day })
    }

    /// `YYYY-MM-DD` exactly (four, two and two digits), a day that exists.
    pub(crate) fn parse_iso(text: &str) -> Option<Self> {
        let t = text.trim();
        let b = t.as_bytes();
        if b.len() != 10 || b[4] != b'-' || b[7] != b'-' {
            return None;
        }
        if !b
            .iter()
            .enumerate()
            .all(|(i, c)| i == 4 || i == 7 || c.is_ascii_digit())
        {
            return None;
        }
        let year = t[..4].parse().ok()?;
        let month = t[5..7].parse().ok()?;
        let day = t[8..].parse().ok()?;
        Self::new(year, month, day)
    }

    /// The ISO form of a date written another common way, for a hint: `DD.MM.YYYY` (German),
    /// `YYYY/MM/DD`, `YYYYMMDD`; `None` when the text is no such date or is ambiguous
    /// (`03/04/2027`: day or month first).
    pub(crate) fn iso_hint(text: &str) -> Option<Self> {
        let t = text.trim();
        let parts: Vec<&str> = t.split(['.', '/', '-']).collect();
        let num = |s: &str| -> Option<u32> {
            (!s.is_empty() && s.bytes().all(|c| c.is_ascii_digit()))
                .then(|| s.parse().ok())
                .flatten()
        };
        match parts.as_slice() {
            [d, m, y] if t.contains('.') && y.len() == 4 => {
                Self::new(i32::try_from(num(y)?).ok()?, num(m)?, num(d)?)
            }
            [y, m, d] if y.len() == 4 => Self::new(i32::try_from(num(y)?).ok()?, num(m)?, num(d)?),
            [one] if one.len() == 8 => Self::new(
                i32::try_from(num(&one[..4])?).ok()?,
                num(&one[4..6])?,
                num(&one[6..])?,
            ),
            _ => None,
        }
    }

    /// The last day of a measurement written `YYYY-MM-DD` or `YYYY-MM-DD to YYYY-MM-DD`
    /// (also with `–`, `—` or `..`), `None` for anything else.
    pub(crate) fn last_of_span(text: &str) -> Option<Self> {
        let t = text.trim();
        if let Some(d) = Self::parse_iso(t) {
            return Some(d);
        }
        for separator in [" to ", "–", "—", ".."] {
            if let Some((from, to)) = t.split_once(separator) {
                let (from, to) = (Self::parse_iso(from)?, Self::parse_iso(to)?);
                return (from <= to).then_some(to);
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iso_dates_only() {
        assert_eq!(
            Date::parse_iso("2027-03-31").map(|d| d.to_string()),
            Some("2027-03-31".into())
        );
        assert_eq!(Date::parse_iso("2028-02-29").map(|d| d.day), Some(29));
        for bad in [
            "2027-02-29",
            "2027-13-01",
            "2027-3-31",
            "31.03.2027",
            "2027/03/31",
            "",
            "2027-03-31x",
        ] {
            assert_eq!(Date::parse_iso(bad), None, "{bad}");
        }
    }

    #[test]
    fn hints_and_spans() {
        let hint = |t: &str| Date::iso_hint(t).map(|d| d.to_string());
        assert_eq!(hint("31.03.2027").as_deref(), Some("2027-03-31"));
        assert_eq!(hint("2027/03/31").as_deref(), Some("2027-03-31"));
        assert_eq!(hint("20270331").as_deref(), Some("2027-03-31"));
        assert_eq!(hint("03/31/2027"), None);
        let last = |t: &str| Date::last_of_span(t).map(|d| d.to_string());
        assert_eq!(
            last("2026-12-03 to 2026-12-04").as_deref(),
            Some("2026-12-04")
        );
        assert_eq!(last("2026-12-03").as_deref(), Some("2026-12-03"));
        assert_eq!(last("2026-12-05 to 2026-12-04"), None);
        assert_eq!(last("early December"), None);
    }
}
