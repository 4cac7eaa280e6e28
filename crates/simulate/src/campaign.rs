//! Multi-mounting campaigns (issue 29 part 5, `docs/MODEL.md`): the accelerometer — a PIGA or
//! a pendulous accelerometer with any of the IEEE 836 model's terms — mounted several ways on
//! the arm of a spindle with error motion and an arm that stretches, each mounting at its own
//! true radius, with its true axes (the fixture's index error: they may differ from the
//! declared ones) and its own bias shift; the noise-free mean outputs over whole revolutions
//! of the exact chain (`accel_model::mounted_point`), and white noise on them, one
//! independent stream per (seed, campaign, mounting).

use accel_model::{
    CaseAxes, ModelCoefficients, MountedPoint, MountedSpindle, MountingPreset, Term, mounted_point,
};
use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};

use crate::error::{Result, SimulateError};

/// The stream tag of the campaigns' noise (beside the scenario's probe and PIGA streams).
const CAMPAIGN_STREAM: u64 = 9;

/// One mounting of a simulated campaign, as it truly is.
#[derive(Debug, Clone, PartialEq)]
pub struct CampaignMounting {
    /// The true case axes in the spindle frame.
    pub axes: CaseAxes,
    /// The true static radius, m.
    pub radius_m: f64,
    /// Added to the output in this mounting (remounting shifts the bias), output units.
    pub bias_shift: f64,
}

/// A multi-mounting campaign.
#[derive(Debug, Clone, PartialEq)]
pub struct MountingCampaign {
    /// The spindle (site, error motion) and the arm stretch.
    pub spindle: MountedSpindle,
    /// The accelerometer's true coefficients (and kind).
    pub coefficients: ModelCoefficients,
    /// The mountings.
    pub mountings: Vec<CampaignMounting>,
    /// The rates of every mounting, rad/s.
    pub rates_rad_s: Vec<f64>,
}

/// The site latitude of [`fixture_spindle`], degrees.
pub const FIXTURE_LATITUDE_DEG: f64 = 39.9;

/// The spindle of the two-orientation and mounting fixtures (fixtures/scenarios/
/// two_orientation.ron) as the multi-mounting campaigns see it: R = 2.5 m, g = 9.8 m/s², at
/// [`FIXTURE_LATITUDE_DEG`]; a static drift of 5.6 µm along the arm and −1.97 µm across it,
/// C_r = 1.6e-6 m·s² along and 0.4e-6 across; an arm that stretches by 0.48e-6 m·s², which the
/// probe does not see. The fixtures, their tests and the joint fit's benchmark share it.
#[must_use]
pub fn fixture_spindle() -> MountedSpindle {
    use kinematics::{Centrifuge, EARTH_RATE_RAD_S, ErrorMotion, Site};
    MountedSpindle {
        centrifuge: Centrifuge {
            radius_m: 2.5,
            site: Site {
                latitude_deg: FIXTURE_LATITUDE_DEG,
                earth_rate_rad_s: EARTH_RATE_RAD_S,
                gravity_m_s2: 9.8,
            },
            error_motion: ErrorMotion {
                dr_xs_m: 5.6e-6,
                dr_ys_m: -1.97e-6,
                c_r_m_s2: 1.6e-6,
                c_r_y_m_s2: 0.4e-6,
                ..ErrorMotion::ZERO
            },
        },
        arm_stretch_m_s2: 0.48e-6,
    }
}

/// The mountings of the fixtures' five-mounting campaigns: preset and static radius, m.
pub const FIXTURE_MOUNTINGS: [(MountingPreset, f64); 5] = [
    (MountingPreset::IaIn, 2.5),
    (MountingPreset::IaOut, 2.54),
    (MountingPreset::Ia45, 2.48),
    (MountingPreset::IaTangential, 2.52),
    (MountingPreset::IaAxial, 2.46),
];

/// The fixtures' PIGA: true coefficients (rad/s per gⁿ; misalignments in rad).
pub const FIXTURE_PIGA_TRUTH: [(Term, f64); 8] = [
    (Term::K0, 1e-5),
    (Term::K1, 0.56),
    (Term::K2, 5e-7),
    (Term::K3, 2e-8),
    (Term::Koq, 3e-7),
    (Term::Kio, 1e-6),
    (Term::DeltaO, 1e-4),
    (Term::DeltaP, -5e-5),
];

/// The fixtures' pendulous accelerometer: true coefficients (mA per gⁿ; misalignments in
/// rad): k2 of 20 µg/g², a cross-axis k_pp and k_io (docs/MODEL.md's worked example).
pub const FIXTURE_PENDULOUS_TRUTH: [(Term, f64); 9] = [
    (Term::K0, 0.02),
    (Term::K1, 1.3),
    (Term::K2, 2.6e-5),
    (Term::K3, 1.3e-6),
    (Term::K4, 4e-8),
    (Term::Kpp, 1.5e-5),
    (Term::Kio, 8e-6),
    (Term::DeltaO, 2e-4),
    (Term::DeltaP, 1e-4),
];

/// The noise-free points of every mounting (mounting by mounting, rate by rate): the mean
/// output over whole revolutions of the exact chain and the mean inputs.
///
/// # Errors
/// [`SimulateError::Campaign`] naming the mounting and rate the model refused.
pub fn campaign_points(campaign: &MountingCampaign) -> Result<Vec<Vec<MountedPoint>>> {
    campaign
        .mountings
        .iter()
        .enumerate()
        .map(|(m, mounting)| {
            campaign
                .rates_rad_s
                .iter()
                .enumerate()
                .map(|(i, &w)| {
                    mounted_point(
                        &campaign.spindle,
                        &campaign.coefficients,
                        &mounting.axes,
                        mounting.radius_m,
                        mounting.bias_shift,
                        w,
                    )
                    .map_err(|source| SimulateError::Campaign {
                        field: format!("mountings[{m}].rates[{i}]"),
                        source,
                    })
                })
                .collect()
        })
        .collect()
}

/// The outputs of campaign number `campaign` (from 0) of a set seeded by `seed`: each
/// noise-free output plus N(0, σ²), `sigma` in output units (finite, ≥ 0).
///
/// # Errors
/// [`SimulateError::Campaign`] for a σ that is not
/// finite and ≥ 0.
pub fn noisy_outputs(
    points: &[Vec<MountedPoint>],
    sigma: f64,
    seed: u64,
    campaign: u64,
) -> Result<Vec<Vec<f64>>> {
    let normal = Normal::new(0.0, sigma).map_err(|_| SimulateError::Campaign {
        field: "sigma".to_owned(),
        source: accel_model::AccelModelError::NonFinite {
            field: "sigma",
            value: sigma,
        },
    })?;
    Ok(points
        .iter()
        .enumerate()
        .map(|(m, mounting)| {
            let key = campaign.wrapping_mul(1 << 16).wrapping_add(m as u64);
            let mut rng = StdRng::seed_from_u64(units::stream_seed(seed, CAMPAIGN_STREAM, key));
            mounting
                .iter()
                .map(|p| p.output + normal.sample(&mut rng))
                .collect()
        })
        .collect())
}
