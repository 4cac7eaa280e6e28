//! `centrifuge_cal._native`: the Rust side of the `centrifuge_cal` Python package.
//!
//! Thin bindings over the workspace's libraries; the Python package
//! (`python/centrifuge_cal`) gives them their Pythonic shape: typed result objects and
//! checked arrays. Equations are those of the libraries called: the per-revolution
//! harmonic fit (eq. 20–21, `harmonics`), the radius-error fit and Δk2 (eq. 16, 19,
//! `identify`), the study with its calibration (eq. 18, 23) and uncertainty budget
//! (`pipeline`, `report`), the test planner (`planning`).
//!
//! What crosses is native: arrays as numpy arrays (a study's tables as
//! `recording::Table`s built from them), results as Python dicts and lists built from the
//! Rust results' `Serialize` (`to_python`), dicts of a configuration read into the
//! configuration's types (`values`, depth-limited), exceptions of classes created here
//! (`errors`) with their fields from the errors' own. Long computations release the GIL
//! and stop on Ctrl-C (`interrupt`); contiguous float64 arrays are read in place.

// One feature set with the tests' build (crates/workspace-hack).
use workspace_hack as _;

mod errors;
mod files;
mod fit;
mod history;
mod interrupt;
mod study;
mod to_python;
mod values;

use pyo3::prelude::*;

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    m.add_function(wrap_pyfunction!(study::defaults, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit_harmonics, m)?)?;
    m.add_function(wrap_pyfunction!(files::read_recording, m)?)?;
    m.add_class::<files::NativeRecording>()?;
    m.add_function(wrap_pyfunction!(study::run_study_file, m)?)?;
    m.add_function(wrap_pyfunction!(study::run_study_dict, m)?)?;
    m.add_function(wrap_pyfunction!(study::plan, m)?)?;
    m.add_function(wrap_pyfunction!(study::fit_radius_error, m)?)?;
    m.add_function(wrap_pyfunction!(study::delta_k2, m)?)?;
    m.add_function(wrap_pyfunction!(study::certificate, m)?)?;
    m.add_function(wrap_pyfunction!(history::unit_history, m)?)?;
    m.add_function(wrap_pyfunction!(history::centrifuge_health, m)?)?;
    m.add_function(wrap_pyfunction!(cli_main, m)?)?;
    m.add("VERSION", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

/// Runs the command line (`cli::run_with`, as the installed `centrifuge-cal`) with `argv`
/// (the program's name first, as `sys.argv`) and returns its exit status; the GIL is
/// released while it runs.
#[pyfunction]
fn cli_main(py: Python<'_>, argv: Vec<std::ffi::OsString>) -> u8 {
    py.detach(|| cli::run_with(&cli::Places::installed(), argv))
}
