//! Parsing one row: the fast in-place path and the field-by-field path.

use std::path::Path;

use super::lines::{field_text, split_fields, trim_quotes};
use super::number::{fast_prefix, parse_f64};
use crate::error::{Hint, RecordingError};

/// Sentinel of [`fast_row`]'s field map: a field that is not stored.
pub(crate) const SKIP: u8 = u8::MAX;

/// How a row's fields are separated and its numbers written.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Syntax {
    /// The delimiter byte (unused when `blank`).
    pub(crate) delimiter: u8,
    /// Runs of blanks separate fields.
    pub(crate) blank: bool,
    /// The decimal mark is `,`.
    pub(crate) comma: bool,
    /// NaN and infinite values are stored rather than refused.
    pub(crate) allow_non_finite: bool,
}

/// What went wrong in a row, before the file and line are attached; `slot` is the place of
/// the column among those read.
pub(crate) enum RowError {
    MissingField {
        slot: usize,
    },
    FieldCount {
        expected: usize,
        found: usize,
    },
    Parse {
        slot: usize,
        text: String,
        hint: Option<Hint>,
    },
    NonFinite {
        slot: usize,
        value: f64,
    },
}

impl RowError {
    pub(crate) fn located(
        self,
        path: &Path,
        line: usize,
        column_name: &dyn Fn(usize) -> String,
        hint_keys: &[&str],
    ) -> RecordingError {
        let path = path.to_owned();
        match self {
            Self::MissingField { slot } => RecordingError::MissingField {
                path,
                line,
                column: column_name(slot),
            },
            Self::FieldCount { expected, found } => RecordingError::FieldCount {
                path,
                line,
                expected,
                found,
            },
            Self::Parse { slot, text, hint } => RecordingError::Parse {
                path,
                line,
                column: column_name(slot),
                text,
                hint: hint.filter(|h| h.is_for(hint_keys)),
            },
            Self::NonFinite { slot, value } => RecordingError::NonFinite {
                path,
                line,
                column: column_name(slot),
                value,
                hint: Some(Hint::OnNonFinite).filter(|h| h.is_for(hint_keys)),
            },
        }
    }
}

/// Parses one row field by field: blanks around fields, quoted fields, any number the
/// standard library reads; finite values only. `wanted` holds `(field, slot)` sorted by
/// field; with `width`, the row must have exactly that many fields.
pub(crate) fn parse_row_slowly(
    row: &[u8],
    syntax: Syntax,
    wanted: &[(usize, usize)],
    width: Option<usize>,
    values: &mut [f64],
) -> Result<(), RowError> {
    let split = || split_fields(row, syntax.delimiter, syntax.blank);
    if let Some(expected) = width {
        let found = split().count();
        if found != expected {
            return Err(RowError::FieldCount { expected, found });
        }
    }
    let mut fields = split();
    let mut next = 0;
    for &(index, slot) in wanted {
        let Some(field) = fields.nth(index - next) else {
            return Err(RowError::MissingField { slot });
        };
        next = index + 1;
        let field = trim_quotes(field);
        let value = parse_f64(field, syntax.comma).ok_or_else(|| RowError::Parse {
            slot,
            text: field_text(field),
            hint: number_hint(field, syntax),
        })?;
        if !value.is_finite() && !syntax.allow_non_finite {
            return Err(RowError::NonFinite { slot, value });
        }
        values[slot] = value;
    }
    Ok(())
}

/// What the field that is not a number probably means.
fn number_hint(field: &[u8], syntax: Syntax) -> Option<Hint> {
    if !syntax.comma && field.contains(&b',') && parse_f64(field, true).is_some() {
        return Some(Hint::DecimalComma);
    }
    if syntax.comma && field.contains(&b'.') && parse_f64(field, false).is_some() {
        return Some(Hint::DecimalPoint);
    }
    if !syntax.blank && field.iter().any(|&b| b == b';' || b == b'\t' || b == b',') {
        return Some(Hint::Delimiter);
    }
    None
}

/// Parses a plain row `number,number,…` starting at `pos` straight from the text: stores
/// the wanted fields (`dest_of[field]` is the slot in `values`, or [`SKIP`]) and returns
/// where the next line starts. Fields after the last one mapped are allowed when
/// `rest_allowed`. `None` on anything else (comment, blank line, blanks around fields,
/// quotes, short row, a value the fast path does not take): the caller then parses the line
/// the slow way, which also reports errors.
#[inline(always)]
pub(crate) fn fast_row(
    text: &[u8],
    mut pos: usize,
    syntax: Syntax,
    dest_of: &[u8],
    rest_allowed: bool,
    values: &mut [f64],
) -> Option<usize> {
    let last = dest_of.len() - 1;
    let Syntax {
        delimiter, blank, ..
    } = syntax;
    let mark = if syntax.comma { b',' } else { b'.' };
    for (f, &dest) in dest_of.iter().enumerate() {
        if dest == SKIP {
            // The skipped field ends at the delimiter; with a blank delimiter at either
            // blank (the slow path's rule), and an empty field there is a run of blanks.
            let off = text.get(pos..)?.iter().position(|&b| {
                b == delimiter || b == b'\n' || (blank && (b == b' ' || b == b'\t'))
            })?;
            if text[pos + off] != delimiter || (blank && off == 0) {
                return None;
            }
            // Other ASCII whitespace (a lone CR, a form feed) next to blanks is trimmed by the
            // slow path's field splitting: leave such a line to it (found by fuzzing).
            if blank && text[pos..pos + off].iter().any(u8::is_ascii_whitespace) {
                return None;
            }
            // A comment line is not a row.
            if f == 0 && text[pos..pos + off].trim_ascii_start().first() == Some(&b'#') {
                return None;
            }
            pos += off + 1;
            continue;
        }
        let (v, used) = fast_prefix(text.get(pos..)?, mark)?;
        *values.get_mut(usize::from(dest))? = v;
        pos += used;
        if f < last {
            if text.get(pos) != Some(&delimiter) {
                return None;
            }
            pos += 1;
        } else {
            return match text.get(pos) {
                None => Some(pos),
                Some(b'\n') => Some(pos + 1),
                Some(b'\r') if text.get(pos + 1) == Some(&b'\n') => Some(pos + 2),
                Some(&b) if b == delimiter && rest_allowed => {
                    let off = text[pos..].iter().position(|&b| b == b'\n');
                    Some(off.map_or(text.len(), |o| pos + o + 1))
                }
                _ => None,
            };
        }
    }
    None
}
