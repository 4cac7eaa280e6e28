//! Behaviour tests of the `uncertainty` crate.

mod correlated;
mod coverage;
mod distributions;
mod errors;
mod linear;
mod nonlinear;
mod reproducible;
mod sensitivity;
mod welch;
