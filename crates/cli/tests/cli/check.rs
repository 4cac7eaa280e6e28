//! `centrifuge-cal check STUDY.ron`: what a study will do, in words (issue 31). Every study of
//! the repository is snapshotted whole; studies written here cover each kind of phase, data
//! set, recording format and section the fixtures do not (their description only: the files
//! they name do not exist, so `check` then lists problems, which other tests cover).

use std::path::{Path, PathBuf};

use test_support::Scratch;

use crate::human::{assert_words, run};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

/// The studies of the repository, relative to its root: `fixtures/studies/*.ron` and the
/// lab export's study.
fn studies() -> Vec<String> {
    let mut found: Vec<String> = std::fs::read_dir(root().join("fixtures/studies"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".ron"))
        .map(|name| format!("fixtures/studies/{name}"))
        .collect();
    found.sort();
    found.push("fixtures/lab-mm-comma/study.ron".to_owned());
    found
}

/// `check` of every study the repository has: accepted, in words (no Rust identifier), and
/// as snapshotted.
#[test]
fn check_every_study_of_the_repository() {
    let tmp = Scratch::new("cli-check-studies");
    let studies = studies();
    assert!(studies.len() >= 10, "{studies:?}");
    for study in &studies {
        let (text, ok) = run(&["check", study], &tmp.0);
        assert!(ok, "{study}: {text}");
        assert_words(study, &text);
        let name = Path::new(study)
            .with_extension("")
            .to_string_lossy()
            .replace(['/', '.'], "_");
        insta::assert_snapshot!(format!("check_{name}"), text);
    }
}

/// The description `check` prints of the study `text` (written to a scratch file): its
/// output up to the first blank line (what follows lists the problems with the files).
fn describe(tag: &str, text: &str) -> String {
    let tmp = Scratch::new(tag);
    let path = tmp.0.join("study.ron");
    std::fs::write(&path, text).unwrap();
    let (out, _) = run(&["check", path.to_str().unwrap()], &tmp.0);
    let end = out.find("\n\n").expect("a description, then a blank line");
    out[..=end].to_owned()
}

/// One unit: every kind of phase, every recording format's delimiter, decimal mark, unit
/// and angle source, a calibration from raw recordings with k1 given, the two-orientation
/// section under its former name with incomplete data sets, mountings by label and angles
/// without compensation, and the mechanism, balance and counterweight.
const ONE_UNIT: &str = r#"(
    name: "variants",
    radius_m: 2.5,
    g_m_s2: 9.8,
    k1_rad_s_g: 0.56,
    lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0, probe_direction: along_o1_x1,
            angle_zero_deg: 12.5),
    radius_model: three_term,
    phases: [
        (name: "blanks", points: recordings((
            format: (delimiter: whitespace, time: (column: "t", unit: ms),
                     gap: (column: "g", unit: nm),
                     angle: encoder(column: "enc", unit: counts(per_rev: 4096))),
            fit: (order: 3, drift: false),
            files: [(rate_deg_s: 10.0, file: "a.csv"), (rate_deg_s: 20.5, file: "b.csv")],
        ))),
        (name: "tabs", points: recordings((
            format: (delimiter: '\t', decimal: comma, skip_lines: 3,
                     time: (column: "t", unit: us),
                     gap: (column: "v", unit: volts(sensitivity: 8.0, sensitivity_unit: v_per_mm,
                                                   u_sensitivity: 0.04)),
                     angle: index_pulse(column: "idx")),
            files: [(rate_deg_s: 30.0, file: "c.csv")],
        ))),
        (name: "declared", points: recordings((
            format: (delimiter: ';', gap: (column: "g", unit: m),
                     angle: rate(start_angle_deg: 15.0)),
            files: [(rate_deg_s: 40.0, file: "d.csv")],
        ))),
        (name: "radians", points: recordings((
            format: (time: (column: "t", unit: ns), gap: (column: "g", unit: mm),
                     angle: encoder(column: "a", unit: rad, optional: false)),
            files: [],
        ))),
        (name: "harm", points: first_harmonic([(rate_deg_s: 10.0, dc1_um: 1.0, ds1_um: 0.5)])),
        (name: "radius", points: radius_error([
            (rate_deg_s: 10.0, radius_error_um: 1.0),
            (rate_deg_s: 20.0, radius_error_um: 1.5),
        ])),
        (name: "change", points: radius_change(from_rate_deg_s: 10.0, to_rate_deg_s: 100.0,
                                               change_um: 2.0)),
    ],
    calibration: (
        recordings: (files: [(rate_deg_s: 10.0, file: "p1.csv"), (rate_deg_s: 20.0, file: "p2.csv")]),
        compensate_with: "harm",
        k1: given(k1_rad_s_g: 0.57, u_rad_s_g: 0.001),
    ),
    uncertainty: (radius_u_m: 1e-6, g_source: "the site's survey"),
    symmetric: (
        orientations: [
            (orientation: ia_out, recordings: (files: [(rate_deg_s: 10.0, file: "o.csv")])),
            (radius_m: 2.5),
        ],
        compare_with: "radius",
    ),
    mountings: (
        kind: pendulous(unit: milli_ampere),
        terms: ["k2", "delta_o"],
        compensate: false,
        list: [
            (label: "on the fixture's first face", preset: "ia_in", table: (file: "m1.csv")),
            (angles: (azimuth_deg: 90.0, elevation_deg: 10.0, roll_deg: 0.0), radius_m: 2.4),
        ],
    ),
    mechanism: (k2_rad_s_g2: 1e-6, rates_deg_s: [10.0, 20.0]),
    balance: (initial: "harm", correction_radius_m: 2.5),
    counterweight: (phase: "change", radial_stiffness_n_m: 5e7, stiffness_source: "a guess",
                    correction_radius_m: 2.5),
)"#;

/// Several units (one with a radius that is not finite, shown as it is), the two-orientation
/// section under its name, mountings compensated with a named phase.
const SEVERAL_UNITS: &str = r#"(
    name: "several",
    k1_rad_s_g: 0.56,
    phases: [
        (name: "spindle", points: first_harmonic([(rate_deg_s: 10.0, dc1_um: 1.0, ds1_um: 0.5)])),
    ],
    two_orientation: (
        orientations: [
            (orientation: ia_in, radius_m: 2.5, table: (file: "in.csv")),
            (orientation: ia_out, radius_m: 2.6, table: (file: "out.csv")),
        ],
    ),
    mountings: (
        kind: piga,
        terms: [],
        compensate_with: "spindle",
        list: [(preset: "ia_45", radius_m: 2.5, table: (file: "m.csv")), ()],
    ),
    units: [
        (
            label: "A",
            k1_rad_s_g: 0.55,
            radius_m: 2.4,
            calibration: (recordings: (files: [(rate_deg_s: 10.0, file: "a.csv")]),
                          compensate_with: "spindle"),
            two_orientation: (
                orientations: [(orientation: ia_in, recordings: (files: []))],
                compare_with: "spindle",
            ),
        ),
        (
            label: "B",
            k1_rad_s_g: 0.57,
            radius_m: inf,
            calibration: (compensate_with: "spindle"),
        ),
    ],
)"#;

/// `check`'s words for what the fixtures do not hold.
#[test]
fn check_describes_every_kind_of_section() {
    for (name, study) in [("one_unit", ONE_UNIT), ("several_units", SEVERAL_UNITS)] {
        let text = describe(&format!("cli-check-{name}"), study);
        insta::assert_snapshot!(format!("check_kinds_{name}"), text);
    }
}

/// Text a terminal would obey: a colour change and a right-to-left override.
const EVIL: &str = "x\u{1b}[31my\u{202e}z";

/// Whether `text` holds a character of [`EVIL`] as it is (not written visibly).
fn raw(text: &str) -> bool {
    text.contains('\u{1b}') || text.contains('\u{202e}')
}

/// Every free text of a study that `check` prints — names, labels, paths, the delimiter,
/// column names, `g_source`, presets and terms, the certificate's fields — is written visibly
/// (`edge_io::visible`): an escape sequence or a bidirectional override in the study file
/// cannot recolour or reorder the terminal.
#[test]
fn check_writes_every_text_of_the_study_visibly() {
    let study = format!(
        r#"(
    name: "{EVIL}",
    k1_rad_s_g: 0.56,
    phases: [
        (name: "p{EVIL}", points: recordings((
            format: (delimiter: '{esc}', time: (column: "t{EVIL}", unit: s),
                     gap: (column: "g{EVIL}", unit: um), angle: encoder(column: "a{EVIL}")),
            files: [(rate_deg_s: 10.0, file: "f{EVIL}.csv")],
        ))),
        (name: "q", points: recordings((
            format: (angle: index_pulse(column: "i{EVIL}")),
            files: [(rate_deg_s: 10.0, file: "f.csv")],
        ))),
    ],
    calibration: (table: (file: "c{EVIL}.csv"), compensate_with: "p{EVIL}"),
    uncertainty: (g_source: "{EVIL}"),
    two_orientation: (
        orientations: [(orientation: ia_in, table: (file: "o{EVIL}.csv"))],
        compare_with: "p{EVIL}",
    ),
    mountings: (
        kind: piga,
        terms: ["{EVIL}"],
        compensate_with: "p{EVIL}",
        list: [(label: "l{EVIL}", table: (file: "m{EVIL}.csv")), (preset: "{EVIL}")],
    ),
)"#,
        esc = '\u{1b}'
    );
    let text = describe("cli-check-hostile", &study);
    assert!(!raw(&text), "{text:?}");
    assert!(text.contains(r"x\u{1b}[31my<U+202E>z"), "{text}");
    // every field above is printed, each escaped (the study name among them)
    assert!(text.contains("`\\u{1b}`-separated"), "{text}");
    assert_eq!(text.matches("<U+202E>").count(), 16, "{text}");
    insta::assert_snapshot!("check_hostile_single", text);

    // a unit's label and certificate
    let units = std::fs::read_to_string(root().join("fixtures/studies/units.ron"))
        .unwrap()
        .replace(r#"label: "A""#, &format!(r#"label: "A{EVIL}""#))
        .replace("CC-2026-0051", &format!("CC{EVIL}"))
        .replace("Example Instruments", &format!("Example{EVIL}"))
        .replace("PIGA-16", &format!("PIGA{EVIL}"))
        .replace("SN 1604-0201", &format!("SN{EVIL}"))
        .replace("Example Guidance Systems Ltd", &format!("Guidance{EVIL}"));
    let text = describe("cli-check-hostile-units", &units);
    assert!(!raw(&text), "{text:?}");
    assert!(text.contains(r"unit Ax\u{1b}[31my<U+202E>z:"), "{text}");
    assert!(
        text.contains(r"customer Guidancex\u{1b}[31my<U+202E>z"),
        "{text}"
    );
}

/// The lab profile's file, as `check` names it (the profile's own names are refused with a
/// hidden character when the profile is read, and written visibly all the same).
#[test]
fn check_writes_the_lab_profiles_file_visibly() {
    let tmp = Scratch::new("cli-check-hostile-profile");
    let profile = format!("lab{EVIL}.ron");
    std::fs::copy(
        root().join("fixtures/lab-folder/lab.ron"),
        tmp.0.join(&profile),
    )
    .unwrap();
    let study = format!(
        r#"(
    name: "profiled",
    profile: "{profile}",
    centrifuge: "ZF-2",
    k1_rad_s_g: 0.56,
    phases: [(name: "p", points: first_harmonic([(rate_deg_s: 10.0, dc1_um: 1.0, ds1_um: 0.5)]))],
)"#
    );
    let path = tmp.0.join("study.ron");
    std::fs::write(&path, study).unwrap();
    let (text, _) = run(&["check", path.to_str().unwrap()], &tmp.0);
    assert!(!raw(&text), "{text:?}");
    let line = text
        .lines()
        .find(|l| l.starts_with("lab profile: "))
        .unwrap_or_else(|| panic!("no lab profile line: {text}"));
    assert!(
        line.starts_with(
            r"lab profile: <tmp>/labx\u{1b}[31my<U+202E>z.ron, centrifuge ZF-2, probe CP-7731;"
        ),
        "{line}"
    );
}
