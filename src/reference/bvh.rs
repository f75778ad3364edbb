//! A bounding volume hierarchy over [`Occluders`], for the occlusion rays of
//! the Monte Carlo reference and for culling the triangles a receiver's view
//! of the light can meet (the exact reference).
//!
//! # How it decides
//!
//! The tree is built by `obvhs` (PLOC with reinsertion, `Bvh2`) over boxes
//! computed in `f64` and rounded *outward* to `f32`, then collapsed into a
//! 4-wide tree of our own whose traversal is conservative (see
//! [`Bvh::segment_unoccluded`]): the `f32` tree only ever prunes boxes the true
//! `f64` segment cannot meet. Every triangle the traversal reaches is decided
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
//! magnitude in `[1e-90, 1e90]` (the domain of `orient3d`); the `f32` tree
//! covers coordinates up to `f32::MAX` (`3.4e38`), and queries reaching
//! beyond it fall back to testing every triangle (slow, still exact).
//! Triangles with a non-finite corner are left out at build and block
//! nothing; zero-area triangles block nothing (the predicate says so).

use super::Occluders;
use crate::kernel::predicate::{orient3d, Sign};
use glam::{DVec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::bvh2::builder::build_bvh2;
use obvhs::bvh2::Bvh2;
use obvhs::BvhBuildParams;
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

/// A node of the 4-wide tree: child boxes in structure-of-arrays form (the
/// slab test runs over the four lanes at once).
#[derive(Clone, Copy)]
struct Node {
    /// `lo[axis][lane]`: box minima; `+∞` for an empty lane.
    lo: [[f32; WIDTH]; 3],
    /// `hi[axis][lane]`: box maxima; `−∞` for an empty lane.
    hi: [[f32; WIDTH]; 3],
    /// Inner child: its node index. Leaf: its first triangle in
    /// `Bvh::triangles`. Empty lane: [`EMPTY`].
    child: [u32; WIDTH],
    /// Triangles in a leaf child; `0` for an inner child.
    count: [u32; WIDTH],
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
}

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
    /// Builds the hierarchy (single-threaded; about 0.1 s per 100k
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
        for (i, t) in occluders.triangles().iter().enumerate() {
            if !t.iter().all(|v| v.is_finite()) {
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
        };
        if boxes.is_empty() {
            return bvh;
        }
        // One triangle per leaf: the 4-wide node test then culls single
        // triangles, cheaper than their exact test (measured: 1.2–2× the
        // rays/s of 4 or 8 per leaf on benches/rays.rs).
        let params = BvhBuildParams {
            max_prims_per_leaf: 1,
            ..BvhBuildParams::medium_build()
        };
        let tree = build_bvh2(&boxes, params, &mut Duration::default());
        bvh.collapse(&tree, &kept);
        bvh
    }

    /// Turns obvhs's binary tree into ours: each node takes up to [`WIDTH`]
    /// descendants (repeatedly opening the inner child of largest area), and
    /// the triangles are copied in leaf order.
    fn collapse(&mut self, tree: &Bvh2, kept: &[u32]) {
        let empty = Node {
            lo: [[f32::INFINITY; WIDTH]; 3],
            hi: [[f32::NEG_INFINITY; WIDTH]; 3],
            child: [EMPTY; WIDTH],
            count: [0; WIDTH],
        };
        let root = &tree.nodes[0];
        // (obvhs node, our node, depth of our node)
        let mut work = vec![(0usize, 0usize, 1usize)];
        self.nodes.push(empty);
        let mut depth = 1;
        while let Some((src, dst, level)) = work.pop() {
            depth = depth.max(level);
            let mut lanes: Vec<usize> = if src == 0 && root.is_leaf() {
                vec![0]
            } else {
                let first = tree.nodes[src].first_index as usize;
                vec![first, first + 1]
            };
            while lanes.len() < WIDTH {
                let widest = lanes
                    .iter()
                    .enumerate()
                    .filter(|(_, &n)| !tree.nodes[n].is_leaf())
                    .max_by(|(_, &a), (_, &b)| {
                        let area = |n: usize| tree.nodes[n].aabb().half_area();
                        area(a).total_cmp(&area(b))
                    })
                    .map(|(k, _)| k);
                let Some(k) = widest else { break };
                let first = tree.nodes[lanes[k]].first_index as usize;
                lanes[k] = first;
                lanes.push(first + 1);
            }
            let mut node = empty;
            for (lane, &n) in lanes.iter().enumerate() {
                let src_node = &tree.nodes[n];
                let b = src_node.aabb();
                for axis in 0..3 {
                    node.lo[axis][lane] = b.min[axis];
                    node.hi[axis][lane] = b.max[axis];
                }
                if src_node.is_leaf() {
                    let first = src_node.first_index as usize;
                    let count = src_node.prim_count as usize;
                    node.child[lane] = self.triangles.len() as u32;
                    node.count[lane] = count as u32;
                    for &prim in &tree.primitive_indices[first..first + count] {
                        let id = kept[prim as usize];
                        self.ids.push(id);
                        self.triangles.push(self.occluders.triangles()[id as usize]);
                    }
                } else {
                    node.child[lane] = self.nodes.len() as u32;
                    work.push((n, self.nodes.len(), level + 1));
                    self.nodes.push(empty);
                }
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
    /// absorbs the `f64` arithmetic computing `δ` and `o ± δ`. So if the true
    /// segment meets a box `B` (which contains its triangles exactly) at
    /// `t*`, the exact `f32` ray lies inside `B` grown by `δ` for all `t`
    /// within `δᵢ/|dᵢ| ≥ 2⁻²²` of `t*` (clipped to `[0, 1]`): the slab
    /// intervals overlap by a width of at least `2⁻²²`. The slab test grows
    /// the box by `δ` through the origins it subtracts (`o ± δ` rounded
    /// outward), and each rounded `t = (plane − origin) · (1/d)` carries at
    /// most three roundings (relative error `γ₃ ≈ 3·2⁻²⁴`, sign exact), so
    /// comparing `t_near ≤ min(t_far, 1) · (1 + 2⁻²⁰)` (Ize, "Robust BVH Ray
    /// Traversal", 2013) cannot reject a box the true segment meets.
    ///
    /// Endpoints with a non-finite coordinate: `true` (no triangle meets
    /// them, by [`segment_blocked`]'s convention). Coordinates beyond
    /// `f32::MAX`: every triangle is tested.
    #[must_use]
    pub fn segment_unoccluded(&self, p: DVec3, x: DVec3) -> bool {
        if self.nodes.is_empty() || !(p.is_finite() && x.is_finite()) {
            return true;
        }
        let Some(ray) = Ray32::new(p, x) else {
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
        loop {
            let n = &self.nodes[node as usize];
            let mut mask = ray.hits(n);
            while mask != 0 {
                let lane = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                let (child, count) = (n.child[lane], n.count[lane]);
                if count == 0 {
                    stack[top] = child;
                    top += 1;
                } else {
                    let first = child as usize;
                    let tris = &self.triangles[first..first + count as usize];
                    if tris.iter().any(|t| segment_blocked(p, x, t)) {
                        return false;
                    }
                }
            }
            if top == 0 {
                return true;
            }
            top -= 1;
            node = stack[top];
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
    /// `f32::MAX`: every indexed triangle. Triangles with a non-finite corner
    /// are never reported (they block nothing).
    pub fn triangles_meeting_hull(&self, points: &[DVec3], out: &mut Vec<u32>) {
        out.clear();
        if points.is_empty() || self.nodes.is_empty() {
            return;
        }
        if !points.iter().all(|&v| in_f32_range(v)) {
            out.extend_from_slice(&self.ids);
            out.sort_unstable();
            return;
        }
        let hull = Hull::new(points);
        let mut stack = vec![0u32];
        while let Some(node) = stack.pop() {
            let n = &self.nodes[node as usize];
            for lane in 0..WIDTH {
                let (child, count) = (n.child[lane], n.count[lane]);
                if child == EMPTY || hull.separated(n, lane) {
                    continue;
                }
                if count == 0 {
                    stack.push(child);
                } else {
                    let first = child as usize;
                    out.extend_from_slice(&self.ids[first..first + count as usize]);
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

/// The per-ray constants of the conservative `f32` slab test (see
/// [`Bvh::segment_unoccluded`] for the argument).
struct Ray32 {
    /// The origin subtracted from the entry plane of each axis.
    near: [f32; 3],
    /// The origin subtracted from the exit plane of each axis.
    far: [f32; 3],
    /// `1/d` per axis.
    inv: [f32; 3],
    /// `dᵢ < 0`: the entry plane is the box's maximum.
    negative: [bool; 3],
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
            negative: [false; 3],
        };
        for i in 0..3 {
            let o = f64::from(p[i] as f32);
            let mut di = d[i] as f32;
            if di.abs() < TINY {
                di = if d[i] < 0.0 { -TINY } else { TINY };
            }
            let delta =
                (p[i].abs() + d[i].abs()) * (1.0 / f64::from(1u32 << 21)) + 4.0 * f64::from(TINY);
            let (up, down) = (f32_up(o + delta), f32_down(o - delta));
            ray.negative[i] = di < 0.0;
            ray.inv[i] = 1.0 / di;
            (ray.near[i], ray.far[i]) = if ray.negative[i] {
                (down, up)
            } else {
                (up, down)
            };
        }
        Some(ray)
    }

    /// The lanes of `n` whose box the segment may meet, as a bit mask.
    #[inline(always)]
    fn hits(&self, n: &Node) -> u32 {
        let mut t_near = [0.0f32; WIDTH];
        let mut t_far = [f32::INFINITY; WIDTH];
        for axis in 0..3 {
            let (entry, exit) = if self.negative[axis] {
                (&n.hi[axis], &n.lo[axis])
            } else {
                (&n.lo[axis], &n.hi[axis])
            };
            let (near, far, inv) = (self.near[axis], self.far[axis], self.inv[axis]);
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
            let limit = t_far[lane].min(1.0) * T_SLACK;
            mask |= u32::from(t_near[lane] <= limit) << lane;
        }
        mask
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
        let lo = DVec3::new(
            f64::from(n.lo[0][lane]),
            f64::from(n.lo[1][lane]),
            f64::from(n.lo[2][lane]),
        );
        let hi = DVec3::new(
            f64::from(n.hi[0][lane]),
            f64::from(n.hi[1][lane]),
            f64::from(n.hi[2][lane]),
        );
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
