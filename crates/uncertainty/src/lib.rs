//! Measurement uncertainty of a model `Y = f(X)` with several inputs and several outputs.
//!
//! The crate knows nothing of what it measures: it evaluates a user-supplied
//! [`MeasurementModel`] (or a closure through [`model_fn`]) at validated [`Inputs`].
//! This first part holds the inputs, the model, the coverage factor from Student's t
//! (JCGM 100:2008 G.3, G.4; [`coverage_factor`]) and the numerical tolerance of
//! JCGM 101:2008 §7.9.2 ([`numerical_tolerance`]).

mod error;
mod input;
mod model;
mod student;
mod tolerance;

pub use error::{ModelError, Result, Statistic, UncertaintyError};
pub use input::{Distribution, Dof, Evaluation, InputQuantity, Inputs};
pub use model::{FnModel, MeasurementModel, model_fn};
pub use student::{coverage_factor, student_t_quantile};
pub use tolerance::numerical_tolerance;
