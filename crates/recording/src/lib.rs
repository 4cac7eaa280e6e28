//! Probe recordings: delimited text files of time, probe gap and, optionally, the spindle
//! encoder's angle, one sample per row (the raw data behind eq. 20).
//!
//! A file is read by one table parser ([`load_table`], [`parse_table`]): it is streamed
//! through one reused buffer of about a megabyte and parsed in a single pass without an
//! allocation per row; the columns grow with the rows read, never with the file's size.
//! Fields are parsed in place by a fast decimal parser (exact for up to 19 significant
//! digits and exponents within ±22, the standard library's parser otherwise). Lines end
//! with LF, CRLF, or (in a file whose first line end is one) a lone CR; a leading UTF-8
//! byte-order mark is skipped; fields may be quoted. Errors name the file and the 1-based
//! line; a loaded recording keeps a compact row → line table, so an error found later (one
//! of [`analyze_recording`]) names its line without reading the file again.
//!
//! ```
//! use recording::{parse_recording, RecordingFormat};
//! let text = "# probe at 10 deg/s\ntime_s,gap_um,angle_deg\n0.000,12.5,359.9\n0.001,12.6,0.1\n";
//! let rec = parse_recording(text.as_bytes(), "probe.csv".as_ref(), &RecordingFormat::default())?;
//! assert_eq!(rec.time_s, [0.0, 0.001]);
//! approx::assert_relative_eq!(rec.angle_rad.as_ref().unwrap()[1], 0.1f64.to_radians());
//! assert_eq!(rec.line_of_sample(1), 4);
//! # Ok::<(), recording::RecordingError>(())
//! ```

mod error;
mod format;
mod line_table;
mod lines;
mod number;
mod piga;
mod probe;
mod rows;
mod stream;
#[cfg(feature = "synthetic")]
mod synth;
mod table;
mod write;

pub use error::{RecordingError, Result};
pub use format::{AngleUnit, LengthUnit, RecordingFormat};
pub use piga::{
    PIGA_OUTPUT_COLUMN, PIGA_RATE_COLUMN, PigaTable, load_piga_table, parse_piga_table,
};
pub use probe::{Recording, analyze_recording, load_recording, parse_recording};
#[cfg(feature = "synthetic")]
pub use synth::SyntheticSpec;
pub use table::{MAX_COLUMNS, Table, TableColumn, TableFormat, load_table, parse_table};
pub use write::{ProbeColumns, WriteOptions, write_probe_csv};
