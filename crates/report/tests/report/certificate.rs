//! The calibration certificate of the simulated campaign: its HTML as a snapshot (a lost
//! item, a renamed field or a changed number fails), what ISO/IEC 17025 §7.8 requires of it,
//! and the headline and summary that read the same numbers.

use std::path::Path;

use pipeline::CertificateResults;
use report::{Provenance, Software};

/// The campaign study, its results and provenance, read through paths relative to this
/// crate (the test's working directory) so that the snapshot holds no absolute path.
fn campaign() -> (pipeline::StudyResults, Provenance) {
    let study = pipeline::load_study(Path::new("../../fixtures/studies/campaign.ron")).unwrap();
    let results = pipeline::run(&study).unwrap();
    let provenance = Provenance::of_study(&study, None).unwrap();
    (results, provenance)
}

/// The certificate section's statements, as the study validated them.
fn info(results: &pipeline::StudyResults) -> CertificateResults {
    results.certificate.clone().expect("a certificate section")
}

fn software() -> Software {
    Software {
        version: "centrifuge-cal (test build)".to_owned(),
        commit: "0000000000000000000000000000000000000000".to_owned(),
    }
}

/// The HTML with its inline figure replaced by a marker (the figure has its own checks).
fn without_svg(html: &str) -> String {
    let start = html.find("<svg").expect("an inline figure");
    let end = html[start..].find("</svg>").expect("a closed figure") + start + "</svg>".len();
    format!("{}<svg>…</svg>{}", &html[..start], &html[end..])
}

#[test]
fn the_campaign_certificate_is_unchanged() {
    let (results, provenance) = campaign();
    let html = report::certificate_html(&results, Some(&provenance), &software()).unwrap();
    insta::assert_snapshot!("campaign_certificate_html", without_svg(&html));
}

#[test]
fn the_certificate_holds_what_iso_17025_asks_and_fetches_nothing() {
    let (results, provenance) = campaign();
    let info = info(&results);
    let html = report::certificate_html(&results, Some(&provenance), &software()).unwrap();
    // self-contained: no external resource of any kind
    // (`url(#…)` is a reference inside the document: a figure's clip path)
    for external in [
        "http://", "https://", "src=", "<link", "@import", "url(h", "url(/", "url(\"", "url('",
    ] {
        let found = html
            .match_indices(external)
            .map(|(i, _)| &html[i.saturating_sub(40)..(i + 40).min(html.len())])
            .find(|context| !context.contains("xmlns=\"http://www.w3.org/2000/svg\""));
        assert!(found.is_none(), "{external} in {found:?}");
    }
    // the id and page x of y on every page (the @page margin boxes), A4
    assert!(html.contains("size: A4"));
    assert!(html.contains("counter(page) \" of \" counter(pages)"));
    assert!(html.contains(&format!("\"Certificate {}\"", info.id)));
    // §7.8.2.1 and §7.8.4.1 items
    for item in [
        &info.laboratory.name,
        &info.laboratory.address,
        &info.customer.name,
        &info.item.model,
        &info.item.serial,
        &info.dates.received,
        &info.dates.measured,
        &info.dates.issued,
        &info.operator,
        &info.procedure,
        &info.authorisation.name,
        &info.authorisation.role,
        &info.location,
    ] {
        assert!(html.contains(&report_escaped(item)), "{item}");
    }
    for e in &info.equipment {
        assert!(html.contains(&report_escaped(&e.identity)));
        assert!(html.contains(&e.calibration_due));
    }
    for t in &info.traceability {
        assert!(
            html.contains(&report_escaped(&t.statement)),
            "{}",
            t.statement
        );
    }
    assert!(html.contains("The results relate only to the item calibrated"));
    assert!(html.contains("End of certificate"));
    // every input file with its digest, the software's version and commit
    for f in provenance.inputs.iter().chain([&provenance.config]) {
        assert!(html.contains(&f.sha256), "{}", f.path);
    }
    assert!(html.contains("0000000000000000000000000000000000000000"));
    // the residual figure is inline and scales to the page
    assert!(html.contains("<svg class=\"figure\""));
    // the conformity statement for k2 under the guard-band rule
    assert!(html.contains("non-binary statement with a guard band w = U"));
    assert!(html.contains("class=\"verdict-pass\">pass<"));
}

fn report_escaped(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&#39;")
}

#[test]
fn a_study_without_certificate_section_has_no_certificate() {
    let study = pipeline::load_study(Path::new("../../fixtures/studies/paper-2025.ron")).unwrap();
    let results = pipeline::run(&study).unwrap();
    let provenance = Provenance::of_study(&study, None).unwrap();
    let err = report::certificate_html(&results, Some(&provenance), &software()).unwrap_err();
    assert!(matches!(err, report::ReportError::NoCertificate), "{err}");
}

#[test]
fn the_terminal_summary_gives_k2_with_its_u95_in_both_units() {
    let (results, _) = campaign();
    let text = report::summary_text(&results).expect("a calibration summary");
    insta::assert_snapshot!("campaign_summary", text);
    let k2 = text
        .lines()
        .find(|l| l.trim_start().starts_with("k2 "))
        .expect("a k2 line");
    assert!(k2.contains("rad/(s·g²)") && k2.contains("µg/g²"), "{k2}");
    assert!(k2.contains('±'), "{k2}");
    assert!(text.contains("C_r = ") && text.contains("Δk2 = "));
}

#[test]
fn results_json_holds_the_stated_intervals_and_the_certificate() {
    let (results, provenance) = campaign();
    let json: serde_json::Value =
        serde_json::from_str(&report::results_json_with_provenance(&results, &provenance).unwrap())
            .unwrap();
    // the §8 headline of each coefficient, with its method and borderline flag
    let k2 = &json["calibration"]["headline"]["k2"];
    let c = results.calibration.as_ref().unwrap();
    assert_eq!(k2["method"], "monte_carlo", "{k2}");
    assert_eq!(k2["borderline"], true, "{k2}");
    assert_eq!(k2["low95"].as_f64(), Some(c.monte_carlo.k2.low95));
    assert_eq!(json["calibration"]["headline"]["k0"]["method"], "gum");
    // the certificate's statements and its conformity verdict
    assert_eq!(json["certificate"]["id"], "CC-2026-0042");
    assert_eq!(
        json["certificate"]["conformity"]["statements"][0]["verdict"],
        "pass"
    );
    assert_eq!(json["certificate"]["conformity"]["rule"], "guard_band");
}

#[test]
fn study_writes_the_certificate_beside_results_json() {
    let (results, provenance) = campaign();
    let dir = std::env::temp_dir().join(format!("report-certificate-{}", std::process::id()));
    let files = report::write_outputs(&dir, &results, None, None, Some(&provenance)).unwrap();
    let html = files.certificate_html.expect("certificate.html written");
    assert_eq!(html, dir.join("certificate.html"));
    let text = std::fs::read_to_string(&html).unwrap();
    assert!(text.contains("CC-2026-0042"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The two-orientation fixture (`fixtures/studies/two_orientation.ron`): a study with a
/// calibration of its IA-in table compensated with the probe phase, a `two_orientation` and a
/// `certificate` section.
fn certified_two_orientation_study() -> (pipeline::StudyResults, Provenance) {
    let study =
        pipeline::load_study(Path::new("../../fixtures/studies/two_orientation.ron")).unwrap();
    let results = pipeline::run(&study).unwrap();
    let provenance = Provenance::of_study(&study, None).unwrap();
    (results, provenance)
}

#[test]
fn the_certificate_states_the_two_orientation_check() {
    let (results, provenance) = certified_two_orientation_study();
    assert!(results.two_orientation.is_some() && results.calibration.is_some());
    let html = report::certificate_html(&results, Some(&provenance), &software()).unwrap();
    let start = html
        .find("<section class=\"check\">")
        .expect("the two-orientation statement");
    let end = start + html[start..].find("</section>").unwrap() + "</section>".len();
    let part = &html[start..end];
    // k2 both ways in both units, C − C_r with its z and the sign convention: the fixture's
    // arm stretch is seen (z ≈ +8)
    for words in [
        "<h3>Check by the two-orientation method</h3>",
        "k2, probe method (a check, not certified)",
        "k2, two-orientation method",
        "k2/k1, two-orientation method",
        "µg/g²",
        "C − C<sub>r</sub>, growth the probe misses",
        "Sign convention",
        "z = (C − C<sub>r</sub>)/u(C − C<sub>r</sub>) = +",
        "The two methods disagree",
        "arm stretching",
    ] {
        assert!(part.contains(words), "{words} not in\n{part}");
    }
    // what is certified is stated before the probe method's table, which is called a check
    let results_part = &html[..start];
    for words in [
        "<strong>Certified: the two-orientation method.</strong>",
        "k0/k1 (input axis towards the spindle axis)",
        "<tr><td>k2/k1</td>",
        "their k2 and k3 are not certified",
    ] {
        assert!(
            results_part.contains(words),
            "{words} not in\n{results_part}"
        );
    }
    assert!(
        part.contains("the two-orientation k2 is the one certified"),
        "{part}"
    );
    insta::assert_snapshot!("two_orientation_certificate_html", part);
}

#[test]
fn the_two_orientation_certificate_has_units_and_no_code_names() {
    let (results, provenance) = certified_two_orientation_study();
    let html = report::certificate_html(&results, Some(&provenance), &software()).unwrap();
    // every input of the budget and of the traceability table has its unit
    assert!(html.contains("<table class=\"budget\">"));
    assert!(
        !html.contains("<td class=\"unit\">—</td>"),
        "an input without its unit"
    );
    // symbols as a person writes them: C_r with its subscript, nothing of the code's names
    for code in ["C_r", "ia_in", "ia_out", "Some(", "None", "k2_probe"] {
        let found = html
            .match_indices(code)
            .map(|(i, _)| &html[i.saturating_sub(60)..(i + 60).min(html.len())])
            // file names hold `ia_in`
            .find(|context| !context.contains(".csv"));
        assert!(found.is_none(), "`{code}` in {found:?}");
    }
    // a file read by two sections (the IA-in table) is listed once, with its digest
    let ia_in = provenance
        .inputs
        .iter()
        .find(|f| f.path.ends_with("piga_ia_in.csv"))
        .expect("the IA-in table");
    assert_eq!(html.matches(&ia_in.sha256).count(), 1);
    for f in provenance.inputs.iter().chain([&provenance.config]) {
        assert!(html.contains(&f.sha256), "{}", f.path);
    }
}
