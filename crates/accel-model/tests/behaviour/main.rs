//! Behaviour tests of the PIGA model against the exact chain and eq. 17.

mod agreement;
mod mechanism;
mod points;

use accel_model::PigaCoefficients;
use kinematics::{Centrifuge, EARTH_RATE_RAD_S, ErrorMotion, Site};

/// Realistic PIGA: the paper's k1; k0, k2, k3 of typical magnitude.
pub(crate) const PIGA: PigaCoefficients = PigaCoefficients {
    k0_rad_s: 1.0e-5,
    k1_rad_s_g: 0.56,
    k2_rad_s_g2: 2.0e-6,
    k3_rad_s_g3: 1.0e-7,
};

/// The paper's rate points, rad/s.
pub(crate) fn paper_rates() -> Vec<f64> {
    [10.0, 60.0, 80.1234, 110.1234, 160.1234, 200.1234]
        .iter()
        .map(|d: &f64| d.to_radians())
        .collect()
}

/// Error motion with every coefficient non-zero (pre-balance magnitudes).
pub(crate) fn errors() -> ErrorMotion {
    ErrorMotion {
        dr_xs_m: 5.6e-6,
        dr_ys_m: -3.1e-6,
        dphi_xs_rad: 4.0e-6,
        dphi_ys_rad: 2.5e-6,
        c_r_m_s2: 1.6e-6,
        c_r_y_m_s2: -0.7e-6,
        c_phi_x_s2: 0.3e-6,
        c_phi_s2: 0.5e-6,
    }
}

pub(crate) fn centrifuge(error_motion: ErrorMotion) -> Centrifuge {
    Centrifuge {
        radius_m: 2.5,
        site: Site {
            latitude_deg: 45.75,
            earth_rate_rad_s: EARTH_RATE_RAD_S,
            gravity_m_s2: 9.8,
        }
        .validated()
        .unwrap(),
        error_motion,
    }
}
