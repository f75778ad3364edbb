//! One precision, `f32` or `f64`: what the scalar kernels written once for
//! both need beyond [`Real`]'s lane arithmetic.
//!
//! A kernel family's body is generic over [`Float`]; its public `f64` and
//! `f32` modules are thin wrappers that name the concrete types. Every
//! method here is the type's own operation, so a generic body compiled for
//! `f64` performs the same IEEE operations in the same order as one written
//! for `f64` alone: the same bits.
//!
//! Constants that are not exact in both precisions are associated constants
//! written as literals of each type (an `f64` literal converted to `f32`
//! would be rounded twice); [`Float::of`] is for the exact ones (small
//! integers, halves).

use crate::kernel::lanes::{forward, Real};
use core::fmt::{Debug, Display};
use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub};

/// `f32` or `f64`, with its vector types.
pub(crate) trait Float:
    Real<Scalar = Self, Mask = bool> + PartialOrd + AddAssign + Debug + Display + 'static
{
    /// The 2D vector of this precision (`DVec2`, `Vec2`).
    type V2: Vector2<Self>;
    /// The 3D vector of this precision (`DVec3`, `Vec3`).
    type V3: Vector3<Self>;

    const PI: Self;
    const FRAC_1_PI: Self;
    const NAN: Self;
    const INFINITY: Self;
    const EPSILON: Self;
    const MAX_EXP: i32;
    const MANTISSA_DIGITS: u32;

    /// `x` in this precision; `x` must be exact in it (small integers,
    /// halves): no rounding happens.
    fn of(x: f64) -> Self;
    /// `i` rounded to this precision (`i as f32`, `i as f64`).
    fn from_i64(i: i64) -> Self;
    /// `i` rounded to this precision (`i as f32`, `i as f64`).
    #[cfg(test)]
    fn from_u64(i: u64) -> Self;
    /// The value in `f64` (exact for both precisions).
    fn to_f64(self) -> f64;
    /// `self as i32`: toward zero, saturating, `NaN` to 0 (for
    /// integer-valued input, without a detour through `f64`).
    fn to_i32(self) -> i32;
    /// The bits, widened to 64.
    #[cfg(test)]
    fn bits(self) -> u64;
    fn is_finite(self) -> bool;
    fn is_nan(self) -> bool;
    fn log2(self) -> Self;
    fn floor(self) -> Self;
    fn ceil(self) -> Self;
    /// A 2D vector in `f64` (exact for both precisions).
    fn wide2(v: Self::V2) -> glam::DVec2;
    fn powi(self, n: i32) -> Self;
    fn clamp(self, min: Self, max: Self) -> Self;
    fn signum(self) -> Self;
    fn sin(self) -> Self;
    fn total_cmp(&self, other: &Self) -> core::cmp::Ordering;
    /// The platform's `atan2` (`f64::atan2`), for the special values only.
    fn atan2_std(self, x: Self) -> Self;
}

/// The arithmetic glam's vectors of either dimension have: sums,
/// differences, products and quotients by a scalar.
pub(crate) trait VectorOps<T>:
    Copy
    + PartialEq
    + Debug
    + Display
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
    + Mul<T, Output = Self>
    + Div<T, Output = Self>
{
}

/// What the kernels use of glam's 2D vectors.
pub(crate) trait Vector2<T>: VectorOps<T> {
    const ZERO: Self;
    fn new(x: T, y: T) -> Self;
    fn x(self) -> T;
    fn y(self) -> T;
    fn abs(self) -> Self;
    fn max_element(self) -> T;
    fn is_finite(self) -> bool;
    fn dot(self, other: Self) -> T;
    const X: Self;
    fn perp(self) -> Self;
    fn min(self, other: Self) -> Self;
    fn max(self, other: Self) -> Self;
    fn length(self) -> T;
    fn length_squared(self) -> T;
}

/// What the kernels use of glam's 3D vectors.
pub(crate) trait Vector3<T>: VectorOps<T> {
    const ZERO: Self;
    fn x(self) -> T;
    fn y(self) -> T;
    fn z(self) -> T;
    fn with_z(self, z: T) -> Self;
    fn abs(self) -> Self;
    fn max_element(self) -> T;
    fn normalize_or_zero(self) -> Self;
    fn length(self) -> T;
    fn cross(self, other: Self) -> Self;
    fn try_normalize(self) -> Option<Self>;
    fn any_orthonormal_vector(self) -> Self;
    fn is_finite(self) -> bool;
    fn dot(self, other: Self) -> T;
}

/// Trait methods that read glam's coordinate fields of the same name.
macro_rules! fields {
    ($T:ty; $($name:ident),*) => {$(
        #[inline(always)]
        fn $name(self) -> $T {
            self.$name
        }
    )*};
}

macro_rules! float {
    ($T:ident, $V2:ident, $V3:ident) => {
        impl Float for $T {
            type V2 = glam::$V2;
            type V3 = glam::$V3;

            const PI: $T = core::$T::consts::PI;
            const FRAC_1_PI: $T = core::$T::consts::FRAC_1_PI;
            const NAN: $T = <$T>::NAN;
            const INFINITY: $T = <$T>::INFINITY;
            const EPSILON: $T = <$T>::EPSILON;
            const MAX_EXP: i32 = <$T>::MAX_EXP;
            const MANTISSA_DIGITS: u32 = <$T>::MANTISSA_DIGITS;

            #[inline(always)]
            fn of(x: f64) -> $T {
                debug_assert!(x as $T as f64 == x || x.is_nan(), "{x} is not exact");
                x as $T
            }
            #[inline(always)]
            fn from_i64(i: i64) -> $T {
                i as $T
            }
            #[cfg(test)]
            fn from_u64(i: u64) -> $T {
                i as $T
            }
            #[inline(always)]
            fn to_f64(self) -> f64 {
                f64::from(self)
            }
            #[inline(always)]
            fn to_i32(self) -> i32 {
                self as i32
            }
            #[cfg(test)]
            fn bits(self) -> u64 {
                u64::from(self.to_bits())
            }
            #[inline(always)]
            fn wide2(v: glam::$V2) -> glam::DVec2 {
                glam::DVec2::from(v)
            }
            #[inline(always)]
            fn total_cmp(&self, other: &$T) -> core::cmp::Ordering {
                <$T>::total_cmp(self, other)
            }
            #[inline(always)]
            fn atan2_std(self, x: $T) -> $T {
                <$T>::atan2(self, x)
            }
            forward!(<$T>;
                fn is_finite(self) -> bool;
                fn is_nan(self) -> bool;
                fn log2(self) -> $T;
                fn floor(self) -> $T;
                fn ceil(self) -> $T;
                fn powi(self, n: i32) -> $T;
                fn clamp(self, min: $T, max: $T) -> $T;
                fn signum(self) -> $T;
                fn sin(self) -> $T;
            );
        }

        impl VectorOps<$T> for glam::$V2 {}
        impl VectorOps<$T> for glam::$V3 {}

        impl Vector2<$T> for glam::$V2 {
            const ZERO: Self = glam::$V2::ZERO;
            const X: Self = glam::$V2::X;
            #[inline(always)]
            fn new(x: $T, y: $T) -> Self {
                glam::$V2::new(x, y)
            }
            fields!($T; x, y);
            forward!(<glam::$V2>;
                fn perp(self) -> Self;
                fn min(self, other: Self) -> Self;
                fn max(self, other: Self) -> Self;
                fn length(self) -> $T;
                fn length_squared(self) -> $T;
                fn abs(self) -> Self;
                fn max_element(self) -> $T;
                fn is_finite(self) -> bool;
                fn dot(self, other: Self) -> $T;
            );
        }

        impl Vector3<$T> for glam::$V3 {
            const ZERO: Self = glam::$V3::ZERO;
            fields!($T; x, y, z);
            #[inline(always)]
            fn with_z(mut self, z: $T) -> Self {
                self.z = z;
                self
            }
            forward!(<glam::$V3>;
                fn length(self) -> $T;
                fn cross(self, other: Self) -> Self;
                fn try_normalize(self) -> Option<Self>;
                fn any_orthonormal_vector(self) -> Self;
                fn is_finite(self) -> bool;
                fn dot(self, other: Self) -> $T;
                fn abs(self) -> Self;
                fn max_element(self) -> $T;
                fn normalize_or_zero(self) -> Self;
            );
        }
    };
}

/// A kernel family's public `f64` and `f32` modules, from the one list of
/// its public items that the family's own macro `$items` declares for a
/// precision given as `($T, $V2, $V3)` (the scalar and glam's vectors):
/// each contract is written once, and each module shows it in full.
macro_rules! both_precisions {
    ($items:ident) => {
        /// `f64` versions.
        pub mod f64 {
            $items!(f64, DVec2, DVec3);
        }

        /// `f32` versions: the same contracts in single precision (their
        /// docs give both precisions' bounds).
        pub mod f32 {
            $items!(f32, Vec2, Vec3);
        }
    };
}
pub(crate) use both_precisions;

float!(f64, DVec2, DVec3);
float!(f32, Vec2, Vec3);
