//! Behaviour of the readers through the public API.

mod bad_samples;
mod binary;
mod daqmx;
mod hostile;
mod piga_recording;
mod piga_table;
mod probe;
mod stream;
mod symbols;
mod table;
mod volts;
