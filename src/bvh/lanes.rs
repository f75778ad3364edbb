//! `N` lanes of `f32`, the operations the occlusion walk needs: one
//! instruction each where the processor has AVX2 (eight lanes in a `ymm`
//! register, four in an `xmm`, through `pulp`'s safe intrinsics: no
//! `unsafe` of ours), a loop over an array elsewhere ([`Portable`]).
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
    /// The lanes as an array.
    fn store(self, a: Self::F) -> [f32; N];
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
    #[inline(always)]
    fn store(self, a: [f32; N]) -> [f32; N] {
        a
    }
}

#[cfg(all(feature = "simd", target_arch = "x86_64"))]
mod avx {
    use super::Lanes;
    use core::arch::x86_64::{__m128, __m256, _CMP_LE_OQ, _CMP_LT_OQ};
    use pulp::x86::V3;

    /// Eight lanes in a `ymm` register.
    #[derive(Clone, Copy, Debug)]
    pub(in super::super) struct Avx8(pub(in super::super) V3);

    /// Four lanes in an `xmm` register.
    #[derive(Clone, Copy, Debug)]
    pub(in super::super) struct Sse4(pub(in super::super) V3);

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
        #[inline(always)]
        fn add(self, a: __m256, b: __m256) -> __m256 {
            self.0.avx._mm256_add_ps(a, b)
        }
        #[inline(always)]
        fn sub(self, a: __m256, b: __m256) -> __m256 {
            self.0.avx._mm256_sub_ps(a, b)
        }
        #[inline(always)]
        fn mul(self, a: __m256, b: __m256) -> __m256 {
            self.0.avx._mm256_mul_ps(a, b)
        }
        #[inline(always)]
        fn max(self, a: __m256, b: __m256) -> __m256 {
            self.0.avx._mm256_max_ps(a, b)
        }
        #[inline(always)]
        fn min(self, a: __m256, b: __m256) -> __m256 {
            self.0.avx._mm256_min_ps(a, b)
        }
        #[inline(always)]
        fn le(self, a: __m256, b: __m256) -> u32 {
            let m = self.0.avx._mm256_cmp_ps::<_CMP_LE_OQ>(a, b);
            self.0.avx._mm256_movemask_ps(m) as u32
        }
        #[inline(always)]
        fn lt(self, a: __m256, b: __m256) -> u32 {
            let m = self.0.avx._mm256_cmp_ps::<_CMP_LT_OQ>(a, b);
            self.0.avx._mm256_movemask_ps(m) as u32
        }
        #[inline(always)]
        fn store(self, a: __m256) -> [f32; 8] {
            pulp::cast(a)
        }
    }

    impl Lanes<4> for Sse4 {
        type F = __m128;
        #[inline(always)]
        fn load(self, a: &[f32; 4]) -> __m128 {
            pulp::cast(*a)
        }
        #[inline(always)]
        fn splat(self, x: f32) -> __m128 {
            self.0.sse._mm_set1_ps(x)
        }
        #[inline(always)]
        fn add(self, a: __m128, b: __m128) -> __m128 {
            self.0.sse._mm_add_ps(a, b)
        }
        #[inline(always)]
        fn sub(self, a: __m128, b: __m128) -> __m128 {
            self.0.sse._mm_sub_ps(a, b)
        }
        #[inline(always)]
        fn mul(self, a: __m128, b: __m128) -> __m128 {
            self.0.sse._mm_mul_ps(a, b)
        }
        #[inline(always)]
        fn max(self, a: __m128, b: __m128) -> __m128 {
            self.0.sse._mm_max_ps(a, b)
        }
        #[inline(always)]
        fn min(self, a: __m128, b: __m128) -> __m128 {
            self.0.sse._mm_min_ps(a, b)
        }
        #[inline(always)]
        fn le(self, a: __m128, b: __m128) -> u32 {
            let m = self.0.avx._mm_cmp_ps::<_CMP_LE_OQ>(a, b);
            self.0.sse._mm_movemask_ps(m) as u32
        }
        #[inline(always)]
        fn lt(self, a: __m128, b: __m128) -> u32 {
            let m = self.0.avx._mm_cmp_ps::<_CMP_LT_OQ>(a, b);
            self.0.sse._mm_movemask_ps(m) as u32
        }
        #[inline(always)]
        fn store(self, a: __m128) -> [f32; 4] {
            pulp::cast(a)
        }
    }
}

#[cfg(all(feature = "simd", target_arch = "x86_64"))]
pub(super) use avx::{Avx8, Sse4};
