//! Hostile text through every free-text field of the certificate section (issue 27, part 5):
//! the payload corpus `fixtures/payloads.json` (HTML and CSS that loads, typst markup that
//! reads files, PDF syntax, ESC/OSC/BEL, bidirectional overrides, NUL, a 100 kB string) in
//! each field of the campaign's certificate. The certificate is typeset by the real engine;
//! its pages show every payload as text (control and bidirectional characters as
//! `[U+XXXX]`), the typesetter was asked for no file, and the PDF has no JavaScript, no
//! action, no embedded file.

use std::path::Path;

use pipeline::CertificateResults;
use report::{Provenance, Software};

struct Payload {
    name: String,
    text: String,
    /// The text repeated and how many times, for the long payload.
    repeated: Option<(String, usize)>,
}

fn payloads() -> Vec<Payload> {
    let text = std::fs::read_to_string(super::root().join("fixtures/payloads.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    json["payloads"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let repeat = p["repeat"].as_u64().unwrap_or(1);
            let unit = p["text"].as_str().unwrap();
            let times = usize::try_from(repeat).unwrap();
            Payload {
                name: p["name"].as_str().unwrap().to_owned(),
                text: unit.repeat(times),
                repeated: (times > 1).then(|| (unit.to_owned(), times)),
            }
        })
        .collect()
}

/// Every free-text field of the certificate section, by its study-file name (the dates are
/// not free text: the study refuses one that is not an ISO 8601 date, naming it).
fn fields(c: &mut CertificateResults) -> Vec<(String, &mut String)> {
    let mut out: Vec<(String, &mut String)> = vec![
        ("id".into(), &mut c.id),
        ("laboratory.name".into(), &mut c.laboratory.name),
        ("laboratory.address".into(), &mut c.laboratory.address),
        ("location".into(), &mut c.location),
        ("customer.name".into(), &mut c.customer.name),
        ("customer.address".into(), &mut c.customer.address),
        ("item.description".into(), &mut c.item.description),
        ("item.manufacturer".into(), &mut c.item.manufacturer),
        ("item.model".into(), &mut c.item.model),
        ("item.serial".into(), &mut c.item.serial),
        ("item.condition".into(), &mut c.item.condition),
        ("operator".into(), &mut c.operator),
        ("procedure".into(), &mut c.procedure),
        ("authorisation.name".into(), &mut c.authorisation.name),
        ("authorisation.role".into(), &mut c.authorisation.role),
    ];
    if let Some(a) = c.laboratory.accreditation.as_mut() {
        out.push(("laboratory.accreditation".into(), a));
    }
    if let Some(p) = c.previous_certificate.as_mut() {
        out.push(("previous_certificate.id".into(), &mut p.id));
    }
    // the reason for the certified method: the study's sentence, holding the laboratory's
    // own words when it certifies despite its check (`certify_despite_check`)
    out.push((
        "certify_despite_check (in the reason)".into(),
        &mut c.certified.reason,
    ));
    if let Some(d) = c.deviations.as_mut() {
        out.push(("deviations".into(), d));
    }
    for (i, e) in c.equipment.iter_mut().enumerate() {
        out.push((format!("equipment[{i}].role"), &mut e.role));
        out.push((format!("equipment[{i}].description"), &mut e.description));
        out.push((format!("equipment[{i}].identity"), &mut e.identity));
        out.push((
            format!("equipment[{i}].calibration_due"),
            &mut e.calibration_due,
        ));
    }
    for (i, x) in c.conditions.iter_mut().enumerate() {
        out.push((format!("conditions[{i}].quantity"), &mut x.quantity));
        out.push((format!("conditions[{i}].value"), &mut x.value));
    }
    for (i, t) in c.traceability.iter_mut().enumerate() {
        out.push((format!("traceability[{i}].statement"), &mut t.statement));
    }
    if let Some(conformity) = c.conformity.as_mut() {
        for (i, s) in conformity.statements.iter_mut().enumerate() {
            if let Some(source) = s.source.as_mut() {
                out.push((format!("limits[{i}].source"), source));
            }
        }
    }
    out
}

fn campaign() -> (pipeline::StudyResults, Provenance) {
    let study = pipeline::load_study(Path::new("../../fixtures/studies/campaign.ron")).unwrap();
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

/// Every table's heading row of the certificate's data, as one text without white space.
fn table_headings(json: &serde_json::Value) -> Vec<String> {
    fn strings(v: &serde_json::Value, out: &mut String) {
        match v {
            serde_json::Value::String(s) => out.push_str(s),
            serde_json::Value::Array(a) => a.iter().for_each(|x| strings(x, out)),
            serde_json::Value::Object(o) => o.values().for_each(|x| strings(x, out)),
            _ => {}
        }
    }
    let mut found = Vec::new();
    match json {
        serde_json::Value::Object(o) => {
            if let Some(columns) = o.get("columns") {
                let mut heading = String::new();
                strings(columns, &mut heading);
                found.push(no_whitespace(&heading));
            }
            o.values().for_each(|v| found.extend(table_headings(v)));
        }
        serde_json::Value::Array(a) => a.iter().for_each(|v| found.extend(table_headings(v))),
        _ => {}
    }
    found
}

fn no_whitespace(text: &str) -> String {
    text.chars().filter(|c| !c.is_whitespace()).collect()
}

/// The names of a PDF's objects (`/Type`, `/JavaScript`), outside its strings, comments and
/// streams: what a reader acts on. The file has no object streams (typst writes none), so
/// every dictionary is in the open.
fn pdf_names(pdf: &[u8]) -> Vec<String> {
    let mut names = Vec::new();
    let mut i = 0;
    while i < pdf.len() {
        match pdf[i] {
            b'%' => {
                while i < pdf.len() && pdf[i] != b'\n' && pdf[i] != b'\r' {
                    i += 1;
                }
            }
            b'(' => {
                // a literal string: balanced parentheses, backslash escapes
                let mut depth = 0usize;
                while i < pdf.len() {
                    match pdf[i] {
                        b'\\' => i += 1,
                        b'(' => depth += 1,
                        b')' => {
                            depth -= 1;
                            if depth == 0 {
                                break;
                            }
                        }
                        _ => {}
                    }
                    i += 1;
                }
            }
            b'<' if pdf.get(i + 1) != Some(&b'<') => {
                while i < pdf.len() && pdf[i] != b'>' {
                    i += 1;
                }
            }
            b'<' => i += 1,
            b's' if pdf[i..].starts_with(b"stream")
                && (i == 0 || !pdf[i - 1].is_ascii_alphanumeric()) =>
            {
                let end = pdf[i..]
                    .windows(9)
                    .position(|w| w == b"endstream")
                    .map_or(pdf.len(), |p| i + p + 9);
                i = end;
                continue;
            }
            b'/' => {
                let start = i + 1;
                i += 1;
                while i < pdf.len()
                    && !pdf[i].is_ascii_whitespace()
                    && !b"/[]<>(){}%".contains(&pdf[i])
                {
                    i += 1;
                }
                names.push(String::from_utf8_lossy(&pdf[start..i]).into_owned());
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    names
}

/// What a PDF must not hold: script, actions that run or load something, attachments.
const ACTIVE: [&str; 15] = [
    "JavaScript",
    "JS",
    "Launch",
    "GoToR",
    "GoToE",
    "URI",
    "SubmitForm",
    "ImportData",
    "EmbeddedFile",
    "EmbeddedFiles",
    "RichMedia",
    "OpenAction",
    "AA",
    "Movie",
    "Sound",
];

fn assert_shown_and_inert(
    payload: &Payload,
    results: &pipeline::StudyResults,
    provenance: &Provenance,
    fields: &[String],
) {
    let doc = report::certificate_document(results, Some(provenance), &software())
        .unwrap_or_else(|e| panic!("{}: {e}", payload.name));
    assert!(
        doc.denied().is_empty(),
        "{}: asked for {:?}",
        payload.name,
        doc.denied()
    );
    // the text between the running head and foot (the page's margins, 24 mm and 22 mm), so
    // that a cell broken across pages reads as one; the head and foot state a field cut to
    // 90 characters, the page states it in full
    let mut text = no_whitespace(
        &doc.body_texts(typeset::Area::inset_mm(0.0, 24.0, 0.0, 22.0))
            .join(""),
    );
    // a table broken across pages repeats its heading row there: taken out, so that a cell
    // broken with it reads as one
    let data = report::certificate_data(results, Some(provenance), &software()).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&report::certificate_json(&data).unwrap()).unwrap();
    for heading in table_headings(&json) {
        text = text.replace(&heading, "");
    }
    for (n, field) in fields.iter().enumerate() {
        if let Some((unit, times)) = payload.repeated.as_ref() {
            // a text longer than a page: a table row broken across pages lays out the row's
            // other cells between its parts, so the text is counted, not matched whole (a
            // repeat cut by a page break is not counted: one a page at most)
            let unit = no_whitespace(unit);
            assert!(
                text.contains(&format!("F{n:02}:{unit}")),
                "{}: field {field}",
                payload.name
            );
            assert!(
                text.matches(&unit).count() + doc.page_count() >= *times,
                "{}: field {field} is not shown whole ({} of {times} repeats)",
                payload.name,
                text.matches(&unit).count()
            );
            continue;
        }
        let shown = no_whitespace(&typeset::printable(&format!("F{n:02}:{}", payload.text)));
        assert!(
            text.contains(&shown),
            "{}: field {field} is not shown as written ({} characters expected)",
            payload.name,
            shown.len()
        );
    }
    let pdf = doc
        .pdf()
        .unwrap_or_else(|e| panic!("{}: no PDF/A: {e}", payload.name));
    let names = pdf_names(&pdf);
    assert!(
        names.iter().any(|n| n == "Catalog"),
        "the tokenizer sees the PDF's objects"
    );
    for active in ACTIVE {
        assert!(
            !names.iter().any(|n| n == active),
            "{}: the PDF holds /{active}",
            payload.name
        );
    }
}

#[test]
fn every_payload_in_every_field_is_shown_as_text_and_runs_nothing() {
    let (results, provenance) = campaign();
    for payload in payloads().iter().filter(|p| p.text.len() < 10_000) {
        let mut hostile = results.clone();
        let cert = hostile.certificate.as_mut().unwrap();
        let mut names = Vec::new();
        for (n, (name, value)) in fields(cert).into_iter().enumerate() {
            *value = format!("F{n:02}:{}", payload.text);
            names.push(name);
        }
        assert!(names.len() > 30, "{} fields", names.len());
        // beyond the certificate section: the name of the probe phase the calibration is
        // compensated with (a study-file string the certificate states twice) and an input
        // file's path as the study file names it
        let phase = format!("F{:02}:{}", names.len(), payload.text);
        let c = hostile.calibration.as_mut().unwrap();
        let old = std::mem::replace(&mut c.compensate_with, phase.clone());
        hostile
            .phases
            .iter_mut()
            .find(|p| p.name == old)
            .expect("the compensating phase")
            .name = phase;
        names.push("phases[].name (the compensating phase)".to_owned());
        let mut provenance = provenance.clone();
        provenance.inputs[0].path = format!("F{:02}:{}", names.len(), payload.text);
        names.push("an input file's path".to_owned());
        assert_shown_and_inert(payload, &hostile, &provenance, &names);
    }
}

/// The 100 kB string: one field at a time (all at once would be some thousand pages).
#[test]
fn a_100_kb_string_in_each_field_is_shown_whole() {
    let (results, provenance) = campaign();
    let payloads = payloads();
    let big = payloads
        .iter()
        .find(|p| p.text.len() >= 100_000)
        .expect("the corpus's 100 kB string");
    let count = fields(results.clone().certificate.as_mut().unwrap()).len();
    // one certificate a field, each typeset with its 100 kB text (about 4 s): on every core, so
    // that this test is not the one the whole binary waits for
    let next = std::sync::atomic::AtomicUsize::new(0);
    let workers = std::thread::available_parallelism().map_or(1, usize::from);
    std::thread::scope(|scope| {
        for _ in 0..workers.min(count) {
            scope.spawn(|| {
                loop {
                    let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    if k >= count {
                        break;
                    }
                    let mut hostile = results.clone();
                    let cert = hostile.certificate.as_mut().unwrap();
                    let mut name = String::new();
                    for (n, (field, value)) in fields(cert).into_iter().enumerate() {
                        if n == k {
                            *value = format!("F00:{}", big.text);
                            name = field;
                        }
                    }
                    assert_shown_and_inert(big, &hostile, &provenance, &[name]);
                }
            });
        }
    });
}
