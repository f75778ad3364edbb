//! The exact open-segment–triangle test: whether the open segment `(p, x)`
//! meets a closed triangle ([`segment_blocked`]), and where it crosses it
//! ([`segment_crossing`]).
//!
//! This is the [visibility](crate::definitions#visibility) decision: the light point `x` is visible
//! from `p` iff the open segment `(p, x)` meets no triangle, with an edge
//! shared by two triangles never leaking light. Every occlusion query of
//! the crate ends in it: the BVH's traversals (`softshadow::bvh`), the
//! exact reference's blocked intervals, the hard shadow; the closest hits
//! of the renderer's primary rays end in [`segment_crossing`], the same
//! decision with the crossing point.
//!
//! # Domain
//!
//! Exact for every triangle corner and endpoint coordinate that is zero or
//! of magnitude in `[1e-90, 1e90]` (the domain of [`orient3d`]). Total
//! outside it: a triangle with a non-finite corner, or of zero area, blocks
//! nothing (every `orient3d(a, b, c, ·)` is then zero); no input panics.
//!
//! # Accuracy
//!
//! The decision is exact within the domain: a rounded evaluation of the
//! five determinants with a derived error bound answers almost every call,
//! and only a sign within that bound goes to the exact [`orient3d`]. The
//! crossing's segment parameter has relative error at most `2⁻²³` (in
//! practice a few ulps).
//!
//! # Source
//!
//! The sign-of-volumes test (the endpoints strictly on both sides of the
//! triangle's plane, the line through them on no strict outer side of an
//! edge), decided with the crate's exact predicates
//! ([`crate::kernel::predicate`], Shewchuk 1997); the filter's error bounds
//! use Higham's `γₙ = nu/(1 − nu)` (*Accuracy and Stability of Numerical
//! Algorithms*, §3.1).

use super::predicate::{orient3d, orient3d_value, Sign};
use glam::DVec3;

/// Whether the open segment `(p, x)` meets the closed triangle `t`: the
/// exact test every occlusion query of the crate ends in.
///
/// `true` iff `orient3d(a, b, c, p)` and `orient3d(a, b, c, x)` are nonzero
/// and opposite (the endpoints lie strictly on both sides of the plane), and
/// the three signs `orient3d(p, x, a, b)`, `orient3d(p, x, b, c)`,
/// `orient3d(p, x, c, a)` contain no strictly opposite pair (the line passes
/// inside or on the boundary of the triangle; it cannot be coplanar with it
/// once the endpoints are strictly apart). Consequences:
///
/// - a segment ending on the triangle (a receiver on a face, a light point
///   on an occluder) is not blocked by it;
/// - a segment through an edge or a vertex is blocked: two triangles
///   sharing an edge leave no gap;
/// - a segment in the triangle's plane is not blocked;
/// - a zero-area triangle blocks nothing (every `orient3d(a, b, c, ·)` is
///   zero), nor does one with a non-finite corner (`orient3d` is then zero).
///
/// Speed: the five determinants are first evaluated once in `f64`, sharing
/// the differences from `p`, with a simple valid error bound (`6 γ₁₀` times
/// the product of the rows' max-norms); only a sign within its bound goes
/// to `orient3d`, so the answer is the exact one.
///
/// Exact for coordinates in the domain of
/// [`orient3d`] (`0` or magnitude in
/// `[1e-90, 1e90]`).
#[must_use]
#[inline]
pub fn segment_blocked(p: DVec3, x: DVec3, t: &[DVec3; 3]) -> bool {
    match segment_blocked_filtered(p, x, t) {
        Some(blocked) => blocked,
        None => segment_blocked_exact(p, x, t),
    }
}

/// [`segment_blocked`] by the five `orient3d` calls.
fn segment_blocked_exact(p: DVec3, x: DVec3, t: &[DVec3; 3]) -> bool {
    let [a, b, c] = *t;
    // The edge tests first: they reject the triangles a ray merely passes
    // near. `orient3d(x, u, v, p) = −orient3d(p, x, u, v)` (an odd
    // permutation) flips all three signs alike, which the test ignores.
    let opposite = |s: Sign, t: Sign| s != Sign::Zero && t == s.flip();
    let e0 = orient3d(x, a, b, p);
    let e1 = orient3d(x, b, c, p);
    if opposite(e0, e1) {
        return false;
    }
    let e2 = orient3d(x, c, a, p);
    let all_zero = (e0, e1, e2) == (Sign::Zero, Sign::Zero, Sign::Zero);
    if opposite(e0, e2) || opposite(e1, e2) || all_zero {
        return false;
    }
    let sp = orient3d(a, b, c, p);
    sp != Sign::Zero && orient3d(a, b, c, x) == sp.flip()
}

/// `γ(10)` times the 6 terms of a 3×3 determinant.
const DET3_BOUND: f64 = 6.0 * super::footprint::f64::gamma(10);
/// Covers the absolute error of products that underflow.
const DET3_FLOOR: f64 = 1e-290;

/// `r · (u × v)` rounded, and a bound on its error against the exact
/// determinant of the exact differences the three rows were rounded from:
/// each of the six terms carries at most ten roundings (three differences,
/// two products, the cross product's difference, the dot product's product
/// and two sums), each term is at most `|r|∞ |u|∞ |v|∞`.
#[inline(always)]
fn det3(r: DVec3, u: DVec3, v: DVec3) -> (f64, f64) {
    let det = r.dot(u.cross(v));
    let bound =
        DET3_BOUND * (r.abs().max_element() * u.abs().max_element()) * v.abs().max_element()
            + DET3_FLOOR;
    (det, bound)
}

/// The sign of `(det, bound)` when certain.
#[inline(always)]
fn certain(det: (f64, f64)) -> Option<Sign> {
    if det.0 > det.1 {
        Some(Sign::Positive)
    } else if det.0 < -det.1 {
        Some(Sign::Negative)
    } else {
        None
    }
}

/// [`segment_blocked`] by one rounded evaluation of the same five
/// determinants (sharing the differences from `p`) with a crude but valid
/// error bound ([`det3`]); `None` when a sign it needs is uncertain. Finite
/// inputs only.
#[inline(always)]
fn segment_blocked_filtered(p: DVec3, x: DVec3, t: &[DVec3; 3]) -> Option<bool> {
    let [a, b, c] = *t;
    let d = x - p;
    let (pa, pb, pc) = (a - p, b - p, c - p);
    // orient3d(x, a, b, p) = det[x − p; a − p; b − p], and so on.
    let e0 = certain(det3(d, pa, pb));
    let e1 = certain(det3(d, pb, pc));
    if let (Some(s0), Some(s1)) = (e0, e1) {
        if s0 != s1 {
            return Some(false);
        }
    }
    let e2 = certain(det3(d, pc, pa));
    let (s0, s1, s2) = (e0?, e1?, e2?);
    if s0 != s1 || s0 != s2 {
        return Some(false);
    }
    // orient3d(a, b, c, p) and orient3d(a, b, c, x).
    let sp = certain(det3(pa, pb, pc))?;
    let sx = certain(det3(a - x, b - x, c - x))?;
    Some(sp != sx)
}

/// Where the open segment `(p, x)` crosses the closed triangle `t`: `Some(u)`
/// with `u ∈ (0, 1]` the segment parameter of the crossing point
/// `p + u (x − p)`, exactly when [`segment_blocked`]`(p, x, t)` (the same
/// exact decision: edges and vertices count, the endpoints do not, a
/// segment in the triangle's plane crosses nothing); `None` otherwise.
///
/// `u` comes from the plane: with `f(q) = orient3d(a, b, c, q)` (affine in
/// `q`), `u = f(p) / (f(p) − f(x))`. Accuracy: relative error at most
/// `2⁻²³` — the rounded evaluation is used when its error bound says so
/// (it is then in practice within a few ulps),
/// otherwise [`orient3d_value`] (relative error `2⁻⁴⁰` each, and the two
/// values have opposite signs, so their difference does not cancel). `u`
/// is rounded up to the least positive `f64` if it underflows, and never
/// exceeds 1.
///
/// Same domain as [`segment_blocked`].
#[must_use]
#[inline]
pub fn segment_crossing(p: DVec3, x: DVec3, t: &[DVec3; 3]) -> Option<f64> {
    let d = x - p;
    crossing(p, x, d, d.abs().max_element(), t)
}

/// [`segment_crossing`] with `d = x − p` and `|d|∞` given (the BVH's
/// closest-hit query computes them once per ray).
#[inline(always)]
pub(crate) fn crossing(p: DVec3, x: DVec3, d: DVec3, d_norm: f64, t: &[DVec3; 3]) -> Option<f64> {
    match crossing_filtered(p, d, d_norm, t) {
        Some(u) => u,
        None => segment_blocked_exact(p, x, t).then(|| crossing_accurate(p, x, t)),
    }
}

/// The bound on the relative error of `f(p)` and of `Σeᵢ` below which the
/// rounded crossing is kept (see [`crossing_filtered`]): `u` is then within
/// `2⁻²⁴ + 2⁻⁵³` of the true value. (The bounds are crude — products of
/// max-norms — and the rounded `u` is in practice within a few ulps; a
/// tighter threshold sends ordinary primary rays, with their small
/// triangles seen from afar, to the expansion arithmetic.)
const CROSSING_REL: f64 = 1.0 / (1u64 << 25) as f64;

/// What the filtered crossing needs of a triangle seen from the
/// segment's start `p`, before the segment's direction: the corners less
/// `p` and their max-norms, and two of the three cross products (the
/// third, `pc × pa`, is needed only past the filter's first exit).
struct Seen {
    pa: DVec3,
    pc: DVec3,
    ma: f64,
    mb: f64,
    mc: f64,
    /// `pb × pc`, `pa × pb`.
    cbc: DVec3,
    cab: DVec3,
}

impl Seen {
    #[inline(always)]
    fn from(p: DVec3, t: &[DVec3; 3]) -> Seen {
        let [a, b, c] = *t;
        let (pa, pb, pc) = (a - p, b - p, c - p);
        Seen {
            pa,
            pc,
            ma: pa.abs().max_element(),
            mb: pb.abs().max_element(),
            mc: pc.abs().max_element(),
            cbc: pb.cross(pc),
            cab: pa.cross(pb),
        }
    }
}

/// [`segment_crossing`] by one rounded evaluation of the determinants of
/// [`segment_blocked_filtered`] (the three edge determinants
/// `eᵢ = d · (pᵢ × pᵢ₊₁)` with `pᵢ` the corners minus `p`, and
/// `f(p) = pa · (pb × pc)`, sharing the cross product of `e₁`): `None`
/// when a sign it needs is uncertain or `u`'s error bound exceeds
/// `2⁻²⁴`; `Some(None)` for a certain miss.
///
/// The plane's value at `x` needs no further product: `f` is affine with
/// linear part `−n`, `n = (b − a) × (c − a)`, and `e₀ + e₁ + e₂ = d · n`
/// exactly, so `f(x) = f(p) − (e₀ + e₁ + e₂)`, and `u = f(p) / Σeᵢ`.
#[inline(always)]
fn crossing_filtered(p: DVec3, d: DVec3, d_norm: f64, t: &[DVec3; 3]) -> Option<Option<f64>> {
    let seen = Seen::from(p, t);
    let (e0, e1) = (d.dot(seen.cab), d.dot(seen.cbc));
    let (b0, b1) = (
        DET3_BOUND * (d_norm * seen.ma) * seen.mb + DET3_FLOOR,
        DET3_BOUND * (d_norm * seen.mb) * seen.mc + DET3_FLOOR,
    );
    // Two edges certainly opposite: the line passes outside (most boxes
    // the traversal reaches hold a triangle the ray misses).
    if (e0 > b0 && e1 < -b1) || (e0 < -b0 && e1 > b1) {
        return Some(None);
    }
    let cca = seen.pc.cross(seen.pa);
    let e2 = d.dot(cca);
    let b2 = DET3_BOUND * (d_norm * seen.mc) * seen.ma + DET3_FLOOR;
    let pos = u8::from(e0 > b0) | u8::from(e1 > b1) << 1 | u8::from(e2 > b2) << 2;
    let neg = u8::from(e0 < -b0) | u8::from(e1 < -b1) << 1 | u8::from(e2 < -b2) << 2;
    if pos != 0 && neg != 0 {
        return Some(None);
    }
    if pos != 7 && neg != 7 {
        return None;
    }
    // The line passes strictly inside; `Σeᵢ = d · n` has the common sign,
    // and its computed value the error of the three terms plus two sums of
    // same-signed terms (`γ₂`).
    let sum = e0 + e1 + e2;
    let sum_bound = (b0 + b1 + b2) * (1.0 + f64::EPSILON) + sum.abs() * (2.0 * f64::EPSILON);
    let fp = seen.pa.dot(seen.cbc);
    let fp_bound = DET3_BOUND * (seen.ma * seen.mb) * seen.mc + DET3_FLOOR;
    if fp.abs() <= fp_bound {
        return None;
    }
    if (fp > 0.0) != (sum > 0.0) {
        // The plane is crossed behind `p`.
        return Some(None);
    }
    // `f(x) = fp − sum` has the other sign iff `|Σeᵢ| > |f(p)|` exactly:
    // decided when the rounded difference clears both bounds (each
    // rounding below covered by a factor `1 ± 2⁻⁵²`).
    let both = (sum_bound + fp_bound) * (1.0 + f64::EPSILON);
    let gap = (sum.abs() - fp.abs()) * (1.0 - f64::EPSILON);
    if gap.is_nan() || gap <= both {
        // Certainly beyond `x`, or too close to `x` to tell.
        let beyond = (fp.abs() - sum.abs()) * (1.0 - f64::EPSILON) > both;
        return if beyond { Some(None) } else { None };
    }
    if fp_bound > fp.abs() * CROSSING_REL || sum_bound > sum.abs() * CROSSING_REL {
        return None;
    }
    Some(Some((fp / sum).max(f64::from_bits(1))))
}

/// What [`crossings_filtered`] found for one lane.
// Used by the BVH's packets alone (feature `bvh`).
#[cfg_attr(not(feature = "bvh"), allow(dead_code))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Filtered {
    /// Certainly no crossing.
    Miss,
    /// The crossing at the lane's `u`.
    Hit,
    /// Not decided: [`crossing`] decides.
    Unsure,
}

/// [`crossing_filtered`] for `N` segments from one origin `p` against one
/// triangle, lane `l` the segment along `(d[0][l], d[1][l], d[2][l])`
/// (its max-norm `d_norm[l]`): each lane's verdict and `u` (meaningful
/// where [`Filtered::Hit`]) are the scalar function's — `Some(None)` a
/// miss, `Some(Some(u))` a hit, `None` unsure — the same operations on the
/// same values in the same order (the terms that depend on the origin and
/// the triangle alone computed once), every rule evaluated and the first
/// that applies, in the scalar function's order, taken. (The scalar
/// function's first rule, two edges certainly opposite, is a case of its
/// second.)
#[cfg_attr(not(feature = "bvh"), allow(dead_code))]
#[inline(always)]
pub(crate) fn crossings_filtered<const N: usize>(
    p: DVec3,
    d: &[[f64; N]; 3],
    d_norm: &[f64; N],
    t: &[DVec3; 3],
) -> ([Filtered; N], [f64; N]) {
    let seen = Seen::from(p, t);
    let cca = seen.pc.cross(seen.pa);
    let fp = seen.pa.dot(seen.cbc);
    let fp_bound = DET3_BOUND * (seen.ma * seen.mb) * seen.mc + DET3_FLOOR;
    let flat = fp.abs() <= fp_bound;
    let dot = |v: DVec3, i: usize| (d[0][i] * v.x) + (d[1][i] * v.y) + (d[2][i] * v.z);
    let mut verdict = [Filtered::Unsure; N];
    let mut u = [0.0; N];
    for i in 0..N {
        let (e0, e1, e2) = (dot(seen.cab, i), dot(seen.cbc, i), dot(cca, i));
        let dn = d_norm[i];
        let b0 = DET3_BOUND * (dn * seen.ma) * seen.mb + DET3_FLOOR;
        let b1 = DET3_BOUND * (dn * seen.mb) * seen.mc + DET3_FLOOR;
        let b2 = DET3_BOUND * (dn * seen.mc) * seen.ma + DET3_FLOOR;
        let (p0, p1, p2) = (e0 > b0, e1 > b1, e2 > b2);
        let (n0, n1, n2) = (e0 < -b0, e1 < -b1, e2 < -b2);
        let sum = e0 + e1 + e2;
        let sum_bound = (b0 + b1 + b2) * (1.0 + f64::EPSILON) + sum.abs() * (2.0 * f64::EPSILON);
        let both = (sum_bound + fp_bound) * (1.0 + f64::EPSILON);
        let gap = (sum.abs() - fp.abs()) * (1.0 - f64::EPSILON);
        let beyond = (fp.abs() - sum.abs()) * (1.0 - f64::EPSILON) > both;
        // The scalar function's rules in its order, without branches (so
        // that the lanes run side by side): the first that applies decides.
        let opposite = (p0 | p1 | p2) & (n0 | n1 | n2);
        let mixed = !(p0 & p1 & p2) & !(n0 & n1 & n2);
        let behind = (fp > 0.0) != (sum > 0.0);
        let near_x = gap.is_nan() | (gap <= both);
        let loose = (fp_bound > fp.abs() * CROSSING_REL) | (sum_bound > sum.abs() * CROSSING_REL);
        let open = !opposite & !mixed & !flat;
        let miss = opposite | (open & (behind | (near_x & beyond)));
        let hit = open & !behind & !near_x & !loose;
        let v = if hit {
            Filtered::Hit
        } else if miss {
            Filtered::Miss
        } else {
            Filtered::Unsure
        };
        verdict[i] = v;
        u[i] = (fp / sum).max(f64::from_bits(1));
    }
    (verdict, u)
}

/// `u` for a segment known to cross the triangle, from the two plane values
/// of [`orient3d_value`] (opposite signs, each within `2⁻⁴⁰` relative).
fn crossing_accurate(p: DVec3, x: DVec3, t: &[DVec3; 3]) -> f64 {
    let [a, b, c] = *t;
    let fp = orient3d_value(a, b, c, p);
    let fx = orient3d_value(a, b, c, x);
    (fp / (fp - fx)).clamp(f64::from_bits(1), 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arbitrary::Rng;

    /// [`crossings_filtered`] is [`crossing_filtered`] lane by lane, bit
    /// for bit, on segments from one origin (as a packet's), against
    /// triangles they cross, graze at an edge or a
    /// corner, miss, or lie nearly in the plane of, at scales from `10⁻⁶`
    /// to `10⁶`; every verdict is seen.
    #[test]
    fn lanes_are_the_one_segment_filter() {
        let mut rng = Rng::new(17);
        let mut seen = [0usize; 3];
        for case in 0..4000 {
            let scale = rng.log_uniform(-6.0, 6.0);
            let point = |rng: &mut Rng| {
                DVec3::new(
                    rng.uniform(-1.0, 1.0),
                    rng.uniform(-1.0, 1.0),
                    rng.uniform(-1.0, 1.0),
                ) * scale
            };
            let mut t = [point(&mut rng), point(&mut rng), point(&mut rng)];
            let shared = point(&mut rng);
            if case % 4 == 0 {
                // Nearly edge-on from the shared origin: a corner pulled
                // to within a relative `10⁻⁹`–`10⁻³` of the plane through
                // the origin and the other two corners.
                let n = (t[0] - shared).cross(t[1] - shared);
                let off = n.dot(t[2] - shared) / n.length_squared();
                t[2] -= n * off * (1.0 - rng.log_uniform(-9.0, -3.0));
            }
            let p = [shared; 8];
            let x: [DVec3; 8] = core::array::from_fn(|l| {
                // Through a corner, an edge's midpoint, the centre, or anywhere,
                // and on to twice as far (or stopping short).
                let aim = match rng.below(4) {
                    0 => t[rng.below(3) as usize],
                    1 => (t[0] + t[1]) * 0.5,
                    2 => (t[0] + t[1] + t[2]) / 3.0,
                    _ => point(&mut rng),
                };
                p[l] + (aim - p[l]) * rng.uniform(0.5, 2.0)
            });
            let d: [DVec3; 8] = core::array::from_fn(|l| x[l] - p[l]);
            let soa = |v: &[DVec3; 8]| -> [[f64; 8]; 3] {
                core::array::from_fn(|k| core::array::from_fn(|l| v[l][k]))
            };
            let norms = d.map(|d| d.abs().max_element());
            let (verdict, u) = crossings_filtered(shared, &soa(&d), &norms, &t);
            for l in 0..8 {
                let one = crossing_filtered(p[l], d[l], norms[l], &t);
                let lane = match verdict[l] {
                    Filtered::Miss => Some(None),
                    Filtered::Hit => Some(Some(u[l])),
                    Filtered::Unsure => None,
                };
                assert_eq!(
                    lane.map(|v| v.map(f64::to_bits)),
                    one.map(|v| v.map(f64::to_bits)),
                    "case {case}, lane {l}"
                );
                seen[verdict[l] as usize] += 1;
            }
        }
        assert!(seen.iter().all(|&n| n > 500), "{seen:?}");
    }
}
