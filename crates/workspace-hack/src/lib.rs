//! One feature set for the shared dependencies (the `workspace-hack` pattern of cargo-hakari,
//! written by hand): this crate has no code; depending on it turns on, in every build, the
//! features `cargo test --workspace` turns on through dev-dependencies, so that `cargo
//! xtask`, the installed command and the Python wheel reuse what the tests compiled instead
//! of compiling typst, faer and the workspace again with other features. `.ci/features`
//! checks that the feature sets agree.

// The dependencies are here for their features only.
use approx as _;
use bit_set as _;
use bit_vec as _;
use bitflags as _;
use edge_io as _;
use either as _;
use fastrand as _;
use harmonics as _;
use matrixmultiply as _;
use num_complex as _;
use num_integer as _;
use recording as _;
