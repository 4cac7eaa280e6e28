//! The simulation itself, in memory: probe recordings, PIGA outputs and the truth.
//!
//! Read in this order: `simulation` (what is produced), `noise` (the random streams),
//! `probe` (the probe recordings), `piga` (the PIGA's outputs); this file runs a scenario.

mod noise;
mod piga;
mod probe;
mod simulation;

use accel_model::{RatePoint, rate_points};
use identify::{CrEstimate, Geometry, delta_k2_rad_s_g2, pseudo_second_order};
use kinematics::{Centrifuge, Chain};
use units::m_to_um;

use crate::error::{Result, SimulateError};
use crate::mounting::Mount;
use crate::scenario::{LoadedScenario, Scenario, piga_recording_file_name};
use noise::{MOUNTING_RECORDING_STREAM, MOUNTING_STREAM, PIGA_RECORDING_STREAM, orientation_index};
use piga::{mounted_points, record_piga};
use probe::{Lever, readers, record};

pub use noise::OutputNoise;
pub use piga::{
    mounted_piga_recording, mounting_recording_file_name, piga_table, piga_table_mounted,
};
pub use simulation::{
    MountingRateTruth, MountingTruth, PigaRow, ProbeTruth, RadiusGrowthTruth, SimulatedMounting,
    SimulatedPigaRecording, SimulatedRecording, Simulation, Truth, TruthRate,
};

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
/// As [`Scenario::check`](crate::Scenario::check) if the scenario was altered after loading so that it is no longer
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
    let (points, mounted) = exact_points(loaded, &centrifuge)?;
    let recorded = record_rates(loaded, &centrifuge, lever, &points, &mounted)?;
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
    let (radius_growth, mounting_truths) =
        two_orientation_truth(s, c_r, &recorded.mountings, &mounted);
    let simulation = Simulation {
        recordings: recorded.recordings,
        second_recordings: recorded.second_recordings,
        piga: recorded.piga,
        piga_recordings: recorded.piga_recordings,
        mountings: recorded.mountings,
        truth: Truth {
            scenario: s.clone(),
            error_motion,
            lever_ratio,
            c_r_m_s2: c_r,
            delta_k2_predicted_rad_s_g2: delta_k2,
            k2_apparent_predicted_rad_s_g2: k.k2_rad_s_g2 + delta_k2,
            rates: recorded.rates,
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

/// The PIGA's noise-free points at each rate on the exact chain: mounted input axis in (with
/// the arm's stretch when there is one), and at each further mounting of the scenario.
fn exact_points(
    loaded: &LoadedScenario,
    centrifuge: &Centrifuge,
) -> Result<(Vec<RatePoint>, Vec<Vec<RatePoint>>)> {
    let s = &loaded.scenario;
    let k = &s.piga.coefficients;
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
        rate_points(centrifuge, k, &rates_rad_s).map_err(accel_error("piga"))?
    } else {
        let mount = Mount {
            arm_stretch_m_s2: s.arm_stretch_m_s2,
            ..Mount::ia_in(s.centrifuge.radius_m)
        };
        mounted_points(centrifuge, k, &mount, &rates_rad_s).map_err(accel_error("piga"))?
    };
    let mounted: Vec<Vec<RatePoint>> = s
        .mountings
        .iter()
        .enumerate()
        .map(|(i, m)| {
            mounted_points(centrifuge, k, &m.mount(s.arm_stretch_m_s2), &rates_rad_s)
                .map_err(accel_error(&format!("mountings[{i}]")))
        })
        .collect::<Result<_>>()?;
    Ok((points, mounted))
}

/// What the campaign records, rate by rate, and the truth of each rate.
struct Recorded {
    recordings: Vec<SimulatedRecording>,
    second_recordings: Vec<SimulatedRecording>,
    piga: Vec<PigaRow>,
    piga_recordings: Vec<SimulatedPigaRecording>,
    mountings: Vec<SimulatedMounting>,
    rates: Vec<TruthRate>,
}

/// At each rate: the probe recordings (one probe, or two), the PIGA's output with its noise
/// (and its raw recording when asked for), each further mounting's, and the rate's truth.
fn record_rates(
    loaded: &LoadedScenario,
    centrifuge: &Centrifuge,
    lever: Lever,
    points: &[RatePoint],
    mounted: &[Vec<RatePoint>],
) -> Result<Recorded> {
    let s = &loaded.scenario;
    let g = s.centrifuge.site.gravity_m_s2;
    let radius = s.centrifuge.radius_m;
    let mut out = Recorded {
        recordings: Vec::with_capacity(points.len()),
        second_recordings: Vec::new(),
        piga: Vec::with_capacity(points.len()),
        piga_recordings: Vec::new(),
        mountings: s
            .mountings
            .iter()
            .map(|m| SimulatedMounting {
                orientation: m.orientation,
                radius_m: m.radius_m,
                file_name: m.table_file_name(),
                piga: Vec::with_capacity(points.len()),
                piga_recordings: Vec::new(),
            })
            .collect(),
        rates: Vec::with_capacity(points.len()),
    };
    for (i, (point, &rate_deg_s)) in points.iter().zip(&s.rates_deg_s).enumerate() {
        let chain = Chain::new(centrifuge, point.rate_rad_s).map_err(|source| {
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
            out.second_recordings
                .push(record(s, &reader, chain.rate_rad_s(), rate_deg_s));
            reader.truth(chain.offsets())
        });
        let noise = OutputNoise {
            sigma_rad_s: s.piga.noise_rad_s,
            seed: s.seed,
        };
        let output_rad_s = noise.added_to(point.output_rad_s, rate_deg_s);
        out.piga.push(PigaRow {
            rate_deg_s,
            output_rad_s,
        });
        if let Some(spec) = &s.piga.recordings {
            out.piga_recordings.push(record_piga(
                s.seed,
                PIGA_RECORDING_STREAM,
                spec,
                &recording,
                output_rad_s,
                piga_recording_file_name(rate_deg_s),
            ));
        }
        for (m, points) in out.mountings.iter_mut().zip(mounted) {
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
        out.rates.push(TruthRate {
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
            radius_error_sigma_um: lever.ratio
                * s.probe.noise_um
                * (2.0 / recording.time_s.len() as f64).sqrt(),
        });
        out.recordings.push(recording);
    }
    Ok(out)
}

/// The truth of a scenario with an arm stretch or mountings: C = C_r + C_a with the total
/// Δk2 it predicts, and each mounting's coefficients and rates.
fn two_orientation_truth(
    s: &Scenario,
    c_r: f64,
    mountings: &[SimulatedMounting],
    mounted: &[Vec<RatePoint>],
) -> (Option<RadiusGrowthTruth>, Vec<MountingTruth>) {
    let g = s.centrifuge.site.gravity_m_s2;
    let radius = s.centrifuge.radius_m;
    let k = &s.piga.coefficients;
    let two_orientation = s.arm_stretch_m_s2 != 0.0 || !s.mountings.is_empty();
    let c_total = c_r + s.arm_stretch_m_s2;
    let dk2_total = |radius_m: f64| delta_k2_rad_s_g2(k.k1_rad_s_g, c_total, radius_m, g);
    let radius_growth = two_orientation.then(|| RadiusGrowthTruth {
        c_r_m_s2: c_r,
        c_a_m_s2: s.arm_stretch_m_s2,
        c_m_s2: c_total,
        delta_k2_total_predicted_rad_s_g2: dk2_total(radius),
    });
    let mounting_truths = s
        .mountings
        .iter()
        .zip(mountings)
        .zip(mounted)
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
    (radius_growth, mounting_truths)
}
