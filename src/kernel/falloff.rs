//! Falloff: the lit fraction of a light across a straight-edged penumbra.
//!
//! A straight silhouette edge sweeping across a uniform disk light uncovers
//! it gradually. With `t ∈ [0, 1]` the normalised position across the
//! penumbra (`0` at its inner edge, where the light is just hidden, `1` at its
//! outer edge, where it is just wholly visible), the visible fraction is
//!
//! - [`f64::disk_edge_falloff`]: the exact answer, the fraction of a uniform
//!   disk on one side of a chord,
//!   `F(t) = (acos(1 − 2t) − (1 − 2t)·√(4t(1 − t))) / π`
//!   (it is the regularised incomplete beta function
//!   `I_t(3/2, 3/2)`);
//! - [`f64::bernstein`]: the cubic `3t² − 2t³` that SSOC (Mo, Popescu,
//!   Wyman, §3.2.2) and the penumbra-map family use "to approximate the
//!   sinusoidal falloff of a spherical light source".
//!
//! [`Falloff`] selects one of them (or SSOC's unsmoothed linear ramp, eq. 1).
//!
//! ## How far apart the two curves are
//!
//! `max |F − bernstein| = 0.039412` (0.0394 to four decimals), attained at
//! `t* = 0.235664` and `1 − t* = 0.764336`, where `F` is brighter near the
//! inner edge and darker near the outer edge. Setting the derivative of the
//! difference to zero, `(8/π)√(t(1 − t)) = 6t(1 − t)`, gives the closed form
//! `t* = (1 − √(1 − 64/(9π²)))/2`. `tests/falloff.rs` finds the maximiser
//! independently (golden-section search) and checks both numbers.
//!
//! Both curves are in [`f32`](mod@f32) and [`f64`](mod@f64) from one body. Measured accuracy:
//! see the function docs and `docs/accuracy/kernels.md`.

/// Which curve maps the normalised penumbra position `t` to a lit fraction.
///
/// Every variant maps `[0, 1]` onto `[0, 1]`, is non-decreasing, and takes
/// the values `0`, `1/2`, `1` at `t = 0, 1/2, 1`; below `0` it is `0`, above
/// `1` it is `1`, and NaN gives `0`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Falloff {
    /// `t` itself (clamped): SSOC's eq. 1 before the paper smooths it.
    Linear,
    /// `3t² − 2t³` ([`f64::bernstein`]): SSOC §3.2.2, the paper's choice and
    /// the default.
    #[default]
    Bernstein,
    /// The exact straight-edge falloff of a uniform disk
    /// ([`f64::disk_edge_falloff`]).
    Exact,
}

use crate::kernel::angle::{self, AngleFloat};
use crate::kernel::eft::two_prod;
use crate::kernel::float::both_precisions;

/// The falloff kernels' constants of one precision.
pub(crate) trait FalloffFloat: AngleFloat {
    /// `16/(3π) = C_HI + C_LO`: the leading coefficient of `F(t)` at
    /// `t → 0`, to twice the working precision.
    const C_HI: Self;
    const C_LO: Self;
    /// `1/π = FRAC_1_PI + FRAC_1_PI_LO` to twice the working precision.
    const FRAC_1_PI_LO: Self;
    /// [`SERIES`] in this precision, and how many of its terms this
    /// precision needs on `t ≤ SERIES_MAX`.
    const SERIES: [Self; 26];
    const SERIES_TERMS: usize;
    /// Below `TINY` (`2⁻⁴⁰⁰`, `f32`: `2⁻⁴⁰`), `t²` or `t^(3/2)` could be subnormal while the result
    /// is still normal: `t` is scaled by `2^SCALE_EXP` (exactly) first and
    /// the result scaled back with one rounding. There the dropped
    /// higher-order terms (relative size below `TINY`) are far below an ulp.
    const TINY: Self;
    const SCALE_EXP: i32;
    /// Where the series gives way to the centre form: `0.3`.
    const SERIES_MAX: Self;
}

impl FalloffFloat for f64 {
    const C_HI: f64 = 1.697_652_726_313_550_248_201_426_809_306_82;
    const C_LO: f64 = -1.049_529_422_676_399_3e-16;
    const FRAC_1_PI_LO: f64 = -1.967_867_667_518_248_6e-17;
    const SERIES: [f64; 26] = SERIES.0;
    const SERIES_TERMS: usize = 26;
    const TINY: f64 = f64::from_bits(((1023 - 400) as u64) << 52);
    const SCALE_EXP: i32 = 100;
    const SERIES_MAX: f64 = 0.3;
}

impl FalloffFloat for f32 {
    const C_HI: f32 = 1.697_652_726_313_550_248_201_426_809_306_82;
    const C_LO: f32 = 2.875_037_8e-8;
    const FRAC_1_PI_LO: f32 = 1.284_127_7e-8;
    const SERIES: [f32; 26] = SERIES.1;
    const SERIES_TERMS: usize = 12;
    const TINY: f32 = f32::from_bits(((127 - 40) as u32) << 23);
    const SCALE_EXP: i32 = 40;
    const SERIES_MAX: f32 = 0.3;
}

/// Series coefficients `c_k = (3/2)·a_k/(k + 3/2)` with
/// `a_k = (−1)^k·C(1/2, k)`, so that `F(t) = (16/(3π))·t^(3/2)·Σ c_k t^k`:
/// integrate `F(t) = (8/π)∫₀ᵗ √s·√(1 − s) ds` term by term after expanding
/// `√(1 − s)` binomially. All `c_k`, `k ≥ 1`, are negative and `|c_k| t^k`
/// decreases; the tail after `K` terms is below `|c_K| t^K / (1 − t)`. For
/// `t ≤ SERIES_MAX = 0.3` that is below 0.05 ulp of the sum with 26 terms in
/// `f64` (0.043 ulp) and 12 terms in `f32` (0.011 ulp).
///
/// The series covers `t ≤ 0.3` rather than `t ≤ 1/4` so that the centre
/// form below only sees `F > 0.2523`: `F` crosses `1/4` at `t = 0.29801`,
/// and below that the centre form's `1/2 − G` would halve the ulp of the
/// result while `G` keeps its error.
///
/// As exact numerator and denominator (both below 2⁵³), then each quotient
/// rounded once in `f64` and in `f32` (the `f32` quotient of the two
/// rounded to `f32`).
const SERIES: ([f64; 26], [f32; 26]) = {
    const FRACTIONS: [(f64, f64); 26] = [
        (1.0, 1.0),
        (-3.0, 10.0),
        (-3.0, 56.0),
        (-1.0, 48.0),
        (-15.0, 1408.0),
        (-21.0, 3328.0),
        (-21.0, 5120.0),
        (-99.0, 34816.0),
        (-1287.0, 622592.0),
        (-715.0, 458752.0),
        (-7293.0, 6029312.0),
        (-12597.0, 13107200.0),
        (-29393.0, 37748736.0),
        (-156009.0, 243269632.0),
        (-557175.0, 1040187392.0),
        (-334305.0, 738197504.0),
        (-5816907.0, 15032385536.0),
        (-53036505.0, 158913789952.0),
        (-64822395.0, 223338299392.0),
        (-358229025.0, 1408749273088.0),
        (-2650894785.0, 11819749998592.0),
        (-109402007.0, 549755813888.0),
        (-18349700265.0, 103354093010944.0),
        (-34305961365.0, 215504279044096.0),
        (-171529806825.0, 1196268651020288.0),
        (-967428110493.0, 7459086882832384.0),
    ];
    let mut c = ([0.0; 26], [0.0; 26]);
    let mut k = 0;
    while k < 26 {
        let (num, den) = FRACTIONS[k];
        c.0[k] = num / den;
        c.1[k] = num as f32 / den as f32;
        k += 1;
    }
    c
};

/// `2^e`, exactly (`e` within the normal range).
#[inline(always)]
fn pow2<T: FalloffFloat>(e: i32) -> T {
    T::of(2.0).powi(e)
}

/// Both falloffs' value outside `(0, 1)`: `0` for `t ≤ 0` and NaN, `1`
/// for `t ≥ 1`; `None` inside.
#[inline(always)]
fn at_an_end<T: FalloffFloat>(t: T) -> Option<T> {
    if t.is_nan() || t <= T::of(0.0) {
        Some(T::of(0.0))
    } else if t >= T::of(1.0) {
        Some(T::of(1.0))
    } else {
        None
    }
}

/// [`f64::bernstein`] in either precision.
#[inline]
pub(crate) fn bernstein<T: FalloffFloat>(t: T) -> T {
    if let Some(end) = at_an_end(t) {
        return end;
    }
    let k = T::of;
    if t < T::TINY {
        // 3t², computed at scale 2^(2·SCALE_EXP).
        let ts = t * pow2(T::SCALE_EXP);
        let (t2, t2_err) = two_prod(ts, ts);
        let (b, b_err) = two_prod(k(3.0), t2);
        let b_err = b_err + k(3.0) * t2_err;
        (b + b_err) * pow2(-2 * T::SCALE_EXP)
    } else if t <= k(0.5) {
        let (b, b_err) = bernstein_low(t);
        b + b_err
    } else {
        // 1 − t is exact for t ≥ 1/2 (Sterbenz).
        let (b, b_err) = bernstein_low(k(1.0) - t);
        one_minus(b, b_err)
    }
}

/// `t²(3 − 2t) = hi + lo` for `0 < t ≤ 1/2`, the rounding errors of the
/// square, the difference and the product carried along (error-free
/// transformations), so `hi + lo` is within about 0.5 ulp.
#[inline]
fn bernstein_low<T: FalloffFloat>(t: T) -> (T, T) {
    let k = T::of;
    let (t2, t2_err) = two_prod(t, t);
    // 2t is exact; 3 ≥ 2t, so Fast2Sum recovers the error of 3 − 2t.
    let m = k(3.0) - k(2.0) * t;
    let m_err = (k(3.0) - m) - k(2.0) * t;
    let (b, b_err) = two_prod(t2, m);
    let b_err = b_err + (t2_err * m + t2 * m_err);
    (b, b_err)
}

/// `1 − (hi + lo)` with one final rounding (TwoSum on `1 − hi`).
#[inline]
fn one_minus<T: FalloffFloat>(hi: T, lo: T) -> T {
    let one = T::of(1.0);
    let r = one - hi;
    let hv = one - r;
    let r_err = (one - (r + hv)) + (hv - hi);
    r + (r_err - lo)
}

/// [`f64::disk_edge_falloff`] in either precision.
#[inline]
pub(crate) fn disk_edge_falloff<T: FalloffFloat>(t: T) -> T {
    if let Some(end) = at_an_end(t) {
        return end;
    }
    let k = T::of;
    let series_max = T::SERIES_MAX;
    if t < T::TINY {
        // (16/(3π)) t^(3/2), computed at scale 2^(3·SCALE_EXP/2).
        let (p, p_err) = three_halves(t * pow2(T::SCALE_EXP));
        let (cp, cp_err) = two_prod(T::C_HI, p);
        let cp_err = cp_err + (T::C_HI * p_err + T::C_LO * p);
        (cp + cp_err) * pow2(-3 * T::SCALE_EXP / 2)
    } else if t <= series_max {
        let (f, f_err) = thin_sliver(t);
        f + f_err
    } else if t >= k(1.0) - series_max {
        // 1 − t is exact for t ≥ 1/2 (Sterbenz).
        let (f, f_err) = thin_sliver(k(1.0) - t);
        one_minus(f, f_err)
    } else {
        centre(t)
    }
}

/// `F(t)` for `0.3 < t < 0.7`: `1/2 − (asin h + h√(1 − h²))/π`,
/// `h = 1 − 2t`. The final subtraction cancels up to one bit
/// (`F(0.3) ≈ 0.2523` from `1/2 − 0.2477`), so the sum and the product by
/// `1/π` carry their rounding errors along (error-free transformations) and
/// only `atan2`, the square root and one final rounding contribute.
#[inline]
fn centre<T: FalloffFloat>(t: T) -> T {
    let k = T::of;
    // h = 1 − 2t is exact for 1/4 ≤ t ≤ 1 (Sterbenz), |h| < 0.4.
    let h = k(1.0) - k(2.0) * t;
    // 1 − h² = (1 − h)(1 + h) with 1 − h = 2t exact: two roundings.
    let w = (k(2.0) * t * (k(1.0) + h)).sqrt();
    let (hw, hw_err) = two_prod(h, w);
    // asin h, by the portable atan2 (the same bits on every platform).
    let a = angle::atan2(h, w);
    // |asin h| ≥ |h·w| with the same sign: Fast2Sum is exact.
    let sum = a + hw;
    let sum_err = (hw - (sum - a)) + hw_err;
    let (g, g_err) = two_prod(sum, T::FRAC_1_PI);
    let g_err = g_err + (sum_err * T::FRAC_1_PI + sum * T::FRAC_1_PI_LO);
    // 1/2 − g with its rounding error (TwoSum), then one rounding.
    let r = k(0.5) - g;
    let gv = k(0.5) - r;
    let r_err = (k(0.5) - (r + gv)) + (gv - g);
    r + (r_err - g_err)
}

/// `F(t) = hi + lo` for `0 < t ≤ 0.3` by the series (see [`SERIES`]).
///
/// The sum is formed by Horner's rule (two chains, even and odd powers)
/// from the highest kept term; the leading 1 is added last, so the rounding
/// of the tail is damped by `|c₁|t ≤ 0.09`. The remaining roundings (the
/// square root, `t·√t`, `1 + t·tail`, the constant and the two products)
/// are carried along by error-free transformations, so `hi + lo` rounds to
/// within 0.75 ulp of `F` (measured).
#[inline]
fn thin_sliver<T: FalloffFloat>(t: T) -> (T, T) {
    let k = T::of;
    // tail = Σ_{k≥1} c_k t^(k−1), as two interleaved Horner chains in t²
    // (even and odd powers) to halve the dependency chain.
    let t2 = t * t;
    let (mut even, mut odd) = (k(0.0), k(0.0));
    let mut m = T::SERIES_TERMS - 1;
    while m > 0 {
        m -= 1;
        if m % 2 == 0 {
            even = even * t2 + T::SERIES[m + 1];
        } else {
            odd = odd * t2 + T::SERIES[m + 1];
        }
    }
    let tail = even + t * odd;
    let (x, x_err) = two_prod(t, tail);
    // 1 ≥ |x|: Fast2Sum.
    let sum = k(1.0) + x;
    let sum_err = ((k(1.0) - sum) + x) + x_err;
    let (p, p_err) = three_halves(t);
    let (cp, cp_err) = two_prod(T::C_HI, p);
    let cp_err = cp_err + (T::C_HI * p_err + T::C_LO * p);
    let (f, f_err) = two_prod(cp, sum);
    let f_err = f_err + (cp * sum_err + cp_err * sum);
    (f, f_err)
}

/// `t^(3/2) = hi + lo` for normal `t > 0`: with `s = fl(√t)`,
/// `√t = s + (t − s²)/(2s)` to first order, so
/// `t·√t = t·s + (s/2)(t − s²)·(t/s²)`, and `t/s² = 1 + O(u)` makes the last
/// factor negligible (no division needed).
#[inline]
fn three_halves<T: FalloffFloat>(t: T) -> (T, T) {
    let s = t.sqrt();
    // t − s² exactly: s² = q + e, and t − q is exact (Sterbenz).
    let (q, e) = two_prod(s, s);
    let residual = (t - q) - e;
    let (p, p_err) = two_prod(t, s);
    (p, p_err + T::of(0.5) * s * residual)
}

/// [`f64::eval`] in either precision.
#[inline]
pub(crate) fn eval<T: FalloffFloat>(falloff: Falloff, t: T) -> T {
    match falloff {
        Falloff::Linear => {
            if t > T::of(0.0) {
                t.min(T::of(1.0))
            } else {
                T::of(0.0)
            }
        }
        Falloff::Bernstein => bernstein(t),
        Falloff::Exact => disk_edge_falloff(t),
    }
}

/// The public items of one precision `($T, $V2, $V3)`, declared once
/// with their contracts, each forwarding to the generic body above;
/// `both_precisions!` makes the modules `f64` and `f32` of them.
macro_rules! precision {
    ($T:ident, $V2:ident, $V3:ident) => {
        use super::Falloff;

        /// The Bernstein smoothstep `3t² − 2t³` (SSOC, Mo, Popescu, Wyman,
        /// §3.2.2: "the Bernstein interpolant s = 3t² − 2t³").
        ///
        /// **Domain**: `[0, 1]`; below `0` the result is `0`, above `1` it is
        /// `1` (clamped). NaN gives `0`. Never NaN.
        ///
        /// **Properties**: `bernstein(0) = 0`, `bernstein(1/2) = 1/2`,
        /// `bernstein(1) = 1` exactly; non-decreasing (checked at adjacent
        /// floats, and for every `f32` in `[0, 1]`); `t > 1/2` is evaluated
        /// as `1 − bernstein(1 − t)` with `1 − t` exact, so
        /// `bernstein(t) + bernstein(1 − t) = 1` to about an ulp.
        ///
        /// **Numerics**: `t²(3 − 2t)` with the rounding errors of the square,
        /// the difference and the product carried along (error-free
        /// transformations: exact products with or without hardware FMA)
        /// and one final rounding; below `TINY`
        /// (`2⁻⁴⁰⁰` in `f64`, `2⁻⁴⁰` in `f32`) `3t²` at an exact power-of-two
        /// scale, so no intermediate is subnormal while the result is normal.
        ///
        /// **Accuracy**: measured against a double-double evaluation over the
        /// stiff generator (`tests/falloff.rs`): max 0.50 ulp (`f64` and
        /// `f32`) for normal results, 0.75 ulp for subnormal results (two
        /// roundings); table in `docs/accuracy/kernels.md`.
        #[must_use]
        #[inline]
        pub fn bernstein(t: $T) -> $T {
            super::bernstein(t)
        }

        /// The exact fraction of a uniform disk on the lit side of a straight
        /// edge, `t` the normalised position across the penumbra:
        ///
        /// `F(t) = (acos(1 − 2t) − (1 − 2t)·√(4t(1 − t))) / π`,
        ///
        /// the area of the circular segment of height `2t` of the unit disk
        /// over `π`.
        ///
        /// **Domain**: `[0, 1]`; below `0` the result is `0`, above `1` it is
        /// `1`, NaN gives `0`. Never NaN. `F(0) = 0`, `F(1/2) = 1/2` and
        /// `F(1) = 1` exactly; non-decreasing (checked at adjacent floats
        /// across every branch point, and for every `f32` in `[0, 1]`);
        /// `F(t) + F(1 − t) = 1` to about an ulp.
        ///
        /// **Numerics**: the formula as written takes `acos` near `±1` and
        /// cancels catastrophically for thin slivers. Instead:
        /// - `t ≤ 0.3`: the series `F = (16/(3π)) t^(3/2) Σ c_k t^k` (see
        ///   `SERIES` in the source: truncation below 0.05 ulp), its roundings
        ///   carried along by error-free transformations; below `TINY`
        ///   (`2⁻⁴⁰⁰`, `f32`: `2⁻⁴⁰`) `t^(3/2)` at an exact power-of-two scale,
        ///   so the relative accuracy holds for every normal result;
        /// - `0.3 < t < 0.7`: with `h = 1 − 2t` (exact there, Sterbenz),
        ///   `F = 1/2 − (asin h + h√(1 − h²))/π`: `asin h` of an exact
        ///   argument `|h| < 0.4`, as `atan2(h, √(1 − h²))` by the crate's
        ///   portable [`atan2`](crate::kernel::angle::f64::atan2) (so the
        ///   result has the same bits on every platform; the sum is
        ///   stationary in the root's error), a sum of like-signed terms,
        ///   the sum and the product by `1/π` compensated, and a final
        ///   subtraction that stays in the result's binade (`F > 0.2523`);
        /// - `t ≥ 0.7`: `1 − F(1 − t)`, `1 − t` exact, one final rounding.
        ///
        /// **Accuracy**: measured against a double-double series evaluation
        /// (`tests/falloff.rs`; 4·10⁶ samples of the stiff generator, 8·10⁶
        /// uniform): max 0.95 ulp (`f64`) and 0.96 ulp (`f32`), in the centre
        /// form, from `atan2`'s error; below 0.75 ulp for `t ≤ 0.3` and
        /// `t ≥ 0.7`. Table in `docs/accuracy/kernels.md`.
        ///
        /// **Source**: circular-segment area.
        #[must_use]
        #[inline]
        pub fn disk_edge_falloff(t: $T) -> $T {
            super::disk_edge_falloff(t)
        }

        /// The chosen falloff curve at `t` (see [`Falloff`]): `t` clamped to
        /// `[0, 1]` for [`Falloff::Linear`], [`bernstein`] or
        /// [`disk_edge_falloff`]. NaN gives `0`; never NaN.
        #[must_use]
        #[inline]
        pub fn eval(falloff: Falloff, t: $T) -> $T {
            super::eval(falloff, t)
        }
    };
}

both_precisions!(precision);

#[cfg(test)]
mod tests {
    use super::*;

    /// The series coefficients are the exact rationals of the recurrence
    /// `a_k = a_{k−1}(k − 3/2)/k`, `c_k = (3/2)a_k/(k + 3/2)`, each rounded
    /// once (numerator and denominator are exact below 2⁵³, so the `f64`
    /// division rounds correctly).
    fn series_coefficients_match_the_recurrence<T: FalloffFloat>() {
        // a_k = num/den with a_0 = 1.
        let (mut num, mut den): (i128, i128) = (1, 1);
        for k in 0..T::SERIES.len() as i128 {
            if k > 0 {
                num *= 2 * k - 3;
                den *= 2 * k;
            }
            // c_k = 3 a_k / (2k + 3)
            let (mut cn, mut cd) = (3 * num, den * (2 * k + 3));
            let g = gcd(cn.abs(), cd);
            cn /= g;
            cd /= g;
            assert!(cn.abs() < 1 << 53 && cd < 1 << 53);
            let expected = (cn as f64) / (cd as f64);
            let got = T::SERIES[k as usize].to_f64();
            if T::MANTISSA_DIGITS == 53 {
                assert_eq!(got, expected, "k = {k}");
            } else {
                // f32 constants may round twice (numerator, then the
                // quotient): within 2 ulp.
                let epsilon = 2f64.powi(1 - T::MANTISSA_DIGITS as i32);
                let tol = 2.0 * epsilon * expected.abs();
                assert!((got - expected).abs() <= tol, "k = {k}");
            }
        }
    }

    fn gcd(mut a: i128, mut b: i128) -> i128 {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    }

    test_in_both_precisions!(series_coefficients_match_the_recurrence);

    fn fixed_points<T: FalloffFloat>() {
        let k = T::of;
        for f in [bernstein as fn(T) -> T, disk_edge_falloff] {
            assert_eq!(f(k(0.0)), k(0.0));
            assert_eq!(f(k(0.5)), k(0.5));
            assert_eq!(f(k(1.0)), k(1.0));
            assert_eq!(f(T::NAN), k(0.0));
            assert_eq!(f(k(-1.0)), k(0.0));
            assert_eq!(f(k(2.0)), k(1.0));
        }
    }

    test_in_both_precisions!(fixed_points);
}
