//! The lab formats: what the columns of a lab's files mean. The layout of a probe recording
//! ([`format`]) and its reading into samples ([`probe`]), the PIGA table ([`piga_table`]),
//! the raw PIGA output recording ([`piga_recording`]) and the probe-recording writer
//! ([`write`]). Built on the text parser (module `text`); the binary readers
//! (module `binary`) build the same [`probe::Recording`].

pub(crate) mod format;
pub(crate) mod piga_recording;
pub(crate) mod piga_table;
pub(crate) mod probe;
pub(crate) mod volts;
pub(crate) mod write;
