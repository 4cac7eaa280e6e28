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
//! * [`monte_carlo`]: the propagation of distributions of **JCGM 101:2008** (GUM Supplement
//!   1): inputs drawn from normal (§6.4.7), rectangular (§6.4.2), scaled-and-shifted t
//!   (§6.4.9) and multivariate normal (§6.4.8) distributions, the estimate and standard
//!   uncertainty (§7.6), the probabilistically symmetric coverage interval (§7.7), and the
//!   adaptive Monte Carlo procedure (§7.9) with the numerical tolerance of §7.9.2
//!   ([`numerical_tolerance`]). Seeded and parallel; the result does not depend on the
//!   number of threads. The draws come from xoshiro256++ (`rand_xoshiro`), one stream per
//!   chunk of 1000 trials, not from the `StdRng` (ChaCha12) the rest of the workspace uses:
//!   the Monte Carlo method needs a statistically sound generator, not an unpredictable one,
//!   and xoshiro256++ is a fixed algorithm (the same numbers for a seed on every platform and
//!   version) that costs several times less per random word.
//! * [`validate`]: the validation of the GUM framework by the Monte Carlo method
//!   (JCGM 101 §8).
//!
//! No function returns `Ok` holding an infinite or NaN number; every failure is an
//! [`UncertaintyError`] naming the input or output concerned.
//!
//! ```
//! use approx::assert_relative_eq;
//! use uncertainty::{
//!     Dof, GumOptions, InputQuantity, Inputs, McOptions, gum, model_fn, monte_carlo, validate,
//! };
//! // A resistance from a voltage and a current: R = V / I.
//! let inputs = Inputs::new(vec![
//!     InputQuantity::type_a("V", 5.0, 0.01, Dof::Finite(9.0)),
//!     InputQuantity::normal("I", 0.02, 2e-5),
//! ])?;
//! let model = model_fn(["R"], |x, y| {
//!     y[0] = x[0] / x[1];
//!     Ok(())
//! });
//! let g = gum(&model, &inputs, &GumOptions::default())?;
//! let r = &g.outputs[0];
//! assert_relative_eq!(r.estimate, 250.0, max_relative = 1e-12);
//! // u_c² = (u_V/I)² + (V·u_I/I²)² = 0.5² + 0.25²
//! assert_relative_eq!(r.standard_uncertainty, (0.25f64 + 0.0625).sqrt(), max_relative = 1e-9);
//! // Welch–Satterthwaite: ν_eff = u_c⁴ / (0.5⁴/9) = 14.06
//! assert_relative_eq!(r.dof.finite().unwrap(), 0.3125f64.powi(2) / (0.0625 / 9.0), max_relative = 1e-9);
//! assert_relative_eq!(r.coverage_factor, 2.1439, max_relative = 1e-4);
//! // The Monte Carlo method draws V from the scaled-and-shifted t_9 (JCGM 101 §6.4.9). Its
//! // interval agrees with R ± U to one significant digit of u_c, not to two.
//! let mc = monte_carlo(&model, &inputs, &McOptions::default())?;
//! assert!(validate(&g, &mc, 1)?.all_agree());
//! assert!(!validate(&g, &mc, 2)?.all_agree());
//! # Ok::<(), uncertainty::UncertaintyError>(())
//! ```
//!
//! # References
//! * JCGM 100:2008, *Evaluation of measurement data — Guide to the expression of uncertainty
//!   in measurement* (GUM).
//! * JCGM 101:2008, *Supplement 1 to the GUM — Propagation of distributions using a Monte
//!   Carlo method*.
//! * JCGM 102:2011, *Supplement 2 to the GUM — Extension to any number of output
//!   quantities*.

mod error;
mod gum;
mod input;
mod kind;
mod model;
mod monte_carlo;
mod stop;
mod student;
mod tolerance;
mod validate;

pub use error::{ModelError, Result, Statistic, UncertaintyError};
pub use gum::{Contribution, DofRounding, GumOptions, GumOutput, GumResult, gum};
pub use input::{InputQuantity, Inputs};
pub use kind::{Distribution, Dof, Evaluation};
pub use model::{FnModel, MeasurementModel, model_fn};
pub use monte_carlo::{
    MAX_TRIALS, MC_BYTES_PER_TRIAL_AND_OUTPUT, McOptions, McOutput, McResult, Stability, Trials,
    check_trials, monte_carlo,
};
pub use stop::stoppable;
pub use student::{coverage_factor, student_t_quantile};
pub use tolerance::numerical_tolerance;
pub use validate::{OutputValidation, Validation, validate};
