//! Lab data as labs store it: the readers of probe recordings and PIGA tables, the
//! probe-recording writer, and the conversion of a recording to the input of the harmonic
//! analysis ([`harmonics::ProbeSignal`], eq. 20).
//!
//! # Formats
//!
//! Text recordings and tables are delimited text read by one parser ([`load_table`], [`parse_table`]):
//! blank lines and lines starting with `#` are skipped, the first other line is the header
//! naming the columns, then one row per line. Lines end with LF, CRLF, or (in a file whose
//! first line end is one) a lone CR; a leading UTF-8 byte-order mark is skipped; fields may
//! be quoted and have blanks around them; with a blank delimiter, runs of blanks separate
//! fields. Columns are found by name; the others are skipped. Every value read must be a
//! finite number.
//!
//! - **Probe recording** ([`load_recording`], [`parse_recording`], [`RecordingFormat`]):
//!   time, probe gap and the spindle's angle source (an encoder in deg, rad or counts, an
//!   index pulse, or the declared rate), one sample per row; delimiter, decimal mark, lines
//!   to skip, column names and units configurable (default `time_s,gap_um[,angle_deg]`,
//!   comma-separated; `docs/YOUR-DATA.md`). Times must increase without a gap of
//!   more than a few nominal sample intervals. Rows may have more fields than are read.
//!   [`write_probe_csv`] writes this format.
//! - **PIGA table** ([`load_piga_table`], [`PigaTable`]): `rate_deg_s,output_rad_s`, the mean
//!   PIGA output at each centrifuge rate (the data of eq. 18); every row as many fields as
//!   the header. A table may also name a text column as each row's label
//!   ([`TableFormat::label`]: a repeat or an orientation).
//! - **Raw PIGA output recording** ([`load_piga_recording`], [`PigaRecordingFormat`]):
//!   time, the PIGA's output angle (deg, rad or pick-off counts; whole turns unwrapped) and
//!   the spindle's angle source, as a probe recording; [`reduce_piga_recording`] gives the
//!   mean output rate over whole spindle revolutions (once-per-revolution terms cancel) with
//!   its standard error across revolutions: one row of eq. 18.
//!
//! - **Binary recordings**: NI TDMS ([`load_tdms`], [`parse_tdms`]) and MATLAB `.mat` v5/v7
//!   ([`load_mat`], [`parse_mat`]) channels or variables named by [`BinaryChannels`], read
//!   into the same [`Recording`]; written from the formats' public descriptions, every
//!   length field checked against the bytes left before anything is allocated from it.
//!
//! # Reading
//!
//! A file is streamed through one reused buffer of about a megabyte and parsed in a single
//! pass without an allocation per row; the columns grow with the rows read, never with the
//! file's size, and a line longer than 16 MiB is refused ([`RecordingError::LineTooLong`]),
//! so a binary file or `/dev/zero` is an error, not unbounded growth. Fields are parsed in
//! place by a fast decimal parser (exact for up to 19 significant digits and exponents
//! within ±22, the standard library's parser otherwise); pieces of 256 kB or more are
//! parsed as two halves on two threads. Errors name the file and the 1-based line; a table
//! keeps a compact row → line table (memory grows with its comment and blank lines, not its
//! rows), so an error found after reading, such as one of [`analyze_recording`], names its
//! line without reading the file again.
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
//!
//! # Layout (a reading order that goes one way)
//!
//! - `error`: [`RecordingError`] and [`Hint`], with the binary files' error details
//!   ([`BinaryFormat`], [`BinaryPart`], [`BinaryDefect`], [`Unsupported`]).
//! - `text`: the delimited-text table parser ([`TableFormat`], [`Table`]): lines, numbers,
//!   rows, the row → line table, the streaming of a file. Knows no lab format.
//! - `lab`: the lab formats on top of it: the probe recording's layout
//!   ([`RecordingFormat`]) and samples ([`Recording`]), the PIGA table, the raw PIGA
//!   recording, the probe-recording writer.
//! - `binary`: the TDMS and MAT readers, which build the same [`Recording`].
//! - `stream`: a text recording analysed as it is read, in bounded memory
//!   ([`analyze_recording_file`]).
//! - `analysis`: the harmonic analysis of a loaded recording and the raw PIGA reduction,
//!   with the diagnostics; the statistics themselves (pooling around bad samples, white
//!   noise, drift and spread tests, the slope variance) are `harmonics`'.
//!
//! # Features
//!
//! - `synthetic`: `SyntheticSpec`, synthetic recordings with known
//!   coefficients for fixtures, tests and benchmarks (the `synth_recording` example), and
//!   `write_long_recording`, a long one written row by row (the `analyze_file` example).
//!
//! # Boundaries
//!
//! The crate reads and writes lab files and hands values to `harmonics`; it knows nothing
//! of kinematics, identification, studies, reports or configuration files. It must not
//! depend on `plotters`, `rand`, `ron`, `faer`, `nalgebra`, `kinematics` or `identify`
//! (`ron` only as a dev-dependency); `.ci/layering` checks this.

mod analysis;
mod binary;
mod digest;
mod error;
mod lab;
mod open;
mod read;
mod stream;
#[cfg(feature = "synthetic")]
mod synth;
mod text;

pub use analysis::diagnostic::{
    Diagnostic, MIN_PLAUSIBLE_GAP_UM, OutlierRevolution, PROBE_RESOLUTION_UM,
    RATE_WARNING_TOLERANCE, SampleAt, SpreadCause,
};
pub use analysis::piga::{PigaOutputRate, reduce_piga_recording};
pub use analysis::probe::{
    RecordingAnalysis, RevolutionStatistics, analyze_recording, check_declared_rate,
    implausible_gap, outlier_check, revolution_statistics,
};
pub use binary::mat::{list_mat, load_mat, mat_variable, parse_mat};
pub use binary::tdms::{list_tdms, load_tdms, parse_tdms, tdms_channel};
pub use binary::{BinaryChannels, ChannelInfo, MatVariables};
pub use digest::{FileDigest, Hasher};
pub use error::{
    BinaryDefect, BinaryFormat, BinaryPart, Hint, RecordingError, Result, Unsupported,
};
/// Ratio of the revolution-to-revolution spread of `d_c1`/`d_s1` to its white-noise σ
/// above which [`Diagnostic::RevolutionSpread`] is raised (`harmonics`' limit).
pub use harmonics::SPREAD_WARNING_RATIO;
pub use lab::format::{
    AngleSource, AngleUnit, Column, DecimalMark, Delimiter, LengthUnit, OnBadSamples, OnOutlier,
    RecordingFormat, TimeUnit,
};
pub use lab::piga_recording::{
    PIGA_OUTPUT_ANGLE_COLUMN, PigaRecording, PigaRecordingFormat, load_piga_recording,
    load_piga_recording_digested, parse_piga_recording,
};
pub use lab::piga_table::{
    PIGA_OUTPUT_COLUMN, PIGA_RATE_COLUMN, PigaTable, PigaTableFormat, RateUnit, load_piga_table,
    load_piga_table_with, parse_piga_table, parse_piga_table_with,
};
#[doc(hidden)]
pub use lab::probe::parse_recording_reference;
pub use lab::probe::{AngleSourceKind, Recording};
pub use lab::volts::{GapUnit, ProbeSensitivity, SensitivityUnit};
pub use lab::write::{ProbeColumns, WriteOptions, write_probe_csv};
pub use read::{load_recording, load_recording_digested, parse_recording};
pub use stream::{
    ReadProgress, ReadStage, STREAM_FROM_BYTES, StreamOptions, StreamedRecording,
    analyze_recording_file,
};
#[cfg(feature = "synthetic")]
pub use synth::{SyntheticSpec, write_long_recording};
#[doc(hidden)]
pub use text::number::{number_paths, parse_number};
#[doc(hidden)]
pub use text::parser::parse_table_reference;
pub use text::parser::{load_table, load_table_digested, parse_table};
pub use text::table::{MAX_COLUMNS, Table, TableColumn, TableFormat};
