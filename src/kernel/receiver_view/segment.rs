//! The receiver view of a segment light ([`SegmentView`]): each triangle
//! hides one interval of the light's parameter, bounded by the four planes
//! of its shadow (the three through the receiver and an edge, and its own);
//! the occluded fraction is the length of their union.

use super::bounded::{det3_exact, max_abs, Bounded, Cross, Row};
use super::{Fraction, Scratch};
use crate::kernel::predicate::{orient2d, orient3d, Sign};
use glam::{DVec2, DVec3};

/// The receiver view of the segment light `a b` from `p`: what each
/// triangle hides is an interval of the light's parameter `s ∈ [0, 1]`
/// (the point `x(s) = a + s (b − a)`).
///
/// A light point `x` is hidden by a triangle `q₀q₁q₂` exactly when the
/// direction `x − p` lies in the cone the triangle spans from `p` and `x`
/// lies strictly beyond the triangle's plane (the open segment of
/// [visibility](crate::definitions#visibility)): four conditions, each the
/// sign of a determinant that is affine in `x`, so along the light
/// `(1 − s) F(a) + s F(b)` with `F(a)`, `F(b)` determinants of the inputs
/// as given (`det[qⱼ − p, qₖ − p, x − p]` for the cone's three planes,
/// `det[q₁ − q₀, q₂ − q₀, x − q₀]` for the triangle's). Their signs are
/// exact and their values accurate ([`SegmentView::blocked`]); no point is
/// constructed, so a triangle `10⁻¹⁷` from the receiver, a light `10⁻¹⁶`
/// long or a corner `10²⁰` away costs no accuracy.
#[derive(Clone, Copy, Debug)]
pub struct SegmentView {
    p: DVec3,
    a: DVec3,
    b: DVec3,
}

/// The largest error of a blocked interval's end, as a fraction of the
/// light, above which its two determinants are evaluated exactly.
const TOLERANCE: f64 = 1.0 / (1u64 << 50) as f64;

impl SegmentView {
    /// The view of the segment `a b` from `p`.
    ///
    /// `None` when an argument is not finite, `a = b`, or `p` lies on the
    /// closed segment (decided exactly; [`Segment::seen_from`] refuses such a
    /// receiver too). A receiver on the light's line beyond an end is
    /// defined: every open segment `(p, x)` lies on that line.
    ///
    /// [`Segment::seen_from`]: crate::kernel::light::Segment::seen_from
    #[must_use]
    pub fn new(p: DVec3, a: DVec3, b: DVec3) -> Option<SegmentView> {
        if !(p.is_finite() && a.is_finite() && b.is_finite()) || a == b {
            return None;
        }
        let collinear = [(0, 1), (1, 2), (2, 0)].iter().all(|&(i, j)| {
            let q = |v: DVec3| DVec2::new(v[i], v[j]);
            orient2d(q(a), q(b), q(p)) == Sign::Zero
        });
        // On the light's line: refused between the ends, inclusive (every
        // coordinate of p between the ends').
        let between = |u: f64, v: f64, w: f64| (u <= w && w <= v) || (v <= w && w <= u);
        let on = collinear && (0..3).all(|k| between(a[k], b[k], p[k]));
        (!on).then_some(SegmentView { p, a, b })
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
    ///
    /// Each of the four conditions of [`SegmentView`] is an affine function
    /// `(1 − s) F(a) + s F(b)` of `s`, oriented to be positive inside: the
    /// cone's planes by `σ`, the exact sign of `det[q₀ − p, q₁ − p, q₂ −
    /// p]` (zero: the triangle's plane holds `p`, and every open segment
    /// `(p, x)` meets that plane at most at `p` or lies in it — nothing is
    /// hidden, as [`segment_blocked`] has it), and the triangle's plane
    /// strictly. Both values have exact signs (the determinants' rounded
    /// values where their error bounds settle the signs, else the exact
    /// ones), so which conditions cut the light, and on which side, is
    /// decided exactly; a cut lies at `F(a) / (F(a) − F(b))`, two values of
    /// opposite signs with errors below `2⁻⁵⁰` of their difference. The
    /// cone is closed (a light lying wholly in a plane through `p` and an
    /// edge is hidden where the segments cross the edge, as
    /// [`segment_blocked`] blocks a segment through an edge), the plane
    /// open.
    ///
    /// [`segment_blocked`]: crate::kernel::segment::segment_blocked
    #[must_use]
    pub fn blocked(&self, tri: &[DVec3; 3]) -> Option<(f64, f64)> {
        self.blocked_bounded(tri)
            .map(|(span, _)| span)
            .filter(|&(lo, hi)| lo < hi)
    }

    /// [`SegmentView::blocked`] with a bound on the error of either end
    /// of the interval; `None` only where the triangle certainly hides
    /// nothing of positive length. Where the rounded ends cross (`s₀ ≥
    /// s₁`) the exact interval, within the bound of them, may still be up
    /// to twice the bound long: then the ends are returned as they are.
    pub(super) fn blocked_bounded(&self, tri: &[DVec3; 3]) -> Option<((f64, f64), f64)> {
        if !tri.iter().all(|v| v.is_finite()) {
            return None;
        }
        let (p, a, b) = (self.p, self.a, self.b);
        let sigma = match orient3d(tri[0], tri[1], tri[2], p) {
            Sign::Positive => 1.0,
            Sign::Negative => -1.0,
            Sign::Zero => return None,
        };
        let (ra, rb) = (Row::diff(a, p), Row::diff(b, p));
        let mut span = Span {
            lo: 0.0,
            hi: 1.0,
            err: 0.0,
        };
        // The cone: for the edge (j, k) opposite corner i, the plane
        // through p and the edge, oriented toward corner i: σ · det[qⱼ − p,
        // qₖ − p, x − p] ≥ 0 (at x = qᵢ it is σ², the rows a cyclic
        // shift). The edge's ends in a canonical order, so that two
        // triangles sharing it cut the light at the same bits.
        for (j, k) in [(1, 2), (2, 0), (0, 1)] {
            let (u, v, s) = if lexicographic(tri[j], tri[k]) {
                (tri[j], tri[k], sigma)
            } else {
                (tri[k], tri[j], -sigma)
            };
            // det[u − p, v − p, ·] = det[u − p, v − u, ·]: the edge's own
            // direction cancels far less.
            let (ru, e) = (Row::diff(u, p), Row::diff(v, u));
            let cross = Cross::of(ru.r, e.r);
            let (fa, fb) = values(&cross, (&ru, &e), &ra, &rb);
            span.cut(fa.signed(s), fb.signed(s), true)?;
        }
        // Strictly beyond the triangle's plane: σ · det[q₁ − q₀, q₂ − q₀,
        // x − q₀] > 0 (at x = p it is −σ: det[q₀ − p, q₁ − p, q₂ − p] =
        // −det[q₁ − q₀, q₂ − q₀, p − q₀]).
        let (e1, e2) = (Row::diff(tri[1], tri[0]), Row::diff(tri[2], tri[0]));
        let cross = Cross::of(e1.r, e2.r);
        let (fa, fb) = values(
            &cross,
            (&e1, &e2),
            &Row::diff(a, tri[0]),
            &Row::diff(b, tri[0]),
        );
        span.cut(fa.signed(sigma), fb.signed(sigma), false)?;
        Some(((span.lo, span.hi), span.err))
    }

    /// How the light is seen from `p` among the triangles: [`Pieces::of`]
    /// their [`SegmentView::blocked`] intervals, the ones whose union
    /// [`SegmentView::occluded_fraction`] measures.
    #[must_use]
    pub fn pieces<'t>(
        &self,
        triangles: impl IntoIterator<Item = &'t [DVec3; 3]>,
        scratch: &mut Scratch,
    ) -> Pieces {
        let intervals = &mut scratch.intervals;
        intervals.clear();
        intervals.extend(triangles.into_iter().filter_map(|t| self.blocked(t)));
        Pieces::of(intervals)
    }

    /// The fraction of the light the triangles hide from `p`, in `[0, 1]`:
    /// the length of the union of [`SegmentView::blocked`].
    #[must_use]
    pub fn occluded_fraction<'t>(
        &self,
        triangles: impl IntoIterator<Item = &'t [DVec3; 3]>,
        scratch: &mut Scratch,
    ) -> f64 {
        self.occluded_fraction_bounded(triangles, scratch).value
    }

    /// [`SegmentView::occluded_fraction`] and a certified bound on its
    /// error: each interval's ends within their bounds, the union's length
    /// moves by at most the sum of those bounds — an interval whose
    /// rounded ends cross, which adds nothing to the length, included —
    /// and its sum by one rounding of the unit interval a term.
    #[must_use]
    pub fn occluded_fraction_bounded<'t>(
        &self,
        triangles: impl IntoIterator<Item = &'t [DVec3; 3]>,
        scratch: &mut Scratch,
    ) -> Fraction {
        scratch.intervals.clear();
        let mut bound = 0.0;
        for tri in triangles {
            if let Some((span, err)) = self.blocked_bounded(tri) {
                scratch.intervals.push(span);
                bound += 2.0 * err;
            }
        }
        let n = scratch.intervals.len() as f64;
        Fraction {
            value: union_length(&mut scratch.intervals),
            bound: bound + 2.0 * n * f64::EPSILON,
        }
    }
}

/// How a receiver sees a segment light: by its *pieces*, the maximal
/// intervals of positive length of the light's parameter `[0, 1]` that no
/// triangle hides ([`Pieces::of`]). Occluding edges soft shadows models a
/// receiver's view as one occluding edge per end of the light, which
/// describes [`Pieces::OneAtEnd`], [`Pieces::Hidden`] and [`Pieces::Whole`]
/// and no other.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Pieces {
    /// One piece holding an end of the light, `[0, t]` or `[t, 1]` with
    /// `0 < t < 1`.
    OneAtEnd,
    /// One piece holding neither end, `[t₀, t₁]` with `0 < t₀ < t₁ < 1`.
    OneInside,
    /// Two pieces or more.
    Several,
    /// No piece: the light is hidden whole (umbra).
    Hidden,
    /// The whole light, `[0, 1]`: nothing hidden.
    Whole,
}

impl Pieces {
    /// Every kind, in the order the report's tables list them.
    pub const ALL: [Pieces; 5] = [
        Pieces::OneAtEnd,
        Pieces::OneInside,
        Pieces::Several,
        Pieces::Hidden,
        Pieces::Whole,
    ];

    /// The pieces of `[0, 1]` outside the union of the `blocked` intervals
    /// `(s₀, s₁)` (sorted here, in place), decided by comparisons of the
    /// ends alone, so exactly for the intervals given.
    ///
    /// - A piece has positive length: intervals that touch (one ends
    ///   where the next begins, `s₁ = s₀′`) or overlap leave none between
    ///   them, and nothing is counted at a single point. A piece however
    ///   short counts.
    /// - A piece holds an end when no interval covers that end: it starts
    ///   at 0 when every interval starts after 0, ends at 1 when every
    ///   interval ends before 1. An interval ending exactly at 0 or 1 takes
    ///   that end.
    /// - Each interval is clamped to `[0, 1]`; one with a NaN end or
    ///   `s₀ ≥ s₁` after clamping hides nothing (as
    ///   [`SegmentView::blocked`] reports none of zero length).
    ///
    /// So no interval is [`Pieces::Whole`], intervals covering `[0, 1]`
    /// without a gap of positive length [`Pieces::Hidden`].
    #[must_use]
    pub fn of(blocked: &mut [(f64, f64)]) -> Pieces {
        blocked.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
        let (mut count, mut at_end) = (0usize, false);
        // How far from 0 the union reaches without a gap.
        let mut reach = 0.0_f64;
        for &(s0, s1) in blocked.iter() {
            // False for a NaN end.
            let hides = s0 < s1 && s0 < 1.0 && s1 > 0.0;
            if !hides {
                continue;
            }
            let (s0, s1) = (s0.max(0.0), s1.min(1.0));
            if s0 > reach {
                count += 1;
                at_end |= reach == 0.0;
            }
            reach = reach.max(s1);
        }
        if reach < 1.0 {
            count += 1;
            at_end = true;
        }
        match count {
            0 => Pieces::Hidden,
            1 if reach == 0.0 => Pieces::Whole,
            1 if at_end => Pieces::OneAtEnd,
            1 => Pieces::OneInside,
            _ => Pieces::Several,
        }
    }
}

/// `F(a)` and `F(b)` for the plane `det[u, v, x − o] = 0` (the rows `u`,
/// `v` relative to `o`, their cross product `cross`; `ra`, `rb` the rows
/// `a − o`, `b − o`): rounded where the bounds settle both signs and keep
/// a cut between them within [`TOLERANCE`] of the light, else exact.
#[inline(always)]
fn values(cross: &Cross, (u, v): (&Row, &Row), ra: &Row, rb: &Row) -> (Bounded, Bounded) {
    let (fa, fb) = (
        cross.dot(ra.r, max_abs(ra.r)),
        cross.dot(rb.r, max_abs(rb.r)),
    );
    let certain = fa.sign().is_some() && fb.sign().is_some();
    // A cut lies at fa / (fa − fb), its error below (δa + δb) / |fa − fb|.
    let accurate = fa.bound + fb.bound <= TOLERANCE * (fa.value - fb.value).abs();
    if certain && (accurate || fa.value * fb.value > 0.0) {
        // Decided on the cheap bounds; the closer ones are reported.
        (
            Bounded {
                bound: cross.precise(ra.r),
                ..fa
            },
            Bounded {
                bound: cross.precise(rb.r),
                ..fb
            },
        )
    } else {
        (det3_exact(u, v, ra), det3_exact(u, v, rb))
    }
}

/// An interval of the light's parameter being narrowed by the conditions,
/// with a bound on the error of its ends.
struct Span {
    lo: f64,
    hi: f64,
    err: f64,
}

impl Span {
    /// Narrows the span to where `(1 − s) fa + s fb` is positive (or zero,
    /// if `closed`); `None` when the condition holds nowhere on the light
    /// (decided exactly: the signs of `fa` and `fb` are exact). A span
    /// whose rounded ends cross is kept: its exact counterpart may be
    /// as long as twice their error.
    #[inline(always)]
    fn cut(&mut self, fa: Bounded, fb: Bounded, closed: bool) -> Option<()> {
        let (a, b) = (fa.value, fb.value);
        let inside = |f: f64| f > 0.0 || (closed && f == 0.0);
        match (inside(a), inside(b)) {
            (true, true) => Some(()),
            (false, false) => None,
            (a_in, _) => {
                // Opposite signs (a zero end is outside here, and the
                // other end strictly inside): no cancellation.
                let s = a / (a - b);
                // The quotient's error: the values' bounds over the
                // difference, and two roundings.
                let err = (fa.bound + fb.bound) / (a - b).abs() + f64::EPSILON;
                if a_in {
                    if s < self.hi {
                        self.hi = s;
                    }
                } else if s > self.lo {
                    self.lo = s;
                }
                self.err = self.err.max(err);
                Some(())
            }
        }
    }
}

/// Whether `a` precedes `b` in lexicographic order of coordinates.
fn lexicographic(a: DVec3, b: DVec3) -> bool {
    (a.x, a.y, a.z) <= (b.x, b.y, b.z)
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
