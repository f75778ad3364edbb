//! A portable `atan2`, the one transcendental function the disk kernels
//! spend most of their time in.
//!
//! Why not `f64::atan2`: the standard library calls the platform's libm, so
//! the last bit of an angle (and of every area built on it) would depend on
//! the operating system and its version. This one is the same arithmetic
//! everywhere, so the references built on it give bit-identical answers on
//! every platform. It is within 1.5 ulp (measured maximum over 10⁶ stiff
//! cases: 1.37 ulp in `f64`, 1.41 ulp in `f32`; `tests/angle.rs`), and costs
//! about 1.3× glibc's `atan2` (13.7 ns against 10.6 ns per call in one run on
//! the benchmark machine, `benches/README.md`).
//!
//! Method: with `t = min(|x|, |y|) / max(|x|, |y|) ∈ [0, 1]`, pick one of
//! `c ∈ {0, ½, 1}` and write `atan t = atan c + atan u` with
//! `u = (num − c·den) / (den + c·num)` (one division; `c·den` and the
//! difference are exact for these `c`), so that `|u| ≤ tan(1/4)`. `atan u` is
//! its Taylor series, truncated where the next term is far below half an ulp
//! (14 terms in `f64`, 7 in `f32`). `atan ½`, `π/4`, `π/2` and `π` are
//! double-word constants, and the octant and quadrant are restored by
//! `π/2 − ·` and `π − ·` on the unevaluated sum.

/// One level of Estrin's scheme: `M = ⌈N/2⌉` sums `t[2i] + zp · t[2i+1]`,
/// the last `t[N−1]` alone when `N` is odd.
#[inline(always)]
fn estrin_level<R: crate::kernel::lanes::Real, const N: usize, const M: usize>(
    t: &[R; N],
    zp: R,
) -> [R; M] {
    const { assert!(M == N.div_ceil(2)) };
    core::array::from_fn(|i| {
        if 2 * i + 1 < N {
            t[2 * i] + zp * t[2 * i + 1]
        } else {
            t[2 * i]
        }
    })
}

macro_rules! angle_kernels {
    ($T:ident, $TERMS:expr, [$($LEVELS:literal),+], $SMALL:expr, $LARGE:expr, $BIG:expr, $T0:expr, $T1:expr, $PHI1:expr, $PI4:expr, $PI2:expr, $PI:expr) => {
        use crate::kernel::lanes::Real;

        /// `tan(1/4)` and `(√10 − 1)/3`: the boundaries between the three
        /// reduction intervals, around `c = 0`, `½` and `1`. The first keeps
        /// the middle interval's angles at or above ¼, in a binade whose ulp
        /// absorbs the reduction's rounding; the second balances `|u|`
        /// between the last two.
        const T0: $T = $T0;
        /// Below `SMALL` `den` and `num` are scaled up by the power of two
        /// `BIG`, above `LARGE` down by it.
        const SMALL: $T = $SMALL;
        const LARGE: $T = $LARGE;
        const BIG: $T = $BIG;
        const T1: $T = $T1;
        /// `atan(½)` as a double-word constant.
        const PHI1: ($T, $T) = $PHI1;
        const PI4: ($T, $T) = $PI4;
        const PI2: ($T, $T) = $PI2;
        const PI: ($T, $T) = $PI;
        /// `(−1)ᵏ / (2k + 1)` for `k = 1 .. TERMS`: the series of
        /// `(atan u − u) / u³` in `z = u²`.
        const TAYLOR: [$T; $TERMS - 1] = {
            let mut c = [0.0; $TERMS - 1];
            let mut k = 1;
            while k < $TERMS {
                let sign: $T = if k % 2 == 0 { 1.0 } else { -1.0 };
                c[k - 1] = sign / (2 * k + 1) as $T;
                k += 1;
            }
            c
        };

        /// `a − b = s + e` exactly (Knuth's TwoSum).
        #[inline(always)]
        fn two_diff<R: Real>(a: R, b: R) -> (R, R) {
            let s = a - b;
            let bv = a - s;
            let av = s + bv;
            (s, (a - av) + (bv - b))
        }

        /// The four-quadrant arctangent of `y / x`, in `[−π, π]`, with the
        /// same special values as the IEEE `atan2` for signed zeros
        /// (`atan2(±0, +0) = ±0`, `atan2(±0, −0) = ±π`).
        ///
        /// **Accuracy**: within 1.5 ulp of the true angle (measured maximum
        /// over 10⁶ stiff cases against a 256-bit evaluation, 1.37 ulp in
        /// `f64`, 1.41 in `f32`: `tests/angle.rs`); the result for small
        /// angles (`|y| ≪ x`) keeps full relative accuracy, which thin
        /// circular segments rely on.
        /// Exactly odd: `atan2(−y, x) = −atan2(y, x)` bit for bit.
        ///
        /// **Edge of the domain**: NaN input gives `0` (no kernel returns NaN;
        /// this is the documented total answer); infinite input is
        /// passed to the platform's `atan2` (its standard special values).
        #[must_use]
        #[inline]
        pub fn atan2(y: $T, x: $T) -> $T {
            let (num, den, swap, regular) = reduce(y, x);
            if !regular {
                if x.is_nan() || y.is_nan() {
                    // No NaN leaves a kernel: the documented total answer.
                    return 0.0;
                }
                // Both zero, or an infinity: the standard special values.
                return y.atan2(x);
            }
            core(num, den, swap, x, y)
        }

        /// `(num, den, swap, regular)`: `num = min(|x|, |y|)`, `den =
        /// max(|x|, |y|)`, `swap` when `|y| > |x|`; `regular` when [`core()`]
        /// applies (`0 < den < ∞`, no NaN), not for the special values.
        #[inline(always)]
        pub(crate) fn reduce<R: Real<Scalar = $T>>(y: R, x: R) -> (R, R, R::Mask, R::Mask) {
            let (ax, ay) = (x.abs(), y.abs());
            let swap = ay.gt(ax);
            let (num, den) = (R::select(swap, ax, ay), R::select(swap, ay, ax));
            // `den − den` is 0 exactly when den is finite. (Not `den < ∞`:
            // LLVM fuses that with `den > 0` into a class test it cannot
            // keep in vector registers.)
            let regular =
                den.gt(R::splat(0.0)) & (den - den).eq(R::splat(0.0)) & num.ge(R::splat(0.0));
            (num, den, swap, regular)
        }

        /// The arctangent once the special values are out of the way:
        /// `num = min(|x|, |y|) ≥ 0`, `0 < den = max(|x|, |y|) < ∞`, `swap`
        /// when `|y| > |x|`. Written as selects rather than branches: which
        /// octant a point is in is unpredictable, a mispredicted branch costs
        /// as much as the polynomial, and over
        /// [`Lanes`](crate::kernel::lanes::Lanes) every lane takes the
        /// same instructions. [`atan2`] is this plus the special values.
        #[inline(always)]
        pub(crate) fn core<R: Real<Scalar = $T>>(num: R, den: R, swap: R::Mask, x: R, y: R) -> R {
            let k = |x: $T| R::splat(x);
            // Subnormal territory: scale both up by a power of two (exact,
            // the ratio is unchanged) so the products below stay normal;
            // near the top, down, to keep den + num finite.
            let scale = R::select(
                den.lt(k(SMALL)),
                k(BIG),
                R::select(den.gt(k(LARGE)), k(1.0 / BIG), k(1.0)),
            );
            let (num, den) = (num * scale, den * scale);
            let (beyond0, beyond1) = (num.gt(k(T0) * den), num.gt(k(T1) * den));
            // c ∈ {0, ½, 1} and its angle φ = atan c.
            let pick = |one: $T, half: $T, zero: $T| {
                R::select(beyond1, k(one), R::select(beyond0, k(half), k(zero)))
            };
            let c = pick(1.0, 0.5, 0.0);
            let phi = (pick(PI4.0, PHI1.0, 0.0), pick(PI4.1, PHI1.1, 0.0));
            // c·den is exact, and so is num − c·den (Sterbenz: num lies
            // within a factor 2 of c·den on each interval).
            let u = (num - c * den) / (den + c * num);
            let z = u * u;
            // atan u = u (1 − z/3 + z²/5 − …): the series in z by Estrin's
            // scheme (a shallow tree instead of Horner's long chain).
            // Each level pairs neighbours, `t[i] = t[2i] + zᵖ t[2i+1]`, the
            // odd one out carried up; written level by level (sizes `$LEVELS`)
            // so that it is straight-line code, in registers.
            let t = TAYLOR.map(k);
            let zp = z;
            $(
                let t: [R; $LEVELS] = super::estrin_level(&t, zp);
                let zp = zp * zp;
            )+
            let _ = zp;
            let atan_u = u + u * (z * t[0]);
            // The angle as an unevaluated sum hi + lo, so that the octant and
            // quadrant steps below add no rounding of their own.
            let (hi, lo) = (phi.0, atan_u + phi.1);
            let (s, e) = two_diff(k(PI2.0), hi);
            let (hi, lo) = (
                R::select(swap, s, hi),
                R::select(swap, e + (k(PI2.1) - lo), lo),
            );
            let (s, e) = two_diff(k(PI.0), hi);
            let negative = x.is_sign_negative();
            let (hi, lo) = (
                R::select(negative, s, hi),
                R::select(negative, e + (k(PI.1) - lo), lo),
            );
            (hi + lo).copysign(y)
        }
    };
}

/// `f64` angle kernels.
pub mod f64 {
    angle_kernels!(
        f64,
        14,
        [7, 4, 2, 1],
        1e-280,
        1e299,
        (1u128 << 110) as f64,
        0.255_341_921_221_036_27,
        0.720_759_220_056_126_5,
        (0.463_647_609_000_806_1, 2.269_877_745_296_168_7e-17),
        (core::f64::consts::FRAC_PI_4, 3.061616997868383e-17),
        (core::f64::consts::FRAC_PI_2, 6.123233995736766e-17),
        (core::f64::consts::PI, 1.2246467991473532e-16)
    );
}

/// `f32` angle kernels.
pub mod f32 {
    angle_kernels!(
        f32,
        7,
        [3, 2, 1],
        1e-29,
        1e34,
        (1u64 << 52) as f32,
        0.255_341_92,
        0.720_759_2,
        (0.463_647_6, 5.012_158_7e-9),
        (core::f32::consts::FRAC_PI_4, -2.185_569_4e-8),
        (core::f32::consts::FRAC_PI_2, -4.371_139e-8),
        (core::f32::consts::PI, -8.742_278e-8)
    );
}
