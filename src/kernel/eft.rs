//! Error-free transformations shared by the kernels and the predicates.
//!
//! `two_prod(a, b)` returns `(p, e)` with `p = fl(a · b)` and `a · b = p + e`
//! exactly (barring underflow of `e` and overflow of the split). With a
//! hardware FMA enabled at build time it is `e = fma(a, b, −p)`; otherwise
//! Dekker's product with Veltkamp's split. Both are exact, so both give the
//! same bits and no result depends on the target features. (Calling
//! `mul_add` without hardware FMA goes through a software routine that costs
//! more than a whole kernel.)

use crate::kernel::float::Float;
use crate::kernel::lanes::Real;

/// `a · b = p + e` exactly; see the module docs.
#[inline(always)]
pub(crate) fn two_prod<R: Real>(a: R, b: R) -> (R, R)
where
    R::Scalar: Float,
{
    #[cfg(target_feature = "fma")]
    {
        two_prod_fma(a, b)
    }
    #[cfg(not(target_feature = "fma"))]
    {
        let p = a * b;
        // Veltkamp's split: x = hi + lo with half-width halves.
        let factor = (1u64 << <R::Scalar as Float>::MANTISSA_DIGITS.div_ceil(2)) + 1;
        let split = |x: R| {
            let c = R::splat(<R::Scalar as Float>::of(factor as f64)) * x;
            let hi = c - (c - x);
            (hi, x - hi)
        };
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
    }
}

/// [`two_prod`] by a fused multiply-add: the same bits, fast only where a
/// hardware FMA is enabled (at build time, or in a function compiled for
/// it); elsewhere `mul_add` is a software routine.
#[inline(always)]
pub(crate) fn two_prod_fma<R: Real>(a: R, b: R) -> (R, R) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// The error-free transformations in `f64`.
pub(crate) mod f64 {
    pub(crate) use super::two_prod;
}

/// `2^k` for `k` in `-1022..=1023` (a normal double, exactly).
fn pow2(k: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&k), "{k}");
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// `x · 2^k` for any `k`, in steps that stay within the normal range, so
/// exact whenever the result is a normal double.
pub(crate) fn times_pow2(mut x: f64, mut k: i32) -> f64 {
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        x *= pow2(step);
        k -= step;
    }
    x
}

/// `(v · 2^k, k)` for the `k` that puts the largest component of `v` in
/// `[1, 4)`: only exponents change, so the direction is `v`'s bit for bit
/// (barring components over 2⁹⁰⁰ times smaller than the largest, which
/// may underflow), and its squared length neither overflows nor
/// underflows — where glam's `normalize` and `length` fail for a vector
/// of length `1e200` or `1e-200`. `None` when `v` is zero or not finite.
///
/// For a vector whose squared length is a normal double, `normalize` and
/// `length` of the scaled vector are the unscaled ones' times `2^k`
/// exactly, so they give the same bits after scaling back.
pub(crate) fn pow2_scaled(v: glam::DVec3) -> Option<(glam::DVec3, i32)> {
    let m = v.abs().max_element();
    if !(v.is_finite() && m > 0.0) {
        return None;
    }
    // A subnormal largest component is first brought into the normal range.
    let (v, m, pre) = if m < f64::MIN_POSITIVE {
        (v * pow2(54), m * pow2(54), 54)
    } else {
        (v, m, 0)
    };
    let exponent = (m.to_bits() >> 52) as i32 - 1023;
    let k = (-exponent).max(-1022);
    Some((v * pow2(k), k + pre))
}

/// `v / ‖v‖` for every finite non-zero `v`, however long or short (through
/// [`pow2_scaled`]: the bits of `v.normalize()` wherever that is finite
/// and its squared length normal); `None` for zero or non-finite `v`.
pub(crate) fn unit(v: glam::DVec3) -> Option<glam::DVec3> {
    pow2_scaled(v).map(|(w, _)| w.normalize())
}

/// `‖v‖` for every finite `v`, without the overflow and underflow of the
/// squared length (`v.length()`'s bits wherever its squared length is a
/// normal double); `+∞` only beyond `f64::MAX`.
pub(crate) fn length(v: glam::DVec3) -> f64 {
    match pow2_scaled(v) {
        Some((w, k)) => times_pow2(w.length(), -k),
        None if v.is_finite() => 0.0,
        None => f64::INFINITY,
    }
}

/// `(n, k)` with `u × v = n · 2^-k`: the cross product of `u` and `v`
/// scaled by powers of two (exactly, see [`pow2_scaled`]) with the
/// largest component of `n` in `[1, 4)`, whatever the lengths of `u` and
/// `v` (half-axes of `1e200` or `1e-200`, whose area overflows or
/// underflows). `None` when `u` or `v` is zero or not finite, or the
/// scaled product is zero (parallel to rounding).
pub(crate) fn scaled_cross(u: glam::DVec3, v: glam::DVec3) -> Option<(glam::DVec3, i32)> {
    let (u, ku) = pow2_scaled(u)?;
    let (v, kv) = pow2_scaled(v)?;
    let (n, kn) = pow2_scaled(u.cross(v))?;
    Some((n, ku + kv + kn))
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    #[test]
    fn scaling_by_powers_of_two_keeps_every_bit() {
        // Ordinary vectors: the same bits as glam's normalize and length.
        let mut x = 0.123_456_789_f64;
        for _ in 0..200 {
            x = (x * 3.7 + 0.31).fract();
            let v = DVec3::new(x - 0.5, (x * 7.0).fract() * 3.0, -(x * 13.0).fract() * 1e3);
            assert_eq!(super::unit(v), Some(v.normalize()), "{v}");
            assert_eq!(super::length(v), v.length(), "{v}");
            let w = DVec3::new(v.z, v.x, v.y * 0.01);
            let (n, k) = super::scaled_cross(v, w).unwrap();
            assert_eq!(n * super::pow2(-k), v.cross(w), "{v} {w}");
        }
        // Lengths whose square overflows or underflows.
        for scale in [1e200, 1e-200, 1e300, 5e-324, f64::MAX] {
            let v = DVec3::new(0.0, -scale, 0.0);
            assert_eq!(super::unit(v), Some(DVec3::NEG_Y), "{scale}");
            assert_eq!(super::length(v), scale, "{scale}");
        }
        let v = DVec3::new(3e200, 4e200, 0.0);
        assert!(
            (super::length(v) / 5e200 - 1.0).abs() <= f64::EPSILON,
            "{v}"
        );
        assert!(
            (super::unit(v).unwrap() - DVec3::new(0.6, 0.8, 0.0)).length() < 4.0 * f64::EPSILON
        );
        assert_eq!(super::unit(DVec3::ZERO), None);
        assert_eq!(super::unit(DVec3::new(f64::NAN, 1.0, 0.0)), None);
        assert_eq!(super::length(DVec3::ZERO), 0.0);
        assert_eq!(super::scaled_cross(DVec3::X, DVec3::X * 3.0), None);
        // An area of 1e400: the direction exact, the magnitude in the
        // exponent.
        let (n, k) = super::scaled_cross(DVec3::X * 1e200, DVec3::Z * 1e200).unwrap();
        assert_eq!(n.normalize(), DVec3::NEG_Y);
        let log2_area = f64::from(-k) + n.length().log2();
        assert!(
            (log2_area - 400.0 * 10f64.log2()).abs() < 1e-12,
            "{log2_area}"
        );
    }

    #[test]
    fn two_prod_is_exact() {
        // (1 + 2⁻³⁰)² = 1 + 2⁻²⁹ + 2⁻⁶⁰: the last term is the error.
        let x = 1.0 + 2f64.powi(-30);
        assert_eq!(
            super::two_prod(x, x),
            (1.0 + 2f64.powi(-29), 2f64.powi(-60))
        );
        let y = 1.0 + 2f32.powi(-13);
        assert_eq!(
            super::two_prod(y, y),
            (1.0 + 2f32.powi(-12), 2f32.powi(-26))
        );
    }
}
