//! The records database: recording, its rules (keyed by hash, never updated in place, a
//! corrected certificate supersedes), refusing files that are not records, and the history
//! computed from it.

mod common;
mod database;
mod history;
