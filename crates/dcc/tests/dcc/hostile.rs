//! Text from the configuration is data in the DCC: markup, entities and quotes are escaped,
//! control characters and bidirectional overrides are written visibly in free text and
//! refused, naming the field, in identifications.

use pipeline::StudyResults;

use crate::fixtures::{assert_valid, campaign};
use crate::tree::Node;

/// The campaign's results (as results.json holds them).
fn results() -> StudyResults {
    serde_json::from_value(campaign().json.clone()).unwrap()
}

fn write(results: &StudyResults) -> dcc::Result<String> {
    let software = dcc::Software {
        name: "centrifuge-cal".to_owned(),
        release: "0.1.0".to_owned(),
        commit: "unknown".to_owned(),
    };
    dcc::write_dcc(&dcc::DccInput {
        results,
        software: &software,
        files: None,
    })
}

const MARKUP: &str = "</dcc:content></dcc:further><script>alert(1)</script>\
                      <!-- x --><![CDATA[ y ]]>&amp; &lt; \"q\" 'a' <?pi x?> <!DOCTYPE d>";

#[test]
fn markup_in_every_free_text_is_character_data() {
    let mut r = results();
    let c = r.certificate.as_mut().unwrap();
    c.customer.address = MARKUP.to_owned();
    c.laboratory.address = MARKUP.to_owned();
    c.location = MARKUP.to_owned();
    c.procedure = MARKUP.to_owned();
    c.item.description = MARKUP.to_owned();
    c.item.condition = MARKUP.to_owned();
    c.conditions[0].value = MARKUP.to_owned();
    c.traceability[0].statement = MARKUP.to_owned();
    // identifications may hold markup characters too: they are escaped, not refused
    c.item.serial = "SN <1234> & \"5\"".to_owned();
    let xml = write(&r).unwrap();
    let doc = Node::parse(&xml);
    assert!(doc.descendants().iter().all(|n| n.name != "script"));
    let count = doc
        .descendants()
        .iter()
        .filter(|n| n.text == MARKUP)
        .count();
    // the two addresses, the place, the procedure (statement and method), the item's
    // description, the condition, the traceability statement
    assert_eq!(count, 8, "{xml}");
    assert!(
        doc.descendants()
            .iter()
            .any(|n| n.text == "Condition on receipt: ".to_owned() + MARKUP)
    );
    assert_eq!(
        doc.find("dcc:identifications/dcc:identification/dcc:value")
            .text,
        "SN <1234> & \"5\""
    );
    assert_valid("markup", &xml);
}

#[test]
fn control_characters_in_free_text_are_shown_visibly() {
    let mut r = results();
    let c = r.certificate.as_mut().unwrap();
    c.customer.address = "4 Gyro Street\u{0}\u{1b}[31m \u{202e}evil\u{202c} \u{ffff}".to_owned();
    c.procedure = "line one\nline two\ttab\rcr \u{9b}".to_owned();
    let xml = write(&r).unwrap();
    let doc = Node::parse(&xml);
    assert_eq!(
        doc.find("dcc:customer/dcc:location/dcc:further/dcc:content")
            .text,
        "4 Gyro Street\\u{0}\\u{1b}[31m <U+202E>evil<U+202C> <U+FFFF>"
    );
    assert!(
        doc.descendants()
            .iter()
            .any(|n| n.text == "line one\\u{a}line two\\u{9}tab\\u{d}cr \\u{9b}")
    );
    assert!(!xml.contains('\u{0}') && !xml.contains('\u{1b}') && !xml.contains('\u{202e}'));
    assert_valid("control", &xml);
}

#[test]
fn a_hidden_character_in_an_identification_is_refused_by_its_field() {
    type Set = fn(&mut pipeline::CertificateResults, String);
    let fields: [(&str, Set); 6] = [
        ("certificate.id", |c, s| c.id = s),
        ("certificate.item.serial", |c, s| c.item.serial = s),
        ("certificate.item.model", |c, s| c.item.model = s),
        ("certificate.item.manufacturer", |c, s| {
            c.item.manufacturer = s
        }),
        ("certificate.customer.name", |c, s| c.customer.name = s),
        ("certificate.equipment[1].identity", |c, s| {
            c.equipment[1].identity = s;
        }),
    ];
    for (field, set) in fields {
        for (payload, code_point, position) in [
            ("SN \u{202e}4321\u{202c}", 0x202e, 4),
            ("SN\u{0}1", 0, 3),
            ("\u{1b}]0;title\u{7}", 0x1b, 1),
        ] {
            let mut r = results();
            set(r.certificate.as_mut().unwrap(), payload.to_owned());
            let e = write(&r).unwrap_err();
            assert_eq!(
                e,
                dcc::DccError::HiddenCharacter {
                    field: field.to_owned(),
                    code_point,
                    position
                },
                "{field} {payload:?}"
            );
            assert!(e.to_string().contains(&format!("`{field}`")), "{e}");
        }
    }
}

#[test]
fn dates_the_dcc_cannot_hold_are_refused_by_their_field() {
    let mut r = results();
    r.certificate.as_mut().unwrap().dates.measured = "19 November 2026".to_owned();
    let e = write(&r).unwrap_err();
    assert!(
        matches!(&e, dcc::DccError::Date { field, .. } if field == "certificate.dates.measured"),
        "{e:?}"
    );
    assert!(e.to_string().contains("2026-11-19 to 2026-11-20"), "{e}");
}

#[test]
fn the_previous_certificate_and_the_country_are_stated() {
    let mut r = results();
    let sha = "ab".repeat(32);
    {
        let c = r.certificate.as_mut().unwrap();
        c.previous_certificate = Some(pipeline::PreviousCertificate {
            id: "CC-2025-0031".to_owned(),
            sha256: Some(sha.clone()),
        });
        c.laboratory.country = Some("DE".to_owned());
    }
    let xml = write(&r).unwrap();
    let doc = Node::parse(&xml);
    let previous = doc.find("dcc:coreData/dcc:previousReport");
    assert_eq!(previous.find("dcc:referralID").text, "CC-2025-0031");
    assert_eq!(previous.find("dcc:procedure").text, "SHA-256");
    assert_eq!(previous.find("dcc:value").text, sha);
    assert_eq!(doc.find("dcc:countryCodeISO3166_1").text, "DE");
    assert_valid("previous", &xml);
    // without them: no previousReport, and the unknown country says so
    let xml = write(&results()).unwrap();
    let doc = Node::parse(&xml);
    assert!(doc.try_find("dcc:previousReport").is_none());
    assert_eq!(doc.find("dcc:countryCodeISO3166_1").text, "ZZ");
    assert!(xml.contains("does not state the laboratory's country"));
    // a previous certificate named without its digest
    let mut r = results();
    r.certificate.as_mut().unwrap().previous_certificate = Some(pipeline::PreviousCertificate {
        id: "CC-2025-0031".to_owned(),
        sha256: None,
    });
    let xml = write(&r).unwrap();
    let doc = Node::parse(&xml);
    assert_eq!(doc.find("dcc:previousReport/dcc:procedure").text, "none");
    assert_valid("previous-no-digest", &xml);
}
