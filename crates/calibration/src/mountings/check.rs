//! The checks of a declaration and its data, before anything is built from them.

use super::error::MountingsError;
use super::spec::{JointSpec, MountingData};

/// Checks the declaration and the data: every problem of the first bad field.
pub(super) fn check(spec: &JointSpec, data: &[MountingData<'_>]) -> Result<(), MountingsError> {
    if data.is_empty() {
        return Err(MountingsError::Empty {
            field: "mountings".to_owned(),
            what: "no mounting",
        });
    }
    if spec.terms.is_empty() {
        return Err(MountingsError::Empty {
            field: "terms".to_owned(),
            what: "no term chosen",
        });
    }
    if !spec.earth_rate_vertical_rad_s.is_finite() {
        return Err(MountingsError::Invalid {
            field: "earth_rate_vertical_rad_s".to_owned(),
            value: spec.earth_rate_vertical_rad_s,
            reason: "must be finite",
        });
    }
    if !(spec.g_m_s2.is_finite() && spec.g_m_s2 > 0.0) {
        return Err(MountingsError::Invalid {
            field: "g_m_s2".to_owned(),
            value: spec.g_m_s2,
            reason: "must be finite and > 0",
        });
    }
    if let Some(p) = spec.probe {
        for (field, value) in [
            ("probe.static_m", p.static_m),
            ("probe.static_across_m", p.static_across_m),
            ("probe.c_ry_m_s2", p.c_ry_m_s2),
            ("probe.c_r_m_s2", p.c_r_m_s2),
            ("probe.c_r_u_m_s2", p.c_r_u_m_s2),
        ] {
            if !value.is_finite() {
                return Err(MountingsError::Invalid {
                    field: field.to_owned(),
                    value,
                    reason: "must be finite",
                });
            }
        }
    }
    let weighted = data.iter().filter(|d| d.sigma.is_some()).count();
    if weighted != 0 && weighted != data.len() {
        let d = data.iter().find(|d| d.sigma.is_none()).unwrap_or(&data[0]);
        return Err(MountingsError::Invalid {
            field: format!("{}.sigma", d.field),
            value: f64::NAN,
            reason: "a weighted fit needs the outputs' σ in every mounting",
        });
    }
    for d in data {
        d.mounting
            .validate()
            .map_err(|source| MountingsError::Mounting {
                field: d.field.clone(),
                source,
            })?;
        let n = d.rates_rad_s.len();
        if d.outputs.len() != n {
            return Err(MountingsError::Length {
                field: format!("{}.outputs", d.field),
                got: d.outputs.len(),
                expected: n,
            });
        }
        if let Some(s) = d.sigma
            && s.len() != n
        {
            return Err(MountingsError::Length {
                field: format!("{}.sigma", d.field),
                got: s.len(),
                expected: n,
            });
        }
        for i in 0..n {
            let w = d.rates_rad_s[i];
            if !(w.is_finite() && w > 0.0) {
                return Err(MountingsError::Invalid {
                    field: format!("{}.rates[{i}]", d.field),
                    value: w,
                    reason: "a rate must be finite and > 0",
                });
            }
            if !d.outputs[i].is_finite() {
                return Err(MountingsError::Invalid {
                    field: format!("{}.outputs[{i}]", d.field),
                    value: d.outputs[i],
                    reason: "an output must be finite",
                });
            }
            if let Some(s) = d.sigma
                && !(s[i].is_finite() && s[i] > 0.0)
            {
                return Err(MountingsError::Invalid {
                    field: format!("{}.sigma[{i}]", d.field),
                    value: s[i],
                    reason: "a σ must be finite and > 0",
                });
            }
        }
    }
    Ok(())
}
