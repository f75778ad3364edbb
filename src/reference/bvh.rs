//! A bounding volume hierarchy over [`Occluders`], for the occlusion rays of
//! the Monte Carlo reference, for culling the triangles a receiver's view
//! of the light can meet (the exact reference), and for the renderer's
//! primary rays ([`Bvh::closest_hit`]: the nearest triangle on a ray,
//! decided with the same exact test).
//!
//! # How it decides
//!
//! The tree is built by `obvhs` (PLOC with reinsertion, `Bvh2`) over boxes
//! computed in `f64` and rounded *outward* to `f32`, then collapsed into a
//! 4-wide tree of our own — one 64-byte node per four children, boxes
//! quantised outward to 8 bits per plane — whose traversal is conservative
//! (see [`Bvh::segment_unoccluded`]): the `f32` tree only ever prunes boxes
//! the true `f64` segment cannot meet. Every triangle the traversal reaches is decided
//! exactly by [`segment_blocked`], in `f64` with the exact
//! [`orient3d`]. The answer is therefore
//! exactly DESIGN §1's: the light point `x` is visible from `p` iff the open
//! segment `(p, x)` meets no triangle, with an edge shared by two triangles
//! never leaking light.
//!
//! obvhs's own traversals are not used for rays: its `Triangle::intersect` is
//! not watertight, its CWBVH node test clamps `t` below at `1e-4` (a box near
//! the receiver would be skipped), and its slab tests round without a bound.
//!
//! # Domain
//!
//! Exact for every triangle corner and endpoint coordinate that is zero or of
//! magnitude in `[1e-90, 1e90]` (the domain of `orient3d`). The `f32` tree
//! holds triangles within `±2⁶⁰` (`1.2e18`; see `TREE_RANGE`); farther ones
//! are tested by every query, and queries reaching beyond `f32::MAX`
//! (`3.4e38`) test every triangle (slow, still exact).
//! Triangles with a non-finite corner are left out at build and block
//! nothing; zero-area triangles block nothing (the predicate says so).

use super::Occluders;
use crate::kernel::predicate::{orient3d, orient3d_value, Sign};
use glam::{DVec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::bvh2::builder::build_bvh2;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::bvh2::Bvh2;
use obvhs::BvhBuildParams;
use rayon::prelude::*;
use std::fmt;
use std::time::Duration;

/// Children per node of our tree.
const WIDTH: usize = 4;
/// `child` of an empty lane.
const EMPTY: u32 = u32::MAX;
/// Stack entries kept on the machine stack; deeper trees use a heap stack.
const STACK: usize = 64;

/// Whether the open segment `(p, x)` meets the closed triangle `t`: the
/// exact test every query of this module ends in.
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

/// `γ₁₀ = 10u/(1 − 10u)`, `u = 2⁻⁵³`, times the 6 terms of a 3×3
/// determinant.
const DET3_BOUND: f64 = 6.0 * 10.0 * (f64::EPSILON / 2.0) / (1.0 - 10.0 * (f64::EPSILON / 2.0));
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

/// [`segment_crossing`] with `d = x − p` and `|d|∞` given.
#[inline(always)]
fn crossing(p: DVec3, x: DVec3, d: DVec3, d_norm: f64, t: &[DVec3; 3]) -> Option<f64> {
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
    let [a, b, c] = *t;
    let (pa, pb, pc) = (a - p, b - p, c - p);
    let (ma, mb, mc) = (
        pa.abs().max_element(),
        pb.abs().max_element(),
        pc.abs().max_element(),
    );
    let cbc = pb.cross(pc);
    let cab = pa.cross(pb);
    let (e0, e1) = (d.dot(cab), d.dot(cbc));
    let (b0, b1) = (
        DET3_BOUND * (d_norm * ma) * mb + DET3_FLOOR,
        DET3_BOUND * (d_norm * mb) * mc + DET3_FLOOR,
    );
    // Two edges certainly opposite: the line passes outside (most boxes
    // the traversal reaches hold a triangle the ray misses).
    if (e0 > b0 && e1 < -b1) || (e0 < -b0 && e1 > b1) {
        return Some(None);
    }
    let cca = pc.cross(pa);
    let e2 = d.dot(cca);
    let b2 = DET3_BOUND * (d_norm * mc) * ma + DET3_FLOOR;
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
    let fp = pa.dot(cbc);
    let fp_bound = DET3_BOUND * (ma * mb) * mc + DET3_FLOOR;
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

/// `u` for a segment known to cross the triangle, from the two plane values
/// of [`orient3d_value`] (opposite signs, each within `2⁻⁴⁰` relative).
fn crossing_accurate(p: DVec3, x: DVec3, t: &[DVec3; 3]) -> f64 {
    let [a, b, c] = *t;
    let fp = orient3d_value(a, b, c, p);
    let fx = orient3d_value(a, b, c, x);
    (fp / (fp - fx)).clamp(f64::from_bits(1), 1.0)
}

/// A node of the 4-wide tree, one 64-byte cache line: the four child boxes
/// quantised to 8 bits per plane on a per-axis power-of-two grid (the
/// compressed wide nodes of Ylitie, Karras and Laine, "Efficient
/// Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs", 2017),
/// in structure-of-arrays form (the slab test runs over the four lanes at
/// once).
///
/// A plane decodes to [`decode`]`(origin, q, scale)`, one `f32` product (exact:
/// `q < 2⁸`, `scale` a power of two) and one rounded sum; the build chooses
/// each `q` by evaluating that very expression, so the decoded box contains
/// the child's `f32` box — rounding included, the traversal computes the
/// same bits.
#[derive(Clone, Copy)]
#[repr(C, align(64))]
struct Node {
    /// Per axis: the grid's origin (the least child minimum).
    origin: [f32; 3],
    /// Per axis: the grid step, a power of two `2ᵉ`, `e ∈ [−126, 127]`.
    scale: [f32; 3],
    /// `q[side][axis][lane]`: quantised box minima (`side` 0; each decodes
    /// to at most the `f32` minimum) and maxima (`side` 1; at least the
    /// maximum).
    q: [[[u8; WIDTH]; 3]; 2],
    /// Inner child: its node index. Leaf: [`LEAF`] `|` its triangle's index
    /// in `Bvh::triangles`. Empty lane: [`EMPTY`].
    child: [u32; WIDTH],
}

/// The flag of a leaf in [`Node::child`].
const LEAF: u32 = 1 << 31;

/// A decoded plane: `origin + q · scale`. The one definition the build and
/// the traversal share, so both round alike (Rust never contracts to FMA).
#[inline(always)]
fn decode(origin: f32, q: u8, scale: f32) -> f32 {
    origin + f32::from(q) * scale
}

impl Node {
    const EMPTY_NODE: Node = Node {
        origin: [0.0; 3],
        scale: [1.0; 3],
        q: [[[0; WIDTH]; 3]; 2],
        child: [EMPTY; WIDTH],
    };

    /// Quantises `boxes` (at most [`WIDTH`]; `f32` boxes with `lo ≤ hi`,
    /// finite) into lanes `0..boxes.len()`, conservatively (see [`Node`]).
    fn quantised(boxes: &[([f32; 3], [f32; 3])]) -> Node {
        let mut node = Node::EMPTY_NODE;
        for axis in 0..3 {
            let origin = boxes
                .iter()
                .map(|b| b.0[axis])
                .fold(f32::INFINITY, f32::min);
            let top = boxes
                .iter()
                .map(|b| b.1[axis])
                .fold(f32::NEG_INFINITY, f32::max);
            let extent = f64::from(top) - f64::from(origin);
            let guess = (extent / 255.0).log2().ceil();
            let mut e = if guess.is_finite() {
                guess as i32
            } else {
                -126
            }
            .clamp(-126, 127);
            // `decode(origin, 255, 2¹²⁷)` is `+∞`: the loop ends.
            while decode(origin, 255, pow2(e)) < top {
                e += 1;
            }
            let scale = pow2(e);
            node.origin[axis] = origin;
            node.scale[axis] = scale;
            for (lane, b) in boxes.iter().enumerate() {
                // `decode` is nondecreasing in `q`; `decode(·, 0, ·)` is
                // `origin ≤ lo` and `decode(·, 255, ·) ≥ top ≥ hi`.
                let (lo, hi) = (b.0[axis], b.1[axis]);
                let fit = |q: f64| q.clamp(0.0, 255.0) as u8;
                let mut q = fit(((f64::from(lo) - f64::from(origin)) / f64::from(scale)).floor());
                while q > 0 && decode(origin, q, scale) > lo {
                    q -= 1;
                }
                while q < 255 && decode(origin, q + 1, scale) <= lo {
                    q += 1;
                }
                node.q[0][axis][lane] = q;
                let mut q = fit(((f64::from(hi) - f64::from(origin)) / f64::from(scale)).ceil());
                while q < 255 && decode(origin, q, scale) < hi {
                    q += 1;
                }
                while q > 0 && decode(origin, q - 1, scale) >= hi {
                    q -= 1;
                }
                node.q[1][axis][lane] = q;
            }
        }
        node
    }

    /// The decoded box of `lane`: `(lo, hi)`.
    fn lane_box(&self, lane: usize) -> (DVec3, DVec3) {
        let plane = |q: &[[u8; WIDTH]; 3], axis: usize| {
            f64::from(decode(self.origin[axis], q[axis][lane], self.scale[axis]))
        };
        (
            DVec3::new(
                plane(&self.q[0], 0),
                plane(&self.q[0], 1),
                plane(&self.q[0], 2),
            ),
            DVec3::new(
                plane(&self.q[1], 0),
                plane(&self.q[1], 1),
                plane(&self.q[1], 2),
            ),
        )
    }
}

/// `2ᵉ` for `e ∈ [−126, 127]` (normal `f32`).
fn pow2(e: i32) -> f32 {
    f32::from_bits(((e + 127) as u32) << 23)
}

/// An entry of a node under construction: an obvhs node, or a run of
/// `primitive_indices` (a leaf of more than one triangle, split in halves).
#[derive(Clone, Copy)]
enum Item {
    Node(usize),
    Prims(usize, usize),
}

/// A BVH over a scene's occluders (owns them). Immutable once built, `Sync`:
/// share one between threads.
pub struct Bvh {
    occluders: Occluders,
    nodes: Vec<Node>,
    /// The finite triangles, in leaf order.
    triangles: Vec<[DVec3; 3]>,
    /// The index in `occluders` of each of `triangles`.
    ids: Vec<u32>,
    /// Stack entries a traversal can need.
    stack_need: usize,
    /// Triangles with a coordinate beyond [`TREE_RANGE`], kept out of the
    /// tree and tested by every query, and their indices in `occluders`.
    outliers: Vec<[DVec3; 3]>,
    outlier_ids: Vec<u32>,
    /// The exact bounding box `(lo, hi)` of every finite triangle (in the
    /// tree or not); `None` when there is none.
    bounds: Option<(DVec3, DVec3)>,
}

/// The largest coordinate magnitude a triangle in the tree may have, 2⁶⁰:
/// the builder works with `f32` surface areas, and any box within
/// `±2⁶⁰` has a finite one (a side of at most 2⁶¹, an area below 2¹²⁴).
/// Beyond it areas overflow to ∞, their differences are NaN, and obvhs's
/// PLOC builder can pair a node with itself (found by the `exact` fuzz
/// target). Far triangles are rare; they are tested by every query.
const TREE_RANGE: f64 = (1u64 << 60) as f64;

impl fmt::Debug for Bvh {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Bvh")
            .field("triangles", &self.occluders.len())
            .field("indexed", &self.triangles.len())
            .field("nodes", &self.nodes.len())
            .finish()
    }
}

/// `v` rounded down to an `f32`, clamped to the finite range.
fn f32_down(v: f64) -> f32 {
    let r = v as f32;
    let r = if f64::from(r) > v { r.next_down() } else { r };
    r.clamp(-f32::MAX, f32::MAX)
}

/// `v` rounded up to an `f32`, clamped to the finite range.
fn f32_up(v: f64) -> f32 {
    let r = v as f32;
    let r = if f64::from(r) < v { r.next_up() } else { r };
    r.clamp(-f32::MAX, f32::MAX)
}

/// Whether every coordinate is finite and at most `f32::MAX` in magnitude:
/// the region the `f32` boxes are valid in (see [`Bvh::new`]).
fn in_f32_range(v: DVec3) -> bool {
    v.abs().max_element() <= f64::from(f32::MAX)
}

impl Bvh {
    /// Builds the hierarchy (single-threaded; about 0.3 s per 100k
    /// triangles).
    ///
    /// Each triangle's box is computed in `f64` and rounded outward to `f32`,
    /// so it contains the triangle exactly; coordinates beyond `f32::MAX`
    /// clamp to it, which keeps the box valid inside `[−f32::MAX,
    /// f32::MAX]³`, the only region queries use the tree in. Triangles with
    /// a non-finite corner are left out.
    #[must_use]
    pub fn new(occluders: Occluders) -> Bvh {
        let mut boxes = Vec::with_capacity(occluders.len());
        let mut kept = Vec::with_capacity(occluders.len());
        let (mut outliers, mut outlier_ids) = (Vec::new(), Vec::new());
        let mut bounds: Option<(DVec3, DVec3)> = None;
        for (i, t) in occluders.triangles().iter().enumerate() {
            if !t.iter().all(|v| v.is_finite()) {
                continue;
            }
            let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
            bounds = Some(bounds.map_or((lo, hi), |(l, h)| (l.min(lo), h.max(hi))));
            if t.iter().any(|v| v.abs().max_element() > TREE_RANGE) {
                outliers.push(*t);
                outlier_ids.push(i as u32);
                continue;
            }
            let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
            boxes.push(Aabb::new(
                Vec3A::new(f32_down(lo.x), f32_down(lo.y), f32_down(lo.z)),
                Vec3A::new(f32_up(hi.x), f32_up(hi.y), f32_up(hi.z)),
            ));
            kept.push(i as u32);
        }
        let mut bvh = Bvh {
            occluders,
            nodes: Vec::new(),
            triangles: Vec::with_capacity(kept.len()),
            ids: Vec::with_capacity(kept.len()),
            stack_need: 1,
            outliers,
            outlier_ids,
            bounds,
        };
        if kept.len() >= LEAF as usize {
            // Beyond the leaf encoding (2³¹ triangles, 144 GiB of corners):
            // no tree, every query tests every triangle.
            for &id in &kept {
                bvh.ids.push(id);
                bvh.triangles.push(bvh.occluders.triangles()[id as usize]);
            }
            return bvh;
        }
        if boxes.is_empty() {
            return bvh;
        }
        // One triangle per leaf: the 4-wide node test then culls single
        // triangles, cheaper than their exact test (measured: 1.2–2× the
        // rays/s of 4 or 8 per leaf on benches/rays.rs). obvhs's slowest
        // preset: its two full reinsertion passes visit 16 % fewer nodes
        // per ray than `medium_build` on the 100k-triangle soup of
        // `examples/ray_corpus.rs` (soup rays/s 1.26×), for a build about
        // 4× as long. The passes run here rather than in `build_bvh2`,
        // whose debug-build validation rejects their result when many
        // boxes coincide (a stale `max_depth`, which only obvhs's own
        // traversal uses).
        let preset = BvhBuildParams::very_slow_build();
        let params = BvhBuildParams {
            max_prims_per_leaf: 1,
            reinsertion_batch_ratio: 0.0,
            ..preset
        };
        let mut tree = build_bvh2(&boxes, params, &mut Duration::default());
        let mut reinsertion = ReinsertionOptimizer::default();
        let ratio = preset.reinsertion_batch_ratio;
        reinsertion.run(&mut tree, ratio, None);
        reinsertion.run(
            &mut tree,
            ratio * preset.post_collapse_reinsertion_batch_ratio_multiplier,
            None,
        );
        bvh.collapse(&tree, &boxes, &kept);
        bvh
    }

    /// Turns obvhs's binary tree into ours: each node takes up to [`WIDTH`]
    /// descendants (repeatedly opening the entry of largest area), every
    /// leaf lane holds one triangle, and the triangles are copied in leaf
    /// order.
    fn collapse(&mut self, tree: &Bvh2, boxes: &[Aabb], kept: &[u32]) {
        let prims = &tree.primitive_indices;
        let aabb = |item: Item| -> Aabb {
            match item {
                Item::Node(n) => *tree.nodes[n].aabb(),
                Item::Prims(first, count) => prims[first..first + count]
                    .iter()
                    .fold(Aabb::empty(), |b, &i| b.union(&boxes[i as usize])),
            }
        };
        // An obvhs leaf is the run of its primitives.
        let normal = |item: Item| match item {
            Item::Node(n) if tree.nodes[n].is_leaf() => {
                let node = &tree.nodes[n];
                Item::Prims(node.first_index as usize, node.prim_count as usize)
            }
            other => other,
        };
        let children = |item: Item| -> Option<[Item; 2]> {
            match item {
                Item::Node(n) => {
                    let first = tree.nodes[n].first_index as usize;
                    Some([normal(Item::Node(first)), normal(Item::Node(first + 1))])
                }
                Item::Prims(first, count) if count > 1 => {
                    let half = count / 2;
                    Some([
                        Item::Prims(first, half),
                        Item::Prims(first + half, count - half),
                    ])
                }
                Item::Prims(..) => None,
            }
        };
        // (entry, our node, depth of our node)
        let mut work = vec![(normal(Item::Node(0)), 0usize, 1usize)];
        self.nodes.push(Node::EMPTY_NODE);
        let mut depth = 1;
        while let Some((src, dst, level)) = work.pop() {
            depth = depth.max(level);
            let mut lanes = vec![src];
            while lanes.len() < WIDTH {
                let widest = lanes
                    .iter()
                    .enumerate()
                    .filter(|(_, &item)| children(item).is_some())
                    .max_by(|(_, &a), (_, &b)| aabb(a).half_area().total_cmp(&aabb(b).half_area()))
                    .map(|(k, _)| k);
                let Some(k) = widest else { break };
                let [left, right] = children(lanes[k]).expect("filtered");
                lanes[k] = left;
                lanes.push(right);
            }
            // (obvhs leaves are never empty; an empty run would not end.)
            lanes.retain(|item| !matches!(item, Item::Prims(_, 0)));
            let lane_boxes: Vec<([f32; 3], [f32; 3])> = lanes
                .iter()
                .map(|&item| {
                    let b = aabb(item);
                    (b.min.to_array(), b.max.to_array())
                })
                .collect();
            let mut node = Node::quantised(&lane_boxes);
            for (lane, &item) in lanes.iter().enumerate() {
                node.child[lane] = match item {
                    Item::Prims(first, 1) => {
                        let id = kept[prims[first] as usize];
                        self.ids.push(id);
                        self.triangles.push(self.occluders.triangles()[id as usize]);
                        LEAF | (self.triangles.len() - 1) as u32
                    }
                    _ => {
                        work.push((item, self.nodes.len(), level + 1));
                        self.nodes.push(Node::EMPTY_NODE);
                        (self.nodes.len() - 1) as u32
                    }
                };
            }
            self.nodes[dst] = node;
        }
        self.stack_need = depth * (WIDTH - 1) + 1;
    }

    /// The triangles it was built over.
    #[must_use]
    pub fn occluders(&self) -> &Occluders {
        &self.occluders
    }

    /// Whether the open segment `(p, x)` meets no triangle, decided exactly
    /// by [`segment_blocked`] on every triangle whose box the segment may
    /// meet (any-hit: stops at the first blocker). Endpoints are not part of
    /// the segment: a receiver on a face is not shadowed by that face.
    ///
    /// Conservative `f32` traversal. With `o = fl32(p)` and
    /// `d = fl32(fl64(x − p))` (a component below `2⁻¹⁰⁰` in magnitude
    /// replaced by `±2⁻¹⁰⁰`), the `f32` ray `o + t d` stays, for every
    /// `t ∈ [0, 1]`, within `δᵢ/2` of the true point `p + t (x − p)` on each
    /// axis, where `δᵢ = 2⁻²¹ (|pᵢ| + |xᵢ − pᵢ|) + 2⁻⁹⁸`: the two roundings to
    /// `f32` contribute at most `2⁻²⁴` relative each, the `f64` difference
    /// `2⁻⁵³`, the substitution `2⁻¹⁰⁰` — a factor-2 margin above `δᵢ/2`
    /// absorbs the `f64` arithmetic computing `δ` and `o ± δ`. Let `B` be a
    /// lane's decoded box: its planes are the `f32` values
    /// `origin + q · scale` (the node's 8-bit `q` on its power-of-two grid,
    /// one rounding), computed with the same operations at
    /// build and at query (so bit-identical), and the build chose each `q`
    /// so that the decoded plane lies on or outside the `f32` box, itself
    /// rounded outward from the `f64` triangles: `B` contains every
    /// triangle below the lane exactly (checked by
    /// `tests::decoded_boxes_contain_their_triangles`). So if the true
    /// segment meets `B` at `t*`, the exact `f32` ray lies inside `B` grown
    /// by `δ` for all `t` within `δᵢ/|dᵢ| ≥ 2⁻²²` of `t*` (clipped to
    /// `[0, 1]`): the slab intervals overlap by a width of at least `2⁻²²`.
    /// The slab test grows the box by at least `δ` through the origins it
    /// subtracts: `o ± δ′` with `δ′ = δ (1 + 2⁻²²) + |o| 2⁻²³`, rounded to
    /// nearest `f32`, lies on or beyond `o ± δ`, since rounding moves it by
    /// at most `2⁻²⁴ (|o| + δ′)`, less than the added `δ 2⁻²² + |o| 2⁻²³`
    /// (with room for the `f64` arithmetic); where that passes `±f32::MAX`
    /// it is clamped there, still beyond every plane. Each rounded
    /// `t = (plane − origin) · (1/d)` carries at most three roundings
    /// (relative error `γ₃ ≈ 3·2⁻²⁴`, sign exact; the decoded plane is an
    /// exact input, not a rounding), so comparing
    /// `t_near ≤ min(t_far, 1) · (1 + 2⁻²⁰)` (Ize, "Robust BVH Ray
    /// Traversal", 2013) cannot reject a box the true segment meets.
    ///
    /// Endpoints with a non-finite coordinate: `true` (no triangle meets
    /// them, by [`segment_blocked`]'s convention). Coordinates beyond
    /// `f32::MAX`: every triangle is tested.
    #[must_use]
    pub fn segment_unoccluded(&self, p: DVec3, x: DVec3) -> bool {
        if !(p.is_finite() && x.is_finite()) {
            return true;
        }
        if self.outliers.iter().any(|t| segment_blocked(p, x, t)) {
            return false;
        }
        let ray = Ray32::new(p, x).filter(|_| !self.nodes.is_empty());
        let Some(ray) = ray else {
            return !self.triangles.iter().any(|t| segment_blocked(p, x, t));
        };
        let mut small = [0u32; STACK];
        let mut large = Vec::new();
        let stack: &mut [u32] = if self.stack_need <= STACK {
            &mut small
        } else {
            large.resize(self.stack_need, 0);
            &mut large
        };
        let mut top = 0;
        let mut node = 0u32;
        // A value read from each child node and leaf triangle as soon as
        // its box is hit: the loads start while this node's other lanes and
        // leaves are handled (the crate forbids the `unsafe` prefetch
        // intrinsic), and `black_box` keeps them. Measured: soup rays/s
        // 1.07× on `examples/ray_corpus.rs`.
        let mut touched = 0u32;
        loop {
            let n = &self.nodes[node as usize];
            let mask = ray.hits(n);
            let mut leaves = 0u32;
            let mut rest = mask;
            while rest != 0 {
                let lane = rest.trailing_zeros() as usize;
                rest &= rest - 1;
                let child = n.child[lane];
                if child & LEAF == 0 {
                    stack[top] = child;
                    top += 1;
                    touched = touched.wrapping_add(self.nodes[child as usize].child[0]);
                } else {
                    leaves |= 1 << lane;
                    let t = &self.triangles[(child & !LEAF) as usize];
                    touched = touched.wrapping_add(t[0].x.to_bits() as u32);
                }
            }
            while leaves != 0 {
                let lane = leaves.trailing_zeros() as usize;
                leaves &= leaves - 1;
                let t = &self.triangles[(n.child[lane] & !LEAF) as usize];
                if segment_blocked(p, x, t) {
                    std::hint::black_box(touched);
                    return false;
                }
            }
            if top == 0 {
                std::hint::black_box(touched);
                return true;
            }
            top -= 1;
            node = stack[top];
        }
    }

    /// The nearest crossing of the ray `origin + t · direction`,
    /// `t ∈ (0, t_max]`, with any triangle (both sides count); `None` when
    /// the ray meets none, or for a non-finite origin or direction, a zero
    /// direction, or `t_max` not positive (or NaN). `t_max` may be `+∞`.
    ///
    /// # How it decides
    ///
    /// The ray is represented by the segment from `origin` to a far point
    /// `x = fl(origin + T · direction)` beyond every triangle (see
    /// [`Bvh::ray_segment`]: `T |direction|∞` is twice the larger of the
    /// max-norm distance to the farthest corner of the box of all triangles
    /// and `|origin|∞`, so `x − o` follows `direction` to a relative
    /// `2⁻⁵¹`). Whether the ray meets a
    /// triangle is decided exactly on that segment by [`segment_crossing`]
    /// (the decision of [`segment_blocked`]): a ray through an edge or a
    /// vertex shared by two triangles meets at least one of them — closed
    /// meshes are watertight — and a hit exactly on an edge counts; a
    /// triangle whose plane contains the origin is not met (`t > 0`).
    /// The crossing's `t` comes from the plane (relative error below
    /// `2⁻²³`, in practice a few ulps), and the hit is the crossing of
    /// least segment parameter (so of least `t`), ties going to the lower
    /// triangle index: the answer is that of testing every triangle
    /// (`tests/closest_hit.rs` checks it bit for bit), independent of the
    /// traversal order and of threads. A crossing whose rounded `t`
    /// exceeds `t_max` is not counted.
    ///
    /// The traversal is the conservative `f32` one of
    /// [`Bvh::segment_unoccluded`], ordered: the lanes a node's slab test
    /// keeps are visited nearest entry first, and each hit shrinks the
    /// segment's far end to its `t`, rounded up and widened by the slab
    /// test's `2⁻²⁰`. The slab test's entry is at most `(1 + 2⁻²¹)` times
    /// the parameter of any point of the true segment in the box, and a
    /// crossing's computed parameter is within `2⁻²³` of the true one
    /// (`2⁻²¹ + 2⁻²³` stays below `2⁻²⁰` less the comparison's
    /// roundings), so no box holding a crossing at or before the current
    /// hit is culled.
    ///
    /// Triangles beyond `±2⁶⁰` (kept out of the tree) are tested by every
    /// query, and a far point beyond `f32::MAX` tests every triangle, as
    /// for [`Bvh::segment_unoccluded`]; far-away triangles also lengthen
    /// the segment, which makes the `f32` culling coarser.
    ///
    /// Returned: `t` rounded from the crossing's parameter and clamped to
    /// `[5e-324, min(t_max, f64::MAX)]`; the triangle, its object id and
    /// its unit geometric normal facing the ray (`normal · direction ≤ 0`,
    /// zero only for a hit so grazing that the rounded normal is
    /// perpendicular to the ray; `−direction` normalised for a triangle
    /// too thin for its normal to be computed).
    ///
    /// Exact for coordinates in the domain of [`orient3d`] (including those
    /// of the far point).
    #[must_use]
    pub fn closest_hit(&self, origin: DVec3, direction: DVec3, t_max: f64) -> Option<Hit> {
        if t_max.is_nan() || t_max <= 0.0 {
            return None;
        }
        let probe = self.probe(origin, direction)?;
        let mut best = Best {
            u: f64::INFINITY,
            id: u32::MAX,
            scale: probe.scale,
            t_max,
        };
        for (t, &id) in self.outliers.iter().zip(&self.outlier_ids) {
            best.offer(probe.crossing(t), id);
        }
        let ray = Ray32::new(probe.o, probe.x).filter(|_| !self.nodes.is_empty());
        match ray {
            Some(ray) => self.closest_in_tree(&probe, &ray, &mut best),
            None => {
                for (t, &id) in self.triangles.iter().zip(&self.ids) {
                    best.offer(probe.crossing(t), id);
                }
            }
        }
        if best.id == u32::MAX {
            return None;
        }
        let t = (best.u * probe.scale).clamp(f64::from_bits(1), t_max.min(f64::MAX));
        let triangle = &self.occluders.triangles()[best.id as usize];
        Some(Hit {
            t,
            triangle: best.id,
            object: self.occluders.objects()[best.id as usize],
            normal: facing_normal(triangle, direction),
        })
    }

    /// [`Bvh::closest_hit`] for every `(origin, direction)` of `rays`, on
    /// the current rayon pool (chunks of 256 rays); the same answers as one
    /// call per ray, in order, whatever the number of threads.
    #[must_use]
    pub fn closest_hit_many(&self, rays: &[(DVec3, DVec3)], t_max: f64) -> Vec<Option<Hit>> {
        let mut out = vec![None; rays.len()];
        out.par_chunks_mut(256)
            .zip(rays.par_chunks(256))
            .for_each(|(out, rays)| {
                for (o, &(origin, direction)) in out.iter_mut().zip(rays) {
                    *o = self.closest_hit(origin, direction, t_max);
                }
            });
        out
    }

    /// The segment [`Bvh::closest_hit`] decides on for the ray
    /// `origin + t · direction`: `Some((x, t_x))` with the far point `x`
    /// and the ray parameter `t_x` it stands for, so that a crossing at
    /// segment parameter `u` (as [`segment_crossing`]`(origin, x, ·)`
    /// returns it) is the hit `t = u · t_x` (rounded). `None` where
    /// [`Bvh::closest_hit`] returns `None` before testing any triangle: no
    /// triangle, non-finite or zero input, or a far point that overflows.
    ///
    /// With `m = |direction|∞` and `s = direction · fl(1/m)` (`direction /
    /// m` for `m` outside `[1e-300, 1e300]`; either way `|s|∞ = 1` to an
    /// ulp):
    /// `T = 2 max(E, |origin|∞)`, `E` the rounded max-norm distance from
    /// `origin` to the farthest corner of the exact box of all finite
    /// triangles (no point `origin + τ s` with `τ > E` is in the box; the
    /// factor 2 covers the rounding, and `|origin|∞` keeps `x − origin`
    /// within a relative `2⁻⁵¹` of `T s`), `x = fl(origin + T s)`,
    /// `t_x = T · fl(1/m)` (or `T / m`).
    #[must_use]
    pub fn ray_segment(&self, origin: DVec3, direction: DVec3) -> Option<(DVec3, f64)> {
        self.probe(origin, direction).map(|p| (p.x, p.scale))
    }

    /// See [`Bvh::ray_segment`].
    fn probe(&self, origin: DVec3, direction: DVec3) -> Option<Probe> {
        if !(origin.is_finite() && direction.is_finite()) {
            return None;
        }
        let (lo, hi) = self.bounds?;
        let m = direction.abs().max_element();
        if m == 0.0 {
            return None;
        }
        // One division where the reciprocal stays in the normal range.
        let inv = 1.0 / m;
        let by_inverse = (1e-300..=1e300).contains(&m);
        let s = if by_inverse {
            direction * inv
        } else {
            direction / m
        };
        // Every point of the box is within `E = max |corner − origin|∞` of
        // the origin, and `|s|∞ = 1`: the ray leaves the box by `τ = E`.
        let far = (hi - origin).max(origin - lo).max_element();
        let reach = 2.0 * far.max(origin.abs().max_element());
        if reach.is_nan() || reach <= 0.0 {
            return None;
        }
        let x = origin + s * reach;
        if !x.is_finite() {
            return None;
        }
        let d = x - origin;
        Some(Probe {
            o: origin,
            x,
            d,
            d_norm: d.abs().max_element(),
            scale: if by_inverse { reach * inv } else { reach / m },
        })
    }

    /// The ordered, culling traversal of [`Bvh::closest_hit`].
    fn closest_in_tree(&self, probe: &Probe, ray: &Ray32, best: &mut Best) {
        let mut limit = 1.0f32;
        if best.t_max < f64::INFINITY {
            // Every counted crossing has `u · scale ≤ t_max`.
            limit = limit.min(f32_up(best.t_max / probe.scale * (1.0 + U_SLACK)));
        }
        if best.id != u32::MAX {
            limit = limit.min(f32_up(best.u));
        }
        // Only the stack the tree needs is cleared (most rays of small
        // scenes visit a node or two: clearing 512 bytes showed).
        let (mut small, mut medium, mut large);
        let stack: &mut [(u32, f32)] = if self.stack_need <= STACK / 2 {
            small = [(0u32, 0.0f32); STACK / 2];
            &mut small
        } else if self.stack_need <= STACK {
            medium = [(0u32, 0.0f32); STACK];
            &mut medium
        } else {
            large = vec![(0, 0.0); self.stack_need];
            &mut large
        };
        let mut top = 0;
        let mut node = 0u32;
        loop {
            let n = &self.nodes[node as usize];
            let (mask, near) = ray.slab(n, limit);
            // The kept lanes by entry (entries are `≥ 0`, so their bits
            // order as integers; the lane rides in the two low bits).
            let mut keys = [u32::MAX; WIDTH];
            let mut count = 0;
            let mut rest = mask;
            while rest != 0 {
                let lane = rest.trailing_zeros();
                rest &= rest - 1;
                let mut key = (near[lane as usize].to_bits() & !3) | lane;
                let mut k = count;
                while k > 0 && keys[k - 1] > key {
                    (keys[k], key) = (keys[k - 1], key);
                    k -= 1;
                }
                keys[k] = key;
                count += 1;
            }
            let mut inner = [(0u32, 0.0f32); WIDTH];
            let mut inner_count = 0;
            for &key in &keys[..count] {
                let lane = (key & 3) as usize;
                let child = n.child[lane];
                if child & LEAF == 0 {
                    inner[inner_count] = (child, near[lane]);
                    inner_count += 1;
                } else if near[lane] <= limit * T_SLACK {
                    let i = (child & !LEAF) as usize;
                    if best.offer(probe.crossing(&self.triangles[i]), self.ids[i]) {
                        limit = limit.min(f32_up(best.u));
                    }
                }
            }
            // Farthest first, so that the nearest is popped next.
            for &entry in inner[..inner_count].iter().rev() {
                stack[top] = entry;
                top += 1;
            }
            loop {
                if top == 0 {
                    return;
                }
                top -= 1;
                let (child, entry) = stack[top];
                if entry <= limit * T_SLACK {
                    node = child;
                    break;
                }
            }
        }
    }

    /// Writes to `out` (after clearing it), in increasing order and without
    /// repetition, the index (into [`Bvh::occluders`]) of every triangle
    /// whose box may meet the convex hull of `points`: a superset of the
    /// triangles that meet the hull. Any finite point set is accepted; the
    /// intended one is a pyramid, the receiver plus the corners of a box or
    /// polygon around the light's measure.
    ///
    /// A box is dropped only when it is separated from the hull, decided
    /// with rounding bounds (never wrongly): by the hull's bounding box
    /// (exact comparisons), or along a normal `n` of one of the hull's faces
    /// — found among the planes through three of the points (for at most
    /// [`Bvh::HULL_FACE_POINTS`] points; any `n` is a valid separating axis,
    /// the face normals are merely the tight ones) — when the box's interval
    /// of `n · (q − points[0])` lies beyond the hull's. Each dot product is
    /// bounded by `γ₆ Σ|nᵢ||qᵢ − aᵢ|` (one rounded difference, product and
    /// two sums need `γ₄`).
    ///
    /// No points: `out` is empty. A non-finite point, or one beyond
    /// `f32::MAX`: every indexed triangle. Triangles beyond `±2⁶⁰`, kept out
    /// of the tree, are always reported; triangles with a non-finite corner
    /// never (they block nothing).
    pub fn triangles_meeting_hull(&self, points: &[DVec3], out: &mut Vec<u32>) {
        out.clear();
        if points.is_empty() {
            return;
        }
        out.extend_from_slice(&self.outlier_ids);
        if self.nodes.is_empty() || !points.iter().all(|&v| in_f32_range(v)) {
            out.extend_from_slice(&self.ids);
            out.sort_unstable();
            return;
        }
        let hull = Hull::new(points);
        let mut stack = vec![0u32];
        while let Some(node) = stack.pop() {
            let n = &self.nodes[node as usize];
            for lane in 0..WIDTH {
                let child = n.child[lane];
                if child == EMPTY || hull.separated(n, lane) {
                    continue;
                }
                if child & LEAF == 0 {
                    stack.push(child);
                } else {
                    out.push(self.ids[(child & !LEAF) as usize]);
                }
            }
        }
        out.sort_unstable();
    }

    /// The most points whose face planes [`Bvh::triangles_meeting_hull`]
    /// looks for (`C(n, 3)` candidate planes); beyond it, only the hull's
    /// bounding box culls.
    pub const HULL_FACE_POINTS: usize = 16;
}

/// The nearest crossing of a ray with the occluders: what
/// [`Bvh::closest_hit`] returns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The ray parameter of the hit point `origin + t · direction`,
    /// `0 < t ≤ t_max`.
    pub t: f64,
    /// The triangle hit: its index in [`Bvh::occluders`].
    pub triangle: u32,
    /// Its object id, `occluders().objects()[triangle]`.
    pub object: u32,
    /// The triangle's unit geometric normal, turned against the ray
    /// (`normal · direction ≤ 0`; see [`Bvh::closest_hit`]).
    pub normal: DVec3,
}

/// The segment a closest-hit query decides on (see [`Bvh::ray_segment`]).
struct Probe {
    o: DVec3,
    /// The far point.
    x: DVec3,
    /// `x − o`, rounded, and its max-norm.
    d: DVec3,
    d_norm: f64,
    /// The ray parameter of `x`: a crossing at `u` is the hit `u · scale`.
    scale: f64,
}

impl Probe {
    #[inline(always)]
    fn crossing(&self, t: &[DVec3; 3]) -> Option<f64> {
        crossing(self.o, self.x, self.d, self.d_norm, t)
    }
}

/// A bound on the relative error of a crossing's `u` (what
/// [`segment_crossing`] promises), for culling.
const U_SLACK: f64 = 1.0 / (1u64 << 23) as f64;

/// The best crossing so far of a closest-hit query.
struct Best {
    /// Segment parameter (`∞`: none yet) and occluder index (`u32::MAX`).
    u: f64,
    id: u32,
    scale: f64,
    t_max: f64,
}

impl Best {
    /// Takes the crossing `u` of occluder `id` if it is the least `(u, id)`
    /// so far and its `t` is within `t_max`; whether it did.
    #[inline(always)]
    fn offer(&mut self, u: Option<f64>, id: u32) -> bool {
        match u {
            Some(u)
                if (u < self.u || (u == self.u && id < self.id))
                    && u * self.scale <= self.t_max =>
            {
                self.u = u;
                self.id = id;
                true
            }
            _ => false,
        }
    }
}

/// The unit normal of `t` turned against `direction` (finite, nonzero): the
/// flip is decided by the rounded `normal · direction` itself, so that a
/// caller evaluating it finds it `≤ 0`.
///
/// The cross product of the two edges at the triangle's largest angle (the
/// corner opposite the longest edge) is the best conditioned of the three;
/// where it under- or overflows (tiny or huge triangles), each edge is first
/// divided by its max-norm.
fn facing_normal(t: &[DVec3; 3], direction: DVec3) -> DVec3 {
    let [a, b, c] = *t;
    let (ab, bc, ca) = (b - a, c - b, a - c);
    let (lab, lbc, lca) = (
        ab.abs().max_element(),
        bc.abs().max_element(),
        ca.abs().max_element(),
    );
    let (u, v, lu, lv) = if lab >= lbc && lab >= lca {
        (bc, ca, lbc, lca)
    } else if lbc >= lca {
        (ca, ab, lca, lab)
    } else {
        (ab, bc, lab, lbc)
    };
    let n = u
        .cross(v)
        .try_normalize()
        .or_else(|| (u / lu).cross(v / lv).try_normalize())
        .unwrap_or_else(|| (-direction / direction.abs().max_element()).normalize());
    // Branch-free: which way a normal faces is unpredictable per pixel.
    DVec3::select(glam::BVec3::splat(n.dot(direction) > 0.0), -n, n)
}

/// The per-ray constants of the conservative `f32` slab test (see
/// [`Bvh::segment_unoccluded`] for the argument).
struct Ray32 {
    /// The origin subtracted from the entry plane of each axis.
    near: [f32; 3],
    /// The origin subtracted from the exit plane of each axis.
    far: [f32; 3],
    /// `1/d` per axis.
    inv: [f32; 3],
    /// The side (index of [`Node::q`]) of the entry plane of each axis: `1`
    /// (the maximum) where `dᵢ < 0`.
    entry: [usize; 3],
}

/// `1 + 2⁻²⁰`: covers the `(1 + γ₃)/(1 − γ₃)` of three roundings on each side
/// of the comparison, and the rounding of the product itself.
const T_SLACK: f32 = 1.0 + 1.0 / (1u32 << 20) as f32;

impl Ray32 {
    /// `None` when `p` or `x` leaves the `f32` range.
    fn new(p: DVec3, x: DVec3) -> Option<Ray32> {
        if !(in_f32_range(p) && in_f32_range(x)) {
            return None;
        }
        const TINY: f32 = 1.0 / (1u128 << 100) as f32;
        let d = x - p;
        let mut ray = Ray32 {
            near: [0.0; 3],
            far: [0.0; 3],
            inv: [0.0; 3],
            entry: [0; 3],
        };
        for i in 0..3 {
            let o = f64::from(p[i] as f32);
            let mut di = d[i] as f32;
            if di.abs() < TINY {
                di = if d[i] < 0.0 { -TINY } else { TINY };
            }
            let delta =
                (p[i].abs() + d[i].abs()) * (1.0 / f64::from(1u32 << 21)) + 4.0 * f64::from(TINY);
            // `o ± wide` rounded to nearest lands on or beyond `o ± delta`
            // (see `Bvh::segment_unoccluded`): no branch per rounding.
            let wide =
                delta * (1.0 + 1.0 / f64::from(1u32 << 22)) + o.abs() / f64::from(1u32 << 23);
            let up = ((o + wide) as f32).clamp(-f32::MAX, f32::MAX);
            let down = ((o - wide) as f32).clamp(-f32::MAX, f32::MAX);
            ray.entry[i] = usize::from(di < 0.0);
            ray.inv[i] = 1.0 / di;
            (ray.near[i], ray.far[i]) = if di < 0.0 { (down, up) } else { (up, down) };
        }
        Some(ray)
    }

    /// The lanes of `n` whose box the segment may meet, as a bit mask.
    #[inline(always)]
    fn hits(&self, n: &Node) -> u32 {
        self.slab(n, 1.0).0
    }

    /// The lanes of `n` whose box the part `[0, limit]` of the segment may
    /// meet (`0 < limit ≤ 1`), as a bit mask, and each lane's entry
    /// parameter: at most `(1 + 2⁻²¹) u` for any `u ≤ limit` at which the
    /// true segment is inside the lane's box (the argument of
    /// [`Bvh::segment_unoccluded`], which shows the rounded entry to be a
    /// conservative `(1 + γ₃)` bound on the entry into the box grown by
    /// `δ`, and that grown box to contain the `f32` ray wherever the true
    /// segment is in the box); `0` when the segment starts inside.
    #[inline(always)]
    fn slab(&self, n: &Node, limit: f32) -> (u32, [f32; WIDTH]) {
        let mut t_near = [0.0f32; WIDTH];
        let mut t_far = [limit; WIDTH];
        for axis in 0..3 {
            let side = self.entry[axis];
            let (entry, exit) = (&n.q[side][axis], &n.q[1 - side][axis]);
            let (near, far, inv) = (self.near[axis], self.far[axis], self.inv[axis]);
            let (origin, scale) = (n.origin[axis], n.scale[axis]);
            let entry: [f32; WIDTH] =
                std::array::from_fn(|lane| decode(origin, entry[lane], scale));
            let exit: [f32; WIDTH] = std::array::from_fn(|lane| decode(origin, exit[lane], scale));
            for lane in 0..WIDTH {
                // Comparisons rather than `f32::max`: no NaN arises (see
                // above), and these map to `maxps`/`minps`.
                let (a, b) = ((entry[lane] - near) * inv, (exit[lane] - far) * inv);
                t_near[lane] = if a > t_near[lane] { a } else { t_near[lane] };
                t_far[lane] = if b < t_far[lane] { b } else { t_far[lane] };
            }
        }
        let mut mask = 0;
        for lane in 0..WIDTH {
            let hit = (t_near[lane] <= t_far[lane] * T_SLACK) & (n.child[lane] != EMPTY);
            mask |= u32::from(hit) << lane;
        }
        (mask, t_near)
    }
}

/// The separating tests of [`Bvh::triangles_meeting_hull`].
struct Hull {
    lo: DVec3,
    hi: DVec3,
    /// Reference point `a` of the axes (the first point).
    origin: DVec3,
    /// `(n, lo, hi)`: the hull lies in `lo ≤ n · (q − a) ≤ hi`.
    axes: Vec<(DVec3, f64, f64)>,
}

/// `γ₆ = 6u/(1 − 6u)`, `u = 2⁻⁵³`.
const GAMMA6: f64 = 6.0 * (f64::EPSILON / 2.0) / (1.0 - 6.0 * (f64::EPSILON / 2.0));

impl Hull {
    fn new(points: &[DVec3]) -> Hull {
        let (mut lo, mut hi) = (points[0], points[0]);
        for &v in points {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        let origin = points[0];
        let mut hull = Hull {
            lo,
            hi,
            origin,
            axes: Vec::new(),
        };
        let n = points.len();
        if !(3..=Bvh::HULL_FACE_POINTS).contains(&n) {
            return hull;
        }
        let mut normals: Vec<DVec3> = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    let (a, b, c) = (points[i], points[j], points[k]);
                    let normal = (b - a).cross(c - a);
                    let Some(unit) = normal.try_normalize() else {
                        continue;
                    };
                    // A face: no point strictly on both sides (rounded test;
                    // only tightness, not soundness, depends on it).
                    let tol = 1e-9 * (b - a).length().max((c - a).length());
                    let (mut below, mut above) = (false, false);
                    for &v in points {
                        let s = unit.dot(v - a);
                        below |= s < -tol;
                        above |= s > tol;
                    }
                    let duplicate = normals.iter().any(|m| m.dot(unit).abs() > 1.0 - 1e-12);
                    let face = !(below && above);
                    if face && !duplicate {
                        normals.push(unit);
                    }
                }
            }
        }
        for normal in normals {
            let (mut l, mut h) = (f64::INFINITY, f64::NEG_INFINITY);
            for &v in points {
                let (s, bound) = dot_bounded(normal, v, origin);
                l = l.min(s - bound);
                h = h.max(s + bound);
            }
            if l.is_finite() && h.is_finite() {
                hull.axes.push((normal, l, h));
            }
        }
        hull
    }

    /// Whether lane `lane` of `n` is certainly disjoint from the hull.
    fn separated(&self, n: &Node, lane: usize) -> bool {
        let (lo, hi) = n.lane_box(lane);
        if lo.cmpgt(self.hi).any() || hi.cmplt(self.lo).any() {
            return true;
        }
        self.axes.iter().any(|&(normal, l, h)| {
            // The corners minimising and maximising `normal · q`.
            let q_min = DVec3::select(normal.cmpge(DVec3::ZERO), lo, hi);
            let q_max = DVec3::select(normal.cmpge(DVec3::ZERO), hi, lo);
            let (s_min, b_min) = dot_bounded(normal, q_min, self.origin);
            let (s_max, b_max) = dot_bounded(normal, q_max, self.origin);
            // NaN (never expected with finite inputs) compares false: kept.
            s_min - b_min > h || s_max + b_max < l
        })
    }
}

/// `n · (q − a)` rounded, and a bound on its rounding error.
fn dot_bounded(n: DVec3, q: DVec3, a: DVec3) -> (f64, f64) {
    let d = q - a;
    (n.dot(d), GAMMA6 * n.abs().dot(d.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arbitrary::Rng;

    /// A coordinate near `centre`, `scale` across, with now and then a value
    /// clamped by the `f32` range or a repeated one.
    fn coordinate(rng: &mut Rng, centre: f64, scale: f64) -> f64 {
        match rng.below(8) {
            0 => f64::from(f32::MAX) * rng.sign(),
            1 => centre,
            _ => centre + rng.uniform(-1.0, 1.0) * scale,
        }
    }

    /// The invariant the traversal's conservativeness rests on: every
    /// decoded lane box contains, exactly, every corner of every triangle
    /// below it (clamped to the `f32` range). Returns the subtree's corner
    /// bounds.
    fn check_subtree(bvh: &Bvh, node: u32, depth: usize) -> (DVec3, DVec3) {
        let clamp = |v: DVec3| {
            v.clamp(
                DVec3::splat(-f64::from(f32::MAX)),
                DVec3::splat(f64::from(f32::MAX)),
            )
        };
        let n = &bvh.nodes[node as usize];
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for lane in 0..WIDTH {
            let child = n.child[lane];
            if child == EMPTY {
                continue;
            }
            let (c_lo, c_hi) = if child & LEAF == 0 {
                check_subtree(bvh, child, depth + 1)
            } else {
                let t = bvh.triangles[(child & !LEAF) as usize].map(clamp);
                (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]))
            };
            let (b_lo, b_hi) = n.lane_box(lane);
            assert!(
                b_lo.cmple(c_lo).all() && b_hi.cmpge(c_hi).all(),
                "lane {lane} of node {node} (depth {depth}): box {b_lo:?}..{b_hi:?} misses {c_lo:?}..{c_hi:?}"
            );
            lo = lo.min(c_lo);
            hi = hi.max(c_hi);
        }
        (lo, hi)
    }

    #[test]
    fn decoded_boxes_contain_their_triangles() {
        let mut rng = Rng::new(11);
        for case in 0..300 {
            let centre = rng.log_uniform(-30.0, 30.0) * rng.sign();
            let scale = centre.abs() * rng.log_uniform(-12.0, 0.5) + rng.log_uniform(-40.0, -20.0);
            let count = 1 + rng.below(if case % 10 == 0 { 3000 } else { 300 }) as usize;
            let triangles: Vec<[DVec3; 3]> = (0..count)
                .map(|_| {
                    let mut corner = || {
                        DVec3::new(
                            coordinate(&mut rng, centre, scale),
                            coordinate(&mut rng, centre, scale),
                            coordinate(&mut rng, centre, scale),
                        )
                    };
                    [corner(), corner(), corner()]
                })
                .collect();
            let bvh = Bvh::new(Occluders::from_triangles(triangles));
            // Triangles beyond TREE_RANGE are kept out of the tree.
            assert_eq!(bvh.triangles.len() + bvh.outliers.len(), count);
            if !bvh.nodes.is_empty() {
                check_subtree(&bvh, 0, 0);
            }
        }
    }

    #[test]
    fn ray_origins_are_padded_outward() {
        // `near`/`far` bracket `fl32(p) ± δ` (the argument of
        // `Bvh::segment_unoccluded`), over many decades and at the edge of
        // the `f32` range.
        let mut rng = Rng::new(13);
        for _ in 0..100_000 {
            let mut point = || {
                DVec3::new(
                    rng.log_uniform(-40.0, 38.5) * rng.sign(),
                    if rng.chance(0.1) {
                        0.0
                    } else {
                        rng.log_uniform(-40.0, 38.5) * rng.sign()
                    },
                    coordinate(&mut rng, 1.0, 1e-3),
                )
            };
            let (p, x) = (point(), point());
            let Some(ray) = Ray32::new(p, x) else {
                continue;
            };
            let d = x - p;
            for i in 0..3 {
                let o = f64::from(p[i] as f32);
                let delta = (p[i].abs() + d[i].abs()) / f64::from(1u32 << 21);
                let max = f64::from(f32::MAX);
                let (lo, hi) = if ray.entry[i] == 1 {
                    (ray.near[i], ray.far[i])
                } else {
                    (ray.far[i], ray.near[i])
                };
                assert!(
                    f64::from(hi) >= (o + delta).min(max),
                    "{p:?} {x:?} axis {i}"
                );
                assert!(
                    f64::from(lo) <= (o - delta).max(-max),
                    "{p:?} {x:?} axis {i}"
                );
            }
        }
    }

    #[test]
    fn quantisation_is_tight_on_its_grid() {
        // Each plane is the nearest grid value on the safe side.
        let mut rng = Rng::new(12);
        for _ in 0..2000 {
            let centre = rng.log_uniform(-20.0, 20.0) * rng.sign();
            let scale = centre.abs() * rng.log_uniform(-9.0, 1.0);
            let boxes: Vec<([f32; 3], [f32; 3])> = (0..1 + rng.below(WIDTH as u64) as usize)
                .map(|_| {
                    let a: [f32; 3] =
                        std::array::from_fn(|_| coordinate(&mut rng, centre, scale) as f32);
                    let b: [f32; 3] =
                        std::array::from_fn(|_| coordinate(&mut rng, centre, scale) as f32);
                    (
                        std::array::from_fn(|i| a[i].min(b[i])),
                        std::array::from_fn(|i| a[i].max(b[i])),
                    )
                })
                .collect();
            let node = Node::quantised(&boxes);
            for (lane, (lo, hi)) in boxes.iter().enumerate() {
                for axis in 0..3 {
                    let (o, s) = (node.origin[axis], node.scale[axis]);
                    let (ql, qh) = (node.q[0][axis][lane], node.q[1][axis][lane]);
                    assert!(
                        decode(o, ql, s) <= lo[axis]
                            && (ql == 255 || decode(o, ql + 1, s) > lo[axis])
                    );
                    assert!(
                        decode(o, qh, s) >= hi[axis]
                            && (qh == 0 || decode(o, qh - 1, s) < hi[axis])
                    );
                }
            }
        }
    }
}
