//! Behaviour tests of the `identify` crate.

mod paper;
