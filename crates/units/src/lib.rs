//! The workspace's shared vocabulary of numbers: unit conversions (the one place where deg/s
//! become rad/s and µm become m), how an error message writes a number ([`Compact`]), what a
//! number must be ([`Requirement`], checked by [`finite`], [`positive`], [`non_negative`],
//! [`require`]), how a seed becomes independent random streams ([`stream_seed`]) and how an
//! error and its causes become one line ([`ErrorChain`]).
//!
//! Every crate that converts a configured or reported quantity calls these `const fn`s, so a
//! conversion factor exists once in the workspace. [`Compact`] is the one way a quantity is
//! written into an error message. No dependencies.

mod chain;
mod compact;
mod requirement;
mod seed;

pub use chain::ErrorChain;
pub use compact::{Compact, CompactList, CompactSeries};
pub use requirement::{Requirement, Unmet, finite, non_negative, positive, require};
pub use seed::stream_seed;

use std::f64::consts::PI;

/// The local gravity the tools accept, m/s² (a study's `g_m_s2`, a plan's
/// `centrifuge.g_m_s2`): the Earth's surface gravity is 9.780 at the equator to 9.832 at the
/// poles, less by about 3·10⁻⁶ per metre of altitude. A value outside is a typing or unit
/// error (g = 1 "in g", or 1e300, which made every bound that scales with it absurd).
pub const GRAVITY_RANGE_M_S2: std::ops::RangeInclusive<f64> = 9.7..=9.9;

/// Degrees per second to radians per second.
pub const fn deg_s_to_rad_s(rate_deg_s: f64) -> f64 {
    rate_deg_s * (PI / 180.0)
}

/// Micrometres to metres.
pub const fn um_to_m(length_um: f64) -> f64 {
    length_um / 1e6
}

/// Metres to micrometres.
pub const fn m_to_um(length_m: f64) -> f64 {
    length_m * 1e6
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions() {
        assert_eq!(deg_s_to_rad_s(180.0), PI);
        assert_eq!(um_to_m(2.5), 2.5e-6);
        assert!((m_to_um(um_to_m(5.598)) - 5.598).abs() < 1e-15);
    }
}
