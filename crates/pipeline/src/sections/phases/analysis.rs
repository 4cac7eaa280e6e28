//! A phase given as probe recordings: each recording is fitted per revolution (eq. 20) and
//! reduced to its mean first harmonic with its standard error (eq. 21), ready for the
//! geometry of eq. 22.

use std::f64::consts::TAU;
use std::path::Path;

use harmonics::Coefficients;
use rayon::prelude::*;
use recording::{AngleSourceKind, Recording, analyze_recording};
use units::deg_s_to_rad_s;

use super::validate::RecordingPhase;
use crate::error::{PipelineError, Result};
use crate::results::{ProbeTrace, Warning};

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
    /// The rate for the radius-error fit, rad/s (measured when the angle is measured).
    pub(crate) rate_rad_s: f64,
    pub(crate) measured_rate_rad_s: Option<f64>,
    pub(crate) angle_source: AngleSourceKind,
    pub(crate) dropped_revolutions: usize,
    /// The recording's diagnostics, as warnings naming the field and the file.
    pub(crate) warnings: Vec<Warning>,
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
            let declared_rad_s = deg_s_to_rad_s(point.rate_deg_s);
            let result =
                analyze_recording(recording, declared_rad_s, &set.fit).map_err(recording_error)?;
            progress(Progress::RecordingDone {
                path: file,
                samples: recording.len(),
            });
            let um = recording.gap_unit.um_per_unit();
            let analysis = &result.analysis;
            let mean_um = analysis.mean.scaled(um);
            let location = format!("{section}.points.files[{i}] ({})", file.display());
            Ok(ProbeHarmonic {
                dc1_um: mean_um.c[0],
                ds1_um: mean_um.s[0],
                dc1_sigma_um: analysis.std_error.as_ref().map(|e| e.c[0] * um),
                ds1_sigma_um: analysis.std_error.as_ref().map(|e| e.s[0] * um),
                revolutions: analysis.revolutions_used(),
                residual_rms_um: result.residual_rms * um,
                dc1_noise_sigma_um: result.mean_noise_sigma[0] * um,
                rate_rad_s: result.rate_rad_s(),
                measured_rate_rad_s: result.measured_rate_rad_s,
                angle_source: result.angle_source,
                dropped_revolutions: result.dropped_revolutions,
                warnings: result
                    .diagnostics
                    .iter()
                    .map(|d| Warning::recording(d, location.clone()))
                    .collect(),
                trace: trace(
                    recording,
                    point.rate_deg_s,
                    declared_rad_s,
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
                None => rate_rad_s * (recording.time_s[i] - t0) + recording.start_angle_rad,
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
