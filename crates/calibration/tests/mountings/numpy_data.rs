//! One simulated five-mounting campaign of each kind, with the joint fit's terms, written as
//! JSON for the independent NumPy fit (`bench/model_numpy.py`): to `$MODEL_NUMPY_DIR` when
//! set, else to a directory under the system's temporary directory (printed).

use accel_model::{AccelKind, OutputUnit, Term};
use calibration::fit_mountings;
use simulate::{campaign_points, noisy_outputs};

use crate::coverage::{PROBE, campaign, data, rates, spec, truth};

fn json_list(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| format!("{x:e}")).collect();
    format!("[{}]", items.join(", "))
}

fn write_kind(kind: AccelKind, tag: &str, dir: &std::path::Path) -> std::path::PathBuf {
    let (coefficients, terms, sigma) = truth(kind);
    let spec = spec(kind, terms.clone());
    let camp = campaign(coefficients);
    let points = campaign_points(&camp).unwrap();
    let outputs = noisy_outputs(&points, sigma, 4711, 0).unwrap();
    let rates = rates();
    let d = data(&rates, &outputs);
    let fit = fit_mountings(&spec, &d).unwrap();
    let mountings: Vec<String> = d
        .iter()
        .enumerate()
        .map(|(m, md)| {
            let a = md.mounting.axes;
            format!(
                "{{\"ia\": {}, \"pa\": {}, \"oa\": {}, \"radius_m\": {:e}, \"own_bias\": {}, \"tilt_rate\": {}, \"outputs\": {}}}",
                json_list(&a.ia),
                json_list(&a.pa),
                json_list(&a.oa),
                md.mounting.radius_m,
                md.nuisances.own_bias && m > 0,
                md.nuisances.tilt_rate,
                json_list(md.outputs)
            )
        })
        .collect();
    let fitted: Vec<String> = terms
        .iter()
        .map(|t| {
            let e = fit.term(*t).unwrap();
            format!("\"{}\": [{:e}, {:e}]", t.tag(), e.value, e.u)
        })
        .collect();
    let arm = fit.arm_stretch.unwrap();
    let text = format!(
        "{{\"kind\": \"{tag}\", \"g_m_s2\": {:e}, \"earth_rate_vertical_rad_s\": {:e}, \
         \"probe\": {{\"static_m\": {:e}, \"c_r_m_s2\": {:e}, \"static_across_m\": {:e}, \"c_ry_m_s2\": {:e}}}, \
         \"rates_rad_s\": {}, \"terms\": [{}], \"mountings\": [{}], \
         \"rust\": {{{}, \"arm_stretch_gamma\": [{:e}, {:e}]}}}}\n",
        spec.g_m_s2,
        spec.earth_rate_vertical_rad_s,
        PROBE.static_m,
        PROBE.c_r_m_s2,
        PROBE.static_across_m,
        PROBE.c_ry_m_s2,
        json_list(&rates),
        terms
            .iter()
            .map(|t| format!("\"{}\"", t.tag()))
            .collect::<Vec<_>>()
            .join(", "),
        mountings.join(", "),
        fitted.join(", "),
        arm.gamma.0,
        arm.gamma.1,
    );
    let path = dir.join(format!("campaign_{tag}.json"));
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
#[allow(clippy::print_stderr)] // where the files went, shown with --nocapture
fn a_campaign_of_each_kind_is_written_for_the_numpy_fit() {
    let dir = std::env::var_os("MODEL_NUMPY_DIR").map_or_else(
        || std::env::temp_dir().join("centrifuge-cal-model-numpy"),
        std::path::PathBuf::from,
    );
    std::fs::create_dir_all(&dir).unwrap();
    for (kind, tag) in [
        (AccelKind::Piga, "piga"),
        (
            AccelKind::Pendulous {
                unit: OutputUnit::MilliAmpere,
            },
            "pendulous",
        ),
    ] {
        let path = write_kind(kind, tag, &dir);
        let back = std::fs::read_to_string(&path).unwrap();
        assert!(back.contains(Term::K2.tag()) && back.contains("\"rust\""));
        eprintln!("wrote {}", path.display());
    }
}
