//! A phase given as probe recordings: each recording is fitted per revolution (eq. 20) and
//! reduced to its mean first harmonic with its standard error (eq. 21), ready for the
//! geometry of eq. 22.

use std::f64::consts::TAU;
use std::path::Path;

use harmonics::Coefficients;
use rayon::prelude::*;
use recording::{Recording, analyze_recording};
use units::deg_s_to_rad_s;

use crate::error::{PipelineError, Result};
use crate::inputs::RecordingPhase;
use crate::results::ProbeTrace;

/// What a study reports of progress, for a command line to show.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Progress<'a> {
    /// The number of recordings the study will analyze.
    Recordings {
        /// How many.
        total: usize,
    },
    /// One recording has been analyzed.
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

/// Most samples drawn per trace (the revolution is decimated evenly beyond this).
const MAX_TRACE_POINTS: usize = 1500;

/// Analyzes every recording of a phase, in parallel; every failure is reported, in the
/// configuration's order.
pub(crate) fn analyze(
    set: &RecordingPhase,
    section: &str,
    config_path: &Path,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<Vec<ProbeHarmonic>> {
    let results: Vec<Result<ProbeHarmonic>> = set
        .files
        .par_iter()
        .enumerate()
        .map(|(i, point)| {
            let recording_error = |source| PipelineError::Recording {
                path: config_path.to_owned(),
                field: format!("{section}.points.files[{i}]"),
                source: Box::new(source),
            };
            let recording = &point.recording;
            let file = &point.file;
            let rate_rad_s = deg_s_to_rad_s(point.rate_deg_s);
            let start_angle_rad = set.start_angle_rad;
            let analysis = analyze_recording(recording, rate_rad_s, start_angle_rad, &set.fit)
                .map_err(recording_error)?;
            progress(Progress::RecordingDone {
                path: file,
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
                    recording,
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
        .collect();
    let mut harmonics = Vec::with_capacity(results.len());
    let mut errors = Vec::new();
    for result in results {
        match result {
            Ok(h) => harmonics.push(h),
            Err(e) => errors.push(e),
        }
    }
    PipelineError::from_list(errors)?;
    Ok(harmonics)
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
