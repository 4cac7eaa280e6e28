//! What a study hands the records: its results and the bytes of the files it wrote (the
//! command line reads them), turned into the rows to store, on values. Everything that can
//! be wrong is found here, before the database is touched: a study that fails records nothing.

use pipeline::{CertifiedMethod, DegreesOfFreedom, HeadlineMethod, StudyResults};
use sha2::{Digest as _, Sha256};

use crate::date::Date;
use crate::error::{RecordsError, Result};

/// A file a study read, as its `results.json` provenance lists it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputFile {
    /// `configuration`, `expected`, `probe_recording`, `piga_table` or `piga_recording`.
    pub role: String,
    /// The configuration field naming it, if any.
    pub field: Option<String>,
    /// The path as the study read it.
    pub path: String,
    /// Its size when read.
    pub bytes: u64,
    /// Its SHA-256, 64 lowercase hexadecimal digits.
    pub sha256: String,
}

/// A study to record.
#[derive(Debug, Clone)]
pub struct Submission<'a> {
    /// The study's results.
    pub results: &'a StudyResults,
    /// `results.json` as written: its SHA-256 is the record's key (it holds the SHA-256 of
    /// the configuration and of every input file).
    pub results_json: &'a [u8],
    /// The files the study read (its provenance).
    pub inputs: Vec<InputFile>,
    /// The version of the tool that ran the study.
    pub tool_version: Option<String>,
    /// `certificate.dcc.xml`, when the study wrote one (stored, and its SHA-256).
    pub dcc_xml: Option<&'a [u8]>,
    /// `certificate.pdf`, when there is one (its SHA-256).
    pub certificate_pdf: Option<&'a [u8]>,
    /// The centrifuge, when named on the command line (else the certificate's equipment
    /// whose role names a centrifuge).
    pub centrifuge: Option<String>,
    /// The date of measurement of a study without a certificate.
    pub date: Option<Date>,
    /// The lab profile the study ran under, if any.
    pub profile: Option<String>,
    /// The identification of the certificate this study's certificate corrects.
    pub supersedes: Option<String>,
}

/// A unit's identity.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct UnitIdentity {
    /// What it is (the certificate's item description).
    pub kind: String,
    /// Its manufacturer.
    pub manufacturer: String,
    /// Its model.
    pub model: String,
    /// Its serial number.
    pub serial: String,
}

impl std::fmt::Display for UnitIdentity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.model, self.serial)
    }
}

/// One certified coefficient as stored.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CertifiedRow {
    pub(crate) term: String,
    pub(crate) mounting: Option<String>,
    pub(crate) unit: String,
    pub(crate) value: f64,
    pub(crate) u: f64,
    pub(crate) expanded: f64,
    pub(crate) k: Option<f64>,
    pub(crate) dof: Option<f64>,
    pub(crate) low95: f64,
    pub(crate) high95: f64,
    pub(crate) interval_method: &'static str,
}

/// A certificate as stored.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CertificateRow {
    pub(crate) id: String,
    pub(crate) unit: UnitIdentity,
    pub(crate) issued: Date,
    pub(crate) method: &'static str,
    pub(crate) dcc_sha256: Option<String>,
    pub(crate) pdf_sha256: Option<String>,
    pub(crate) dcc_xml_zlib: Option<Vec<u8>>,
    pub(crate) certified: Vec<CertifiedRow>,
    pub(crate) covariance: Vec<Vec<f64>>,
}

/// A probe phase as stored.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PhaseRow {
    pub(crate) name: String,
    pub(crate) c_r_m_s2: f64,
    pub(crate) c_r_u_m_s2: Option<f64>,
    pub(crate) offset_um: f64,
    pub(crate) delta_k2_rad_s_g2: f64,
    pub(crate) delta_k2_u_rad_s_g2: Option<f64>,
}

/// Everything one study adds to the records.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Rows {
    pub(crate) hash: String,
    pub(crate) name: String,
    pub(crate) measured: (Date, Date),
    pub(crate) operator: Option<String>,
    pub(crate) procedure: Option<String>,
    pub(crate) profile: Option<String>,
    pub(crate) tool_version: Option<String>,
    pub(crate) centrifuge: Option<String>,
    pub(crate) radius_m: f64,
    pub(crate) g_m_s2: f64,
    pub(crate) k1_rad_s_g: f64,
    pub(crate) compensated_with: Option<String>,
    pub(crate) inputs: Vec<InputFile>,
    pub(crate) phases: Vec<PhaseRow>,
    pub(crate) certificate: Option<CertificateRow>,
    pub(crate) supersedes: Option<String>,
}

/// SHA-256 in 64 lowercase hexadecimal digits.
pub fn sha256_hex(bytes: &[u8]) -> String {
    use std::fmt::Write as _;
    Sha256::digest(bytes)
        .iter()
        .fold(String::with_capacity(64), |mut s, b| {
            let _ = write!(s, "{b:02x}");
            s
        })
}

fn finite(what: impl FnOnce() -> String, x: f64) -> Result<f64> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(RecordsError::NonFinite { what: what() })
    }
}

/// The centrifuge a certificate names: the identity of its first equipment whose role
/// mentions a centrifuge.
fn centrifuge_of(results: &StudyResults) -> Option<String> {
    results.certificate.as_ref().and_then(|c| {
        c.equipment
            .iter()
            .find(|e| e.role.to_lowercase().contains("centrifuge"))
            .map(|e| e.identity.clone())
    })
}

impl Submission<'_> {
    /// The rows to store, every check done.
    pub(crate) fn rows(&self) -> Result<Rows> {
        let r = self.results;
        let centrifuge = self.centrifuge.clone().or_else(|| centrifuge_of(r));
        if r.certificate.is_none() && centrifuge.is_none() {
            return Err(RecordsError::NothingToRecord {
                study: r.study.clone(),
            });
        }
        if let (Some(id), None) = (&self.supersedes, &r.certificate) {
            return Err(RecordsError::SupersedesWithoutCertificate { id: id.clone() });
        }
        let measured = match (&r.certificate, self.date) {
            (_, Some(d)) => (d, d),
            (Some(c), None) => Date::parse_span("certificate.dates.measured", &c.dates.measured)?,
            (None, None) => {
                return Err(RecordsError::NoDate {
                    study: r.study.clone(),
                });
            }
        };
        let phases = r
            .phases
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let w = |q: &'static str| move || format!("phases[{i}].{q}");
                Ok(PhaseRow {
                    name: p.name.clone(),
                    c_r_m_s2: finite(w("c_r_m_s2"), p.fit.c_r_m_s2)?,
                    c_r_u_m_s2: p.fit.c_r_sigma_m_s2.filter(|u| u.is_finite() && *u > 0.0),
                    offset_um: finite(w("offset_um"), p.fit.offset_um)?,
                    delta_k2_rad_s_g2: finite(w("delta_k2_rad_s_g2"), p.fit.delta_k2_rad_s_g2)?,
                    delta_k2_u_rad_s_g2: p
                        .fit
                        .delta_k2_sigma_rad_s_g2
                        .filter(|u| u.is_finite() && *u > 0.0),
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let certificate = r.certificate.as_ref().map(|c| -> Result<CertificateRow> {
            let certified = c
                .certified
                .coefficients
                .iter()
                .enumerate()
                .map(|(i, k)| {
                    let w = |q: &'static str| {
                        move || format!("certificate.certified.coefficients[{i}].{q}")
                    };
                    Ok(CertifiedRow {
                        term: k.name.clone(),
                        mounting: k.mounting.clone(),
                        unit: k.unit.clone(),
                        value: finite(w("value"), k.value)?,
                        u: finite(w("u"), k.u)?,
                        expanded: finite(w("expanded"), k.expanded)?,
                        k: k.k.filter(|k| k.is_finite()),
                        dof: match k.dof {
                            DegreesOfFreedom::Finite(nu) => Some(finite(w("dof"), nu)?),
                            DegreesOfFreedom::Infinite(_) => None,
                        },
                        low95: finite(w("low95"), k.low95)?,
                        high95: finite(w("high95"), k.high95)?,
                        interval_method: match k.interval_method {
                            HeadlineMethod::Gum => "gum",
                            HeadlineMethod::MonteCarlo => "monte_carlo",
                        },
                    })
                })
                .collect::<Result<Vec<_>>>()?;
            for (i, row) in c.certified.covariance.iter().enumerate() {
                for (j, x) in row.iter().enumerate() {
                    finite(|| format!("certificate.certified.covariance[{i}][{j}]"), *x)?;
                }
            }
            Ok(CertificateRow {
                id: c.id.clone(),
                unit: UnitIdentity {
                    kind: c.item.description.clone(),
                    manufacturer: c.item.manufacturer.clone(),
                    model: c.item.model.clone(),
                    serial: c.item.serial.clone(),
                },
                issued: Date::parse_field("certificate.dates.issued", &c.dates.issued)?,
                method: match c.certified.method {
                    CertifiedMethod::Probe => "probe",
                    CertifiedMethod::TwoOrientation => "two_orientation",
                },
                dcc_sha256: self.dcc_xml.map(sha256_hex),
                pdf_sha256: self.certificate_pdf.map(sha256_hex),
                dcc_xml_zlib: self
                    .dcc_xml
                    .map(|x| miniz_oxide::deflate::compress_to_vec_zlib(x, 6)),
                certified,
                covariance: c.certified.covariance.clone(),
            })
        });
        let certificate = certificate.transpose()?;
        Ok(Rows {
            hash: sha256_hex(self.results_json),
            name: r.study.clone(),
            measured,
            operator: r.certificate.as_ref().map(|c| c.operator.clone()),
            procedure: r.certificate.as_ref().map(|c| c.procedure.clone()),
            profile: self.profile.clone(),
            tool_version: self.tool_version.clone(),
            centrifuge,
            radius_m: r.inputs.radius_m,
            g_m_s2: r.inputs.g_m_s2,
            k1_rad_s_g: r.inputs.k1_rad_s_g,
            compensated_with: r.calibration.as_ref().map(|c| c.compensate_with.clone()),
            inputs: self.inputs.clone(),
            phases,
            certificate,
            supersedes: self.supersedes.clone(),
        })
    }
}
