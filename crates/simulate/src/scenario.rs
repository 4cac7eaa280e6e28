//! The simulation scenario, read from RON and validated.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use accel_model::PigaCoefficients;
use harmonics::{FitConfig, LeverGeometry};
use kinematics::{ErrorMotion, ErrorMotionSpec, Site};
use serde::{Deserialize, Serialize};

use crate::error::{Result, SimulateError};
use crate::mounting::{Mount, Orientation};

/// Highest sleeve harmonic a scenario may add to the probe signal (the harmonic fit supports
/// orders up to 8).
pub const MAX_SLEEVE_ORDER: usize = 8;

/// Most samples all recordings of one scenario may hold together (memory guard: 2·10⁸
/// samples are about 5 GB of columns).
pub const MAX_TOTAL_SAMPLES: f64 = 2.0e8;

/// Largest magnitude of the arm stretch coefficient, m·s² (1.2 cm at 200 deg/s, far beyond
/// any arm; the first-order model of `docs/theory.md` section 11 needs it small).
const MAX_ARM_STRETCH_M_S2: f64 = 1e-3;

/// Most revolutions per rate point.
const MAX_REVOLUTIONS: usize = 10_000;

/// Largest magnitude of a probe length in a scenario (offset, noise σ, sleeve harmonic), µm:
/// a kilometre, far beyond any probe, and small enough that no sum of them overflows.
const MAX_LENGTH_UM: f64 = 1e9;

/// A closed-loop simulation scenario: a centrifuge with spindle error motion, a displacement
/// probe on its sleeve and a PIGA on its arm, run at a list of rates.
///
/// Every number carries its unit in its name. See `docs/SIMULATION.md` for the file format.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// A short name, copied into `truth.json`.
    pub name: String,
    /// Seed of the random number generator: the same seed gives the same files.
    pub seed: u64,
    /// Working radius and site.
    pub centrifuge: CentrifugeSpec,
    /// Spindle error motion: coefficients (static + `C ω²`) or a physical imbalance (eq. 1–4).
    pub error_motion: ErrorMotionSpec,
    /// The displacement probe and its recordings.
    pub probe: ProbeSpec,
    /// The PIGA's coefficients (eq. 15) and the noise on its per-rate mean output.
    pub piga: PigaSpec,
    /// Spindle rates of the calibration, deg/s (strictly positive, distinct).
    pub rates_deg_s: Vec<f64>,
    /// Whole revolutions recorded by the probe at each rate (at least; see `min_duration_s`).
    pub revolutions: usize,
    /// Shortest recording, s: a rate records more whole revolutions than `revolutions` if that
    /// is needed to last this long (default 0: exactly `revolutions` at every rate). Equal
    /// durations give every rate the same number of samples, hence first harmonics of equal
    /// variance, which is what an unweighted `C_r` fit assumes.
    #[serde(default)]
    pub min_duration_s: f64,
    /// A second displacement probe at another height (absent: one probe). With it, both
    /// probes read the spindle axis as the straight line of the chain (translation and tilt,
    /// eq. 5) at their own heights, so that two probe planes separate translation from tilt;
    /// without it, the probe keeps the cone of eq. 22.
    #[serde(default)]
    pub second_probe: Option<SecondProbeSpec>,
    /// Arm stretch `C_a`, m·s² (default 0): the radius at the PIGA grows by `C_a·ω²` beyond
    /// the spindle's own motion (the arm's elastic stretch under centrifugal load), which the
    /// probe does not see. It applies to `piga.csv` and to every mounting.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub arm_stretch_m_s2: f64,
    /// Further mountings of the PIGA (issue 20): each records the PIGA table again with its
    /// input axis in or out, at its own radius (`piga_ia_in.csv`, `piga_ia_out.csv`, and
    /// `piga_ia_out_<rate>deg_s.csv` raw recordings when `piga.recordings` asks for them).
    /// At most one per orientation. Empty (the default): `piga.csv` only.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub mountings: Vec<MountingSpec>,
}

/// One mounting of the PIGA in a two-orientation (symmetric) calibration.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MountingSpec {
    /// `ia_in` (towards the spindle axis) or `ia_out` (away from it).
    pub orientation: Orientation,
    /// Static radius of this mounting, m (PIGA centre of mass to the mean spindle axis).
    pub radius_m: f64,
    /// Added to the PIGA's k0 in this mounting, rad/s (default 0): remounting shifts the bias.
    #[serde(default)]
    pub bias_shift_rad_s: f64,
}

impl MountingSpec {
    /// The mounting as the chain needs it, with the scenario's arm stretch.
    #[must_use]
    pub const fn mount(&self, arm_stretch_m_s2: f64) -> Mount {
        Mount {
            orientation: self.orientation,
            radius_m: self.radius_m,
            arm_stretch_m_s2,
            bias_shift_rad_s: self.bias_shift_rad_s,
        }
    }

    /// The file name of this mounting's PIGA table: `piga_ia_in.csv` / `piga_ia_out.csv`.
    #[must_use]
    pub fn table_file_name(&self) -> String {
        format!("piga_{}.csv", self.orientation.tag())
    }
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// The second displacement probe: its height and direction. Sampling, noise, `l0`, sleeve
/// harmonics, encoder and speed ripple are the first probe's; its noise is an independent
/// stream. Its recordings are `probe2_<rate>deg_s.csv`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SecondProbeSpec {
    /// Height from the second probe's plane up to the PIGA plane, mm (positive below the PIGA
    /// plane, as the first probe's `probe_to_piga_mm`; it must differ from it).
    pub probe_to_piga_mm: f64,
    /// Its measuring direction (default: against `O1X1`).
    #[serde(default)]
    pub probe_direction: harmonics::ProbeDirection,
}

/// The centrifuge without its error motion (which has its own section).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CentrifugeSpec {
    /// Static working radius R (PIGA centre of mass to the mean spindle axis), m.
    pub radius_m: f64,
    /// Latitude, Earth rate and gravity.
    pub site: Site,
}

/// The displacement probe on the spindle sleeve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeSpec {
    /// Heights from the tilt pivot to the probe plane and on to the PIGA plane, and the
    /// probe's measuring direction (eq. 21–22).
    pub lever: LeverGeometry,
    /// Sampling rate, Hz.
    pub sample_rate_hz: f64,
    /// Standard deviation of the white Gaussian noise on each gap sample, µm (0: none).
    pub noise_um: f64,
    /// Mean gap `l0`, µm.
    pub l0_um: f64,
    /// Harmonics of the spindle angle from the sleeve's roundness and uneven stiffness
    /// (orders 2 to 8), added to the gap.
    #[serde(default)]
    pub sleeve_harmonics: Vec<SleeveHarmonic>,
    /// Write the spindle encoder's angle as a third column `angle_deg`.
    #[serde(default)]
    pub encoder_angle: bool,
    /// Once-per-revolution ripple of the spindle speed, so that the angle does not advance
    /// uniformly in time.
    #[serde(default)]
    pub speed_ripple: Option<SpeedRipple>,
    /// Spindle angle at the first sample, deg from `O1X1`.
    #[serde(default)]
    pub start_angle_deg: f64,
}

/// One sleeve harmonic: `c_um·cos kθ + s_um·sin kθ` with `k = order`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SleeveHarmonic {
    /// Order `k` (2 to 8).
    pub order: usize,
    /// Cosine coefficient, µm.
    pub c_um: f64,
    /// Sine coefficient, µm.
    pub s_um: f64,
}

/// Once-per-revolution speed ripple: the spindle angle is
/// `θ(t) = θ₀ + ωt + A·(sin(ωt + φ) − sin φ)`, so the instantaneous rate is
/// `ω·(1 + A cos(ωt + φ))` and every revolution still takes `2π/ω`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedRipple {
    /// Angle amplitude `A`, deg (below one radian, 57.29°, so that the angle keeps advancing).
    pub amplitude_deg: f64,
    /// Phase `φ`, deg.
    pub phase_deg: f64,
}

/// The PIGA of the simulated calibration.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PigaSpec {
    /// `k0…k3` of eq. 15.
    pub coefficients: PigaCoefficients,
    /// Standard deviation of the white Gaussian noise added to each per-rate mean output,
    /// rad/s (0: noise-free).
    #[serde(default)]
    pub noise_rad_s: f64,
    /// Raw output recordings, one per rate at the probe's sampling
    /// (`piga_<rate>deg_s.csv`), when given.
    #[serde(default)]
    pub recordings: Option<PigaRecordingSpec>,
}

/// Raw PIGA output recordings: the output angle `θ_out(t) = ω̄_out·t + A·sin(θ + φ) + e`,
/// with `ω̄_out` the rate's mean output (`piga.csv`'s value), `θ` the spindle angle, and
/// white noise `e`, sampled with the probe (same times, same encoder angle).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PigaRecordingSpec {
    /// Standard deviation of the white noise of each output-angle sample, rad.
    pub angle_noise_rad: f64,
    /// Amplitude A of a once-per-revolution term of the output angle, rad (default 0): a
    /// periodic input that whole revolutions cancel.
    #[serde(default)]
    pub ripple_rad: f64,
    /// Its phase φ, deg (default 0).
    #[serde(default)]
    pub ripple_phase_deg: f64,
}

/// A scenario read from a file (or text) and validated.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedScenario {
    /// Where it came from (named in every later error).
    pub path: PathBuf,
    /// The validated scenario.
    pub scenario: Scenario,
    /// The error motion's coefficients (resolved from a physical imbalance if need be).
    pub error_motion: ErrorMotion,
}

impl Scenario {
    /// Reads and validates a scenario file.
    ///
    /// # Errors
    /// [`SimulateError::File`] when the file cannot be read, is larger than
    /// [`edge_io::CONFIG_MAX_BYTES`] (16 MiB) or is not UTF-8 (a leading byte-order mark is
    /// ignored); otherwise as [`Scenario::parse`].
    pub fn load(path: &Path) -> Result<LoadedScenario> {
        let text = edge_io::read_text_capped(path, edge_io::CONFIG_MAX_BYTES)?;
        Self::parse(&text, path)
    }

    /// Parses and validates RON text; `path` only names the source in errors.
    ///
    /// # Errors
    /// [`SimulateError::Parse`] for malformed RON, an unknown or a missing field; otherwise as
    /// [`Scenario::check`].
    pub fn parse(text: &str, path: &Path) -> Result<LoadedScenario> {
        let scenario: Self = edge_io::from_ron(text, path).map_err(|e| SimulateError::Parse {
            line: e.line,
            column: e.column,
            message: e.code.to_string(),
            path: e.path,
        })?;
        scenario.check(path)
    }

    /// Validates a scenario built in code; `path` names it in errors.
    ///
    /// # Errors
    /// [`SimulateError::InvalidField`] naming the field (e.g. `centrifuge.radius_m`,
    /// `probe.sleeve_harmonics[1].order`) for a number outside its domain (probe lengths in
    /// µm at most 1e9 in magnitude);
    /// [`SimulateError::EmptyList`] for no rates; [`SimulateError::DuplicateRate`] for a rate
    /// given twice; [`SimulateError::RecordingNameCollision`] for two rates that would share
    /// a recording's file name; [`SimulateError::RateTooFast`] for a rate at which a
    /// revolution holds fewer samples than the order-4 harmonic fit (with drift) needs;
    /// [`SimulateError::Kinematics`] for a bad error motion; [`SimulateError::Harmonics`] for a
    /// bad lever geometry.
    pub fn check(self, path: &Path) -> Result<LoadedScenario> {
        let error_motion = self.validate(path)?;
        Ok(LoadedScenario {
            path: path.to_owned(),
            scenario: self,
            error_motion,
        })
    }

    /// Checks every field; returns the resolved error motion.
    pub(crate) fn validate(&self, path: &Path) -> Result<ErrorMotion> {
        let v = Validator { path };
        self.validate_centrifuge(&v)?;
        let error_motion =
            self.error_motion
                .resolve()
                .map_err(|source| SimulateError::Kinematics {
                    path: path.to_owned(),
                    field: "error_motion".to_owned(),
                    source,
                })?;
        self.validate_probe(&v)?;
        self.validate_piga(&v)?;
        self.validate_mountings(&v)?;
        self.validate_rates(&v)?;
        self.validate_durations(&v)?;
        Ok(error_motion)
    }

    /// The centrifuge: its radius and site.
    fn validate_centrifuge(&self, v: &Validator<'_>) -> Result<()> {
        let c = &self.centrifuge;
        v.positive("centrifuge.radius_m", c.radius_m)?;
        v.finite("centrifuge.site.latitude_deg", c.site.latitude_deg)?;
        if !(-90.0..=90.0).contains(&c.site.latitude_deg) {
            return Err(v.invalid(
                "centrifuge.site.latitude_deg",
                c.site.latitude_deg,
                "must lie in [-90, 90]",
            ));
        }
        v.finite("centrifuge.site.earth_rate_rad_s", c.site.earth_rate_rad_s)?;
        v.positive("centrifuge.site.gravity_m_s2", c.site.gravity_m_s2)?;
        Ok(())
    }

    /// The probe (its lever, sampling, noise, lengths, sleeve harmonics and speed ripple) and
    /// the second probe's plane.
    fn validate_probe(&self, v: &Validator<'_>) -> Result<()> {
        let p = &self.probe;
        p.lever
            .validate()
            .map_err(|source| SimulateError::Harmonics {
                path: v.path.to_owned(),
                field: "probe.lever".to_owned(),
                source,
            })?;
        v.positive("probe.sample_rate_hz", p.sample_rate_hz)?;
        v.non_negative("probe.noise_um", p.noise_um)?;
        v.length_um("probe.noise_um", p.noise_um)?;
        v.length_um("probe.l0_um", p.l0_um)?;
        v.finite("probe.start_angle_deg", p.start_angle_deg)?;
        for (i, h) in p.sleeve_harmonics.iter().enumerate() {
            let field = format!("probe.sleeve_harmonics[{i}]");
            if !(2..=MAX_SLEEVE_ORDER).contains(&h.order) {
                return Err(v.invalid(
                    &format!("{field}.order"),
                    h.order as f64,
                    "a sleeve harmonic's order must lie in 2..=8",
                ));
            }
            if p.sleeve_harmonics[..i].iter().any(|q| q.order == h.order) {
                return Err(v.invalid(
                    &format!("{field}.order"),
                    h.order as f64,
                    "this order appears twice",
                ));
            }
            v.length_um(&format!("{field}.c_um"), h.c_um)?;
            v.length_um(&format!("{field}.s_um"), h.s_um)?;
        }
        if let Some(q) = &self.second_probe {
            v.finite("second_probe.probe_to_piga_mm", q.probe_to_piga_mm)?;
            if q.probe_to_piga_mm == p.lever.probe_to_piga_mm {
                return Err(v.invalid(
                    "second_probe.probe_to_piga_mm",
                    q.probe_to_piga_mm,
                    "must differ from probe.lever.probe_to_piga_mm (two planes)",
                ));
            }
        }
        if let Some(r) = &p.speed_ripple {
            v.finite("probe.speed_ripple.amplitude_deg", r.amplitude_deg)?;
            if r.amplitude_deg.abs().to_radians() >= 1.0 {
                return Err(v.invalid(
                    "probe.speed_ripple.amplitude_deg",
                    r.amplitude_deg,
                    "must be below one radian (57.29°) in magnitude, so that the angle keeps advancing",
                ));
            }
            v.finite("probe.speed_ripple.phase_deg", r.phase_deg)?;
        }
        Ok(())
    }

    /// The PIGA's coefficients, noise and raw recordings.
    fn validate_piga(&self, v: &Validator<'_>) -> Result<()> {
        let k = &self.piga.coefficients;
        v.finite("piga.coefficients.k0_rad_s", k.k0_rad_s)?;
        v.finite("piga.coefficients.k1_rad_s_g", k.k1_rad_s_g)?;
        v.finite("piga.coefficients.k2_rad_s_g2", k.k2_rad_s_g2)?;
        v.finite("piga.coefficients.k3_rad_s_g3", k.k3_rad_s_g3)?;
        v.non_negative("piga.noise_rad_s", self.piga.noise_rad_s)?;
        if let Some(r) = &self.piga.recordings {
            v.non_negative("piga.recordings.angle_noise_rad", r.angle_noise_rad)?;
            v.non_negative("piga.recordings.ripple_rad", r.ripple_rad)?;
            v.finite("piga.recordings.ripple_phase_deg", r.ripple_phase_deg)?;
        }
        Ok(())
    }

    /// The arm's stretch and the mountings, one per orientation.
    fn validate_mountings(&self, v: &Validator<'_>) -> Result<()> {
        v.finite("arm_stretch_m_s2", self.arm_stretch_m_s2)?;
        if self.arm_stretch_m_s2.abs() > MAX_ARM_STRETCH_M_S2 {
            return Err(v.invalid(
                "arm_stretch_m_s2",
                self.arm_stretch_m_s2,
                "must be at most 1e-3 m·s² in magnitude (1.2 cm of stretch at 200 deg/s)",
            ));
        }
        for (i, m) in self.mountings.iter().enumerate() {
            let field = format!("mountings[{i}]");
            v.positive(&format!("{field}.radius_m"), m.radius_m)?;
            v.finite(&format!("{field}.bias_shift_rad_s"), m.bias_shift_rad_s)?;
            if self.mountings[..i]
                .iter()
                .any(|q| q.orientation == m.orientation)
            {
                return Err(v.invalid(
                    &format!("{field}.orientation"),
                    m.orientation.sign(),
                    "this orientation appears twice (one mounting per orientation)",
                ));
            }
        }
        Ok(())
    }

    /// The rates: at least one, each finite and > 0, slow enough for the order-4 fit, none
    /// twice and no two sharing a recording's file name.
    fn validate_rates(&self, v: &Validator<'_>) -> Result<()> {
        let p = &self.probe;
        if self.rates_deg_s.is_empty() {
            return Err(SimulateError::EmptyList {
                path: v.path.to_owned(),
                field: "rates_deg_s".to_owned(),
            });
        }
        // Every revolution must hold enough samples for the paper's order-4 fit (with drift).
        let min_samples = FitConfig {
            drift: true,
            ..FitConfig::default()
        }
        .min_samples();
        // First index of each rate (by bits: the rates are finite and > 0 when looked up, so
        // equal values have equal bits) and of each file name: linear in the number of rates.
        let mut first_of_rate: HashMap<u64, usize> = HashMap::with_capacity(self.rates_deg_s.len());
        let mut first_of_name: HashMap<String, usize> =
            HashMap::with_capacity(self.rates_deg_s.len());
        for (i, &r) in self.rates_deg_s.iter().enumerate() {
            let field = format!("rates_deg_s[{i}]");
            if !(r.is_finite() && r > 0.0) {
                return Err(v.invalid(&field, r, "a rate must be finite and > 0"));
            }
            let samples_per_revolution = p.sample_rate_hz * 360.0 / r;
            if samples_per_revolution < min_samples as f64 {
                return Err(SimulateError::RateTooFast {
                    path: v.path.to_owned(),
                    field,
                    rate_deg_s: r,
                    samples_per_revolution,
                    need: min_samples,
                    max_rate_deg_s: p.sample_rate_hz * 360.0 / min_samples as f64,
                });
            }
            if let Some(&j) = first_of_rate.get(&r.to_bits()) {
                return Err(SimulateError::DuplicateRate {
                    path: v.path.to_owned(),
                    field,
                    first: format!("rates_deg_s[{j}]"),
                    rate_deg_s: r,
                });
            }
            first_of_rate.insert(r.to_bits(), i);
            let name = recording_file_name(r);
            if let Some(&j) = first_of_name.get(&name) {
                return Err(SimulateError::RecordingNameCollision {
                    path: v.path.to_owned(),
                    field,
                    first: format!("rates_deg_s[{j}]"),
                    rate_deg_s: r,
                    first_rate_deg_s: self.rates_deg_s[j],
                    file_name: name,
                });
            }
            first_of_name.insert(name, i);
        }
        Ok(())
    }

    /// The revolutions and durations: within bounds, the fastest rate resolving the highest
    /// sleeve harmonic, the recordings within the total number of samples.
    fn validate_durations(&self, v: &Validator<'_>) -> Result<()> {
        let p = &self.probe;
        if self.revolutions == 0 || self.revolutions > MAX_REVOLUTIONS {
            return Err(v.invalid(
                "revolutions",
                self.revolutions as f64,
                "must lie in 1..=10000",
            ));
        }
        v.non_negative("min_duration_s", self.min_duration_s)?;
        if self
            .rates_deg_s
            .iter()
            .any(|&r| self.revolutions_at(r) > MAX_REVOLUTIONS)
        {
            return Err(v.invalid(
                "min_duration_s",
                self.min_duration_s,
                "needs more than 10000 revolutions at the fastest rate",
            ));
        }
        // The fastest rate has the fewest samples per revolution; they must resolve the
        // highest sleeve harmonic (more than two samples per period of it).
        let fastest = self.rates_deg_s.iter().copied().fold(0.0, f64::max);
        let highest = p
            .sleeve_harmonics
            .iter()
            .map(|h| h.order)
            .max()
            .unwrap_or(1);
        let per_rev_fastest = p.sample_rate_hz * 360.0 / fastest;
        if per_rev_fastest <= (2 * highest + 2) as f64 {
            return Err(v.invalid(
                "probe.sample_rate_hz",
                p.sample_rate_hz,
                "too low: the fastest rate needs more than 2·(highest harmonic) + 2 samples per revolution",
            ));
        }
        let total: f64 = self
            .rates_deg_s
            .iter()
            .map(|&r| p.sample_rate_hz * 360.0 / r * self.revolutions_at(r) as f64)
            .sum();
        if total > MAX_TOTAL_SAMPLES {
            return Err(v.invalid(
                "revolutions",
                self.revolutions as f64,
                "the recordings would hold more than 2e8 samples; lower revolutions, min_duration_s or sample_rate_hz",
            ));
        }
        Ok(())
    }

    /// Whole revolutions recorded at `rate_deg_s`: `revolutions`, or more if needed to last
    /// `min_duration_s` (a duration within 1e-9 of a whole number of turns counts as that
    /// number).
    ///
    /// ```
    /// # let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/scenarios/post-balance.ron")).unwrap();
    /// let mut s = simulate::Scenario::parse(&text, std::path::Path::new("post-balance.ron"))?.scenario;
    /// s.revolutions = 2;
    /// s.min_duration_s = 72.0;
    /// assert_eq!(s.revolutions_at(10.0), 2);    // 36 s per turn
    /// assert_eq!(s.revolutions_at(100.0), 20);  // 3.6 s per turn
    /// assert_eq!(s.revolutions_at(200.1234), 41);
    /// # Ok::<(), simulate::SimulateError>(())
    /// ```
    #[must_use]
    pub fn revolutions_at(&self, rate_deg_s: f64) -> usize {
        let turns = self.min_duration_s * rate_deg_s / 360.0;
        let needed = if (turns - turns.round()).abs() < 1e-9 {
            turns.round()
        } else {
            turns.ceil()
        };
        // `as` saturates; validation bounds the result
        self.revolutions.max(needed as usize)
    }
}

/// The file name of the probe recording at `rate_deg_s`: `probe_010.0000deg_s.csv`
/// (four decimals, zero-padded to three integer digits).
///
/// ```
/// assert_eq!(simulate::recording_file_name(10.0), "probe_010.0000deg_s.csv");
/// assert_eq!(simulate::recording_file_name(200.1234), "probe_200.1234deg_s.csv");
/// ```
#[must_use]
pub fn recording_file_name(rate_deg_s: f64) -> String {
    format!("probe_{rate_deg_s:08.4}deg_s.csv")
}

/// File name of the raw PIGA output recording at a rate: `piga_<rate>deg_s.csv`, as
/// [`recording_file_name`].
///
/// ```
/// assert_eq!(simulate::piga_recording_file_name(20.0), "piga_020.0000deg_s.csv");
/// ```
#[must_use]
pub fn piga_recording_file_name(rate_deg_s: f64) -> String {
    format!("piga_{rate_deg_s:08.4}deg_s.csv")
}

/// The file name of the second probe's recording at `rate_deg_s`:
/// `probe2_010.0000deg_s.csv`.
///
/// ```
/// assert_eq!(simulate::second_recording_file_name(10.0), "probe2_010.0000deg_s.csv");
/// ```
#[must_use]
pub fn second_recording_file_name(rate_deg_s: f64) -> String {
    format!("probe2_{rate_deg_s:08.4}deg_s.csv")
}

/// Field checks that name the file and the field.
struct Validator<'a> {
    path: &'a Path,
}

impl Validator<'_> {
    fn invalid(&self, field: &str, value: f64, reason: &'static str) -> SimulateError {
        SimulateError::InvalidField {
            path: self.path.to_owned(),
            field: field.to_owned(),
            value,
            reason,
        }
    }

    fn finite(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(self.invalid(field, value, "must be finite"))
        }
    }

    fn positive(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(self.invalid(field, value, "must be finite and > 0"))
        }
    }

    /// A length in µm: finite and at most [`MAX_LENGTH_UM`] in magnitude, so that sums of
    /// such lengths in a recording stay finite.
    fn length_um(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value.abs() <= MAX_LENGTH_UM {
            Ok(())
        } else {
            Err(self.invalid(
                field,
                value,
                "must be finite and at most 1e9 µm in magnitude",
            ))
        }
    }

    fn non_negative(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(self.invalid(field, value, "must be finite and >= 0"))
        }
    }
}
