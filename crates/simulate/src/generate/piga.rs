//! The PIGA's outputs: its calibration table (eq. 15 averaged over whole revolutions, plus
//! noise), a mounting's table, and the raw output recording sampled with the probe's.

use accel_model::{PigaCoefficients, RatePoint, rate_points};
use kinematics::Centrifuge;
use rand_distr::Distribution;

use super::noise::{
    MOUNTING_RECORDING_STREAM, MOUNTING_STREAM, OutputNoise, normal, orientation_index, stream,
};
use super::simulation::{PigaRow, SimulatedPigaRecording, SimulatedRecording};
use crate::error::SimulateError;
use crate::mounting::{Mount, Orientation, mounted_rate_point};
use crate::scenario::PigaRecordingSpec;

/// The raw PIGA output recording at one rate, sampled with the probe's recording: the
/// output angle `ω̄_out·t + A·sin(θ + φ) + e` with `θ` the spindle angle of each sample (the
/// encoder's when the probe records one; the same formula of time otherwise).
pub(super) fn record_piga(
    seed: u64,
    purpose: u64,
    spec: &PigaRecordingSpec,
    probe: &SimulatedRecording,
    output_rad_s: f64,
    file_name: String,
) -> SimulatedPigaRecording {
    let mut rng = stream(seed, purpose, probe.rate_deg_s.to_bits());
    let noise = normal(spec.angle_noise_rad);
    let phase = spec.ripple_phase_deg.to_radians();
    let rate_rad_s = probe.rate_deg_s.to_radians();
    let output_rad = probe
        .time_s
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let theta = probe
                .angle_deg
                .as_ref()
                .map_or(rate_rad_s * t, |a| a[i].to_radians());
            let e = noise.as_ref().map_or(0.0, |d| d.sample(&mut rng));
            output_rad_s * t + spec.ripple_rad * (theta + phase).sin() + e
        })
        .collect();
    SimulatedPigaRecording {
        rate_deg_s: probe.rate_deg_s,
        file_name,
        time_s: probe.time_s.clone(),
        output_rad,
        angle_deg: probe.angle_deg.clone(),
    }
}

/// The mean outputs of a mounting at each rate ([`mounted_rate_point`]).
pub(super) fn mounted_points(
    centrifuge: &Centrifuge,
    piga: &PigaCoefficients,
    mount: &Mount,
    rates_rad_s: &[f64],
) -> std::result::Result<Vec<RatePoint>, accel_model::AccelModelError> {
    if rates_rad_s.is_empty() {
        return Err(accel_model::AccelModelError::NoRates);
    }
    rates_rad_s
        .iter()
        .enumerate()
        .map(|(index, &w)| {
            if !w.is_finite() {
                return Err(accel_model::AccelModelError::NonFiniteRate { index, value: w });
            }
            mounted_rate_point(centrifuge, piga, mount, w)
        })
        .collect()
}

/// A PIGA calibration table in one mounting (issue 20): at each rate, eq. 15 averaged over
/// whole revolutions of the exact chain with the mounting's orientation, radius, arm stretch
/// and bias shift ([`mounted_rate_point`]), plus the output noise from the orientation's own
/// stream (the tables of the two orientations have independent noise; the IA-in stream is
/// not [`piga_table`]'s). The centrifuge's `radius_m` is not used.
///
/// # Errors
/// The PIGA model's error for an input it refuses (a non-finite rate, coefficient or
/// mounting field; no rates).
pub fn piga_table_mounted(
    centrifuge: &Centrifuge,
    piga: &PigaCoefficients,
    mount: &Mount,
    rates_deg_s: &[f64],
    noise: &OutputNoise,
) -> std::result::Result<Vec<PigaRow>, accel_model::AccelModelError> {
    let rates_rad_s: Vec<f64> = rates_deg_s.iter().map(|d| d.to_radians()).collect();
    let points = mounted_points(centrifuge, piga, mount, &rates_rad_s)?;
    let purpose = MOUNTING_STREAM[orientation_index(mount.orientation)];
    Ok(points
        .iter()
        .zip(rates_deg_s)
        .map(|(point, &rate_deg_s)| PigaRow {
            rate_deg_s,
            output_rad_s: noise.added_to_stream(purpose, point.output_rad_s, rate_deg_s),
        })
        .collect())
}

/// A raw PIGA output recording in one mounting at one rate, on its own (no probe
/// recording): `revolutions` whole spindle revolutions sampled evenly at about
/// `sample_rate_hz` (the last sample at exactly the end of the last revolution), the output
/// angle `ω̄_out·t + e` with `ω̄_out` the mounting's exact mean output
/// ([`mounted_rate_point`]) and white angle noise `e` of σ `angle_noise_rad` from the
/// mounting's recording stream keyed by `seed`; no ripple, no encoder column (the study takes
/// the spindle angle from the declared rate). For checking a plan's points through the
/// study's reduction (`recording::reduce_piga_recording`).
///
/// # Errors
/// [`SimulateError::InvalidField`] for a rate or sample rate that is not finite and
/// positive, a negative or non-finite noise, or no revolution;
/// [`SimulateError::AccelModel`] for a mounting or PIGA the model refuses. Both name the
/// recording's file name as the path.
#[allow(clippy::too_many_arguments)]
pub fn mounted_piga_recording(
    centrifuge: &Centrifuge,
    piga: &PigaCoefficients,
    mount: &Mount,
    rate_deg_s: f64,
    revolutions: u32,
    sample_rate_hz: f64,
    angle_noise_rad: f64,
    seed: u64,
) -> crate::Result<SimulatedPigaRecording> {
    let file_name = mounting_recording_file_name(mount.orientation, rate_deg_s);
    for (field, value, ok, reason) in [
        (
            "rate_deg_s",
            rate_deg_s,
            rate_deg_s > 0.0,
            "must be finite and > 0",
        ),
        (
            "sample_rate_hz",
            sample_rate_hz,
            sample_rate_hz > 0.0,
            "must be finite and > 0",
        ),
        (
            "angle_noise_rad",
            angle_noise_rad,
            angle_noise_rad >= 0.0,
            "must be finite and ≥ 0",
        ),
        (
            "revolutions",
            f64::from(revolutions),
            revolutions > 0,
            "must be ≥ 1",
        ),
    ] {
        if !(ok && value.is_finite()) {
            return Err(SimulateError::InvalidField {
                path: file_name.clone().into(),
                field: field.to_owned(),
                value,
                reason,
            });
        }
    }
    let w = rate_deg_s.to_radians();
    let point = mounted_rate_point(centrifuge, piga, mount, w).map_err(|source| {
        SimulateError::AccelModel {
            path: file_name.clone().into(),
            field: "piga".to_owned(),
            source,
        }
    })?;
    let duration_s = f64::from(revolutions) * std::f64::consts::TAU / w;
    let intervals = (duration_s * sample_rate_hz).round().max(1.0) as usize;
    let purpose = MOUNTING_RECORDING_STREAM[orientation_index(mount.orientation)];
    let mut rng = stream(seed, purpose, rate_deg_s.to_bits());
    let noise = normal(angle_noise_rad);
    let time_s: Vec<f64> = (0..=intervals)
        .map(|i| duration_s * i as f64 / intervals as f64)
        .collect();
    let output_rad = time_s
        .iter()
        .map(|&t| point.output_rad_s * t + noise.as_ref().map_or(0.0, |d| d.sample(&mut rng)))
        .collect();
    Ok(SimulatedPigaRecording {
        rate_deg_s,
        file_name,
        time_s,
        output_rad,
        angle_deg: None,
    })
}

/// File name of a mounting's raw PIGA output recording at a rate:
/// `piga_ia_out_<rate>deg_s.csv`.
///
/// ```
/// use simulate::{Orientation, mounting_recording_file_name};
/// assert_eq!(mounting_recording_file_name(Orientation::IaOut, 20.0), "piga_ia_out_020.0000deg_s.csv");
/// ```
#[must_use]
pub fn mounting_recording_file_name(orientation: Orientation, rate_deg_s: f64) -> String {
    format!("piga_{}_{rate_deg_s:08.4}deg_s.csv", orientation.tag())
}

/// A PIGA calibration table: at each rate, eq. 15 averaged over whole revolutions of the
/// exact chain (`accel_model::rate_points`) plus the output noise. The same rows
/// [`simulate`](fn@crate::simulate) writes to `piga.csv`.
///
/// # Errors
/// The PIGA model's error for an input it refuses (a non-finite rate or coefficient).
pub fn piga_table(
    centrifuge: &Centrifuge,
    piga: &PigaCoefficients,
    rates_deg_s: &[f64],
    noise: &OutputNoise,
) -> std::result::Result<Vec<PigaRow>, accel_model::AccelModelError> {
    let rates_rad_s: Vec<f64> = rates_deg_s.iter().map(|d| d.to_radians()).collect();
    let points = rate_points(centrifuge, piga, &rates_rad_s)?;
    Ok(points
        .iter()
        .zip(rates_deg_s)
        .map(|(point, &rate_deg_s)| PigaRow {
            rate_deg_s,
            output_rad_s: noise.added_to(point.output_rad_s, rate_deg_s),
        })
        .collect())
}
