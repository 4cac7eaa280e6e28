//! `--from results.json`: what identify takes from a study's results — R and g as the study
//! used them, C_r of the phase its calibration compensated with, k1 as it chose it.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use identify::{CrEstimate, Geometry};

/// What `--from results.json [--phase NAME]` takes from a study's results.
#[derive(Debug)]
pub(super) struct FromStudy {
    pub(super) results: PathBuf,
    pub(super) geometry: Geometry,
    /// k1 given (`None`: fitted, as the study's calibration chose).
    pub(super) k1_rad_s_g: Option<f64>,
    /// Where k1 comes from, in words.
    pub(super) k1_words: String,
    pub(super) c_r: CrEstimate,
    /// Whose C_r, in words.
    pub(super) c_r_words: String,
}

impl FromStudy {
    pub(super) fn read(path: &Path, phase: Option<&str>) -> anyhow::Result<Self> {
        let text = edge_io::read_text_capped(path, edge_io::CONFIG_MAX_BYTES * 4)?;
        let json: serde_json::Value = serde_json::from_str(&text)
            .with_context(|| format!("{}: not a results.json", path.display()))?;
        let number = |value: &serde_json::Value, key: &str| -> anyhow::Result<f64> {
            value
                .get(key)
                .and_then(serde_json::Value::as_f64)
                .filter(|v| v.is_finite())
                .with_context(|| format!("{}: no finite number at `{key}`", path.display()))
        };
        let inputs = json
            .get("inputs")
            .with_context(|| format!("{}: no `inputs` section", path.display()))?;
        let phases = json
            .get("phases")
            .and_then(serde_json::Value::as_array)
            .with_context(|| format!("{}: no `phases` list", path.display()))?;
        let names: Vec<&str> = phases
            .iter()
            .filter_map(|p| p.get("name").and_then(serde_json::Value::as_str))
            .collect();
        let calibration = json.get("calibration").filter(|c| c.is_object());
        // The phase the study's calibration compensated with, unless one is named.
        let (phase, phase_words) = match phase {
            Some(p) => (p.to_owned(), "named with --phase"),
            None => (
                calibration
                    .and_then(|c| c.get("compensate_with"))
                    .and_then(serde_json::Value::as_str)
                    .with_context(|| {
                        format!(
                            "{}: the study has no calibration naming the phase it compensated \
                             with: name one with --phase (the study's phases: {})",
                            path.display(),
                            names.join(", ")
                        )
                    })?
                    .to_owned(),
                "the one the study's calibration compensated with",
            ),
        };
        let found = phases
            .iter()
            .find(|p| p.get("name").and_then(serde_json::Value::as_str) == Some(phase.as_str()))
            .with_context(|| {
                format!(
                    "{}: no phase named `{phase}` (the study's phases: {})",
                    path.display(),
                    names.join(", ")
                )
            })?;
        // A phase with no σ(C_r) (an exact two-point fit) compensates with C_r taken as exact.
        let sigma = found
            .get("c_r_sigma_m_s2")
            .and_then(serde_json::Value::as_f64)
            .unwrap_or(0.0);
        // k1 as the study chose it: its calibration's (fitted or given); without a
        // calibration, the configured k1 its Δk2 used.
        let (k1_rad_s_g, k1_words) = match calibration {
            Some(cal) => match cal.get("k1_source").and_then(serde_json::Value::as_str) {
                Some("fitted") => (
                    None,
                    "fitted, as the study's calibration chose (c₂·g/R)".to_owned(),
                ),
                Some("given") => {
                    let k1 = cal
                        .get("coefficients")
                        .and_then(|c| c.get("k1"))
                        .map(|k| number(k, "value"))
                        .transpose()?
                        .with_context(|| {
                            format!("{}: no `calibration.coefficients.k1`", path.display())
                        })?;
                    (
                        Some(k1),
                        "given, as the study's calibration chose".to_owned(),
                    )
                }
                other => anyhow::bail!(
                    "{}: `calibration.k1_source` is {other:?}: expected \"fitted\" or \"given\"",
                    path.display()
                ),
            },
            None => (
                Some(number(inputs, "k1_rad_s_g")?),
                "the study's configured k1, which its Δk2 used (the study has no calibration)"
                    .to_owned(),
            ),
        };
        let g_m_s2 = match calibration {
            Some(cal) => number(cal, "g_m_s2")?,
            None => number(inputs, "g_m_s2")?,
        };
        Ok(Self {
            results: path.to_path_buf(),
            geometry: Geometry {
                radius_m: number(inputs, "radius_m")?,
                g_m_s2,
            },
            k1_rad_s_g,
            k1_words,
            c_r: CrEstimate {
                c_r_m_s2: number(found, "c_r_m_s2")?,
                c_r_sigma_m_s2: sigma,
            },
            c_r_words: format!(
                "phase `{phase}` of the study, {phase_words}; σ from its fit, without the \
                 study's Type B inputs"
            ),
        })
    }
}
