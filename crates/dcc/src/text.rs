//! Text that may enter the certificate: every string from the study's configuration, its
//! files or its results passes one of two gates before the XML writer (which escapes `<`,
//! `>`, `&`, quotes and CR) sees it.
//!
//! - [`Text::identification`] (the certificate's id, the item's serial number, model and
//!   manufacturer, the names of the laboratory, the customer and the persons, an instrument's
//!   identity, the previous certificate's id): a character that XML 1.0 cannot hold (C0
//!   controls but tab, LF and CR; U+FFFE, U+FFFF), a control character of any kind (C0 with
//!   tab, LF and CR, DEL, C1) or a bidirectional override or isolate (U+202A–U+202E,
//!   U+2066–U+2069) is refused with [`DccError::HiddenCharacter`] naming the field: an
//!   identification must read as what it is.
//! - [`Text::free`] (addresses, descriptions, conditions, statements, file paths, the
//!   study's own words): the same characters are written visibly instead (`\u{1b}` for ESC,
//!   `<U+202E>` for a bidirectional override, `<U+FFFE>` for a non-character), so the document
//!   stays valid XML and shows what the source held.
//!
//! Both trim white space at the ends (the DCC's `notEmptyStringType` has none there) and
//! refuse an empty text ([`DccError::EmptyText`]).

use crate::error::{DccError, Result};

/// Text checked for the certificate: it holds no character XML 1.0 cannot hold, no control
/// character and no bidirectional override, and has no white space at its ends.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Text(String);

impl Text {
    /// An identification: refused when it holds a hidden character or is blank.
    pub(crate) fn identification(field: &str, text: &str) -> Result<Self> {
        let trimmed = trim(text);
        if let Some((position, c)) = trimmed
            .chars()
            .enumerate()
            .find(|(_, c)| is_hidden(*c) || is_xml_forbidden(*c))
        {
            return Err(DccError::HiddenCharacter {
                field: field.to_owned(),
                code_point: u32::from(c),
                position: position + 1,
            });
        }
        Self::non_empty(field, trimmed.to_owned())
    }

    /// Free text: hidden characters written visibly; refused only when blank.
    pub(crate) fn free(field: &str, text: &str) -> Result<Self> {
        Self::non_empty(field, visible(trim(text)))
    }

    /// Text the writer itself composes from checked parts and its own words.
    pub(crate) fn own(text: impl Into<String>) -> Self {
        let text = text.into();
        debug_assert!(!text.chars().any(|c| is_hidden(c) || is_xml_forbidden(c)));
        Self(text)
    }

    fn non_empty(field: &str, text: String) -> Result<Self> {
        if text.is_empty() {
            return Err(DccError::EmptyText {
                field: field.to_owned(),
            });
        }
        Ok(Self(text))
    }

    /// The text.
    pub(crate) fn as_str(&self) -> &str {
        &self.0
    }
}

/// `text` without white space at its ends, as XML Schema's `\s` counts it (space, tab, LF,
/// CR) and as Rust does otherwise.
fn trim(text: &str) -> &str {
    text.trim()
}

/// Whether `c` hides, reorders or acts instead of showing (the workspace's one definition:
/// C0 and C1 controls, DEL, bidirectional overrides and isolates).
const fn is_hidden(c: char) -> bool {
    edge_io::is_hidden(c)
}

/// Whether XML 1.0 cannot hold `c` at all (its `Char` production): C0 controls but tab, LF
/// and CR, and the non-characters U+FFFE and U+FFFF (surrogates are not `char`s).
const fn is_xml_forbidden(c: char) -> bool {
    matches!(c, '\u{0}'..='\u{8}' | '\u{b}' | '\u{c}' | '\u{e}'..='\u{1f}' | '\u{fffe}' | '\u{ffff}')
}

/// `text` with every hidden or XML-forbidden character written visibly, as the workspace
/// writes them (`edge_io::visible`: `\u{1b}` for a control character, `<U+202E>` for a
/// bidirectional override or isolate), and the non-characters U+FFFE and U+FFFF, which only
/// XML refuses, as `<U+FFFE>`.
fn visible(text: &str) -> String {
    let shown = edge_io::visible(text);
    if !shown.chars().any(is_xml_forbidden) {
        return shown.into_owned();
    }
    shown
        .chars()
        .map(|c| {
            if is_xml_forbidden(c) {
                format!("<U+{:04X}>", u32::from(c))
            } else {
                c.to_string()
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_identification_with_a_hidden_character_is_refused_by_its_field() {
        for (text, code_point, position) in [
            ("SN \u{202e}evil\u{202c} 1234", 0x202e, 4),
            ("SN\u{0}1", 0, 3),
            ("a\u{1b}]0;x\u{7}", 0x1b, 2),
            ("c1 \u{9b}", 0x9b, 4),
            ("x\u{fffe}", 0xfffe, 2),
            ("two\nlines", 0x0a, 4),
        ] {
            let e = Text::identification("certificate.item.serial", text).unwrap_err();
            assert_eq!(
                e,
                DccError::HiddenCharacter {
                    field: "certificate.item.serial".to_owned(),
                    code_point,
                    position,
                },
                "{text:?}"
            );
            let message = e.to_string();
            assert!(message.contains("`certificate.item.serial`"), "{message}");
            assert!(
                message.contains(&format!("U+{code_point:04X}")),
                "{message}"
            );
        }
        assert_eq!(
            Text::identification("id", "  CC-2026-0042 ")
                .unwrap()
                .as_str(),
            "CC-2026-0042"
        );
        assert_eq!(
            Text::identification("id", " \t ").unwrap_err(),
            DccError::EmptyText {
                field: "id".to_owned()
            }
        );
    }

    #[test]
    fn free_text_shows_every_hidden_character() {
        assert_eq!(
            Text::free("f", "Grüße, 東京").unwrap().as_str(),
            "Grüße, 東京"
        );
        assert_eq!(
            Text::free("f", "a\u{1b}[31mb\u{0}").unwrap().as_str(),
            "a\\u{1b}[31mb\\u{0}"
        );
        assert_eq!(
            Text::free("f", "SN \u{202e}evil\u{202c} 1 \u{ffff}")
                .unwrap()
                .as_str(),
            "SN <U+202E>evil<U+202C> 1 <U+FFFF>"
        );
        // markup is data here: the writer escapes it
        assert_eq!(
            Text::free("f", "</dcc:name><script>").unwrap().as_str(),
            "</dcc:name><script>"
        );
    }
}
