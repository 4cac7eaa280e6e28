//! A study with a certificate (the campaign fixture, run once) and variations of it.

use std::path::Path;
use std::sync::OnceLock;

use pipeline::StudyResults;
use records::{Date, Submission};

/// The campaign fixture's results (a certificate of PIGA-16 SN 1604-0117 on centrifuge CF-2).
pub(crate) fn campaign() -> &'static StudyResults {
    static RESULTS: OnceLock<StudyResults> = OnceLock::new();
    RESULTS.get_or_init(|| {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let inputs = pipeline::load_study(&root.join("fixtures/studies/campaign.ron")).unwrap();
        pipeline::run(&inputs).unwrap()
    })
}

/// The campaign's results as a certificate `id` measured on `date`, with k2 (and its
/// interval) moved to `k2`, and C_r moved to `c_r_m_s2` (Δk2 with it, eq. 19).
pub(crate) fn variant(
    id: &str,
    date: &str,
    k2: Option<f64>,
    c_r_m_s2: Option<f64>,
) -> StudyResults {
    let mut r = campaign().clone();
    let cert = r.certificate.as_mut().unwrap();
    cert.id = id.to_owned();
    cert.dates.measured = date.to_owned();
    cert.dates.issued = Date::parse(date).unwrap().plus_years(0.02).to_string();
    if let Some(k2) = k2 {
        let c = cert
            .certified
            .coefficients
            .iter_mut()
            .find(|c| c.name == "k2")
            .unwrap();
        let shift = k2 - c.value;
        c.value = k2;
        c.low95 += shift;
        c.high95 += shift;
    }
    if let Some(c_r) = c_r_m_s2 {
        let p = &mut r.phases[0];
        let ratio = c_r / p.fit.c_r_m_s2;
        p.fit.c_r_m_s2 = c_r;
        p.fit.delta_k2_rad_s_g2 *= ratio;
    }
    r
}

/// The JSON bytes a study would have written for `r` (their hash keys the record).
pub(crate) fn json(r: &StudyResults) -> Vec<u8> {
    serde_json::to_vec(r).unwrap()
}

/// A submission of `r` with no files beside it.
pub(crate) fn submission<'a>(r: &'a StudyResults, bytes: &'a [u8]) -> Submission<'a> {
    Submission {
        results: r,
        results_json: bytes,
        inputs: Vec::new(),
        tool_version: Some("test".into()),
        dcc_xml: None,
        certificate_pdf: None,
        centrifuge: None,
        date: None,
        profile: None,
        supersedes: None,
    }
}
