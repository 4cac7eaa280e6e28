//! What the certificate identifies and how: the identification table, what is certified
//! and within which range, the method with its references, and the files and software.

use pipeline::{CertificateResults, StudyResults};

use super::super::certified::{Certified, Method};
use super::super::model::{self, Field, Files};
use super::text::{method_name, mounting_label, rich, t, table};
use crate::format;
use crate::provenance::{FileRecord, Provenance, Software};

/// The identification fields; `study` is the study's name, the laboratory's reference of the
/// reduction (results.json holds it).
pub(super) fn identification(info: &CertificateResults, study: &str) -> Vec<Field> {
    let item = &info.item;
    let field = |label: &str, value: String| Field {
        label: label.to_owned(),
        value,
    };
    let mut fields = vec![
        field("Certificate", info.id.clone()),
        field(
            "Issued by",
            match &info.laboratory.accreditation {
                Some(a) => format!("{}, {}; {a}", info.laboratory.name, info.laboratory.address),
                None => format!("{}, {}", info.laboratory.name, info.laboratory.address),
            },
        ),
        field(
            "Item",
            format!("{}, {} {}", item.description, item.manufacturer, item.model),
        ),
        field("Serial number", item.serial.clone()),
        field("Condition on receipt", item.condition.clone()),
        field(
            "Customer",
            format!("{}, {}", info.customer.name, info.customer.address),
        ),
        field("Place of calibration", info.location.clone()),
        field("Date of receipt", info.dates.received.clone()),
        field("Date(s) of measurement", info.dates.measured.clone()),
        field("Date of issue", info.dates.issued.clone()),
        field("Procedure", info.procedure.clone()),
        field("Laboratory reference", study.to_owned()),
        field("Performed by", info.operator.clone()),
        field(
            "Authorised by",
            format!("{}, {}", info.authorisation.name, info.authorisation.role),
        ),
    ];
    if let Some(p) = &info.previous_certificate {
        fields.push(field(
            "Follows certificate",
            match &p.sha256 {
                Some(h) => format!("{} (SHA-256 of its file {h})", p.id),
                None => p.id.clone(),
            },
        ));
    }
    fields
}

pub(super) fn certified_section(cert: &Certified) -> model::Certified {
    let name = method_name(cert.method);
    let mountings: Vec<&str> = cert
        .validity
        .iter()
        .map(|v| v.mounting_words.as_str())
        .collect();
    let statement = match cert.method {
        Method::Probe => format!(
            "This certificate states the coefficients of the {name} (Liu et al. 2025): the \
             PIGA mounted with its {}, k2 compensated for the spindle's radius growth C_r \
             measured by a displacement probe.",
            mountings.join(" and ")
        ),
        Method::TwoOrientation => format!(
            "This certificate states the coefficients of the {name} (Sun et al. 2022, with \
             the model of Liu et al. 2025): the PIGA measured with its {}, k2 and k3 shared by \
             the two mountings and free of the centrifuge's radius growth.",
            mountings.join(" and with its ")
        ),
    };
    let refuted = cert.refuted_by_check.then(|| {
        let other = cert
            .check
            .map_or("the other method", |k| method_name(k.method));
        rich(&format!(
            "The laboratory certifies a value that its own check refutes: the {other} \
             disagrees with the certified k2 beyond its uncertainty (|z| > 3, see the check \
             below). The certified values are stated because the laboratory chose the {name} \
             explicitly."
        ))
    });
    model::Certified {
        method: name.to_owned(),
        statement: rich(&statement),
        reason: t(&cert.reason),
        model: rich(
            "Model of the mean output rate: ω_out = k0 + k1·a + k2·a² + k3·a³, with a the \
             specific force along the input axis in g (a = R·ω²/g at the working radius R and \
             spindle rate ω).",
        ),
        refuted,
        validity: table(
            &[
                "mounting",
                "working radius R",
                "spindle rates",
                "specific force along the input axis",
                "points",
            ],
            &[false, true, true, true, true],
            &[5, 2, 3, 3, 1],
            cert.validity
                .iter()
                .map(|v| {
                    vec![
                        t(format!(
                            "{}: {}",
                            mounting_label(Some(v.mounting.as_str())),
                            v.mounting_words
                        )),
                        t(format!("{} m", format::plain(v.radius_m))),
                        t(format!(
                            "{} to {} deg/s",
                            format::rate(v.rate_low_deg_s),
                            format::rate(v.rate_high_deg_s)
                        )),
                        t(format!(
                            "{} g to {} g",
                            format::significant(v.specific_force_low_g, 3),
                            format::significant(v.specific_force_high_g, 3)
                        )),
                        t(v.points.to_string()),
                    ]
                })
                .collect(),
        ),
    }
}

pub(super) fn method(
    results: &StudyResults,
    info: &CertificateResults,
    cert: &Certified,
) -> model::Method {
    let mut paragraphs = vec![rich(&format!(
        "The PIGA is mounted on the centrifuge arm at the working radius R = {} m with its \
         input axis towards the spindle axis, and calibrated at the rates stated under “What \
         is certified”; at each rate its mean output rate over whole spindle revolutions is \
         measured (IEEE Std 836). The centrifuge's dynamic imbalance makes the working radius \
         grow as C_r·ω², which adds k1·C_r·ω⁴/g to the output (Liu et al. 2025, eq. 17): \
         indistinguishable by least squares from k2·a², it would appear as a \
         pseudo-second-order term Δk2 = k1·C_r·g/R² (eq. 19). C_r is measured by a \
         displacement probe on the spindle (first harmonic of the gap per revolution, eq. \
         20–22) and the term removed. The coefficients are the least-squares solution of eq. \
         18 (columns 1, ω, ω², ω³, a², a³), through QR with column scaling; the terms in ω \
         and ω³ are nuisance terms of the set-up.",
        format::plain(results.inputs.radius_m)
    ))];
    if results.two_orientation.is_some() {
        paragraphs.push(rich(
            "The two-orientation method (Sun et al. 2022) fits the mean outputs of both \
             mountings (IA in and IA out) jointly (eq. 23): a bias k0, a scale factor k1 and an \
             ω term per mounting; k2, k3, an ω³ term and the radius growth's term γ = k1·C/g \
             shared, γ with the sign of the mounting. C − C_r is compared with its standard \
             uncertainty: |z| = |C − C_r|/u(C − C_r) above 3 is a disagreement.",
        ));
    }
    paragraphs.push(rich(&format!(
        "Uncertainties are evaluated by the GUM (JCGM 100) through the whole measurement \
         model and checked by the Monte Carlo method (JCGM 101); the certified values are \
         those of the {}. Statements of conformity follow ILAC-G8:09/2019.",
        method_name(cert.method)
    )));
    model::Method {
        paragraphs,
        deviations: info.deviations.clone(),
        references: [
            "Liu Y., Zhang C., He D., Yu Z., Ren S. (2025), The mechanism of PIGA's \
             pseudo-second-order term generated by spindle dynamic imbalance of centrifuge, \
             Navigation Positioning and Timing, doi:10.19306/j.cnki.2095-8110.2025.01.013 \
             (eq. 17–22).",
            "Sun, Ren, Cao, Huo (2022), Measurement: calibration with the input axis in two \
             orientations on a centrifuge (eq. 23).",
            "IEEE Std 836-2009, Recommended Practice for Precision Centrifuge Testing of Linear \
             Accelerometers.",
            "JCGM 100:2008, Evaluation of measurement data — Guide to the expression of \
             uncertainty in measurement (GUM).",
            "JCGM 101:2008, Evaluation of measurement data — Supplement 1 to the GUM — \
             Propagation of distributions using a Monte Carlo method.",
            "ILAC-G8:09/2019, Guidelines on Decision Rules and Statements of Conformity.",
            "ISO/IEC 17025:2017, General requirements for the competence of testing and \
             calibration laboratories, §7.8.",
        ]
        .into_iter()
        .map(t)
        .collect(),
    }
}

pub(super) fn files(provenance: Option<&Provenance>, software: &Software) -> Files {
    let Some(provenance) = provenance else {
        return Files {
            missing: Some(t(
                "The input files and their SHA-256 digests were not recorded with these results.",
            )),
            table: None,
            software: software.version.clone(),
            commit: software.commit.clone(),
        };
    };
    // a file read by two sections (the IA-in table by the calibration and the two-orientation
    // fit) is listed once
    let mut listed: Vec<(String, String)> = Vec::new();
    let mut rows = Vec::new();
    let mut record = |what: &str, f: &FileRecord| {
        let key = (f.path.clone(), f.sha256.clone());
        if listed.contains(&key) {
            return;
        }
        listed.push(key);
        rows.push(vec![
            t(what),
            t(&f.path),
            t(f.bytes.to_string()),
            t(&f.sha256),
        ]);
    };
    record("study file", &provenance.config);
    if let Some(p) = &provenance.profile {
        record("lab profile", p);
    }
    for f in &provenance.inputs {
        record(role_words(f.role.as_deref()), f);
    }
    if let Some(e) = &provenance.expected {
        record("expected values", e);
    }
    Files {
        missing: None,
        table: Some(table(
            &["file", "path", "bytes", "SHA-256"],
            &[false, false, true, false],
            &[3, 9, 2, 9],
            rows,
        )),
        software: software.version.clone(),
        commit: software.commit.clone(),
    }
}

/// A data file's role in words.
fn role_words(role: Option<&str>) -> &'static str {
    match role {
        Some("probe_recording") => "probe recording",
        Some("piga_table") => "PIGA table",
        Some("piga_recording") => "PIGA recording",
        _ => "data file",
    }
}
