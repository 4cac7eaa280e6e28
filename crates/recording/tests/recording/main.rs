//! Behaviour of the readers through the public API.

mod binary;
mod probe;
mod table;
