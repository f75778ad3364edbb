//! The receiver view of a segment light ([`SegmentView`]): the plane
//! through the receiver and the segment cuts each triangle in a segment,
//! which blocks one interval of the light's parameter; the occluded
//! fraction is the length of their union.

use super::area::crossing;
use super::Scratch;
use crate::kernel::predicate::{orient2d, orient3d, orient3d_value, Sign};
use crate::kernel::segment::segment_blocked;
use glam::{DVec2, DVec3};

/// The receiver view of the segment light `a b` from `p`: what each
/// triangle hides is an interval of the light's parameter `s ∈ [0, 1]`
/// (the point `a + s (b − a)`).
#[derive(Clone, Copy, Debug)]
pub struct SegmentView {
    p: DVec3,
    a: DVec3,
    b: DVec3,
    /// The plane through `p`, `a`, `b`; `None` when `p` lies on the
    /// light's line.
    plane: Option<Plane>,
}

/// The plane through the receiver and the light, with the three lines that
/// bound the triangle `(p, a, b)` in it as dot products: with `p` at the
/// origin and `n` the plane's unit normal, a point `q` of the plane has
/// `f = n · (ra × q) = q · (n × ra) ≥ 0` on `b`'s side of the ray to `a`,
/// `g = n · (q × rb) = q · (rb × n) ≥ 0` on `a`'s side of the ray to `b`,
/// and `h = n · ((rb − ra) × (q − ra)) = (q − ra) · (n × (rb − ra)) ≥ 0` on
/// `p`'s side of the light — one product per receiver, not per triangle.
#[derive(Clone, Copy, Debug)]
struct Plane {
    ra: DVec3,
    f: DVec3,
    g: DVec3,
    h: DVec3,
}

impl Plane {
    fn new(ra: DVec3, rb: DVec3, n: DVec3) -> Plane {
        Plane {
            ra,
            f: n.cross(ra),
            g: rb.cross(n),
            h: n.cross(rb - ra),
        }
    }

    /// `[f, g, h]` at `q` (relative to `p`).
    fn sides(&self, q: DVec3) -> [f64; 3] {
        [q.dot(self.f), q.dot(self.g), (q - self.ra).dot(self.h)]
    }
}

impl SegmentView {
    /// The view of the segment `a b` from `p`.
    ///
    /// `None` when an argument is not finite, `a = b`, or `p` lies on the
    /// closed segment (decided exactly; [`Light::emitter`] refuses such a
    /// receiver too). A receiver on the light's line beyond an end is
    /// defined: every open segment `(p, x)` lies on that line.
    ///
    /// [`Light::emitter`]: crate::scene::Light::emitter
    #[must_use]
    pub fn new(p: DVec3, a: DVec3, b: DVec3) -> Option<SegmentView> {
        if !(p.is_finite() && a.is_finite() && b.is_finite()) || a == b {
            return None;
        }
        let collinear = [(0, 1), (1, 2), (2, 0)].iter().all(|&(i, j)| {
            let q = |v: DVec3| DVec2::new(v[i], v[j]);
            orient2d(q(a), q(b), q(p)) == Sign::Zero
        });
        let n = (a - p).cross(b - p);
        if collinear || n == DVec3::ZERO || !n.is_finite() {
            // On the light's line (or so nearly that the plane's normal
            // rounds to nothing): refused between the ends, inclusive
            // (every coordinate of p between the ends').
            let between = |u: f64, v: f64, w: f64| (u <= w && w <= v) || (v <= w && w <= u);
            let on = collinear && (0..3).all(|k| between(a[k], b[k], p[k]));
            return (!on).then_some(SegmentView {
                p,
                a,
                b,
                plane: None,
            });
        }
        // The plane's unit normal (scaled to its largest component first, so
        // that neither a light of size 1e-77 nor one of 1e77 under- or
        // overflows the products below).
        let n = (n / n.abs().max_element()).normalize();
        Some(SegmentView {
            p,
            a,
            b,
            plane: Some(Plane::new(a - p, b - p, n)),
        })
    }

    /// The triangle `(p, a, b)`: every triangle that hides some light
    /// point from `p` meets it, so a culling structure may skip the
    /// triangles that miss it.
    #[must_use]
    pub fn hull(&self) -> [DVec3; 3] {
        [self.p, self.a, self.b]
    }

    /// The interval `(s₀, s₁)`, `0 ≤ s₀ < s₁ ≤ 1`, of the light's
    /// parameter the triangle hides from `p`; `None` when it hides nothing
    /// of positive length (or has a non-finite corner).
    #[must_use]
    pub fn blocked(&self, tri: &[DVec3; 3]) -> Option<(f64, f64)> {
        match self.plane {
            Some(plane) => blocked_interval(self.p, self.a, self.b, &plane, tri),
            None => self.blocked_on_line(tri),
        }
    }

    /// The fraction of the light the triangles hide from `p`, in `[0, 1]`:
    /// the length of the union of [`SegmentView::blocked`].
    #[must_use]
    pub fn occluded_fraction<'t>(
        &self,
        triangles: impl IntoIterator<Item = &'t [DVec3; 3]>,
        scratch: &mut Scratch,
    ) -> f64 {
        scratch.intervals.clear();
        for tri in triangles {
            if let Some(span) = self.blocked(tri) {
                scratch.intervals.push(span);
            }
        }
        union_length(&mut scratch.intervals)
    }

    /// A receiver on the light's line (but not on the light): every open
    /// segment `(p, x)` lies on that line, so a triangle blocking the
    /// segment to the nearer end hides the whole light, and one crossing
    /// the line farther hides what lies beyond its crossing.
    fn blocked_on_line(&self, tri: &[DVec3; 3]) -> Option<(f64, f64)> {
        let (p, a, b) = (self.p, self.a, self.b);
        if !tri.iter().all(|v| v.is_finite()) {
            return None;
        }
        let a_nearer = (a - p).length_squared() <= (b - p).length_squared();
        let (near, far) = if a_nearer { (a, b) } else { (b, a) };
        if segment_blocked(p, near, tri) {
            return Some((0.0, 1.0));
        }
        if !segment_blocked(p, far, tri) {
            return None;
        }
        // The crossing as a fraction of the light from its nearer end:
        // what lies before it is visible.
        let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
        let s = n.dot(tri[0] - near) / n.dot(far - near);
        let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) };
        let span = if a_nearer { (s, 1.0) } else { (0.0, 1.0 - s) };
        (span.0 < span.1).then_some(span)
    }
}

/// The interval of the segment light's parameter `s ∈ [0, 1]` (the point
/// `a + s (b − a)`) that the triangle blocks from `p`, in the `plane`
/// through `p`, `a`, `b`.
fn blocked_interval(
    p: DVec3,
    a: DVec3,
    b: DVec3,
    plane: &Plane,
    tri: &[DVec3; 3],
) -> Option<(f64, f64)> {
    if !tri.iter().all(|v| v.is_finite()) {
        return None;
    }
    // A triangle whose plane holds p (a receiver on it), or holds the
    // light: every open segment (p, x) meets its plane at most at an end.
    let [t0, t1, t2] = *tri;
    if orient3d(t0, t1, t2, p) == Sign::Zero
        || (orient3d(t0, t1, t2, a) == Sign::Zero && orient3d(t0, t1, t2, b) == Sign::Zero)
    {
        return None;
    }
    // Each corner's side of the plane (p, a, b): exact signs, and values
    // accurate enough that an edge crossing the plane is cut on it even
    // when the edge is within ulps of the plane.
    let dist = tri.map(|v| orient3d_value(p, a, b, v));
    let side = dist.map(Sign::of);
    if side.iter().all(|&s| s == Sign::Zero) {
        // In the plane: the open segments graze it and are not blocked.
        return None;
    }
    let rel = tri.map(|v| v - p);
    // The triangle's trace on the plane: corners on it and edge crossings.
    let mut pts = [DVec3::ZERO; 3];
    let mut m = 0;
    for k in 0..3 {
        let j = (k + 1) % 3;
        if side[k] == Sign::Zero {
            pts[m] = rel[k];
            m += 1;
        } else if side[j] != Sign::Zero && side[k] != side[j] && m < 3 {
            pts[m] = crossing(rel[k], dist[k], rel[j], dist[j]);
            m += 1;
        }
    }
    if m < 2 {
        return None;
    }
    let (mut e0, mut e1) = (pts[0], pts[1]);
    // Clip the trace to the triangle (p, a, b); each cut measured from the
    // end nearer the cutting line (a trace end 10²⁰ away must not set the
    // rounding of a cut near the light).
    for k in 0..3 {
        let (v0, v1) = (plane.sides(e0)[k], plane.sides(e1)[k]);
        if v0.is_nan() || v1.is_nan() || (v0 < 0.0 && v1 < 0.0) || (v0 <= 0.0 && v1 <= 0.0) {
            // Outside, or on the line: nothing of positive length is left.
            return None;
        }
        if v0 < 0.0 {
            e0 = crossing(e0, v0, e1, v1);
        } else if v1 < 0.0 {
            e1 = crossing(e0, v0, e1, v1);
        }
    }
    // Project both ends from p onto the light: s = f / (f + g).
    let param = |q: DVec3| {
        let [fq, gq, _] = plane.sides(q);
        let den = fq + gq;
        (den > 0.0).then(|| (fq / den).clamp(0.0, 1.0))
    };
    let (s0, s1) = match (param(e0), param(e1)) {
        (Some(x), Some(y)) => (x, y),
        // An end at p itself: the trace runs along a ray from p, one point.
        _ => return None,
    };
    let (lo, hi) = (s0.min(s1), s0.max(s1));
    (lo < hi).then_some((lo, hi))
}

/// The total length of a union of intervals of `[0, 1]`.
fn union_length(intervals: &mut [(f64, f64)]) -> f64 {
    intervals.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
    let mut total = 0.0;
    let mut reach = 0.0_f64;
    for &(s, e) in intervals.iter() {
        let s = s.max(reach);
        if e > s {
            total += e - s;
            reach = e;
        }
    }
    total.min(1.0)
}
