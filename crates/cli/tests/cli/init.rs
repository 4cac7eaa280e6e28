//! `init` on the lab variants of docs/YOUR-DATA.md, with known truth: the simulated campaign
//! of its worked examples (C_r = 1.2e-6 m·s²) rewritten as labs export them. For each, `init` writes a configuration that, with the geometry filled
//! in, gives C_r within 3σ of the truth; or it states what it could not determine. Bad input
//! (an empty folder, a file of unknown shape, two files at one rate, a header without units)
//! is explained file by file and nothing is written.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub(crate) use test_support::Scratch;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn cli(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(args)
        .output()
        .expect("runs")
}

/// One simulated recording: its declared rate and samples (time s, gap µm, angle deg).
#[derive(Clone)]
struct Simulated {
    rate: f64,
    rows: Vec<(f64, f64, f64)>,
}

/// The simulated campaign of docs/YOUR-DATA.md's worked examples (C_r = 1.2e-6 m·s², six
/// rates, 72 s each at 200 Hz, an encoder, start angle 40°), written by `simulate` into `dir`.
fn simulate_into(dir: &Path) {
    let scenario = dir.join("lab.ron");
    std::fs::write(
        &scenario,
        r#"(
    name: "lab", seed: 11,
    centrifuge: (radius_m: 2.5, site: (latitude_deg: 39.9, earth_rate_rad_s: 7.292115e-5, gravity_m_s2: 9.8)),
    error_motion: Coefficients((dr_xs_m: 5.6e-6, dr_ys_m: -1.97e-6, c_r_m_s2: 1.2e-6, c_r_y_m_s2: 0.3e-6)),
    probe: (
        lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0, probe_direction: against_o1_x1),
        sample_rate_hz: 200.0, noise_um: 0.05, l0_um: 50.0,
        sleeve_harmonics: [(order: 2, c_um: 0.35, s_um: -0.12)],
        encoder_angle: true, start_angle_deg: 40.0,
    ),
    piga: (coefficients: (k0_rad_s: 0.0, k1_rad_s_g: 0.56, k2_rad_s_g2: 5.0e-7, k3_rad_s_g3: 0.0)),
    rates_deg_s: [20.1234, 40.1234, 80.1234, 110.1234, 160.1234, 200.1234], revolutions: 2, min_duration_s: 72.0,
)"#,
    )
    .unwrap();
    let out = cli(&[
        "simulate",
        "--config",
        scenario.to_str().unwrap(),
        "--out",
        dir.join("sim").to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The campaign's six recordings (simulated once per test process, in a scratch folder
/// removed after use).
fn simulated() -> Vec<Simulated> {
    static SIMULATED: std::sync::OnceLock<Vec<Simulated>> = std::sync::OnceLock::new();
    SIMULATED
        .get_or_init(|| {
            let scratch = Scratch::new("cli-init-simulated");
            simulate_into(&scratch.0);
            read_simulated(&scratch.0.join("sim"))
        })
        .clone()
}

/// The probe recordings `simulate` wrote into `dir`.
fn read_simulated(dir: &Path) -> Vec<Simulated> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let Some(rate) = name
            .strip_prefix("probe_")
            .and_then(|n| n.strip_suffix("deg_s.csv"))
        else {
            continue;
        };
        let text = std::fs::read_to_string(&path).unwrap();
        let rows = text
            .lines()
            .filter(|l| !l.starts_with('#'))
            .skip(1)
            .map(|l| {
                let v: Vec<f64> = l.split(',').map(|f| f.parse().unwrap()).collect();
                (v[0], v[1], v[2])
            })
            .collect();
        out.push(Simulated {
            rate: rate.parse().unwrap(),
            rows,
        });
    }
    out.sort_by(|a, b| a.rate.total_cmp(&b.rate));
    assert_eq!(out.len(), 6);
    out
}

/// The truth's C_r, m·s².
fn c_r_true() -> f64 {
    1.2e-6
}

/// Writes each recording into `dir` as `name(i, rate)`, `header`, then `row(i, t, gap, angle)`
/// lines ended by `eol`.
fn write_variant(
    dir: &Path,
    sims: &[Simulated],
    name: &dyn Fn(usize, f64) -> String,
    header: &str,
    eol: &str,
    row: &dyn Fn(usize, f64, f64, f64) -> String,
) {
    for (k, s) in sims.iter().enumerate() {
        let mut text = String::from(header);
        text.push_str(eol);
        for (i, &(t, g, a)) in s.rows.iter().enumerate() {
            text.push_str(&row(i, t, g, a));
            text.push_str(eol);
        }
        std::fs::write(dir.join(name(k, s.rate)), text).unwrap();
    }
}

/// The configuration's placeholders filled with the simulated centrifuge's geometry.
pub(crate) fn fill_in(text: &str) -> String {
    text.lines()
        .map(|line| {
            let (code, comment) = match line.find("//") {
                Some(at) => line.split_at(at),
                None => (line, ""),
            };
            if !code.contains("FILL_IN") {
                return line.to_owned();
            }
            let key = code.trim().split(':').next().unwrap_or("").trim();
            let value = match key {
                "radius_m" => "2.5",
                "g_m_s2" => "9.8",
                "k1_rad_s_g" => "0.56",
                "pivot_to_probe_mm" => "700.0",
                "probe_to_piga_mm" => "510.0",
                "probe_direction" => "against_o1_x1",
                "g_source" => "\"the simulation's 9.8 m/s²\"",
                // every Type B input is stated (a zero would need its reason)
                "radius_u_m" => "5.0e-6",
                "g_u_m_s2" => "1.0e-5",
                "rate_u_relative" => "1.0e-6",
                "pivot_to_probe_u_mm" | "probe_to_piga_u_mm" => "0.5",
                "probe_gain_u_relative" => "2.0e-3",
                _ => "0.0",
            };
            let filled = if key == "g_source" {
                format!("    g_source: {value},")
            } else {
                code.replacen("FILL_IN", value, 1)
            };
            format!("{filled}{comment}")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// `init` on `dir`, the placeholders filled, the study run: (C_r, σ(C_r), init's output).
fn init_and_study(dir: &Path) -> (f64, f64, String) {
    let out = cli(&["init", dir.to_str().unwrap()]);
    let printed = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "init failed:\n{printed}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let config = dir.join("study.ron");
    let text = std::fs::read_to_string(&config).unwrap();
    let filled = fill_in(&text);
    assert!(
        !filled
            .lines()
            .any(|l| l.split("//").next().unwrap_or("").contains("FILL_IN")),
        "{filled}"
    );
    std::fs::write(&config, filled).unwrap();
    let results = dir.join("out");
    let study = cli(&[
        "study",
        "--config",
        config.to_str().unwrap(),
        "--out",
        results.to_str().unwrap(),
    ]);
    assert!(
        study.status.success(),
        "study failed on\n{text}\n{}",
        String::from_utf8_lossy(&study.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(results.join("results.json")).unwrap())
            .unwrap();
    let fit = &json["phases"][0];
    (
        fit["c_r_m_s2"].as_f64().unwrap(),
        fit["c_r_sigma_m_s2"].as_f64().unwrap(),
        printed,
    )
}

#[track_caller]
fn assert_within_3_sigma(what: &str, dir: &Path) -> String {
    assert_within_3_sigma_of(what, dir, c_r_true())
}

#[track_caller]
fn assert_within_3_sigma_of(what: &str, dir: &Path, truth: f64) -> String {
    let (c, s, printed) = init_and_study(dir);
    assert!(
        (c - truth).abs() < 3.0 * s,
        "{what}: C_r = {c:e} ± {s:e}, truth {truth:e}"
    );
    printed
}

fn named(_: usize, rate: f64) -> String {
    format!("probe_{rate:08.4}deg_s.csv")
}

#[test]
fn documented_format() {
    let tmp = Scratch::new("cli-init-documented");
    write_variant(
        &tmp.0,
        &simulated(),
        &named,
        "time_s,gap_um,angle_deg",
        "\n",
        &|_, t, g, a| format!("{t:.9},{g:.9},{a:.9}"),
    );
    let printed = assert_within_3_sigma("documented", &tmp.0);
    assert!(
        printed.contains("encoder `angle_deg` in degrees"),
        "{printed}"
    );
    // The human output of init and check: snapshots, free of Rust identifiers.
    let folder = tmp.0.file_name().unwrap().to_string_lossy().into_owned();
    let tidy = |s: &str| {
        s.replace(&tmp.0.display().to_string(), "<tmp>")
            .replace(&folder, "<lab>")
    };
    let printed = tidy(&printed);
    assert!(
        crate::human::rust_identifiers(&printed).is_empty(),
        "{printed}"
    );
    insta::assert_snapshot!("init_documented", printed);
    let check = cli(&["check", tmp.0.join("study.ron").to_str().unwrap()]);
    assert!(
        check.status.success(),
        "{}",
        String::from_utf8_lossy(&check.stderr)
    );
    let text = tidy(&String::from_utf8_lossy(&check.stdout));
    assert!(crate::human::rust_identifiers(&text).is_empty(), "{text}");
    insta::assert_snapshot!("check_documented", text);
}

#[test]
fn european_daq_export() {
    // CRLF, five metadata lines, `;`, decimal comma, mm, an encoder in counts that wraps.
    let tmp = Scratch::new("cli-init-european");
    let header = "Messgerät: XY-3000\r\nDatum: 2025-03-01\r\nKanal: 2\r\nAbtastrate: 25 Hz\r\n\r\n\
                  Zeit [s];Spalt [mm];Winkel [cnt]";
    write_variant(
        &tmp.0,
        &simulated(),
        &named,
        header,
        "\r\n",
        &|_, t, g, a| {
            let counts = ((a / 360.0) * 1_048_576.0).round() as u64 % 1_048_576;
            format!("{t:.6};{:.9};{counts}", g / 1000.0).replace('.', ",")
        },
    );
    let printed = assert_within_3_sigma("european", &tmp.0);
    let config = std::fs::read_to_string(tmp.0.join("study.ron")).unwrap();
    assert!(config.contains("decimal: comma"), "{config}");
    assert!(config.contains("skip_lines: 5"), "{config}");
    assert!(config.contains("counts(per_rev: 1048576)"), "{config}");
    assert!(printed.contains("semicolon"), "{printed}");
}

#[test]
fn tab_separated_with_units_and_time_in_ms() {
    let tmp = Scratch::new("cli-init-tab-ms");
    write_variant(
        &tmp.0,
        &simulated(),
        &named,
        "Time (ms)\tGap [um]\tAngle [deg]",
        "\n",
        &|_, t, g, a| format!("{:.6}\t{g:.9}\t{a:.9}", t * 1000.0),
    );
    assert_within_3_sigma("tab, ms", &tmp.0);
    let config = std::fs::read_to_string(tmp.0.join("study.ron")).unwrap();
    assert!(config.contains("unit: ms"), "{config}");
}

#[test]
fn index_pulse_and_rates_measured() {
    // No rate in the names (`run_1.csv`…): each rate is measured from the index pulses.
    let tmp = Scratch::new("cli-init-index");
    let sims = simulated();
    for (k, s) in sims.iter().enumerate() {
        let mut text = String::from("time_s,gap_um,index\n");
        for (i, &(t, g, a)) in s.rows.iter().enumerate() {
            let prev = if i == 0 { a } else { s.rows[i - 1].2 };
            let pulse = u8::from(i > 0 && a < prev);
            text += &format!("{t:.9},{g:.9},{pulse}\n");
        }
        std::fs::write(tmp.0.join(format!("run_{}.csv", k + 1)), text).unwrap();
    }
    let printed = assert_within_3_sigma("index pulse", &tmp.0);
    assert!(printed.contains("index pulse `index`"), "{printed}");
    let config = std::fs::read_to_string(tmp.0.join("study.ron")).unwrap();
    assert!(config.contains("measured from"), "{config}");
}

#[test]
fn encoder_counts_and_epoch_time() {
    let tmp = Scratch::new("cli-init-epoch");
    write_variant(
        &tmp.0,
        &simulated(),
        &named,
        "timestamp [s],gap [um],encoder",
        "\n",
        &|_, t, g, a| {
            let counts = ((a / 360.0) * 4096.0).round() as u64 % 4096;
            format!("{:.6},{g:.9},{counts}", 1.7e9 + t)
        },
    );
    assert_within_3_sigma("epoch time, counts", &tmp.0);
    let config = std::fs::read_to_string(tmp.0.join("study.ron")).unwrap();
    assert!(config.contains("counts(per_rev: 4096)"), "{config}");
    assert!(config.contains("epoch time"), "{config}");
}

#[test]
fn a_header_without_units_leaves_placeholders_the_study_refuses() {
    let tmp = Scratch::new("cli-init-no-units");
    write_variant(
        &tmp.0,
        &simulated(),
        &named,
        "time,gap,angle",
        "\n",
        &|_, t, g, a| format!("{t:.9},{g:.9},{a:.9}"),
    );
    let out = cli(&["init", tmp.0.to_str().unwrap()]);
    assert!(out.status.success());
    let printed = String::from_utf8_lossy(&out.stdout);
    // Each value to fill in is listed with its field and its question.
    assert!(
        printed.contains(
            "`phases[0].points.format.time.unit`: In which unit is the time column: s, ms, us or ns?"
        ),
        "{printed}"
    );
    let config = tmp.0.join("study.ron");
    let text = std::fs::read_to_string(&config).unwrap();
    assert!(text.contains("has no unit"), "{text}");
    // With only the geometry filled in, the study still refuses the units left open.
    let partly: String = text
        .lines()
        .map(|l| {
            if l.contains("unit: FILL_IN") {
                l.to_owned()
            } else {
                fill_in(l)
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(&config, partly).unwrap();
    let study = cli(&[
        "study",
        "--config",
        config.to_str().unwrap(),
        "--out",
        tmp.0.join("out").to_str().unwrap(),
    ]);
    assert!(!study.status.success());
    let err = String::from_utf8_lossy(&study.stderr);
    assert!(err.contains("not filled in"), "{err}");
    assert!(
        err.contains(
            "`phases[0].points.format.gap.unit`: In which unit is the gap column: nm, um, mm or m?"
        ),
        "{err}"
    );
    assert!(!tmp.0.join("out").exists());
}

#[test]
fn bad_input_is_explained_file_by_file_and_nothing_is_written() {
    // An empty folder.
    let empty = Scratch::new("cli-init-empty");
    let out = cli(&["init", empty.0.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no data file"));

    // Two files at one rate, and a file of unknown shape.
    let tmp = Scratch::new("cli-init-bad");
    let sims = simulated();
    write_variant(
        &tmp.0,
        &sims[..2],
        &named,
        "time_s,gap_um,angle_deg",
        "\n",
        &|_, t, g, a| format!("{t:.9},{g:.9},{a:.9}"),
    );
    std::fs::copy(
        tmp.0.join(named(0, sims[0].rate)),
        tmp.0.join("probe_020.1234deg_s_2.csv"),
    )
    .unwrap();
    std::fs::write(tmp.0.join("notes.txt"), "spindle serviced 2025-02\nok\n").unwrap();
    let out = cli(&["init", tmp.0.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let printed = String::from_utf8_lossy(&out.stdout);
    assert!(printed.contains("notes.txt: unknown shape"), "{printed}");
    assert!(
        printed.contains("probe_020.1234deg_s_2.csv: claims the rate 20.1234 deg/s"),
        "{printed}"
    );
    assert!(!tmp.0.join("study.ron").exists());
}

#[test]
fn no_overwrite_without_force() {
    let tmp = Scratch::new("cli-init-force");
    write_variant(
        &tmp.0,
        &simulated(),
        &named,
        "time_s,gap_um,angle_deg",
        "\n",
        &|_, t, g, a| format!("{t:.9},{g:.9},{a:.9}"),
    );
    assert!(cli(&["init", tmp.0.to_str().unwrap()]).status.success());
    let study = tmp.0.join("study.ron");
    let written = std::fs::read_to_string(&study).unwrap();
    // The configuration init wrote, edited below its first line.
    let first_line = written.lines().next().unwrap();
    let edited = format!("{first_line}\nmy edits\n");
    std::fs::write(&study, &edited).unwrap();
    let again = cli(&["init", tmp.0.to_str().unwrap()]);
    assert_eq!(again.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&again.stderr).contains("--force"));
    assert_eq!(std::fs::read_to_string(&study).unwrap(), edited);
    assert!(
        cli(&["init", tmp.0.to_str().unwrap(), "--force"])
            .status
            .success()
    );
    assert_eq!(std::fs::read_to_string(&study).unwrap(), written);
    // A file init did not write is left alone even with --force (issue 32).
    std::fs::write(&study, "my edits").unwrap();
    let forced = cli(&["init", tmp.0.to_str().unwrap(), "--force"]);
    assert_eq!(forced.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&forced.stderr).contains("was not written by init"),
        "{}",
        String::from_utf8_lossy(&forced.stderr)
    );
    assert_eq!(std::fs::read_to_string(&study).unwrap(), "my edits");
}

/// The simulated campaign's C_r (fixtures/campaign/truth.json), whose probe recordings
/// `fixtures/recordings/binary/make_campaign.py` wrote as TDMS (npTDMS) and MAT (scipy).
fn campaign_c_r() -> f64 {
    let truth: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root().join("fixtures/campaign/truth.json")).unwrap(),
    )
    .unwrap();
    truth["scenario"]["error_motion"]["Coefficients"]["c_r_m_s2"]
        .as_f64()
        .unwrap()
}

/// The files of `fixtures/recordings/NAME` copied into a scratch folder.
fn copied(name: &str) -> Scratch {
    let tmp = Scratch::new(name);
    for entry in std::fs::read_dir(root().join("fixtures/recordings").join(name)).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, tmp.0.join(path.file_name().unwrap())).unwrap();
    }
    tmp
}

#[test]
fn tdms_from_an_ni_logger() {
    // Group `Spindle`, channels `Gap` and `Angle` with unit_string properties, no time
    // channel: the times are the waveform's (wf_increment).
    let tmp = copied("campaign-tdms");
    let printed = assert_within_3_sigma_of("TDMS", &tmp.0, campaign_c_r());
    assert!(printed.contains("encoder `Angle` in degrees"), "{printed}");
    let config = std::fs::read_to_string(tmp.0.join("study.ron")).unwrap();
    for want in [
        "group: \"Spindle\"",
        "waveform_time: true",
        "gap: (column: \"Gap\", unit: um)",
        "the file's unit `um`",
    ] {
        assert!(config.contains(want), "{want}:\n{config}");
    }
}

#[test]
fn mat_files_with_units_in_the_variable_names() {
    // Top-level `time_ms`, `gap_mm`, `angle_rad`.
    let tmp = copied("campaign-mat");
    assert_within_3_sigma_of("MAT", &tmp.0, campaign_c_r());
    let config = std::fs::read_to_string(tmp.0.join("study.ron")).unwrap();
    for want in [
        "time: (column: \"time_ms\", unit: ms)",
        "gap: (column: \"gap_mm\", unit: mm)",
        "angle: encoder(column: \"angle_rad\", unit: rad)",
    ] {
        assert!(config.contains(want), "{want}:\n{config}");
    }
}

#[test]
fn a_probe_in_volts_in_tdms_or_mat_asks_for_its_sensitivity() {
    let tmp = Scratch::new("cli-init-volts");
    for (file, unit) in [
        ("probe_120deg_s_volts.tdms", "the file's unit `V`"),
        ("probe_120deg_s_volts.mat", "the unit `V` in its name"),
    ] {
        let from = root().join("fixtures/recordings/binary").join(file);
        let out = tmp.0.join(format!("{file}.ron"));
        let run = cli(&[
            "init",
            from.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let config = std::fs::read_to_string(&out).unwrap();
        assert!(
            config.contains("unit: volts(sensitivity: FILL_IN, sensitivity_unit: um_per_v, u_sensitivity: FILL_IN)"),
            "{config}"
        );
        assert!(config.contains(unit), "{config}");
        assert!(config.contains("probe's sensitivity"), "{config}");
        // the angle zero, optional, is explained and left out (0 taken, and said)
        assert!(
            config.contains("        // angle_zero_deg: 0.0,\n"),
            "{config}"
        );
        // `check` names the field left to fill in and asks for it.
        let check = cli(&["check", out.to_str().unwrap()]);
        assert_eq!(check.status.code(), Some(1));
        let printed = String::from_utf8_lossy(&check.stdout);
        assert!(
            printed.contains(
                "`phases[0].points.format.gap.unit` is not filled in (FILL_IN): What are the \
                 probe's sensitivity and its standard uncertainty"
            ),
            "{printed}"
        );
        // the direction still to fill in is described by what to check at the machine, not
        // as the stand-in `check` reads in its place
        assert!(
            printed.contains(
                "direction (`lever.probe_direction`): not filled in: `against_o1_x1` if the \
                 probe's gap closes (its reading falls) when the spindle moves towards the PIGA"
            ),
            "{printed}"
        );
    }
}

#[test]
fn an_unreadable_binary_file_is_named_with_what_was_wrong() {
    let tmp = Scratch::new("cli-init-binary-bad");
    std::fs::write(tmp.0.join("probe_120deg_s.tdms"), b"TDSm\x02").unwrap();
    std::fs::write(tmp.0.join("probe_60deg_s.mat"), b"not a mat file").unwrap();
    let out = cli(&["init", tmp.0.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let printed = String::from_utf8_lossy(&out.stdout);
    assert!(
        printed.contains("probe_120deg_s.tdms: cannot be read as an NI TDMS file"),
        "{printed}"
    );
    assert!(
        printed.contains("probe_60deg_s.mat: cannot be read as a MATLAB file"),
        "{printed}"
    );
    assert!(!tmp.0.join("study.ron").exists());
}

#[test]
fn seven_recordings_with_one_fault_give_one_grouped_message() {
    // Seven files written with a decimal comma, a configuration that does not say so.
    let tmp = Scratch::new("cli-init-seven");
    let mut files = String::new();
    for k in 0..7 {
        let name = format!("probe_{}deg_s.csv", 20 * (k + 1));
        let mut text = String::from("time_s;gap_um;angle_deg\n");
        for i in 0..50 {
            text += &format!("0,{i:03};1,5;{}\n", i * 3);
        }
        std::fs::write(tmp.0.join(&name), text).unwrap();
        files += &format!("(rate_deg_s: {}.0, file: {name:?}), ", 20 * (k + 1));
    }
    let config = tmp.0.join("study.ron");
    std::fs::write(
        &config,
        format!(
            "(name: \"seven\", radius_m: 2.5, g_m_s2: 9.8, k1_rad_s_g: 0.56,
              lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0),
              phases: [(name: \"spindle\", points: recordings((format: (delimiter: ';'), files: [{files}])))])"
        ),
    )
    .unwrap();
    let out = cli(&["check", config.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let printed = String::from_utf8_lossy(&out.stdout);
    assert!(printed.contains("7 problems (1 distinct)"), "{printed}");
    assert_eq!(printed.matches("cannot parse").count(), 1, "{printed}");
    assert!(
        printed.contains(
            "the same in 7 files: probe_20deg_s.csv, probe_40deg_s.csv, probe_60deg_s.csv, \
             probe_80deg_s.csv, probe_100deg_s.csv, probe_120deg_s.csv, probe_140deg_s.csv"
        ),
        "{printed}"
    );
    // The study reports them the same way.
    let study = cli(&[
        "study",
        "--config",
        config.to_str().unwrap(),
        "--out",
        tmp.0.join("out").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&study.stderr);
    assert!(err.contains("7 problems (1 distinct)"), "{err}");
    assert!(err.contains("the same in 7 files"), "{err}");
}

/// A PIGA table as a German DAQ exports it (metadata lines, `;`, decimal comma, units in
/// the header, a label column) beside the campaign's probe recordings: `init` writes its
/// `format` block, and the study's calibration equals the one from the same rows written
/// plainly (`rate_deg_s,output_rad_s`), which `init` writes with the column keys.
#[test]
fn a_german_piga_table_export_is_written_as_its_format_block() {
    let export = root().join("fixtures/recordings/piga-table-de/piga_export_utf8.csv");
    let text = std::fs::read_to_string(&export).unwrap();
    let mut plain = String::from("rate_deg_s,output_rad_s,Lage\n");
    for line in text.lines().skip(6).filter(|l| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split(';').collect();
        plain += &format!(
            "{},{},{}\n",
            f[0].replace(',', "."),
            f[1].replace(',', "."),
            f[3]
        );
    }
    let calibration = |tag: &str, name: &str, contents: &str| {
        let tmp = Scratch::new(tag);
        for entry in std::fs::read_dir(root().join("fixtures/campaign")).unwrap() {
            let path = entry.unwrap().path();
            if path
                .file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("probe_")
            {
                std::fs::copy(&path, tmp.0.join(path.file_name().unwrap())).unwrap();
            }
        }
        std::fs::write(tmp.0.join(name), contents).unwrap();
        let (_, _, printed) = init_and_study(&tmp.0);
        let config = std::fs::read_to_string(tmp.0.join("study.ron")).unwrap();
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(tmp.0.join("out/results.json")).unwrap())
                .unwrap();
        (json["calibration"].clone(), config, printed)
    };
    let (german, config, printed) = calibration("piga-de", "piga_export.csv", &text);
    let table = &config[config.find("table: (").unwrap()..config.find("compensate_with").unwrap()];
    assert!(table.contains("format: ("), "{table}");
    assert!(config.contains("decimal: comma"), "{config}");
    assert!(config.contains("skip_lines: 5"), "{config}");
    assert!(
        config.contains(r#"rate: (column: "Drehrate [°/s]", unit: deg_s)"#),
        "{config}"
    );
    assert!(config.contains(r#"label: "Lage""#), "{config}");
    assert!(printed.contains("PIGA table"), "{printed}");
    let (reference, config, _) = calibration("piga-plain", "piga.csv", &plain);
    assert!(config.contains(r#"rate_column: "rate_deg_s""#), "{config}");
    let table = &config[config.find("table: (").unwrap()..config.find("compensate_with").unwrap()];
    assert!(!table.contains("format"), "{table}");
    assert_eq!(german["points"], reference["points"]);
    assert_eq!(german["coefficients"], reference["coefficients"]);
    assert_eq!(german["delta_k2"], reference["delta_k2"]);
}

/// File names as labs and their systems write them — a backslash, quotes, non-ASCII letters —
/// are written into the study exactly (a RON string that reads back to the same name), and
/// the study reads the same files: `probe\080deg_s.csv` was once written as
/// `probe/080deg_s.csv`, another file.
#[test]
fn file_names_are_written_exactly_and_read_back_to_the_same_files() {
    let tmp = Scratch::new("cli-init-names");
    let names = [
        "probe\\020.1234deg_s.csv",
        "\"probe\"_040.1234deg_s.csv",
        "µprobe_080.1234deg_s.csv",
        "probe°_110.1234deg_s.csv",
        "probe'_160.1234deg_s.csv",
        "probe_200.1234deg_s.csv",
    ];
    write_variant(
        &tmp.0,
        &simulated(),
        &|k, _| names[k].to_owned(),
        "time_s,gap_um,angle_deg",
        "\n",
        &|_, t, g, a| format!("{t:.9},{g:.9},{a:.9}"),
    );
    let (c, s, _) = init_and_study(&tmp.0);
    assert!((c - c_r_true()).abs() < 3.0 * s, "C_r = {c:e} ± {s:e}");
    let config = tmp.0.join("study.ron");
    let text = std::fs::read_to_string(&config).unwrap();
    assert!(
        text.contains(r#"file: "probe\\020.1234deg_s.csv""#),
        "{text}"
    );
    assert!(
        text.contains(r#"file: "\"probe\"_040.1234deg_s.csv""#),
        "{text}"
    );
    assert!(
        text.contains(r#"file: "µprobe_080.1234deg_s.csv""#),
        "{text}"
    );
    // Read back by the study's own reader: the same names, each an existing file.
    let parsed = pipeline::StudyConfig::from_ron(&text, &config).unwrap();
    let pipeline::Points::Recordings(set) = &parsed.phases[0].points else {
        panic!("recordings");
    };
    let mut read: Vec<String> = set
        .files
        .iter()
        .map(|f| f.file.to_str().unwrap().to_owned())
        .collect();
    read.sort();
    let mut written: Vec<String> = names.iter().map(|n| (*n).to_owned()).collect();
    written.sort();
    assert_eq!(read, written);
    // The study read those files: their SHA-256 in its provenance.
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.0.join("out/results.json")).unwrap())
            .unwrap();
    for record in json["provenance"]["inputs"].as_array().unwrap() {
        let path = Path::new(record["path"].as_str().unwrap());
        let bytes = std::fs::read(path).unwrap();
        assert_eq!(
            record["sha256"].as_str().unwrap(),
            pipeline::FileDigest::of(&bytes).sha256,
            "{}",
            path.display()
        );
        assert!(names.contains(&path.file_name().unwrap().to_str().unwrap()));
    }
}

/// A folder with one run's probe recordings and several PIGA tables that name no mounting
/// (the two-unit fixture): `init` writes a `units` list, one unit per table labelled from its
/// name, each with its k1 to fill in; filled in, the study calibrates both units.
#[test]
fn a_folder_with_several_units_tables_becomes_a_units_list() {
    let tmp = Scratch::new("cli-init-units");
    for entry in std::fs::read_dir(root().join("fixtures/units")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "csv") {
            std::fs::copy(&path, tmp.0.join(path.file_name().unwrap())).unwrap();
        }
    }
    let out = cli(&["init", tmp.0.to_str().unwrap()]);
    let printed = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{printed}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        printed.contains("2 units calibrated in one run (A, B)"),
        "{printed}"
    );
    assert!(printed.contains("units[1].k1_rad_s_g"), "{printed}");
    let config = tmp.0.join("study.ron");
    let text = std::fs::read_to_string(&config).unwrap();
    assert!(text.contains("    units: ["), "{text}");
    assert!(text.contains("label: \"A\""), "{text}");
    assert!(text.contains("file: \"piga_B.csv\""), "{text}");
    assert!(!text.contains("\n    calibration: ("), "{text}");
    std::fs::write(&config, fill_in(&text)).unwrap();
    let results = tmp.0.join("out");
    let study = cli(&[
        "study",
        "--config",
        config.to_str().unwrap(),
        "--out",
        results.to_str().unwrap(),
    ]);
    assert!(
        study.status.success(),
        "{}",
        String::from_utf8_lossy(&study.stderr)
    );
    for unit in ["A", "B"] {
        assert!(
            results
                .join("units")
                .join(unit)
                .join("results.json")
                .is_file()
        );
    }
}
