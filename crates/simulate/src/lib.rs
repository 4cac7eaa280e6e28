//! Closed-loop simulation of a centrifuge calibration: probe recordings, PIGA outputs and
//! the truth behind them, from a RON scenario.
//!
//! A [`Scenario`] describes a centrifuge (radius, site), its spindle error motion (eq. 1–5,
//! 16), a displacement probe on the sleeve (lever heights, direction, sampling, noise, sleeve
//! harmonics, encoder, speed ripple), a PIGA (eq. 15) and a list of rates. [`simulate`] gives,
//! in memory, one probe recording per rate, the PIGA calibration table and a [`Truth`];
//! [`write_simulation`] writes them as `probe_<rate>deg_s.csv`, `piga.csv` and `truth.json`.
//!
//! **Probe model.** The chain of eq. 5 pivots the tilt at the PIGA plane (the `O2` origin),
//! while the paper's probe analysis (eq. 22) assumes a cone about a pivot
//! `h_p + h_a` below that plane. The simulator takes the spindle-axis point at the PIGA plane
//! from the exact chain, `T₂¹(θ)·[0 0 0 1]ᵀ = ΔR(cos(θ+β), sin(θ+β), 0)`, scales its `X1`
//! component by `h_p/(h_p + h_a)` to the probe plane, and reads it against `O1X1`
//! (`gap = l0 − x`) or along it (`gap = l0 + x`), adding the sleeve harmonics
//! `Σ c_k cos kθ + s_k sin kθ` and white noise. Then `d_c1 = −ΔR1 cos β` (eq. 21) and
//! `−d_c1·(h_p + h_a)/h_p = Δr_x = Δr_xs + C_r ω²` (eq. 22) hold exactly for the noise-free
//! signal. See `docs/SIMULATION.md`.
//!
//! **Second probe.** A scenario's optional `second_probe` adds a probe at another height
//! (`probe2_<rate>deg_s.csv`). With it, both probes read the spindle axis as the straight
//! line of the chain, `T₂¹(θ)·[0 0 −h 1]ᵀ` at each probe's depth `h` below the PIGA plane
//! (translation plus tilt times height, no cone), so that two probe planes separate the
//! translation from the tilt (`balance::AxisMotion`).
//!
//! **PIGA.** Each row of `piga.csv` is `accel_model::rate_points` — eq. 15 evaluated on the
//! exact inputs of eq. 12–13 and averaged over whole revolutions — plus N(0, σ²). With
//! `piga.recordings`, each rate also gets a raw output recording `piga_<rate>deg_s.csv`
//! sampled with the probe: the output angle `ω̄_out·t + A·sin(θ + φ) + e` whose mean slope
//! is that row's output, a once-per-revolution term that whole revolutions cancel, and white
//! noise.
//!
//! **Two orientations and arm stretch** (issue 20, `docs/theory.md` section 11). A scenario's
//! `mountings` record the PIGA again with its input axis in or out ([`Orientation`]), at its
//! own radius and bias shift, and `arm_stretch_m_s2` (`C_a`) grows the radius at the PIGA by
//! `C_a·ω²` beyond the spindle's motion, unseen by the probe: the mount of eq. 10 becomes
//! `Trans(R_s + C_a ω², 0, 0)·Rot(z₂, 180°)` (IA in) or `Trans(R_s + C_a ω², 0, 0)` (IA out)
//! ([`Mount`], [`mounted_rate_point`], [`piga_table_mounted`]). [`mounted_piga_recording`]
//! gives one mounting's raw PIGA output recording at a rate on its own (the test planner's
//! check of a plan's points through the study's reduction).
//!
//! **Multi-mounting campaigns** (issue 29, `docs/MODEL.md`): [`MountingCampaign`] mounts a
//! PIGA or a pendulous accelerometer with the IEEE 836 model's terms several ways on the arm
//! (true axes, radii and bias shifts), and [`campaign_points`] gives each mounting's mean
//! outputs over whole revolutions of the exact chain (`accel_model::mounted_point`), with the
//! spindle's error motion and the arm stretch; [`noisy_outputs`] adds white noise.

mod campaign;
mod error;
mod generate;
mod mounting;
mod scenario;
mod write;

pub use campaign::{
    CampaignMounting, FIXTURE_LATITUDE_DEG, FIXTURE_MOUNTINGS, FIXTURE_PENDULOUS_TRUTH,
    FIXTURE_PIGA_TRUTH, MountingCampaign, campaign_points, fixture_spindle, noisy_outputs,
};
pub use error::{Result, SimulateError};
pub use generate::{
    MountingRateTruth, MountingTruth, OutputNoise, PigaRow, ProbeTruth, RadiusGrowthTruth,
    SimulatedMounting, SimulatedPigaRecording, SimulatedRecording, Simulation, Truth, TruthRate,
    mounted_piga_recording, mounting_recording_file_name, piga_table, piga_table_mounted, simulate,
};
pub use mounting::{Mount, Orientation, mounted_rate_point};
pub use scenario::{
    CentrifugeSpec, LoadedScenario, MAX_SLEEVE_ORDER, MAX_TOTAL_SAMPLES, MountingSpec,
    PigaRecordingSpec, PigaSpec, ProbeSpec, Scenario, SecondProbeSpec, SleeveHarmonic, SpeedRipple,
    piga_recording_file_name, recording_file_name, second_recording_file_name,
};
pub use write::{SimulationFiles, piga_csv_text, write_simulation};
