//! Expected-value files: a regression against one must be able to fail.

use std::path::Path;

use edge_io::EdgeIoError;
use report::{Expected, ReportError};

use super::{Scratch, root};

const FILE: &str = "expected.ron";

fn parse(checks: &str) -> Result<Expected, ReportError> {
    Expected::parse(
        &format!("(source: \"test\", checks: [{checks}])"),
        Path::new(FILE),
    )
}

const GOOD: &str =
    r#"(path: "post_balance.c_r_m_s2", value: -4.05e-8, tolerance: 5e-11, note: "x")"#;

#[test]
fn the_fixtures_are_valid() {
    for name in ["paper-2025.ron", "recordings-small.ron"] {
        let e = Expected::load(&root().join("fixtures/expected").join(name)).unwrap();
        assert!(e.checks.iter().any(|c| c.regress), "{name}");
    }
}

#[test]
fn no_checks_is_refused() {
    match parse("") {
        Err(ReportError::NoRegressionChecks { path, checks: 0 }) => {
            assert_eq!(path, Path::new(FILE))
        }
        other => panic!("expected NoRegressionChecks, got {other:?}"),
    }
    let shown_only = r#"(path: "a.b", value: 1.0, tolerance: 0.1, note: "x", regress: false)"#;
    let e = parse(shown_only).unwrap_err();
    assert!(
        matches!(e, ReportError::NoRegressionChecks { checks: 1, .. }),
        "{e:?}"
    );
    assert!(
        e.to_string()
            .starts_with("expected.ron: `checks`: no check with `regress: true`"),
        "{e}"
    );
}

#[test]
fn tolerances_must_be_finite_and_not_negative() {
    for (tolerance, reason) in [
        (
            "inf",
            "not a finite number: the check would pass whatever the results",
        ),
        (
            "NaN",
            "not a finite number: the check would pass whatever the results",
        ),
        ("-1e-9", "negative: the check could never pass"),
    ] {
        let check =
            format!(r#"{GOOD}, (path: "a.b", value: 1.0, tolerance: {tolerance}, note: "x")"#);
        match parse(&check) {
            Err(ReportError::InvalidCheckNumber {
                field, reason: r, ..
            }) => assert_eq!((field.as_str(), r), ("checks[1].tolerance", reason)),
            other => panic!("{tolerance}: expected InvalidCheckNumber, got {other:?}"),
        }
    }
    let e = parse(r#"(path: "a.b", value: 1.0, tolerance: inf, note: "x")"#).unwrap_err();
    assert_eq!(
        e.to_string(),
        "expected.ron: `checks[0].tolerance` = inf: not a finite number: the check would pass \
         whatever the results"
    );
}

#[test]
fn values_must_be_finite() {
    match parse(r#"(path: "a.b", value: -inf, tolerance: 0.0, note: "x")"#) {
        Err(ReportError::InvalidCheckNumber { field, .. }) => assert_eq!(field, "checks[0].value"),
        other => panic!("expected InvalidCheckNumber, got {other:?}"),
    }
}

#[test]
fn paths_must_be_well_formed() {
    for bad in ["", "a..b", "points[x.y].c", "points[0"] {
        let check = format!(r#"{GOOD}, (path: "{bad}", value: 1.0, tolerance: 0.1, note: "x")"#);
        match parse(&check) {
            Err(ReportError::InvalidCheckPath {
                index, check_path, ..
            }) => assert_eq!((index, check_path.as_str()), (1, bad)),
            other => panic!("{bad:?}: expected InvalidCheckPath, got {other:?}"),
        }
    }
}

#[test]
fn a_path_takes_one_published_value_and_one_other_check() {
    let published = r#"(path: "post_balance.c_r_m_s2", value: -4.0e-8, tolerance: 1e-9, note: "paper", published: true)"#;
    parse(&format!("{GOOD}, {published}")).unwrap();
    match parse(&format!("{GOOD}, {published}, {GOOD}")) {
        Err(ReportError::DuplicateCheckPath {
            index,
            first,
            check_path,
            ..
        }) => assert_eq!(
            (index, first, check_path.as_str()),
            (2, 0, "post_balance.c_r_m_s2")
        ),
        other => panic!("expected DuplicateCheckPath, got {other:?}"),
    }
}

#[test]
fn a_file_with_a_byte_order_mark_loads() {
    let dir = Scratch::new("expected-bom");
    let path = dir.0.join("bom.ron");
    let text = format!("\u{FEFF}(source: \"editor\", checks: [{GOOD}])");
    std::fs::write(&path, text).unwrap();
    assert_eq!(Expected::load(&path).unwrap().checks.len(), 1);
}

#[test]
fn a_file_above_the_cap_is_refused_unread() {
    let dir = Scratch::new("expected-huge");
    let path = dir.0.join("huge.ron");
    std::fs::File::create(&path)
        .unwrap()
        .set_len(edge_io::CONFIG_MAX_BYTES + 1)
        .unwrap();
    match Expected::load(&path) {
        Err(ReportError::File(EdgeIoError::TooLarge {
            path: p,
            limit_bytes,
            size_bytes,
        })) => {
            assert_eq!(p, path);
            assert_eq!(limit_bytes, 16 << 20);
            assert_eq!(size_bytes, Some((16 << 20) + 1));
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
}
