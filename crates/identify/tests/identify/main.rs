//! Behaviour tests of the `identify` crate.

mod nist;
mod paper;
mod solver;
