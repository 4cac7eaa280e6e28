//! Behaviour of the simulator: scenario validation, the probe model and the files it writes.

mod common;
mod files;
mod probe_model;
mod scenario_errors;
mod symmetric;
