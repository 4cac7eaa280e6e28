//! NI's channel scaling in TDMS properties (`NI_Number_Of_Scales`, `NI_Scale[i]_…`): the
//! chain from a channel's raw values (or one of its DAQmx scalers) through linear and
//! polynomial scales to the engineering unit, as npTDMS applies it.
//!
//! Scale `n − 1` (the last) gives the channel's values; each scale reads its input source:
//! another scale, or the raw data (`0xFFFFFFFF`). A scale without a `Scale_Type` property is
//! the DAQmx scaler of the same id. `NI_Scaling_Status = "scaled"` means the stored values
//! are already scaled.

use crate::error::Unsupported;

/// A channel's raw values, as the input source names them.
pub(super) const RAW_SOURCE: u32 = 0xFFFF_FFFF;

/// A property value the readers keep.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Prop {
    /// A number.
    Num(f64),
    /// A string.
    Text(String),
}

/// Where a scaling chain starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Leaf {
    /// The channel's raw values.
    Raw,
    /// The values of the channel's DAQmx scaler with this scale id.
    Scaler(u32),
}

/// One scale of the chain, applied to its input.
#[derive(Debug, Clone, PartialEq)]
enum Step {
    /// `x·slope + intercept`.
    Linear { slope: f64, intercept: f64 },
    /// `Σ cⱼ xʲ` (Horner, as numpy's `polyval`).
    Polynomial { coefficients: Vec<f64> },
}

/// A channel's scaling: where it starts and the scales from there to the channel's values.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Scaling {
    /// Where the chain starts.
    pub(super) leaf: Leaf,
    /// The scales, first applied first.
    steps: Vec<Step>,
}

/// The longest chain followed (a chain that loops is refused).
const MAX_SCALES: u32 = 64;

impl Scaling {
    /// No scaling: the values of `leaf` as they are.
    pub(super) fn none(leaf: Leaf) -> Self {
        Self {
            leaf,
            steps: Vec::new(),
        }
    }

    /// The scaling the properties describe (`props` of the channel, else of its group,
    /// else of the file, as npTDMS looks them up); `None` when none of them has scales or
    /// they say the values are already scaled.
    ///
    /// # Errors
    /// [`Unsupported::TdmsScaling`] for a scale type other than linear, polynomial, a
    /// DAQmx scaler or NI's pass-through `AdvancedAPI`, a missing coefficient, or a chain that loops.
    pub(super) fn from_properties(
        levels: &[&[(String, Prop)]],
    ) -> Result<Option<Self>, Unsupported> {
        let Some(props) = levels
            .iter()
            .find(|p| scale_count(p).is_some_and(|n| n > 0))
        else {
            return Ok(None);
        };
        if text(props, "NI_Scaling_Status") == Some("scaled") {
            return Ok(None);
        }
        let n = scale_count(props).unwrap_or(0);
        let mut steps = Vec::new();
        let mut index = n - 1;
        for _ in 0..=MAX_SCALES.min(n) {
            if index == RAW_SOURCE {
                steps.reverse();
                return Ok(Some(Self {
                    leaf: Leaf::Raw,
                    steps,
                }));
            }
            let i = index;
            let key = |field: &str| format!("NI_Scale[{i}]_{field}");
            let source = |kind: &str| {
                number(props, &key(&format!("{kind}_Input_Source")))
                    .map_or(RAW_SOURCE, |v| v as u32)
            };
            let missing = |field: String| Unsupported::TdmsScaling(format!("no {field}"));
            match text(props, &key("Scale_Type")) {
                None => {
                    steps.reverse();
                    return Ok(Some(Self {
                        leaf: Leaf::Scaler(i),
                        steps,
                    }));
                }
                Some("Linear") => {
                    let slope = number(props, &key("Linear_Slope"))
                        .ok_or_else(|| missing(key("Linear_Slope")))?;
                    let intercept = number(props, &key("Linear_Y_Intercept"))
                        .ok_or_else(|| missing(key("Linear_Y_Intercept")))?;
                    steps.push(Step::Linear { slope, intercept });
                    index = source("Linear");
                }
                Some("Polynomial") => {
                    let size = number(props, &key("Polynomial_Coefficients_Size"))
                        .map_or(4, |v| v as usize);
                    let coefficients = (0..size.min(64))
                        .map(|j| {
                            let k = key(&format!("Polynomial_Coefficients[{j}]"));
                            number(props, &k).ok_or_else(|| missing(k))
                        })
                        .collect::<Result<Vec<f64>, _>>()?;
                    steps.push(Step::Polynomial { coefficients });
                    index = source("Polynomial");
                }
                // NI's "advanced API" scale: the values pass through (as npTDMS reads it).
                Some("AdvancedAPI") => index = source("AdvancedAPI"),
                Some(other) => {
                    return Err(Unsupported::TdmsScaling(format!("scale type `{other}`")));
                }
            }
        }
        Err(Unsupported::TdmsScaling(
            "a chain of scales that loops".into(),
        ))
    }

    /// Whether the scaling leaves the values as they are.
    pub(super) fn is_identity(&self) -> bool {
        self.steps.is_empty()
    }

    /// Applies the scales to the leaf's values, in place.
    pub(super) fn apply(&self, values: &mut [f64]) {
        for step in &self.steps {
            match step {
                Step::Linear { slope, intercept } => {
                    for v in values.iter_mut() {
                        *v = *v * slope + intercept;
                    }
                }
                Step::Polynomial { coefficients } => {
                    for v in values.iter_mut() {
                        let x = *v;
                        *v = match coefficients.split_last() {
                            None => 0.0,
                            Some((last, rest)) => {
                                rest.iter().rev().fold(*last, |acc, c| c + acc * x)
                            }
                        };
                    }
                }
            }
        }
    }
}

/// `NI_Number_Of_Scales`, else one more than the largest `NI_Scale[i]_Scale_Type` index.
fn scale_count(props: &[(String, Prop)]) -> Option<u32> {
    if let Some(n) = number(props, "NI_Number_Of_Scales") {
        return Some(n as u32);
    }
    props
        .iter()
        .filter_map(|(name, _)| {
            name.strip_prefix("NI_Scale[")?
                .strip_suffix("]_Scale_Type")?
                .parse::<u32>()
                .ok()
        })
        .max()
        .map(|i| i.saturating_add(1))
}

fn number(props: &[(String, Prop)], name: &str) -> Option<f64> {
    props.iter().rev().find_map(|(n, v)| match v {
        Prop::Num(x) if n == name => Some(*x),
        _ => None,
    })
}

fn text<'p>(props: &'p [(String, Prop)], name: &str) -> Option<&'p str> {
    props.iter().rev().find_map(|(n, v)| match v {
        Prop::Text(s) if n == name => Some(s.as_str()),
        _ => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn props(list: &[(&str, Prop)]) -> Vec<(String, Prop)> {
        list.iter()
            .map(|(n, v)| ((*n).to_string(), v.clone()))
            .collect()
    }

    #[test]
    fn a_chain_from_a_daqmx_scaler_through_polynomial_and_linear() {
        let p = props(&[
            ("NI_Number_Of_Scales", Prop::Num(3.0)),
            ("NI_Scale[1]_Scale_Type", Prop::Text("Polynomial".into())),
            ("NI_Scale[1]_Polynomial_Coefficients_Size", Prop::Num(3.0)),
            ("NI_Scale[1]_Polynomial_Coefficients[0]", Prop::Num(1.0)),
            ("NI_Scale[1]_Polynomial_Coefficients[1]", Prop::Num(2.0)),
            ("NI_Scale[1]_Polynomial_Coefficients[2]", Prop::Num(3.0)),
            ("NI_Scale[1]_Polynomial_Input_Source", Prop::Num(0.0)),
            ("NI_Scale[2]_Scale_Type", Prop::Text("Linear".into())),
            ("NI_Scale[2]_Linear_Slope", Prop::Num(10.0)),
            ("NI_Scale[2]_Linear_Y_Intercept", Prop::Num(-1.0)),
            ("NI_Scale[2]_Linear_Input_Source", Prop::Num(1.0)),
        ]);
        let s = Scaling::from_properties(&[&p]).unwrap().unwrap();
        assert_eq!(s.leaf, Leaf::Scaler(0));
        let mut v = [2.0];
        s.apply(&mut v);
        // (1 + 2·2 + 3·4)·10 − 1
        assert_eq!(v, [169.0]);
    }

    #[test]
    fn scaled_status_loops_and_unknown_types() {
        let scaled = props(&[
            ("NI_Number_Of_Scales", Prop::Num(1.0)),
            ("NI_Scaling_Status", Prop::Text("scaled".into())),
            ("NI_Scale[0]_Scale_Type", Prop::Text("Linear".into())),
        ]);
        assert_eq!(Scaling::from_properties(&[&scaled]), Ok(None));
        let looping = props(&[
            ("NI_Number_Of_Scales", Prop::Num(1.0)),
            ("NI_Scale[0]_Scale_Type", Prop::Text("Linear".into())),
            ("NI_Scale[0]_Linear_Slope", Prop::Num(1.0)),
            ("NI_Scale[0]_Linear_Y_Intercept", Prop::Num(0.0)),
            ("NI_Scale[0]_Linear_Input_Source", Prop::Num(0.0)),
        ]);
        assert!(Scaling::from_properties(&[&looping]).is_err());
        let rtd = props(&[("NI_Scale[0]_Scale_Type", Prop::Text("RTD".into()))]);
        assert!(matches!(
            Scaling::from_properties(&[&rtd]),
            Err(Unsupported::TdmsScaling(t)) if t.contains("RTD")
        ));
        assert_eq!(Scaling::from_properties(&[&[], &[]]), Ok(None));
    }
}
