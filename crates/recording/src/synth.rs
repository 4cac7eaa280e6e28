//! Synthetic recordings with known coefficients (feature `synthetic`).

use crate::error::Result;
use crate::lab::write::{ProbeColumns, WriteOptions, write_probe_csv};

/// A synthetic probe recording with known coefficients, written in the default
/// [`RecordingFormat`](super::RecordingFormat): for fixtures, benchmarks and demonstrations (see the
/// `synth_recording` example).
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticSpec {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// Sample rate, Hz.
    pub sample_rate_hz: f64,
    /// Turns recorded (a fraction leaves an incomplete last revolution).
    pub revolutions: f64,
    /// Write the encoder-angle column.
    pub encoder: bool,
    /// Standard deviation of the gap noise, µm.
    pub noise_um: f64,
    /// Non-uniform part of the spindle angle, rad (see [`harmonics::SyntheticRecording`]).
    pub wobble_rad: f64,
    /// Angle of the first sample from O1X1, deg.
    pub start_angle_deg: f64,
    /// Seed of the noise.
    pub seed: u64,
    /// The coefficients of eq. 20, µm.
    pub coefficients: harmonics::Coefficients,
}

impl Default for SyntheticSpec {
    fn default() -> Self {
        Self {
            rate_deg_s: 120.0,
            sample_rate_hz: 500.0,
            revolutions: 2.5,
            encoder: true,
            noise_um: 0.02,
            wobble_rad: 0.05,
            start_angle_deg: 30.0,
            seed: 20_250_101,
            coefficients: harmonics::Coefficients {
                l0: 50.0,
                c: vec![-3.0, 0.4, -0.15, 0.05],
                s: vec![-1.2, 0.25, 0.1, -0.03],
                drift_per_s: None,
            },
        }
    }
}

impl SyntheticSpec {
    /// Number of samples.
    pub fn samples(&self) -> usize {
        (self.revolutions * 360.0 / self.rate_deg_s * self.sample_rate_hz).round() as usize
    }

    /// The generator of the samples.
    pub fn recording(&self) -> harmonics::SyntheticRecording {
        harmonics::SyntheticRecording {
            rate_rad_s: self.rate_deg_s.to_radians(),
            sample_rate_hz: self.sample_rate_hz,
            samples: self.samples(),
            start_time_s: 0.0,
            start_angle_rad: self.start_angle_deg.to_radians(),
            coefficients: self.coefficients.clone(),
            noise_std: self.noise_um,
            wobble_rad: self.wobble_rad,
            seed: self.seed,
        }
    }

    /// The CSV text written by [`write_probe_csv`](crate::write_probe_csv): a comment line
    /// naming the settings, `time_s,gap_um[,angle_deg]`, six decimals.
    ///
    /// # Errors
    /// [`RecordingError::NonFiniteValue`](crate::RecordingError::NonFiniteValue) if the settings give a NaN or infinite sample.
    pub fn csv(&self) -> Result<String> {
        let data = self.recording().generate();
        let angle_deg: Option<Vec<f64>> = self
            .encoder
            .then(|| data.angle_rad.iter().map(|a| a.to_degrees()).collect());
        let columns = ProbeColumns::new(&data.time_s, &data.gap, angle_deg.as_deref())?;
        let comment = format!(
            "synthetic probe recording: {} deg/s, {} Hz, {} turns, noise {} um, seed {}",
            self.rate_deg_s, self.sample_rate_hz, self.revolutions, self.noise_um, self.seed
        );
        let options = WriteOptions {
            decimals: 6,
            header_comment: Some(&comment),
        };
        let mut out = Vec::with_capacity(data.time_s.len() * 32 + 128);
        // Writing to a Vec cannot fail.
        let _ = write_probe_csv(&mut out, &columns, &options);
        // The writer writes ASCII only.
        Ok(String::from_utf8(out)
            .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned()))
    }
}

/// A long recording in the default format written row by row to `out`, never held in
/// memory: `rows` samples at 1 kHz of a spindle at 30 deg/s with an encoder column
/// (`time_s,gap_um,angle_deg`), a 3.2 µm first harmonic on a 50 µm gap with a small
/// deterministic scatter, every number exact in thousandths (integers written with three
/// decimals). For the memory bound of the streamed analysis and the example that times it
/// (37 M rows make 1 GB). `out` is flushed at the end; buffer it.
///
/// # Errors
/// `out`'s.
pub fn write_long_recording(mut out: impl std::io::Write, rows: usize) -> std::io::Result<()> {
    out.write_all(b"time_s,gap_um,angle_deg\n")?;
    for i in 0..rows {
        // Angle in thousandths of a degree, gap in thousandths of a micrometre: integers.
        let milli_deg = (i as u64 * 30) % 360_000;
        let theta = (milli_deg as f64 / 1000.0).to_radians();
        let gap = 50_000 + (3_200.0 * theta.cos()) as i64 + ((i * 7919) % 21) as i64 - 10;
        writeln!(
            out,
            "{}.{:03},{}.{:03},{}.{:03}",
            i / 1000,
            i % 1000,
            gap / 1000,
            gap % 1000,
            milli_deg / 1000,
            milli_deg % 1000
        )?;
    }
    out.flush()
}
