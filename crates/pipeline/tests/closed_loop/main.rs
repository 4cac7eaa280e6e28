//! Closed-loop behaviour of the simulator: scenario validation, the probe model, the files,
//! and the loop simulate → harmonics → C_r fit → compensated identification (issue 4).

mod common;
mod files;
mod mechanism;
mod probe_model;
mod scenario_errors;
