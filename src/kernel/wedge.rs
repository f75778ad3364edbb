//! Penumbra wedges and penumbra quads: conservative bounds of the region a
//! silhouette edge can partially occlude a sphere light from.
//!
//! A receiver `p` is *affected* by the edge `E = [e0, e1]` when the edge
//! meets the open segment from `p` to some point of the light's facing disk
//! ([visibility](crate::definitions#visibility)). The facing disk lies in the ball `B` (centre `c`, radius
//! `r`), so every affected point lies in
//!
//! ```text
//! W = { q + t (q − y) : q ∈ E, y ∈ B, t > 0 },
//! ```
//!
//! the union of the cones cast by the edge's points away from the ball.
//! Both bounds here contain `W` (not only a rounded version of it): they
//! never miss an affected receiver.
//!
//! - [`f64::PenumbraWedge`] / [`f32::PenumbraWedge`]: four half-spaces in
//!   world space, Assarsson and Akenine-Möller's wedge ("A geometry-based
//!   soft shadow volume algorithm using graphics hardware", SIGGRAPH 2003,
//!   §3.1), with side planes chosen so that the wedge is always conservative.
//! - [`f64::penumbra_quad`] / [`f32::penumbra_quad`]: the rectangle on the
//!   light image plane that contains the projection of every affected
//!   receiver up to a depth `z_max` (SISM, Johnson et al. 2009, §2.2 and
//!   §2.5: the coarse penumbra test), with a footprint radius that is
//!   rigorous for the exact (tilted) facing disk.
//!
//! Both are generated from one body for `f32` and `f64`.
//!
//! # The half-space lemma (why the wedge is conservative)
//!
//! Call a vector `n` *separating* when `n · (e_i − c) ≥ r‖n‖` for both
//! endpoints: the plane through the tangent point `c + r n/‖n‖` with normal
//! `n` has the whole ball on one side and the whole edge on the other. For
//! such `n`, every `p = q + t(q − y) ∈ W` satisfies
//! `n · (p − c) = n · (q − c) + t (n · (q − c) − n · (y − c)) ≥ n · (q − c)
//! ≥ min_i n · (e_i − c)`, because `n · (q − c) ≥ r‖n‖ ≥ n · (y − c)`. So
//! `W ⊂ { p : n · (p − c) ≥ min_i n · (e_i − c) }` for **every** separating
//! `n`, and any intersection of such half-spaces is a conservative wedge.
//!
//! The wedge uses four separating normals, computed in the plane `Σ`
//! through the edge and `c` (any plane through the edge when it points at
//! `c`), with `d` the edge direction and `b` the normal of `Σ`:
//!
//! - **front and back**: when the edge's line misses the ball, the two
//!   planes through the edge tangent to the sphere (AAM's front and back
//!   planes; they touch `W` along the whole edge). When the line meets the
//!   ball (an edge pointing at the light), no such plane exists; the
//!   separating normals nearest `±b` are then the tangent planes through the
//!   nearer endpoint.
//! - **sides**: in `Σ`, the separating normals of extreme angle: the tangent
//!   lines through an endpoint that separate the light's great circle from
//!   the segment (the 2D boundary of `W ∩ Σ`). AAM place the side plane at
//!   `e0` tangent through `e0`; when the edge turns toward the light that
//!   plane cuts the other endpoint off (`W` is not contained), and their
//!   paper moves vertices to repair it. Here the extreme separating normal is
//!   taken instead: the tangent through `e0` when it is separating for `e1`,
//!   else the tangent through `e1` — always separating, so always
//!   conservative.
//!
//! # Rounding
//!
//! The normals are computed for a radius inflated by a small derived margin
//! (`32 ε (‖e − c‖ + r)`, raised eightfold up to 12 times when needed) and
//! then *verified* on the input data with a rigorous forward error bound:
//! a normal is kept only if it is provably separating for the true radius,
//! and its offset is a proven lower bound of `min_i n · (e_i − c)`.
//! [`f64::PenumbraWedge::contains`] adds the error bound of its own dot
//! product in favour of inclusion. A plane that cannot be verified is
//! dropped, which only enlarges the wedge; this happens only for an edge
//! passing within rounding distance of the light's surface (measured over
//! the `wedge_case` generator in `tests/wedge.rs`: for `f64`, only edges
//! whose distance to the centre exceeds `r` by less than `2e-11 r`, all from
//! its tangent-within-a-few-ulps cases).

/// Why a wedge or a quad could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum WedgeError {
    /// A NaN or infinite coordinate, radius or depth.
    NonFinite,
    /// The light radius is zero or negative (a point light has no penumbra).
    NonPositiveRadius,
    /// The edge has zero length (`PenumbraWedge` only).
    ZeroLengthEdge,
    /// The edge touches or enters the light, as rounded: no plane can
    /// separate them.
    EdgeTouchesLight,
    /// The magnitudes are outside the representable range of the
    /// construction (squares of the coordinates relative to the light
    /// overflow, or they are subnormal).
    OutOfRange,
    /// `z_max ≤ 0` (`penumbra_quad` only).
    NonPositiveDepthBound,
}

impl_error!(WedgeError, |error, f| {
    let what = match error {
        WedgeError::NonFinite => "a coordinate, radius or depth is not finite",
        WedgeError::NonPositiveRadius => "the light radius must be positive",
        WedgeError::ZeroLengthEdge => "the edge has zero length",
        WedgeError::EdgeTouchesLight => "the edge touches or enters the light",
        WedgeError::OutOfRange => "the magnitudes are out of the supported range",
        WedgeError::NonPositiveDepthBound => "the receiver depth bound must be positive",
    };
    f.write_str(what)
});

/// Which plane of a wedge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WedgePlaneKind {
    /// Through the edge, tangent to the light, on one side of the edge's
    /// plane `Σ` (the `+b` side, `b = d × w` with `d` the edge direction and
    /// `w` pointing from the light centre toward the edge).
    Front,
    /// The same on the `−b` side.
    Back,
    /// The side plane at the `e0` end.
    Side0,
    /// The side plane at the `e1` end.
    Side1,
}

use crate::kernel::float::{both_precisions, Float, Vector2, Vector3};
use crate::kernel::footprint::gamma;
use crate::kernel::predicate::{orient2d, Sign};

/// Number of times the radius margin is raised (eightfold each).
const RETRIES: i32 = 12;

/// One half-space of a wedge: `p` is inside when
/// `normal · (p − center) ≥ offset`, `center` the light's centre.
///
/// `normal` is a unit vector up to rounding; `offset` is a proven
/// lower bound of `min_i normal · (e_i − center)` (in the exact
/// arithmetic of the stored values), and `normal` is proven
/// separating (see the [module docs](self)).
///
/// One type for both precisions: [`f64::WedgePlane`] and
/// [`f32::WedgePlane`] name it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WedgePlane<V, T> {
    /// Which plane.
    pub kind: WedgePlaneKind,
    /// The inward normal.
    pub normal: V,
    /// The offset from the light centre along `normal`.
    pub offset: T,
}

/// A penumbra wedge: a conservative bound of the points a silhouette
/// edge can partially occlude a sphere light from (see the [module
/// docs](self) for the construction and its proof).
///
/// One type for both precisions: [`f64::PenumbraWedge`] and
/// [`f32::PenumbraWedge`] name it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PenumbraWedge<V, T> {
    center: V,
    planes: [Option<WedgePlane<V, T>>; 4],
}

impl<V: Copy, T: Copy> PenumbraWedge<V, T> {
    /// The light centre the planes are measured from.
    #[must_use]
    pub fn center(&self) -> V {
        self.center
    }

    /// The verified planes (four, except for an edge within rounding
    /// distance of the light: see [`new`](f64::PenumbraWedge::new)).
    pub fn planes(&self) -> impl Iterator<Item = WedgePlane<V, T>> + '_ {
        self.planes.iter().flatten().copied()
    }
}

/// [`f64::PenumbraWedge::new`] in either precision.
#[inline]
fn new_wedge<T: Float>(
    (e0, e1): (T::V3, T::V3),
    center: T::V3,
    radius: T,
) -> Result<PenumbraWedge<T::V3, T>, WedgeError> {
    if !(e0.is_finite() && e1.is_finite() && center.is_finite() && radius.is_finite()) {
        return Err(WedgeError::NonFinite);
    }
    if radius <= T::of(0.0) {
        return Err(WedgeError::NonPositiveRadius);
    }
    if e0 == e1 {
        return Err(WedgeError::ZeroLengthEdge);
    }
    let a = [e0 - center, e1 - center];
    let span = a[0]
        .abs()
        .max_element()
        .max(a[1].abs().max_element())
        .max(radius);
    // A power of two brings the magnitudes near 1 exactly, so squares
    // neither overflow nor underflow (an integer-valued exponent, converted
    // in its own width).
    let scale = T::of(2.0).powi(-span.log2().ceil().to_i32());
    let a_s = [a[0] * scale, a[1] * scale];
    let u_s = (e1 - e0) * scale;
    let r_s = radius * scale;
    if !(a[0].is_finite()
        && a[1].is_finite()
        && scale.is_finite()
        && scale > T::of(0.0)
        && u_s.is_finite()
        && u_s != T::V3::ZERO)
    {
        return Err(WedgeError::OutOfRange);
    }
    let frame = Frame::<T>::new(a_s, u_s);
    if frame.distance_to_segment(a_s) <= r_s {
        return Err(WedgeError::EdgeTouchesLight);
    }
    let a_max = a_s[0].length().max(a_s[1].length());
    let mut planes: [Option<WedgePlane<T::V3, T>>; 4] = [None; 4];
    let mut margin = T::of(32.0) * T::EPSILON * (a_max + r_s);
    for _ in 0..=RETRIES {
        let normals = frame.normals(r_s + margin);
        for (slot, normal) in planes.iter_mut().zip(normals) {
            if slot.is_none() {
                *slot = normal.and_then(|(kind, n)| verify::<T>(kind, n, a, radius));
            }
        }
        if planes.iter().all(Option::is_some) {
            break;
        }
        margin = margin * T::of(8.0);
    }
    Ok(PenumbraWedge { center, planes })
}

/// [`f64::PenumbraWedge::contains`] in either precision.
#[inline]
fn wedge_contains<T: Float>(wedge: &PenumbraWedge<T::V3, T>, p: T::V3) -> bool {
    if !p.is_finite() {
        return false;
    }
    let v = p - wedge.center;
    wedge.planes.iter().flatten().all(|plane| {
        let s = plane.normal.dot(v);
        let err = gamma::<T>(8) * plane.normal.abs().dot(v.abs());
        s + err >= plane.offset
    })
}

/// Proves `n` separating for the exact data (`a_i = fl(e_i − c)`
/// rounded once per component) and returns the plane with a proven
/// lower offset, or `None`.
///
/// `fl(n · fl(e_i − c))` carries at most 4 roundings per monomial
/// (difference, product, two additions): error `≤ γ(4) Σ|n_j||a_ij|`
/// with the exact `a`, `≤ γ(5)` times the computed permanent; `γ(12)`
/// also absorbs the rounding of the subtraction. `‖n‖` is bounded
/// above by its rounded value times `1 + γ(4)`.
fn verify<T: Float>(
    kind: WedgePlaneKind,
    n: T::V3,
    a: [T::V3; 2],
    r: T,
) -> Option<WedgePlane<T::V3, T>> {
    if !n.is_finite() {
        return None;
    }
    let one = T::of(1.0);
    let norm_up = n.length() * (one + gamma(4));
    let need = r * norm_up * (one + gamma(2));
    let mut offset = T::INFINITY;
    for ai in a {
        let k = n.dot(ai) - gamma::<T>(12) * n.abs().dot(ai.abs());
        if k.is_nan() || k < need {
            return None;
        }
        offset = offset.min(k);
    }
    Some(WedgePlane {
        kind,
        normal: n,
        offset,
    })
}

/// The edge's frame: `d` along the edge, `w` in `Σ` from the light
/// toward the edge, `b = d × w`; endpoints in `Σ` coordinates
/// `P_i = (a_i · d, a_i · w)`.
struct Frame<T: Float> {
    d: T::V3,
    w: T::V3,
    b: T::V3,
    p: [T::V2; 2],
    length: T,
}

impl<T: Float> Frame<T> {
    fn new(a: [T::V3; 2], u: T::V3) -> Frame<T> {
        let length = u.length();
        let d = u / length;
        // a0 × u, not a0 × a1: for a short edge far from the light a0 and a1
        // are nearly parallel and their cross product cancels
        // catastrophically; u = e1 − e0 is computed directly.
        let g = a[0].cross(u);
        let b = (g - d * g.dot(d))
            .try_normalize()
            .unwrap_or_else(|| d.any_orthonormal_vector());
        let mut w = b.cross(d);
        let mut p = a.map(|ai| T::V2::new(ai.dot(d), ai.dot(w)));
        if p[0].y() + p[1].y() < T::of(0.0) {
            w = -w;
            p = p.map(|pi| T::V2::new(pi.x(), -pi.y()));
        }
        Frame {
            d,
            w,
            b: d.cross(w),
            p,
            length,
        }
    }

    fn distance_to_segment(&self, a: [T::V3; 2]) -> T {
        let t = (-a[0].dot(self.d)).clamp(T::of(0.0), self.length);
        (a[0] + self.d * t).length()
    }

    /// The four separating normals for radius `rc` (module docs): front,
    /// back, side at `e0`, side at `e1`.
    fn normals(&self, rc: T) -> [Option<(WedgePlaneKind, T::V3)>; 4] {
        let [p0, p1] = self.p;
        let (l0, l1) = (p0.length(), p1.length());
        if !(l0 > rc && l1 > rc) {
            return [None; 4];
        }
        // Tangent from P at distance A: n = (rc P ± t P⊥) / A²,
        // t = √((A − rc)(A + rc)) (no cancellation in A² − rc²).
        let t0 = ((l0 - rc) * (l0 + rc)).sqrt();
        let t1 = ((l1 - rc) * (l1 + rc)).sqrt();
        let tangent = |p: T::V2, l: T, t: T, sign: T| (p * rc + p.perp() * (sign * t)) / (l * l);
        // Of two candidate normals, the one separating for the other
        // endpoint too (the larger margin there).
        let pick = |n0: T::V2, n1: T::V2| {
            if n0.dot(p1) - rc >= n1.dot(p0) - rc {
                n0
            } else {
                n1
            }
        };
        let (minus, plus) = (T::of(-1.0), T::of(1.0));
        let side0 = pick(tangent(p0, l0, t0, minus), tangent(p1, l1, t1, minus));
        let side1 = pick(tangent(p0, l0, t0, plus), tangent(p1, l1, t1, plus));
        let rho = T::of(0.5) * (p0.y() + p1.y());
        let (m, z) = if rho > rc {
            // The planes through the edge: m · P_i = rc for both.
            (
                T::V2::new(T::of(0.0), rc / rho),
                ((rho - rc) * (rho + rc)).sqrt() / rho,
            )
        } else {
            // The line meets the ball: tangent planes through the endpoint
            // whose polar point is feasible for the other.
            let (m0, m1) = (p0 * rc / (l0 * l0), p1 * rc / (l1 * l1));
            if m0.dot(p1) - rc >= m1.dot(p0) - rc {
                (m0, t0 / l0)
            } else {
                (m1, t1 / l1)
            }
        };
        let world = |n: T::V2, z: T| self.d * n.x() + self.w * n.y() + self.b * z;
        [
            Some((WedgePlaneKind::Front, world(m, z))),
            Some((WedgePlaneKind::Back, world(m, -z))),
            Some((WedgePlaneKind::Side0, world(side0, T::of(0.0)))),
            Some((WedgePlaneKind::Side1, world(side1, T::of(0.0)))),
        ]
    }
}

/// The light-image-plane rectangle of [`penumbra_quad`](f64::penumbra_quad).
///
/// Corners counter-clockwise: `center ∓ half_length·axis ∓
/// half_width·axis⊥`, starting behind `e0` on the right of the
/// projected edge. `min`/`max` bound the corners.
///
/// One type for both precisions: [`f64::PenumbraQuad`] and
/// [`f32::PenumbraQuad`] name it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PenumbraQuad<V, T> {
    /// The four corners, counter-clockwise.
    pub corners: [V; 4],
    /// Lower corner of the axis-aligned bound.
    pub min: V,
    /// Upper corner of the axis-aligned bound.
    pub max: V,
    /// Centre of the rectangle.
    pub center: V,
    /// Unit direction of the projected edge (`+x` when it projects
    /// to a point).
    pub axis: V,
    /// Half the rectangle's extent along `axis`.
    pub half_length: T,
    /// Half the rectangle's extent across `axis`.
    pub half_width: T,
    /// The footprint radius bound `R` used (rounded up).
    pub radius: T,
}

/// [`f64::PenumbraQuad::contains`] in either precision.
#[inline]
fn quad_contains<T: Float>(quad: &PenumbraQuad<T::V2, T>, q: T::V2) -> bool {
    let q = T::wide2(q);
    (0..4).all(|i| {
        let (a, b) = (
            T::wide2(quad.corners[i]),
            T::wide2(quad.corners[(i + 1) % 4]),
        );
        orient2d(a, b, q) != Sign::Negative
    })
}

/// What [`penumbra_quad`](f64::penumbra_quad) found.
///
/// One type for both precisions: [`f64::QuadBound`] and [`f32::QuadBound`]
/// name it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum QuadBound<V, T> {
    /// Every affected receiver at depth `≤ z_max` projects into the
    /// quad.
    Quad(PenumbraQuad<V, T>),
    /// No receiver at depth `≤ z_max` can be affected: the edge lies
    /// entirely at depth `≥ z_max` (and beyond the light's depth
    /// slab).
    Empty,
    /// The edge reaches the light's depth slab (`z ≤ r`, including
    /// behind the light): rays through it leave at arbitrary angles,
    /// no bounded quad exists, every receiver must be tested.
    Unbounded,
}

/// [`f64::penumbra_quad`] in either precision.
#[inline]
fn penumbra_quad<T: Float>(
    (e0, e1): (T::V3, T::V3),
    radius: T,
    z_max: T,
) -> Result<QuadBound<T::V2, T>, WedgeError> {
    let (zero, half, one, two) = (T::of(0.0), T::of(0.5), T::of(1.0), T::of(2.0));
    if !(e0.is_finite() && e1.is_finite() && radius.is_finite() && z_max.is_finite()) {
        return Err(WedgeError::NonFinite);
    }
    if radius <= zero {
        return Err(WedgeError::NonPositiveRadius);
    }
    if z_max <= zero {
        return Err(WedgeError::NonPositiveDepthBound);
    }
    // Near and far endpoint, keeping track of the edge's direction.
    let swapped = e1.z() < e0.z();
    let (near, far) = if swapped { (e1, e0) } else { (e0, e1) };
    let z_min = near.z();
    if z_min <= radius {
        return Ok(QuadBound::Unbounded);
    }
    if z_min >= z_max {
        return Ok(QuadBound::Empty);
    }
    let project = |q: T::V3| T::V2::new(q.x() / q.z(), q.y() / q.z());
    let a = project(near);
    let mut b = project(far);
    if far.z() > z_max {
        // The image point at depth z_max: π(near + λ(far − near)) =
        // a + μ(b − a) with μ = λ far.z / z_max; μ rounded up.
        let lambda = (z_max - near.z()) / (far.z() - near.z());
        let mu = (lambda * far.z() / z_max * (one + gamma(6))).min(one);
        b = a + (b - a) * mu;
    }
    let k = (one + a.length_squared())
        .max(one + b.length_squared())
        .sqrt();
    let radius_up = radius * k * ((z_max - z_min) / z_max) / (z_min - radius) * (one + gamma(10));
    let (start, end) = if swapped { (b, a) } else { (a, b) };
    let span = end - start;
    let length = span.length();
    let axis = if length > zero {
        span / length
    } else {
        T::V2::X
    };
    let axis = if axis.is_finite() { axis } else { T::V2::X };
    let slack = gamma::<T>(16) * (a.length() + b.length() + length + two * radius_up);
    let half_length = half * length + radius_up + slack;
    let half_width = radius_up + slack;
    let center = (start + end) * half;
    let (along, across) = (axis * half_length, axis.perp() * half_width);
    let corners = [
        center - along - across,
        center + along - across,
        center + along + across,
        center - along + across,
    ];
    let quad = PenumbraQuad {
        corners,
        min: corners[0].min(corners[1]).min(corners[2].min(corners[3])),
        max: corners[0].max(corners[1]).max(corners[2].max(corners[3])),
        center,
        axis,
        half_length,
        half_width,
        radius: radius_up,
    };
    if quad.corners.iter().all(|c| c.is_finite()) && radius_up.is_finite() {
        Ok(QuadBound::Quad(quad))
    } else {
        Ok(QuadBound::Unbounded)
    }
}

/// The public items of one precision `($T, $V2, $V3)`, declared once
/// with their contracts, each forwarding to the generic body above;
/// `both_precisions!` makes the modules `f64` and `f32` of them.
macro_rules! precision {
    ($T:ident, $V2:ident, $V3:ident) => {
        use super::WedgeError;
        use glam::{$V2, $V3};

        #[doc = concat!("[`WedgePlane`](super::WedgePlane) in `", stringify!($T), "`.")]
        pub type WedgePlane = super::WedgePlane<$V3, $T>;

        #[doc = concat!("[`PenumbraWedge`](super::PenumbraWedge) in `", stringify!($T), "`.")]
        pub type PenumbraWedge = super::PenumbraWedge<$V3, $T>;

        #[doc = concat!("[`PenumbraQuad`](super::PenumbraQuad) in `", stringify!($T), "`.")]
        pub type PenumbraQuad = super::PenumbraQuad<$V2, $T>;

        #[doc = concat!("[`QuadBound`](super::QuadBound) in `", stringify!($T), "`.")]
        pub type QuadBound = super::QuadBound<$V2, $T>;

        impl PenumbraWedge {
            /// The wedge of edge `[e0, e1]` and the sphere light
            /// (`center`, `radius`).
            ///
            /// Domain: finite input, `radius > 0`, `e0 ≠ e1`, the edge
            /// outside the light, magnitudes relative to the light centre
            /// such that their squares neither overflow nor lose all
            /// precision (about `1e±150` for `f64`, `1e±18` for `f32`).
            /// Every plane is verified (module docs); a plane that cannot be
            /// verified is left out, so [`contains`](Self::contains) stays
            /// conservative for every accepted input.
            ///
            /// # Errors
            ///
            /// [`WedgeError::NonFinite`], [`WedgeError::NonPositiveRadius`],
            /// [`WedgeError::ZeroLengthEdge`],
            /// [`WedgeError::EdgeTouchesLight`] (the rounded distance from
            /// the centre to the segment is `≤ radius`),
            /// [`WedgeError::OutOfRange`].
            pub fn new(e0: $V3, e1: $V3, center: $V3, radius: $T) -> Result<Self, WedgeError> {
                super::new_wedge::<$T>((e0, e1), center, radius)
            }

            /// `true` for every point the edge can partially occlude the
            /// light from — every point of `W` in the module docs, exactly,
            /// in spite of rounding: each plane test adds the forward error
            /// bound `γ(8) Σ_j |n_j| |p_j − c_j|` of its dot product in
            /// favour of inclusion. May be `true` for points near `W` too
            /// (measured tightness in `tests/wedge.rs`). `false` for a
            /// non-finite `p`.
            #[must_use]
            pub fn contains(&self, p: $V3) -> bool {
                super::wedge_contains::<$T>(self, p)
            }
        }

        impl PenumbraQuad {
            /// `true` when `q` is inside the rectangle (closed), decided with
            /// the exact `orient2d` on the corners.
            #[must_use]
            pub fn contains(&self, q: $V2) -> bool {
                super::quad_contains::<$T>(self, q)
            }
        }

        /// The penumbra quad of the edge `[e0, e1]` for a sphere light of
        /// radius `radius`, in the **light frame** ([light frame](crate::definitions#light-frame): light centre
        /// at the origin, `+z` toward the scene, image plane `z = 1`,
        /// `(x, y, z) ↦ (x/z, y/z)`): a rectangle containing the projection
        /// of every receiver at depth `z_p ≤ z_max` that the edge partially
        /// occludes (SISM §2.2, the coarse test).
        ///
        /// The edge is first clipped to `z ≤ z_max` (points deeper than
        /// every receiver cannot occlude it, since occluders lie strictly
        /// between receiver and light). With `z_min` the edge's least depth
        /// and `K = max √(1 + |π(q)|²)` over the clipped edge's endpoints
        /// (`1/cos` of the largest off-axis angle), the quad is the
        /// projected clipped edge extended by `R` at both ends and on both
        /// sides, with
        ///
        /// ```text
        /// R = r · K · (1 − z_min/z_max) / (z_min − r).
        /// ```
        ///
        /// **Proof.** If `q ∈ (p, y)` with `y` in the facing disk
        /// (`|y| ≤ r`), then `p ∥ q − σy` with `σ = t/(1+t) ∈ (0, 1)`, and
        /// `z_p (1 − σ) = q_z − σ y_z ≥ q_z − σ r` gives
        /// `σ ≤ (z_p − q_z)/(z_p − r)`. Projecting the ball of radius `σr`
        /// around `q`: `|π(q + δ) − π(q)| = |δ_xy − π(q) δ_z| / (q_z + δ_z) ≤
        /// |δ| √(1 + |π(q)|²) / (q_z − |δ|)`, increasing in `|δ| ≤ σ r`;
        /// substituting `σ`'s bound gives `|π(p) − π(q)| ≤ K_q r (z_p − q_z)
        /// / (z_p (q_z − r))`, increasing in `z_p ≤ z_max` and decreasing in
        /// `q_z ≥ z_min`. `|π(q)|` is convex along the projected segment, so
        /// `K` is reached at an endpoint.
        ///
        /// SISM's footprint radius `r (1/z_min − 1/z_max)` ([footprint radius](crate::definitions#footprint-radius)) is
        /// exact for a light disk in the plane `z = 0`, i.e. on the light's
        /// axis; the exact facing disk tilts with `p`, and its footprint is
        /// a slightly larger ellipse off-axis. The bound here is larger than
        /// SISM's by the factor `K z_min / (z_min − r)` (1 on the axis for
        /// `r ≪ z_min`; 1.28 at 30° off-axis with `r = z_min/10`).
        ///
        /// Rounding: `R` is rounded up (`γ(10)`, ten rounded operations on
        /// positive quantities), the clip parameter is rounded toward the
        /// far end, and the half extents get `γ(16)` times the magnitudes
        /// of the projected endpoints, the length and `R`, which covers the
        /// projection, the clipping, the direction of `axis` and the
        /// corners' own rounding.
        ///
        /// # Errors
        ///
        /// [`WedgeError::NonFinite`], [`WedgeError::NonPositiveRadius`],
        /// [`WedgeError::NonPositiveDepthBound`]. A zero-length edge is
        /// accepted (a square around its projection).
        pub fn penumbra_quad(
            e0: $V3,
            e1: $V3,
            radius: $T,
            z_max: $T,
        ) -> Result<QuadBound, WedgeError> {
            super::penumbra_quad::<$T>((e0, e1), radius, z_max)
        }
    };
}

both_precisions!(precision);

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    #[test]
    fn aam_planes_of_a_simple_edge() {
        // Unit light at the origin, edge along x at y = 3: the tangent planes
        // through the edge have normals (0, 1/3, ±√8/3); in the plane z = 0
        // the side tangents through (∓1, 3) have normals (±0.8, 0.6).
        let (e0, e1) = (DVec3::new(-1.0, 3.0, 0.0), DVec3::new(1.0, 3.0, 0.0));
        let wedge = f64::PenumbraWedge::new(e0, e1, DVec3::ZERO, 1.0).unwrap();
        let planes: Vec<f64::WedgePlane> = wedge.planes().collect();
        assert_eq!(planes.len(), 4);
        let s8 = 8f64.sqrt() / 3.0;
        for (plane, kind, normal, offset) in [
            (
                planes[0],
                WedgePlaneKind::Front,
                DVec3::new(0.0, 1.0 / 3.0, s8),
                1.0,
            ),
            (
                planes[1],
                WedgePlaneKind::Back,
                DVec3::new(0.0, 1.0 / 3.0, -s8),
                1.0,
            ),
            (
                planes[2],
                WedgePlaneKind::Side0,
                DVec3::new(0.8, 0.6, 0.0),
                1.0,
            ),
            (
                planes[3],
                WedgePlaneKind::Side1,
                DVec3::new(-0.8, 0.6, 0.0),
                1.0,
            ),
        ] {
            assert_eq!(plane.kind, kind);
            // The front/back pair may come out with b = ±z: compare up to
            // the sign of z.
            let n = DVec3::new(plane.normal.x, plane.normal.y, plane.normal.z.abs());
            let want = DVec3::new(normal.x, normal.y, normal.z.abs());
            assert!((n - want).length() < 1e-13, "{plane:?}");
            // The inflated radius tilts the normal by ~1e-14: the offset is
            // the edge's (verified) distance along it, within that of 1.
            assert!((plane.offset - offset).abs() < 1e-12, "{plane:?}");
        }
        assert!(wedge.contains(DVec3::new(0.0, 6.0, 0.0)));
        assert!(wedge.contains(e0) && wedge.contains(e1));
        assert!(!wedge.contains(DVec3::ZERO));
        assert!(!wedge.contains(DVec3::new(0.0, 3.0, 3.0)));
        assert!(!wedge.contains(DVec3::new(f64::NAN, 6.0, 0.0)));
    }

    #[test]
    fn degenerate_input_is_an_error() {
        let (c, e) = (DVec3::ZERO, DVec3::new(0.0, 3.0, 0.0));
        let new = f64::PenumbraWedge::new;
        assert_eq!(new(e, e, c, 1.0), Err(WedgeError::ZeroLengthEdge));
        assert_eq!(
            new(e, DVec3::X * 5.0, c, 0.0),
            Err(WedgeError::NonPositiveRadius)
        );
        assert_eq!(
            new(e, DVec3::X * 5.0, c, f64::NAN),
            Err(WedgeError::NonFinite)
        );
        // Within the light, and tangent to it.
        for y in [0.5, 1.0] {
            let (a, b) = (DVec3::new(-1.0, y, 0.0), DVec3::new(1.0, y, 0.0));
            assert_eq!(new(a, b, c, 1.0), Err(WedgeError::EdgeTouchesLight));
        }
    }

    #[test]
    fn quad_on_the_axis() {
        // A short edge across the axis at depth 2, light radius 0.5,
        // receivers up to depth 4. SISM's R = 0.5 (1/2 − 1/4) = 0.125;
        // the rigorous bound is R · K z_min/(z_min − r) with K = √(1 + 0.01²).
        let e0 = DVec3::new(-0.02, 0.0, 2.0);
        let e1 = DVec3::new(0.02, 0.0, 2.0);
        let f64::QuadBound::Quad(q) = f64::penumbra_quad(e0, e1, 0.5, 4.0).unwrap() else {
            panic!("a quad expected");
        };
        let want = 0.125 * (1.0f64 + 1e-4).sqrt() * 2.0 / 1.5;
        assert!(q.radius >= want && q.radius < want * (1.0 + 1e-14));
        assert_eq!(q.axis, DVec2::X);
        assert!(q.contains(DVec2::new(0.01 + want, want)));
        assert!(!q.contains(DVec2::new(0.0, 2.0 * want)));
        assert!(q.min.x <= -0.01 - want && q.max.y >= want);
        assert_eq!(
            f64::penumbra_quad(e0, e1, 0.5, 1.5),
            Ok(f64::QuadBound::Empty)
        );
        assert_eq!(
            f64::penumbra_quad(e0, e1, 2.5, 4.0),
            Ok(f64::QuadBound::Unbounded)
        );
        assert_eq!(
            f64::penumbra_quad(e0, e1, 0.5, 0.0),
            Err(WedgeError::NonPositiveDepthBound)
        );
        assert_eq!(
            f64::penumbra_quad(e0, e1, -0.5, 1.0),
            Err(WedgeError::NonPositiveRadius)
        );
    }
}
