//! The span of an edge that a triangle covers.

use super::tri::Tri;
use crate::kernel::predicate::orient2d_values_finite;
use glam::DVec2;

/// The parameter interval of the edge `a → b` that the triangle covers,
/// `None` when it covers none of positive length. Closed triangle; where
/// the edge runs along an edge of `t` the rule of the
/// [module documentation](super) applies: covered when `t` lies on the
/// other side, or on the same side and `t_first` (it comes first in index
/// order). A span of rounding's length whose points lie nowhere near the
/// triangle's bounds is none ([`credible`]).
#[inline(always)]
pub(super) fn covered_span(a: DVec2, b: DVec2, t: &Tri, t_first: bool) -> Option<(f64, f64)> {
    let mut span = (0.0_f64, 1.0_f64);
    // Signed areas with exact signs and accurate values: the cut of this
    // edge by an edge `f` of `t` and the cut of `f` by this edge land on
    // the same point even for nearly parallel edges. The first edge of `t`
    // at both ends side by side (most triangles the search meets end
    // there), then the other two at both ends.
    let [v0, v1, v2] = t.v;
    let w = orient2d_values_finite(
        [[v0.x, v0.x], [v0.y, v0.y]],
        [[v1.x, v1.x], [v1.y, v1.y]],
        [[a.x, b.x], [a.y, b.y]],
    );
    cut_by_edge(&mut span, w[0], w[1], a, b, (v0, v1), t_first)?;
    let v = orient2d_values_finite(
        [[v1.x, v1.x, v2.x, v2.x], [v1.y, v1.y, v2.y, v2.y]],
        [[v2.x, v2.x, v0.x, v0.x], [v2.y, v2.y, v0.y, v0.y]],
        [[a.x, b.x, a.x, b.x], [a.y, b.y, a.y, b.y]],
    );
    cut_by_edge(&mut span, v[0], v[1], a, b, (v1, v2), t_first)?;
    cut_by_edge(&mut span, v[2], v[3], a, b, (v2, v0), t_first)?;
    (span.0 < span.1 && credible(a, b, span, t)).then_some(span)
}

/// Whether a span of the edge `a → b` that [`covered_span`] found may be
/// one the exact cuts leave non-empty: longer than `2⁻³⁷` of the edge, or
/// its points within `2⁻³⁵ m` of the triangle's bounds, `m` the largest
/// coordinate of the edge's ends and the bounds.
///
/// A span the exact cuts leave empty is shorter: its ends are two cuts,
/// each within `3 · 2⁻⁴⁰` of the exact one's parameter (signed areas
/// within `2⁻⁴⁰` of their own value, of opposite signs), and the exact
/// ones are in the other order. And every span found where the edge truly
/// meets the triangle is near its bounds: the exact span's ends are points
/// of the triangle, and the maximum of the entering cuts and the minimum
/// of the leaving ones move no further than the cuts do; with the point's
/// own rounding, its ends lie within `2⁻³⁷ m` of the triangle in each
/// coordinate (`|b − a|` at most `2 m` in each), `2⁻³⁶ m` in distance.
/// So the spans dropped are all false: those of a **sliver** (a triangle
/// whose three lines almost coincide, the image of a face seen nearly
/// edge-on) or of a very sharp corner, crossed by the edge where its
/// lines run on far from it, the rounded cuts there in the wrong order by
/// rounding's size. Dropping them moves the area toward the exact union's, and makes
/// the premise of every pruning of the search true: each span's points
/// lie within `2⁻³⁴ m` (its length included) of its triangle's bounds —
/// and within `2⁻³³ m` of the triangle itself. For they also lie in the
/// triangle with each line moved out by `δ = 2⁻³⁶ m`; a point of that
/// outside the triangle and more than `δ` from it lies past a corner,
/// within `δ` of its bisector and at most `δ / sin(α/2)` beyond it (`α`
/// the corner's angle); where that reaches past `2⁻³⁵ m`, `α` is so sharp
/// that the corner is the triangle's farthest point along the coordinate
/// axis nearest the bisector, and the grown bounds stop the point within
/// `√2 (2⁻³⁵ m + 2δ)` of it.
#[inline(always)]
pub(super) fn credible(a: DVec2, b: DVec2, (s, e): (f64, f64), t: &Tri) -> bool {
    e - s > SHORT || near_bounds(a, b, (s, e), t)
}

/// Whether the points of the edge `a → b` at the parameters `(s, e)` lie
/// within `2⁻³⁵ m` of the triangle's bounds ([`credible`]), out of the
/// search's loop: few spans are that short.
#[cold]
#[inline(never)]
fn near_bounds(a: DVec2, b: DVec2, (s, e): (f64, f64), t: &Tri) -> bool {
    let d = b - a;
    let (p, q) = (a + d * s, a + d * e);
    let m = a
        .abs()
        .max(b.abs())
        .max(t.lo.abs())
        .max(t.hi.abs())
        .max_element();
    let g = m * NEAR;
    p.min(q).cmple(t.hi + g).all() && p.max(q).cmpge(t.lo - g).all()
}

/// How near its triangle's bounds a short span must come, relatively
/// ([`credible`]): `2⁻³⁵`.
const NEAR: f64 = 1.0 / (1_u64 << 35) as f64;

/// How long a span must be for [`credible`] to keep it unchecked:
/// `2⁻³⁷` of the edge, above the `6 · 2⁻⁴⁰` a span the exact cuts leave
/// empty can reach.
const SHORT: f64 = 1.0 / (1_u64 << 37) as f64;

/// Narrows `span` (parameters of the edge `a → b`) to the inner side of
/// the triangle's edge `f`, given the signed areas `va`, `vb` of `a` and
/// `b` against it; `None` when nothing of positive length is left on that
/// side (see [`covered_span`]).
#[inline(always)]
pub(super) fn cut_by_edge(
    span: &mut (f64, f64),
    va: f64,
    vb: f64,
    a: DVec2,
    b: DVec2,
    (f0, f1): (DVec2, DVec2),
    t_first: bool,
) -> Option<()> {
    // The signs' cases by comparisons (a NaN counts as zero, as `Sign`
    // has it; the values are finite).
    let (a_in, a_out, b_in, b_out) = (va > 0.0, va < 0.0, vb > 0.0, vb < 0.0);
    if !a_in && !b_in {
        if a_out || b_out {
            // Outside, touching the line at most at one end.
            return None;
        }
        // Along the line.
        let same_side = (b - a).dot(f1 - f0) > 0.0;
        if same_side && !t_first {
            return None;
        }
    } else if (a_out && b_in) || (a_in && b_out) {
        // A strict crossing: va and vb have opposite signs, so va − vb
        // does not cancel.
        let s = (va / (va - vb)).clamp(0.0, 1.0);
        if a_out {
            span.0 = span.0.max(s);
        } else {
            span.1 = span.1.min(s);
        }
    }
    Some(())
}
