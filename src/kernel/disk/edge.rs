//! What the disk kernels share: each precision's safe range, the accurate
//! cross product and the plain dot product, exact powers of two, and the
//! batched kernels' frame (a branch-free pass, then the one-edge kernel
//! for the edges it leaves).

use crate::kernel::angle::AngleFloat;
use crate::kernel::eft::{two_prod, two_prod_fma};
use crate::kernel::float::{Float, Vector2};
use crate::kernel::lanes::{self, Real};

/// The disk kernels' constants of one precision.
pub(super) trait DiskFloat: AngleFloat {
    /// With the radius at least `SAFE_LO` and every magnitude at most
    /// `SAFE_HI`, every intermediate product (up to the fourth power of a
    /// coordinate, and `(|p| r)²` with a cancellation margin) stays in the
    /// normal range.
    const SAFE_LO: Self;
    const SAFE_HI: Self;
    /// `1 / (n (n + 1))` for `n = 4, 6, …, 18`: the ratios of successive
    /// terms of the sine series, `θ^(n+1)/(n+1)! = θ^(n−1)/(n−1)! ·
    /// θ²/(n (n + 1))`, each rounded once in this precision.
    const SINE_RATIOS: [Self; 8];
}

/// [`DiskFloat::SINE_RATIOS`] of both precisions.
const SINE_RATIOS: ([f64; 8], [f32; 8]) = {
    let mut c = ([0.0; 8], [0.0; 8]);
    let mut j = 0;
    while j < 8 {
        let n = (2 * j + 4) as f64;
        c.0[j] = 1.0 / (n * (n + 1.0));
        let n = (2 * j + 4) as f32;
        c.1[j] = 1.0 / (n * (n + 1.0));
        j += 1;
    }
    c
};

impl DiskFloat for f64 {
    const SAFE_LO: f64 = 1.0e-60;
    const SAFE_HI: f64 = 1.0e60;
    const SINE_RATIOS: [f64; 8] = SINE_RATIOS.0;
}

impl DiskFloat for f32 {
    const SAFE_LO: f32 = 1.0e-6;
    const SAFE_HI: f32 = 1.0e6;
    const SINE_RATIOS: [f32; 8] = SINE_RATIOS.1;
}

/// Edges evaluated side by side by the batched kernels: four, one AVX2
/// register of `f64` (of `f32`, half of one: eight `f32` lanes measured
/// twice as slow, the compiler's eight-wide code spilling and converting
/// masks).
pub(super) const LANES: usize = 4;

/// The 2D cross product `p × q`, accurate to about one ulp even under
/// cancellation (both products exactly, then their difference), and
/// exactly antisymmetric: `cross(q, p)` is `−cross(p, q)` bit for bit.
#[inline(always)]
pub(super) fn cross<T: Float>(p: T::V2, q: T::V2) -> T {
    cross_by::<T, T, false>(p.x(), p.y(), q.x(), q.y())
}

/// [`cross`] of `(px, py)` and `(qx, qy)`, on one value or on lanes, its
/// exact products by a fused multiply-add when `FMA` (for code compiled
/// where a hardware FMA is enabled): the same bits.
#[inline(always)]
pub(super) fn cross_by<T: Float, R: Real<Scalar = T>, const FMA: bool>(
    px: R,
    py: R,
    qx: R,
    qy: R,
) -> R {
    let prod = if FMA { two_prod_fma } else { two_prod };
    let (s, se) = prod(px, qy);
    let (t, te) = prod(py, qx);
    (s - t) + (se - te)
}

/// The dot product `p · q`, plainly rounded: its absolute error
/// `ε |p| |q|` costs the angles and positions it feeds no more than their
/// own rounding.
#[inline(always)]
pub(super) fn dot<T: Float>(p: T::V2, q: T::V2) -> T {
    dot_of(p.x(), p.y(), q.x(), q.y())
}

/// [`dot`] of `(px, py)` and `(qx, qy)`, on one value or on lanes.
#[inline(always)]
pub(super) fn dot_of<R: Real>(px: R, py: R, qx: R, qy: R) -> R {
    px * qx + py * qy
}

/// `2^e` for `|e|` below the exponent range, exactly.
#[inline]
pub(super) fn pow2<T: Float>(e: i32) -> T {
    T::of(2.0).powi(e)
}

/// The exponent `e` for which `x · 2^-e` lies near 1, clamped so that
/// `2^-e` is finite.
#[inline]
pub(super) fn rescale_exponent<T: Float>(x: T) -> i32 {
    let limit = T::MAX_EXP - 2;
    x.log2().floor().to_i32().clamp(-limit, limit)
}

/// `out` replaced by one value per input: `branch_free(fma, inputs, out)`
/// (compiled for AVX2 and FMA where the processor has them, `fma` saying
/// whether it is; the answer whether it left any entry `NaN`), then `one`
/// for each entry so left — which the one-input kernels never return.
#[inline(always)]
pub(super) fn batch<T: Float, E: Copy>(
    inputs: &[E],
    out: &mut Vec<T>,
    branch_free: impl FnOnce(bool, &[E], &mut [T]) -> bool,
    one: impl Fn(E) -> T,
) {
    // Every entry is overwritten: only new ones are zeroed first.
    out.truncate(inputs.len());
    out.resize(inputs.len(), T::of(0.0));
    let marked = lanes::vectorized(
        #[inline(always)]
        |fma| branch_free(fma, inputs, out),
    );
    if marked {
        for (o, &e) in out.iter_mut().zip(inputs) {
            if o.is_nan() {
                *o = one(e);
            }
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::Float;

    /// Uniform values in `[0, 1)` from a 64-bit LCG seeded with `state`.
    pub(in crate::kernel::disk) fn uniform<T: Float>(mut state: u64) -> impl FnMut() -> T {
        move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            T::from_u64(state >> 11) / T::from_u64(1u64 << 53)
        }
    }
}
