//! One formula, one value or several lanes at once.
//!
//! The kernels that have a batched form write their formulas once, generic
//! over [`Real`]: instantiated with `f64` (or `f32`) they are the scalar
//! kernels, with [`Lanes`] they evaluate several inputs side by side. A
//! [`Lanes`] operation is the same IEEE operation on each lane, written as a
//! short loop the compiler turns into vector instructions (SSE2 on the
//! baseline target, AVX2 where a caller is compiled for it), so a lane's
//! result is bit for bit the scalar one. Branches become [`Real::select`]:
//! every path is computed and the answer picked per lane.

use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// `f(fma)`, compiled for AVX2 and FMA and run so where the processor has
/// them (with the `simd` feature on x86-64: [`pulp`]'s run-time dispatch),
/// else compiled for the build's target; `fma` says whether a fused
/// multiply-add is an instruction where `f` runs. For loops written to be
/// vectorised: `f` should be `#[inline(always)]` and call
/// `#[inline(always)]` functions only, so that all of it is compiled with
/// the wider instructions (a function the compiler keeps apart is compiled
/// for the build's target). The answer is the same either way: the wider
/// instructions are the same IEEE operations.
#[inline(always)]
pub(crate) fn vectorized<R>(f: impl FnOnce(bool) -> R) -> R {
    #[cfg(all(feature = "simd", target_arch = "x86_64"))]
    if let Some(v3) = pulp::x86::V3::try_new().filter(|_| dispatch::on()) {
        return v3.vectorize(
            #[inline(always)]
            || f(true),
        );
    }
    f(cfg!(target_feature = "fma"))
}

/// Whether [`vectorized`] dispatches: always, but in a unit test that asks
/// for the build's target with `dispatch::without`, so that it can check
/// the dispatched code against the same code compiled for the target.
pub(crate) mod dispatch {
    #[cfg(test)]
    std::thread_local! {
        static OFF: core::cell::Cell<bool> = const { core::cell::Cell::new(false) };
    }

    #[cfg(all(feature = "simd", target_arch = "x86_64", not(test)))]
    #[inline(always)]
    pub(super) fn on() -> bool {
        true
    }

    #[cfg(all(feature = "simd", target_arch = "x86_64", test))]
    pub(super) fn on() -> bool {
        !OFF.get()
    }

    /// `f()` with every [`vectorized`](super::vectorized) call on this
    /// thread run as compiled for the build's target.
    #[cfg(test)]
    pub(crate) fn without<R>(f: impl FnOnce() -> R) -> R {
        OFF.set(true);
        let r = f();
        OFF.set(false);
        r
    }
}

/// Arithmetic on one value or on lanes of values: IEEE operations, lane by
/// lane, with comparisons giving a [`Real::Mask`].
pub(crate) trait Real:
    Copy
    + Default
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The scalar type of a lane.
    type Scalar: Copy;
    /// One boolean per lane.
    type Mask: Copy
        + Default
        + BitAnd<Output = Self::Mask>
        + BitOr<Output = Self::Mask>
        + Not<Output = Self::Mask>;

    /// The same value in every lane.
    fn splat(x: Self::Scalar) -> Self;
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
    /// `f64::min`: the other operand where one is NaN.
    fn min(self, other: Self) -> Self;
    /// `f64::max`: the other operand where one is NaN.
    fn max(self, other: Self) -> Self;
    /// `self · b + c` with one rounding (a software routine unless a
    /// hardware FMA is enabled where it is compiled).
    fn mul_add(self, b: Self, c: Self) -> Self;
    /// The magnitude of `self` with the sign bit of `sign`.
    fn copysign(self, sign: Self) -> Self;
    fn is_sign_negative(self) -> Self::Mask;
    fn lt(self, other: Self) -> Self::Mask;
    fn le(self, other: Self) -> Self::Mask;
    fn gt(self, other: Self) -> Self::Mask;
    fn ge(self, other: Self) -> Self::Mask;
    fn eq(self, other: Self) -> Self::Mask;
    /// `if_true` in the lanes where `mask` holds, `if_false` elsewhere.
    fn select(mask: Self::Mask, if_true: Self, if_false: Self) -> Self;
    /// Whether `mask` holds in any lane.
    fn any(mask: Self::Mask) -> bool;
}

/// Trait methods that call the type's own method of the same name with
/// the same arguments: `forward!(<Type>; fn name(self, arg: A) -> R; …);`
/// (`#[inline(always)]`, so a call is the type's operation itself).
macro_rules! forward {
    (<$ty:ty>; $(fn $name:ident(self $(, $arg:ident: $A:ty)*) -> $R:ty;)*) => {$(
        #[inline(always)]
        fn $name(self $(, $arg: $A)*) -> $R {
            <$ty>::$name(self $(, $arg)*)
        }
    )*};
}
pub(crate) use forward;

macro_rules! scalar_real {
    ($T:ident) => {
        impl Real for $T {
            type Scalar = $T;
            type Mask = bool;

            #[inline(always)]
            fn splat(x: $T) -> $T {
                x
            }
            forward!(<$T>;
                fn sqrt(self) -> $T;
                fn abs(self) -> $T;
                fn min(self, other: $T) -> $T;
                fn max(self, other: $T) -> $T;
                fn mul_add(self, b: $T, c: $T) -> $T;
                fn copysign(self, sign: $T) -> $T;
                fn is_sign_negative(self) -> bool;
            );
            #[inline(always)]
            fn lt(self, other: $T) -> bool {
                self < other
            }
            #[inline(always)]
            fn le(self, other: $T) -> bool {
                self <= other
            }
            #[inline(always)]
            fn gt(self, other: $T) -> bool {
                self > other
            }
            #[inline(always)]
            fn ge(self, other: $T) -> bool {
                self >= other
            }
            #[inline(always)]
            fn eq(self, other: $T) -> bool {
                self == other
            }
            #[inline(always)]
            fn any(mask: bool) -> bool {
                mask
            }
            #[inline(always)]
            fn select(mask: bool, if_true: $T, if_false: $T) -> $T {
                if mask {
                    if_true
                } else {
                    if_false
                }
            }
        }
    };
}

scalar_real!(f64);
scalar_real!(f32);

/// `N` values side by side (4 `f64` fill an AVX2 register).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lanes<T, const N: usize>(pub [T; N]);

impl<T: Copy + Default, const N: usize> Default for Lanes<T, N> {
    fn default() -> Self {
        Lanes([T::default(); N])
    }
}

/// One boolean per lane of [`Lanes`], as a lane-wide integer: all ones for
/// true, zero for false (what a vector comparison produces, so masks stay
/// in vector registers).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Mask<U, const N: usize>(pub [U; N]);

impl<U: Copy + Default, const N: usize> Default for Mask<U, N> {
    fn default() -> Self {
        Mask([U::default(); N])
    }
}

macro_rules! mask_ops {
    ($U:ident) => {
        impl<const N: usize> BitAnd for Mask<$U, N> {
            type Output = Self;
            #[inline(always)]
            fn bitand(self, o: Self) -> Self {
                Mask(core::array::from_fn(|i| self.0[i] & o.0[i]))
            }
        }

        impl<const N: usize> BitOr for Mask<$U, N> {
            type Output = Self;
            #[inline(always)]
            fn bitor(self, o: Self) -> Self {
                Mask(core::array::from_fn(|i| self.0[i] | o.0[i]))
            }
        }

        impl<const N: usize> Not for Mask<$U, N> {
            type Output = Self;
            #[inline(always)]
            fn not(self) -> Self {
                Mask(self.0.map(|m| !m))
            }
        }
    };
}

mask_ops!(u64);
mask_ops!(u32);

macro_rules! lanes_real {
    ($T:ident, $U:ident, $I:ident) => {
        impl<const N: usize> Add for Lanes<$T, N> {
            type Output = Self;
            #[inline(always)]
            fn add(self, o: Self) -> Self {
                Lanes(core::array::from_fn(|i| self.0[i] + o.0[i]))
            }
        }
        impl<const N: usize> Sub for Lanes<$T, N> {
            type Output = Self;
            #[inline(always)]
            fn sub(self, o: Self) -> Self {
                Lanes(core::array::from_fn(|i| self.0[i] - o.0[i]))
            }
        }
        impl<const N: usize> Mul for Lanes<$T, N> {
            type Output = Self;
            #[inline(always)]
            fn mul(self, o: Self) -> Self {
                Lanes(core::array::from_fn(|i| self.0[i] * o.0[i]))
            }
        }
        impl<const N: usize> Div for Lanes<$T, N> {
            type Output = Self;
            #[inline(always)]
            fn div(self, o: Self) -> Self {
                Lanes(core::array::from_fn(|i| self.0[i] / o.0[i]))
            }
        }
        impl<const N: usize> Neg for Lanes<$T, N> {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                Lanes(self.0.map(|x| -x))
            }
        }

        impl<const N: usize> Real for Lanes<$T, N> {
            type Scalar = $T;
            type Mask = Mask<$U, N>;

            #[inline(always)]
            fn splat(x: $T) -> Self {
                Lanes([x; N])
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                Lanes(self.0.map(<$T>::sqrt))
            }
            #[inline(always)]
            fn abs(self) -> Self {
                Lanes(self.0.map(<$T>::abs))
            }
            #[inline(always)]
            fn min(self, o: Self) -> Self {
                Lanes(core::array::from_fn(|i| self.0[i].min(o.0[i])))
            }
            #[inline(always)]
            fn max(self, o: Self) -> Self {
                Lanes(core::array::from_fn(|i| self.0[i].max(o.0[i])))
            }
            #[inline(always)]
            fn mul_add(self, b: Self, c: Self) -> Self {
                Lanes(core::array::from_fn(|i| self.0[i].mul_add(b.0[i], c.0[i])))
            }
            #[inline(always)]
            fn copysign(self, sign: Self) -> Self {
                Lanes(core::array::from_fn(|i| self.0[i].copysign(sign.0[i])))
            }
            #[inline(always)]
            fn is_sign_negative(self) -> Mask<$U, N> {
                Mask(
                    self.0
                        .map(|x| <$U>::from((x.to_bits() as $I) < 0).wrapping_neg()),
                )
            }
            #[inline(always)]
            fn lt(self, o: Self) -> Mask<$U, N> {
                Mask(core::array::from_fn(|i| {
                    <$U>::from(self.0[i] < o.0[i]).wrapping_neg()
                }))
            }
            #[inline(always)]
            fn le(self, o: Self) -> Mask<$U, N> {
                Mask(core::array::from_fn(|i| {
                    <$U>::from(self.0[i] <= o.0[i]).wrapping_neg()
                }))
            }
            #[inline(always)]
            fn gt(self, o: Self) -> Mask<$U, N> {
                Mask(core::array::from_fn(|i| {
                    <$U>::from(self.0[i] > o.0[i]).wrapping_neg()
                }))
            }
            #[inline(always)]
            fn ge(self, o: Self) -> Mask<$U, N> {
                Mask(core::array::from_fn(|i| {
                    <$U>::from(self.0[i] >= o.0[i]).wrapping_neg()
                }))
            }
            #[inline(always)]
            fn eq(self, o: Self) -> Mask<$U, N> {
                Mask(core::array::from_fn(|i| {
                    <$U>::from(self.0[i] == o.0[i]).wrapping_neg()
                }))
            }
            #[inline(always)]
            fn any(mask: Mask<$U, N>) -> bool {
                mask.0.iter().any(|&m| m != 0)
            }
            #[inline(always)]
            fn select(mask: Mask<$U, N>, if_true: Self, if_false: Self) -> Self {
                Lanes(core::array::from_fn(|i| {
                    <$T>::from_bits(
                        (mask.0[i] & if_true.0[i].to_bits())
                            | (!mask.0[i] & if_false.0[i].to_bits()),
                    )
                }))
            }
        }
    };
}

lanes_real!(f64, u64, i64);
lanes_real!(f32, u32, i32);

#[cfg(test)]
mod tests {
    use super::*;

    /// Inside [`dispatch::without`], `vectorized` runs `f` as compiled for
    /// the build's target (a fused multiply-add only where the target has
    /// it); outside, where the processor has AVX2 and FMA and the `simd`
    /// feature is on, dispatched to them.
    #[test]
    fn without_dispatch_runs_the_targets_code() {
        assert_eq!(
            dispatch::without(|| vectorized(|fma| fma)),
            cfg!(target_feature = "fma")
        );
        #[cfg(all(feature = "simd", target_arch = "x86_64"))]
        assert_eq!(
            vectorized(|fma| fma),
            pulp::x86::V3::try_new().is_some() || cfg!(target_feature = "fma")
        );
    }

    /// Every `Lanes` operation is the scalar operation lane by lane, bit for
    /// bit, on values chosen to break it: signed zeros, infinities, NaNs of
    /// both signs, subnormals, ties.
    #[test]
    fn lanes_are_the_scalar_operations_lane_by_lane() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -1.5,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
            5e-324,
            -2.5e-310,
            1e300,
            3.0,
        ];
        let n = values.len();
        let bits = |x: f64| x.to_bits();
        // Every ordered pair, four lanes at a time.
        let pairs: Vec<(f64, f64)> = (0..n * n).map(|i| (values[i / n], values[i % n])).collect();
        for group in pairs.chunks(4) {
            let mut a = [0.0; 4];
            let mut b = [0.0; 4];
            for (i, &(x, y)) in group.iter().enumerate() {
                a[i] = x;
                b[i] = y;
            }
            let (la, lb) = (Lanes(a), Lanes(b));
            let c = Lanes([2.0, -0.0, f64::NAN, 7.0]);
            let ops: [(L4, Op); 9] = [
                (la + lb, |x, y, _| x + y),
                (la - lb, |x, y, _| x - y),
                (la * lb, |x, y, _| x * y),
                (la / lb, |x, y, _| x / y),
                (-la, |x, _, _| -x),
                (la.min(lb), |x, y, _| x.min(y)),
                (la.max(lb), |x, y, _| x.max(y)),
                (la.copysign(lb), |x, y, _| x.copysign(y)),
                (la.mul_add(lb, c), |x, y, z| x.mul_add(y, z)),
            ];
            for (k, (got, want)) in ops.iter().enumerate() {
                for i in 0..4 {
                    let w = want(a[i], b[i], c.0[i]);
                    assert!(
                        bits(got.0[i]) == bits(w) || (got.0[i].is_nan() && w.is_nan()),
                        "op {k}, lane {i}: {} vs {w} for {} and {}",
                        got.0[i],
                        a[i],
                        b[i]
                    );
                }
            }
            let masks = [
                (
                    la.lt(lb),
                    [a[0] < b[0], a[1] < b[1], a[2] < b[2], a[3] < b[3]],
                ),
                (
                    la.le(lb),
                    [a[0] <= b[0], a[1] <= b[1], a[2] <= b[2], a[3] <= b[3]],
                ),
                (
                    la.gt(lb),
                    [a[0] > b[0], a[1] > b[1], a[2] > b[2], a[3] > b[3]],
                ),
                (
                    la.ge(lb),
                    [a[0] >= b[0], a[1] >= b[1], a[2] >= b[2], a[3] >= b[3]],
                ),
                (
                    la.eq(lb),
                    [a[0] == b[0], a[1] == b[1], a[2] == b[2], a[3] == b[3]],
                ),
                (la.is_sign_negative(), a.map(f64::is_sign_negative)),
            ];
            for (m, want) in masks {
                assert_eq!(m.0.map(|x| x != 0), want, "{a:?} {b:?}");
                assert!(m.0.iter().all(|&x| x == 0 || x == u64::MAX));
                assert_eq!(Lanes::<f64, 4>::any(m), want.iter().any(|&x| x));
                let picked = Lanes::select(m, la, lb);
                for i in 0..4 {
                    let w = if want[i] { a[i] } else { b[i] };
                    assert_eq!(bits(picked.0[i]), bits(w));
                }
                let (and, or, not) = (m & masks_of(want), m | Mask([0; 4]), !m);
                assert_eq!(and.0, m.0);
                assert_eq!(or.0, m.0);
                assert_eq!(not.0.map(|x| x != 0), want.map(|x| !x));
            }
            for ((&x, s), abs) in a.iter().zip(la.sqrt().0).zip(la.abs().0) {
                let w = x.sqrt();
                assert!(bits(s) == bits(w) || (s.is_nan() && w.is_nan()));
                assert_eq!(bits(abs), bits(x.abs()));
            }
        }
    }

    type L4 = Lanes<f64, 4>;
    /// The scalar operation a lane operation should be.
    type Op = fn(f64, f64, f64) -> f64;

    fn masks_of(b: [bool; 4]) -> Mask<u64, 4> {
        Mask(b.map(|x| if x { u64::MAX } else { 0 }))
    }
}
