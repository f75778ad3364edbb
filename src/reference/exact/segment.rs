//! Segment lights: the plane through the receiver and the segment cuts
//! each triangle in a segment, which blocks one interval of the light's
//! parameter; the visibility is one minus the length of their union.

use super::view::crossing;
use super::Scratch;
use crate::bvh::Bvh;
use crate::kernel::predicate::{orient2d, orient3d, orient3d_value, Sign};
use crate::kernel::segment::segment_blocked;
use glam::{DVec2, DVec3};

/// The visibility of a segment light `a b` from `p`.
pub(super) fn segment_visibility(
    bvh: &Bvh,
    p: DVec3,
    a: DVec3,
    b: DVec3,
    scratch: &mut Scratch,
) -> f64 {
    let (ra, rb) = (a - p, b - p);
    let n = ra.cross(rb);
    let collinear = [(0, 1), (1, 2), (2, 0)].iter().all(|&(i, j)| {
        let q = |v: DVec3| DVec2::new(v[i], v[j]);
        orient2d(q(a), q(b), q(p)) == Sign::Zero
    });
    bvh.triangles_meeting_hull(&[p, a, b], &mut scratch.candidates);
    let triangles = bvh.occluders().triangles();
    if collinear || n == DVec3::ZERO {
        return collinear_segment_visibility(bvh, p, a, b, &scratch.candidates);
    }
    // The plane's unit normal (scaled to its largest component first, so
    // that neither a light of size 1e-77 nor one of 1e77 under- or overflows
    // the products below).
    let n = (n / n.abs().max_element()).normalize();
    scratch.intervals.clear();
    for &i in &scratch.candidates {
        let Some(tri) = triangles.get(i as usize) else {
            continue;
        };
        if let Some(span) = blocked_interval(p, a, b, n, tri) {
            scratch.intervals.push(span);
        }
    }
    1.0 - union_length(&mut scratch.intervals)
}

/// The interval of the segment light's parameter `s ∈ [0, 1]` (the point
/// `a + s (b − a)`) that the triangle blocks from `p`; `n` the unit normal
/// along `(a − p) × (b − p)`.
fn blocked_interval(
    p: DVec3,
    a: DVec3,
    b: DVec3,
    n: DVec3,
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
    let (ra, rb) = (a - p, b - p);
    // In the plane, with p at the origin: f ≥ 0 on b's side of the ray to
    // a, g ≥ 0 on a's side of the ray to b, h ≥ 0 on p's side of the light.
    let f = |q: DVec3| n.dot(ra.cross(q));
    let g = |q: DVec3| n.dot(q.cross(rb));
    let h = |q: DVec3| n.dot((rb - ra).cross(q - ra));
    // Clip the trace to the triangle (p, a, b); each cut measured from the
    // end nearer the cutting line (a trace end 10²⁰ away must not set the
    // rounding of a cut near the light).
    for fun in [&f as &dyn Fn(DVec3) -> f64, &g, &h] {
        let (v0, v1) = (fun(e0), fun(e1));
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
        let (fq, gq) = (f(q), g(q));
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

/// A receiver on the segment light's line (but not on the light): every
/// open segment `(p, x)` lies on that line, and `x` is blocked beyond the
/// first crossing.
fn collinear_segment_visibility(
    bvh: &Bvh,
    p: DVec3,
    a: DVec3,
    b: DVec3,
    candidates: &[u32],
) -> f64 {
    let (near, far) = if (a - p).length_squared() <= (b - p).length_squared() {
        (a, b)
    } else {
        (b, a)
    };
    if !bvh.segment_unoccluded(p, near) {
        return 0.0;
    }
    // The first crossing beyond `near`, as a fraction of the light: what
    // lies before it is visible.
    let dir = far - near;
    let mut first = 1.0_f64;
    for &i in candidates {
        let Some(tri) = bvh.occluders().triangles().get(i as usize) else {
            continue;
        };
        if segment_blocked(p, far, tri) {
            let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
            let s = n.dot(tri[0] - near) / n.dot(dir);
            first = first.min(if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) });
        }
    }
    first
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
