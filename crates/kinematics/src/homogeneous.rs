//! Untyped 4×4 rigid homogeneous transforms: the building blocks `Rot` and `Trans`.

use core::ops::Mul;

use crate::jet::{Jet, Scalar};

/// A coordinate axis of the frame a rotation is expressed in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Axis {
    /// The x axis.
    X,
    /// The y axis.
    Y,
    /// The z axis.
    Z,
}

/// A rigid homogeneous transform `[R t; 0 1]` over a [`Scalar`] (plain `f64` or [`Jet`]).
///
/// It maps coordinates in a child frame to coordinates in its parent frame:
/// `p_parent = R·p_child + t`. The columns of `R` are the child's axes written in the parent,
/// and `t` is the child's origin in the parent. Composition is matrix multiplication, in the
/// paper's order (`T₃¹ = T₂¹·T₃²`).
///
/// The elementary transforms are the paper's (right-handed, active):
///
/// ```text
///             ⎡1    0      0     0⎤                     ⎡1  0  0  a⎤
/// Rot(x, α) = ⎢0  cos α  −sin α  0⎥,   Trans(a, b, c) = ⎢0  1  0  b⎥
///             ⎢0  sin α  cos α   0⎥                     ⎢0  0  1  c⎥
///             ⎣0    0      0     1⎦                     ⎣0  0  0  1⎦
/// ```
///
/// and cyclically for `y` and `z`. The frame-typed wrapper is [`crate::Transform`].
///
/// ```
/// use approx::assert_relative_eq;
/// use kinematics::{Axis, Homogeneous};
/// let t = Homogeneous::rot(Axis::Z, std::f64::consts::FRAC_PI_2) * Homogeneous::trans(1.0, 0.0, 0.0);
/// let p = t.transform_point([0.0, 0.0, 0.0]);
/// assert_relative_eq!(p[1], 1.0, max_relative = 1e-15);
/// assert!(p[0].abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Homogeneous<S = f64> {
    rotation: [[S; 3]; 3],
    translation: [S; 3],
}

impl<S: Scalar> Homogeneous<S> {
    /// The identity transform.
    #[must_use]
    pub fn identity() -> Self {
        let (o, z) = (S::constant(1.0), S::constant(0.0));
        Self {
            rotation: [[o, z, z], [z, o, z], [z, z, o]],
            translation: [z; 3],
        }
    }

    /// `Rot(axis, angle)`: a rotation by `angle` (radians) about `axis`.
    #[must_use]
    pub fn rot(axis: Axis, angle: S) -> Self {
        let (s, c) = (angle.sine(), angle.cosine());
        let (o, z) = (S::constant(1.0), S::constant(0.0));
        let rotation = match axis {
            Axis::X => [[o, z, z], [z, c, -s], [z, s, c]],
            Axis::Y => [[c, z, s], [z, o, z], [-s, z, c]],
            Axis::Z => [[c, -s, z], [s, c, z], [z, z, o]],
        };
        Self {
            rotation,
            translation: [z; 3],
        }
    }

    /// `Trans(x, y, z)`: a translation.
    #[must_use]
    pub fn trans(x: S, y: S, z: S) -> Self {
        Self {
            translation: [x, y, z],
            ..Self::identity()
        }
    }

    /// Builds a transform from a rotation matrix and a translation. The caller is responsible
    /// for `rotation` being orthonormal with determinant +1.
    #[must_use]
    pub const fn from_parts(rotation: [[S; 3]; 3], translation: [S; 3]) -> Self {
        Self {
            rotation,
            translation,
        }
    }

    /// The rotation block `A` (row-major).
    #[must_use]
    pub const fn rotation(&self) -> [[S; 3]; 3] {
        self.rotation
    }

    /// The translation column `D`.
    #[must_use]
    pub const fn translation(&self) -> [S; 3] {
        self.translation
    }

    /// The inverse `[Rᵀ  −Rᵀt; 0 1]` (exact for a rigid transform, no matrix inversion).
    #[must_use]
    pub fn inverse(&self) -> Self {
        let rt = transpose(&self.rotation);
        let t = mat_vec(&rt, &self.translation);
        Self {
            rotation: rt,
            translation: [-t[0], -t[1], -t[2]],
        }
    }

    /// Maps a point from child to parent coordinates: `R·p + t`.
    #[must_use]
    pub fn transform_point(&self, p: [S; 3]) -> [S; 3] {
        let r = mat_vec(&self.rotation, &p);
        [
            r[0] + self.translation[0],
            r[1] + self.translation[1],
            r[2] + self.translation[2],
        ]
    }

    /// Maps a free vector from child to parent coordinates: `R·v`.
    #[must_use]
    pub fn transform_vector(&self, v: [S; 3]) -> [S; 3] {
        mat_vec(&self.rotation, &v)
    }

    /// Drops derivatives: the plain-valued transform.
    #[must_use]
    pub fn value(&self) -> Homogeneous<f64> {
        Homogeneous {
            rotation: self.rotation.map(|row| row.map(Scalar::value)),
            translation: self.translation.map(Scalar::value),
        }
    }
}

impl Homogeneous<f64> {
    /// The full 4×4 matrix, row-major.
    #[must_use]
    pub fn to_matrix(&self) -> [[f64; 4]; 4] {
        let mut m = [[0.0; 4]; 4];
        for (i, row) in self.rotation.iter().enumerate() {
            m[i][..3].copy_from_slice(row);
            m[i][3] = self.translation[i];
        }
        m[3][3] = 1.0;
        m
    }

    /// Largest absolute difference between corresponding matrix entries.
    #[must_use]
    pub fn max_abs_diff(&self, other: &Self) -> f64 {
        let (a, b) = (self.to_matrix(), other.to_matrix());
        a.iter()
            .flatten()
            .zip(b.iter().flatten())
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    }
}

impl Homogeneous<Jet> {
    /// Element-wise first time derivative of the rotation block, `dA/dt`.
    #[must_use]
    pub fn rotation_d1(&self) -> [[f64; 3]; 3] {
        self.rotation.map(|row| row.map(|x| x.d1))
    }

    /// First time derivative of the translation, `dD/dt`.
    #[must_use]
    pub fn translation_d1(&self) -> [f64; 3] {
        self.translation.map(|x| x.d1)
    }

    /// Second time derivative of the translation, `d²D/dt²`.
    #[must_use]
    pub fn translation_d2(&self) -> [f64; 3] {
        self.translation.map(|x| x.d2)
    }
}

impl<S: Scalar> Mul for Homogeneous<S> {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        let rotation = mat_mul(&self.rotation, &rhs.rotation);
        let t = mat_vec(&self.rotation, &rhs.translation);
        Self {
            rotation,
            translation: [
                t[0] + self.translation[0],
                t[1] + self.translation[1],
                t[2] + self.translation[2],
            ],
        }
    }
}

pub(crate) fn transpose<S: Copy>(m: &[[S; 3]; 3]) -> [[S; 3]; 3] {
    [
        [m[0][0], m[1][0], m[2][0]],
        [m[0][1], m[1][1], m[2][1]],
        [m[0][2], m[1][2], m[2][2]],
    ]
}

pub(crate) fn mat_vec<S: Scalar>(m: &[[S; 3]; 3], v: &[S; 3]) -> [S; 3] {
    m.map(|row| row[0] * v[0] + row[1] * v[1] + row[2] * v[2])
}

pub(crate) fn mat_mul<S: Scalar>(a: &[[S; 3]; 3], b: &[[S; 3]; 3]) -> [[S; 3]; 3] {
    let mut out = [[S::constant(0.0); 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    out
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn elementary_rotations_are_right_handed() {
        let q = core::f64::consts::FRAC_PI_2;
        // Rot(z, 90°) takes x to y, Rot(x, 90°) takes y to z, Rot(y, 90°) takes z to x.
        let cases = [
            (Axis::Z, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            (Axis::X, [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            (Axis::Y, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        ];
        for (axis, from, to) in cases {
            let v = Homogeneous::rot(axis, q).transform_vector(from);
            for k in 0..3 {
                assert!((v[k] - to[k]).abs() < 1e-15, "{axis:?}: {v:?}");
            }
        }
    }

    #[test]
    fn matrix_layout_matches_the_paper() {
        let m = (Homogeneous::trans(1.0, 2.0, 3.0) * Homogeneous::rot(Axis::X, 0.3)).to_matrix();
        assert_relative_eq!(m[1][2], -(0.3_f64.sin()), max_relative = 1e-15);
        assert_relative_eq!(m[2][1], 0.3_f64.sin(), max_relative = 1e-15);
        assert_relative_eq!(m[0][3], 1.0);
        assert_relative_eq!(m[2][3], 3.0);
        assert_relative_eq!(m[3][3], 1.0);
        assert_eq!(m[3][..3], [0.0; 3]);
    }
}
