//! Determinism and the written files: recordings in the loader's format, piga.csv, truth.json.

use std::collections::BTreeMap;
use std::path::Path;

use approx::assert_relative_eq;
use edge_io::EdgeIoError;
use harmonics::{FitConfig, analyze};
use recording::{RecordingFormat, parse_recording};
use simulate::{Scenario, SimulateError, piga_csv_text, simulate, write_simulation};

use crate::common::{modified, post_balance, pre_balance};

#[test]
fn the_same_seed_gives_the_same_simulation_and_another_seed_does_not() {
    let base = modified(&post_balance(), |s| s.piga.noise_rad_s = 1e-7);
    let a = simulate(&base).unwrap();
    let b = simulate(&base).unwrap();
    assert_eq!(a, b);
    let other = modified(&base, |s| s.seed += 1);
    let c = simulate(&other).unwrap();
    assert_ne!(a.recordings[0].gap_um, c.recordings[0].gap_um);
    assert_ne!(a.piga[0].output_rad_s, c.piga[0].output_rad_s);
    // the noise-free parts do not depend on the seed
    assert_eq!(a.truth.rates[3].a_x_g, c.truth.rates[3].a_x_g);
    assert_eq!(a.recordings[0].time_s, c.recordings[0].time_s);
}

#[test]
fn each_rate_has_its_own_noise_stream() {
    // dropping and reordering rates leaves the other rates' noise unchanged
    let base = modified(&post_balance(), |s| s.piga.noise_rad_s = 1e-7);
    let changed = modified(&base, |s| {
        s.rates_deg_s.remove(0);
        s.rates_deg_s.reverse();
    });
    let a = simulate(&base).unwrap();
    let b = simulate(&changed).unwrap();
    for (rec, row) in b.recordings.iter().zip(&b.piga) {
        let i = a
            .recordings
            .iter()
            .position(|r| r.rate_deg_s == rec.rate_deg_s)
            .unwrap();
        assert_eq!(rec, &a.recordings[i]);
        assert_eq!(row, &a.piga[i]);
    }
}

#[test]
fn the_probe_noise_has_the_scenario_sigma() {
    let loaded = post_balance();
    let s = &loaded.scenario;
    let sim = simulate(&loaded).unwrap();
    for (rec, truth) in sim.recordings.iter().zip(&sim.truth.rates) {
        let angles = rec.angle_rad().unwrap();
        let h = truth.probe_first_harmonic;
        let residual: Vec<f64> = rec
            .gap_um
            .iter()
            .zip(&angles)
            .map(|(g, th)| {
                let sleeve: f64 = s
                    .probe
                    .sleeve_harmonics
                    .iter()
                    .map(|k| {
                        let x = k.order as f64 * th;
                        k.c_um * x.cos() + k.s_um * x.sin()
                    })
                    .sum();
                g - (s.probe.l0_um + h.dc1_um * th.cos() + h.ds1_um * th.sin() + sleeve)
            })
            .collect();
        let n = residual.len() as f64;
        let mean = residual.iter().sum::<f64>() / n;
        let sd = (residual.iter().map(|r| r * r).sum::<f64>() / n).sqrt();
        // mean within 5 standard errors of 0; σ̂/σ within 5 standard errors (≈ 1/√(2n)) of 1
        assert!(mean.abs() < 5.0 * s.probe.noise_um / n.sqrt(), "{mean}");
        assert_relative_eq!(sd / s.probe.noise_um, 1.0, epsilon = 5.0 / (2.0 * n).sqrt());
    }
}

#[test]
fn recordings_round_trip_through_the_recording_loader() {
    let sim = simulate(&pre_balance()).unwrap();
    let format = RecordingFormat::default();
    for rec in [&sim.recordings[0], &sim.recordings[7]] {
        let mut bytes = Vec::new();
        rec.write_csv(&mut bytes).unwrap();
        let text = std::str::from_utf8(&bytes).unwrap();
        assert!(text.starts_with("time_s,gap_um,angle_deg\n"));
        let loaded = parse_recording(&bytes, Path::new(&rec.file_name), &format).unwrap();
        assert_eq!(loaded.len(), rec.time_s.len());
        let angle = loaded.angle_rad.as_ref().unwrap();
        for i in [0, 1, rec.time_s.len() / 2, rec.time_s.len() - 1] {
            assert!((loaded.time_s[i] - rec.time_s[i]).abs() <= 5e-10);
            assert!((loaded.gap[i] - rec.gap_um[i]).abs() <= 5e-10);
            let d = (angle[i] - rec.angle_deg.as_ref().unwrap()[i].to_radians()).abs();
            assert!(d <= 1e-10, "{d}");
        }
        // the file's harmonics agree with the in-memory ones to the printed precision
        let config = FitConfig {
            order: 5,
            ..FitConfig::default()
        };
        let from_file = analyze(&loaded.signal(0.0), &config).unwrap();
        let mem_angle = rec.angle_rad().unwrap();
        let in_memory = analyze(
            &harmonics::ProbeSignal {
                time_s: &rec.time_s,
                gap: &rec.gap_um,
                angle: harmonics::SpindleAngle::Encoder(&mem_angle),
            },
            &config,
        )
        .unwrap();
        assert_relative_eq!(from_file.mean.c[0], in_memory.mean.c[0], epsilon = 1e-9);
        assert_relative_eq!(from_file.mean.s[0], in_memory.mean.s[0], epsilon = 1e-9);
    }
    // without the encoder column the file has two columns
    let no_encoder = modified(&pre_balance(), |s| s.probe.encoder_angle = false);
    let sim = simulate(&no_encoder).unwrap();
    let mut bytes = Vec::new();
    sim.recordings[3].write_csv(&mut bytes).unwrap();
    assert!(bytes.starts_with(b"time_s,gap_um\n"));
    let loaded = parse_recording(&bytes, Path::new("x.csv"), &format).unwrap();
    assert!(loaded.angle_rad.is_none());
}

#[test]
fn the_committed_small_recordings_are_the_simulator_output() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let scenario = Scenario::load(&root.join("fixtures/scenarios/pre-balance-small.ron")).unwrap();
    let sim = simulate(&scenario).unwrap();
    let dir = root.join("fixtures/recordings/pre-balance-small");
    let regenerate = "regenerate with `cargo xtask simulate --config \
        fixtures/scenarios/pre-balance-small.ron --out fixtures/recordings/pre-balance-small`";
    for rec in &sim.recordings {
        let mut bytes = Vec::new();
        rec.write_csv(&mut bytes).unwrap();
        let committed = std::fs::read(dir.join(&rec.file_name)).unwrap();
        assert!(
            committed == bytes,
            "{} differs: {regenerate}",
            rec.file_name
        );
    }
    let piga = std::fs::read_to_string(dir.join("piga.csv")).unwrap();
    assert!(
        piga == piga_csv_text(&sim.piga),
        "piga.csv differs: {regenerate}"
    );
}

#[test]
fn a_recording_the_reader_would_refuse_is_not_written() {
    let sim = simulate(&pre_balance()).unwrap();
    let mut rec = sim.recordings[0].clone();
    rec.gap_um.pop();
    let mut bytes = Vec::new();
    let e = rec.write_csv(&mut bytes).unwrap_err();
    assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput);
    assert!(matches!(
        e.get_ref()
            .and_then(|e| e.downcast_ref::<recording::RecordingError>()),
        Some(recording::RecordingError::ColumnLengths { .. })
    ));
    assert!(bytes.is_empty());
}

#[test]
fn piga_csv_is_exact_and_parses_back() {
    let base = modified(&post_balance(), |s| s.piga.noise_rad_s = 1e-6);
    let sim = simulate(&base).unwrap();
    let text = piga_csv_text(&sim.piga);
    assert!(text.starts_with("rate_deg_s,output_rad_s\n"));
    // the PIGA-table reader reads every number back exactly
    let table = recording::parse_piga_table(text.as_bytes(), Path::new("piga.csv")).unwrap();
    assert_eq!(table.len(), sim.piga.len());
    for ((r, y), row) in table
        .rate_deg_s
        .iter()
        .zip(&table.output_rad_s)
        .zip(&sim.piga)
    {
        assert_eq!(*r, row.rate_deg_s);
        assert_eq!(*y, row.output_rad_s);
    }
    // the noise is added to the exact mean
    for (row, truth) in sim.piga.iter().zip(&sim.truth.rates) {
        assert_eq!(row.output_rad_s, truth.output_rad_s);
        assert!((row.output_rad_s - truth.output_noise_free_rad_s).abs() < 6e-6);
        assert_ne!(row.output_rad_s, truth.output_noise_free_rad_s);
    }
}

#[test]
fn truth_holds_the_exact_inputs_and_the_predicted_delta_k2() {
    let loaded = pre_balance();
    let sim = simulate(&loaded).unwrap();
    let t = &sim.truth;
    let s = &loaded.scenario;
    let (r, g) = (s.centrifuge.radius_m, s.centrifuge.site.gravity_m_s2);
    let k1 = s.piga.coefficients.k1_rad_s_g;
    // the physical imbalance resolves to C_r = m·R_cm/k_r (eq. 1)
    assert_relative_eq!(t.c_r_m_s2, 32.0 * 2.5 / 5.0e7, max_relative = 1e-12);
    assert_relative_eq!(
        t.delta_k2_predicted_rad_s_g2,
        k1 * t.c_r_m_s2 * g / (r * r),
        max_relative = 1e-15
    );
    assert_eq!(t.rates.len(), s.rates_deg_s.len());
    for p in &t.rates {
        let w = p.rate_rad_s;
        let fo = kinematics::Chain::new(
            &kinematics::Centrifuge {
                radius_m: r,
                site: s.centrifuge.site,
                error_motion: loaded.error_motion,
            },
            w,
        )
        .unwrap()
        .first_order();
        // eq. 14 plus the Coriolis term, to second order in the error motion
        assert_relative_eq!(p.a_x_g, fo.a_x_g + fo.coriolis_a_x_g, max_relative = 1e-9);
        assert_relative_eq!(p.a_nominal_g, r * w * w / g, max_relative = 1e-15);
        assert_relative_eq!(
            p.radius_error_um,
            (t.error_motion.dr_xs_m + t.c_r_m_s2 * w * w) * 1e6,
            max_relative = 1e-12
        );
    }
    // every scenario parameter is in truth.json
    let json: serde_json::Value = serde_json::to_value(t).unwrap();
    assert_eq!(json["scenario"]["seed"], s.seed);
    assert_eq!(json["scenario"]["probe"]["l0_um"], 50.0);
    assert!(json["scenario"]["error_motion"]["Physical"]["mass_kg"].is_number());
    assert!(json["rates"][0]["a_x_g"].is_number());
    assert!(json["rates"][0]["omega_i_rad_s"].is_number());
    assert!(json["rates"][0]["probe_first_harmonic"]["dc1_um"].is_number());
}

#[test]
fn write_simulation_writes_every_file() {
    let sim = simulate(&post_balance()).unwrap();
    let dir = std::env::temp_dir().join(format!("centrifuge-cal-simulate-{}", std::process::id()));
    let files = write_simulation(&dir, &sim).unwrap();
    assert_eq!(files.recordings.len(), sim.recordings.len());
    assert_eq!(
        files.recordings[0].file_name().unwrap(),
        "probe_010.0000deg_s.csv"
    );
    assert_eq!(
        files.recordings[7].file_name().unwrap(),
        "probe_200.1234deg_s.csv"
    );
    let piga = std::fs::read_to_string(&files.piga_csv).unwrap();
    assert_eq!(piga, piga_csv_text(&sim.piga));
    let truth: simulate::Truth =
        serde_json::from_str(&std::fs::read_to_string(&files.truth_json).unwrap()).unwrap();
    assert_eq!(truth.scenario.name, sim.truth.scenario.name);
    assert_eq!(truth.rates.len(), sim.truth.rates.len());
    assert_relative_eq!(
        truth.delta_k2_predicted_rad_s_g2,
        sim.truth.delta_k2_predicted_rad_s_g2,
        max_relative = 1e-15
    );
    let rec = recording::load_recording(&files.recordings[7], &RecordingFormat::default()).unwrap();
    assert_eq!(rec.len(), sim.recordings[7].time_s.len());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every file of a directory with its bytes.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect()
}

#[test]
fn a_failed_write_leaves_the_previous_simulation_and_a_good_one_replaces_it() {
    let parent = std::env::temp_dir().join(format!("simulate-atomic-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&parent);
    let dir = parent.join("out");
    let first = simulate(&post_balance()).unwrap();
    write_simulation(&dir, &first).unwrap();
    let before = snapshot(&dir);
    // the recordings, piga.csv, truth.json and the record of what was written (issue 32)
    assert_eq!(before.len(), first.recordings.len() + 3);
    assert!(before.contains_key(edge_io::OUTPUT_RECORD));

    // a scenario without the first rate, failing at its last file
    let fewer = modified(&post_balance(), |s| {
        s.rates_deg_s.remove(0);
    });
    let second = simulate(&fewer).unwrap();
    {
        let _fail = edge_io::fault::fail_writing("truth.json");
        match write_simulation(&dir, &second) {
            Err(SimulateError::File(EdgeIoError::Write { path, .. })) => {
                assert_eq!(path, dir.join("truth.json"));
            }
            other => panic!("expected a write error, got {other:?}"),
        }
    }
    assert_eq!(snapshot(&dir), before, "the previous files, byte for byte");

    let files = write_simulation(&dir, &second).unwrap();
    let after = snapshot(&dir);
    assert_eq!(after.len(), second.recordings.len() + 3);
    assert!(
        !after.contains_key("probe_010.0000deg_s.csv"),
        "the dropped rate's recording is removed"
    );
    assert_eq!(
        after["truth.json"],
        std::fs::read(&files.truth_json).unwrap()
    );
    let siblings: Vec<_> = std::fs::read_dir(&parent).unwrap().collect();
    assert_eq!(siblings.len(), 1, "no staging directory is left");
    std::fs::remove_dir_all(&parent).unwrap();
}
