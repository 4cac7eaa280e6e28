//! Probe recordings in the binary formats labs store beside CSV: NI TDMS (`tdms`) and
//! MATLAB MAT v5/v7 (`mat`). This module holds what both share: the channel selection,
//! the typed error parts, the sample conversion, and the assembly of a [`Recording`].
//!
//! # Samples have no line
//!
//! A CSV recording keeps the line of each sample; a binary one has none, so
//! [`Recording::line_of_sample`] is 0 for it and its errors name the channel (or variable)
//! and the 0-based sample index ([`RecordingError::NonFiniteSample`],
//! [`RecordingError::TimeAxis`], [`RecordingError::Samples`] with `line: None`).
//!
//! # Bounded reading
//!
//! The whole file is read into memory (its size is the bound), and every length field is
//! checked against the bytes that remain before anything is sliced or allocated from it:
//! a sample vector is allocated only for samples whose bytes are in the file. A compressed
//! MAT variable grows only with its inflated output, at most 1032 times its compressed size
//! (DEFLATE's largest ratio).

mod channels;
mod daqmx;
mod decode;
pub(crate) mod mat;
mod scaling;
mod source;
pub(crate) mod tdms;

pub use channels::{BinaryChannels, MatVariables};
