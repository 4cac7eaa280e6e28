//! Behaviour of the simulator: scenario validation, the probe model and the files it writes.

use test_support::scenarios as common;
mod files;
mod probe_model;
mod scenario_errors;
mod two_orientation;
