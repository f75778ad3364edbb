//! The union's triangles and the area it is measured with.

use crate::kernel::disk::f64::segment_disk_area;
use crate::kernel::predicate::{orient2d, Sign};
use glam::DVec2;

/// A projected triangle, counter-clockwise, with its bounds; its corners
/// are finite (the orientation of a non-finite point is zero, so
/// [`Tri::new`] refuses it).
#[derive(Clone, Copy, Debug)]
pub(in crate::kernel::receiver_view) struct Tri {
    pub(super) v: [DVec2; 3],
    pub(super) lo: DVec2,
    pub(super) hi: DVec2,
}

impl Tri {
    /// The triangle oriented counter-clockwise; `None` when it is
    /// degenerate (decided exactly).
    pub(in crate::kernel::receiver_view) fn new(a: DVec2, b: DVec2, c: DVec2) -> Option<Tri> {
        let v = match orient2d(a, b, c) {
            Sign::Positive => [a, b, c],
            Sign::Negative => [a, c, b],
            Sign::Zero => return None,
        };
        Some(Tri {
            v,
            lo: a.min(b).min(c),
            hi: a.max(b).max(c),
        })
    }

    /// Whether the triangle's first edge runs `a → b` (it was given
    /// counter-clockwise, not reversed).
    pub(in crate::kernel::receiver_view) fn first_edge_is(&self, a: DVec2, b: DVec2) -> bool {
        self.v[0] == a && self.v[1] == b
    }

    /// Whether the triangle's bounds miss the box `lo..hi` (touching
    /// meets it).
    #[inline(always)]
    pub(super) fn bounds_miss(&self, lo: DVec2, hi: DVec2) -> bool {
        self.hi.x < lo.x || self.lo.x > hi.x || self.hi.y < lo.y || self.lo.y > hi.y
    }

    pub(super) fn edge(&self, k: usize) -> (DVec2, DVec2) {
        (self.v[k], self.v[(k + 1) % 3])
    }

    /// Twice the area, rounded (positive, or zero where it underflows).
    pub(super) fn doubled_area(&self) -> f64 {
        let [a, b, c] = self.v;
        (b - a).perp_dot(c - a)
    }
}

/// What area the union is measured with.
#[derive(Clone, Copy, Debug)]
pub(in crate::kernel::receiver_view) enum Measure {
    /// The disk of this radius about the origin.
    Disk(f64),
    /// The square `[−1, 1]²`, inside which every projected triangle lies.
    Square,
}

impl Measure {
    /// The half-width of the measure's box.
    pub(in crate::kernel::receiver_view) fn radius(self) -> f64 {
        match self {
            Measure::Disk(r) => r,
            Measure::Square => 1.0,
        }
    }

    /// The signed area the directed boundary piece `a → b` contributes.
    pub(super) fn piece(self, a: DVec2, b: DVec2) -> f64 {
        match self {
            Measure::Disk(r) => segment_disk_area(r, a, b),
            Measure::Square => 0.5 * a.perp_dot(b),
        }
    }

    /// Whether the triangle certainly misses the measure (bounds apart).
    /// Whether the triangle misses the measure's interior (the disk: the
    /// centre outside it and every edge at least `r` away; so a lit
    /// receiver gets `V = 1` exactly, with no boundary pieces to sum).
    pub(in crate::kernel::receiver_view) fn misses(self, t: &Tri) -> bool {
        let r = match self {
            Measure::Disk(r) => r,
            Measure::Square => 1.0,
        };
        if t.lo.x >= r || t.lo.y >= r || t.hi.x <= -r || t.hi.y <= -r {
            return true;
        }
        let Measure::Disk(r) = self else {
            return false;
        };
        // Bounds inside the disk by a margin far above rounding: every
        // edge's nearest point to the centre, computed, lies within a few
        // ulps of them, so nearer than `r` (the answer below, found
        // without its predicates and divisions).
        let far = |lo: f64, hi: f64| lo.abs().max(hi.abs());
        let (fx, fy) = (far(t.lo.x, t.hi.x), far(t.lo.y, t.hi.y));
        if fx * fx + fy * fy < r * r * (1.0 - INSIDE) {
            return false;
        }
        // The centre outside (some edge has it on its right), then every
        // edge at least `r` from it; loops written out, which the compiler
        // keeps inline.
        let mut centre_outside = false;
        for k in 0..3 {
            let (a, b) = t.edge(k);
            if orient2d(a, b, DVec2::ZERO) == Sign::Negative {
                centre_outside = true;
                break;
            }
        }
        if !centre_outside {
            return false;
        }
        for k in 0..3 {
            let (a, b) = t.edge(k);
            let d = b - a;
            let s = (-a.dot(d) / d.length_squared()).clamp(0.0, 1.0);
            let away = (a + d * s).length_squared() >= r * r;
            if !away {
                return false;
            }
        }
        true
    }

    /// Whether some point within `margin` of the triangle `v` (any
    /// orientation, or degenerate) may lie in the measure: its bounds
    /// within `margin` of the square's; for the disk, also the centre
    /// inside or on it, or an edge within `r + margin` of the centre (the
    /// distances' rounding added).
    pub(in crate::kernel::receiver_view) fn near(self, v: &[DVec2; 3], margin: f64) -> bool {
        let r = self.radius();
        let reach = r + margin;
        let (lo, hi) = (v[0].min(v[1]).min(v[2]), v[0].max(v[1]).max(v[2]));
        if margin.is_nan() {
            return true;
        }
        let in_box = lo.cmplt(DVec2::splat(reach)).all() && hi.cmpgt(DVec2::splat(-reach)).all();
        if !in_box || !reach.is_finite() || matches!(self, Measure::Square) {
            return in_box;
        }
        let signs = (0..3).map(|k| orient2d(v[k], v[(k + 1) % 3], DVec2::ZERO));
        let centre_in = !signs.clone().any(|s| s == Sign::Negative)
            || !signs.clone().any(|s| s == Sign::Positive);
        centre_in
            || (0..3).any(|k| {
                let (a, b) = (v[k], v[(k + 1) % 3]);
                let d = b - a;
                let s = (-a.dot(d) / d.length_squared()).clamp(0.0, 1.0);
                let s = if s.is_nan() { 0.0 } else { s };
                let size = a.abs().max_element() + b.abs().max_element();
                (a + d * s).length() <= reach + 16.0 * f64::EPSILON * (size + reach)
            })
    }

    /// Whether the triangle alone covers the whole measure.
    pub(in crate::kernel::receiver_view) fn covered_by(self, t: &Tri) -> bool {
        self.covered_by_convex(&t.v)
    }

    /// Whether the convex polygon `v` (counter-clockwise) alone covers the
    /// whole measure: the disk's centre at least `r` inside every edge, or
    /// every corner of the square on the inner side of every edge. An edge
    /// of length 0 passes either test and constrains nothing, so a polygon
    /// needs an edge of positive length to cover anything (then the
    /// polygon winds at least once around every point of the measure, each
    /// edge turning about it by a non-negative angle): one whose vertices
    /// all coincide (a clipped image collapsed to a point) covers nothing.
    pub(in crate::kernel::receiver_view) fn covered_by_convex(self, v: &[DVec2]) -> bool {
        let n = v.len();
        if n < 3 || v.iter().all(|&q| q == v[0]) {
            return false;
        }
        let edges = (0..n).map(|k| (v[k], v[(k + 1) % n]));
        match self {
            Measure::Disk(r) => edges.clone().all(|(a, b)| {
                let d = b - a;
                // Signed distance of the centre from the edge's line.
                d.perp_dot(-a) >= r * d.length()
            }),
            Measure::Square => [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .iter()
                .all(|&(x, y)| {
                    let c = DVec2::new(x, y);
                    edges
                        .clone()
                        .all(|(a, b)| orient2d(a, b, c) != Sign::Negative)
                }),
        }
    }
}

/// How far inside the disk, relative to `r²`, the farthest corner of a
/// triangle's bounds must lie for [`Measure::misses`] to answer without
/// its edge tests (far above the rounding of those tests, a few ulps).
const INSIDE: f64 = 1.0 / (1u64 << 20) as f64;
