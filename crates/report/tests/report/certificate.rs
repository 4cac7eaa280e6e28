//! The calibration certificate of the fixtures, typeset by the real engine: its data model
//! and its pages' text as snapshots (a lost item, a renamed field or a changed number
//! fails), what ISO/IEC 17025 §7.8 and issue 27 require of it, every glyph inside the
//! printable area of A4, the PDF/A declaration, and the study's and the `certificate`
//! command's PDF the same bytes.

use std::path::Path;

use report::{Provenance, Software};

/// A study of the fixtures with its provenance, read through paths relative to this crate
/// (the test's working directory) so that the snapshots hold no absolute path.
fn study(name: &str) -> (pipeline::StudyResults, Provenance) {
    let study = pipeline::load_study(&Path::new("../../fixtures/studies").join(name)).unwrap();
    let results = pipeline::run(&study).unwrap();
    let provenance = Provenance::of_study(&study, None).unwrap();
    (results, provenance)
}

fn software() -> Software {
    Software {
        version: "centrifuge-cal (test build)".to_owned(),
        commit: "0000000000000000000000000000000000000000".to_owned(),
    }
}

/// The document and its pages' text.
fn typeset(
    name: &str,
) -> (
    pipeline::StudyResults,
    Provenance,
    typeset::Document,
    Vec<String>,
) {
    let (results, provenance) = study(name);
    let doc = report::certificate_document(&results, Some(&provenance), &software()).unwrap();
    let pages = doc.page_texts();
    (results, provenance, doc, pages)
}

/// All the pages' text with every run of whitespace one space (a cell's text may wrap).
fn flat(pages: &[String]) -> String {
    pages
        .join(" ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

fn pages_snapshot(pages: &[String]) -> String {
    pages
        .iter()
        .enumerate()
        .map(|(n, p)| format!("======== page {} ========\n{p}\n", n + 1))
        .collect()
}

#[test]
fn the_campaign_certificate_data_is_unchanged() {
    let (results, provenance) = study("campaign.ron");
    let data = report::certificate_data(&results, Some(&provenance), &software()).unwrap();
    insta::assert_snapshot!(
        "campaign_certificate_json",
        report::certificate_json(&data).unwrap()
    );
}

#[test]
fn the_two_orientation_certificate_data_is_unchanged() {
    let (results, provenance) = study("two_orientation.ron");
    let data = report::certificate_data(&results, Some(&provenance), &software()).unwrap();
    insta::assert_snapshot!(
        "two_orientation_certificate_json",
        report::certificate_json(&data).unwrap()
    );
}

#[test]
fn the_campaign_certificate_pages_are_unchanged() {
    let (_, _, _, pages) = typeset("campaign.ron");
    insta::assert_snapshot!("campaign_certificate_pages", pages_snapshot(&pages));
}

#[test]
fn the_two_orientation_certificate_pages_are_unchanged() {
    let (_, _, _, pages) = typeset("two_orientation.ron");
    insta::assert_snapshot!("two_orientation_certificate_pages", pages_snapshot(&pages));
}

/// Every glyph, rule and image inside the page less 17 mm left and right (the text area:
/// tables included) and 8 mm top and bottom (the running head and foot).
#[test]
fn everything_lies_inside_the_printable_area_of_a4() {
    for name in ["campaign.ron", "two_orientation.ron"] {
        let (_, _, doc, _) = typeset(name);
        let (w, h) = doc.page_size_pt(0).unwrap();
        assert!(
            (w - 595.28).abs() < 0.01 && (h - 841.89).abs() < 0.01,
            "A4: {w} × {h}"
        );
        let strays = doc.outside(typeset::Area::inset_mm(17.0, 8.0, 17.0, 8.0));
        assert!(strays.is_empty(), "{name}: {strays:#?}");
    }
}

#[test]
fn the_certificate_holds_what_iso_17025_asks() {
    let (results, provenance, doc, pages) = typeset("campaign.ron");
    let text = flat(&doc.laid_out_texts());
    let packed: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    let info = results.certificate.as_ref().unwrap();
    // §7.8.2.1 and §7.8.4.1 items, each as the study file gives it
    for item in [
        &info.id,
        &info.laboratory.name,
        &info.laboratory.address,
        &info.customer.name,
        &info.customer.address,
        &info.item.description,
        &info.item.manufacturer,
        &info.item.model,
        &info.item.serial,
        &info.item.condition,
        &info.dates.received,
        &info.dates.measured,
        &info.dates.issued,
        &info.operator,
        &info.procedure,
        &info.authorisation.name,
        &info.authorisation.role,
        &info.location,
    ] {
        assert!(text.contains(item.as_str()), "{item}");
    }
    for e in &info.equipment {
        assert!(text.contains(&e.identity) && text.contains(&e.calibration_due));
    }
    for t in &info.traceability {
        assert!(text.contains(&t.statement), "{}", t.statement);
    }
    assert!(text.contains("The results relate only to the item calibrated"));
    // the id and "Page x of y" on every page, a marked end on the last
    let n = doc.page_count();
    assert!((2..=8).contains(&n), "{n} pages");
    for (p, page) in pages.iter().enumerate() {
        assert!(
            page.contains(&format!("Certificate {}", info.id)),
            "page {}",
            p + 1
        );
        assert!(
            page.contains(&format!("Page {} of {n}", p + 1)),
            "page {}",
            p + 1
        );
    }
    assert!(pages[n - 1].contains(&format!("End of certificate {}", info.id)));
    // every input file with its digest, the software's version and commit
    // (a digest may wrap in its column: compared without white space)
    for f in provenance.inputs.iter().chain([&provenance.config]) {
        assert!(packed.contains(&f.sha256), "{}", f.path);
    }
    assert!(packed.contains("0000000000000000000000000000000000000000"));
    // the conformity statement for k2 under the guard-band rule, with its limit's source
    assert!(text.contains("non-binary statement with a guard band w = U"));
    assert!(packed.contains("customerspecificationES-PIGA-16rev.B(example)"));
}

#[test]
fn what_a_customer_asks_is_on_page_1_or_2() {
    let (results, _, doc, _) = typeset("campaign.ron");
    let laid_out = doc.laid_out_texts();
    let front = flat(&laid_out[..2]);
    let c = results.calibration.as_ref().unwrap();
    let low = c
        .residuals
        .iter()
        .map(|r| r.rate_deg_s)
        .fold(f64::INFINITY, f64::min);
    let high = c.residuals.iter().map(|r| r.rate_deg_s).fold(0.0, f64::max);
    // the rates and specific forces of the points fitted, the mounting in words, the method
    // with its references, the certified method and why
    let a = |rate: f64| results.inputs.radius_m * rate.to_radians().powi(2) / c.g_m_s2;
    for words in [
        format!("{low} to {high} deg/s"),
        format!("{:.4} g to {:.2} g", a(low), a(high)),
        "input axis pointing towards the spindle axis".to_owned(),
        "probe method (Liu et al. 2025)".to_owned(),
        "One mounting was measured".to_owned(),
        // uncertainties labelled, each with its own k
        "standard uncertainty u".to_owned(),
        "expanded uncertainty U (95 %)".to_owned(),
        "limit from".to_owned(),
    ] {
        assert!(front.contains(&words), "{words} not in\n{front}");
    }
    let all = flat(&laid_out);
    for reference in [
        "Liu Y.",
        "Sun, Ren, Cao, Huo",
        "IEEE Std 836",
        "JCGM 100",
        "JCGM 101",
        "ILAC-G8",
    ] {
        assert!(all.contains(reference), "{reference}");
    }
}

#[test]
fn no_configuration_or_code_name_is_printed() {
    for name in ["campaign.ron", "two_orientation.ron"] {
        let (results, provenance, doc, _) = typeset(name);
        // file paths hold underscores and the input names of the fixtures: take them out, and
        // the study's name, the laboratory's own text (the fixture's is `two_orientation`)
        let mut text = flat(&doc.laid_out_texts());
        for f in provenance.inputs.iter().chain([&provenance.config]) {
            text = text.replace(&f.path, "");
        }
        let study_field = format!("Laboratory reference {}", results.study);
        assert!(text.contains(&study_field), "{name}: no {study_field:?}");
        text = text.replace(&study_field, "");
        for code in [
            "C_r",
            "ia_in",
            "ia_out",
            "Some(",
            "None",
            "k2_probe",
            "compensate_with",
            "probe_direction",
            "study field",
            "`",
            "certificate.",
            "calibration.",
            "uncertainty.",
            "lever.",
            "two_orientation",
            "_u_",
            "_m_s2",
            "_deg_s",
            "against_o1_x1",
            "index_pulse",
            "O1X1",
            "paper's set-up",
        ] {
            // a name ending in `.` is a field path only when a field's name follows it
            let found = text
                .match_indices(code)
                .find(|(i, _)| {
                    !code.ends_with('.')
                        || text[i + code.len()..]
                            .starts_with(|c: char| c.is_ascii_lowercase() || c == '_')
                })
                .map(|(i, _)| {
                    let around: String = text[i..].chars().take(80).collect();
                    around
                });
            assert!(found.is_none(), "{name}: `{code}` in {found:?}");
        }
        // nor any other name joined by an underscore (a field, a variable, a symbol of the
        // paper written as code, `d_c1`): a file's name is the only word that may hold one
        // (and a long one is laid out in pieces: a piece of a path is a file's name too)
        let named: Vec<&str> = text
            .split_whitespace()
            .filter(|w| {
                w.contains('_')
                    && !provenance
                        .inputs
                        .iter()
                        .chain([&provenance.config])
                        .any(|f| f.path.contains(w))
            })
            .collect();
        assert!(named.is_empty(), "{name}: {named:?}");
    }
}

/// Every row of the uncertainty budget and of the traceability table states its unit, and
/// so does every row of the results, the check, the conformity and the GUM-against-Monte-Carlo
/// tables (a "unit" column with no dash in it).
#[test]
fn every_table_with_a_unit_column_has_a_unit_in_every_row() {
    for name in ["campaign.ron", "two_orientation.ron"] {
        let (results, provenance) = study(name);
        let data = report::certificate_data(&results, Some(&provenance), &software()).unwrap();
        let json: serde_json::Value =
            serde_json::from_str(&report::certificate_json(&data).unwrap()).unwrap();
        let mut tables = 0;
        let mut stack = vec![&json];
        while let Some(v) = stack.pop() {
            match v {
                serde_json::Value::Object(o) => {
                    if let (Some(columns), Some(rows)) = (o.get("columns"), o.get("rows"))
                        && let Some(unit) =
                            columns.as_array().unwrap().iter().position(|c| c == "unit")
                    {
                        tables += 1;
                        for row in rows.as_array().unwrap() {
                            let cell = &row[unit];
                            assert!(
                                !cell.is_null() && cell != "—" && cell != "",
                                "{name}: a row without its unit: {row}"
                            );
                        }
                    }
                    stack.extend(o.values());
                }
                serde_json::Value::Array(a) => stack.extend(a),
                _ => {}
            }
        }
        assert!(tables >= 5, "{name}: {tables} tables with a unit column");
    }
}

#[test]
fn each_quantity_has_its_own_coverage_factor() {
    let (results, provenance) = study("campaign.ron");
    let data = report::certificate_data(&results, Some(&provenance), &software()).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&report::certificate_json(&data).unwrap()).unwrap();
    // C_r and Δk2 are stated with their standard uncertainty alone: no coverage factor
    // borrowed from k2
    let compensation = &json["compensation"];
    assert_eq!(compensation["columns"][2], "standard uncertainty u");
    let text = compensation.to_string();
    assert!(!text.contains("k = "), "{text}");
    // the results table: k of each coefficient from its own GUM evaluation (— for a Monte
    // Carlo interval, which has none)
    let c = results.calibration.as_ref().unwrap();
    let rows = json["results"]["rows"].as_array().unwrap();
    for (n, (head, gum)) in [
        (&c.headline.k0, &c.coefficients.k0),
        (&c.headline.k1, &c.coefficients.k1),
        (&c.headline.k2, &c.coefficients.k2),
        (&c.headline.k3, &c.coefficients.k3),
    ]
    .into_iter()
    .enumerate()
    {
        let k = rows[n][4].as_str().unwrap();
        if head.method == pipeline::HeadlineMethod::Gum {
            assert!(
                (k.parse::<f64>().unwrap() - gum.k).abs() < 0.01,
                "k{n}: {k} against {}",
                gum.k
            );
        } else {
            assert_eq!(k, "—", "k{n}");
        }
    }
}

#[test]
fn the_two_orientation_certificate_states_its_check() {
    let (results, provenance, doc, _) = typeset("two_orientation.ron");
    let text = flat(&doc.laid_out_texts());
    let packed: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    // both mountings measured, the methods disagree: the two-orientation k2 is certified,
    // the probe method is its check, and the page says they disagree
    for words in [
        "This certificate states the coefficients of the two-orientation method",
        "Check by the probe method (not certified)",
        "its values below are a check, not certified",
        "k2, two-orientation method (certified)",
        "k2, probe method (a check, not certified)",
        "k2, probe method (a check, not certified), relative to k1",
        "The two methods disagree",
        "the two-orientation k2 is the one certified",
        "it is not certified",
        "arm stretching",
        "input axis pointing towards the spindle axis",
        "input axis pointing away from the spindle axis",
    ] {
        assert!(text.contains(words), "{words} not in the certificate");
    }
    assert!(!text.contains("certifies a value that its own check refutes"));
    assert!(
        !text.contains("probe method (certified)"),
        "the probe method is not certified"
    );
    // what is certified comes first: the method, the mountings in words and each certified
    // coefficient with its interval (the results table), then the probe method as the check
    let at = |words: &str| text.find(words).unwrap_or_else(|| panic!("{words}"));
    let check = at("Check by the probe method (not certified)");
    for first in [
        "What is certified",
        "This certificate states the coefficients of the two-orientation method",
        "IA out: input axis pointing away from the spindle axis",
        "k0 (IA in)",
        "k0 (IA out)",
        "k2/k1",
        "k3/k1",
    ] {
        assert!(at(first) < check, "{first} is not stated before the check");
    }
    // a file read by two sections (the IA-in table) is listed once, with its digest
    let ia_in = provenance
        .inputs
        .iter()
        .find(|f| f.path.ends_with("piga_ia_in.csv"))
        .expect("the IA-in table");
    assert_eq!(packed.matches(&ia_in.sha256).count(), 1);
    // the k2 stated is the certified one (the two-orientation method's), not the probe
    // method's that the check refutes
    let certified = &results.certificate.as_ref().unwrap().certified;
    assert_eq!(certified.method, pipeline::CertifiedMethod::TwoOrientation);
    let k2 = certified
        .coefficients
        .iter()
        .find(|c| c.name == "k2")
        .unwrap();
    let micro = k2.relative.as_ref().unwrap();
    let probe = results.calibration.as_ref().unwrap();
    let probe_micro = probe.coefficients.k2.value * 1e6 / probe.coefficients.k1.value;
    assert!(
        (micro.value - probe_micro).abs() > 10.0 * micro.expanded,
        "the methods differ"
    );
    let data = report::certificate_data(&results, Some(&provenance), &software()).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&report::certificate_json(&data).unwrap()).unwrap();
    let row = json["results"]["rows"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r[0] == "k2/k1")
        .expect("a k2/k1 row");
    let stated: f64 = row[1].as_str().unwrap().parse().unwrap();
    assert!(
        (stated - micro.value).abs() <= micro.expanded / 10.0,
        "{stated} against {}",
        micro.value
    );
}

/// The two-orientation fixture certifying the probe method, which its own check refutes,
/// because the laboratory says so with its reason: the certificate says so, marked, and calls
/// the two-orientation method's rows a check, not certified.
#[test]
fn a_refuted_probe_method_certified_by_the_laboratorys_choice_says_so() {
    let path = Path::new("../../fixtures/studies/two_orientation.ron");
    let text = std::fs::read_to_string(path).unwrap();
    let edited = text.replacen(
        "    certificate: (\n",
        "    certificate: (\n        certify: probe,\n        certify_despite_check: \"the \
         customer's contract CC-9 asks for the probe method\",\n",
        1,
    );
    assert_ne!(edited, text, "the fixture's certificate section");
    let study = pipeline::parse_study(&edited, path).unwrap();
    let results = pipeline::run(&study).unwrap();
    let provenance = Provenance::of_study(&study, None).unwrap();
    let doc = report::certificate_document(&results, Some(&provenance), &software()).unwrap();
    let text = flat(&doc.laid_out_texts());
    for words in [
        "This certificate states the coefficients of the probe method",
        "The laboratory certifies a value that its own check refutes",
        "the customer's contract CC-9 asks for the probe method",
        "Check by the two-orientation method (not certified)",
        "as a check, not certified",
        "k2, probe method (certified)",
        "k2, two-orientation method (a check, not certified)",
        "The two methods disagree",
        "it is certified only because the laboratory chose the probe method explicitly",
    ] {
        assert!(text.contains(words), "{words} not in the certificate");
    }
    // the configuration's names are not printed
    assert!(!text.contains("certify_despite_check"));
}

#[test]
fn the_pdf_is_pdf_a_2b_with_nothing_active() {
    let (results, provenance) = study("campaign.ron");
    let pdf = report::certificate_pdf(&results, Some(&provenance), &software()).unwrap();
    let bytes = String::from_utf8_lossy(&pdf);
    assert!(bytes.contains("<pdfaid:part>2</pdfaid:part>"));
    assert!(bytes.contains("<pdfaid:conformance>B</pdfaid:conformance>"));
    assert!(
        bytes.contains("Calibration certificate CC-2026-0042"),
        "the title"
    );
    for active in [
        "/JavaScript",
        "/JS ",
        "/Launch",
        "/GoToR",
        "/URI",
        "/EmbeddedFile",
        "/SubmitForm",
    ] {
        assert!(!bytes.contains(active), "{active}");
    }
    // the same bytes every time
    assert_eq!(
        pdf,
        report::certificate_pdf(&results, Some(&provenance), &software()).unwrap()
    );
}

#[test]
fn a_study_without_certificate_section_has_no_certificate() {
    let (results, provenance) = study("paper-2025.ron");
    let err = report::certificate_pdf(&results, Some(&provenance), &software()).unwrap_err();
    assert!(matches!(err, report::ReportError::NoCertificate), "{err}");
}

#[test]
fn the_terminal_summary_gives_k2_with_its_u95_in_both_units() {
    let (results, _) = study("campaign.ron");
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
    let (results, provenance) = study("campaign.ron");
    let json: serde_json::Value =
        serde_json::from_str(&report::results_json_with_provenance(&results, &provenance).unwrap())
            .unwrap();
    let k2 = &json["calibration"]["headline"]["k2"];
    let c = results.calibration.as_ref().unwrap();
    assert_eq!(k2["method"], "monte_carlo", "{k2}");
    assert_eq!(k2["borderline"], true, "{k2}");
    assert_eq!(k2["low95"].as_f64(), Some(c.monte_carlo.k2.low95));
    assert_eq!(json["calibration"]["headline"]["k0"]["method"], "gum");
    assert_eq!(json["certificate"]["id"], "CC-2026-0042");
    let statement = &json["certificate"]["conformity"]["statements"][0];
    assert_eq!(statement["verdict"], "pass");
    assert_eq!(
        statement["source"],
        "customer specification ES-PIGA-16 rev. B (example)"
    );
    assert_eq!(json["certificate"]["conformity"]["rule"], "guard_band");
}

/// `study` writes certificate.pdf; the results folder read back gives the same results and
/// provenance, and the `certificate` command's PDF is the same bytes.
#[test]
fn study_writes_the_certificate_and_it_can_be_written_again_from_results_json() {
    let (results, provenance) = study("campaign.ron");
    let dir = super::Scratch::new("certificate");
    let out = dir.0.join("study");
    let files = report::write_outputs(&out, &results, None, None, Some(&provenance)).unwrap();
    let pdf_path = files.certificate_pdf.expect("certificate.pdf written");
    assert_eq!(pdf_path, out.join("certificate.pdf"));
    assert!(!out.join("certificate.html").exists());
    let saved = report::read_results(&out).unwrap();
    // (the numbers are read back as serde_json parses them, not always to the last bit: the
    // certificate written from them is compared below, byte for byte)
    assert_eq!(
        saved.results.certificate.map(|c| c.id),
        Some("CC-2026-0042".to_owned())
    );
    assert_eq!(saved.provenance.as_ref(), Some(&provenance));
    let again = report::write_certificate(&out, Some(&dir.0.join("again.pdf"))).unwrap();
    assert_eq!(
        std::fs::read(&again).unwrap(),
        std::fs::read(&pdf_path).unwrap()
    );
    // results without a certificate section: the error says what is missing, nothing written
    let (paper, _) = study("paper-2025.ron");
    let plain = dir.0.join("paper");
    report::write_outputs(&plain, &paper, None, None, None).unwrap();
    let err = report::write_certificate(&plain, None).unwrap_err();
    assert!(err.to_string().contains("`certificate` section"), "{err}");
    assert!(!plain.join("certificate.pdf").exists());
    // a folder without results.json is named
    let err = report::write_certificate(&dir.0, None).unwrap_err();
    assert!(err.to_string().contains("results.json"), "{err}");
}

/// Every page of both fixtures' certificates as a PNG under `target/certificate-pages/`, for a
/// person to look at (the typesetter's own rasteriser: what a screen shows).
#[test]
fn the_pages_are_drawn_for_a_person_to_look_at() {
    let dir = super::root().join("target/certificate-pages");
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["campaign", "two_orientation"] {
        let (_, _, doc, _) = typeset(&format!("{name}.ron"));
        let pngs = doc.png_pages(100.0).unwrap();
        assert_eq!(pngs.len(), doc.page_count());
        for (n, png) in pngs.iter().enumerate() {
            assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
            std::fs::write(dir.join(format!("{name}-page-{}.png", n + 1)), png).unwrap();
        }
    }
}
