//! The pieces of the union's error bound: the cuts' errors, and the part
//! of an edge's band that other triangles hold deep inside.

use super::span::{credible, cut_by_edge};
use super::tri::Tri;
use crate::kernel::predicate::{orient2d_value_bounded, Bounded};
use glam::DVec2;
use std::f64::consts::SQRT_2;

/// For an edge `a → b` with pieces on the boundary, the sum of `|b − a|
/// Δt` over the pieces' ends that are cuts by other edges, `Δt` a bound on
/// each cut's error, from every span its search found (each computed
/// again with its ends' errors: the pieces are the complement of their
/// union, whatever the order; the raster's covered passages, whose ends
/// are never a piece's, with none).
#[inline(never)]
pub(super) fn cut_errors(a: DVec2, b: DVec2, spans: &mut [[f64; 4]]) -> f64 {
    // The complement of the union of the spans, in order: its interior
    // ends are span ends, each with its error (the larger where ends
    // coincide).
    // Spans starting at the same point: the largest error first (so that
    // the bound does not depend on the order the search found them in).
    spans.sort_unstable_by(|x, y| x[0].total_cmp(&y[0]).then(y[2].total_cmp(&x[2])));
    let mut total = 0.0;
    let (mut reach, mut reach_err) = (0.0_f64, 0.0_f64);
    for &[s, e, es, ee] in spans.iter() {
        if s > reach {
            // A piece (reach, s): its start a cut unless at 0, its end a cut.
            total += reach_err + es;
            reach = e;
            reach_err = ee;
        } else if e > reach {
            reach = e;
            reach_err = ee;
        } else if e == reach {
            reach_err = reach_err.max(ee);
        }
    }
    if reach < 1.0 {
        total += reach_err;
    }
    total * (b - a).length() * (1.0 + 4.0 * f64::EPSILON)
}

/// [`covered_span`] computed one signed area at a time (the same values,
/// so the same span) with bounds, and a bound on each end's error: `[s₀,
/// s₁, Δs₀, Δs₁]`; with it, the parameters `t ∈ [−x, 1 + x]` where the
/// point `a + t (b − a)` lies at least `depth` inside each of the
/// triangle's edge lines ([`Deep`]; possibly empty).
///
/// [`covered_span`]: super::span::covered_span
pub(super) fn covered_span_bounded(
    a: DVec2,
    b: DVec2,
    t: &Tri,
    t_first: bool,
    deep: Deep,
) -> Option<([f64; 4], (f64, f64))> {
    let mut span = [0.0, 1.0, 0.0, 0.0];
    let mut inside = (-deep.x, 1.0 + deep.x);
    let [v0, v1, v2] = t.v;
    for (f0, f1) in [(v0, v1), (v1, v2), (v2, v0)] {
        let (va, vb) = (
            orient2d_value_bounded(f0, f1, a),
            orient2d_value_bounded(f0, f1, b),
        );
        let mut narrowed = (span[0], span[1]);
        cut_by_edge(&mut narrowed, va.value, vb.value, a, b, (f0, f1), t_first)?;
        // The cut's error: the values' bounds over their difference (no
        // cancellation: opposite signs), and the quotient's rounding.
        let err = (va.bound + vb.bound) / (va.value - vb.value).abs() + f64::EPSILON;
        if narrowed.0 != span[0] {
            span[2] = err;
        }
        if narrowed.1 != span[1] {
            span[3] = err;
        }
        (span[0], span[1]) = narrowed;
        inside = deep.narrow(inside, va, vb, (f1 - f0).abs().max_element());
    }
    (span[0] < span[1] && credible(a, b, (span[0], span[1]), t)).then_some((span, inside))
}

/// How deep inside a covering triangle a point of a searched edge must lie
/// for the edge's band there to be inside both unions (the computed and
/// the exact), and how far past the edge's ends (in its parameter) the
/// band runs; see [`walk_edges`](super::boundary).
#[derive(Clone, Copy, Debug)]
pub(super) struct Deep {
    pub(super) depth: f64,
    pub(super) x: f64,
}

impl Deep {
    /// For an edge of length `len` and images of reach `reach`
    /// ([`Image::reach`](crate::kernel::receiver_view::Image)): the band's cross-section at `t` lies within
    /// `reach` of the point `t`, so that point must lie `2 reach` inside
    /// (then every point of the cross-section lies more than `reach` inside
    /// the covering triangle, so in its exact image too), and the band runs
    /// `reach / len` past either end.
    pub(super) fn of(reach: f64, len: f64) -> Deep {
        Deep {
            depth: 2.0 * reach * (1.0 + 8.0 * f64::EPSILON),
            x: reach / len * (1.0 + 4.0 * f64::EPSILON),
        }
    }

    /// `inside` narrowed to where the edge's point lies at least `depth`
    /// inside the line `f` (`max_f` its larger coordinate difference), given
    /// the signed areas `va`, `vb` of the edge's ends against it: `g(t) =
    /// va + t (vb − va)` is `|f|` times the signed distance of the point `t`
    /// from the line (`|f| ≤ √2 max_f`), within `(1 + x)(Δva + Δvb)` of its
    /// exact value on `[−x, 1 + x]`. The quotient's end is moved inward by
    /// its rounding; a line both ends lie that far inside of (with `x |vb
    /// − va|` to spare) leaves `inside` as it is.
    #[inline(always)]
    fn narrow(self, inside: (f64, f64), va: Bounded, vb: Bounded, max_f: f64) -> (f64, f64) {
        const EMPTY: (f64, f64) = (1.0, 0.0);
        let eps = f64::EPSILON;
        let need = self.depth * max_f * (SQRT_2 * (1.0 + 4.0 * eps))
            + (1.0 + self.x) * (va.bound + vb.bound) * (1.0 + 4.0 * eps);
        if !need.is_finite() {
            return EMPTY;
        }
        let k = vb.value - va.value;
        let spare = (need + self.x * k.abs()) * (1.0 + 4.0 * eps);
        if va.value >= spare && vb.value >= spare {
            return inside;
        }
        if k == 0.0 {
            return if va.value >= need { inside } else { EMPTY };
        }
        let t = (need - va.value) / k;
        let slack = 8.0 * eps * ((need.abs() + va.value.abs()) / k.abs() + t.abs());
        if !(t.is_finite() && slack.is_finite()) {
            // Where the point is inside for every `t` (k tiny, `va` deep)
            // or none, a quotient that overflows: taken as none.
            return EMPTY;
        }
        if k > 0.0 {
            (inside.0.max(t + slack), inside.1)
        } else {
            (inside.0, inside.1.min(t - slack))
        }
    }
}

/// The measure of the parameters of `[−x, 1 + x]` outside every interval
/// of `deep` (sorted here), rounded up: the part of an edge's band not
/// shown inside both unions, over the band's length.
pub(super) fn outside_deep(deep: &mut [(f64, f64)], x: f64) -> f64 {
    let eps = f64::EPSILON;
    let end = 1.0 + x;
    deep.sort_unstable_by(|p, q| p.0.total_cmp(&q.0));
    let (mut reach, mut total, mut gaps) = (-x, 0.0, 0.0);
    for &(s, e) in deep.iter() {
        if s.is_nan() || e.is_nan() || s > e {
            continue;
        }
        if s > reach {
            total += s.min(end) - reach;
            gaps += 1.0;
        }
        reach = reach.max(e);
        if reach >= end {
            break;
        }
    }
    if reach < end {
        total += end - reach;
        gaps += 1.0;
    }
    total * (1.0 + 4.0 * eps) + gaps * 2.0 * eps * end
}
