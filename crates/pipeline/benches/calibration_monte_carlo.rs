//! Monte Carlo throughput of the PIGA calibration's measurement model (issue 11).
//!
//! `cargo bench -p pipeline --bench calibration_monte_carlo`. A typical study, held in memory:
//! the spindle's C_r fitted to radius errors at eight rates (ν = 6), and the PIGA table at
//! the same eight rates, each measured twice (sixteen rows: the eq. 18 fit then has ν = 10,
//! so that the multivariate t of its coefficients has a finite variance; one reading per rate
//! leaves ν = 2). [`pipeline::calibration_measurement`] sets the evaluation up as the study
//! does — fourteen inputs: six normal Type B inputs, C_r drawn from t with ν = 6, k1 (fitted,
//! so exact here) and the six eq. 18 coefficients as one multivariate t group — and the
//! benchmark times `uncertainty::monte_carlo` with 10⁶ trials per iteration, on one thread and
//! on all threads.
//!
//! With `CALIBRATION_MC_JSON=path`, the inputs and one run's results are written to `path`
//! first, for `bench/calibration_numpy.py`, which runs the same Monte Carlo in NumPy.

use std::collections::HashMap;
use std::hint::black_box;
use std::path::{Path, PathBuf};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use pipeline::{CalibrationMeasurement, DataSource, Inputs, StudyConfig};
use recording::{Recording, RecordingError, RecordingFormat, Table, TableFormat};
use uncertainty::{Distribution, Dof, McOptions, Trials, monte_carlo};

const TRIALS: u64 = 1_000_000;
const RATES_DEG_S: [f64; 8] = [25.0, 50.0, 75.0, 100.0, 125.0, 150.0, 175.0, 200.0];
const RADIUS_M: f64 = 2.5;
const G_M_S2: f64 = 9.8;

/// A deterministic wiggle in [−½, ½), so that both fits have residuals.
fn wiggle(i: usize) -> f64 {
    ((i * 7919) % 13) as f64 / 13.0 - 0.5
}

/// The PIGA table: eq. 18 with fixed coefficients at each rate twice, plus 10⁻⁸ rad/s of
/// wiggle.
fn piga_csv() -> String {
    let k = [1e-5, 2e-6, 0.56 * RADIUS_M / G_M_S2, -3e-9, 5e-7, 2e-8];
    let mut csv = String::from("rate_deg_s,output_rad_s\n");
    for (i, &rate_deg_s) in RATES_DEG_S.iter().chain(&RATES_DEG_S).enumerate() {
        let w = units::deg_s_to_rad_s(rate_deg_s);
        let a = RADIUS_M * w * w / G_M_S2;
        let output_rad_s = k[0]
            + k[1] * w
            + k[2] * w * w
            + k[3] * w.powi(3)
            + k[4] * a * a
            + k[5] * a.powi(3)
            + 1e-8 * wiggle(i);
        csv.push_str(&format!("{rate_deg_s},{output_rad_s}\n"));
    }
    csv
}

/// The study: radius errors `1 µm + C_r·ω²` (C_r = 1.6·10⁻⁶ m·s²) with 0.2 µm of wiggle.
fn study_text() -> String {
    let points: Vec<String> = RATES_DEG_S
        .iter()
        .enumerate()
        .map(|(i, &rate_deg_s)| {
            let w = units::deg_s_to_rad_s(rate_deg_s);
            let radius_error_um = 1.0 + 1.6e-6 * w * w * 1e6 + 0.2 * wiggle(i + 3);
            format!("(rate_deg_s: {rate_deg_s}, radius_error_um: {radius_error_um})")
        })
        .collect();
    format!(
        r#"(
    name: "typical", radius_m: {RADIUS_M}, g_m_s2: {G_M_S2}, k1_rad_s_g: 0.56,
    lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0),
    phases: [(name: "spindle", points: radius_error([{}]))],
    calibration: (table: (file: "piga.csv"), compensate_with: "spindle", k1: fitted, seed: 1,
                  trials: fixed({TRIALS})),
    uncertainty: (radius_u_m: 5.0e-6, g_u_m_s2: 1.0e-5, g_source: "nominal",
                  rate_u_relative: 1.0e-6, pivot_to_probe_u_mm: 0.5, probe_to_piga_u_mm: 0.5,
                  probe_gain_u_relative: 2.0e-3),
)"#,
        points.join(", ")
    )
}

/// The PIGA table in memory; no recordings.
struct Memory {
    files: HashMap<PathBuf, Vec<u8>>,
}

impl DataSource for Memory {
    fn recording(
        &self,
        path: &Path,
        format: &RecordingFormat,
    ) -> Result<Recording, RecordingError> {
        recording::parse_recording(&self.files[path], path, format)
    }

    fn table(&self, path: &Path, format: &TableFormat) -> Result<Table, RecordingError> {
        recording::parse_table(&self.files[path], path, format)
    }
}

fn measurement() -> CalibrationMeasurement {
    let source = Path::new("/nonexistent/typical.ron");
    let memory = Memory {
        files: HashMap::from([(
            PathBuf::from("/nonexistent/piga.csv"),
            piga_csv().into_bytes(),
        )]),
    };
    let config = StudyConfig::from_ron(&study_text(), source).expect("valid study");
    let inputs = Inputs::new(config, source, &memory).expect("valid inputs");
    pipeline::calibration_measurement(&inputs)
        .expect("the calibration sets up")
        .expect("the study has a calibration")
}

/// The inputs, their correlation and one run's results as JSON, for the NumPy script.
fn write_json(path: &Path, m: &CalibrationMeasurement, options: &McOptions) {
    let q = m.inputs.quantities();
    let inputs: Vec<serde_json::Value> = q
        .iter()
        .map(|q| {
            serde_json::json!({
                "name": q.name,
                "value": q.value,
                "u": q.standard_uncertainty,
                "dof": match q.dof { Dof::Finite(nu) => Some(nu), Dof::Infinite => None },
                "distribution": match q.distribution {
                    Distribution::Normal => "normal",
                    Distribution::Rectangular => "rectangular",
                    Distribution::StudentT => "t",
                },
            })
        })
        .collect();
    let n = q.len();
    let correlation: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| m.inputs.correlation(i, j)).collect())
        .collect();
    let mc = monte_carlo(&m.model, &m.inputs, options).expect("monte carlo");
    let outputs: Vec<serde_json::Value> = mc
        .outputs
        .iter()
        .map(|o| {
            serde_json::json!({
                "name": o.name,
                "mean": o.estimate,
                "u": o.standard_uncertainty,
                "low95": o.coverage_interval.0,
                "high95": o.coverage_interval.1,
            })
        })
        .collect();
    let json = serde_json::json!({
        "inputs": inputs,
        "correlation": correlation,
        // The study fits k1 (the model ignores the "k1 (given)" input).
        "k1_fitted": true,
        "rust": { "trials": mc.trials, "seed": options.seed, "outputs": outputs },
    });
    std::fs::write(path, serde_json::to_string_pretty(&json).expect("json"))
        .expect("write CALIBRATION_MC_JSON");
}

fn bench(c: &mut Criterion) {
    let m = measurement();
    let options = McOptions {
        trials: Trials::Fixed(TRIALS),
        ..m.options
    };
    if let Some(path) = std::env::var_os("CALIBRATION_MC_JSON") {
        write_json(Path::new(&path), &m, &options);
    }
    let mut group = c.benchmark_group("calibration_monte_carlo_8_rates");
    group.throughput(Throughput::Elements(TRIALS));
    group.sample_size(10);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    for threads in [1, cores] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        group.bench_function(format!("{threads}_threads"), |b| {
            b.iter(|| {
                pool.install(|| monte_carlo(black_box(&m.model), &m.inputs, &options))
                    .expect("monte carlo")
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
