//! Specific force and angular rate seen by the PIGA (eq. 12, 13).

use crate::frames::{Ground, Piga, Transform};
use crate::homogeneous::{cross, mat_mul, mat_vec, transpose};
use crate::jet::Jet;
use crate::site::Site;

/// The PIGA's inputs in its own frame `O3` at one instant (or averaged over a revolution).
///
/// With `T₃⁰ = [A D; 0 1]` (eq. 11) and `Ω_ie = [0, ω_ie cos L, ω_ie sin L]`, in g (eq. 12):
///
/// ```text
/// a_R = Aᵀ·D̈/g,    a_G = Aᵀ·[0 0 1]ᵀ,    a_C = 2·Aᵀ·(Ω_ie × Ḋ)/g
/// ```
///
/// and the angular rate (eq. 13) is `Aᵀ(Ω_ie + w)`, where `[w]× = Ȧ Aᵀ` is the angular
/// velocity of the PIGA relative to the ground; for the chain of eq. 5 with constant error
/// motion `w = ω ẑ`, which is the paper's form. Index 0 is the input axis `X3` (IA).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PigaInputs {
    /// Centripetal part a_R (the whole kinematic acceleration `Aᵀ D̈ / g`), g.
    pub centripetal_g: [f64; 3],
    /// Gravity part a_G (the specific force that supports the PIGA), g.
    pub gravity_g: [f64; 3],
    /// Coriolis part a_C, g.
    pub coriolis_g: [f64; 3],
    /// Angular rate of the PIGA relative to inertial space, in `O3`, rad/s.
    pub angular_rate_rad_s: [f64; 3],
}

impl PigaInputs {
    /// Evaluates eq. 12 and 13 from the jet of the pose `T₃⁰(t)`, whose translation carries
    /// `D, Ḋ, D̈` and whose rotation carries `A, Ȧ` exactly.
    #[must_use]
    pub fn from_pose_jet(pose: &Transform<Ground, Piga, Jet>, site: &Site) -> Self {
        let h = pose.homogeneous();
        let a = h.value().rotation();
        let at = transpose(&a);
        let g = site.gravity_m_s2;
        let omega_ie = site.earth_rate_vector_rad_s();
        let d1 = h.translation_d1();
        let d2 = h.translation_d2();

        let centripetal_g = mat_vec(&at, &d2).map(|x| x / g);
        let gravity_g = [at[0][2], at[1][2], at[2][2]];
        let coriolis_g = mat_vec(&at, &cross(omega_ie, d1)).map(|x| 2.0 * x / g);

        // [w]x = dA/dt · Aᵀ, taken from its antisymmetric part
        let w_skew = mat_mul(&h.rotation_d1(), &at);
        let w = [
            0.5 * (w_skew[2][1] - w_skew[1][2]),
            0.5 * (w_skew[0][2] - w_skew[2][0]),
            0.5 * (w_skew[1][0] - w_skew[0][1]),
        ];
        let total = [w[0] + omega_ie[0], w[1] + omega_ie[1], w[2] + omega_ie[2]];
        Self {
            centripetal_g,
            gravity_g,
            coriolis_g,
            angular_rate_rad_s: mat_vec(&at, &total),
        }
    }

    /// The total specific force `a_R + a_G + a_C`, g.
    #[must_use]
    pub fn specific_force_g(&self) -> [f64; 3] {
        core::array::from_fn(|i| self.centripetal_g[i] + self.gravity_g[i] + self.coriolis_g[i])
    }

    /// `a_x`: the specific force along the input axis, g.
    #[must_use]
    pub fn a_x_g(&self) -> f64 {
        self.specific_force_g()[0]
    }

    /// `ω_I`: the angular rate about the input axis, rad/s.
    #[must_use]
    pub fn omega_i_rad_s(&self) -> f64 {
        self.angular_rate_rad_s[0]
    }

    /// The twelve numbers in a fixed order (for averaging).
    pub(crate) fn to_array(self) -> [f64; 12] {
        let mut out = [0.0; 12];
        for (k, v) in [
            self.centripetal_g,
            self.gravity_g,
            self.coriolis_g,
            self.angular_rate_rad_s,
        ]
        .iter()
        .enumerate()
        {
            out[3 * k..3 * k + 3].copy_from_slice(v);
        }
        out
    }

    /// Inverse of [`Self::to_array`].
    pub(crate) fn from_array(a: [f64; 12]) -> Self {
        let part = |k: usize| [a[3 * k], a[3 * k + 1], a[3 * k + 2]];
        Self {
            centripetal_g: part(0),
            gravity_g: part(1),
            coriolis_g: part(2),
            angular_rate_rad_s: part(3),
        }
    }
}
