//! Measurement uncertainty of a model `Y = f(X)` with several inputs and several outputs.
//!
//! The crate knows nothing of what it measures: it evaluates a user-supplied
//! [`MeasurementModel`] (or a closure through [`model_fn`]) at validated [`Inputs`].
//!
//! * [`gum`]: the GUM uncertainty framework of **JCGM 100:2008** (GUM): the estimate
//!   (§4.1.4), sensitivity coefficients computed numerically through the model (eq. 11a), the
//!   combined standard uncertainty for uncorrelated (§5.1, eq. 10) and correlated (§5.2,
//!   eq. 13) inputs, each input's contribution, the effective degrees of freedom by
//!   Welch–Satterthwaite (Annex G, eq. G.2b), the coverage factor from Student's t
//!   (G.3, G.4; [`coverage_factor`]) and the expanded uncertainty (§6). The outputs'
//!   covariance follows JCGM 102:2011 §6.2.1.3.
//! * [`numerical_tolerance`]: δ of JCGM 101:2008 §7.9.2.

mod error;
mod gum;
mod input;
mod model;
mod student;
mod tolerance;

pub use error::{ModelError, Result, Statistic, UncertaintyError};
pub use gum::{Contribution, DofRounding, GumOptions, GumOutput, GumResult, gum};
pub use input::{Distribution, Dof, Evaluation, InputQuantity, Inputs};
pub use model::{FnModel, MeasurementModel, model_fn};
pub use student::{coverage_factor, student_t_quantile};
pub use tolerance::numerical_tolerance;
