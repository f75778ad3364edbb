//! The span of an edge that a triangle covers.

use super::tri::Tri;
use crate::kernel::predicate::orient2d_values_finite;
use glam::DVec2;

/// The parameter interval of the edge `a → b` that the triangle covers,
/// `None` when it covers none of positive length. Closed triangle; where
/// the edge runs along an edge of `t` the rule of the
/// [module documentation](super) applies: covered when `t` lies on the
/// other side, or on the same side and `t_first` (it comes first in index
/// order).
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
    (span.0 < span.1).then_some(span)
}

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
