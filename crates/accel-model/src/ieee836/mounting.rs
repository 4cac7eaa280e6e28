//! How the case axes (IA, PA, OA) lie on the arm: the named presets, general angles, and the
//! nominal inputs along each axis that the fit's columns are made of.
//!
//! Frame: the spindle frame O2 of eq. 5 — `X2` along the arm, outwards (towards the
//! accelerometer), `Y2` tangential (the direction of motion for ω > 0), `Z2` along the spindle
//! axis, up. The case axes are a right-handed triad, `IA × PA = OA`. Eq. 10's mounting (IA in)
//! is `IA = −X2`, `PA = −Y2`, `OA = Z2`.

use crate::error::{AccelModelError, Result};

const HALF_SQRT_2: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// The case axes in the spindle frame O2, unit vectors (components along `X2`, `Y2`, `Z2`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CaseAxes {
    /// The input axis IA.
    pub ia: [f64; 3],
    /// The pendulous axis PA.
    pub pa: [f64; 3],
    /// The output (hinge) axis OA = IA × PA.
    pub oa: [f64; 3],
}

impl CaseAxes {
    /// The axes as rows: IA, PA, OA.
    #[must_use]
    pub const fn rows(&self) -> [[f64; 3]; 3] {
        [self.ia, self.pa, self.oa]
    }

    /// The rotation whose columns are IA, PA, OA in O2 (the rotation block of `T₃²`).
    #[must_use]
    pub const fn rotation(&self) -> [[f64; 3]; 3] {
        let [i, p, o] = [self.ia, self.pa, self.oa];
        [[i[0], p[0], o[0]], [i[1], p[1], o[1]], [i[2], p[2], o[2]]]
    }

    /// The nominal input along each case axis, `a_j = c_j·a + t_j·b + z_j` with
    /// `a = ρ_x·ω²/g` and `b = ρ_y·ω²/g`: the specific force at a point `(ρ_x, ρ_y, 0)` of the
    /// spindle frame turning at ω with no Earth rate is `(−a, −b, 1)` g in O2 (the centripetal
    /// acceleration towards the axis, gravity's support up), so `c_j = −x_j` is the axis's
    /// inward radial component, `t_j = −y_j` its component against the motion and `z_j` its
    /// vertical one. `ρ_x` is the radius (with the spindle's drift along the arm), `ρ_y` the
    /// drift across it.
    #[must_use]
    pub fn nominal(&self) -> [NominalAxis; 3] {
        self.rows().map(|v| NominalAxis {
            radial: -v[0],
            across: -v[1],
            vertical: v[2],
        })
    }

    /// The component of IA along the spindle axis: a PIGA's `ω_i` is `ω` times it (plus the
    /// Earth rate and the error motion).
    #[must_use]
    pub const fn ia_vertical(&self) -> f64 {
        self.ia[2]
    }

    /// Checks that the axes are unit vectors, orthogonal and right-handed to 1e-9.
    ///
    /// # Errors
    /// [`AccelModelError::NotACaseFrame`] naming the first failed condition.
    pub fn validate(&self) -> Result<()> {
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let all_finite = self.rows().iter().flatten().all(|v| v.is_finite());
        let checks = [
            (all_finite, "every component must be finite"),
            (
                self.rows().iter().all(|v| (dot(*v, *v) - 1.0).abs() < 1e-9),
                "IA, PA and OA must be unit vectors",
            ),
            (
                dot(self.ia, self.pa).abs() < 1e-9
                    && dot(self.ia, self.oa).abs() < 1e-9
                    && dot(self.pa, self.oa).abs() < 1e-9,
                "IA, PA and OA must be orthogonal",
            ),
            (
                {
                    let c = cross(self.ia, self.pa);
                    (0..3).all(|k| (c[k] - self.oa[k]).abs() < 1e-9)
                },
                "OA must be IA × PA (a right-handed triad)",
            ),
        ];
        match checks.into_iter().find(|(ok, _)| !ok) {
            None => Ok(()),
            Some((_, reason)) => Err(AccelModelError::NotACaseFrame { reason }),
        }
    }
}

/// The nominal input along one case axis: `c·a + t·b + z` in g, `a = ρ_x·ω²/g`,
/// `b = ρ_y·ω²/g` ([`CaseAxes::nominal`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NominalAxis {
    /// `c`: the axis's inward radial component (IA in: 1, IA out: −1, tangential: 0).
    pub radial: f64,
    /// `t`: the axis's component against the motion, `−y` (IA tangential along −Y2: 1).
    pub across: f64,
    /// `z`: the axis's component along the spindle axis (gravity's share, g).
    pub vertical: f64,
}

/// A mounting's orientation by three angles, from IA in (eq. 10): turn the case about the
/// spindle axis by `azimuth_deg` (from IA pointing inwards towards IA pointing along −Y2),
/// raise IA towards the spindle axis by `elevation_deg`, then roll PA about IA towards OA by
/// `roll_deg`. `IA = (−cos e·cos z, −cos e·sin z, sin e)`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct MountingAngles {
    /// Turn about the spindle axis, degrees (0: IA in, 180: IA out, 90: IA tangential).
    pub azimuth_deg: f64,
    /// IA raised towards the spindle axis (up), degrees (90: IA along the spindle axis).
    pub elevation_deg: f64,
    /// PA rolled about IA towards OA, degrees.
    pub roll_deg: f64,
}

impl MountingAngles {
    /// The case axes of these angles.
    ///
    /// # Errors
    /// [`AccelModelError::NonFinite`] naming a non-finite angle.
    pub fn axes(&self) -> Result<CaseAxes> {
        for (field, value) in [
            ("azimuth_deg", self.azimuth_deg),
            ("elevation_deg", self.elevation_deg),
            ("roll_deg", self.roll_deg),
        ] {
            if !value.is_finite() {
                return Err(AccelModelError::NonFinite { field, value });
            }
        }
        let (sz, cz) = trig_deg(self.azimuth_deg);
        let (se, ce) = trig_deg(self.elevation_deg);
        let (sr, cr) = trig_deg(self.roll_deg);
        let ia = [-ce * cz, -ce * sz, se];
        let pa0 = [sz, -cz, 0.0];
        // OA0 = IA × PA0
        let oa0 = [se * cz, se * sz, ce];
        let pa = std::array::from_fn(|k| cr * pa0[k] + sr * oa0[k]);
        let oa = std::array::from_fn(|k| -sr * pa0[k] + cr * oa0[k]);
        Ok(CaseAxes { ia, pa, oa })
    }
}

/// `(sin, cos)` of an angle in degrees, exact at the multiples of 90°.
fn trig_deg(deg: f64) -> (f64, f64) {
    let r = deg.rem_euclid(360.0);
    match r {
        0.0 => (0.0, 1.0),
        90.0 => (1.0, 0.0),
        180.0 => (0.0, -1.0),
        270.0 => (-1.0, 0.0),
        _ => r.to_radians().sin_cos(),
    }
}

/// The usual mountings of a centrifuge test, by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum MountingPreset {
    /// IA towards the spindle axis, PA tangential, OA up (eq. 10).
    IaIn,
    /// IA away from the spindle axis, PA tangential, OA up (eq. 23's IA out).
    IaOut,
    /// IA tangential, PA radial (outwards), OA up.
    IaTangential,
    /// IA along the spindle axis (up), PA tangential, OA radial (outwards).
    IaAxial,
    /// IA along the spindle axis (up), PA radial (outwards), OA tangential.
    PaRadial,
    /// IA tangential, PA up, OA radial (inwards).
    OaRadial,
    /// IA at 45° between inwards radial and up, PA tangential.
    Ia45,
}

impl MountingPreset {
    /// Every preset.
    pub const ALL: [Self; 7] = [
        Self::IaIn,
        Self::IaOut,
        Self::IaTangential,
        Self::IaAxial,
        Self::PaRadial,
        Self::OaRadial,
        Self::Ia45,
    ];

    /// The preset's angles.
    #[must_use]
    pub const fn angles(self) -> MountingAngles {
        let (azimuth_deg, elevation_deg, roll_deg) = match self {
            Self::IaIn => (0.0, 0.0, 0.0),
            Self::IaOut => (180.0, 0.0, 0.0),
            Self::IaTangential => (90.0, 0.0, 0.0),
            Self::IaAxial => (0.0, 90.0, 0.0),
            Self::PaRadial => (0.0, 90.0, 90.0),
            Self::OaRadial => (90.0, 0.0, 90.0),
            Self::Ia45 => (0.0, 45.0, 0.0),
        };
        MountingAngles {
            azimuth_deg,
            elevation_deg,
            roll_deg,
        }
    }

    /// The preset's case axes, exact (0, ±1, ±1/√2).
    #[must_use]
    pub fn axes(self) -> CaseAxes {
        let h = HALF_SQRT_2;
        let (ia, pa, oa) = match self {
            Self::IaIn => ([-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]),
            Self::IaOut => ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            Self::IaTangential => ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            Self::IaAxial => ([0.0, 0.0, 1.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]),
            Self::PaRadial => ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            Self::OaRadial => ([0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]),
            Self::Ia45 => ([-h, 0.0, h], [0.0, -1.0, 0.0], [h, 0.0, h]),
        };
        CaseAxes { ia, pa, oa }
    }

    /// The preset of a tag (`ia_in`, `ia_45`), `None` for another word.
    #[must_use]
    pub fn from_tag(tag: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.tag() == tag)
    }

    /// The tag of configuration files: `ia_in`, `pa_radial`, `ia_45`.
    #[must_use]
    pub const fn tag(self) -> &'static str {
        match self {
            Self::IaIn => "ia_in",
            Self::IaOut => "ia_out",
            Self::IaTangential => "ia_tangential",
            Self::IaAxial => "ia_axial",
            Self::PaRadial => "pa_radial",
            Self::OaRadial => "oa_radial",
            Self::Ia45 => "ia_45",
        }
    }

    /// Words for a reader.
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Self::IaIn => "IA in",
            Self::IaOut => "IA out",
            Self::IaTangential => "IA tangential (PA radial, OA up)",
            Self::IaAxial => "IA along the spindle axis (OA radial)",
            Self::PaRadial => "IA along the spindle axis (PA radial)",
            Self::OaRadial => "IA tangential (OA radial, PA up)",
            Self::Ia45 => "IA at 45° between radial and the spindle axis",
        }
    }
}

/// One mounting of the accelerometer on the arm: how its case axes lie, at which static
/// radius, and how well the fixture sets its angles.
#[derive(Debug, Clone, PartialEq)]
pub struct Mounting {
    /// Its name for a reader (the preset's words, or the lab's).
    pub label: String,
    /// The case axes in O2 as declared.
    pub axes: CaseAxes,
    /// Static radius, m: the accelerometer's centre of mass (its proof mass) to the mean
    /// spindle axis at rest.
    pub radius_m: f64,
    /// Standard uncertainty of the fixture's angles (each of the three), degrees: an index
    /// error leaks the radial input into the cross terms (IEEE 836 §6.2).
    pub angle_u_deg: f64,
}

impl Mounting {
    /// A preset at `radius_m`, with the fixture's angular uncertainty `angle_u_deg`.
    #[must_use]
    pub fn preset(preset: MountingPreset, radius_m: f64, angle_u_deg: f64) -> Self {
        Self {
            label: preset.label().to_owned(),
            axes: preset.axes(),
            radius_m,
            angle_u_deg,
        }
    }

    /// A mounting of general angles.
    ///
    /// # Errors
    /// As [`MountingAngles::axes`].
    pub fn angles(
        label: &str,
        angles: MountingAngles,
        radius_m: f64,
        angle_u_deg: f64,
    ) -> Result<Self> {
        Ok(Self {
            label: label.to_owned(),
            axes: angles.axes()?,
            radius_m,
            angle_u_deg,
        })
    }

    /// Checks the radius (finite, > 0), the angular uncertainty (finite, ≥ 0) and the axes.
    ///
    /// # Errors
    /// [`AccelModelError::NonFinite`] or [`AccelModelError::NotPositive`] naming the field;
    /// [`AccelModelError::NotACaseFrame`].
    pub fn validate(&self) -> Result<()> {
        if !(self.radius_m.is_finite() && self.radius_m > 0.0) {
            return Err(AccelModelError::NotPositive {
                field: "radius_m",
                value: self.radius_m,
            });
        }
        if !(self.angle_u_deg.is_finite() && self.angle_u_deg >= 0.0) {
            return Err(AccelModelError::NonFinite {
                field: "angle_u_deg",
                value: self.angle_u_deg,
            });
        }
        self.axes.validate()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_presets_are_their_angles_and_right_handed() {
        for p in MountingPreset::ALL {
            let exact = p.axes();
            exact.validate().unwrap();
            let from_angles = p.angles().axes().unwrap();
            for (a, b) in exact.rows().iter().zip(from_angles.rows()) {
                for k in 0..3 {
                    assert!((a[k] - b[k]).abs() < 1e-15, "{}: {a:?} {b:?}", p.tag());
                }
            }
        }
        // eq. 10: IA in sees a = R·ω²/g along IA and nothing else radial
        let n = MountingPreset::IaIn.axes().nominal();
        assert_eq!((n[0].radial, n[0].vertical), (1.0, 0.0));
        assert_eq!((n[2].radial, n[2].vertical), (0.0, 1.0));
        let out = MountingPreset::IaOut.axes().nominal();
        assert_eq!((out[0].radial, out[0].vertical), (-1.0, 0.0));
    }

    #[test]
    fn general_angles_give_a_case_frame_and_a_bad_one_is_refused() {
        let m = MountingAngles {
            azimuth_deg: 17.0,
            elevation_deg: -33.0,
            roll_deg: 61.0,
        };
        m.axes().unwrap().validate().unwrap();
        let mut bad = MountingPreset::IaIn.axes();
        bad.oa = [0.0, 0.0, -1.0];
        assert!(matches!(
            bad.validate(),
            Err(AccelModelError::NotACaseFrame { .. })
        ));
    }
}
