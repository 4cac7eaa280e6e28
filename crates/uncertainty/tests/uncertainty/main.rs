//! Behaviour tests of the `uncertainty` crate.

mod coverage;
mod sensitivity;
mod welch;
