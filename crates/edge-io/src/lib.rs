//! File I/O at the edge of centrifuge-cal, shared by the crates that touch files.
//!
//! - [`read_text_capped`]: reads a configuration-like text file (study configuration,
//!   simulation scenario, expected values) with a size cap, so a wrong or hostile path cannot
//!   make a command read gigabytes before the parser refuses it. A UTF-8 byte-order mark is
//!   dropped; text that is not UTF-8 is refused naming the line, column and byte offset.
//!   [`CONFIG_MAX_BYTES`] (16 MiB) is the cap of every such file in the workspace.
//! - [`open_regular`]: opens a file only if it is a regular file, checked on the open
//!   handle, never blocking on a FIFO; every reader of the workspace's edges opens through it,
//!   the recording readers included (they take this crate without its `formats` feature, so
//!   without RON and JSON).
//! - [`OutputSet`]: writes a set of output files (a study's `results.json`, `report.md` and
//!   figures; a simulation's recordings) into a staging directory beside the target and swaps
//!   it into place, so a run leaves either the complete new set or the previous one untouched.
//! - [`to_json_pretty`] and [`check_finite`]: the JSON writer of result files and `--json`
//!   output, which refuses a NaN or ±∞ anywhere in the value (serde_json would write `null`),
//!   naming its path.
//!
//! - [`ron_options`]: the one RON dialect of the workspace's configuration files (studies,
//!   scenarios, expected values, plans): optional sections are written without `Some(...)`;
//!   [`from_ron`], the one reader of them, whose error ([`RonError`]) is located (file, line,
//!   column).
//!
//! - [`visible`] and [`hidden_char`]: text from a file shown to a person, with the characters
//!   that hide, reorder or act (control characters, bidirectional overrides) written visibly or
//!   found, for the fields that refuse them.
//!
//! Errors are one typed enum, [`EdgeIoError`], whose every variant names the file or directory.

mod error;
#[doc(hidden)]
pub mod fault;
#[cfg(feature = "formats")]
mod json;
mod open;
mod output;
#[cfg(feature = "formats")]
mod ron_read;
mod text;
mod visible;

pub use error::{EdgeIoError, Result};
#[cfg(feature = "formats")]
pub use json::{JsonError, NonFiniteValue, check_finite, to_json_pretty};
pub use open::{kind_of, open_regular};
pub use output::{OUTPUT_RECORD, OutputSet};
#[cfg(feature = "formats")]
pub use ron_read::{RonError, from_ron};
pub use text::{CONFIG_MAX_BYTES, read_bytes_capped, read_text_capped, text_from_bytes};
pub use visible::{HiddenChar, hidden_char, is_hidden, visible, visible_lines};

#[cfg(feature = "formats")]
/// The RON dialect of every configuration file in the workspace: RON with implicit `Some`
/// (an optional section is written as its value, not `Some(value)`).
pub fn ron_options() -> ron::Options {
    ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
}
