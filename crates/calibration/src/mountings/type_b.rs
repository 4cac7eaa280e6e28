//! The Type B inputs of the joint fit (issue 29 part 3): each mounting's radius, the local g,
//! the rate scale, the probe's scale (its gain and lever) and each fixture's three angles, propagated to every chosen term by the
//! GUM's law of propagation (JCGM 100 §5.1.2), with sensitivities from refits at each input
//! moved by ± its standard uncertainty (central differences: the fit is smooth in each input
//! and nearly linear over one u).
//!
//! The inputs are taken as independent: the radii were measured one mounting at a time, and a
//! fixture's index error about one axis says nothing of another. A lab whose radii share a
//! reference (one arm length measured once) has a correlated part this does not see; the
//! results say so in their scope.

use accel_model::CaseAxes;

use super::error::MountingsError;
use super::fit::refit_values;
use super::spec::{JointSpec, MountingData};

/// The Type B standard uncertainties the lab states for a multi-mounting study (the fixtures'
/// angular uncertainty is each mounting's own, [`accel_model::Mounting::angle_u_deg`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MountingsTypeB {
    /// u of each mounting's static radius, m (each independent).
    pub radius_u_m: f64,
    /// u of the local g, m/s².
    pub g_u_m_s2: f64,
    /// Relative u of the rate scale common to every rate.
    pub rate_u_relative: f64,
    /// Relative u of the probe's compensation as a whole (its gain and the lever ratio of
    /// eq. 22 scale the static offset, C_r and the drift across the arm alike).
    pub probe_scale_u_relative: f64,
}

/// Which input a [`TypeBContribution`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TypeBInput {
    /// The static radius of mounting `i`.
    Radius(usize),
    /// The local g.
    Gravity,
    /// The rate scale.
    RateScale,
    /// The probe's compensation as a whole (gain and lever ratio).
    ProbeScale,
    /// Mounting `i`'s fixture turned about its own input, pendulous or output axis.
    Angle(usize, CaseAxis),
}

/// One of the case's axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CaseAxis {
    /// The input axis IA.
    Input,
    /// The pendulous axis PA.
    Pendulous,
    /// The output axis OA.
    Output,
}

impl CaseAxis {
    /// The axis as a reader names it.
    #[must_use]
    pub const fn words(self) -> &'static str {
        match self {
            Self::Input => "IA",
            Self::Pendulous => "PA",
            Self::Output => "OA",
        }
    }
}

/// One Type B input's share of every chosen term's uncertainty.
#[derive(Debug, Clone, PartialEq)]
pub struct TypeBContribution {
    /// The input.
    pub input: TypeBInput,
    /// Its standard uncertainty, in its own unit (m, m/s², relative, rad).
    pub u: f64,
    /// `|c|·u` for each chosen term, in the fit's order ([`super::MountingsFit::terms`]).
    pub contributions: Vec<f64>,
}

/// Each Type B input with a non-zero u, and its contribution to each chosen term's standard
/// uncertainty.
///
/// # Errors
/// The [`MountingsError`] of a refit (one the unmoved fit passed: a moved input that makes
/// the design singular, which one u should never do).
pub fn type_b_contributions(
    spec: &JointSpec,
    data: &[MountingData<'_>],
    type_b: &MountingsTypeB,
) -> Result<Vec<TypeBContribution>, MountingsError> {
    let mut inputs = Vec::new();
    for (i, d) in data.iter().enumerate() {
        if type_b.radius_u_m > 0.0 {
            inputs.push((TypeBInput::Radius(i), type_b.radius_u_m));
        }
        let angle_u_rad = d.mounting.angle_u_deg.to_radians();
        if angle_u_rad > 0.0 {
            for axis in [CaseAxis::Input, CaseAxis::Pendulous, CaseAxis::Output] {
                inputs.push((TypeBInput::Angle(i, axis), angle_u_rad));
            }
        }
    }
    if type_b.g_u_m_s2 > 0.0 {
        inputs.push((TypeBInput::Gravity, type_b.g_u_m_s2));
    }
    if type_b.rate_u_relative > 0.0 {
        inputs.push((TypeBInput::RateScale, type_b.rate_u_relative));
    }
    if type_b.probe_scale_u_relative > 0.0 && spec.probe.is_some() {
        inputs.push((TypeBInput::ProbeScale, type_b.probe_scale_u_relative));
    }
    inputs
        .into_iter()
        .map(|(input, u)| {
            let plus = moved_terms(spec, data, input, u)?;
            let minus = moved_terms(spec, data, input, -u)?;
            Ok(TypeBContribution {
                input,
                u,
                contributions: plus
                    .iter()
                    .zip(&minus)
                    .map(|(p, m)| ((p - m) / 2.0).abs())
                    .collect(),
            })
        })
        .collect()
}

/// The chosen terms' values refitted with `input` moved by `by`.
fn moved_terms(
    spec: &JointSpec,
    data: &[MountingData<'_>],
    input: TypeBInput,
    by: f64,
) -> Result<Vec<f64>, MountingsError> {
    let mut spec = spec.clone();
    let mut data = data.to_vec();
    let scaled: Vec<Vec<f64>>;
    match input {
        TypeBInput::Radius(i) => data[i].mounting.radius_m += by,
        TypeBInput::Gravity => spec.g_m_s2 += by,
        TypeBInput::Angle(i, axis) => {
            data[i].mounting.axes = turned(&data[i].mounting.axes, axis, by);
        }
        TypeBInput::ProbeScale => {
            if let Some(p) = &mut spec.probe {
                let f = 1.0 + by;
                p.static_m *= f;
                p.c_r_m_s2 *= f;
                p.static_across_m *= f;
                p.c_ry_m_s2 *= f;
            }
        }
        TypeBInput::RateScale => {
            scaled = data
                .iter()
                .map(|d| d.rates_rad_s.iter().map(|w| w * (1.0 + by)).collect())
                .collect();
            for (d, rates) in data.iter_mut().zip(&scaled) {
                d.rates_rad_s = rates;
            }
        }
    }
    Ok(refit_values(&spec, &data)?
        .terms
        .iter()
        .map(|t| t.value)
        .collect())
}

/// The case axes turned by `angle_rad` about one of them (Rodrigues' formula: the axis turned
/// about stays, the other two turn in their plane).
fn turned(axes: &CaseAxes, about: CaseAxis, angle_rad: f64) -> CaseAxes {
    let k = match about {
        CaseAxis::Input => axes.ia,
        CaseAxis::Pendulous => axes.pa,
        CaseAxis::Output => axes.oa,
    };
    let (s, c) = angle_rad.sin_cos();
    let rotate = |v: [f64; 3]| -> [f64; 3] {
        let cross = [
            k[1] * v[2] - k[2] * v[1],
            k[2] * v[0] - k[0] * v[2],
            k[0] * v[1] - k[1] * v[0],
        ];
        let dot = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
        std::array::from_fn(|j| v[j] * c + cross[j] * s + k[j] * dot * (1.0 - c))
    };
    CaseAxes {
        ia: rotate(axes.ia),
        pa: rotate(axes.pa),
        oa: rotate(axes.oa),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use accel_model::MountingPreset;

    #[test]
    fn a_turn_keeps_the_axes_orthonormal_and_right_handed() {
        let axes = MountingPreset::Ia45.axes();
        for about in [CaseAxis::Input, CaseAxis::Pendulous, CaseAxis::Output] {
            let t = turned(&axes, about, 0.3);
            t.validate().expect("orthonormal, right-handed");
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            // the axis turned about stays; the others move by the angle
            let (kept, moved) = match about {
                CaseAxis::Input => (dot(t.ia, axes.ia), dot(t.pa, axes.pa)),
                CaseAxis::Pendulous => (dot(t.pa, axes.pa), dot(t.oa, axes.oa)),
                CaseAxis::Output => (dot(t.oa, axes.oa), dot(t.ia, axes.ia)),
            };
            assert!((kept - 1.0).abs() < 1e-15, "{about:?}: {kept}");
            assert!((moved - 0.3_f64.cos()).abs() < 1e-15, "{about:?}: {moved}");
        }
    }
}
