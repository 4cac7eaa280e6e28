//! The measurement model `Y = f(X)`.

use crate::error::ModelError;

/// A measurement model `Y = f(X)` with several inputs and several outputs (JCGM 100 §4.1,
/// JCGM 102 for several outputs).
///
/// `evaluate` is called with the inputs in the order of the [`Inputs`](crate::Inputs) and
/// writes one value per output name into `y` (whose length is `output_names().len()`). It is
/// called from several threads at once by the Monte Carlo method, hence `Sync`; it should not
/// allocate, as it runs once per trial.
pub trait MeasurementModel: Sync {
    /// The output quantities' names, in the order `evaluate` writes them.
    fn output_names(&self) -> Vec<String>;

    /// Evaluates the model at `x`, writing the outputs into `y`. A failure at some draws (a
    /// singular design, a value outside the model's domain) is a [`ModelError`].
    fn evaluate(&self, x: &[f64], y: &mut [f64]) -> Result<(), ModelError>;

    /// The number of inputs the model takes, when it knows it; checked against the inputs
    /// given (`None`, the default, skips the check).
    fn input_count(&self) -> Option<usize> {
        None
    }

    /// Evaluates the model at `len` trials at once; the Monte Carlo method calls this.
    ///
    /// Input `i` of trial `t` is `x[i·stride + t]` (one column of `stride ≥ len` values per
    /// input); output `k` of trial `t` goes to `y[t·m + k]` for `m` outputs
    /// (`y.len() = len·m`). A trial that fails has all its outputs set to NaN, and the first
    /// failure is returned with its trial index. The default calls
    /// [`evaluate`](Self::evaluate) trial by trial; a model may override it with a loop over
    /// the trials that the compiler can vectorise, which must give the same values.
    fn evaluate_trials(
        &self,
        x: &[f64],
        stride: usize,
        len: usize,
        y: &mut [f64],
    ) -> Option<(usize, ModelError)> {
        let n = x.len().checked_div(stride).unwrap_or(0);
        let m = y.len().checked_div(len).unwrap_or(0);
        let mut xt = vec![0.0; n];
        let mut first = None;
        for (t, yt) in y.chunks_exact_mut(m.max(1)).take(len).enumerate() {
            for (i, v) in xt.iter_mut().enumerate() {
                *v = x[i * stride + t];
            }
            if let Err(e) = self.evaluate(&xt, yt) {
                yt.fill(f64::NAN);
                first.get_or_insert((t, e));
            }
        }
        first
    }
}

/// A measurement model made of a closure, from [`model_fn`].
pub struct FnModel<F> {
    outputs: Vec<String>,
    inputs: Option<usize>,
    f: F,
}

impl<F> std::fmt::Debug for FnModel<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FnModel")
            .field("outputs", &self.outputs)
            .field("inputs", &self.inputs)
            .finish_non_exhaustive()
    }
}

impl<F> FnModel<F> {
    /// The same model, declaring that it takes `count` inputs (checked by [`gum`](crate::gum)
    /// and [`monte_carlo`](crate::monte_carlo)).
    pub fn with_input_count(mut self, count: usize) -> Self {
        self.inputs = Some(count);
        self
    }
}

/// A measurement model from output names and a closure `f(x, y)`.
///
/// ```
/// use uncertainty::{MeasurementModel, model_fn};
/// let ratio = model_fn(["ratio"], |x, y| {
///     y[0] = x[0] / x[1];
///     Ok(())
/// });
/// let mut y = [0.0];
/// ratio.evaluate(&[3.0, 4.0], &mut y)?;
/// assert_eq!(y[0], 0.75);
/// # Ok::<(), uncertainty::ModelError>(())
/// ```
pub fn model_fn<F, S>(outputs: impl IntoIterator<Item = S>, f: F) -> FnModel<F>
where
    F: Fn(&[f64], &mut [f64]) -> Result<(), ModelError> + Sync,
    S: Into<String>,
{
    FnModel {
        outputs: outputs.into_iter().map(Into::into).collect(),
        inputs: None,
        f,
    }
}

impl<F> MeasurementModel for FnModel<F>
where
    F: Fn(&[f64], &mut [f64]) -> Result<(), ModelError> + Sync,
{
    fn output_names(&self) -> Vec<String> {
        self.outputs.clone()
    }

    fn evaluate(&self, x: &[f64], y: &mut [f64]) -> Result<(), ModelError> {
        (self.f)(x, y)
    }

    fn input_count(&self) -> Option<usize> {
        self.inputs
    }
}

impl<M: MeasurementModel + ?Sized> MeasurementModel for &M {
    fn output_names(&self) -> Vec<String> {
        (**self).output_names()
    }

    fn evaluate(&self, x: &[f64], y: &mut [f64]) -> Result<(), ModelError> {
        (**self).evaluate(x, y)
    }

    fn input_count(&self) -> Option<usize> {
        (**self).input_count()
    }

    fn evaluate_trials(
        &self,
        x: &[f64],
        stride: usize,
        len: usize,
        y: &mut [f64],
    ) -> Option<(usize, ModelError)> {
        (**self).evaluate_trials(x, stride, len, y)
    }
}

/// The model's output names, checked (at least one, none empty, none repeated), after checking
/// the model's declared input count against `inputs`.
pub(crate) fn checked_output_names<M: MeasurementModel + ?Sized>(
    model: &M,
    inputs: usize,
) -> crate::Result<Vec<String>> {
    use crate::UncertaintyError;
    if let Some(count) = model.input_count()
        && count != inputs
    {
        return Err(UncertaintyError::InputCount {
            model: count,
            given: inputs,
        });
    }
    let names = model.output_names();
    if names.is_empty() {
        return Err(UncertaintyError::NoOutputs);
    }
    let mut seen = std::collections::HashSet::with_capacity(names.len());
    for (index, name) in names.iter().enumerate() {
        if name.is_empty() {
            return Err(UncertaintyError::EmptyName { index });
        }
        if !seen.insert(name.as_str()) {
            return Err(UncertaintyError::DuplicateName { name: name.clone() });
        }
    }
    Ok(names)
}
