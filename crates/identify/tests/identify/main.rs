//! Behaviour tests of the `identify` crate.

mod calibration;
mod nist;
mod paper;
mod solver;
