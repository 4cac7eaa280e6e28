//! The probe-recording writer.

use std::io::Write;

use super::format::{ANGLE_COLUMN, GAP_COLUMN, TIME_COLUMN};
use crate::error::{RecordingError, Result};

/// The columns of a probe recording to write: time (s), gap (µm) and, optionally, the
/// encoder angle (deg), all of one length and every value finite, so that
/// [`load_recording`](crate::load_recording) reads back what [`write_probe_csv`] writes
/// (to its decimals).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeColumns<'a> {
    time_s: &'a [f64],
    gap_um: &'a [f64],
    angle_deg: Option<&'a [f64]>,
}

impl<'a> ProbeColumns<'a> {
    /// Checks the columns: [`RecordingError::ColumnLengths`] if their lengths differ,
    /// [`RecordingError::NonFiniteValue`] for the first NaN or infinite value.
    pub fn new(time_s: &'a [f64], gap_um: &'a [f64], angle_deg: Option<&'a [f64]>) -> Result<Self> {
        if gap_um.len() != time_s.len() || angle_deg.is_some_and(|a| a.len() != time_s.len()) {
            return Err(RecordingError::ColumnLengths {
                time: time_s.len(),
                gap: gap_um.len(),
                angle: angle_deg.map(<[f64]>::len),
            });
        }
        let named = [
            (TIME_COLUMN, Some(time_s)),
            (GAP_COLUMN, Some(gap_um)),
            (ANGLE_COLUMN, angle_deg),
        ];
        for (column, values) in named {
            let values = values.unwrap_or_default();
            if let Some(index) = values.iter().position(|v| !v.is_finite()) {
                return Err(RecordingError::NonFiniteValue {
                    column,
                    index,
                    value: values[index],
                });
            }
        }
        Ok(Self {
            time_s,
            gap_um,
            angle_deg,
        })
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }
}

/// How [`write_probe_csv`] writes a recording.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WriteOptions<'a> {
    /// Decimals of every value (fixed-point).
    pub decimals: usize,
    /// Text written before the header as `#` comment lines, one per line of the text.
    pub header_comment: Option<&'a str>,
}

/// Writes a probe recording as CSV in the default [`RecordingFormat`](crate::RecordingFormat):
/// the comment lines, the header `time_s,gap_um[,angle_deg]`, then one row per sample with
/// every value in fixed point with `options.decimals` decimals. Lines end with LF.
///
/// ```
/// use recording::{ProbeColumns, WriteOptions, write_probe_csv};
/// let columns = ProbeColumns::new(&[0.0, 0.001], &[12.5, 12.625], None)?;
/// let mut out = Vec::new();
/// let options = WriteOptions { decimals: 3, header_comment: Some("probe 1") };
/// write_probe_csv(&mut out, &columns, &options).unwrap();
/// assert_eq!(out, b"# probe 1\ntime_s,gap_um\n0.000,12.500\n0.001,12.625\n");
/// # Ok::<(), recording::RecordingError>(())
/// ```
///
/// # Errors
/// Whatever `out` returns.
pub fn write_probe_csv<W: Write>(
    out: &mut W,
    columns: &ProbeColumns<'_>,
    options: &WriteOptions<'_>,
) -> std::io::Result<()> {
    if let Some(comment) = options.header_comment {
        // A CR inside the comment would end its line too.
        for line in comment.split(['\n', '\r']).filter(|l| !l.is_empty()) {
            writeln!(out, "# {line}")?;
        }
    }
    let p = options.decimals;
    let rows = columns.time_s.iter().zip(columns.gap_um);
    match columns.angle_deg {
        Some(angle) => {
            writeln!(out, "{TIME_COLUMN},{GAP_COLUMN},{ANGLE_COLUMN}")?;
            for ((t, g), a) in rows.zip(angle) {
                writeln!(out, "{t:.p$},{g:.p$},{a:.p$}")?;
            }
        }
        None => {
            writeln!(out, "{TIME_COLUMN},{GAP_COLUMN}")?;
            for (t, g) in rows {
                writeln!(out, "{t:.p$},{g:.p$}")?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::format::RecordingFormat;
    use crate::read::parse_recording;

    #[test]
    fn refuses_what_the_reader_would_refuse() {
        let t = [0.0, 0.001, 0.002];
        assert!(matches!(
            ProbeColumns::new(&t, &[1.0, 2.0], None),
            Err(RecordingError::ColumnLengths {
                time: 3,
                gap: 2,
                angle: None
            })
        ));
        assert!(matches!(
            ProbeColumns::new(&t, &[1.0, 2.0, 3.0], Some(&[0.0; 4])),
            Err(RecordingError::ColumnLengths { angle: Some(4), .. })
        ));
        let e = ProbeColumns::new(&t, &[1.0, f64::NAN, 3.0], None).unwrap_err();
        assert!(
            matches!(
                e,
                RecordingError::NonFiniteValue {
                    column: "gap_um",
                    index: 1,
                    ..
                }
            ),
            "{e}"
        );
        let e = ProbeColumns::new(&t, &[1.0; 3], Some(&[0.0, 1.0, f64::INFINITY])).unwrap_err();
        assert!(
            matches!(
                e,
                RecordingError::NonFiniteValue {
                    column: "angle_deg",
                    index: 2,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn written_file_reads_back_with_its_comment_lines_skipped() {
        let t = [0.0, 0.5, 1.0];
        let g = [1.25, -2.5, 3.0];
        let a = [359.5, 0.25, 1.0];
        let columns = ProbeColumns::new(&t, &g, Some(&a)).unwrap();
        let mut out = Vec::new();
        let options = WriteOptions {
            decimals: 9,
            header_comment: Some("two\nlines\r\nand a lone\rCR"),
        };
        write_probe_csv(&mut out, &columns, &options).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(
            text.starts_with("# two\n# lines\n# and a lone\n# CR\ntime_s,gap_um,angle_deg\n"),
            "{text}"
        );
        assert!(
            text.ends_with("1.000000000,3.000000000,1.000000000\n"),
            "{text}"
        );
        let rec = parse_recording(
            text.as_bytes(),
            "w.csv".as_ref(),
            &RecordingFormat::default(),
        )
        .unwrap();
        assert_eq!(rec.time_s, t);
        assert_eq!(rec.gap, g);
        assert_eq!(rec.line_of_sample(0), 6);
    }
}
