//! The centrifuge and the PIGA a plan's simulation check simulates (`plan --simulate`), for
//! one mounting or two: one home for both.

use planning::PlanInputs;

/// The plan's centrifuge at `latitude_deg` (its radius, g and the expected C_r) and its PIGA's
/// coefficients, as `simulate` takes them.
pub(crate) fn simulated(
    inputs: &PlanInputs,
    latitude_deg: f64,
) -> (kinematics::Centrifuge, accel_model::PigaCoefficients) {
    let centrifuge = kinematics::Centrifuge {
        radius_m: inputs.centrifuge.radius_m,
        site: kinematics::Site {
            latitude_deg,
            earth_rate_rad_s: kinematics::EARTH_RATE_RAD_S,
            gravity_m_s2: inputs.centrifuge.g_m_s2,
        },
        error_motion: kinematics::ErrorMotion {
            c_r_m_s2: inputs.c_r.expected_m_s2,
            ..kinematics::ErrorMotion::ZERO
        },
    };
    let p = &inputs.piga;
    let piga = accel_model::PigaCoefficients {
        k0_rad_s: p.k0_rad_s,
        k1_rad_s_g: p.k1_rad_s_g,
        k2_rad_s_g2: p.k2_rad_s_g2,
        k3_rad_s_g3: p.k3_rad_s_g3,
    };
    (centrifuge, piga)
}
