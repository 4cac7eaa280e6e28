//! The PIGA's outputs: its calibration table (eq. 15 averaged over whole revolutions, plus
//! noise), a mounting's table, and the raw output recording sampled with the probe's.

use accel_model::{PigaCoefficients, RatePoint, rate_points};
use kinematics::Centrifuge;
use rand_distr::Distribution;

use super::noise::{MOUNTING_STREAM, OutputNoise, normal, orientation_index, stream};
use super::simulation::{PigaRow, SimulatedPigaRecording, SimulatedRecording};
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
