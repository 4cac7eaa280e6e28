//! The layout of a delimited text file, guessed from its first lines: the delimiter, the
//! decimal mark, the lines above the header, the header's column names and units. Works on
//! bytes; the caller reads the file.

use std::fmt;

/// How many lines are looked at to guess the layout.
pub(crate) const SNIFF_LINES: usize = 400;

/// The field delimiter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Delim {
    /// One character.
    Char(char),
    /// Runs of blanks.
    Whitespace,
}

impl Delim {
    /// The delimiter as the study file writes it (`';'`, `'\t'`, `whitespace`).
    pub(crate) fn ron(self) -> String {
        match self {
            Self::Char('\t') => "'\\t'".to_owned(),
            Self::Char(c) => format!("'{c}'"),
            Self::Whitespace => "whitespace".to_owned(),
        }
    }

    fn split(self, line: &str) -> Vec<&str> {
        match self {
            Self::Char(c) => line.split(c).map(clean).collect(),
            Self::Whitespace => line.split_whitespace().map(clean).collect(),
        }
    }
}

impl fmt::Display for Delim {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Char('\t') => f.write_str("tab"),
            Self::Char(';') => f.write_str("semicolon"),
            Self::Char(',') => f.write_str("comma"),
            Self::Char(' ') => f.write_str("space"),
            Self::Char(c) => write!(f, "`{c}`"),
            Self::Whitespace => f.write_str("blanks"),
        }
    }
}

/// A field without the blanks and quotes around it.
fn clean(field: &str) -> &str {
    field.trim().trim_matches('"').trim()
}

/// The layout of a text file's table.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Layout {
    /// The delimiter.
    pub(crate) delimiter: Delim,
    /// Numbers written with a decimal comma.
    pub(crate) decimal_comma: bool,
    /// Lines before the header (its 0-based line index): the study's `skip_lines`.
    pub(crate) skip_lines: usize,
    /// The metadata lines above the header (neither blank nor `#` comments).
    pub(crate) metadata: Vec<String>,
    /// Line ends are CR LF.
    pub(crate) crlf: bool,
    /// The header's names, as written.
    pub(crate) header: Vec<String>,
    /// The first data rows, each as many numbers as the header has names (`None`: a field
    /// that is not a number, e.g. a label).
    pub(crate) rows: Vec<Vec<Option<f64>>>,
}

/// Why no layout was found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum LayoutProblem {
    /// Nothing but blank and comment lines.
    Empty,
    /// Not text (a NUL byte or invalid UTF-8 in the first lines).
    Binary,
    /// No run of lines with the same number (two or more) of numeric fields.
    NoNumericRows,
    /// Numeric rows, but no header line above them naming the columns.
    NoHeader {
        /// The first data line, 1-based.
        first_data_line: usize,
    },
}

impl fmt::Display for LayoutProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty => f.write_str("holds no data lines (only blank or `#` lines)"),
            Self::Binary => f.write_str("is not text (binary bytes in its first lines)"),
            Self::NoNumericRows => f.write_str(
                "has no rows of two or more numbers separated by a comma, semicolon, tab, \
                 `|` or blanks",
            ),
            Self::NoHeader { first_data_line } => write!(
                f,
                "has numbers from line {first_data_line} but no header line above them \
                 naming the columns (add one, e.g. `time_s,gap_um,angle_deg`)"
            ),
        }
    }
}

/// A number as a lab writes it, with a decimal point or comma: the recording readers' own
/// syntax ([`recording::parse_number`]), so that what init takes for a number is what the
/// study then reads.
pub(crate) fn number(field: &str, decimal_comma: bool) -> Option<f64> {
    let field = clean(field);
    if field.is_empty() {
        return None;
    }
    let parsed = recording::parse_number(field, decimal_comma);
    // `inf`, `nan` parse as numbers but say nothing about a layout.
    parsed.filter(|v| v.is_finite() || field.eq_ignore_ascii_case("nan"))
}

/// The layout of `bytes`' first [`SNIFF_LINES`] lines.
pub(crate) fn sniff(bytes: &[u8]) -> Result<Layout, LayoutProblem> {
    let head = &bytes[..bytes.len().min(1 << 20)];
    let bom = head.strip_prefix(b"\xef\xbb\xbf").unwrap_or(head);
    if bom.iter().take(8192).any(|&b| b == 0) {
        return Err(LayoutProblem::Binary);
    }
    // The last line may be cut at the 1 MiB mark: keep whole lines only.
    let text = match std::str::from_utf8(bom) {
        Ok(t) => t,
        Err(e) if e.valid_up_to() > bom.len().saturating_sub(4) || bom.len() == head.len() => {
            std::str::from_utf8(&bom[..e.valid_up_to()]).map_err(|_| LayoutProblem::Binary)?
        }
        Err(_) => return Err(LayoutProblem::Binary),
    };
    let crlf = text.contains("\r\n");
    let lines: Vec<&str> = text
        .split('\n')
        .take(SNIFF_LINES)
        .map(|l| l.trim_end_matches('\r'))
        .collect();
    let content = |l: &str| !l.trim().is_empty() && !l.trim_start().starts_with('#');
    if !lines.iter().any(|l| content(l)) {
        return Err(LayoutProblem::Empty);
    }
    let candidates = [
        (Delim::Char('\t'), false),
        (Delim::Char(';'), false),
        (Delim::Char(';'), true),
        (Delim::Char(','), false),
        (Delim::Char('|'), false),
        (Delim::Char('|'), true),
        (Delim::Char('\t'), true),
        (Delim::Whitespace, false),
        (Delim::Whitespace, true),
    ];
    // For each candidate, the last block of content lines with the same number of fields,
    // all numbers (a label column allowed), and the header above it. A candidate whose
    // header splits into as many names as the data lines have fields beats one without
    // (a `;`-separated table with decimal commas also splits at its commas, into fields of
    // which one is text: `20,0;0,017` is `20`, `0;0`, `017` at commas); then the one
    // with fewer text fields per line, then more lines, then more fields.
    let mut best: Option<(Candidate, (bool, usize, usize, usize))> = None;
    for (delim, comma) in candidates {
        let Some(block) = data_block(&lines, delim, comma) else {
            continue;
        };
        let header = header_above(&lines, &block, delim, comma);
        let score = (
            header.is_some(),
            usize::MAX - block.text_fields,
            block.count,
            block.fields,
        );
        if best.as_ref().is_none_or(|(_, s)| score > *s) {
            best = Some((
                Candidate {
                    delim,
                    comma,
                    block,
                    header,
                },
                score,
            ));
        }
    }
    let Candidate {
        delim: delimiter,
        comma: decimal_comma,
        block,
        header,
    } = best.ok_or(LayoutProblem::NoNumericRows)?.0;
    let (fields, first) = (block.fields, block.first);
    let header_index = header.ok_or(LayoutProblem::NoHeader {
        first_data_line: first + 1,
    })?;
    let header: Vec<String> = delimiter
        .split(lines[header_index])
        .into_iter()
        .map(str::to_owned)
        .collect();
    let metadata = lines[..header_index]
        .iter()
        .filter(|l| content(l))
        .map(|l| (*l).to_owned())
        .collect();
    let rows = lines[first..]
        .iter()
        .filter(|l| content(l))
        .map(|l| {
            delimiter
                .split(l)
                .iter()
                .map(|f| number(f, decimal_comma))
                .collect::<Vec<_>>()
        })
        .filter(|r| r.len() == fields)
        .collect();
    Ok(Layout {
        delimiter,
        decimal_comma,
        skip_lines: header_index,
        metadata,
        crlf,
        header,
        rows,
    })
}

/// A delimiter and decimal mark tried, with its block of data lines and header.
struct Candidate {
    delim: Delim,
    comma: bool,
    block: Block,
    /// The header line's index, when the line above the data splits into as many names.
    header: Option<usize>,
}

/// A block of data lines under one delimiter and decimal mark.
struct Block {
    /// How many lines.
    count: usize,
    /// Fields per line.
    fields: usize,
    /// Index of its first line.
    first: usize,
    /// Fields per line that are not numbers (0, or 1: a label).
    text_fields: usize,
}

/// The header of a block: the last content line above the data with as many fields, not
/// all of them numbers, none empty.
fn header_above(lines: &[&str], block: &Block, delim: Delim, comma: bool) -> Option<usize> {
    let content = |l: &str| !l.trim().is_empty() && !l.trim_start().starts_with('#');
    (0..block.first)
        .rev()
        .find(|&i| content(lines[i]))
        .filter(|&i| {
            let names = delim.split(lines[i]);
            names.len() == block.fields
                && names.iter().any(|n| number(n, comma).is_none())
                && names.iter().all(|n| !n.is_empty())
        })
}

/// The block of data lines at the end of the sniffed lines under one delimiter and decimal
/// mark. A data line has two or more fields, at least two of them numbers, and at most one
/// that is not (a label).
fn data_block(lines: &[&str], delim: Delim, comma: bool) -> Option<Block> {
    if comma && delim == Delim::Char(',') {
        return None;
    }
    let shape = |line: &str| -> Option<(usize, usize)> {
        let fields = delim.split(line);
        let numbers = fields.iter().filter(|f| number(f, comma).is_some()).count();
        (fields.len() >= 2 && numbers >= 2 && fields.len() - numbers <= 1)
            .then_some((fields.len(), fields.len() - numbers))
    };
    let content: Vec<usize> = (0..lines.len())
        .filter(|&i| !lines[i].trim().is_empty() && !lines[i].trim_start().starts_with('#'))
        .collect();
    // The last line may be cut short by the sniffing window: ignore it when it does not fit.
    let mut end = content.len();
    while end > 0 && shape(lines[content[end - 1]]).is_none() {
        end -= 1;
        if content.len() - end > 1 {
            return None;
        }
    }
    let (fields, _) = shape(lines[content[end.checked_sub(1)?]])?;
    let mut start = end - 1;
    let mut text_fields = 0;
    while start > 0
        && let Some((f, text)) = shape(lines[content[start - 1]])
        && f == fields
    {
        text_fields = text_fields.max(text);
        start -= 1;
    }
    text_fields = text_fields.max(shape(lines[content[end - 1]]).map_or(0, |(_, t)| t));
    // With a decimal comma, the numbers must use it (else the point reading is the same).
    if comma
        && !content[start..end]
            .iter()
            .any(|&i| delim.split(lines[i]).iter().any(|f| f.contains(',')))
    {
        return None;
    }
    Some(Block {
        count: end - start,
        fields,
        first: content[start],
        text_fields,
    })
}

/// A header name split into its quantity and unit: `Spalt [mm]`, `Time (ms)`, `gap_um`,
/// `rate_deg_s`, `Winkel/°`; `None` as the unit when the name carries none.
pub(crate) fn name_and_unit(name: &str) -> (String, Option<String>) {
    let trimmed = name.trim();
    for (open, close) in [('[', ']'), ('(', ')'), ('{', '}')] {
        if let Some(body) = trimmed.strip_suffix(close)
            && let Some(at) = body.rfind(open)
        {
            let unit = body[at + open.len_utf8()..].trim();
            let quantity = body[..at].trim().trim_end_matches(['_', ' ', '/']);
            if !unit.is_empty() && !quantity.is_empty() {
                return (quantity.to_owned(), Some(unit.to_owned()));
            }
        }
    }
    if let Some((quantity, unit)) = trimmed.rsplit_once(" in ")
        && !unit.contains(' ')
    {
        return (quantity.trim().to_owned(), Some(unit.trim().to_owned()));
    }
    if let Some((quantity, unit)) = trimmed.rsplit_once('/')
        && !quantity.is_empty()
        && !unit.is_empty()
        && !unit.contains(' ')
    {
        return (quantity.trim().to_owned(), Some(unit.trim().to_owned()));
    }
    // `name_unit`, the unit among those known (longest first: `rate_deg_s` is deg/s).
    let lower = trimmed.to_lowercase();
    for suffix in [
        "_deg_s", "_rad_s", "_deg", "_rad", "_counts", "_cnt", "_ms", "_us", "_ns", "_um", "_mm",
        "_nm", "_mv", "_v", "_s", "_m",
    ] {
        if lower.ends_with(suffix) && lower.len() > suffix.len() {
            let cut = trimmed.len() - suffix.len();
            let unit = trimmed[cut + 1..].replace('_', "/");
            return (trimmed[..cut].to_owned(), Some(unit));
        }
    }
    (trimmed.to_owned(), None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn european_export_with_metadata() {
        let text = "Messgerät: XY-3000\r\nDatum: 2025-03-01\r\nKanal: 2\r\nAbtastrate: 200 Hz\r\n\r\n\
                    Zeit [s];Spalt [mm];Winkel\r\n0,000000;0,05001;0\r\n0,005000;0,05002;1024\r\n\
                    0,010000;0,05003;2048\r\n";
        let l = sniff(text.as_bytes()).unwrap();
        assert_eq!(l.delimiter, Delim::Char(';'));
        assert!(l.decimal_comma);
        assert_eq!(l.skip_lines, 5);
        assert!(l.crlf);
        assert_eq!(l.metadata.len(), 4);
        assert_eq!(l.header, ["Zeit [s]", "Spalt [mm]", "Winkel"]);
        assert_eq!(l.rows.len(), 3);
        assert_eq!(l.rows[1][0], Some(0.005));
    }

    #[test]
    fn documented_csv_and_tab_separated() {
        let l = sniff(b"time_s,gap_um,angle_deg\n0.0,1.5,0.0\n0.01,1.6,1.0\n").unwrap();
        assert_eq!(
            (l.delimiter, l.decimal_comma, l.skip_lines),
            (Delim::Char(','), false, 0)
        );
        let l = sniff(b"Time [s]\tGap [um]\tAngle [deg]\n0.0\t1.5\t0.0\n0.01\t1.6\t1.0\n").unwrap();
        assert_eq!(l.delimiter, Delim::Char('\t'));
        assert_eq!(l.header[1], "Gap [um]");
    }

    /// Two-column tables in every delimiter and decimal mark: a `;` table with decimal
    /// commas also splits at its commas into three fields (one of them text) and once lost
    /// to that reading ("no header line above them").
    #[test]
    fn two_column_tables_in_any_delimiter_and_decimal_mark() {
        let rows = [(20.0, 0.017_421), (30.0, 0.039_182), (40.0, 0.069_646)];
        for (delimiter, comma, expected) in [
            (";", true, Delim::Char(';')),
            (";", false, Delim::Char(';')),
            ("\t", true, Delim::Char('\t')),
            ("\t", false, Delim::Char('\t')),
            (",", false, Delim::Char(',')),
            ("   ", true, Delim::Whitespace),
            (" ", false, Delim::Whitespace),
            ("|", true, Delim::Char('|')),
        ] {
            let number = |v: f64| {
                let t = format!("{v}");
                if comma { t.replace('.', ",") } else { t }
            };
            let mut text = format!("Drehrate_deg_s{delimiter}Ausgang_rad_s\r\n");
            for (r, o) in rows {
                text += &format!("{}{delimiter}{}\r\n", number(r), number(o));
            }
            let l = sniff(text.as_bytes())
                .unwrap_or_else(|e| panic!("{delimiter:?} comma {comma}: {e}"));
            assert_eq!(
                (l.delimiter, l.decimal_comma, l.skip_lines),
                (expected, comma, 0),
                "{delimiter:?} comma {comma}"
            );
            assert_eq!(l.header, ["Drehrate_deg_s", "Ausgang_rad_s"]);
            assert_eq!(l.rows[2], [Some(40.0), Some(0.069_646)]);
        }
        // The German export's two columns, with units in brackets and metadata above.
        let text = "Messprogramm: Zentrifuge ZF-2;\nDatum: 24.11.2026;\n;\n\
                    Drehrate [°/s];Ausgang [rad/s]\n20,0;0,0174\n30,0;0,0391\n40,0;0,0696\n";
        let l = sniff(text.as_bytes()).unwrap();
        assert_eq!(
            (l.delimiter, l.decimal_comma, l.skip_lines),
            (Delim::Char(';'), true, 3)
        );
        assert_eq!(l.header, ["Drehrate [°/s]", "Ausgang [rad/s]"]);
    }

    #[test]
    fn problems_are_named() {
        assert_eq!(sniff(b"# nothing\n\n"), Err(LayoutProblem::Empty));
        assert_eq!(sniff(b"\x00\x01\x02"), Err(LayoutProblem::Binary));
        assert_eq!(
            sniff(b"0.0,1.0\n0.1,1.1\n"),
            Err(LayoutProblem::NoHeader { first_data_line: 1 })
        );
        assert_eq!(
            sniff(b"hello world\nno numbers\n"),
            Err(LayoutProblem::NoNumericRows)
        );
    }

    #[test]
    fn units_from_headers() {
        let u = |n: &str| name_and_unit(n);
        assert_eq!(u("Spalt [mm]"), ("Spalt".into(), Some("mm".into())));
        assert_eq!(u("Time (ms)"), ("Time".into(), Some("ms".into())));
        assert_eq!(u("gap_um"), ("gap".into(), Some("um".into())));
        assert_eq!(u("rate_deg_s"), ("rate".into(), Some("deg/s".into())));
        assert_eq!(u("Winkel"), ("Winkel".into(), None));
        assert_eq!(u("time_ms"), ("time".into(), Some("ms".into())));
        assert_eq!(u("index"), ("index".into(), None));
    }
}
