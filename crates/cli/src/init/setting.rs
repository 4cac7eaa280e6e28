//! One setting of a file's format as the study file writes it, with its evidence; the
//! placeholder a user must fill in. A leaf: the file analysis and the table's settings both
//! use it.

use std::fmt::Write as _;

use super::columns::Column;

/// The placeholder left where the user must write a value; `check` and `study` refuse a
/// configuration that still holds it.
pub(crate) const PLACEHOLDER: &str = "FILL_IN";

/// One setting of the format: its RON text in the study file and why.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Setting {
    /// `key: value` as the study file writes it.
    pub(crate) ron: String,
    /// The evidence, or what is missing when the value is a placeholder.
    pub(crate) evidence: String,
}

impl Setting {
    pub(crate) fn new(ron: impl Into<String>, evidence: impl Into<String>) -> Self {
        Self {
            ron: ron.into(),
            evidence: evidence.into(),
        }
    }

    /// Whether the user must fill it in.
    pub(crate) fn is_placeholder(&self) -> bool {
        self.ron.contains(PLACEHOLDER)
    }
}

/// A string as a RON literal that reads back to the same text: quotes and backslashes
/// escaped, control characters (line ends, tabs, ESC, NUL…) and invisible or
/// direction-changing characters as `\u{…}` escapes, every other character as it is (`µ`,
/// `°`, `ü`). The one writer of strings into a study file: file names, column names, names.
pub(crate) fn ron_string(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if needs_escape(c) => {
                let _ = write!(out, "\\u{{{:x}}}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Characters that must not appear raw in a study file or a comment: control characters
/// (C0, DEL, C1), bidirectional controls and other invisible format characters.
fn needs_escape(c: char) -> bool {
    c.is_control()
        || matches!(
            c,
            '\u{200b}'..='\u{200f}' | '\u{2028}'..='\u{202e}' | '\u{2060}'..='\u{2069}' | '\u{feff}'
        )
}

/// Text for a `//` comment of the study file: one line, whatever the text holds (a file
/// name with a line end cannot end the comment and write configuration).
pub(crate) fn comment_text(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if needs_escape(c) {
            let _ = write!(out, "\\u{{{:x}}}", u32::from(c));
        } else {
            out.push(c);
        }
    }
    out
}

/// A column named in the study file.
pub(crate) fn quoted(name: &str) -> String {
    ron_string(name)
}

/// A column's unit in words for the evidence.
pub(crate) fn unit_words(c: &Column) -> String {
    c.unit.as_deref().map_or_else(
        || " (no unit in the header)".to_owned(),
        |u| format!(" ({u})"),
    )
}

impl Setting {
    /// For a placeholder, the field it fills (relative to the format block: `time.unit`)
    /// and the one-line question a technician answers to fill it.
    pub(crate) fn question(&self) -> Option<(&'static str, &'static str)> {
        if !self.is_placeholder() {
            return None;
        }
        let r = self.ron.as_str();
        Some(if r.starts_with("time:") {
            (
                "time.unit",
                "In which unit is the time column: s, ms, us or ns?",
            )
        } else if r.starts_with("gap:") && r.contains("volts(") {
            (
                "gap.unit",
                "What are the probe's sensitivity and its standard uncertainty, from its \
                 calibration certificate (in the unit written beside them)?",
            )
        } else if r.starts_with("gap:") {
            (
                "gap.unit",
                "In which unit is the gap column: nm, um, mm or m?",
            )
        } else if r.contains("start_angle_deg") {
            (
                "angle.start_angle_deg",
                "Where was the spindle at the first sample, in degrees from the arm towards the \
                 PIGA (O1X1)?",
            )
        } else if r.contains("per_rev") {
            (
                "unit.per_rev",
                "How many counts does the encoder (or pick-off) give per revolution?",
            )
        } else {
            (
                "unit",
                "In which unit is this angle column: deg, rad or counts(per_rev: N)?",
            )
        })
    }
}

/// The comment that carries a placeholder's question: `// ASK field: question` (`check` and
/// `study` repeat it when the placeholder is left).
pub(crate) fn ask(field: &str, question: &str) -> String {
    format!("{ASK} {field}: {}", comment_text(question))
}

/// The marker of a placeholder's question in a comment.
pub(crate) const ASK: &str = "ASK";

#[cfg(test)]
mod tests {
    use super::*;

    /// Every string written reads back, by the study's RON reader, to the same text.
    #[test]
    fn ron_strings_read_back_to_the_same_text() {
        for text in [
            "probe\\080deg_s.csv",
            "C:\\lab\\run \"3\"\\probe.csv",
            "Spalt [µm] ü °",
            "line\nbreak\r\ttab\u{1b}[31m esc \u{0} nul",
            "bidi \u{202e}evil\u{202c} and \u{feff} bom",
            "",
        ] {
            let written = ron_string(text);
            assert!(
                !written.contains('\n') && !written.contains('\u{202e}'),
                "{written}"
            );
            let read: String = edge_io::ron_options().from_str(&written).unwrap();
            assert_eq!(read, text, "{written}");
        }
        assert_eq!(ron_string("a\\b"), r#""a\\b""#);
        assert_eq!(comment_text("a\nb"), "a\\u{a}b");
    }
}
