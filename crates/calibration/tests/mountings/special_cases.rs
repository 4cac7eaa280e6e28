//! Eq. 18 (one mounting, IA in) and eq. 23 (IA in and IA out) through the general model give
//! the existing fits' coefficients on the fixtures' data.

use accel_model::{AccelKind, Mounting, MountingPreset, Term};
use calibration::{
    ArmStretch, Column, JointSpec, MountingData, Nuisances, Orientation, OrientationData, Points,
    calibrate, fit_mountings, fit_two_orientation,
};

fn fixture(path: &str) -> (Vec<f64>, Vec<f64>) {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/");
    let text = std::fs::read_to_string(format!("{root}{path}")).expect("the fixture");
    let mut rates = Vec::new();
    let mut outputs = Vec::new();
    for line in text.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let v: Vec<f64> = line
            .split(',')
            .map(|x| x.trim().parse().expect("a number"))
            .collect();
        rates.push(v[0].to_radians());
        outputs.push(v[1]);
    }
    (rates, outputs)
}

fn spec(terms: &[Term], arm_stretch: ArmStretch) -> JointSpec {
    JointSpec {
        kind: AccelKind::Piga,
        terms: terms.to_vec(),
        omega3: true,
        arm_stretch,
        g_m_s2: 9.8,
        earth_rate_vertical_rad_s: 0.0,
        probe: None,
    }
}

fn close(what: &str, a: f64, b: f64, rel: f64) {
    assert!(
        (a - b).abs() <= rel * b.abs(),
        "{what}: {a:e} through the general model against {b:e} ({:e} relative)",
        (a / b - 1.0).abs()
    );
}

const K0_3: [Term; 4] = [Term::K0, Term::K1, Term::K2, Term::K3];

#[test]
fn eq18_is_one_ia_in_mounting_with_k0_to_k3() {
    let (rates, outputs) = fixture("campaign/piga.csv");
    let geometry = identify::Geometry {
        radius_m: 2.5,
        g_m_s2: 9.8,
    };
    let points = Points {
        rates_rad_s: &rates,
        outputs_rad_s: &outputs,
        sigma_rad_s: None,
    };
    let eq18 = calibrate(&points, geometry).unwrap().calibration;
    let data = [MountingData {
        field: "mountings[0]".to_owned(),
        mounting: Mounting::preset(MountingPreset::IaIn, 2.5, 0.0),
        nuisances: Nuisances::REFERENCE,
        rates_rad_s: &rates,
        outputs: &outputs,
        sigma: None,
    }];
    let general = fit_mountings(&spec(&K0_3, ArmStretch::Off), &data).unwrap();
    let t = |term| general.term(term).unwrap();
    close("k0", t(Term::K0).value, eq18.bias_rad_s, 1e-12);
    close("k1", t(Term::K1).value, eq18.k1_implied_rad_s_g, 1e-12);
    close("k2", t(Term::K2).value, eq18.k2_apparent_rad_s_g2, 1e-12);
    close("k3", t(Term::K3).value, eq18.k3_rad_s_g3, 1e-12);
    close(
        "ω",
        general.coefficient(Column::TiltRate(0)).unwrap().0,
        eq18.omega_coeff,
        1e-12,
    );
    close(
        "ω³",
        general.coefficient(Column::Omega3).unwrap().0,
        eq18.omega3_coeff_s2,
        1e-12,
    );
    close(
        "u(k2)",
        t(Term::K2).u,
        eq18.k2_apparent_sigma_rad_s_g2,
        1e-12,
    );
    close("u(k3)", t(Term::K3).u, eq18.k3_sigma_rad_s_g3, 1e-12);
}

#[test]
fn eq23_is_ia_in_and_ia_out_with_their_own_bias_scale_and_omega_terms() {
    let (rin, yin) = fixture("two_orientation/piga_ia_in.csv");
    let (rout, yout) = fixture("two_orientation/piga_ia_out.csv");
    let sets = [
        OrientationData {
            field: "in",
            orientation: Some(Orientation::IaIn),
            radius_m: Some(2.5),
            rates_rad_s: &rin,
            output_rad_s: &yin,
            sigma_rad_s: None,
        },
        OrientationData {
            field: "out",
            orientation: Some(Orientation::IaOut),
            radius_m: Some(2.54),
            rates_rad_s: &rout,
            output_rad_s: &yout,
            sigma_rad_s: None,
        },
    ];
    let eq23 = fit_two_orientation(&sets, 9.8, "o").unwrap();
    let data = [
        MountingData {
            field: "mountings[0]".to_owned(),
            mounting: Mounting::preset(MountingPreset::IaIn, 2.5, 0.0),
            nuisances: Nuisances::REFERENCE,
            rates_rad_s: &rin,
            outputs: &yin,
            sigma: None,
        },
        MountingData {
            field: "mountings[1]".to_owned(),
            mounting: Mounting::preset(MountingPreset::IaOut, 2.54, 0.0),
            nuisances: Nuisances {
                own_bias: true,
                own_scale: true,
                tilt_rate: true,
            },
            rates_rad_s: &rout,
            outputs: &yout,
            sigma: None,
        },
    ];
    let general = fit_mountings(&spec(&K0_3, ArmStretch::Fit), &data).unwrap();
    let t = |term| general.term(term).unwrap();
    let [m_in, m_out] = &eq23.mountings;
    let rel = 1e-12;
    close("k0 (IA in)", t(Term::K0).value, m_in.k0_rad_s.0, rel);
    close("k1 (IA in)", t(Term::K1).value, m_in.k1_rad_s_g.0, rel);
    let coef = |c| general.coefficient(c).unwrap().0;
    close(
        "k0 (IA out)",
        coef(Column::OwnBias(1)),
        m_out.k0_rad_s.0,
        rel,
    );
    close(
        "k1 (IA out)",
        coef(Column::OwnScale(1)),
        m_out.k1_rad_s_g.0,
        rel,
    );
    close("b1 (IA in)", coef(Column::TiltRate(0)), m_in.b1.0, rel);
    // IA out's ω column is s·ω with s = −1, as eq. 23 writes it
    close("b1 (IA out)", coef(Column::TiltRate(1)), m_out.b1.0, rel);
    close("b3", coef(Column::Omega3), eq23.b3.0, rel);
    close("k2", t(Term::K2).value, eq23.k2_rad_s_g2.0, rel);
    close("k3", t(Term::K3).value, eq23.k3_rad_s_g3.0, rel);
    close("γ", coef(Column::ArmStretch), eq23.gamma.0, rel);
    close("u(k2)", t(Term::K2).u, eq23.k2_rad_s_g2.1, rel);
    close(
        "u(γ)",
        general.coefficient(Column::ArmStretch).unwrap().1,
        eq23.gamma.1,
        rel,
    );
}
