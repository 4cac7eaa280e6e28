//! What a simulation produces, in memory: the probe recordings, the PIGA's table and raw
//! recordings, each mounting's, and the truth they were drawn from.

use serde::{Deserialize, Serialize};

use accel_model::PigaCoefficients;
use kinematics::{ErrorMotion, SpindleOffsets};

use crate::mounting::Orientation;
use crate::scenario::Scenario;

/// Everything a scenario produces, in memory.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Simulation {
    /// One probe recording per rate, in the scenario's order.
    pub recordings: Vec<SimulatedRecording>,
    /// The second probe's recordings (`probe2_<rate>deg_s.csv`), one per rate, when the
    /// scenario has a second probe; else empty.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub second_recordings: Vec<SimulatedRecording>,
    /// The PIGA calibration table (`piga.csv`), one row per rate.
    pub piga: Vec<PigaRow>,
    /// The raw PIGA output recordings (`piga_<rate>deg_s.csv`), one per rate, when the
    /// scenario asks for them (`piga.recordings`); else empty.
    pub piga_recordings: Vec<SimulatedPigaRecording>,
    /// The further mountings' tables and recordings, in the scenario's order (empty without
    /// `mountings`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub mountings: Vec<SimulatedMounting>,
    /// Every parameter and the exact per-rate quantities (`truth.json`).
    pub truth: Truth,
}

/// One further mounting's PIGA data: `piga_ia_in.csv` or `piga_ia_out.csv` and, when asked
/// for, its raw output recordings `piga_ia_out_<rate>deg_s.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SimulatedMounting {
    /// IA in or out.
    pub orientation: Orientation,
    /// The mounting's static radius, m.
    pub radius_m: f64,
    /// The table's file name.
    pub file_name: String,
    /// One row per rate, in the scenario's order.
    pub piga: Vec<PigaRow>,
    /// The raw output recordings, one per rate (when `piga.recordings`); else empty.
    pub piga_recordings: Vec<SimulatedPigaRecording>,
}

/// One probe recording: the columns of `probe_<rate>deg_s.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SimulatedRecording {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// File name (`probe_010.0000deg_s.csv`).
    pub file_name: String,
    /// Sample times, s (`i / sample_rate_hz`).
    pub time_s: Vec<f64>,
    /// Probe gap, µm.
    pub gap_um: Vec<f64>,
    /// Encoder angle of the spindle from `O1X1`, deg in `[0, 360)`, when the scenario asks
    /// for it.
    pub angle_deg: Option<Vec<f64>>,
}

impl SimulatedRecording {
    /// The encoder angle in radians (for `harmonics::SpindleAngle::Encoder`).
    #[must_use]
    pub fn angle_rad(&self) -> Option<Vec<f64>> {
        self.angle_deg
            .as_ref()
            .map(|a| a.iter().map(|d| d.to_radians()).collect())
    }
}

/// One raw PIGA output recording: the columns of `piga_<rate>deg_s.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SimulatedPigaRecording {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// File name (`piga_010.0000deg_s.csv`).
    pub file_name: String,
    /// Sample times, s (the probe's).
    pub time_s: Vec<f64>,
    /// The PIGA's output angle, rad (not wrapped).
    pub output_rad: Vec<f64>,
    /// Encoder angle of the spindle from `O1X1`, deg in `[0, 360)` (the probe's), when the
    /// scenario asks for it.
    pub angle_deg: Option<Vec<f64>>,
}

/// One row of `piga.csv`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PigaRow {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// Mean PIGA output over whole revolutions plus the scenario's noise, rad/s.
    pub output_rad_s: f64,
}

/// The truth behind a simulation (`truth.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Truth {
    /// The scenario as given.
    pub scenario: Scenario,
    /// The error-motion coefficients it stands for (resolved from a physical imbalance if the
    /// scenario gives one).
    pub error_motion: ErrorMotion,
    /// Lever ratio `(h_probe + h_piga)/h_probe` of the probe geometry.
    pub lever_ratio: f64,
    /// `C_r`, m·s² (from `error_motion`).
    pub c_r_m_s2: f64,
    /// The pseudo-second-order error the scenario should produce, `Δk2 = k1·C_r·g/R²`
    /// (eq. 19), rad/(s·g²).
    pub delta_k2_predicted_rad_s_g2: f64,
    /// `k2 + Δk2`: the apparent k2 an uncompensated eq. 18 fit should return, rad/(s·g²).
    pub k2_apparent_predicted_rad_s_g2: f64,
    /// Per-rate truth, in the scenario's order.
    pub rates: Vec<TruthRate>,
    /// The total dynamic radius growth at the PIGA, spindle plus arm (present when the
    /// scenario has an arm stretch or further mountings).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_growth: Option<RadiusGrowthTruth>,
    /// The further mountings (issue 20), in the scenario's order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub mountings: Vec<MountingTruth>,
}

/// The dynamic radius growth at the PIGA: `C = C_r + C_a`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RadiusGrowthTruth {
    /// `C_r`: the spindle's radial drift per ω² along `X2`, m·s² (what the probe measures).
    pub c_r_m_s2: f64,
    /// `C_a`: the arm's stretch per ω², m·s² (unseen by the probe).
    pub c_a_m_s2: f64,
    /// `C = C_r + C_a`, m·s².
    pub c_m_s2: f64,
    /// `Δk2,total = k1·C·g/R²` at the centrifuge's radius, rad/(s·g²).
    pub delta_k2_total_predicted_rad_s_g2: f64,
}

/// The truth of one further mounting.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MountingTruth {
    /// IA in or out.
    pub orientation: Orientation,
    /// `s`: +1 for IA in, −1 for IA out.
    pub sign: f64,
    /// Static radius `R_s`, m.
    pub radius_m: f64,
    /// The PIGA's coefficients in this mounting (k0 with the mounting's bias shift).
    pub coefficients: PigaCoefficients,
    /// `Δk2,total = k1·C·g/R_s²` at this mounting's radius, rad/(s·g²).
    pub delta_k2_total_predicted_rad_s_g2: f64,
    /// The table's file name.
    pub table: String,
    /// Per-rate truth, in the scenario's order.
    pub rates: Vec<MountingRateTruth>,
}

/// The exact quantities of one mounting at one rate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MountingRateTruth {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// Nominal input magnitude `a_s = R_s·ω²/g`, g.
    pub a_nominal_g: f64,
    /// Exact mean specific force along the input axis over a revolution, g (negative for IA
    /// out).
    pub a_x_g: f64,
    /// Exact mean angular rate about the input axis over a revolution, rad/s.
    pub omega_i_rad_s: f64,
    /// Mean PIGA output over a revolution without noise, rad/s.
    pub output_noise_free_rad_s: f64,
    /// The output written to the table (noise included), rad/s.
    pub output_rad_s: f64,
    /// The raw output recording's file name, when the scenario asks for one.
    pub piga_recording: Option<String>,
}

/// The exact quantities at one rate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TruthRate {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// Spindle rate, rad/s.
    pub rate_rad_s: f64,
    /// Nominal input `a = Rω²/g`, g.
    pub a_nominal_g: f64,
    /// Exact mean specific force along the input axis over a revolution, g (eq. 12).
    pub a_x_g: f64,
    /// Exact mean angular rate about the input axis over a revolution, rad/s (eq. 13).
    pub omega_i_rad_s: f64,
    /// Mean PIGA output over a revolution without noise, rad/s (eq. 15).
    pub output_noise_free_rad_s: f64,
    /// The output written to `piga.csv` (noise included), rad/s; also the mean slope of the
    /// raw output recording.
    pub output_rad_s: f64,
    /// The raw output recording's file name, when the scenario asks for one.
    pub piga_recording: Option<String>,
    /// Drift and tilt of the spindle at this rate in `O2` (eq. 5).
    pub offsets: SpindleOffsets,
    /// Radius error at the PIGA plane, `Δr_x = Δr_xs + C_r ω²`, µm.
    pub radius_error_um: f64,
    /// The first harmonic the probe sees (eq. 21), without noise.
    pub probe_first_harmonic: ProbeTruth,
    /// The first harmonic the second probe sees, without noise (with a second probe).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub second_probe_first_harmonic: Option<ProbeTruth>,
    /// The recording's file name.
    pub recording: String,
    /// Whole revolutions in the recording.
    pub revolutions: usize,
    /// Number of samples in the recording.
    pub samples: usize,
    /// Standard deviation that the probe noise gives the radius error fitted from this
    /// recording, µm: `ratio·σ·√(2/N)` for N samples spread evenly over whole revolutions
    /// (the variance of a least-squares Fourier coefficient). Recordings of fixed
    /// revolutions have N ∝ 1/ω, so their radius errors are not equally precise.
    pub radius_error_sigma_um: f64,
}

/// The exact first harmonic of the probe gap at one rate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ProbeTruth {
    /// `d_c1`, µm.
    pub dc1_um: f64,
    /// `d_s1`, µm.
    pub ds1_um: f64,
    /// `ΔR1 = hypot(d_c1, d_s1)`, µm.
    pub amplitude_um: f64,
    /// Azimuth β of the drift from `X2`, deg (eq. 7).
    pub beta_deg: f64,
}
