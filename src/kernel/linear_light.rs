//! OESS: the visible part of a segment light past one occluding edge, and
//! its endpoint weights.
//!
//! Occluding Edges Soft Shadows (Reimann, Dreier, GRAPP 2016, substep 4.3)
//! lights a fragment `F` with a linear light `[L, R]` sampled only at its two
//! endpoints. In the plane through `L`, `R` and `F`, the occluder's
//! silhouette shows as one point `E`, the *occluding edge*; the line from `F`
//! through `E` (the *shadow line*) meets the light's line at `P`, and the
//! part of the light on the occluder's side of `P` is hidden. With `s` the
//! parameter along `L → R` (`L` at 0, `R` at 1) and `P = L + s_P (R − L)`:
//!
//! - the visible fraction `i` is `s_P` when the occluder lies toward `R`
//!   (visible part `[0, s_P]`, the paper's figure 5), `1 − s_P` when it lies
//!   toward `L` (visible part `[s_P, 1]`), clamped to `[0, 1]`;
//! - for a light whose emission falls off linearly between the two samples,
//!   `w_R(s) = s`, `w_L(s) = 1 − s` (the paper's function `f`, figure 6), the
//!   weights of the two endpoint samples are the areas
//!   `A = ∫ s ds` (right sample) and `B = ∫ (1 − s) ds` (left sample) over the
//!   visible part; `A + B = i`.
//!
//! [`f64::visible_part`] returns all of these as a [`f64::VisiblePart`];
//! [`f64::visible_part_3d`] takes 3D points and reduces them to that plane.
//!
//! ## The stable construction
//!
//! Every decision is made exactly, with [`orient2d`] and one [`orient3d`]
//! (the sign of `(R − L) × (E − F)`, lifted to 3D): whether `E` occludes at
//! all, and whether `P` lies before `L`, beyond `R`, or inside. Only inside
//! is anything computed: with `a = (E − F) × (L − F)` and
//! `b = (E − F) × (R − F)` (twice the signed distances of `L` and `R` from the
//! shadow line, times `|E − F|`), which then have opposite signs,
//!
//! `s_P = |a| / (|a| + |b|)`,  `1 − s_P = |b| / (|a| + |b|)`,
//!
//! a ratio of like-signed terms: no cancellation, both complements accurate,
//! `s_P ∈ [0, 1]` by construction. `a` and `b` are compensated
//! difference-of-products cross products (exact products and error terms,
//! within `2u` relative) of rounded difference vectors (which move them by
//! at most `2u·|E − F||L − F|`), each vector rescaled by an exact power of
//! two so no magnitude overflows or underflows. Error bound (first
//! order, `u = 2⁻⁵³`, `f32`: `2⁻²⁴`):
//!
//! `|ŝ − s_P| ≤ s_P (1 − s_P) (2u/sin θ_L + 2u/sin θ_R + 4u) + 2u·s_P`
//!
//! (and the same for `1 − s_P`), with `θ_L`, `θ_R` the angles at `F` between
//! the shadow line and `FL`, `FR`: the kernel loses accuracy only where the
//! answer itself is ill-conditioned (the shadow line grazing the direction of
//! an endpoint, while `P` stays away from it). `tests/linear_light.rs`
//! checks the rigorous version of this bound against an exact
//! (floating-point expansion) reference over the stiff generator: the
//! largest error is 0.79 of the bound (`f64`) and 0.77 (`f32`); on
//! well-conditioned configurations the error is at most `6.7e-16`
//! (`f64`) and `3.2e-7` (`f32`). The weights follow with
//! `|∂w/∂s| ≤ 1` and two more roundings.
//!
//! ## Conventions (total answers, never NaN)
//!
//! The occluder blocks light only when `E` lies between `F` and the light's
//! line: on `F`'s side of that line (or on it) and strictly closer to it than
//! `F`. Otherwise the answer is *fully visible* ([`f64::VisiblePart::FULL`]):
//! - `E` beyond the light's line (the occluder is behind the light), or
//!   farther from it than `F` (behind the fragment);
//! - the shadow line parallel to the light (`E` as far from the light's line
//!   as `F`), including `E = F`;
//! - `F` on the light's line (the light is seen edge-on), `L = R` (no
//!   length), and any non-finite coordinate.
//!
//! `E` on the light's line occludes, with `P = E` (the limit of an edge
//! approaching the light). When `P` falls outside the segment the light is
//! wholly visible or wholly hidden, as the occluder side says: the visible
//! interval is clamped.
//!
//! Decisions are exact for coordinates in the domain of [`orient2d`]
//! (nonzero magnitudes in `[1e-140, 1e150]`, or zero). The one
//! [`orient3d`] lifts the points to heights `0` and `1`, so its products are
//! still products of two coordinate differences and the same domain holds.
//! Every finite `f32` input is inside it.
//!
//! ## The paper's form
//!
//! OESS eq. 1 writes `i = sin β · sin δ / (sin α · sin(π − δ − γ))`. The
//! figure that names the angles is lost; the reading consistent with the law
//! of sines is: in triangle `L R F`, `α` is the angle at `F`, `β` at `R`,
//! `γ` at `L`; `δ` is the angle at `F` between `FL` and `FP`. Then
//! `|LR| = |FL| sin α / sin β` (triangle `LRF`) and
//! `|LP| = |FL| sin δ / sin(π − δ − γ)` (triangle `LPF`, whose angle at `P`
//! is `π − δ − γ`), so `i = |LP| / |LR|`: the fraction from `L` to `P`, the
//! occluder-toward-`R` case. [`f64::law_of_sines_fraction`] evaluates it with
//! stable angles (`atan2(|cross|, dot)`); it agrees with the construction
//! above, but loses accuracy where a sine is taken near `π`: `α → π` (`F`
//! near the light segment), `β → π` or `γ → π` (`F` near the light's line
//! beyond an endpoint), `δ + γ → π` (the shadow line grazing the light).
//!
//! All kernels are in [`f32`](mod@f32) and [`f64`](mod@f64) from one body; the `f32` versions
//! compute in `f32` and decide exactly (the promotion to `f64` is exact).

use crate::kernel::angle::{self, AngleFloat};
use crate::kernel::eft::two_prod;
use crate::kernel::float::{both_precisions, Float, Vector2, Vector3};
use crate::kernel::predicate::{orient2d, orient3d, Sign};
use glam::DVec2;

/// On which side of the shadow line the occluder lies, named by the light
/// endpoint on that side: it hides the part of the light between `P` and
/// that endpoint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OccluderSide {
    /// The occluder hides `[L, P]`; the visible part is `[P, R]`.
    TowardL,
    /// The occluder hides `[P, R]`; the visible part is `[L, P]` (OESS
    /// figure 5: a fragment in the penumbra left of an occluder).
    TowardR,
}

impl OccluderSide {
    /// The other side.
    #[must_use]
    #[inline]
    pub fn flip(self) -> OccluderSide {
        match self {
            OccluderSide::TowardL => OccluderSide::TowardR,
            OccluderSide::TowardR => OccluderSide::TowardL,
        }
    }
}

/// Where the shadow line of an occluding `E` meets the light's line, decided
/// exactly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Crossing {
    /// `s_P ≤ 0`.
    BeforeL,
    /// `0 < s_P < 1`.
    Inside,
    /// `s_P ≥ 1`.
    BeyondR,
}

/// The exact sign of `(R − L) × (E − F)`.
///
/// It is the determinant `orient3d((L, 0), (R, 0), (F, 1), (E, 1))`: with
/// `d = (E, 1)`, the rows are `(L − E, −1)`, `(R − E, −1)`, `(F − E, 0)`, and
/// expanding along the last column gives
/// `(L − E) × (F − E) − (R − E) × (F − E) = (R − L) × (E − F)`.
#[inline]
fn cross_sign(l: DVec2, r: DVec2, f: DVec2, e: DVec2) -> Sign {
    orient3d(l.extend(0.0), r.extend(0.0), f.extend(1.0), e.extend(1.0))
}

/// Classify the configuration exactly: `None` when `E` does not occlude (see
/// the module docs), else where the shadow line meets the light's line.
///
/// With `c_X = (R − L) × (X − L)` (signed distance from the light's line) and
/// `D = (R − L) × (E − F)`, the shadow line is `F + t(E − F)` and
/// `t = −c_F/D`, `t − 1 = −c_E/D`; `E` occludes when `t ≥ 1`, i.e.
/// `sign D = −sign c_F` and `c_E` is zero or of the sign of `c_F`. The
/// crossing parameter is `s_P = a/(a − b)` with `a = orient2d(F, E, L)`,
/// `b = orient2d(F, E, R)` and `a − b = D`, so `s_P ≤ 0` iff
/// `sign a · sign D ≤ 0` and `s_P ≥ 1` iff `sign b · sign D ≥ 0`.
fn classify(l: DVec2, r: DVec2, f: DVec2, e: DVec2) -> Option<Crossing> {
    // Zero for F on the light's line, for L = R, and for non-finite input.
    let side_f = orient2d(l, r, f);
    if side_f == Sign::Zero {
        return None;
    }
    // Zero when the shadow line is parallel to the light, or E = F; the other
    // nonzero sign when E is farther from the light's line than F.
    if cross_sign(l, r, f, e) != side_f.flip() {
        return None;
    }
    // E strictly beyond the light's line.
    if orient2d(l, r, e) == side_f.flip() {
        return None;
    }
    let d = side_f.flip().to_i32();
    Some(if orient2d(f, e, l).to_i32() * d <= 0 {
        Crossing::BeforeL
    } else if orient2d(f, e, r).to_i32() * d >= 0 {
        Crossing::BeyondR
    } else {
        Crossing::Inside
    })
}

/// Whether the ray from `F` through `E` crosses the closed segment `[L, R]`
/// with `F` off the light's line: the domain of the paper's eq. 1.
fn ray_crosses_light(l: DVec2, r: DVec2, f: DVec2, e: DVec2) -> bool {
    let side_f = orient2d(l, r, f);
    if side_f == Sign::Zero || cross_sign(l, r, f, e) != side_f.flip() {
        return false;
    }
    let d = side_f.flip().to_i32();
    orient2d(f, e, l).to_i32() * d >= 0 && orient2d(f, e, r).to_i32() * d <= 0
}

/// Magnitudes in `[SAFE_LO, SAFE_HI]` need no rescaling: the product of two
/// of them is finite, and normal even after a factor `sin θ` as small as
/// `1e-20`.
pub(crate) trait LinearFloat: AngleFloat {
    const SAFE_LO: Self;
    const SAFE_HI: Self;
    /// The largest finite value.
    const MAX: Self;
    /// The predicates' coordinates (an exact promotion).
    fn to_d2(p: Self::V2) -> DVec2;
}

impl LinearFloat for f64 {
    const SAFE_LO: f64 = 1e-100;
    const SAFE_HI: f64 = 1e100;
    const MAX: f64 = f64::MAX;
    #[inline]
    fn to_d2(p: DVec2) -> DVec2 {
        p
    }
}

impl LinearFloat for f32 {
    const SAFE_LO: f32 = 1e-9;
    const SAFE_HI: f32 = 1e9;
    const MAX: f32 = f32::MAX;
    #[inline]
    fn to_d2(p: glam::Vec2) -> DVec2 {
        p.as_dvec2()
    }
}

/// The visible part of a segment light `[L, R]` and the weights of its
/// endpoint samples for linear emission (OESS substep 4.3, figures 5
/// and 6), all as fractions of the light's length.
///
/// One type for both precisions: [`f64::VisiblePart`] and
/// [`f32::VisiblePart`] name it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VisiblePart<T> {
    /// Where the visible interval starts, as the parameter `s ∈ [0, 1]`
    /// along `L → R`.
    pub start: T,
    /// Where it ends (`start ≤ end ≤ 1`). An empty interval (the light
    /// wholly hidden) has `start = end`.
    pub end: T,
    /// The visible fraction `i = end − start`, computed directly (not
    /// by the subtraction), so it is accurate when small.
    pub fraction: T,
    /// `A = ∫ s ds` over the visible part: the weight of the `R`
    /// endpoint sample.
    pub weight_r: T,
    /// `B = ∫ (1 − s) ds` over the visible part: the weight of the `L`
    /// endpoint sample. `weight_l + weight_r = fraction` within
    /// `6u·fraction` (`u = 2⁻⁵³`, `f32`: `2⁻²⁴`), plus the subnormal
    /// spacing when the weights are subnormal.
    pub weight_l: T,
}

/// `[start, end]` with its fraction and weights: [`f64::VisiblePart`]'s
/// `interval` in either precision.
fn interval<T: Float>(start: T, end: T) -> VisiblePart<T> {
    let (zero, one, half) = (T::of(0.0), T::of(1.0), T::of(0.5));
    let (s, e) = (start.clamp(zero, one), end.clamp(zero, one));
    if s.is_nan() || e.is_nan() || e <= s {
        let at = if s.is_nan() { zero } else { s };
        return VisiblePart {
            start: at,
            end: at,
            ..empty_of(zero)
        };
    }
    let i = e - s;
    VisiblePart {
        start: s,
        end: e,
        fraction: i,
        weight_r: half * i * (e + s),
        weight_l: half * i * ((one - e) + (one - s)),
    }
}

/// `[0, s]`, given `s` and `q = 1 − s` (each computed directly).
#[inline]
fn up_to<T: Float>(s: T, q: T) -> VisiblePart<T> {
    let half = T::of(0.5);
    VisiblePart {
        start: T::of(0.0),
        end: s,
        fraction: s,
        // ∫₀ˢ σ dσ = s²/2; ∫₀ˢ (1 − σ) dσ = s(2 − s)/2 = s(1 + q)/2.
        weight_r: half * s * s,
        weight_l: half * s * (T::of(1.0) + q),
    }
}

/// `[s, 1]`, given `s` and `q = 1 − s`.
#[inline]
fn from<T: Float>(s: T, q: T) -> VisiblePart<T> {
    let half = T::of(0.5);
    VisiblePart {
        start: s,
        end: T::of(1.0),
        fraction: q,
        // ∫ₛ¹ σ dσ = (1 − s²)/2 = q(1 + s)/2; ∫ₛ¹ (1 − σ) dσ = q²/2.
        weight_r: half * q * (T::of(1.0) + s),
        weight_l: half * q * q,
    }
}

/// The whole light visible: `[0, 1]`, `i = 1`, `A = B = 1/2`, given `0`,
/// `1/2` and `1` in the precision.
const fn full_of<T: Copy>(zero: T, half: T, one: T) -> VisiblePart<T> {
    VisiblePart {
        start: zero,
        end: one,
        fraction: one,
        weight_r: half,
        weight_l: half,
    }
}

/// Nothing visible: the empty interval at 0, given `0` in the precision.
const fn empty_of<T: Copy>(zero: T) -> VisiblePart<T> {
    VisiblePart {
        start: zero,
        end: zero,
        fraction: zero,
        weight_r: zero,
        weight_l: zero,
    }
}

/// [`full_of`] in either precision.
fn full<T: Float>() -> VisiblePart<T> {
    full_of(T::of(0.0), T::of(0.5), T::of(1.0))
}

/// `a·b − c·d` within `2u` relative (plus `O(u²)|ab|`): both products split
/// exactly (TwoProd), `p − q` exact when they are within a factor 2
/// (Sterbenz) and otherwise free of cancellation, the error terms summed
/// exactly (TwoSum). The same bits with or without a hardware FMA (see
/// `kernel::eft`).
#[inline]
fn difference_of_products<T: Float>(a: T, b: T, c: T, d: T) -> T {
    let (p, e) = two_prod(a, b);
    let (q, f) = two_prod(c, d);
    let s = e - f;
    let bv = s - e;
    let t = (e - (s - bv)) + (-f - bv);
    ((p - q) + s) + t
}

#[inline]
fn cross<T: Float>(p: T::V2, q: T::V2) -> T {
    difference_of_products(p.x(), q.y(), p.y(), q.x())
}

/// An exact power of two `k` such that `m·k` lies near 1, or `1` when `m` is
/// already in the safe range (or zero).
#[inline]
fn rescale<T: LinearFloat>(m: T) -> T {
    if m == T::of(0.0) || (T::SAFE_LO..=T::SAFE_HI).contains(&m) {
        return T::of(1.0);
    }
    let limit = T::MAX_EXP - 2;
    // An integer-valued float, converted in its own width (`to_i32`).
    let e = m.log2().floor().to_i32().clamp(-limit, limit);
    T::of(2.0).powi(-e)
}

/// Points whose largest coordinate exceeds a quarter of the largest finite
/// value are quartered (exactly, but for subnormal coordinates), so that no
/// difference of two of them overflows.
#[inline]
fn guard_overflow<T: LinearFloat, const N: usize>(points: [T::V2; N]) -> [T::V2; N] {
    let m = points
        .iter()
        .fold(T::of(0.0), |m, p| m.max(p.abs().max_element()));
    if m > T::of(0.25) * T::MAX {
        points.map(|p| p * T::of(0.25))
    } else {
        points
    }
}

/// `(s_P, 1 − s_P)` for a crossing known to be inside the segment.
#[inline]
fn crossing_parameter<T: LinearFloat>(l: T::V2, r: T::V2, f: T::V2, e: T::V2) -> (T, T) {
    let [l, r, f, e] = guard_overflow::<T, 4>([l, r, f, e]);
    // s_P is invariant under scaling the shadow direction and, jointly, the
    // two endpoint directions: normalise each to magnitude ~1.
    let p = e - f;
    let p = p * rescale(p.abs().max_element());
    let (ql, qr) = (l - f, r - f);
    let k = rescale(ql.abs().max_element().max(qr.abs().max_element()));
    let a = cross::<T>(p, ql * k).abs();
    let b = cross::<T>(p, qr * k).abs();
    let sum = a + b;
    if sum > T::of(0.0) {
        (a / sum, b / sum)
    } else {
        // Both distances below the precision's range although the exact
        // signs differ: any point of the segment is within rounding of P.
        // Take the middle.
        (T::of(0.5), T::of(0.5))
    }
}

/// [`f64::visible_part`] in either precision.
pub(crate) fn visible_part<T: LinearFloat>(
    l: T::V2,
    r: T::V2,
    f: T::V2,
    e: T::V2,
    side: OccluderSide,
) -> VisiblePart<T> {
    let Some(crossing) = classify(T::to_d2(l), T::to_d2(r), T::to_d2(f), T::to_d2(e)) else {
        return full();
    };
    let (s, q) = match crossing {
        Crossing::BeforeL => (T::of(0.0), T::of(1.0)),
        Crossing::BeyondR => (T::of(1.0), T::of(0.0)),
        Crossing::Inside => crossing_parameter::<T>(l, r, f, e),
    };
    match side {
        OccluderSide::TowardR => up_to(s, q),
        OccluderSide::TowardL => from(s, q),
    }
}

/// [`f64::visible_part_3d`] in either precision.
pub(crate) fn visible_part_3d<T: LinearFloat>(
    l: T::V3,
    r: T::V3,
    f: T::V3,
    e: T::V3,
    side: OccluderSide,
) -> VisiblePart<T> {
    if !(l.is_finite() && r.is_finite() && f.is_finite() && e.is_finite()) {
        return full();
    }
    let m = l.abs().max_element().max(r.abs().max_element());
    let m = m.max(f.abs().max_element()).max(e.abs().max_element());
    let quarter = T::of(0.25);
    let (l, r, f, e) = if m > quarter * T::MAX {
        (l * quarter, r * quarter, f * quarter, e * quarter)
    } else {
        (l, r, f, e)
    };
    let (u, w, g) = (r - l, f - l, e - l);
    let k = rescale(
        u.abs()
            .max_element()
            .max(w.abs().max_element())
            .max(g.abs().max_element()),
    );
    let (u, w, g) = (u * k, w * k, g * k);
    let x = u.normalize_or_zero();
    let y = (w - x * w.dot(x)).normalize_or_zero();
    if x == T::V3::ZERO || y == T::V3::ZERO {
        return full();
    }
    visible_part(
        T::V2::ZERO,
        T::V2::new(u.dot(x), T::of(0.0)),
        T::V2::new(w.dot(x), w.dot(y)),
        T::V2::new(g.dot(x), g.dot(y)),
        side,
    )
}

/// [`f64::law_of_sines_fraction`] in either precision.
pub(crate) fn law_of_sines_fraction<T: LinearFloat>(
    l: T::V2,
    r: T::V2,
    f: T::V2,
    e: T::V2,
) -> Option<T> {
    if !ray_crosses_light(T::to_d2(l), T::to_d2(r), T::to_d2(f), T::to_d2(e)) {
        return None;
    }
    let [l, r, f, e] = guard_overflow::<T, 4>([l, r, f, e]);
    let k = rescale((r - l).abs().max_element().max((f - l).abs().max_element()));
    let (fl, fr, lr) = ((l - f) * k, (r - f) * k, (r - l) * k);
    let fe = e - f;
    let fe = fe * rescale(fe.abs().max_element());
    let angle = |p: T::V2, q: T::V2| angle::atan2(cross::<T>(p, q).abs(), p.dot(q));
    let alpha = angle(fl, fr);
    let beta = angle(-lr, -fr);
    let gamma = angle(lr, -fl);
    let delta = angle(fl, fe);
    let i = (beta.sin() * delta.sin()) / (alpha.sin() * (T::PI - delta - gamma).sin());
    if i.is_nan() {
        None
    } else {
        Some(i.clamp(T::of(0.0), T::of(1.0)))
    }
}

/// The public items of one precision `($T, $V2, $V3)`, declared once
/// with their contracts, each forwarding to the generic body above;
/// `both_precisions!` makes the modules `f64` and `f32` of them.
macro_rules! precision {
    ($T:ident, $V2:ident, $V3:ident) => {
        use super::OccluderSide;
        use glam::{$V2, $V3};

        #[doc = concat!("[`VisiblePart`](super::VisiblePart) in `", stringify!($T), "`.")]
        pub type VisiblePart = super::VisiblePart<$T>;

        impl VisiblePart {
            /// The whole light visible: `[0, 1]`, `i = 1`, `A = B = 1/2`.
            pub const FULL: VisiblePart = super::full_of(0.0, 0.5, 1.0);

            /// Nothing visible: the empty interval at 0.
            pub const EMPTY: VisiblePart = super::empty_of(0.0);

            /// The interval `[start, end]` of the light's parameter, clamped
            /// to `[0, 1]` (an empty interval where `end ≤ start`, or for a
            /// NaN bound), with its fraction `end − start` and the endpoint
            /// weights `A = (end² − start²)/2`, `B = fraction − A`, each
            /// formed without cancellation: `A = (end − start)(end +
            /// start)/2`, `B = (end − start)(2 − end − start)/2`.
            #[must_use]
            pub fn interval(start: $T, end: $T) -> VisiblePart {
                super::interval(start, end)
            }

            /// The part visible in both `self` and `other` (the
            /// intersection of the intervals), as [`VisiblePart::interval`].
            #[must_use]
            pub fn intersect(&self, other: &VisiblePart) -> VisiblePart {
                super::interval(self.start.max(other.start), self.end.min(other.end))
            }
        }

        /// The visible part of the segment light `[l, r]` seen from the
        /// fragment `f` past the occluding edge point `e`, the occluder lying
        /// on `side` of the shadow line (OESS substep 4.3). 2D coordinates in the plane through the light and
        /// the fragment.
        ///
        /// **Domain**: finite points, `l ≠ r`, `f` off the light's line; for
        /// exact decisions, magnitudes as [`orient2d`](crate::kernel::predicate::orient2d).
        ///
        /// **Edge of the domain** (see the module docs): fully visible
        /// ([`VisiblePart::FULL`]) when `e` does not lie between `f` and the
        /// light's line, when the shadow line is parallel to the light,
        /// `e = f`, `f` on the light's line, `l = r`, or any coordinate is
        /// non-finite. When the shadow line meets the light's line outside
        /// the segment, the light is wholly visible or wholly hidden
        /// (`fraction = 0`, `start = end`, both weights `0`) as `side` says.
        /// Never NaN.
        ///
        /// **Properties**: `fraction ∈ [0, 1]`, weights `≥ 0`,
        /// `weight_l + weight_r = fraction` to a few ulps; swapping `l` and
        /// `r` together with `side` swaps the weights and mirrors the
        /// interval bit for bit; scaling all points by a power of two changes
        /// nothing.
        ///
        /// **Accuracy**: `|ŝ − s_P| ≤ s_P(1 − s_P)(2u/sin θ_L + 2u/sin θ_R + 4u) + 2u·s_P`
        /// to first order, `θ_L`, `θ_R` the angles at `f` between the shadow
        /// line and `fl`, `fr` (module docs); measured in
        /// `tests/linear_light.rs`, `docs/accuracy/kernels.md`.
        #[must_use]
        pub fn visible_part(l: $V2, r: $V2, f: $V2, e: $V2, side: OccluderSide) -> VisiblePart {
            super::visible_part::<$T>(l, r, f, e, side)
        }

        /// [`visible_part`] for 3D points: `e` is projected orthogonally onto
        /// the plane through `l`, `r`, `f` (OESS interpolates its occluding
        /// edges so that `e` lies in that plane; the projection absorbs
        /// rounding), and the configuration is expressed in an orthonormal
        /// frame of that plane with origin `l` and first axis along `r − l`.
        ///
        /// **Domain and edge of the domain**: as [`visible_part`]; fully
        /// visible also when `f` is within rounding of the light's line (the
        /// plane is then undefined). Magnitudes are rescaled by powers of
        /// two, so any finite input works; the decisions are exact for the
        /// projected 2D configuration.
        ///
        /// **Accuracy**: the projection perturbs each 2D coordinate by a few
        /// ulps of the configuration's largest coordinate (after rescaling);
        /// the effect on `s_P` follows the conditioning of [`visible_part`].
        /// `tests/linear_light.rs` bounds the perturbation by `32u` times the
        /// largest coordinate (embedding rotation included); measured errors
        /// stay below 0.15 of that bound.
        #[must_use]
        pub fn visible_part_3d(l: $V3, r: $V3, f: $V3, e: $V3, side: OccluderSide) -> VisiblePart {
            super::visible_part_3d::<$T>(l, r, f, e, side)
        }

        /// The paper's law-of-sines form of the visible fraction (OESS
        /// eq. 1): `i = sin β · sin δ / (sin α · sin(π − δ − γ)) = |LP|/|LR|`,
        /// the fraction from `L` to the point `P` where the ray from `f`
        /// through `e` meets the light (see the module docs for the angles).
        /// For comparison with [`visible_part`], which is the stable form.
        ///
        /// Angles are `atan2(|cross|, dot)` of rescaled difference vectors, by
        /// the crate's portable [`atan2`](crate::kernel::angle::f64::atan2);
        /// the sines are the platform's.
        ///
        /// **Domain**: `Some` exactly when `f` is off the light's line and
        /// the ray from `f` through `e` meets the closed segment `[l, r]`
        /// (decided exactly); `None` otherwise (including `l = r`, `e = f`,
        /// non-finite input). Inside the domain the value is clamped to
        /// `[0, 1]`; if the computed `sin α` vanishes (`f` within rounding of
        /// the light's line) the quotient is clamped too, and `0/0` gives
        /// `None`.
        ///
        /// **Accuracy**: numerically weaker than [`visible_part`]: a sine near
        /// `π` has an absolute error of a few `u`, so the relative error grows
        /// like `u/|π − angle|` as `α`, `β`, `γ` or `δ + γ` approach `π`
        /// (module docs). Measured (`tests/linear_light.rs`): on
        /// well-conditioned configurations within `2.1e-15` (`f64`) and
        /// `1.2e-6` (`f32`) of the exact value, about 3–4 times the stable
        /// form's error; with the fragment `1e-8` above the middle of a unit
        /// light, `1.2e-9` off, and with a grazing shadow line at that height,
        /// `3.5e-8` off, where the stable form is exact to the last bit.
        #[must_use]
        pub fn law_of_sines_fraction(l: $V2, r: $V2, f: $V2, e: $V2) -> Option<$T> {
            super::law_of_sines_fraction::<$T>(l, r, f, e)
        }
    };
}

both_precisions!(precision);

#[cfg(test)]
mod tests {
    use super::*;

    /// The lifted orient3d has the sign of the plain cross product wherever
    /// the rounded cross product is clearly nonzero.
    #[test]
    fn cross_sign_matches_the_cross_product() {
        let mut rng = crate::arbitrary::Rng::new(7);
        for _ in 0..10_000 {
            let mut p = || DVec2::new(rng.uniform(-4.0, 4.0), rng.uniform(-4.0, 4.0));
            let (l, r, f, e) = (p(), p(), p(), p());
            let c = (r - l).perp_dot(e - f);
            if c.abs() > 1e-9 {
                let expected = if c > 0.0 {
                    Sign::Positive
                } else {
                    Sign::Negative
                };
                assert_eq!(cross_sign(l, r, f, e), expected);
            }
        }
        // Exactly parallel (every coordinate and difference exact), and
        // one ulp off it either way.
        let (l, r) = (DVec2::new(0.25, 0.5), DVec2::new(0.75, 1.0));
        let f = DVec2::new(3.0, -1.0);
        let e = DVec2::new(3.5, -0.5);
        assert_eq!(cross_sign(l, r, f, e), Sign::Zero);
        let up = DVec2::new(3.5, (-0.5f64).next_up());
        let down = DVec2::new(3.5, (-0.5f64).next_down());
        assert_eq!(cross_sign(l, r, f, up), Sign::Positive);
        assert_eq!(cross_sign(l, r, f, down), Sign::Negative);
    }

    #[test]
    fn intervals_carry_their_weights_and_intersect() {
        use super::f64::VisiblePart;
        let v = VisiblePart::interval(0.25, 0.75);
        assert_eq!((v.start, v.end, v.fraction), (0.25, 0.75, 0.5));
        // A = ∫ s ds = (0.75² − 0.25²)/2 = 0.25, B = 0.5 − 0.25.
        assert_eq!((v.weight_r, v.weight_l), (0.25, 0.25));
        assert_eq!(VisiblePart::interval(0.0, 1.0), VisiblePart::FULL);
        assert_eq!(VisiblePart::interval(-3.0, 7.0), VisiblePart::FULL);
        let empty = VisiblePart::interval(0.6, 0.4);
        assert_eq!(
            (empty.fraction, empty.weight_l, empty.weight_r),
            (0.0, 0.0, 0.0)
        );
        assert_eq!(VisiblePart::interval(f64::NAN, 0.5).fraction, 0.0);
        let w = VisiblePart::interval(0.5, 0.9).intersect(&v);
        assert_eq!((w.start, w.end), (0.5, 0.75));
        assert!(v.intersect(&VisiblePart::interval(0.8, 1.0)).fraction == 0.0);
        // The weights sum to the fraction.
        for (a, b) in [(0.1, 0.3), (0.0, 1e-300), (0.999, 1.0)] {
            let p = VisiblePart::interval(a, b);
            assert!(
                (p.weight_l + p.weight_r - p.fraction).abs() <= 4.0 * f64::EPSILON * p.fraction
            );
        }
    }
}
