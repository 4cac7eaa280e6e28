//! The simulation itself, in memory: probe recordings, PIGA outputs and the truth.

use std::f64::consts::TAU;

use accel_model::{PigaCoefficients, RatePoint, rate_points};
use harmonics::{FirstHarmonic, LeverGeometry};
use identify::{CrEstimate, Geometry, pseudo_second_order};
use kinematics::{
    Centrifuge, Chain, ErrorMotion, Point, Spindle, SpindleOffsets, spindle_transform,
};
use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};
use serde::{Deserialize, Serialize};

use super::mounting::{Mount, Orientation, mounted_rate_point};
use super::scenario::{
    LoadedScenario, PigaRecordingSpec, ProbeSpec, Scenario, piga_recording_file_name,
    recording_file_name, second_recording_file_name,
};
use crate::error::{Result, SimulateError};
use units::m_to_um;

/// Stream tags that keep the random streams of the probe and the PIGA independent of each
/// other; each rate has its own streams, keyed by its value, so that adding, removing or
/// reordering rates leaves the noise of the others unchanged.
const PROBE_STREAM: u64 = 1;
const PIGA_STREAM: u64 = 2;
const PIGA_RECORDING_STREAM: u64 = 3;
const SECOND_PROBE_STREAM: u64 = 4;
/// The mountings' tables and raw recordings: one stream each per orientation.
const MOUNTING_STREAM: [u64; 2] = [5, 6];
const MOUNTING_RECORDING_STREAM: [u64; 2] = [7, 8];

/// Index of an orientation in the mounting stream tables.
const fn orientation_index(o: Orientation) -> usize {
    match o {
        Orientation::IaIn => 0,
        Orientation::IaOut => 1,
    }
}

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

/// Runs a scenario in memory.
///
/// For each rate, the probe recording follows the probe model of `docs/SIMULATION.md`: the
/// spindle-axis point at the PIGA plane from the exact chain (eq. 5), carried to the probe
/// plane by the cone of eq. 22, read against (or along) `O1X1`, plus the sleeve harmonics and
/// white noise. The PIGA row is `accel_model::rate_points` (eq. 15 averaged over whole
/// revolutions of the exact inputs) plus white noise. Deterministic for a given seed.
///
/// ```
/// use std::path::Path;
/// let text = r#"(
///     name: "doc", seed: 1,
///     centrifuge: (radius_m: 2.5, site: (latitude_deg: 45.0, earth_rate_rad_s: 7.292115e-5, gravity_m_s2: 9.8)),
///     error_motion: Coefficients((dr_xs_m: 5.6e-6, c_r_m_s2: -4.05e-8)),
///     probe: (lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0),
///             sample_rate_hz: 1000.0, noise_um: 0.0, l0_um: 50.0),
///     piga: (coefficients: (k0_rad_s: 0.0, k1_rad_s_g: 0.56, k2_rad_s_g2: 0.0, k3_rad_s_g3: 0.0)),
///     rates_deg_s: [100.0, 200.0],
///     revolutions: 1,
/// )"#;
/// let scenario = simulate::Scenario::parse(text, Path::new("doc.ron"))?;
/// let sim = simulate::simulate(&scenario)?;
/// assert_eq!(sim.recordings.len(), 2);
/// assert_eq!(sim.recordings[0].time_s.len(), 3600); // one revolution at 100 deg/s, 1 kHz
/// // noise-free: the gap is l0 − Δr_x·700/1210·cos θ at θ = 0
/// let dr_x_um = 5.6 - 0.0405 * 100f64.to_radians().powi(2);
/// approx::assert_relative_eq!(sim.recordings[0].gap_um[0], 50.0 - dr_x_um * 700.0 / 1210.0,
///                             max_relative = 1e-12);
/// // Δk2 = k1·C_r·g/R² (eq. 19)
/// approx::assert_relative_eq!(sim.truth.delta_k2_predicted_rad_s_g2,
///                             0.56 * -4.05e-8 * 9.8 / 6.25, max_relative = 1e-12);
/// # Ok::<(), simulate::SimulateError>(())
/// ```
///
/// # Errors
/// As [`Scenario::check`] if the scenario was altered after loading so that it is no longer
/// valid; [`SimulateError::Kinematics`] or [`SimulateError::AccelModel`] if the chain or the
/// PIGA model refuses an input or its result is not finite (e.g. `c_r_m_s2: 1e300`);
/// [`SimulateError::NonFiniteOutput`] for any other number of the simulation that is not
/// finite, by its path (`truth.rates[0].a_nominal_g`).
pub fn simulate(loaded: &LoadedScenario) -> Result<Simulation> {
    let s = &loaded.scenario;
    // `LoadedScenario`'s fields are public: check again rather than trust them (cheap).
    let error_motion = s.validate(&loaded.path)?;
    let centrifuge = Centrifuge {
        radius_m: s.centrifuge.radius_m,
        site: s.centrifuge.site,
        error_motion,
    };
    let g = s.centrifuge.site.gravity_m_s2;
    let radius = s.centrifuge.radius_m;
    let k = &s.piga.coefficients;
    let lever = Lever::new(&s.probe.lever).map_err(|source| SimulateError::Harmonics {
        path: loaded.path.clone(),
        field: "probe.lever".to_owned(),
        source,
    })?;
    let lever_ratio = lever.ratio;

    let rates_rad_s: Vec<f64> = s.rates_deg_s.iter().map(|d| d.to_radians()).collect();
    let accel_error = |field: &str| {
        let path = loaded.path.clone();
        let field = field.to_owned();
        move |source| SimulateError::AccelModel {
            path,
            field,
            source,
        }
    };
    // Without an arm stretch, the paper's chain as `accel_model` evaluates it (the files of
    // scenarios written before issue 20 stay byte for byte); with one, the mounted chain.
    let points = if s.arm_stretch_m_s2 == 0.0 {
        rate_points(&centrifuge, k, &rates_rad_s).map_err(accel_error("piga"))?
    } else {
        let mount = Mount {
            arm_stretch_m_s2: s.arm_stretch_m_s2,
            ..Mount::ia_in(radius)
        };
        mounted_points(&centrifuge, k, &mount, &rates_rad_s).map_err(accel_error("piga"))?
    };
    let mounted: Vec<Vec<RatePoint>> = s
        .mountings
        .iter()
        .enumerate()
        .map(|(i, m)| {
            mounted_points(&centrifuge, k, &m.mount(s.arm_stretch_m_s2), &rates_rad_s)
                .map_err(accel_error(&format!("mountings[{i}]")))
        })
        .collect::<Result<_>>()?;
    let mut mountings: Vec<SimulatedMounting> = s
        .mountings
        .iter()
        .map(|m| SimulatedMounting {
            orientation: m.orientation,
            radius_m: m.radius_m,
            file_name: m.table_file_name(),
            piga: Vec::with_capacity(points.len()),
            piga_recordings: Vec::new(),
        })
        .collect();

    let mut recordings = Vec::with_capacity(points.len());
    let mut piga_recordings = Vec::new();
    let mut second_recordings = Vec::new();
    let mut piga = Vec::with_capacity(points.len());
    let mut rates = Vec::with_capacity(points.len());
    for (i, (point, &rate_deg_s)) in points.iter().zip(&s.rates_deg_s).enumerate() {
        let chain = Chain::new(&centrifuge, point.rate_rad_s).map_err(|source| {
            SimulateError::Kinematics {
                path: loaded.path.clone(),
                field: format!("rates_deg_s[{i}]"),
                source,
            }
        })?;
        // the probes' readers: the cone of eq. 22, or two points of the axis line
        let (first, second) = readers(s, lever, chain.offsets(), rate_deg_s);
        let recording = record(s, &first, chain.rate_rad_s(), rate_deg_s);
        let second_probe_first_harmonic = second.map(|reader| {
            second_recordings.push(record(s, &reader, chain.rate_rad_s(), rate_deg_s));
            reader.truth(chain.offsets())
        });
        let noise = OutputNoise {
            sigma_rad_s: s.piga.noise_rad_s,
            seed: s.seed,
        };
        let output_rad_s = noise.added_to(point.output_rad_s, rate_deg_s);
        piga.push(PigaRow {
            rate_deg_s,
            output_rad_s,
        });
        if let Some(spec) = &s.piga.recordings {
            piga_recordings.push(record_piga(
                s.seed,
                PIGA_RECORDING_STREAM,
                spec,
                &recording,
                output_rad_s,
                piga_recording_file_name(rate_deg_s),
            ));
        }
        for (m, points) in mountings.iter_mut().zip(&mounted) {
            let o = orientation_index(m.orientation);
            let output_rad_s =
                noise.added_to_stream(MOUNTING_STREAM[o], points[i].output_rad_s, rate_deg_s);
            m.piga.push(PigaRow {
                rate_deg_s,
                output_rad_s,
            });
            if let Some(spec) = &s.piga.recordings {
                m.piga_recordings.push(record_piga(
                    s.seed,
                    MOUNTING_RECORDING_STREAM[o],
                    spec,
                    &recording,
                    output_rad_s,
                    mounting_recording_file_name(m.orientation, rate_deg_s),
                ));
            }
        }
        let offsets = *chain.offsets();
        let w = point.rate_rad_s;
        rates.push(TruthRate {
            rate_deg_s,
            rate_rad_s: w,
            a_nominal_g: radius * w * w / g,
            a_x_g: point.a_x_g,
            omega_i_rad_s: point.omega_i_rad_s,
            output_noise_free_rad_s: point.output_rad_s,
            output_rad_s,
            piga_recording: s
                .piga
                .recordings
                .map(|_| piga_recording_file_name(rate_deg_s)),
            offsets,
            radius_error_um: m_to_um(offsets.dr_x_m),
            probe_first_harmonic: first.truth(&offsets),
            second_probe_first_harmonic,
            recording: recording.file_name.clone(),
            revolutions: s.revolutions_at(rate_deg_s),
            samples: recording.time_s.len(),
            radius_error_sigma_um: lever_ratio
                * s.probe.noise_um
                * (2.0 / recording.time_s.len() as f64).sqrt(),
        });
        recordings.push(recording);
    }

    let c_r = error_motion.c_r_m_s2;
    // σ(C_r) = 0: the truth is exact
    let exact_c_r = CrEstimate {
        c_r_m_s2: c_r,
        c_r_sigma_m_s2: 0.0,
    };
    let geometry = Geometry {
        radius_m: radius,
        g_m_s2: g,
    };
    let delta_k2 = pseudo_second_order(k.k1_rad_s_g, exact_c_r, geometry)
        .map_err(|source| SimulateError::Identify {
            path: loaded.path.clone(),
            field: "piga".to_owned(),
            source,
        })?
        .delta_k2_rad_s_g2;
    let symmetric = s.arm_stretch_m_s2 != 0.0 || !s.mountings.is_empty();
    let c_total = c_r + s.arm_stretch_m_s2;
    let dk2_total = |radius_m: f64| k.k1_rad_s_g * c_total * g / (radius_m * radius_m);
    let radius_growth = symmetric.then(|| RadiusGrowthTruth {
        c_r_m_s2: c_r,
        c_a_m_s2: s.arm_stretch_m_s2,
        c_m_s2: c_total,
        delta_k2_total_predicted_rad_s_g2: dk2_total(radius),
    });
    let mounting_truths = s
        .mountings
        .iter()
        .zip(&mountings)
        .zip(&mounted)
        .map(|((spec, sim), points)| MountingTruth {
            orientation: spec.orientation,
            sign: spec.orientation.sign(),
            radius_m: spec.radius_m,
            coefficients: spec.mount(s.arm_stretch_m_s2).coefficients(k),
            delta_k2_total_predicted_rad_s_g2: dk2_total(spec.radius_m),
            table: spec.table_file_name(),
            rates: points
                .iter()
                .zip(&sim.piga)
                .enumerate()
                .map(|(i, (p, row))| MountingRateTruth {
                    rate_deg_s: row.rate_deg_s,
                    a_nominal_g: spec.radius_m * p.rate_rad_s * p.rate_rad_s / g,
                    a_x_g: p.a_x_g,
                    omega_i_rad_s: p.omega_i_rad_s,
                    output_noise_free_rad_s: p.output_rad_s,
                    output_rad_s: row.output_rad_s,
                    piga_recording: sim.piga_recordings.get(i).map(|r| r.file_name.clone()),
                })
                .collect(),
        })
        .collect();
    let simulation = Simulation {
        recordings,
        second_recordings,
        piga,
        piga_recordings,
        mountings,
        truth: Truth {
            scenario: s.clone(),
            error_motion,
            lever_ratio,
            c_r_m_s2: c_r,
            delta_k2_predicted_rad_s_g2: delta_k2,
            k2_apparent_predicted_rad_s_g2: k.k2_rad_s_g2 + delta_k2,
            rates,
            radius_growth,
            mountings: mounting_truths,
        },
    };
    // Every number the simulation returns is finite (the libraries check their own results;
    // this catches what is combined here, e.g. `a_nominal_g = R·ω²/g`).
    edge_io::check_finite(&simulation).map_err(|e| SimulateError::NonFiniteOutput {
        what: "the simulation",
        field: e.path,
        value: e.value,
    })?;
    Ok(simulation)
}

/// The probe geometry as the simulator uses it, both numbers from `harmonics`' conventions.
#[derive(Debug, Clone, Copy)]
struct Lever {
    /// `(h_probe + h_piga)/h_probe` ([`LeverGeometry::lever_ratio`]).
    ratio: f64,
    /// `+1` for a probe that measures along `O1X1` (the gap opens as the axis moves to `+X1`),
    /// `−1` against it (the paper's set-up: the gap closes).
    sign: f64,
}

impl Lever {
    fn new(lever: &LeverGeometry) -> std::result::Result<Self, harmonics::HarmonicsError> {
        let ratio = lever.lever_ratio()?;
        // Eq. 21–22 as `harmonics` reads them: a unit d_c1 stands for a radius error of
        // ±ratio at the PIGA plane, + along O1X1 and − against it.
        let sign = lever
            .project(FirstHarmonic { c1: 1.0, s1: 0.0 })?
            .radius_error
            .signum();
        Ok(Self { ratio, sign })
    }
}

/// How one probe reads the spindle axis at one rate: the axis point in its plane at spindle
/// angle 0 (in `O1`, which then turns with the spindle), its sign and its noise stream.
#[derive(Debug, Clone)]
struct Reader {
    /// `(x, y)` of the axis point in the probe plane at θ = 0, µm.
    point_um: [f64; 2],
    /// `+1` along `O1X1`, `−1` against.
    sign: f64,
    /// Noise stream tag.
    purpose: u64,
    file_name: String,
}

impl Reader {
    /// The exact first harmonic of the gap: the axis point in the probe plane turned by θ,
    /// `x cos θ − y sin θ` along `O1X1`, read with the probe's sign.
    fn truth(&self, offsets: &SpindleOffsets) -> ProbeTruth {
        let dc1_um = self.sign * self.point_um[0];
        let ds1_um = -self.sign * self.point_um[1];
        ProbeTruth {
            dc1_um,
            ds1_um,
            amplitude_um: dc1_um.hypot(ds1_um),
            beta_deg: offsets.drift_azimuth_rad().to_degrees(),
        }
    }
}

/// The readers of a scenario's probes at one rate. One probe: the spindle-axis point at the
/// PIGA plane carried down the cone of eq. 22 (`/ratio`). Two probes: each reads the axis
/// line of the chain (eq. 5) at its own height, `T₂¹(0)·[0 0 −h 1]ᵀ` (translation plus tilt
/// times height), with no cone.
fn readers(
    s: &Scenario,
    lever: Lever,
    offsets: &SpindleOffsets,
    rate_deg_s: f64,
) -> (Reader, Option<Reader>) {
    let at_height = |below_piga_mm: f64| {
        let p = spindle_transform(0.0, offsets)
            .apply(Point::<Spindle>::new([0.0, 0.0, -below_piga_mm * 1e-3]))
            .coords_m;
        [m_to_um(p[0]), m_to_um(p[1])]
    };
    let Some(q) = &s.second_probe else {
        let p0 = axis_point_at_piga(offsets, 0.0);
        let first = Reader {
            point_um: [m_to_um(p0[0]) / lever.ratio, m_to_um(p0[1]) / lever.ratio],
            sign: lever.sign,
            purpose: PROBE_STREAM,
            file_name: recording_file_name(rate_deg_s),
        };
        return (first, None);
    };
    let first = Reader {
        point_um: at_height(s.probe.lever.probe_to_piga_mm),
        sign: lever.sign,
        purpose: PROBE_STREAM,
        file_name: recording_file_name(rate_deg_s),
    };
    let second = Reader {
        point_um: at_height(q.probe_to_piga_mm),
        sign: match q.probe_direction {
            harmonics::ProbeDirection::AlongO1X1 => 1.0,
            harmonics::ProbeDirection::AgainstO1X1 => -1.0,
        },
        purpose: SECOND_PROBE_STREAM,
        file_name: second_recording_file_name(rate_deg_s),
    };
    (first, Some(second))
}

/// Number of samples that cover `revolutions` whole turns at `rate_deg_s`: every sample
/// time `i/f_s` is below the end time `revolutions·360/rate` (an end time that falls on a
/// sample to within 1e-6 of an interval counts as falling on it).
pub(crate) fn sample_count(sample_rate_hz: f64, rate_deg_s: f64, revolutions: usize) -> usize {
    let x = revolutions as f64 * 360.0 / rate_deg_s * sample_rate_hz;
    let n = if (x - x.round()).abs() < 1e-6 {
        x.round()
    } else {
        x.ceil()
    };
    // a validated scenario keeps this well below usize::MAX (MAX_TOTAL_SAMPLES)
    n as usize
}

/// The spindle angle `θ(t) = θ₀ + ωt + A·(sin(ωt + φ) − sin φ)`, rad (not wrapped).
fn spindle_angle_rad(probe: &ProbeSpec, rate_rad_s: f64, t_s: f64) -> f64 {
    let theta0 = probe.start_angle_deg.to_radians();
    let wt = rate_rad_s * t_s;
    let ripple = probe.speed_ripple.map_or(0.0, |r| {
        let (a, phi) = (r.amplitude_deg.to_radians(), r.phase_deg.to_radians());
        a * ((wt + phi).sin() - phi.sin())
    });
    theta0 + wt + ripple
}

/// One probe's recording at one rate.
fn record(s: &Scenario, reader: &Reader, rate_rad_s: f64, rate_deg_s: f64) -> SimulatedRecording {
    let probe = &s.probe;
    let n = sample_count(
        probe.sample_rate_hz,
        rate_deg_s,
        s.revolutions_at(rate_deg_s),
    );
    let sign = reader.sign;
    let mut rng = stream(s.seed, reader.purpose, rate_deg_s.to_bits());
    let noise = normal(probe.noise_um);
    // The spindle-axis point in the probe plane, in the sleeve frame. Eq. 5 begins with
    // Rot(z₁, θ), so T₂¹(θ) = Rot(z₁, θ)·T₂¹(0) and the point at angle θ is the chain's point
    // at θ = 0 turned by θ (equal to evaluating the chain at θ; tested).
    let p0 = reader.point_um;
    let harmonics: Vec<(usize, f64, f64)> = probe
        .sleeve_harmonics
        .iter()
        .map(|h| (h.order, h.c_um, h.s_um))
        .collect();
    let highest = harmonics.iter().map(|h| h.0).max().unwrap_or(1);
    let mut cos_k = vec![0.0; highest + 1];
    let mut sin_k = vec![0.0; highest + 1];

    let mut time_s = Vec::with_capacity(n);
    let mut gap_um = Vec::with_capacity(n);
    let mut angle_deg = probe.encoder_angle.then(|| Vec::with_capacity(n));
    for i in 0..n {
        let t = i as f64 / probe.sample_rate_hz;
        let theta = spindle_angle_rad(probe, rate_rad_s, t);
        let (sin1, cos1) = theta.sin_cos();
        // X1 component of Rot(z, θ)·p0
        let x_probe_um = p0[0] * cos1 - p0[1] * sin1;
        // cos kθ, sin kθ by the angle-addition recurrence
        (cos_k[0], sin_k[0]) = (1.0, 0.0);
        for k in 1..=highest {
            cos_k[k] = cos_k[k - 1] * cos1 - sin_k[k - 1] * sin1;
            sin_k[k] = sin_k[k - 1] * cos1 + cos_k[k - 1] * sin1;
        }
        let sleeve: f64 = harmonics
            .iter()
            .map(|&(k, c, s)| c * cos_k[k] + s * sin_k[k])
            .sum();
        let e = noise.as_ref().map_or(0.0, |d| d.sample(&mut rng));
        time_s.push(t);
        gap_um.push(probe.l0_um + sign * x_probe_um + sleeve + e);
        if let Some(a) = angle_deg.as_mut() {
            a.push(theta.rem_euclid(TAU).to_degrees() % 360.0);
        }
    }
    SimulatedRecording {
        rate_deg_s,
        file_name: reader.file_name.clone(),
        time_s,
        gap_um,
        angle_deg,
    }
}

/// The raw PIGA output recording at one rate, sampled with the probe's recording: the
/// output angle `ω̄_out·t + A·sin(θ + φ) + e` with `θ` the spindle angle of each sample (the
/// encoder's when the probe records one; the same formula of time otherwise).
fn record_piga(
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

/// White noise on the PIGA's per-rate mean output: N(0, σ²), one independent stream per rate
/// drawn from the seed (the simulator's one noise model for PIGA tables).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputNoise {
    /// Standard deviation, rad/s (0: noise-free; must be finite and ≥ 0).
    pub sigma_rad_s: f64,
    /// Seed of the streams.
    pub seed: u64,
}

impl OutputNoise {
    /// `output_rad_s` plus this rate's draw.
    fn added_to(&self, output_rad_s: f64, rate_deg_s: f64) -> f64 {
        self.added_to_stream(PIGA_STREAM, output_rad_s, rate_deg_s)
    }

    /// `output_rad_s` plus this rate's draw from the stream `purpose`.
    fn added_to_stream(&self, purpose: u64, output_rad_s: f64, rate_deg_s: f64) -> f64 {
        let mut rng = stream(self.seed, purpose, rate_deg_s.to_bits());
        output_rad_s + normal(self.sigma_rad_s).map_or(0.0, |d| d.sample(&mut rng))
    }
}

/// The mean outputs of a mounting at each rate ([`mounted_rate_point`]).
fn mounted_points(
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
/// [`simulate`] writes to `piga.csv`.
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

/// An independent random stream per (seed, purpose, key): the workspace's one seeding
/// convention, [`units::stream_seed`].
fn stream(seed: u64, purpose: u64, key: u64) -> StdRng {
    StdRng::seed_from_u64(units::stream_seed(seed, purpose, key))
}

/// The spindle-axis point at the PIGA plane (the `O2` origin) in the sleeve frame at spindle
/// angle θ, from the chain of eq. 5: `T₂¹(θ)·[0 0 0 1]ᵀ`, m.
fn axis_point_at_piga(offsets: &SpindleOffsets, theta_rad: f64) -> [f64; 3] {
    spindle_transform(theta_rad, offsets)
        .apply(Point::<Spindle>::new([0.0, 0.0, 0.0]))
        .coords_m
}

/// N(0, σ²), or `None` (no draws at all) when σ is 0.
fn normal(sigma: f64) -> Option<Normal<f64>> {
    // σ was validated finite and ≥ 0, so `Normal::new` cannot fail
    (sigma > 0.0)
        .then(|| Normal::new(0.0, sigma).ok())
        .flatten()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn sample_count_covers_whole_revolutions() {
        // 10 deg/s at 1 kHz: 36 s per revolution, samples 0 … 71999 for two turns
        assert_eq!(sample_count(1000.0, 10.0, 2), 72_000);
        // 200.1234 deg/s: 1798.89 samples per turn, the last sample is inside the turn
        let n = sample_count(1000.0, 200.1234, 1);
        assert_eq!(n, 1799);
        assert!(((n - 1) as f64) / 1000.0 < 360.0 / 200.1234);
    }

    #[test]
    fn streams_are_distinct_and_repeatable() {
        use rand::Rng;
        let a: u64 = stream(7, PROBE_STREAM, 0).random();
        let b: u64 = stream(7, PROBE_STREAM, 1).random();
        let c: u64 = stream(7, PIGA_STREAM, 0).random();
        let a2: u64 = stream(7, PROBE_STREAM, 0).random();
        assert_eq!(a, a2);
        assert_ne!(a, b);
        assert_ne!(a, c);
    }

    #[test]
    fn the_turned_point_is_the_chain_evaluated_at_the_angle() {
        let offsets = SpindleOffsets {
            dr_x_m: 5.6e-6,
            dr_y_m: -2.0e-6,
            dphi_x_rad: 3e-6,
            dphi_y_rad: -1e-6,
        };
        let p0 = axis_point_at_piga(&offsets, 0.0);
        for k in 0..50 {
            let theta = 0.37 * f64::from(k) - 3.0;
            let (s, c) = theta.sin_cos();
            let turned = [p0[0] * c - p0[1] * s, p0[0] * s + p0[1] * c, p0[2]];
            let direct = axis_point_at_piga(&offsets, theta);
            for (a, b) in turned.iter().zip(&direct) {
                assert!((a - b).abs() < 1e-20, "{theta}: {a} vs {b}");
            }
            // and it is ΔR·(cos(θ+β), sin(θ+β), 0) (eq. 9, corrected)
            let dr = offsets.drift_magnitude_m();
            let beta = offsets.drift_azimuth_rad();
            assert_relative_eq!(direct[0], dr * (theta + beta).cos(), epsilon = 1e-20);
            assert_relative_eq!(direct[1], dr * (theta + beta).sin(), epsilon = 1e-20);
            assert_eq!(direct[2], 0.0);
        }
    }

    #[test]
    fn lever_takes_ratio_and_sign_from_harmonics() {
        use harmonics::ProbeDirection;
        for (direction, sign) in [
            (ProbeDirection::AgainstO1X1, -1.0),
            (ProbeDirection::AlongO1X1, 1.0),
        ] {
            let lever = Lever::new(&LeverGeometry {
                pivot_to_probe_mm: 700.0,
                probe_to_piga_mm: 510.0,
                probe_direction: direction,
            })
            .unwrap();
            assert_eq!(lever.sign, sign, "{direction:?}");
            assert_relative_eq!(lever.ratio, 1210.0 / 700.0, max_relative = 1e-15);
        }
        let bad = LeverGeometry {
            pivot_to_probe_mm: 0.0,
            probe_to_piga_mm: 510.0,
            probe_direction: ProbeDirection::AlongO1X1,
        };
        assert!(Lever::new(&bad).is_err());
    }

    #[test]
    fn ripple_keeps_the_period_and_the_mean_rate() {
        let probe = ProbeSpec {
            lever: harmonics::LeverGeometry {
                pivot_to_probe_mm: 700.0,
                probe_to_piga_mm: 510.0,
                probe_direction: harmonics::ProbeDirection::AgainstO1X1,
            },
            sample_rate_hz: 1000.0,
            noise_um: 0.0,
            l0_um: 0.0,
            sleeve_harmonics: vec![],
            encoder_angle: true,
            speed_ripple: Some(super::super::scenario::SpeedRipple {
                amplitude_deg: 2.0,
                phase_deg: 40.0,
            }),
            start_angle_deg: 15.0,
        };
        let w = 1.3;
        let theta0 = spindle_angle_rad(&probe, w, 0.0);
        assert_relative_eq!(theta0, 15f64.to_radians(), max_relative = 1e-15);
        let one_turn = spindle_angle_rad(&probe, w, TAU / w);
        assert_relative_eq!(one_turn - theta0, TAU, max_relative = 1e-12);
        // but not uniform within the turn
        let quarter = spindle_angle_rad(&probe, w, 0.25 * TAU / w) - theta0;
        assert!((quarter - 0.25 * TAU).abs() > 1e-3);
    }
}
