//! Behaviour of the readers through the public API.

mod binary;
mod piga_recording;
mod probe;
mod table;
