//! Johnson et al.'s signed circle-segment occlusion (SISM eq. 3), one edge
//! at a time ([`circle_segment_occlusion`]) and many side by side
//! ([`circle_segment_occlusions`]). The contracts are on the public `f64`
//! forms ([`super::f64`]).

use super::edge::{batch, pow2, rescale_exponent, DiskFloat, LANES};
use crate::kernel::angle;
use crate::kernel::float::Float;
use crate::kernel::lanes::{Lanes, Real};

/// `θ − sin θ` for `0 ≤ θ < 1`, with full relative accuracy, from the
/// Taylor series `θ³/3! − θ⁵/5! + …` in nested form,
/// `θ³/6 · (1 − θ²/(4·5) (1 − θ²/(6·7) (1 − …)))`, up to `θ¹⁹/19!`; the
/// first omitted term, `θ²¹/21!`, is below 2⁻⁶⁵ of the sum on that
/// interval. (No libm `sin`: the result is the same on every platform.)
#[inline(always)]
fn theta_minus_sin<T: DiskFloat, R: Real<Scalar = T>>(theta: R) -> R {
    let one = R::splat(T::of(1.0));
    let x2 = theta * theta;
    let mut s = one;
    for &c in T::SINE_RATIOS.iter().rev() {
        s = one - x2 * R::splat(c) * s;
    }
    theta * x2 / R::splat(T::of(6.0)) * s
}

/// [`f64::circle_segment_occlusion`](super::f64::circle_segment_occlusion)
/// in either precision.
pub(super) fn circle_segment_occlusion<T: DiskFloat>(d: T, w0: T, w1: T) -> T {
    let k = T::of;
    if !(d.is_finite() && w0.is_finite() && w1.is_finite()) {
        return k(0.0);
    }
    let sign = if d.is_sign_negative() {
        k(-1.0)
    } else {
        k(1.0)
    };
    let d = d.abs();
    if d >= k(1.0) {
        return k(0.0);
    }
    // Clip to the chord: the endpoints' positions are −w0 and +w1.
    let s = ((k(1.0) - d) * (k(1.0) + d)).sqrt();
    let w0 = w0.clamp(-s, s);
    let w1 = w1.clamp(-s, s);
    let length = w0 + w1;
    if length == k(0.0) {
        return k(0.0);
    }
    if d == k(0.0) {
        // The limit d → 0⁺: each endpoint's angle from the perpendicular is
        // ±π/2 (0 at the centre itself).
        let half_turns = |w: T| {
            if w == k(0.0) {
                k(0.0)
            } else {
                k(0.5) * w.signum()
            }
        };
        return sign * (half_turns(w0) + half_turns(w1)) * k(0.5);
    }
    // The complex product (d + i·w1)(d + i·w0) has argument θ. θ is
    // scale-invariant: tiny inputs are scaled up (exactly) first, so that
    // its parts do not underflow.
    let c = d * length;
    let big = d.max(w0.abs()).max(w1.abs());
    let scale = if big < T::SAFE_LO {
        pow2::<T>(-rescale_exponent(big))
    } else {
        k(1.0)
    };
    let (dk, w0k, w1k) = (d * scale, w0 * scale, w1 * scale);
    let theta = if dk >= T::SAFE_LO {
        angle::atan2(dk * (w0k + w1k), dk * dk - w0k * w1k)
    } else {
        // d far below the endpoints' distances: the products would
        // underflow, so add the endpoints' angles instead.
        angle::atan2(w1k, dk) + angle::atan2(w0k, dk)
    };
    let abs_theta = theta.abs();
    // θ − ρ sin θ with c = ρ sin θ: split as (θ − sin θ) + (1 − ρ) sin θ when
    // θ is small and both terms are small; directly otherwise.
    let value = if abs_theta < k(1.0) {
        let (rho, one_minus_rho2) = rho_of(d, w0, w1, s);
        // c = ρ sin θ; ρ underflows only for endpoints at the centre.
        let sin_theta = if rho > k(0.0) {
            c.abs() / rho
        } else {
            abs_theta.sin()
        };
        thin_value(theta, sin_theta, rho, one_minus_rho2)
    } else {
        theta - c
    };
    sign * value / (k(2.0) * T::PI)
}

/// `ρ = |p0||p1|` for the clipped endpoints `p0 = (d, −w0)`, `p1 = (d, w1)`,
/// and `1 − ρ²` without cancellation near the circle (`s` the half chord).
#[inline(always)]
fn rho_of<T: Float, R: Real<Scalar = T>>(d: R, w0: R, w1: R, s: R) -> (R, R) {
    let r0 = d * d + w0 * w0;
    let r1 = d * d + w1 * w1;
    // 1 − ρ² = a0 + a1 − a0 a1, with a = 1 − |p|² = s² − w² = (s − w)(s + w):
    // no cancellation near the circle.
    let a0 = (s - w0.abs()) * (s + w0.abs());
    let a1 = (s - w1.abs()) * (s + w1.abs());
    let one_minus_rho2 = (a0 + a1 - a0 * a1).max(R::splat(T::of(0.0)));
    ((r0 * r1).sqrt(), one_minus_rho2)
}

/// `θ − ρ sin θ` for `|θ| < 1`, as `(θ − sin θ) + (1 − ρ) sin θ`.
#[inline(always)]
fn thin_value<T: DiskFloat, R: Real<Scalar = T>>(
    theta: R,
    sin_theta: R,
    rho: R,
    one_minus_rho2: R,
) -> R {
    let rest = one_minus_rho2 / (R::splat(T::of(1.0)) + rho) * sin_theta;
    (theta_minus_sin(theta.abs()) + rest).copysign(theta)
}

/// [`f64::circle_segment_occlusions`](super::f64::circle_segment_occlusions)
/// in either precision.
pub(super) fn circle_segment_occlusions<T: DiskFloat>(edges: &[(T, T, T)], out: &mut Vec<T>)
where
    Lanes<T, LANES>: Real<Scalar = T>,
{
    batch(
        edges,
        out,
        #[inline(always)]
        |_, edges, out| occlusions_branch_free(edges, out),
        |(d, w0, w1)| circle_segment_occlusion(d, w0, w1),
    );
}

/// [`circle_segment_occlusions`]' loop, [`LANES`] edges at a time (the last
/// group padded with a regular edge); `out` as long as `edges`; the answer
/// is whether any entry was left `NaN` for the scalar path.
#[inline(always)]
fn occlusions_branch_free<T: DiskFloat>(edges: &[(T, T, T)], out: &mut [T]) -> bool
where
    Lanes<T, LANES>: Real<Scalar = T>,
{
    #[inline(always)]
    fn group<T: DiskFloat>(e: &[(T, T, T)]) -> Lanes<T, LANES>
    where
        Lanes<T, LANES>: Real<Scalar = T>,
    {
        let lane = |pick: fn(&(T, T, T)) -> T| {
            Lanes(core::array::from_fn(|i| e.get(i).map_or(T::of(0.5), pick)))
        };
        occlusion_lanes::<T, Lanes<T, LANES>>(lane(|e| e.0), lane(|e| e.1), lane(|e| e.2))
    }
    let mut marked = <Lanes<T, LANES> as Real>::Mask::default();
    for (o, e) in out.chunks_mut(LANES).zip(edges.chunks(LANES)) {
        let values = group(e);
        marked = marked | !values.eq(values);
        o.copy_from_slice(&values.0[..o.len()]);
    }
    Lanes::<T, LANES>::any(marked)
}

/// [`circle_segment_occlusion`] side by side, as straight-line code; `NaN`
/// for an edge the scalar path must take (see
/// [`circle_segment_occlusions`]).
#[inline(always)]
fn occlusion_lanes<T: DiskFloat, R: Real<Scalar = T>>(d: R, w0: R, w1: R) -> R {
    let k = |x: f64| R::splat(T::of(x));
    // Finite: `x − x` is 0 exactly then.
    #[allow(clippy::eq_op)] // `x − x`: deliberate, see above.
    let finite = (d - d).eq(k(0.0)) & (w0 - w0).eq(k(0.0)) & (w1 - w1).eq(k(0.0));
    let sign = R::select(d.is_sign_negative(), k(-1.0), k(1.0));
    let d = d.abs();
    let s = ((k(1.0) - d) * (k(1.0) + d)).sqrt();
    // `clamp(−s, s)`, the order of `f64::clamp` (`w` itself unless beyond a
    // bound).
    let clamp = |w: R| R::select(w.lt(-s), -s, R::select(w.gt(s), s, w));
    let (w0, w1) = (clamp(w0), clamp(w1));
    let length = w0 + w1;
    // `atan2(c, d² − w0 w1)`: `c = d (w0 + w1)` is its first part.
    let c = d * length;
    let x = d * d - w0 * w1;
    let (num, den, swap, regular) = angle::reduce(c, x);
    let theta = angle::core(num, den, swap, x, c);
    let (rho, one_minus_rho2) = rho_of(d, w0, w1, s);
    let thin = thin_value(theta, c.abs() / rho, rho, one_minus_rho2);
    let value = R::select(theta.abs().lt(k(1.0)), thin, theta - c);
    // `d = 0`: each endpoint's angle from the perpendicular is ±π/2 (0 at
    // the centre itself).
    let half_turns = |w: R| R::select(w.eq(k(0.0)), k(0.0), k(0.5) * k(1.0).copysign(w));
    let at_centre = d.eq(k(0.0));
    let value = R::select(
        at_centre,
        sign * (half_turns(w0) + half_turns(w1)) * k(0.5),
        sign * value / R::splat(T::of(2.0) * T::PI),
    );
    // In range: `|d| < 1`, a chord of nonzero length, and `d = 0` or
    // `d ≥ SAFE_LO` (no rescaling, one `atan2`) with a regular angle and
    // `ρ > 0`.
    let valid = finite
        & d.lt(k(1.0))
        & !length.eq(k(0.0))
        & (at_centre | (d.ge(R::splat(T::SAFE_LO)) & regular & rho.gt(k(0.0))));
    R::select(valid, value, R::splat(T::NAN))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::disk::edge::tests::uniform;

    /// The branch-free occlusion, compiled for the build's target (the form
    /// a processor without AVX2 runs), gives `circle_segment_occlusion`'s
    /// bits wherever it does not leave the edge to the scalar path, and
    /// leaves exactly the edges outside its range (`tests/disk.rs` checks
    /// the public entry).
    fn branch_free_occlusion_is_the_scalar_kernel<T: DiskFloat>()
    where
        Lanes<T, LANES>: Real<Scalar = T>,
    {
        let k = T::of;
        let mut unit = uniform::<T>(0x2545_f491_4f6c_dd1d);
        let mut edges: Vec<(T, T, T)> = (0..4001)
            .map(|i| {
                // 0.3, 0.9, 0.999 and 0.001, each rounded once.
                let (num, den) = [(3.0, 10.0), (9.0, 10.0), (999.0, 1e3), (1.0, 1e3)][i % 4];
                let d = k(num) / k(den) * (k(2.0) * unit() - k(1.0));
                let w = k([0.5, 1.0, 3.0][i % 3]);
                let w0 = w * (k(2.0) * unit() - k(1.0));
                (d, w0, w * (k(2.0) * unit() - k(1.0)))
            })
            .collect();
        edges.extend([
            (k(0.0), k(1.0), k(1.0)),
            (k(-0.0), k(0.0), k(1.0)),
            (k(0.0), k(-0.5), k(0.0)),
            (T::NAN, k(0.5), k(0.5)),
            (k(0.5), k(0.25), k(-0.25)),
            (k(1.0), k(0.0), k(0.0)),
            (T::SAFE_LO / k(2.0), k(0.5), k(0.5)),
        ]);
        let mut out = vec![k(0.0); edges.len()];
        assert!(occlusions_branch_free(&edges, &mut out));
        let mut vector = 0;
        for (&(d, w0, w1), &got) in edges.iter().zip(&out) {
            let want = circle_segment_occlusion(d, w0, w1);
            let s = ((k(1.0) - d.abs()) * (k(1.0) + d.abs())).max(k(0.0)).sqrt();
            let length = w0.clamp(-s, s) + w1.clamp(-s, s);
            let in_range = d.is_finite()
                && (d == k(0.0) || (d.abs() >= T::SAFE_LO && d.abs() < k(1.0)))
                && length != k(0.0);
            assert_eq!(got.is_nan(), !in_range, "d={d} w0={w0} w1={w1}");
            if !got.is_nan() {
                assert_eq!(got.bits(), want.bits(), "d={d} w0={w0} w1={w1}");
                vector += 1;
            }
        }
        assert!(vector >= 3000, "{vector} edges on the vector path");
    }

    test_in_both_precisions!(branch_free_occlusion_is_the_scalar_kernel);
}
