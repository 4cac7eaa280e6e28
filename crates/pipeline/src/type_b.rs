//! The `uncertainty` section's Type B inputs, validated once for every section that carries
//! them (the calibration and the two-orientation calibration): every input stated — its
//! standard uncertainty, or 0 with the reason in `zero_reasons` — each finite and ≥ 0, the
//! probe gain stated once (here or by the compared phase's recordings in volts). Core: used by
//! sections, importing none.

use crate::config::{StudyConfig, UncertaintyConfig};
use crate::error::{PipelineError, Result};
use crate::inputs::Check;

/// Type B standard uncertainties, validated (all finite and ≥ 0), and where g comes from.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct TypeB {
    pub(crate) values: ::calibration::TypeB,
    pub(crate) g_source: String,
    /// What the budget says beside an input (by its index in `calibration::input`): the
    /// reason for a zero, or where the probe gain's uncertainty comes from.
    pub(crate) notes: Vec<(usize, String)>,
    /// Whether the study has an `uncertainty` section (else only the recordings' stated
    /// probe gain).
    pub(crate) from_section: bool,
}

/// The Type B uncertainties of the `uncertainty` section `u` (absent: none given) and the
/// probe gain stated by the compensating phase's recordings in volts (`stated_gain`: its
/// relative u and the field stating it): every input stated, each finite and ≥ 0, a zero
/// with its reason, the probe gain stated once. `None` when neither states anything. Every
/// problem at once.
pub(crate) fn type_b(
    check: &Check<'_>,
    u: Option<&UncertaintyConfig>,
    stated_gain: Option<(f64, String)>,
) -> Result<Option<TypeB>> {
    use ::calibration::input;
    let Some(u) = u else {
        // Only the recordings state something: the probe gain.
        return Ok(stated_gain.map(|(gain, field)| TypeB {
            values: ::calibration::TypeB {
                probe_gain_u_relative: gain,
                ..::calibration::TypeB::default()
            },
            g_source: String::new(),
            notes: vec![(
                input::PROBE_GAIN,
                format!("from the probe's stated sensitivity ({field})"),
            )],
            from_section: false,
        }));
    };
    let mut errors = Vec::new();
    let mut notes = Vec::new();
    let mut values = [0.0; 6];
    let fields = [
        ("radius_u_m", u.radius_u_m, input::RADIUS),
        ("g_u_m_s2", u.g_u_m_s2, input::G),
        ("rate_u_relative", u.rate_u_relative, input::RATE_SCALE),
        (
            "pivot_to_probe_u_mm",
            u.pivot_to_probe_u_mm,
            input::PIVOT_TO_PROBE,
        ),
        (
            "probe_to_piga_u_mm",
            u.probe_to_piga_u_mm,
            input::PROBE_TO_PIGA,
        ),
        (
            "probe_gain_u_relative",
            u.probe_gain_u_relative,
            input::PROBE_GAIN,
        ),
    ];
    for (slot, (name, value, index)) in fields.into_iter().enumerate() {
        let field = format!("uncertainty.{name}");
        if index == input::PROBE_GAIN
            && let Some((gain, stated)) = &stated_gain
        {
            if value.is_some() {
                errors.push(PipelineError::StatedTwice {
                    path: check.path.to_owned(),
                    field: field.clone(),
                    other: stated.clone(),
                    what: "the probe gain's uncertainty",
                });
            }
            values[slot] = *gain;
            notes.push((
                index,
                format!("from the probe's stated sensitivity ({stated})"),
            ));
            continue;
        }
        let Some(v) = value else {
            errors.push(PipelineError::MissingField {
                path: check.path.to_owned(),
                field,
                hint: "every Type B input of the budget is stated: its standard uncertainty, or 0 \
                       with the reason in `zero_reasons`"
                    .to_owned(),
            });
            continue;
        };
        if let Err(e) = check.non_negative(&field, v) {
            errors.push(e);
            continue;
        }
        values[slot] = v;
        if v == 0.0 {
            match u.zero_reasons.get(name).filter(|r| !r.trim().is_empty()) {
                Some(reason) => notes.push((index, format!("taken as 0: {reason}"))),
                None => errors.push(PipelineError::MissingField {
                    path: check.path.to_owned(),
                    field: format!("uncertainty.zero_reasons.{name}"),
                    hint: format!(
                        "`{field}` is 0: say why it is negligible (`zero_reasons: {{\"{name}\": \"…\"}}`)"
                    ),
                }),
            }
        }
    }
    for key in u.zero_reasons.keys() {
        if !fields.iter().any(|(name, ..)| name == key) {
            errors.push(PipelineError::UnknownKey {
                path: check.path.to_owned(),
                field: "uncertainty.zero_reasons".to_owned(),
                key: key.clone(),
                known: fields.iter().map(|(n, ..)| (*n).to_owned()).collect(),
            });
        }
    }
    PipelineError::from_list(errors)?;
    Ok(Some(TypeB {
        values: ::calibration::TypeB {
            radius_u_m: values[0],
            g_u_m_s2: values[1],
            rate_u_relative: values[2],
            pivot_to_probe_u_mm: values[3],
            probe_to_piga_u_mm: values[4],
            probe_gain_u_relative: values[5],
            // the two-orientation section states it (its own latitude and spin)
            axial_earth_rate: ::calibration::AxialEarthRate::default(),
        },
        g_source: u.g_source.clone(),
        notes,
        from_section: true,
    }))
}

/// The Type B uncertainties of `config` that are as large as the quantity they are the
/// uncertainty of (u(R) ≥ R, u(g) ≥ g, a relative u ≥ 1, u of the pivot-to-probe height ≥ that
/// height): a unit slip or a typing error, never a plausible statement. Every one at once.
pub(crate) fn implausible(check: &Check<'_>, config: &StudyConfig) -> Vec<PipelineError> {
    let Some(u) = &config.uncertainty else {
        return Vec::new();
    };
    let mut radii: Vec<(String, f64)> = config
        .radius_m
        .map(|r| ("radius_m".to_owned(), r))
        .into_iter()
        .collect();
    if let Some(t) = &config.two_orientation {
        for (i, o) in t.orientations.iter().enumerate() {
            if let Some(r) = o.radius_m {
                radii.push((format!("two_orientation.orientations[{i}].radius_m"), r));
            }
        }
    }
    let smallest_radius = radii
        .iter()
        .filter(|(_, r)| r.is_finite() && *r > 0.0)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .cloned();
    let mut list = Vec::new();
    let mut one = |name: &str, value: Option<f64>, quantity: Option<(String, f64)>, unit| {
        if let (Some(v), Some((quantity_field, q))) = (value, quantity)
            && v.is_finite()
            && q.is_finite()
            && q > 0.0
            && v >= q
        {
            list.push(PipelineError::ImplausibleUncertainty {
                path: check.path.to_owned(),
                field: format!("uncertainty.{name}"),
                u: v,
                quantity_field,
                quantity: q,
                unit,
            });
        }
    };
    one("radius_u_m", u.radius_u_m, smallest_radius, "m");
    one(
        "g_u_m_s2",
        u.g_u_m_s2,
        config.g_m_s2.map(|g| ("g_m_s2".to_owned(), g)),
        "m/s²",
    );
    one(
        "rate_u_relative",
        u.rate_u_relative,
        Some(("the rate itself".to_owned(), 1.0)),
        "relative",
    );
    one(
        "probe_gain_u_relative",
        u.probe_gain_u_relative,
        Some(("the probe gain itself".to_owned(), 1.0)),
        "relative",
    );
    one(
        "pivot_to_probe_u_mm",
        u.pivot_to_probe_u_mm,
        config
            .lever
            .pivot_to_probe_mm
            .map(|h| ("lever.pivot_to_probe_mm".to_owned(), h)),
        "mm",
    );
    list
}
