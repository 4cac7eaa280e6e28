//! Bad scenarios give typed errors that name the file and the field; never a panic.

use std::path::{Path, PathBuf};
use test_support::Scratch;

use edge_io::EdgeIoError;
use simulate::{Scenario, SimulateError};

use crate::common::{POST_BALANCE, PRE_BALANCE, post_balance};

const FILE: &str = "bad.ron";

/// Parses the post-balance fixture with one text substitution (which must apply).
fn parse_with(from: &str, to: &str) -> Result<simulate::LoadedScenario, SimulateError> {
    assert!(POST_BALANCE.contains(from), "fixture lacks {from:?}");
    Scenario::parse(&POST_BALANCE.replacen(from, to, 1), Path::new(FILE))
}

/// Asserts an `InvalidField` naming `bad.ron` and `field`.
#[track_caller]
fn assert_invalid(result: Result<simulate::LoadedScenario, SimulateError>, field: &str) {
    match result {
        Err(SimulateError::InvalidField { path, field: f, .. }) => {
            assert_eq!(path, PathBuf::from(FILE));
            assert_eq!(f, field);
        }
        other => panic!("expected InvalidField for {field}, got {other:?}"),
    }
}

#[test]
fn fixtures_are_valid() {
    assert!(Scenario::parse(POST_BALANCE, Path::new("post")).is_ok());
    assert!(Scenario::parse(PRE_BALANCE, Path::new("pre")).is_ok());
}

#[test]
fn unknown_field_is_a_parse_error_naming_it() {
    let r = parse_with("l0_um: 50.0,", "l0_um: 50.0, gain_um_per_v: 2.0,");
    match r {
        Err(SimulateError::Parse {
            path,
            line,
            message,
            ..
        }) => {
            assert_eq!(path, PathBuf::from(FILE));
            assert!(message.contains("gain_um_per_v"), "{message}");
            let expect = POST_BALANCE
                .lines()
                .position(|l| l.contains("l0_um"))
                .unwrap()
                + 1;
            assert_eq!(line, expect);
        }
        other => panic!("expected Parse, got {other:?}"),
    }
    // unknown fields are refused inside nested sections too
    assert!(matches!(
        parse_with("gravity_m_s2: 9.8", "gravity_m_s2: 9.8, g_units: 1.0"),
        Err(SimulateError::Parse { .. })
    ));
    assert!(matches!(
        parse_with("c_phi_s2: 5.0e-9,", "c_phi_s2: 5.0e-9, c_z: 1.0,"),
        Err(SimulateError::Parse { .. })
    ));
}

#[test]
fn missing_field_is_a_parse_error() {
    let r = parse_with("    revolutions: 2,\n", "");
    match r {
        Err(SimulateError::Parse { message, .. }) => {
            assert!(message.contains("revolutions"), "{message}");
        }
        other => panic!("expected Parse, got {other:?}"),
    }
}

#[test]
fn negative_or_zero_radius() {
    assert_invalid(
        parse_with("radius_m: 2.5", "radius_m: -2.5"),
        "centrifuge.radius_m",
    );
    assert_invalid(
        parse_with("radius_m: 2.5", "radius_m: 0.0"),
        "centrifuge.radius_m",
    );
}

#[test]
fn no_rates() {
    let r = parse_with(
        "rates_deg_s: [10.0, 40.0, 60.0, 80.1234, 110.1234, 135.0, 160.1234, 200.1234]",
        "rates_deg_s: []",
    );
    match r {
        Err(SimulateError::EmptyList { path, field }) => {
            assert_eq!(path, PathBuf::from(FILE));
            assert_eq!(field, "rates_deg_s");
        }
        other => panic!("expected EmptyList, got {other:?}"),
    }
}

#[test]
fn non_finite_numbers_in_the_file() {
    assert_invalid(
        parse_with("noise_um: 0.01", "noise_um: NaN"),
        "probe.noise_um",
    );
    assert_invalid(
        parse_with("sample_rate_hz: 1000.0", "sample_rate_hz: inf"),
        "probe.sample_rate_hz",
    );
    assert_invalid(
        parse_with("latitude_deg: 39.9", "latitude_deg: NaN"),
        "centrifuge.site.latitude_deg",
    );
    assert_invalid(
        parse_with("k2_rad_s_g2: 5.0e-7", "k2_rad_s_g2: -inf"),
        "piga.coefficients.k2_rad_s_g2",
    );
    assert_invalid(
        parse_with("135.0, 160.1234", "NaN, 160.1234"),
        "rates_deg_s[5]",
    );
    assert_invalid(
        parse_with("(order: 3, c_um: 0.08", "(order: 3, c_um: inf"),
        "probe.sleeve_harmonics[1].c_um",
    );
    // a non-finite error-motion coefficient is refused by kinematics, named by its field
    match parse_with("c_r_m_s2: -4.05e-8", "c_r_m_s2: NaN") {
        Err(SimulateError::Kinematics {
            path,
            field,
            source: kinematics::KinematicsError::NonFinite { field: inner, .. },
        }) => {
            assert_eq!(path, PathBuf::from(FILE));
            assert_eq!(field, "error_motion");
            assert_eq!(inner, "c_r_m_s2");
        }
        other => panic!("expected Kinematics, got {other:?}"),
    }
}

#[test]
fn other_domains() {
    assert_invalid(
        parse_with("latitude_deg: 39.9", "latitude_deg: 91.0"),
        "centrifuge.site.latitude_deg",
    );
    assert_invalid(
        parse_with("gravity_m_s2: 9.8", "gravity_m_s2: 0.0"),
        "centrifuge.site.gravity_m_s2",
    );
    assert_invalid(
        parse_with("noise_um: 0.01", "noise_um: -0.01"),
        "probe.noise_um",
    );
    assert_invalid(
        parse_with("noise_rad_s: 0.0", "noise_rad_s: -1e-9"),
        "piga.noise_rad_s",
    );
    assert_invalid(
        parse_with("(order: 6,", "(order: 9,"),
        "probe.sleeve_harmonics[3].order",
    );
    assert_invalid(
        parse_with("(order: 6,", "(order: 1,"),
        "probe.sleeve_harmonics[3].order",
    );
    assert_invalid(
        parse_with("(order: 6,", "(order: 3,"),
        "probe.sleeve_harmonics[3].order",
    );
    assert_invalid(
        parse_with("amplitude_deg: 0.3", "amplitude_deg: 60.0"),
        "probe.speed_ripple.amplitude_deg",
    );
    assert_invalid(
        parse_with("revolutions: 2", "revolutions: 0"),
        "revolutions",
    );
    assert_invalid(
        parse_with("135.0, 160.1234", "-135.0, 160.1234"),
        "rates_deg_s[5]",
    );
    // 7 Hz gives 12.6 samples per turn at 200 deg/s: enough for the order-4 fit, too few for
    // the 6th sleeve harmonic
    assert_invalid(
        parse_with("sample_rate_hz: 1000.0", "sample_rate_hz: 7.0"),
        "probe.sample_rate_hz",
    );
    // a billion samples are refused before any allocation
    assert_invalid(
        parse_with("revolutions: 2", "revolutions: 9000"),
        "revolutions",
    );
}

#[test]
fn duplicate_rates() {
    match parse_with("135.0, 160.1234", "40.0, 160.1234") {
        Err(SimulateError::DuplicateRate {
            field,
            first,
            rate_deg_s,
            ..
        }) => {
            assert_eq!(field, "rates_deg_s[5]");
            assert_eq!(first, "rates_deg_s[1]");
            assert_eq!(rate_deg_s, 40.0);
        }
        other => panic!("expected DuplicateRate, got {other:?}"),
    }
    // distinct rates that would share a file name are reported as such, naming both
    let result = parse_with("10.0, 40.0,", "10.00001, 10.00002,");
    let message = result
        .as_ref()
        .map_or_else(ToString::to_string, |_| String::new());
    assert!(!message.contains("twice"), "{message}");
    assert!(
        message.contains("10.00001") && message.contains("10.00002"),
        "{message}"
    );
    match result {
        Err(SimulateError::RecordingNameCollision {
            field,
            first,
            rate_deg_s,
            first_rate_deg_s,
            file_name,
            ..
        }) => {
            assert_eq!(field, "rates_deg_s[1]");
            assert_eq!(first, "rates_deg_s[0]");
            assert_eq!((first_rate_deg_s, rate_deg_s), (10.00001, 10.00002));
            assert_eq!(file_name, "probe_010.0000deg_s.csv");
        }
        other => panic!("expected RecordingNameCollision, got {other:?}"),
    }
}

#[test]
fn probe_lengths_are_bounded() {
    for (from, to, field) in [
        ("l0_um: 50.0", "l0_um: 1e308", "probe.l0_um"),
        ("l0_um: 50.0", "l0_um: -1.1e9", "probe.l0_um"),
        ("noise_um: 0.01", "noise_um: 1e308", "probe.noise_um"),
        ("noise_um: 0.01", "noise_um: 2e9", "probe.noise_um"),
        (
            "(order: 6,",
            "(order: 6, c_um: 1e300, s_um: 0.0), (order: 7,",
            "probe.sleeve_harmonics[3].c_um",
        ),
    ] {
        assert_invalid(parse_with(from, to), field);
    }
    // a kilometre is still accepted, and it simulates to finite gaps
    let mut s = parse_with("l0_um: 50.0", "l0_um: -1e9").unwrap();
    s.scenario.probe.noise_um = 1e9;
    s.scenario.rates_deg_s = vec![200.0];
    s.scenario.revolutions = 1;
    s.scenario.min_duration_s = 0.0;
    let sim = simulate::simulate(&s).unwrap();
    assert!(sim.recordings[0].gap_um.iter().all(|g| g.is_finite()));
}

#[test]
fn a_rate_too_fast_for_the_sample_rate_is_named() {
    // 1e300 deg/s: blamed on the rate, not on min_duration_s or the sample rate
    match parse_with("135.0, 160.1234", "1e300, 160.1234") {
        Err(SimulateError::RateTooFast {
            field,
            rate_deg_s,
            need,
            max_rate_deg_s,
            ..
        }) => {
            assert_eq!(field, "rates_deg_s[5]");
            assert_eq!(rate_deg_s, 1e300);
            // order 4 with drift: 2·4 + 2 parameters, one more sample than that
            assert_eq!(need, 11);
            approx::assert_relative_eq!(max_rate_deg_s, 1000.0 * 360.0 / 11.0);
        }
        other => panic!("expected RateTooFast, got {other:?}"),
    }
    // 5 Hz gives 9.0 samples per turn at 200.1234 deg/s, too few for the order-4 fit
    match parse_with("sample_rate_hz: 1000.0", "sample_rate_hz: 5.0") {
        Err(SimulateError::RateTooFast {
            field,
            samples_per_revolution,
            ..
        }) => {
            assert_eq!(field, "rates_deg_s[7]");
            approx::assert_relative_eq!(samples_per_revolution, 5.0 * 360.0 / 200.1234);
        }
        other => panic!("expected RateTooFast, got {other:?}"),
    }
    // the bound is 32727.27 deg/s at 1 kHz: just below it the rate passes (and the 6th sleeve
    // harmonic then blames the sample rate), just above it the rate is refused
    assert_invalid(parse_with("200.1234]", "32727.0]"), "probe.sample_rate_hz");
    assert!(matches!(
        parse_with("200.1234]", "32728.0]"),
        Err(SimulateError::RateTooFast { field, .. }) if field == "rates_deg_s[7]"
    ));
}

#[test]
fn bad_physical_imbalance_and_lever() {
    let text = PRE_BALANCE.replacen(
        "radial_stiffness_n_m: 5.0e7",
        "radial_stiffness_n_m: 0.0",
        1,
    );
    match Scenario::parse(&text, Path::new(FILE)) {
        Err(SimulateError::Kinematics {
            field,
            source: kinematics::KinematicsError::NotPositive { field: inner, .. },
            ..
        }) => {
            assert_eq!(field, "error_motion");
            assert_eq!(inner, "radial_stiffness_n_m");
        }
        other => panic!("expected Kinematics, got {other:?}"),
    }
    match parse_with("pivot_to_probe_mm: 700.0", "pivot_to_probe_mm: -700.0") {
        Err(SimulateError::Harmonics {
            field,
            source: harmonics::HarmonicsError::InvalidGeometry { field: inner, .. },
            ..
        }) => {
            assert_eq!(field, "probe.lever");
            assert_eq!(inner, "pivot_to_probe_mm");
        }
        other => panic!("expected Harmonics, got {other:?}"),
    }
}

#[test]
fn scenarios_built_in_code_are_checked_too() {
    let mut s = post_balance().scenario;
    s.centrifuge.radius_m = f64::NAN;
    assert!(matches!(
        s.check(Path::new("code")),
        Err(SimulateError::InvalidField { field, .. }) if field == "centrifuge.radius_m"
    ));
}

#[test]
fn simulate_checks_a_scenario_altered_after_loading() {
    let mut loaded = post_balance();
    loaded.scenario.probe.sample_rate_hz = 0.0;
    match simulate::simulate(&loaded) {
        Err(SimulateError::InvalidField { field, .. }) => {
            assert_eq!(field, "probe.sample_rate_hz");
        }
        other => panic!("expected InvalidField, got {other:?}"),
    }
}

#[test]
fn unreadable_file_is_a_read_error() {
    let missing = Path::new("/nonexistent/scenario.ron");
    match Scenario::load(missing) {
        Err(SimulateError::File(EdgeIoError::Read { path, .. })) => assert_eq!(path, missing),
        other => panic!("expected Read, got {other:?}"),
    }
}

#[test]
fn a_scenario_with_a_byte_order_mark_loads() {
    let dir = Scratch::new("simulate-bom");
    let path = dir.0.join("post-balance.ron");
    std::fs::write(&path, format!("\u{FEFF}{POST_BALANCE}")).unwrap();
    assert_eq!(
        Scenario::load(&path).unwrap().scenario,
        post_balance().scenario
    );
}

#[test]
fn a_scenario_above_the_cap_is_refused_unread() {
    let dir = Scratch::new("simulate-huge");
    let path = dir.0.join("huge.ron");
    // 2 GiB of holes: read whole, it would be gigabytes of memory before the RON error
    std::fs::File::create(&path)
        .unwrap()
        .set_len(2 << 30)
        .unwrap();
    match Scenario::load(&path) {
        Err(SimulateError::File(EdgeIoError::TooLarge {
            path: p,
            limit_bytes,
            size_bytes,
        })) => {
            assert_eq!(p, path);
            assert_eq!(limit_bytes, edge_io::CONFIG_MAX_BYTES);
            assert_eq!(size_bytes, Some(2 << 30));
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
}

/// Valid but extreme scenarios whose results overflow double precision: before, `simulate`
/// returned them and `piga.csv` held `inf`, `truth.json` `null`s; now a typed error names the
/// quantity and the inputs, with short numbers, and nothing is written.
#[test]
fn scenarios_whose_results_overflow_are_named_errors() {
    for (from, to, input) in [
        ("c_r_m_s2: -4.05e-8", "c_r_m_s2: 1e300", "c_r_m_s2 = 1e300"),
        ("gravity_m_s2: 9.8", "gravity_m_s2: 1e-300", "1e-300"),
        ("radius_m: 2.5", "radius_m: 1e-300", "radius_m = 1e-300"),
    ] {
        let loaded = parse_with(from, to).expect("the scenario itself is valid");
        let err = simulate::simulate(&loaded).unwrap_err();
        let message = err.to_string();
        assert!(
            matches!(
                err,
                SimulateError::AccelModel { .. }
                    | SimulateError::Identify { .. }
                    | SimulateError::Kinematics { .. }
                    | SimulateError::NonFiniteOutput { .. }
            ),
            "{to}: {err:?}"
        );
        assert!(message.contains("not finite"), "{to}: {message}");
        assert!(message.contains(input), "{to}: {message}");
        assert!(
            !message.contains("0000000000"),
            "{to}: a long expansion in {message}"
        );
    }
}

/// 1e5 distinct rates, then one repeated and one whose file name collides: the duplicate and
/// collision checks are linear (before: pairwise, 80 s for 2e4 rates, 1e5 hung).
#[test]
fn a_hundred_thousand_rates_are_checked_in_linear_time() {
    let n = 100_000;
    // 1e-4 deg/s apart from 50 deg/s: distinct rates with distinct file names (4 decimals).
    let rates: Vec<String> = (0..n)
        .map(|i| format!("{:.4}", 50.0 + f64::from(i) * 1e-4))
        .collect();
    let list = |extra: &str| format!("rates_deg_s: [{}, {extra}]", rates.join(", "));
    let from = "rates_deg_s: [10.0, 40.0, 60.0, 80.1234, 110.1234, 135.0, 160.1234, 200.1234]";
    match parse_with(from, &list("50.0003")) {
        Err(SimulateError::DuplicateRate { field, first, .. }) => {
            assert_eq!(field, format!("rates_deg_s[{n}]"));
            assert_eq!(first, "rates_deg_s[3]");
        }
        other => panic!("expected DuplicateRate, got {other:?}"),
    }
    match parse_with(from, &list("50.00030001")) {
        Err(SimulateError::RecordingNameCollision { field, first, .. }) => {
            assert_eq!(field, format!("rates_deg_s[{n}]"));
            assert_eq!(first, "rates_deg_s[3]");
        }
        other => panic!("expected RecordingNameCollision, got {other:?}"),
    }
}

#[test]
fn a_second_probe_at_the_first_probes_depth_names_its_field() {
    let at = |mm: &str| {
        parse_with(
            "revolutions:",
            &format!("second_probe: (probe_to_piga_mm: {mm}), revolutions:"),
        )
    };
    assert!(at("1110.0").is_ok());
    assert_invalid(at("510.0"), "second_probe.probe_to_piga_mm");
    assert_invalid(at("inf"), "second_probe.probe_to_piga_mm");
}
