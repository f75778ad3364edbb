//! The pieces of the union's error bound: the cuts' errors.

use super::span::cut_by_edge;
use super::tri::Tri;
use crate::kernel::predicate::orient2d_value_bounded;
use glam::DVec2;

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
/// s₁, Δs₀, Δs₁]`.
pub(super) fn covered_span_bounded(a: DVec2, b: DVec2, t: &Tri, t_first: bool) -> Option<[f64; 4]> {
    let mut span = [0.0, 1.0, 0.0, 0.0];
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
    }
    (span[0] < span[1]).then_some(span)
}
