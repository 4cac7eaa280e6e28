//! Behaviour of the readers through the public API.

mod probe;
mod table;
