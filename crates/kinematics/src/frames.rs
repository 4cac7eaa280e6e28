//! Frame-typed transforms: a wrong composition does not compile.

use core::fmt;
use core::marker::PhantomData;
use core::ops::Mul;

use crate::homogeneous::Homogeneous;
use crate::jet::Scalar;

/// A coordinate frame of the paper's chain (a type-level marker, never instantiated).
pub trait Frame {
    /// Short name, as in the paper (`"O0"` … `"O3"`).
    const NAME: &'static str;
}

/// `O0X0Y0Z0`, the local geographic frame: X east, Y north, Z up (the Earth rate is
/// `[0, ω_ie cos L, ω_ie sin L]` in it, eq. 12).
#[derive(Debug)]
pub enum Ground {}

/// `O1X1Y1Z1`, the spindle sleeve (bearing housing). It coincides with `O0`.
#[derive(Debug)]
pub enum Sleeve {}

/// `O2X2Y2Z2`, the spindle: turns with the rotor by `ωt` about `Z1` and carries the spindle
/// error motion. At `t = 0` (and without error motion) it coincides with `O1`.
#[derive(Debug)]
pub enum Spindle {}

/// `O3X3Y3Z3`, the PIGA: origin at its centre of mass on the extension of `O2X2` at the
/// working radius R; `X3` is the input axis IA, pointing at the spindle axis (eq. 10).
#[derive(Debug)]
pub enum Piga {}

impl Frame for Ground {
    const NAME: &'static str = "O0";
}
impl Frame for Sleeve {
    const NAME: &'static str = "O1";
}
impl Frame for Spindle {
    const NAME: &'static str = "O2";
}
impl Frame for Piga {
    const NAME: &'static str = "O3";
}

/// The pose of frame `Child` in frame `Parent`: the paper's `T_Child^Parent`, a
/// [`Homogeneous`] transform that maps `Child` coordinates to `Parent` coordinates.
///
/// `Transform<A, B> * Transform<B, C>` is a `Transform<A, C>`; the product is only defined
/// when the inner frames agree, so the chain of eq. 11 is checked by the compiler:
///
/// ```
/// use kinematics::{Homogeneous, Piga, Sleeve, Spindle, Transform};
/// let t21: Transform<Sleeve, Spindle> = Transform::from_homogeneous(Homogeneous::identity());
/// let t32: Transform<Spindle, Piga> = Transform::from_homogeneous(Homogeneous::trans(2.5, 0.0, 0.0));
/// let t31: Transform<Sleeve, Piga> = t21 * t32;
/// # let _ = t31;
/// ```
///
/// The other order does not compile:
///
/// ```compile_fail,E0277
/// use kinematics::{Homogeneous, Piga, Sleeve, Spindle, Transform};
/// let t21: Transform<Sleeve, Spindle> = Transform::from_homogeneous(Homogeneous::identity());
/// let t32: Transform<Spindle, Piga> = Transform::from_homogeneous(Homogeneous::trans(2.5, 0.0, 0.0));
/// let wrong = t32 * t21; // O3 ≠ O1: no `Mul` impl
/// ```
pub struct Transform<Parent, Child, S = f64> {
    inner: Homogeneous<S>,
    frames: PhantomData<fn() -> (Parent, Child)>,
}

impl<P, C, S: Scalar> Transform<P, C, S> {
    /// Asserts that `h` is the pose of `C` in `P`. This is the one place where frames are
    /// attached by hand; everything built from it is checked.
    #[must_use]
    pub const fn from_homogeneous(h: Homogeneous<S>) -> Self {
        Self {
            inner: h,
            frames: PhantomData,
        }
    }

    /// The identity (for frames that coincide, such as `O0` and `O1`).
    #[must_use]
    pub fn identity() -> Self {
        Self::from_homogeneous(Homogeneous::identity())
    }

    /// The untyped matrix.
    #[must_use]
    pub const fn homogeneous(&self) -> &Homogeneous<S> {
        &self.inner
    }

    /// The inverse pose: `Parent` in `Child`.
    #[must_use]
    pub fn inverse(&self) -> Transform<C, P, S> {
        Transform::from_homogeneous(self.inner.inverse())
    }

    /// Drops derivatives.
    #[must_use]
    pub fn value(&self) -> Transform<P, C, f64> {
        Transform::from_homogeneous(self.inner.value())
    }
}

impl<P, C> Transform<P, C, f64> {
    /// Maps a point given in `C` to `P`.
    #[must_use]
    pub fn apply(&self, p: Point<C>) -> Point<P> {
        Point::new(self.inner.transform_point(p.coords_m))
    }
}

impl<A, B, C, S: Scalar> Mul<Transform<B, C, S>> for Transform<A, B, S> {
    type Output = Transform<A, C, S>;
    fn mul(self, rhs: Transform<B, C, S>) -> Transform<A, C, S> {
        Transform::from_homogeneous(self.inner * rhs.inner)
    }
}

impl<P, C> Mul<Point<C>> for Transform<P, C, f64> {
    type Output = Point<P>;
    fn mul(self, rhs: Point<C>) -> Point<P> {
        self.apply(rhs)
    }
}

impl<P, C, S: Copy> Clone for Transform<P, C, S> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<P, C, S: Copy> Copy for Transform<P, C, S> {}

impl<P: Frame, C: Frame, S: fmt::Debug> fmt::Debug for Transform<P, C, S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "T[{} <- {}] ", P::NAME, C::NAME)?;
        self.inner.fmt(f)
    }
}

/// A point with coordinates (in metres) in frame `F`.
pub struct Point<F> {
    /// Coordinates along the frame's x, y, z axes, in metres.
    pub coords_m: [f64; 3],
    frame: PhantomData<fn() -> F>,
}

impl<F> Point<F> {
    /// A point from its coordinates in `F`.
    #[must_use]
    pub const fn new(coords_m: [f64; 3]) -> Self {
        Self {
            coords_m,
            frame: PhantomData,
        }
    }
}

impl<F> Clone for Point<F> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<F> Copy for Point<F> {}
impl<F: Frame> fmt::Debug for Point<F> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Point[{}]{:?}", F::NAME, self.coords_m)
    }
}
impl<F> PartialEq for Point<F> {
    fn eq(&self, other: &Self) -> bool {
        self.coords_m == other.coords_m
    }
}
