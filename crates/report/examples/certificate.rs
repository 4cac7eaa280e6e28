//! Runs a study and writes its calibration certificate (`certificate.html`) beside its other
//! outputs, with the certificate items from a separate RON file. CI renders the campaign
//! fixture's certificate with it (`.ci/certificate`):
//!
//! ```sh
//! cargo run -p report --example certificate -- fixtures/studies/campaign.ron \
//!     fixtures/certificates/campaign.ron target/ci-certificate
//! ```

use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    let [study, info, out] = args.as_slice() else {
        return Err("usage: certificate STUDY.ron CERTIFICATE.ron OUT_DIR".into());
    };
    let inputs = pipeline::load_study(study)?;
    let results = pipeline::run(&inputs)?;
    let provenance = report::Provenance::of_study(&inputs, None)?;
    let text = std::fs::read_to_string(info)?;
    let info: report::CertificateInfo =
        ron::from_str(&text).map_err(|e| format!("{}: {e}", info.display()))?;
    let html = report::certificate_html(
        &results,
        &info,
        &provenance,
        &report::Software::this_build(),
    )?;
    report::write_outputs(out, &results, None, None, Some(&provenance))?;
    std::fs::create_dir_all(out)?;
    std::fs::write(out.join("certificate.html"), html)?;
    Ok(())
}
