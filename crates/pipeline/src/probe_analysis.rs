//! A phase given as probe recordings: each file is loaded, fitted per revolution (eq. 20) and
//! reduced to its mean first harmonic with its standard error (eq. 21), ready for the
//! geometry of eq. 22.

use std::f64::consts::TAU;
use std::path::{Path, PathBuf};

use harmonics::{Coefficients, FitConfig};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::{PipelineError, Result};
use recording::{Recording, RecordingFormat, analyze_recording, load_recording};
use units::deg_s_to_rad_s;

/// Probe recordings of one phase, one file per rate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordingSet {
    /// Layout of the files (columns, units, delimiter); defaults to `time_s,gap_um[,angle_deg]`.
    #[serde(default)]
    pub format: RecordingFormat,
    /// Settings of the per-revolution fit (order 4 by default, as in the paper).
    #[serde(default)]
    pub fit: FitConfig,
    /// Angle of each recording's first sample from O1X1, deg, used when a file has no encoder
    /// column (default 0).
    #[serde(default)]
    pub start_angle_deg: f64,
    /// The recordings.
    pub files: Vec<RecordingPoint>,
}

/// One recording and the rate it was taken at.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordingPoint {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// The CSV file, relative to the configuration file's folder unless absolute.
    pub file: PathBuf,
}

/// What a study reports of progress, for a command line to show.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Progress<'a> {
    /// The number of recordings the study will analyse.
    Recordings {
        /// How many.
        total: usize,
    },
    /// One recording has been analysed.
    RecordingDone {
        /// The file.
        path: &'a Path,
        /// Its number of samples.
        samples: usize,
    },
}

/// The first harmonic of one recording, in µm, with what it rests on.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ProbeHarmonic {
    pub(crate) dc1_um: f64,
    pub(crate) ds1_um: f64,
    pub(crate) dc1_sigma_um: Option<f64>,
    pub(crate) ds1_sigma_um: Option<f64>,
    pub(crate) revolutions: usize,
    pub(crate) residual_rms_um: f64,
    /// Standard error of `dc1_um` from the fit residuals (white noise), µm.
    pub(crate) dc1_noise_sigma_um: f64,
    pub(crate) trace: ProbeTrace,
}

/// One revolution of a recording and the fitted eq. 20 curve: the paper's Fig. 4.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ProbeTrace {
    /// Rate, deg/s.
    pub rate_deg_s: f64,
    /// Spindle angle of each shown sample, deg in [0, 360).
    pub angle_deg: Vec<f64>,
    /// Gap of each shown sample, µm.
    pub gap_um: Vec<f64>,
    /// Mean fitted coefficients over the revolutions used, µm.
    pub fit_um: Option<Coefficients>,
}

/// Most samples drawn per trace (the revolution is decimated evenly beyond this).
const MAX_TRACE_POINTS: usize = 1500;

/// The folder that relative recording paths are resolved against.
fn base_dir(config_path: &Path) -> &Path {
    config_path.parent().unwrap_or_else(|| Path::new("."))
}

/// Analyses every recording of a phase, in parallel, in the configuration's order.
pub(crate) fn analyse(
    set: &RecordingSet,
    section: &str,
    config_path: &Path,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<Vec<ProbeHarmonic>> {
    let base = base_dir(config_path);
    set.files
        .par_iter()
        .enumerate()
        .map(|(i, point)| {
            let file = base.join(&point.file);
            let recording_error = |source| PipelineError::Recording {
                path: config_path.to_owned(),
                field: format!("{section}.points.files[{i}]"),
                source: Box::new(source),
            };
            let recording = load_recording(&file, &set.format).map_err(recording_error)?;
            let rate_rad_s = deg_s_to_rad_s(point.rate_deg_s);
            let start_angle_rad = set.start_angle_deg.to_radians();
            let analysis = analyze_recording(&recording, rate_rad_s, start_angle_rad, &set.fit)
                .map_err(recording_error)?;
            progress(Progress::RecordingDone {
                path: &file,
                samples: recording.len(),
            });
            let um = recording.gap_unit.um_per_unit();
            let revs = &analysis.revolutions;
            let samples: usize = revs.iter().map(|r| r.samples).sum();
            // Pooled residual variance s² of the per-revolution fits.
            let pooled = revs
                .iter()
                .map(|r| r.residual_rms * r.residual_rms * r.samples as f64)
                .sum::<f64>()
                / samples as f64;
            // White-noise standard error of the mean first-harmonic coefficient: each
            // revolution's d_c1 has variance ≈ 2s²/nᵣ, and K revolutions are averaged.
            let k = revs.len() as f64;
            let noise_sigma = revs
                .iter()
                .map(|r| 2.0 * pooled / r.samples as f64)
                .sum::<f64>()
                .sqrt()
                / k;
            let mean_um = analysis.mean.scaled(um);
            Ok(ProbeHarmonic {
                dc1_um: mean_um.c[0],
                ds1_um: mean_um.s[0],
                dc1_sigma_um: analysis.std_error.as_ref().map(|e| e.c[0] * um),
                ds1_sigma_um: analysis.std_error.as_ref().map(|e| e.s[0] * um),
                revolutions: analysis.revolutions_used(),
                residual_rms_um: pooled.sqrt() * um,
                dc1_noise_sigma_um: noise_sigma * um,
                trace: trace(
                    &recording,
                    point.rate_deg_s,
                    rate_rad_s,
                    start_angle_rad,
                    analysis
                        .revolutions
                        .first()
                        .map(|r| (r.first_sample, r.samples)),
                    mean_um,
                ),
            })
        })
        .collect()
}

/// The first fitted revolution's samples, decimated, against the absolute spindle angle.
fn trace(
    recording: &Recording,
    rate_deg_s: f64,
    rate_rad_s: f64,
    start_angle_rad: f64,
    revolution: Option<(usize, usize)>,
    fit_um: Coefficients,
) -> ProbeTrace {
    let Some((first, count)) = revolution else {
        return ProbeTrace::default();
    };
    let step = count.div_ceil(MAX_TRACE_POINTS).max(1);
    let um = recording.gap_unit.um_per_unit();
    let t0 = recording.time_s[0];
    let (angle_deg, gap_um) = (first..first + count)
        .step_by(step)
        .map(|i| {
            let theta = match &recording.angle_rad {
                Some(a) => a[i],
                None => rate_rad_s * (recording.time_s[i] - t0) + start_angle_rad,
            };
            (theta.rem_euclid(TAU).to_degrees(), recording.gap[i] * um)
        })
        .unzip();
    ProbeTrace {
        rate_deg_s,
        angle_deg,
        gap_um,
        fit_um: Some(fit_um),
    }
}
