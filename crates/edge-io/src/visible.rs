//! Text from a file or a configuration shown to a person: characters that hide, reorder or
//! act instead of showing (control characters C0 and C1 — NUL, ESC, BEL, DEL — and the
//! bidirectional overrides and isolates U+202A–U+202E, U+2066–U+2069) are found
//! ([`hidden_char`], for fields that refuse them) or written visibly ([`visible`], for text
//! that is shown whatever it holds: `\u{1b}` for ESC, `<U+202E>` for RIGHT-TO-LEFT OVERRIDE).

use std::borrow::Cow;

/// Whether `c` hides, reorders or acts instead of showing: a C0 or C1 control character,
/// DEL, or a bidirectional override or isolate.
#[must_use]
pub const fn is_hidden(c: char) -> bool {
    matches!(c, '\u{0}'..='\u{1f}' | '\u{7f}'..='\u{9f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// The first character of `text` that [`is_hidden`], with its position (in characters,
/// from 1) and a name a person can look up (`U+001B (ESC)`).
#[must_use]
pub fn hidden_char(text: &str) -> Option<HiddenChar> {
    text.chars()
        .enumerate()
        .find(|(_, c)| is_hidden(*c))
        .map(|(i, c)| HiddenChar {
            position: i + 1,
            character: c,
        })
}

/// A character that hides, reorders or acts, and where it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HiddenChar {
    /// Its position in the text, in characters from 1.
    pub position: usize,
    /// The character.
    pub character: char,
}

impl std::fmt::Display for HiddenChar {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let c = self.character;
        write!(f, "U+{:04X}", u32::from(c))?;
        let name = match c {
            '\u{0}' => "NUL",
            '\u{7}' => "BEL",
            '\u{8}' => "BACKSPACE",
            '\t' => "TAB",
            '\n' => "LINE FEED",
            '\r' => "CARRIAGE RETURN",
            '\u{1b}' => "ESC",
            '\u{7f}' => "DEL",
            '\u{9b}' => "CSI",
            '\u{9d}' => "OSC",
            '\u{202a}' => "LEFT-TO-RIGHT EMBEDDING",
            '\u{202b}' => "RIGHT-TO-LEFT EMBEDDING",
            '\u{202c}' => "POP DIRECTIONAL FORMATTING",
            '\u{202d}' => "LEFT-TO-RIGHT OVERRIDE",
            '\u{202e}' => "RIGHT-TO-LEFT OVERRIDE",
            '\u{2066}' => "LEFT-TO-RIGHT ISOLATE",
            '\u{2067}' => "RIGHT-TO-LEFT ISOLATE",
            '\u{2068}' => "FIRST STRONG ISOLATE",
            '\u{2069}' => "POP DIRECTIONAL ISOLATE",
            _ => "",
        };
        if !name.is_empty() {
            write!(f, " ({name})")?;
        }
        write!(f, " at character {}", self.position)
    }
}

/// `text` with every character that [`is_hidden`] written visibly: `\u{1b}` for a control
/// character, `<U+202E>` for a bidirectional override or isolate. Unchanged (borrowed) when
/// it holds none.
#[must_use]
pub fn visible(text: &str) -> Cow<'_, str> {
    if !text.chars().any(is_hidden) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if !is_hidden(c) {
            out.push(c);
        } else if c <= '\u{9f}' {
            out.push_str(&format!("\\u{{{:x}}}", u32::from(c)));
        } else {
            out.push_str(&format!("<U+{:04X}>", u32::from(c)));
        }
    }
    Cow::Owned(out)
}

/// [`visible`] for text of several lines, such as a terminal's: line feeds and tabs are kept,
/// every other hidden character (ESC, BEL, NUL, a carriage return that would overwrite a line,
/// a bidirectional override) is written visibly.
#[must_use]
pub fn visible_lines(text: &str) -> Cow<'_, str> {
    let hidden = |c: char| is_hidden(c) && c != '\n' && c != '\t';
    if !text.chars().any(hidden) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for line in text.split_inclusive('\n') {
        let (body, end) = line.strip_suffix('\n').map_or((line, ""), |b| (b, "\n"));
        for part in body.split_inclusive('\t') {
            let (cell, tab) = part.strip_suffix('\t').map_or((part, ""), |c| (c, "\t"));
            out.push_str(&visible(cell));
            out.push_str(tab);
        }
        out.push_str(end);
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hidden_characters_are_found_and_named() {
        assert_eq!(hidden_char("SN 1234"), None);
        assert_eq!(hidden_char("Grüße, 東京"), None);
        let h = hidden_char("SN \u{202e}evil").unwrap();
        assert_eq!(h.position, 4);
        assert_eq!(
            h.to_string(),
            "U+202E (RIGHT-TO-LEFT OVERRIDE) at character 4"
        );
        assert_eq!(
            hidden_char("a\u{1b}]0;x\u{7}").unwrap().to_string(),
            "U+001B (ESC) at character 2"
        );
        assert!(hidden_char("nul\0").is_some());
        assert!(hidden_char("c1 \u{9b}").is_some());
        assert!(hidden_char("isolate \u{2067}").is_some());
    }

    #[test]
    fn visible_lines_keep_line_feeds_and_tabs() {
        assert!(matches!(visible_lines("a\n\tb\n"), Cow::Borrowed(_)));
        assert_eq!(
            visible_lines("study \u{1b}]0;pwned\u{7}\n\tSN \u{202e}x\r\n"),
            "study \\u{1b}]0;pwned\\u{7}\n\tSN <U+202E>x\\u{d}\n"
        );
    }

    #[test]
    fn visible_text_shows_every_hidden_character() {
        assert!(matches!(visible("plain"), Cow::Borrowed("plain")));
        assert_eq!(visible("a\u{1b}[31mb"), "a\\u{1b}[31mb");
        assert_eq!(
            visible("SN \u{202e}evil\u{202c} 1"),
            "SN <U+202E>evil<U+202C> 1"
        );
        assert_eq!(visible("x\0y"), "x\\u{0}y");
        assert!(!visible("\u{7}\u{9d}\u{2066}").chars().any(is_hidden));
    }
}
