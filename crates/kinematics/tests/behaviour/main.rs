//! Behaviour tests of the kinematic chain (eq. 5–14).

mod chain;
mod first_order;
mod properties;
mod scenario_files;

use kinematics::{Centrifuge, ErrorMotion, Site};

/// A realistic error motion (pre-balance magnitudes) with every coefficient non-zero.
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

pub(crate) fn site() -> Site {
    Site {
        latitude_deg: 45.75,
        earth_rate_rad_s: kinematics::EARTH_RATE_RAD_S,
        gravity_m_s2: 9.8,
    }
    .validated()
    .unwrap()
}

pub(crate) fn centrifuge(error_motion: ErrorMotion) -> Centrifuge {
    Centrifuge {
        radius_m: 2.5,
        site: site(),
        error_motion,
    }
}
