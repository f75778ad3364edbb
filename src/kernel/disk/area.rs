//! The area of a polygon ∩ a disk, edge by edge: one edge's signed area
//! ([`segment_disk_area`]), many edges side by side
//! ([`segment_disk_areas`]), and their compensated sum over a polygon
//! ([`polygon_disk_area`]). The contracts are on the public `f64` forms
//! ([`super::f64`]).

use super::edge::{batch, cross, cross_by, dot, dot_of, pow2, rescale_exponent, DiskFloat, LANES};
use crate::kernel::angle;
use crate::kernel::float::{Float, Vector2};
use crate::kernel::lanes::{Lanes, Real};

/// [`f64::segment_disk_area`](super::f64::segment_disk_area) in either
/// precision.
pub(super) fn segment_disk_area<T: DiskFloat>(r: T, a: T::V2, b: T::V2) -> T {
    let zero = T::of(0.0);
    if !(r > zero && r.is_finite() && a.is_finite() && b.is_finite()) {
        return zero;
    }
    let m = a.abs().max_element().max(b.abs().max_element()).max(r);
    if m <= T::SAFE_HI && r >= T::SAFE_LO {
        return area_in_range(r, a, b);
    }
    // Rescale by an exact power of two; the area scales by its square.
    let e = rescale_exponent(m);
    let s = pow2::<T>(-e);
    let back = pow2::<T>(e);
    area_in_range(r * s, a * s, b * s) * back * back
}

/// [`segment_disk_area`] for finite input of moderate magnitude.
///
/// Every step is exactly antisymmetric in `a ↔ b` (negations, commuted
/// sums and products, an odd `atan2`), which is what makes reversing the
/// edge negate the result bit for bit.
#[inline(always)]
fn area_in_range<T: DiskFloat>(r: T, a: T::V2, b: T::V2) -> T {
    let half = T::of(0.5);
    let ab_cross = cross::<T>(a, b);
    if ab_cross == T::of(0.0) {
        // Collinear with the centre, or a zero-length edge.
        return T::of(0.0);
    }
    let r2 = r * r;
    if dot::<T>(a, a) <= r2 && dot::<T>(b, b) <= r2 {
        // Both endpoints inside: the whole triangle.
        return half * ab_cross;
    }
    let (g, ta, tb) = edge_frame(a.x(), a.y(), b.x(), b.y(), ab_cross);
    let abs_g = g.abs();
    if abs_g >= r {
        // The whole edge lies outside: one circular sector.
        return half * r2 * angle::atan2(ab_cross, dot::<T>(a, b));
    }
    let w = half_chord(r, abs_g);
    if tb <= -w || ta >= w {
        return half * r2 * angle::atan2(ab_cross, dot::<T>(a, b));
    }
    let (triangle, outside, im, re) = crossing_pieces(g, w, ta, tb);
    if !outside {
        return triangle;
    }
    triangle + half * r2 * angle::atan2(im, re)
}

/// The edge `a → b` in its own frame, from `a × b`: the distance `g` of its
/// line from the centre, signed by the orientation, and the positions
/// `ta < tb` of its ends along its direction, measured from the foot of the
/// perpendicular from the centre.
#[inline(always)]
fn edge_frame<T: Float, R: Real<Scalar = T>>(ax: R, ay: R, bx: R, by: R, ab_cross: R) -> (R, R, R) {
    let (dx, dy) = (bx - ax, by - ay);
    let inv_len = R::splat(T::of(1.0)) / dot_of(dx, dy, dx, dy).sqrt();
    (
        ab_cross * inv_len,
        dot_of(ax, ay, dx, dy) * inv_len,
        dot_of(bx, by, dx, dy) * inv_len,
    )
}

/// Half the chord the line at distance `|g| < r` cuts from the circle,
/// `√((r − |g|)(r + |g|))`: no cancellation as the line becomes tangent.
/// The disk spans `[−w, w]` in the edge's frame.
#[inline(always)]
fn half_chord<R: Real>(r: R, abs_g: R) -> R {
    ((r - abs_g) * (r + abs_g)).sqrt()
}

/// The pieces of an edge that crosses the circle, in its frame (distance
/// `g`, the disk spanning `[−w, w]`, endpoints at `ta < tb`, overlapping
/// it): the triangle inside the disk, whether a piece lies outside, and the
/// complex number `re + i im` whose argument is the outside pieces' angle.
#[inline(always)]
fn crossing_pieces<T: Float, R: Real<Scalar = T>>(g: R, w: R, ta: R, tb: R) -> (R, R::Mask, R, R) {
    let k = |x: f64| R::splat(T::of(x));
    // The piece inside the disk is a triangle of height g.
    let triangle = k(0.5) * g * (tb.min(w) - ta.max(-w));
    // The pieces outside are sectors. The angle between the points at
    // t1 < t2 is arg(t1 t2 + g² + i g (t2 − t1)); when both pieces exist
    // their angles are summed as one complex product (the sum stays below
    // π, as the triangle's angle at the origin does).
    let g2 = g * g;
    let before = ta.lt(-w);
    let after = tb.gt(w);
    let re1 = R::select(before, -w * ta + g2, k(1.0));
    let im1 = R::select(before, g * (-w - ta), k(0.0));
    let re2 = R::select(after, w * tb + g2, k(1.0));
    let im2 = R::select(after, g * (tb - w), k(0.0));
    let re = re1 * re2 - im1 * im2;
    let im = re1 * im2 + im1 * re2;
    (triangle, before | after, im, re)
}

/// [`f64::segment_disk_areas`](super::f64::segment_disk_areas) in either
/// precision.
pub(super) fn segment_disk_areas<T: DiskFloat>(r: T, edges: &[(T::V2, T::V2)], out: &mut Vec<T>)
where
    Lanes<T, LANES>: Real<Scalar = T>,
{
    if (T::SAFE_LO..=T::SAFE_HI).contains(&r) {
        batch(
            edges,
            out,
            #[inline(always)]
            |fma, edges, out| {
                if fma {
                    areas_branch_free::<T, true>(r, edges, out)
                } else {
                    areas_branch_free::<T, false>(r, edges, out)
                }
            },
            |(a, b)| segment_disk_area(r, a, b),
        );
    } else {
        out.clear();
        out.extend(edges.iter().map(|&(a, b)| segment_disk_area(r, a, b)));
    }
}

/// Edges per block of [`areas_branch_free`]: its scratch array stays on the
/// stack and in the first-level cache.
const BLOCK: usize = 16 * LANES;

/// The edges in blocks of up to [`BLOCK`], each in two passes over
/// [`LANES`] edges at a time (the last group padded with zero-length
/// edges): [`frame_of_lanes`], then the angle and the answer
/// ([`finish_lanes`]). Two short loops rather than one long one: the
/// processor overlaps several groups' latency chains (square roots,
/// divisions) only when a group's instructions are few. `out` is as long as
/// `edges`; the answer is whether any entry was left `NaN` for the scalar
/// path. (Functions, not closures: a closure would be compiled apart,
/// without the caller's target features.)
#[inline(always)]
fn areas_branch_free<T: DiskFloat, const FMA: bool>(
    r: T,
    edges: &[(T::V2, T::V2)],
    out: &mut [T],
) -> bool
where
    Lanes<T, LANES>: Real<Scalar = T>,
{
    #[inline(always)]
    fn frame<T: DiskFloat, const FMA: bool>(
        r: Lanes<T, LANES>,
        r2: Lanes<T, LANES>,
        e: &[(T::V2, T::V2); LANES],
    ) -> Frame<Lanes<T, LANES>>
    where
        Lanes<T, LANES>: Real<Scalar = T>,
    {
        let coord = |pick: fn(&(T::V2, T::V2)) -> T| Lanes(core::array::from_fn(|i| pick(&e[i])));
        frame_of_lanes::<T, Lanes<T, LANES>, FMA>(
            r,
            r2,
            coord(|e| e.0.x()),
            coord(|e| e.0.y()),
            coord(|e| e.1.x()),
            coord(|e| e.1.y()),
        )
    }
    type L<T> = Lanes<T, LANES>;
    let (r, r2) = (L::splat(r), L::splat(r * r));
    let mut frames = [Frame::<L<T>>::default(); BLOCK / LANES];
    // Lanes marked NaN for the scalar path (a padding lane never is).
    let mut marked = <L<T> as Real>::Mask::default();
    for (o, e) in out.chunks_mut(BLOCK).zip(edges.chunks(BLOCK)) {
        let groups = e.chunks_exact(LANES);
        let rest = groups.remainder();
        let mut n = 0;
        for (f, g) in frames.iter_mut().zip(groups) {
            if let Ok(g) = <&[(T::V2, T::V2); LANES]>::try_from(g) {
                *f = frame::<T, FMA>(r, r2, g);
                n += 1;
            }
        }
        if !rest.is_empty() {
            let mut padded = [(T::V2::ZERO, T::V2::ZERO); LANES];
            padded[..rest.len()].copy_from_slice(rest);
            if let Some(f) = frames.get_mut(n) {
                *f = frame::<T, FMA>(r, r2, &padded);
            }
        }
        let mut outs = o.chunks_exact_mut(LANES);
        for (f, o) in frames.iter().zip(&mut outs) {
            let areas = finish_lanes(r2, f);
            marked = marked | !areas.eq(areas);
            o.copy_from_slice(&areas.0);
        }
        let o = outs.into_remainder();
        if let Some(f) = frames.get(n).filter(|_| !o.is_empty()) {
            let areas = finish_lanes(r2, f);
            marked = marked | !areas.eq(areas);
            o.copy_from_slice(&areas.0[..o.len()]);
        }
    }
    L::any(marked)
}

/// What [`frame_of_lanes`] leaves for [`finish_lanes`]: the answer without
/// its angle (`pre`), the angle's `atan2(y, x)` arguments, and whether the
/// answer is the sector alone or `pre` plus it.
#[derive(Clone, Copy, Default)]
struct Frame<R: Real> {
    pre: R,
    y: R,
    x: R,
    sector: R::Mask,
    plus_sector: R::Mask,
}

/// [`area_in_range`] of edges side by side, as straight-line code (every
/// path computed, the answer selected), up to the angle. `pre` is `NaN` for
/// an edge that needs the scalar path. `r` lies in the safe range.
#[inline(always)]
fn frame_of_lanes<T: DiskFloat, R: Real<Scalar = T>, const FMA: bool>(
    r: R,
    r2: R,
    ax: R,
    ay: R,
    bx: R,
    by: R,
) -> Frame<R> {
    let k = |x: f64| R::splat(T::of(x));
    let (aa, bb) = (dot_of(ax, ay, ax, ay), dot_of(bx, by, bx, by));
    // Within the safe range (every coordinate at most SAFE_HI, none NaN)
    // when |a|, |b| ≤ SAFE_HI: stricter than the scalar test, so a few
    // edges near its limit take the scalar path needlessly, never the other
    // way round.
    let hi2 = R::splat(T::SAFE_HI * T::SAFE_HI);
    let in_range = aa.le(hi2) & bb.le(hi2);
    let ab_cross = cross_by::<T, R, FMA>(ax, ay, bx, by);
    let zero = ab_cross.eq(k(0.0));
    let inside = aa.le(r2) & bb.le(r2);
    let (g, ta, tb) = edge_frame(ax, ay, bx, by, ab_cross);
    let abs_g = g.abs();
    let w = half_chord(r, abs_g);
    let sector = abs_g.ge(r) | tb.le(-w) | ta.ge(w);
    let (triangle, outside, im, re) = crossing_pieces(g, w, ta, tb);
    let pre = R::select(inside, k(0.5) * ab_cross, triangle);
    let pre = R::select(in_range, pre, R::splat(T::NAN));
    let angle = !zero & in_range & !inside;
    Frame {
        pre: R::select(zero, k(0.0), pre),
        y: R::select(sector, ab_cross, im),
        x: R::select(sector, dot_of(ax, ay, bx, by), re),
        sector: angle & sector,
        plus_sector: angle & !sector & outside,
    }
}

/// The answer of a [`Frame`]: `pre`, the sector, or their sum; `NaN` where
/// the angle has no regular value (both parts zero).
#[inline(always)]
fn finish_lanes<T: DiskFloat, R: Real<Scalar = T>>(r2: R, f: &Frame<R>) -> R {
    let (num, den, swap, regular) = angle::reduce(f.y, f.x);
    let angle_term = R::splat(T::of(0.5)) * r2 * angle::core(num, den, swap, f.x, f.y);
    let value = R::select(
        f.sector,
        angle_term,
        R::select(f.plus_sector, f.pre + angle_term, f.pre),
    );
    R::select(
        (f.sector | f.plus_sector) & !regular,
        R::splat(T::NAN),
        value,
    )
}

/// [`f64::polygon_disk_area`](super::f64::polygon_disk_area) in either
/// precision.
pub(super) fn polygon_disk_area<T: DiskFloat>(r: T, vertices: &[T::V2]) -> T {
    let (zero, one) = (T::of(0.0), T::of(1.0));
    if vertices.len() < 3 || !(r > zero && r.is_finite()) {
        return zero;
    }
    // Rescale by an exact power of two when the disk or the polygon leaves
    // the safe range: no product in the edge tests overflows, no edge's
    // area overflows, and the sum never meets ∞ − ∞.
    let m = vertices
        .iter()
        .filter(|v| v.is_finite())
        .fold(r, |m, v| m.max(v.abs().max_element()));
    let (s, back) = if m <= T::SAFE_HI && r >= T::SAFE_LO {
        (one, one)
    } else {
        let e = rescale_exponent(m);
        (pow2::<T>(-e), pow2::<T>(e))
    };
    let rs = r * s;
    let r2 = rs * rs;
    // The exact answer when no edge comes within r of the centre (a closed
    // polygon: every vertex finite).
    if vertices.iter().all(|v| v.is_finite()) {
        let mut touches = false;
        let mut winding: i64 = 0;
        let mut prev = vertices[vertices.len() - 1] * s;
        for &v in vertices {
            let v = v * s;
            touches = touches || edge_meets_disk::<T>(prev, v, r2);
            winding += crossing::<T>(prev, v);
            prev = v;
        }
        if !touches {
            return T::from_i64(winding) * T::PI * r2 * back * back;
        }
    }
    let mut sum = zero;
    let mut comp = zero;
    let mut prev = vertices[vertices.len() - 1] * s;
    for &v in vertices {
        let v = v * s;
        let x = segment_disk_area(rs, prev, v);
        let t = sum + x;
        comp += if sum.abs() >= x.abs() {
            (sum - t) + x
        } else {
            (x - t) + sum
        };
        sum = t;
        prev = v;
    }
    (sum + comp) * back * back
}

/// Whether the segment `a b` comes within `√r2` of the centre. The distance
/// of the line is `|a × b| / |b − a|` from the accurate cross product (a
/// foot point `a + t (b − a)` would be off by `ε |b − a|`, far more than `r`
/// for long edges); the decision can err only within a few ulps of
/// tangency, where the overlap it would miss is far below the kernel's
/// error.
#[inline]
fn edge_meets_disk<T: Float>(a: T::V2, b: T::V2, r2: T) -> bool {
    if dot::<T>(a, a) < r2 || dot::<T>(b, b) < r2 {
        return true;
    }
    let d = b - a;
    // The foot of the perpendicular lies inside the segment.
    let zero = T::of(0.0);
    let interior = dot::<T>(a, d) < zero && dot::<T>(b, d) > zero;
    let c = cross::<T>(a, b);
    interior && c * c < r2 * dot::<T>(d, d)
}

/// This edge's contribution to the winding number of the origin (`+1`
/// upward crossing with the origin on the left, `−1` downward with it on
/// the right, the half-open rule on `y`), decided exactly.
#[inline]
fn crossing<T: Float>(a: T::V2, b: T::V2) -> i64 {
    use crate::kernel::predicate::{orient2d, Sign};
    // Promotion to f64 is exact for both precisions.
    let wide = |p: T::V2| glam::DVec2::new(p.x().to_f64(), p.y().to_f64());
    let side = || orient2d(wide(a), wide(b), glam::DVec2::ZERO);
    let zero = T::of(0.0);
    if a.y() <= zero {
        if b.y() > zero && side() == Sign::Positive {
            return 1;
        }
    } else if b.y() <= zero && side() == Sign::Negative {
        return -1;
    }
    0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::disk::edge::tests::uniform;

    /// Both forms of the branch-free loop — products by FMA and by
    /// Dekker's split — give `segment_disk_area`'s bits on edges of every
    /// kind (inside, crossing, outside, tangent, degenerate, out of range),
    /// whichever one the processor's dispatch picks. (`tests/disk.rs`
    /// checks the public entry on stiff edges.)
    fn both_branch_free_forms_are_the_scalar_kernel<T: DiskFloat>()
    where
        Lanes<T, LANES>: Real<Scalar = T>,
    {
        let mut unit = uniform::<T>(0x9e37_79b9_7f4a_7c15);
        let k = T::of;
        let mut edges: Vec<(T::V2, T::V2)> = (0..997)
            .map(|i| {
                // Boxes from well inside the unit disk to far outside.
                let s = k([0.5, 1.0, 2.0, 8.0, 1e3][i % 5]);
                let mut p = || {
                    let x = s * (k(2.0) * unit() - k(1.0));
                    T::V2::new(x, s * (k(2.0) * unit() - k(1.0)))
                };
                (p(), p())
            })
            .collect();
        let p = T::V2::new(k(0.25), k(-1.5));
        let hi = k(2.0) * T::SAFE_HI;
        edges.extend([
            (p, p),
            (p, -p),
            (T::V2::ZERO, p),
            (T::V2::new(k(1.0), k(-1.0)), T::V2::new(k(1.0), k(1.0))),
            (T::V2::new(k(1.0), k(0.0)), T::V2::new(k(0.0), k(1.0))),
            (T::V2::new(T::NAN, k(0.0)), p),
            (p, T::V2::new(T::INFINITY, k(0.0))),
            (T::V2::new(-hi, k(0.5)), T::V2::new(hi, k(0.5))),
        ]);
        for r in [k(1.0), k(0.75)] {
            let mut out = vec![k(0.0); edges.len()];
            let marked = areas_branch_free::<T, false>(r, &edges, &mut out);
            let mut fused = vec![k(0.0); edges.len()];
            let marked_fused = areas_branch_free::<T, true>(r, &edges, &mut fused);
            assert!(marked && marked_fused, "the non-finite edges are marked");
            for (i, &(a, b)) in edges.iter().enumerate() {
                let want = segment_disk_area(r, a, b);
                for got in [out[i], fused[i]] {
                    assert!(
                        got.bits() == want.bits() || got.is_nan(),
                        "r={r} a={a} b={b}: {got} vs {want}"
                    );
                }
                // Only edges outside the safe range are left to the scalar
                // path.
                let far = a.abs().max_element().max(b.abs().max_element());
                let in_range = a.is_finite() && b.is_finite() && far <= T::SAFE_HI;
                assert_eq!(out[i].is_nan(), !in_range, "a={a} b={b}");
            }
        }
    }

    test_in_both_precisions!(both_branch_free_forms_are_the_scalar_kernel);
}
