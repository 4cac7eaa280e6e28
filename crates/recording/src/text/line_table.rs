//! Where each data row of a table is in its file: the row → line table.

/// The 1-based line of each data row, kept as breakpoints `(row, line)` only where a row is
/// not on the line after the previous row's: the first row, and each row after a comment, a
/// blank line or another line that is not a row. A row between breakpoints is on the line
/// of the breakpoint before it plus its distance from it, so memory grows with the lines
/// that are not rows, not with the rows.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(crate) struct LineTable {
    /// `(row, line)`, rows strictly increasing.
    breaks: Vec<(usize, usize)>,
}

impl LineTable {
    /// The line `row` would be on if it followed the last recorded row directly (0, which
    /// is no line, before any row).
    pub(crate) fn predicted(&self, row: usize) -> usize {
        self.breaks
            .last()
            .map_or(0, |&(r, l)| l + row.saturating_sub(r))
    }

    /// Records that `row` is on `line`; rows are recorded in increasing order, and a row on
    /// its predicted line is not stored.
    pub(crate) fn record(&mut self, row: usize, line: usize) {
        if line != self.predicted(row) {
            self.breaks.push((row, line));
        }
    }

    /// Appends the table of a later piece of the same text whose rows and lines were
    /// counted from 0: its rows follow `rows` rows, its lines follow line `lines`.
    pub(crate) fn append(&mut self, later: &Self, rows: usize, lines: usize) {
        for &(r, l) in &later.breaks {
            self.record(r + rows, l + lines);
        }
    }

    /// The 1-based line of data row `row` (0-based); 0 for an empty table. A row past the
    /// last one is counted on from it.
    pub(crate) fn line_of(&self, row: usize) -> usize {
        let i = self.breaks.partition_point(|&(r, _)| r <= row);
        match i.checked_sub(1) {
            Some(i) => {
                let (r, l) = self.breaks[i];
                l + (row - r)
            }
            None => 0,
        }
    }

    /// Number of breakpoints stored.
    #[cfg(test)]
    pub(crate) fn breakpoints(&self) -> usize {
        self.breaks.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn breakpoints_only_where_numbering_jumps() {
        let mut t = LineTable::default();
        assert_eq!(t.line_of(0), 0);
        // Header on line 2, rows on 3..=5, a comment on 6, rows on 7..=8, blank 9 and 10.
        for (row, line) in [(0, 3), (1, 4), (2, 5), (3, 7), (4, 8), (5, 11)] {
            t.record(row, line);
        }
        assert_eq!(t.breakpoints(), 3);
        let lines: Vec<usize> = (0..6).map(|r| t.line_of(r)).collect();
        assert_eq!(lines, [3, 4, 5, 7, 8, 11]);
        assert_eq!(t.line_of(7), 13);
    }

    #[test]
    fn appended_pieces_join_without_redundant_breakpoints() {
        let mut whole = LineTable::default();
        for (row, line) in [(0, 2), (1, 3), (2, 4), (3, 6), (4, 7)] {
            whole.record(row, line);
        }
        // The same rows parsed as two pieces: rows 0..2 on lines 2..=4 (piece of 4 lines),
        // then rows 2..5 counted from 0 on lines 1, 3, 4 of the second piece.
        let mut first = LineTable::default();
        for (row, line) in [(0, 2), (1, 3)] {
            first.record(row, line);
        }
        let mut second = LineTable::default();
        for (row, line) in [(0, 1), (1, 3), (2, 4)] {
            second.record(row, line);
        }
        first.append(&second, 2, 3);
        assert_eq!(first, whole);
        assert_eq!(whole.breakpoints(), 2);
    }
}
