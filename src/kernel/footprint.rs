//! The light as one receiver sees it, drawn on the light image plane: the
//! geometry every method that projects from the light's centre shares.
//!
//! In the light frame (origin at the light's centre, `+z` toward the
//! scene), a point `(x, y, z)`, `z > 0`, projects to `(x/z, y/z)` on the
//! image plane `z = 1` ([`f64::project`]). A light of radius `r` in the
//! plane `z = 0`, seen from a receiver `p` at depth `z_p` through the depth
//! `z_q` of an occluder point, covers the disk of radius
//!
//! `R = r·(1/z_q − 1/z_p)` ([`f64::radius`])
//!
//! around `p`'s projection — the receiver's *footprint* at that depth
//! (Johnson et al. 2009, §2.2; SSOC's distortion is `2R`). An occluder
//! point at depth `z_q` projecting to `π(q)` hides the light point
//! `r·(π(q) − π(p))/R`: dividing by `R` maps an occluder's projected edge
//! into the *unit footprint* ([`f64::map_edge`]), where the light is the
//! unit disk and the disk-occlusion kernels apply.
//!
//! Also here: the near- and far-depth clips of a light-frame segment
//! ([`f64::clip_near`], [`f64::clip_far`]) and the rounding bound
//! `γ(n) = nu/(1 − nu)` ([`f64::gamma`], Higham's notation) every error
//! analysis of the crate uses. Everything is in [`f32`](mod@f32) and
//! [`f64`](mod@f64) from one body.

use crate::kernel::float::{both_precisions, Float, Vector2, Vector3};

/// [`f64::gamma`] in either precision (inlined, so that a constant `n`
/// folds to a constant).
#[inline(always)]
pub(crate) fn gamma<T: Float>(n: u32) -> T {
    let nu = T::from_i64(i64::from(n)) * (T::EPSILON / T::of(2.0));
    nu / (T::of(1.0) - nu)
}

/// [`f64::radius`] in either precision.
#[inline]
pub(crate) fn radius<T: Float>(light_radius: T, z_occluder: T, z_receiver: T) -> T {
    let (r, zq, zp) = (light_radius, z_occluder, z_receiver);
    let (zero, one) = (T::of(0.0), T::of(1.0));
    // Comparisons with NaN are false: every NaN lands here.
    if !(r > zero && zq > zero && zp > zq && zq < T::INFINITY) {
        return zero;
    }
    let behind = if zp <= T::of(2.0) * zq {
        // Exact difference (Sterbenz).
        (zp - zq) / zp
    } else {
        // z_q/z_p < 1/2: no cancellation; z_p = +∞ gives 1.
        one - zq / zp
    };
    (r * behind) / zq
}

/// [`f64::reach_depth`] in either precision.
#[inline]
pub(crate) fn reach_depth<T: Float>(light_radius: T, z_occluder: T, reach: T) -> T {
    if reach <= T::of(0.0) {
        return z_occluder;
    }
    let inv = T::of(1.0) / z_occluder - reach / light_radius;
    if inv > T::of(0.0) {
        T::of(1.0) / inv
    } else {
        T::INFINITY
    }
}

/// [`f64::project`] in either precision.
#[inline]
pub(crate) fn project<T: Float>(q: T::V3) -> T::V2 {
    T::V2::new(q.x() / q.z(), q.y() / q.z())
}

/// The point of segment `[a, b]` at depth `z` (exactly `z`), for `z`
/// strictly between the ends' depths.
#[inline]
fn cut<T: Float>(a: T::V3, b: T::V3, z: T) -> T::V3 {
    // From the end nearer the plane (ties in lexicographic order): the same
    // bits whichever way the segment runs, and `t ≤ ½`, so that a far end
    // does not round `t` to 1 and swamp the cut.
    let key = |v: T::V3| [v.x(), v.y(), v.z()];
    let (a, b) = match (a.z() - z).abs().total_cmp(&(b.z() - z).abs()) {
        core::cmp::Ordering::Less => (a, b),
        core::cmp::Ordering::Greater => (b, a),
        core::cmp::Ordering::Equal if key(a) <= key(b) => (a, b),
        core::cmp::Ordering::Equal => (b, a),
    };
    let t = (z - a.z()) / (b.z() - a.z());
    let c = a + (b - a) * t;
    c.with_z(z)
}

/// [`f64::clip_near`] in either precision.
#[inline]
pub(crate) fn clip_near<T: Float>(a: T::V3, b: T::V3, near: T) -> Option<(T::V3, T::V3)> {
    match (a.z() >= near, b.z() >= near) {
        (true, true) => Some((a, b)),
        (false, false) => None,
        (true, false) => Some((a, cut(a, b, near))),
        (false, true) => Some((cut(a, b, near), b)),
    }
}

/// [`f64::clip_far`] in either precision.
#[inline]
pub(crate) fn clip_far<T: Float>(a: T::V3, b: T::V3, far: T) -> Option<(T::V3, T::V3)> {
    match (a.z() < far, b.z() < far) {
        (true, true) => Some((a, b)),
        (false, false) => None,
        (true, false) => Some((a, cut(a, b, far))),
        (false, true) => Some((cut(a, b, far), b)),
    }
}

/// [`f64::map_edge`] in either precision; `hair` is `1 − 10⁻⁶` rounded to
/// the precision.
pub(crate) fn map_edge<T: Float>(
    (a, b): (T::V2, T::V2),
    (la, lb): (T::V3, T::V3),
    s: T::V2,
    z_p: T,
    r: T,
    hair: T,
) -> Option<(T::V2, T::V2)> {
    let (ca, cb) = clip_far::<T>(la, lb, z_p * hair)?;
    let pa = if ca == la { a } else { project::<T>(ca) };
    let pb = if cb == lb { b } else { project::<T>(cb) };
    let ra = radius(r, ca.z(), z_p);
    let rb = radius(r, cb.z(), z_p);
    if !(ra > T::of(0.0) && rb > T::of(0.0)) {
        return None;
    }
    Some(((pa - s) / ra, (pb - s) / rb))
}

/// The public items of one precision `($T, $V2, $V3)`, declared once
/// with their contracts, each forwarding to the generic body above;
/// `both_precisions!` makes the modules `f64` and `f32` of them.
macro_rules! precision {
    ($T:ident, $V2:ident, $V3:ident) => {
        use glam::{$V2, $V3};

        /// `γ(n) = n·u/(1 − n·u)`, `u = ε/2` the unit roundoff: `n` rounded
        /// operations (additions, products, quotients) multiply a result by
        /// a factor in `[1 − γ(n), 1 + γ(n)]` (Higham, *Accuracy and
        /// Stability of Numerical Algorithms*, §3.1). Valid for `n·u < 1`.
        #[must_use]
        pub const fn gamma(n: u32) -> $T {
            let nu = n as $T * ($T::EPSILON / 2.0);
            nu / (1.0 - nu)
        }

        /// The footprint radius `R = r·(1/z_q − 1/z_p)` of a light of
        /// radius `light_radius` seen from a receiver at depth `z_receiver`
        /// through depth `z_occluder`, in light-image-plane units (module
        /// docs).
        ///
        /// **Domain**: `r ≥ 0`, `0 < z_q < z_p ≤ +∞`. `z_p = +∞` gives the
        /// limit `r/z_q`.
        ///
        /// **Edge of the domain**: a receiver not behind the occluder
        /// (`z_p ≤ z_q`) sees no footprint there: `0`; so does any input
        /// outside the domain (`r ≤ 0`, `z_q ≤ 0`, `z_q = +∞`, a NaN).
        /// Never NaN, never negative; `+∞` only when the true value
        /// overflows (or `r = +∞`).
        ///
        /// **Numerics**: the difference of reciprocals cancels as
        /// `z_p → z_q`; it is evaluated as `(r·w)/z_q` with `w = 1 −
        /// z_q/z_p` formed as `(z_p − z_q)/z_p` for `z_p ≤ 2z_q`, where the
        /// difference is exact (Sterbenz), and as `1 − z_q/z_p` beyond,
        /// where nothing cancels. No product `z_q·z_p` can overflow. Each
        /// step is correctly rounded and monotone, so `R` never decreases
        /// with `z_p`.
        ///
        /// **Accuracy**: relative error at most `4u` (4 ulp) when the result
        /// is a normal number; measured through [`max_distortion`], which is
        /// exactly `2R` (`docs/accuracy/kernels.md`: max 2.54 ulp in `f64`,
        /// 2.66 ulp in `f32`).
        ///
        /// [`max_distortion`]: crate::kernel::distortion::f64::max_distortion
        #[must_use]
        #[inline]
        pub fn radius(light_radius: $T, z_occluder: $T, z_receiver: $T) -> $T {
            super::radius(light_radius, z_occluder, z_receiver)
        }

        /// The depth at which a light of radius `light_radius`, seen
        /// through depth `z_occluder`, has a footprint of radius `reach`:
        /// the `z_p` solving `r·(1/z_q − 1/z_p) = reach`, i.e.
        /// `1/z_p = 1/z_q − reach/r`; receivers shallower than it have a
        /// smaller footprint. `+∞` when no depth reaches that far (`reach ≥
        /// r/z_q`), `z_q` for `reach ≤ 0`; NaN input gives `+∞` (no bound).
        ///
        /// **Accuracy**: a few roundings (relative `γ(4)` on `1/z_p` away
        /// from cancellation): callers widen it by a relative margin.
        #[must_use]
        #[inline]
        pub fn reach_depth(light_radius: $T, z_occluder: $T, reach: $T) -> $T {
            super::reach_depth(light_radius, z_occluder, reach)
        }

        /// The light-image-plane projection `(x/z, y/z)` of a light-frame
        /// point. Not finite for `z = 0` or non-finite input; callers keep
        /// `z > 0` (see [`clip_near`]).
        #[must_use]
        #[inline]
        pub fn project(q: $V3) -> $V2 {
            super::project::<$T>(q)
        }

        /// The part of the light-frame segment `[a, b]` at depth `z ≥ near`
        /// (in front of a near plane), its order kept; `None` when none is.
        /// An end already in front is returned bit for bit, and the cut is
        /// interpolated from the end nearer the plane whichever way the
        /// segment runs, so an edge shared by two triangles is cut at the
        /// same point from both, and a far end does not swamp it.
        #[must_use]
        #[inline]
        pub fn clip_near(a: $V3, b: $V3, near: $T) -> Option<($V3, $V3)> {
            super::clip_near::<$T>(a, b, near)
        }

        /// The part of `[a, b]` at depth `z < far` (in front of a receiver
        /// at depth `far`), its order kept; `None` when none is. Ends
        /// already in front are returned bit for bit.
        #[must_use]
        #[inline]
        pub fn clip_far(a: $V3, b: $V3, far: $T) -> Option<($V3, $V3)> {
            super::clip_far::<$T>(a, b, far)
        }

        /// An occluder edge mapped into the unit footprint of a receiver:
        /// the edge's light-frame ends `la`, `lb` (depths `> 0`) with their
        /// projections `a`, `b`; the receiver at image point `s`, depth
        /// `z_p`; the light's radius `r`. The edge is first clipped to the
        /// part in front of the receiver (depth below `z_p·(1 − 10⁻⁶)`, a
        /// relative hair that keeps the radii away from the `0/0` at the
        /// receiver's own depth); each end is then mapped with its own
        /// depth's [`radius`], `(a − s)/R_a`, so that a chain of edges
        /// stays closed. `None` when no part is in front or a radius is
        /// not positive.
        ///
        /// The image of a straight edge is straight only when its ends
        /// share a depth; a sloped edge's mapped chord is the method's
        /// approximation (SISM §5.1's single point of projection).
        #[must_use]
        pub fn map_edge(
            a: $V2,
            b: $V2,
            la: $V3,
            lb: $V3,
            s: $V2,
            z_p: $T,
            r: $T,
        ) -> Option<($V2, $V2)> {
            super::map_edge::<$T>((a, b), (la, lb), s, z_p, r, 1.0 - 1e-6)
        }
    };
}

both_precisions!(precision);
