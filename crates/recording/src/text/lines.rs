//! Lines of a text: line ends, comments, blank lines and fields.

/// The UTF-8 byte-order mark, skipped at the start of a file.
pub(crate) const BOM: &[u8] = b"\xEF\xBB\xBF";

/// Whether a text's line ends are lone CRs: its first line end is a CR not followed by LF.
/// `None` while the text read so far does not tell.
pub(crate) fn lone_cr_line_ends(text: &[u8], complete: bool) -> Option<bool> {
    match text.iter().position(|&b| b == b'\n' || b == b'\r') {
        Some(i) if text[i] == b'\n' => Some(false),
        Some(i) if i + 1 < text.len() => Some(text[i + 1] != b'\n'),
        // A CR as the last byte read: a lone CR only if nothing follows.
        Some(_) => complete.then_some(true),
        None => complete.then_some(false),
    }
}

/// The text without a leading byte-order mark and with lone-CR line ends turned into LF
/// (copied only then).
pub(crate) fn normalized(text: &[u8]) -> std::borrow::Cow<'_, [u8]> {
    let text = text.strip_prefix(BOM).unwrap_or(text);
    if lone_cr_line_ends(text, true) == Some(true) {
        text.iter()
            .map(|&b| if b == b'\r' { b'\n' } else { b })
            .collect::<Vec<u8>>()
            .into()
    } else {
        text.into()
    }
}

/// Lines of a text with their 1-based numbers; `next_content` skips blank lines and
/// `#` comments.
pub(crate) struct Lines<'a> {
    pub(crate) text: &'a [u8],
    pub(crate) pos: usize,
    pub(crate) line: usize,
}

impl<'a> Lines<'a> {
    pub(crate) fn next_line(&mut self) -> Option<(usize, &'a [u8])> {
        if self.pos >= self.text.len() {
            return None;
        }
        let rest = &self.text[self.pos..];
        let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        // Past the line end, or at the text's end when the last line has none.
        self.pos = (self.pos + end + 1).min(self.text.len());
        self.line += 1;
        let mut line = &rest[..end];
        if let [head @ .., b'\r'] = line {
            line = head;
        }
        Some((self.line, line))
    }

    pub(crate) fn next_content(&mut self) -> Option<(usize, &'a [u8])> {
        while let Some((n, line)) = self.next_line() {
            let t = line.trim_ascii_start();
            if t.is_empty() || t[0] == b'#' {
                continue;
            }
            return Some((n, line));
        }
        None
    }
}

/// Fields of a line. With `blank`, any run of blanks (spaces and tabs) separates fields and
/// `delimiter` is not used.
pub(crate) fn split_fields(line: &[u8], delimiter: u8, blank: bool) -> impl Iterator<Item = &[u8]> {
    let mut rest = Some(if blank { line.trim_ascii() } else { line });
    std::iter::from_fn(move || {
        let r = rest?;
        if blank {
            match r.iter().position(|&b| b == b' ' || b == b'\t') {
                Some(i) => {
                    rest = Some(r[i..].trim_ascii_start());
                    Some(&r[..i])
                }
                None => {
                    rest = None;
                    Some(r)
                }
            }
        } else {
            match r.iter().position(|&b| b == delimiter) {
                Some(i) => {
                    rest = Some(&r[i + 1..]);
                    Some(&r[..i])
                }
                None => {
                    rest = None;
                    Some(r)
                }
            }
        }
    })
}

pub(crate) fn trim_quotes(field: &[u8]) -> &[u8] {
    let f = field.trim_ascii();
    match f {
        [b'"', inner @ .., b'"'] => inner,
        _ => f,
    }
}

/// A field's text: UTF-8 when it is valid UTF-8, else read as Latin-1 (ISO 8859-1), as a
/// Windows export in code page 1252 writes `°`, `µ` and umlauts in headers, so that a
/// header such as `Drehrate [°/s]` matches its name in the configuration either way.
pub(crate) fn field_text(field: &[u8]) -> String {
    match std::str::from_utf8(field) {
        Ok(s) => s.to_owned(),
        Err(_) => field.iter().map(|&b| char::from(b)).collect(),
    }
}
