//! A portable `atan2`, the one transcendental function the disk kernels
//! spend most of their time in.
//!
//! Why not `f64::atan2`: the standard library calls the platform's libm, so
//! the last bit of an angle (and of every area built on it) would depend on
//! the operating system and its version. This one is the same arithmetic
//! everywhere, so the references built on it give bit-identical answers on
//! every platform. It is within 1.5 ulp (measured maximum over 10⁶ stiff
//! cases: 1.37 ulp in `f64`, 1.41 ulp in `f32`; `tests/angle.rs`), at a
//! cost somewhat above glibc's `atan2` (measured in `benches/README.md` §
//! Disk occlusion against a ray–triangle test).
//!
//! Method: with `t = min(|x|, |y|) / max(|x|, |y|) ∈ [0, 1]`, pick one of
//! `c ∈ {0, ½, 1}` and write `atan t = atan c + atan u` with
//! `u = (num − c·den) / (den + c·num)` (one division; `c·den` and the
//! difference are exact for these `c`), so that `|u| ≤ tan(1/4)`. `atan u` is
//! its Taylor series, truncated where the next term is far below half an ulp
//! (14 terms in `f64`, 7 in `f32`). `atan ½`, `π/4`, `π/2` and `π` are
//! double-word constants, and the octant and quadrant are restored by
//! `π/2 − ·` and `π − ·` on the unevaluated sum.

use crate::kernel::float::{both_precisions, Float};
use crate::kernel::lanes::Real;

/// The constants of one precision's arctangent.
pub(crate) trait AngleFloat: Float {
    /// `tan(1/4)` and `(√10 − 1)/3`: the boundaries between the three
    /// reduction intervals, around `c = 0`, `½` and `1`. The first keeps the
    /// middle interval's angles at or above ¼, in a binade whose ulp absorbs
    /// the reduction's rounding; the second balances `|u|` between the last
    /// two.
    const T0: Self;
    const T1: Self;
    /// Below `SMALL` `den` and `num` are scaled up by the power of two
    /// `BIG`, above `LARGE` down by it.
    const SMALL: Self;
    const LARGE: Self;
    const BIG: Self;
    /// `atan(½)`, `π/4`, `π/2` and `π` (`PI_2W`) as double-word constants.
    const PHI1: (Self, Self);
    const PI4: (Self, Self);
    const PI2: (Self, Self);
    const PI_2W: (Self, Self);

    /// `(atan u − u) / u³` as a series in `z = u²`, truncated where the next
    /// term is far below half an ulp: `Σ (−1)ᵏ zᵏ⁻¹ / (2k + 1)` for
    /// `k = 1 .. TERMS` (14 terms in `f64`, 7 in `f32`), by Estrin's scheme
    /// (a shallow tree instead of Horner's long chain), level by level, so
    /// that it is straight-line code, in registers.
    fn series<R: Real<Scalar = Self>>(z: R) -> R;
}

impl AngleFloat for f64 {
    const T0: f64 = 0.255_341_921_221_036_27;
    const T1: f64 = 0.720_759_220_056_126_5;
    const SMALL: f64 = 1e-280;
    const LARGE: f64 = 1e299;
    const BIG: f64 = (1u128 << 110) as f64;
    const PHI1: (f64, f64) = (0.463_647_609_000_806_1, 2.269_877_745_296_168_7e-17);
    const PI4: (f64, f64) = (core::f64::consts::FRAC_PI_4, 3.061616997868383e-17);
    const PI2: (f64, f64) = (core::f64::consts::FRAC_PI_2, 6.123233995736766e-17);
    const PI_2W: (f64, f64) = (core::f64::consts::PI, 1.2246467991473532e-16);

    #[inline(always)]
    fn series<R: Real<Scalar = f64>>(z: R) -> R {
        let t = TAYLOR.0.map(R::splat);
        let t: [R; 7] = estrin_level(&t, z);
        let zp = z * z;
        let t: [R; 4] = estrin_level(&t, zp);
        let zp = zp * zp;
        let t: [R; 2] = estrin_level(&t, zp);
        let zp = zp * zp;
        let t: [R; 1] = estrin_level(&t, zp);
        t[0]
    }
}

impl AngleFloat for f32 {
    const T0: f32 = 0.255_341_92;
    const T1: f32 = 0.720_759_2;
    const SMALL: f32 = 1e-29;
    const LARGE: f32 = 1e34;
    const BIG: f32 = (1u64 << 52) as f32;
    const PHI1: (f32, f32) = (0.463_647_6, 5.012_158_7e-9);
    const PI4: (f32, f32) = (core::f32::consts::FRAC_PI_4, -2.185_569_4e-8);
    const PI2: (f32, f32) = (core::f32::consts::FRAC_PI_2, -4.371_139e-8);
    const PI_2W: (f32, f32) = (core::f32::consts::PI, -8.742_278e-8);

    #[inline(always)]
    fn series<R: Real<Scalar = f32>>(z: R) -> R {
        let t: [R; 6] = core::array::from_fn(|i| R::splat(TAYLOR.1[i]));
        let t: [R; 3] = estrin_level(&t, z);
        let zp = z * z;
        let t: [R; 2] = estrin_level(&t, zp);
        let zp = zp * zp;
        let t: [R; 1] = estrin_level(&t, zp);
        t[0]
    }
}

/// `(−1)ᵏ / (2k + 1)` for `k = 1 ..= 13`, each rounded once in `f64` and
/// in `f32` (`f32` uses the first 6).
const TAYLOR: ([f64; 13], [f32; 13]) = {
    let mut c = ([0.0; 13], [0.0; 13]);
    let mut k = 1;
    while k <= 13 {
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        c.0[k - 1] = sign / (2 * k + 1) as f64;
        c.1[k - 1] = sign as f32 / (2 * k + 1) as f32;
        k += 1;
    }
    c
};

/// One level of Estrin's scheme: `M = ⌈N/2⌉` sums `t[2i] + zp · t[2i+1]`,
/// the last `t[N−1]` alone when `N` is odd.
#[inline(always)]
fn estrin_level<R: Real, const N: usize, const M: usize>(t: &[R; N], zp: R) -> [R; M] {
    const { assert!(M == N.div_ceil(2)) };
    core::array::from_fn(|i| {
        if 2 * i + 1 < N {
            t[2 * i] + zp * t[2 * i + 1]
        } else {
            t[2 * i]
        }
    })
}

/// `a − b = s + e` exactly (Knuth's TwoSum).
#[inline(always)]
fn two_diff<R: Real>(a: R, b: R) -> (R, R) {
    let s = a - b;
    let bv = a - s;
    let av = s + bv;
    (s, (a - av) + (bv - b))
}

/// [`f64::atan2`] in either precision.
#[inline]
pub(crate) fn atan2<T: AngleFloat>(y: T, x: T) -> T {
    let (num, den, swap, regular) = reduce(y, x);
    if !regular {
        if x.is_nan() || y.is_nan() {
            // No NaN leaves a kernel: the documented total answer.
            return T::of(0.0);
        }
        // Both zero, or an infinity: the standard special values.
        return y.atan2_std(x);
    }
    core(num, den, swap, x, y)
}

/// `(num, den, swap, regular)`: `num = min(|x|, |y|)`, `den = max(|x|,
/// |y|)`, `swap` when `|y| > |x|`; `regular` when [`core()`] applies
/// (`0 < den < ∞`, no NaN), not for the special values.
#[inline(always)]
pub(crate) fn reduce<T: Float, R: Real<Scalar = T>>(y: R, x: R) -> (R, R, R::Mask, R::Mask) {
    let zero = R::splat(T::of(0.0));
    let (ax, ay) = (x.abs(), y.abs());
    let swap = ay.gt(ax);
    let (num, den) = (R::select(swap, ax, ay), R::select(swap, ay, ax));
    // `den − den` is 0 exactly when den is finite. (Not `den < ∞`: LLVM
    // fuses that with `den > 0` into a class test it cannot keep in vector
    // registers.)
    #[allow(clippy::eq_op)] // `den − den`: deliberate, see above.
    let regular = den.gt(zero) & (den - den).eq(zero) & num.ge(zero);
    (num, den, swap, regular)
}

/// The arctangent once the special values are out of the way: `num =
/// min(|x|, |y|) ≥ 0`, `0 < den = max(|x|, |y|) < ∞`, `swap` when `|y| >
/// |x|`. Written as selects rather than branches: which octant a point is
/// in is unpredictable, a mispredicted branch costs as much as the
/// polynomial, and over [`Lanes`](crate::kernel::lanes::Lanes) every lane
/// takes the same instructions. [`atan2`] is this plus the special values.
#[inline(always)]
pub(crate) fn core<T: AngleFloat, R: Real<Scalar = T>>(
    num: R,
    den: R,
    swap: R::Mask,
    x: R,
    y: R,
) -> R {
    let k = R::splat;
    // Subnormal territory: scale both up by a power of two (exact, the
    // ratio is unchanged) so the products below stay normal; near the top,
    // down, to keep den + num finite.
    let scale = R::select(
        den.lt(k(T::SMALL)),
        k(T::BIG),
        R::select(den.gt(k(T::LARGE)), k(T::of(1.0) / T::BIG), k(T::of(1.0))),
    );
    let (num, den) = (num * scale, den * scale);
    let (beyond0, beyond1) = (num.gt(k(T::T0) * den), num.gt(k(T::T1) * den));
    // c ∈ {0, ½, 1} and its angle φ = atan c.
    let pick =
        |one: T, half: T, zero: T| R::select(beyond1, k(one), R::select(beyond0, k(half), k(zero)));
    let c = pick(T::of(1.0), T::of(0.5), T::of(0.0));
    let phi = (
        pick(T::PI4.0, T::PHI1.0, T::of(0.0)),
        pick(T::PI4.1, T::PHI1.1, T::of(0.0)),
    );
    // c·den is exact, and so is num − c·den (Sterbenz: num lies within a
    // factor 2 of c·den on each interval).
    let u = (num - c * den) / (den + c * num);
    let z = u * u;
    // atan u = u (1 − z/3 + z²/5 − …).
    let atan_u = u + u * (z * T::series(z));
    // The angle as an unevaluated sum hi + lo, so that the octant and
    // quadrant steps below add no rounding of their own.
    let (hi, lo) = (phi.0, atan_u + phi.1);
    let (s, e) = two_diff(k(T::PI2.0), hi);
    let (hi, lo) = (
        R::select(swap, s, hi),
        R::select(swap, e + (k(T::PI2.1) - lo), lo),
    );
    let (s, e) = two_diff(k(T::PI_2W.0), hi);
    let negative = x.is_sign_negative();
    let (hi, lo) = (
        R::select(negative, s, hi),
        R::select(negative, e + (k(T::PI_2W.1) - lo), lo),
    );
    (hi + lo).copysign(y)
}

/// The public items of one precision `($T, $V2, $V3)`, declared once
/// with their contracts, each forwarding to the generic body above;
/// `both_precisions!` makes the modules `f64` and `f32` of them.
macro_rules! precision {
    ($T:ident, $V2:ident, $V3:ident) => {
        /// The four-quadrant arctangent of `y / x`, in `[−π, π]`, with the same
        /// special values as the IEEE `atan2` for signed zeros (`atan2(±0, +0) =
        /// ±0`, `atan2(±0, −0) = ±π`).
        ///
        /// **Accuracy**: within 1.5 ulp of the true angle (measured maximum over
        /// 10⁶ stiff cases against a 256-bit evaluation, 1.37 ulp in `f64`,
        /// 1.41 in `f32`: `tests/angle.rs`); the result for small angles
        /// (`|y| ≪ x`) keeps full relative accuracy, which thin circular
        /// segments rely on. Exactly odd: `atan2(−y, x) = −atan2(y, x)` bit for
        /// bit.
        ///
        /// **Edge of the domain**: NaN input gives `0` (no kernel returns NaN;
        /// this is the documented total answer); infinite input is passed to
        /// the platform's `atan2` (its standard special values).
        #[must_use]
        #[inline]
        pub fn atan2(y: $T, x: $T) -> $T {
            super::atan2(y, x)
        }
    };
}

both_precisions!(precision);
