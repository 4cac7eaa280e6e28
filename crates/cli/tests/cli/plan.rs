//! `cargo xtask plan`: the fixture plan's --json output (snapshot), its files, and an
//! infeasible plan as an error naming the binding constraint.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn out_dir(tag: &str) -> PathBuf {
    std::env::temp_dir().join(format!("xtask-plan-{tag}-{}", std::process::id()))
}

#[test]
fn plan_json_snapshot_and_files() {
    let dir = out_dir("json");
    let out = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args([
            "plan",
            "--config",
            "fixtures/plans/paper-centrifuge.ron",
            "--compare-rates",
            "10,60,80.1234,110.1234,160.1234,200.1234",
            "--simulate",
            "1000",
            "--json",
            "--out",
        ])
        .arg(&dir)
        .current_dir(root())
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("plan.json")).unwrap()).unwrap();
    assert_eq!(value, written, "--json prints plan.json");
    let csv = std::fs::read_to_string(dir.join("run_sheet.csv")).unwrap();
    assert_eq!(csv.lines().count(), 11, "a header and ten points");
    assert!(
        std::fs::read_to_string(dir.join("run_sheet.md"))
            .unwrap()
            .contains("| total |")
    );
    std::fs::remove_dir_all(&dir).unwrap();
    let ratio = value["simulation"]["ratio"].as_f64().unwrap();
    assert!((ratio - 1.0).abs() < 0.1, "simulated/predicted {ratio}");
    value.as_object_mut().unwrap().remove("config");
    insta::assert_snapshot!(serde_json::to_string_pretty(&value).unwrap());
}

#[test]
fn an_unreachable_target_names_the_binding_constraint() {
    let dir = out_dir("bad");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(root().join("fixtures/plans/paper-centrifuge.ron"))
        .unwrap()
        .replace("u95_k2_rad_s_g2: 1.0e-6", "u95_k2_rad_s_g2: 1.0e-8");
    let config = dir.join("tight.ron");
    std::fs::write(&config, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(["plan", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(dir.join("out"))
        .current_dir(root())
        .output()
        .expect("runs");
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("target.u95_k2_rad_s_g2"), "{stderr}");
    assert!(
        stderr.contains("s of centrifuge time would reach it"),
        "{stderr}"
    );
}

/// A two-orientation plan (issue 20): the human output in words (snapshot), its run sheet
/// with both mountings, and the probe method beside it in plan.json.
#[test]
fn two_orientation_plan_in_words() {
    let dir = out_dir("two");
    let out = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args([
            "plan",
            "--config",
            "fixtures/plans/two_orientation.ron",
            "--simulate",
            "1000",
            "--out",
        ])
        .arg(&dir)
        .current_dir(root())
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout)
        .unwrap()
        .replace(&dir.display().to_string(), "<tmp>");
    let found = crate::human::rust_identifiers(&text);
    assert!(found.is_empty(), "Rust identifiers {found:?} in\n{text}");
    let value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("plan.json")).unwrap()).unwrap();
    let csv = std::fs::read_to_string(dir.join("run_sheet.csv")).unwrap();
    let md = std::fs::read_to_string(dir.join("run_sheet.md")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(csv.lines().count(), 17, "a header and sixteen points");
    assert_eq!(csv.lines().filter(|l| l.contains(",ia_out,")).count(), 8);
    assert!(md.contains("turn the PIGA round"), "{md}");
    let two = &value["two_orientation"];
    assert!(
        two["probe_method"]["compensated"]["u_rad_s_g2"]
            .as_f64()
            .unwrap()
            > 0.0
    );
    let ratio = value["simulation"]["ratio"].as_f64().unwrap();
    assert!((ratio - 1.0).abs() < 0.1, "simulated/predicted {ratio}");
    insta::assert_snapshot!("two_orientation_plan", text);
}

/// Runs `plan` on `config`, killed (and the test failed) after 60 s.
fn plan_within(config: &Path, extra: &[&str]) -> (Option<i32>, String) {
    let dir = out_dir(&format!("capped-{}", extra.len()));
    let mut child = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(["plan", "--config"])
        .arg(config)
        .args(extra)
        .arg("--out")
        .arg(&dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .current_dir(root())
        .spawn()
        .expect("runs");
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > std::time::Duration::from_secs(60) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("plan {extra:?} did not end within 60 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (status.code(), stderr)
}

#[test]
fn a_simulate_count_beyond_the_cap_is_refused_with_its_cost() {
    // Issue 32: 1e7 took about five minutes and 2^64 - 1 never ended.
    for (plan, n, cost) in [
        ("paper-centrifuge.ron", "10000000", "about 300 s of CPU"),
        ("paper-centrifuge.ron", "18446744073709551615", "s of CPU"),
        ("two_orientation.ron", "10000000", "about 1500 s of CPU"),
    ] {
        let config = root().join("fixtures/plans").join(plan);
        let (code, stderr) = plan_within(&config, &["--simulate", n]);
        assert_eq!(code, Some(1), "{stderr}");
        assert!(
            stderr.contains(&format!("--simulate {n}"))
                && stderr.contains("at most 1000000 simulated campaigns are run")
                && stderr.contains(cost),
            "{stderr}"
        );
    }
}

#[test]
fn huge_numbers_in_a_plan_are_short_in_its_errors() {
    let text = std::fs::read_to_string(root().join("fixtures/plans/paper-centrifuge.ron")).unwrap();
    let dir = out_dir("huge");
    std::fs::create_dir_all(&dir).unwrap();
    for (from, to, expect) in [
        (
            "budget_s: 3600.0",
            "budget_s: 1e300",
            "schedule.budget_s = 1e300",
        ),
        (
            "g_m_s2: 9.8",
            "g_m_s2: 1e300",
            "centrifuge.g_m_s2 = 1e300: must lie within 9.7…9.9 m/s²",
        ),
    ] {
        let config = dir.join("plan.ron");
        std::fs::write(&config, text.replace(from, to)).unwrap();
        let (code, stderr) = plan_within(&config, &[]);
        assert_eq!(code, Some(1), "{stderr}");
        assert!(stderr.contains(expect), "{stderr}");
        assert!(!stderr.contains("0000000000"), "{stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
