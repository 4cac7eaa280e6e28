//! The DCC's administrative data: the software, the core data (country, language, the
//! certificate's id, the dates, the previous certificate), the item, the laboratory, the
//! responsible persons, the customer and the statements that concern the whole calibration.

use pipeline::CertificateResults;

use crate::date::Date;
use crate::error::Result;
use crate::input::Software;
use crate::text::Text;
use crate::xml::{LANG, Xml};

/// The country written when the study states none: ISO 3166-1 reserves `ZZ` for users; CLDR
/// and others use it for "unknown".
const UNKNOWN_COUNTRY: &str = "ZZ";

/// `dcc:administrativeData` of certificate `cert`, written by `software`.
pub(crate) fn administrative_data(
    x: &mut Xml,
    cert: &CertificateResults,
    software: &Software,
) -> Result<()> {
    // everything read and checked first: an error leaves nothing half-written
    let id = Text::identification("certificate.id", &cert.id)?;
    let received = Date::parse("certificate.dates.received", &cert.dates.received)?;
    let (begin, end) = Date::parse_span("certificate.dates.measured", &cert.dates.measured)?;
    let issued = Date::parse("certificate.dates.issued", &cert.dates.issued)?;
    x.el("dcc:administrativeData", |x| {
        x.el("dcc:dccSoftware", |x| software_element(x, software))?;
        x.el("dcc:coreData", |x| {
            let country = cert.laboratory.country.as_deref();
            x.leaf(
                "dcc:countryCodeISO3166_1",
                &match country {
                    Some(c) => Text::identification("certificate.laboratory.country", c)?,
                    None => Text::own(UNKNOWN_COUNTRY),
                },
            )?;
            x.own("dcc:usedLangCodeISO639_1", LANG)?;
            x.own("dcc:mandatoryLangCodeISO639_1", LANG)?;
            x.leaf("dcc:uniqueIdentifier", &id)?;
            x.own("dcc:receiptDate", &received.to_string())?;
            x.own("dcc:beginPerformanceDate", &begin.to_string())?;
            x.own("dcc:endPerformanceDate", &end.to_string())?;
            // the study states the place in words: the words are a statement below
            x.own("dcc:performanceLocation", "other")?;
            x.own("dcc:issueDate", &issued.to_string())?;
            if let Some(previous) = &cert.previous_certificate {
                let previous_id =
                    Text::identification("certificate.previous_certificate.id", &previous.id)?;
                x.el("dcc:previousReport", |x| {
                    x.own_content("dcc:referral", "the calibration certificate this one follows")?;
                    x.leaf("dcc:referralID", &previous_id)?;
                    match &previous.sha256 {
                        Some(sha) => {
                            x.own("dcc:procedure", "SHA-256")?;
                            x.leaf(
                                "dcc:value",
                                &Text::identification(
                                    "certificate.previous_certificate.sha256",
                                    sha,
                                )?,
                            )
                        }
                        None => {
                            x.own("dcc:procedure", "none")?;
                            x.own("dcc:value", "not stated")?;
                            x.own_content(
                                "dcc:description",
                                "The study names the previous certificate without the digest of its file.",
                            )
                        }
                    }
                })?;
            }
            Ok(())
        })?;
        items(x, cert)?;
        x.el("dcc:calibrationLaboratory", |x| {
            x.el("dcc:contact", |x| {
                x.content(
                    "dcc:name",
                    &Text::identification("certificate.laboratory.name", &cert.laboratory.name)?,
                )?;
                address(x, "certificate.laboratory.address", &cert.laboratory.address)
            })
        })?;
        x.el("dcc:respPersons", |x| {
            x.el("dcc:respPerson", |x| {
                x.el("dcc:person", |x| {
                    x.content(
                        "dcc:name",
                        &Text::identification("certificate.operator", &cert.operator)?,
                    )
                })?;
                x.own("dcc:role", "performed the calibration")
            })?;
            x.el("dcc:respPerson", |x| {
                x.el("dcc:person", |x| {
                    x.content(
                        "dcc:name",
                        &Text::identification(
                            "certificate.authorisation.name",
                            &cert.authorisation.name,
                        )?,
                    )
                })?;
                x.own_content(
                    "dcc:description",
                    "authorises the certificate",
                )?;
                x.leaf(
                    "dcc:role",
                    &Text::free("certificate.authorisation.role", &cert.authorisation.role)?,
                )?;
                x.own("dcc:mainSigner", "true")
            })
        })?;
        x.el("dcc:customer", |x| {
            x.content(
                "dcc:name",
                &Text::identification("certificate.customer.name", &cert.customer.name)?,
            )?;
            address(x, "certificate.customer.address", &cert.customer.address)
        })?;
        x.el("dcc:statements", |x| statements(x, cert))
    })
}

/// `dcc:software`: the tool with its release and the commit it was built from.
pub(crate) fn software_element(x: &mut Xml, software: &Software) -> Result<()> {
    x.el("dcc:software", |x| {
        x.content("dcc:name", &Text::free("software name", &software.name)?)?;
        x.leaf(
            "dcc:release",
            &Text::free("software release", &software.release)?,
        )?;
        x.own("dcc:type", "application")?;
        x.content(
            "dcc:description",
            &Text::free(
                "software commit",
                &format!(
                    "Computed the results and wrote this certificate; built from source commit {}.",
                    software.commit
                ),
            )?,
        )
    })
}

/// `dcc:items`: the PIGA with its manufacturer, model and serial number.
fn items(x: &mut Xml, cert: &CertificateResults) -> Result<()> {
    let item = &cert.item;
    x.el("dcc:items", |x| {
        x.el("dcc:item", |x| {
            x.content(
                "dcc:name",
                &Text::free("certificate.item.description", &item.description)?,
            )?;
            x.content(
                "dcc:description",
                &Text::free(
                    "certificate.item.condition",
                    &format!("Condition on receipt: {}", item.condition),
                )?,
            )?;
            x.el("dcc:manufacturer", |x| {
                x.content(
                    "dcc:name",
                    &Text::identification("certificate.item.manufacturer", &item.manufacturer)?,
                )
            })?;
            x.leaf(
                "dcc:model",
                &Text::identification("certificate.item.model", &item.model)?,
            )?;
            x.el("dcc:identifications", |x| {
                x.el("dcc:identification", |x| {
                    x.own("dcc:issuer", "manufacturer")?;
                    x.leaf(
                        "dcc:value",
                        &Text::identification("certificate.item.serial", &item.serial)?,
                    )?;
                    x.own_content("dcc:name", "serial number")
                })
            })
        })
    })
}

/// `dcc:location` holding a one-line postal address as written.
fn address(x: &mut Xml, field: &str, address: &str) -> Result<()> {
    let text = Text::free(field, address)?;
    x.el("dcc:location", |x| x.content("dcc:further", &text))
}

/// One `dcc:statement` of the administrative data: a name and a declaration.
fn statement(x: &mut Xml, name: &str, declaration: &Text) -> Result<()> {
    x.el("dcc:statement", |x| {
        x.own_content("dcc:name", name)?;
        x.content("dcc:declaration", declaration)
    })
}

/// The statements that concern the whole calibration: where it was performed, the
/// laboratory's accreditation and country, the procedure and departures from it, and how
/// each Type B input of the budget is traceable.
fn statements(x: &mut Xml, cert: &CertificateResults) -> Result<()> {
    statement(
        x,
        "Place of calibration",
        &Text::free("certificate.location", &cert.location)?,
    )?;
    if let Some(a) = &cert.laboratory.accreditation {
        statement(
            x,
            "Accreditation",
            &Text::free("certificate.laboratory.accreditation", a)?,
        )?;
    }
    if cert.laboratory.country.is_none() {
        statement(
            x,
            "Country of the laboratory",
            &Text::own(format!(
                "The study (and its lab profile, if it names one) does not state the laboratory's \
                 country: {UNKNOWN_COUNTRY} (a code ISO 3166-1 leaves to users, read as unknown) \
                 is written in its place."
            )),
        )?;
    }
    statement(
        x,
        "Procedure",
        &Text::free("certificate.procedure", &cert.procedure)?,
    )?;
    statement(
        x,
        "Departures from the procedure",
        &match &cert.deviations {
            Some(d) => Text::free("certificate.deviations", d)?,
            None => Text::own("none stated"),
        },
    )?;
    for (i, t) in cert.traceability.iter().enumerate() {
        x.el("dcc:statement", |x| {
            x.content(
                "dcc:name",
                &Text::free(
                    &format!("certificate.traceability[{i}].input"),
                    &format!("Traceability of the input {}", t.input),
                )?,
            )?;
            x.own("dcc:traceable", "true")?;
            x.content(
                "dcc:declaration",
                &Text::free(
                    &format!("certificate.traceability[{i}].statement"),
                    &t.statement,
                )?,
            )
        })?;
    }
    Ok(())
}
