//! `N` lanes of `f32`, the operations the occlusion walk needs: one
//! instruction each where the processor has AVX2 (eight lanes in a `ymm`
//! register, through `pulp`'s safe intrinsics: no `unsafe` of ours), a
//! loop over an array elsewhere ([`Portable`]); and the per-segment slab
//! constants in four `f64` lanes ([`axes4`]).
//!
//! Each operation is the same IEEE operation on every lane in every form
//! (no fused multiply-add; `max` and `min` as `maxps` and `minps` define
//! them, `a > b ? a : b` and `a < b ? a : b`), so the forms give the same
//! bits (`tests::forms_agree`).

/// `N` lanes of `f32` (see the module docs).
pub(super) trait Lanes<const N: usize>: Copy {
    /// A vector of `N` lanes.
    type F: Copy;
    fn load(self, a: &[f32; N]) -> Self::F;
    fn splat(self, x: f32) -> Self::F;
    fn add(self, a: Self::F, b: Self::F) -> Self::F;
    fn sub(self, a: Self::F, b: Self::F) -> Self::F;
    fn mul(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a > b ? a : b`, lane by lane.
    fn max(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a < b ? a : b`, lane by lane.
    fn min(self, a: Self::F, b: Self::F) -> Self::F;
    /// The lanes where `a ≤ b`, as bits.
    fn le(self, a: Self::F, b: Self::F) -> u32;
    /// The lanes where `a < b`, as bits.
    fn lt(self, a: Self::F, b: Self::F) -> u32;
    /// The lanes where `a > b`, as bits.
    fn gt(self, a: Self::F, b: Self::F) -> u32 {
        self.lt(b, a)
    }
}

/// Lanes as arrays, one operation a lane.
#[derive(Clone, Copy, Debug)]
pub(super) struct Portable;

impl<const N: usize> Lanes<N> for Portable {
    type F = [f32; N];
    #[inline(always)]
    fn load(self, a: &[f32; N]) -> [f32; N] {
        *a
    }
    #[inline(always)]
    fn splat(self, x: f32) -> [f32; N] {
        [x; N]
    }
    #[inline(always)]
    fn add(self, a: [f32; N], b: [f32; N]) -> [f32; N] {
        core::array::from_fn(|l| a[l] + b[l])
    }
    #[inline(always)]
    fn sub(self, a: [f32; N], b: [f32; N]) -> [f32; N] {
        core::array::from_fn(|l| a[l] - b[l])
    }
    #[inline(always)]
    fn mul(self, a: [f32; N], b: [f32; N]) -> [f32; N] {
        core::array::from_fn(|l| a[l] * b[l])
    }
    #[inline(always)]
    fn max(self, a: [f32; N], b: [f32; N]) -> [f32; N] {
        core::array::from_fn(|l| if a[l] > b[l] { a[l] } else { b[l] })
    }
    #[inline(always)]
    fn min(self, a: [f32; N], b: [f32; N]) -> [f32; N] {
        core::array::from_fn(|l| if a[l] < b[l] { a[l] } else { b[l] })
    }
    #[inline(always)]
    fn le(self, a: [f32; N], b: [f32; N]) -> u32 {
        (0..N).fold(0, |m, l| m | u32::from(a[l] <= b[l]) << l)
    }
    #[inline(always)]
    fn lt(self, a: [f32; N], b: [f32; N]) -> u32 {
        (0..N).fold(0, |m, l| m | u32::from(a[l] < b[l]) << l)
    }
}

#[cfg(all(feature = "simd", target_arch = "x86_64"))]
mod avx {
    use super::Lanes;
    use core::arch::x86_64::{__m256, _CMP_LE_OQ, _CMP_LT_OQ};
    use pulp::x86::V3;

    /// Eight lanes in a `ymm` register.
    #[derive(Clone, Copy, Debug)]
    pub(in super::super) struct Avx8(pub(in super::super) V3);

    /// The lane operations that are one AVX instruction on two vectors.
    macro_rules! binary {
        ($($name:ident: $op:ident),* $(,)?) => {$(
            #[inline(always)]
            fn $name(self, a: __m256, b: __m256) -> __m256 {
                self.0.avx.$op(a, b)
            }
        )*};
    }

    impl Avx8 {
        /// A comparison's lanes as bits.
        #[inline(always)]
        fn bits(self, m: __m256) -> u32 {
            self.0.avx._mm256_movemask_ps(m) as u32
        }
    }

    impl Lanes<8> for Avx8 {
        type F = __m256;
        #[inline(always)]
        fn load(self, a: &[f32; 8]) -> __m256 {
            pulp::cast(*a)
        }
        #[inline(always)]
        fn splat(self, x: f32) -> __m256 {
            self.0.avx._mm256_set1_ps(x)
        }
        binary! {
            add: _mm256_add_ps,
            sub: _mm256_sub_ps,
            mul: _mm256_mul_ps,
            max: _mm256_max_ps,
            min: _mm256_min_ps,
        }
        #[inline(always)]
        fn le(self, a: __m256, b: __m256) -> u32 {
            self.bits(self.0.avx._mm256_cmp_ps::<_CMP_LE_OQ>(a, b))
        }
        #[inline(always)]
        fn lt(self, a: __m256, b: __m256) -> u32 {
            self.bits(self.0.avx._mm256_cmp_ps::<_CMP_LT_OQ>(a, b))
        }
    }
}

#[cfg(all(feature = "simd", target_arch = "x86_64"))]
pub(super) use avx::Avx8;

/// [`Ray32::axes`](super::ray::Ray32::axes) of four lanes in AVX
/// registers: the same operations in the same order on each lane (so the
/// same bits), four `f64` at a time.
#[cfg(all(feature = "simd", target_arch = "x86_64"))]
#[inline(always)]
pub(super) fn axes4(v3: pulp::x86::V3, p: [f64; 4], d: [f64; 4]) -> Axes32<4> {
    use core::arch::x86_64::{__m128, __m256d, _CMP_LT_OQ};
    const TINY: f32 = 1.0 / (1u128 << 100) as f32;
    let (avx, sse, sse41) = (v3.avx, v3.sse, v3.sse4_1);
    let pv: __m256d = pulp::cast(p);
    let dv: __m256d = pulp::cast(d);
    let abs_pd = avx._mm256_castsi256_pd(avx._mm256_set1_epi64x(i64::MAX));
    let abs_ps = v3.sse2._mm_castsi128_ps(v3.sse2._mm_set1_epi32(i32::MAX));
    // o = f64(p as f32); di = d as f32, ±TINY (the sign of `d < 0`) where
    // |di| < TINY.
    let o = avx._mm256_cvtps_pd(avx._mm256_cvtpd_ps(pv));
    let di = avx._mm256_cvtpd_ps(dv);
    let negative: __m128 = avx._mm256_cvtpd_ps(avx._mm256_and_pd(
        avx._mm256_cmp_pd::<_CMP_LT_OQ>(dv, avx._mm256_setzero_pd()),
        avx._mm256_set1_pd(-1.0),
    ));
    let backward_d = avx._mm_cmp_ps::<_CMP_LT_OQ>(negative, sse._mm_setzero_ps());
    let tiny = sse41._mm_blendv_ps(sse._mm_set1_ps(TINY), sse._mm_set1_ps(-TINY), backward_d);
    let small = avx._mm_cmp_ps::<_CMP_LT_OQ>(sse._mm_and_ps(di, abs_ps), sse._mm_set1_ps(TINY));
    let di = sse41._mm_blendv_ps(di, tiny, small);
    // delta = (|p| + |d|) 2⁻²¹ + 4 TINY; wide = delta (1 + 2⁻²²) + |o| / 2²³.
    let sum = avx._mm256_add_pd(avx._mm256_and_pd(pv, abs_pd), avx._mm256_and_pd(dv, abs_pd));
    let delta = avx._mm256_add_pd(
        avx._mm256_mul_pd(sum, avx._mm256_set1_pd(1.0 / f64::from(1u32 << 21))),
        avx._mm256_set1_pd(4.0 * f64::from(TINY)),
    );
    let wide = avx._mm256_add_pd(
        avx._mm256_mul_pd(delta, avx._mm256_set1_pd(1.0 + 1.0 / f64::from(1u32 << 22))),
        avx._mm256_mul_pd(
            avx._mm256_and_pd(o, abs_pd),
            avx._mm256_set1_pd(1.0 / f64::from(1u32 << 23)),
        ),
    );
    let up = clamp4(v3, avx._mm256_cvtpd_ps(avx._mm256_add_pd(o, wide)));
    let down = clamp4(v3, avx._mm256_cvtpd_ps(avx._mm256_sub_pd(o, wide)));
    let backward = avx._mm_cmp_ps::<_CMP_LT_OQ>(di, sse._mm_setzero_ps());
    let near = sse41._mm_blendv_ps(up, down, backward);
    let far = sse41._mm_blendv_ps(down, up, backward);
    let inv = sse._mm_div_ps(sse._mm_set1_ps(1.0), di);
    let mask = sse._mm_movemask_ps(backward);
    Axes32 {
        near: pulp::cast(near),
        far: pulp::cast(far),
        inv: pulp::cast(inv),
        backward: [0, 1, 2, 3].map(|l| mask >> l & 1 == 1),
    }
}

/// `f32::clamp(v, −f32::MAX, f32::MAX)` lane by lane (no NaN arises).
#[cfg(all(feature = "simd", target_arch = "x86_64"))]
#[inline(always)]
fn clamp4(v3: pulp::x86::V3, v: core::arch::x86_64::__m128) -> core::arch::x86_64::__m128 {
    let sse = v3.sse;
    sse._mm_max_ps(
        sse._mm_min_ps(v, sse._mm_set1_ps(f32::MAX)),
        sse._mm_set1_ps(-f32::MAX),
    )
}

/// Axes of [`Ray32`](super::ray::Ray32)s, lane by lane
/// ([`Ray32::axes`](super::ray::Ray32::axes), [`axes4`]).
pub(super) struct Axes32<const L: usize> {
    pub(super) near: [f32; L],
    pub(super) far: [f32; L],
    pub(super) inv: [f32; L],
    pub(super) backward: [bool; L],
}
