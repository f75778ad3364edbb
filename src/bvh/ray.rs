//! The conservative `f32` slab test of a segment against a node's child
//! boxes, and the any-hit traversal over the occlusion tree
//! ([`Bvh::segment_unoccluded`]).

#[cfg(all(feature = "simd", target_arch = "x86_64"))]
use super::lanes::Avx8;
use super::lanes::{Axes32, Lanes, Portable};
use super::leaf::{self, LeafRay, PACK};
use super::node::{decode, Node, EMPTY, WIDTH};
use super::wide::{WideNode, LEAF as WIDE_LEAF, WIDE};
use super::{in_f32_range, Bvh};
use crate::kernel::lanes;
use crate::kernel::segment::segment_blocked;
use glam::DVec3;

/// Stack entries kept on the machine stack by the depth-first traversals;
/// deeper trees use a heap stack.
pub(super) const STACK: usize = 64;

/// A traversal's stack of node indices: on the machine stack up to `N`
/// entries, on the heap beyond.
pub(super) struct NodeStack<const N: usize> {
    small: [u32; N],
    large: Vec<u32>,
}

impl<const N: usize> NodeStack<N> {
    pub(super) fn new() -> NodeStack<N> {
        NodeStack {
            small: [0; N],
            large: Vec::new(),
        }
    }

    /// `need` entries, all 0 (the root's index): exactly as many, so that
    /// a traversal outgrowing its proven bound fails loudly in the tests
    /// rather than silently using the spare entries.
    #[inline(always)]
    pub(super) fn entries(&mut self, need: usize) -> &mut [u32] {
        if need <= N {
            &mut self.small[..need]
        } else {
            self.large_entries(need)
        }
    }

    /// [`NodeStack::entries`] beyond the machine stack's `N`.
    #[cold]
    #[inline(never)]
    fn large_entries(&mut self, need: usize) -> &mut [u32] {
        self.large.resize(need, 0);
        &mut self.large
    }
}

impl Bvh {
    /// Whether the open segment `(p, x)` meets no triangle, decided exactly
    /// by [`segment_blocked`] on every triangle whose box the segment may
    /// meet (any-hit: stops at the first blocker). Endpoints are not part of
    /// the segment: a receiver on a face is not shadowed by that face.
    ///
    /// # How it decides
    ///
    /// The walk goes over the occlusion tree (eight child boxes a node,
    /// leaves of up to eight triangles; `wide.rs`) depth first, the loads
    /// of a node's hit children and packs started together (a value read
    /// from each) before any is used.
    ///
    /// *The boxes are conservative.* With `o = fl32(p)` and
    /// `d = fl32(fl64(x − p))` (a component below `2⁻¹⁰⁰` in magnitude
    /// replaced by `±2⁻¹⁰⁰`), the `f32` ray `o + t d` stays, for every
    /// `t ∈ [0, 1]`, within `δᵢ/2` of the true point `p + t (x − p)` on each
    /// axis, where `δᵢ = 2⁻²¹ (|pᵢ| + |xᵢ − pᵢ|) + 2⁻⁹⁸`: the two roundings to
    /// `f32` contribute at most `2⁻²⁴` relative each, the `f64` difference
    /// `2⁻⁵³`, the substitution `2⁻¹⁰⁰` — a factor-2 margin above `δᵢ/2`
    /// absorbs the `f64` arithmetic computing `δ` and `o ± δ`. A child's box
    /// `B` is the `f32` box of the build, rounded outward from the `f64`
    /// triangles: it contains every triangle below it exactly (checked by
    /// `tests::wide_boxes_contain_their_triangles`). So if the true segment
    /// meets `B` at `t*`, the exact `f32` ray lies inside `B` grown by `δ`
    /// for all `t` within `δᵢ/|dᵢ| ≥ 2⁻²²` of `t*` (clipped to `[0, 1]`):
    /// the slab intervals overlap by a width of at least `2⁻²²`. The slab
    /// test grows the box by at least `δ` through the origins it
    /// subtracts: `o ± δ′` with `δ′ = δ (1 + 2⁻²²) + |o| 2⁻²³`, rounded to
    /// nearest `f32`, lies on or beyond `o ± δ`, since rounding moves it by
    /// at most `2⁻²⁴ (|o| + δ′)`, less than the added `δ 2⁻²² + |o| 2⁻²³`
    /// (with room for the `f64` arithmetic); where that passes `±f32::MAX`
    /// it is clamped there, still beyond every plane. Each rounded
    /// `t = (plane − origin) · (1/d)` carries at most three roundings
    /// (relative error `γ₃ ≈ 3·2⁻²⁴`, sign exact), so comparing
    /// `t_near ≤ min(t_far, 1) · (1 + 2⁻²⁰)` (Ize, "Robust BVH Ray
    /// Traversal", 2013) cannot reject a box the true segment meets: a box
    /// test may keep a box the segment misses, never drop one it meets.
    /// An empty lane's box is inverted (`lo = f32::MAX > hi = −f32::MAX`):
    /// its entry is `+∞` or positive beyond its exit, and no NaN arises
    /// (`1/d` is finite and nonzero, the origins finite).
    ///
    /// *The leaves are tested in `f32` where that is certain.* The
    /// triangles of a leaf whose box the walk keeps are tested together in
    /// `f32`, each determinant of the exact test with a proven error bound
    /// (`leaf.rs`); a triangle whose every sign is certain under the bound
    /// is decided there, any other by [`segment_blocked`], in `f64` with
    /// the exact [`orient3d`](crate::kernel::predicate::orient3d). So
    /// every triangle whose box the segment may meet is decided as
    /// [`segment_blocked`] decides it, and the answer does not depend on
    /// the order of the walk: it is whether some triangle blocks the
    /// segment.
    ///
    /// Endpoints with a non-finite coordinate: `true` (no triangle meets
    /// them, by [`segment_blocked`]'s convention). Coordinates beyond
    /// `f32::MAX`: every triangle is tested.
    #[must_use]
    pub fn segment_unoccluded(&self, p: DVec3, x: DVec3) -> bool {
        self.unoccluded_with(p, x, &mut ())
    }

    /// [`Bvh::segment_unoccluded`], counting the work of the walk into
    /// `counts` (nodes visited, leaves and triangles tested in `f32`, and
    /// triangles the `f32` test left to the exact one): the same answer.
    /// For measuring the tree, not for speed.
    pub fn segment_unoccluded_counting(
        &self,
        p: DVec3,
        x: DVec3,
        counts: &mut OcclusionCounts,
    ) -> bool {
        counts.segments += 1;
        self.unoccluded_with(p, x, counts)
    }

    /// [`Bvh::segment_unoccluded`] on the widest lanes the processor has
    /// (AVX2 where present, through `pulp`'s run-time dispatch: the same
    /// answers; the whole walk compiled for it).
    #[inline(always)]
    fn unoccluded_with<T: Tally>(&self, p: DVec3, x: DVec3, tally: &mut T) -> bool {
        lanes::vectorized(
            #[inline(always)]
            |_| {
                #[cfg(all(feature = "simd", target_arch = "x86_64"))]
                if let Some(v3) = pulp::x86::V3::try_new() {
                    return self.unoccluded_here(v3, p, x, tally);
                }
                self.unoccluded_here(Portable, p, x, tally)
            },
        )
    }

    /// [`Bvh::segment_unoccluded`] on the lanes `s`, compiled where it is
    /// called.
    #[inline(always)]
    pub(super) fn unoccluded_here<S: WalkLanes, T: Tally>(
        &self,
        s: S,
        p: DVec3,
        x: DVec3,
        tally: &mut T,
    ) -> bool {
        // The common case in one test (a NaN or an infinity fails it too),
        // the others out of line: for a segment that misses the root's
        // boxes the set-up is most of the query.
        let common =
            in_f32_range(p) && in_f32_range(x) && self.outliers.is_empty() && !self.wide.is_empty();
        if !common {
            if let Some(answer) = self.unoccluded_off_tree(p, x) {
                return answer;
            }
        }
        let d = x - p;
        let axes = s.axes([p.x, p.y, p.z, p.z], [d.x, d.y, d.z, d.z]);
        let ray = Ray32 {
            near: [axes.near[0], axes.near[1], axes.near[2]],
            far: [axes.far[0], axes.far[1], axes.far[2]],
            inv: [axes.inv[0], axes.inv[1], axes.inv[2]],
            entry: [0, 1, 2].map(|k| usize::from(axes.backward[k])),
        };
        let need = self.wide_stack_need();
        if need <= STACK {
            self.walk(s, p, x, &ray, tally, &mut ArrayStack::new(need))
        } else {
            self.deep_walk(s, p, x, &ray, tally)
        }
    }

    /// [`Bvh::walk`] on a tree too deep for an [`ArrayStack`]: its stack
    /// on the heap.
    #[cold]
    #[inline(never)]
    fn deep_walk<S: WalkLanes, T: Tally>(
        &self,
        s: S,
        p: DVec3,
        x: DVec3,
        ray: &Ray32,
        tally: &mut T,
    ) -> bool {
        let mut entries = vec![0; self.wide_stack_need()];
        self.walk(s, p, x, ray, tally, &mut SliceStack(&mut entries))
    }

    /// [`Bvh::segment_unoccluded`] where its endpoints leave the `f32`
    /// range, an outlier triangle may block it or there is no tree: the
    /// answer, or `None` when the walk over the tree decides it.
    #[cold]
    #[inline(never)]
    fn unoccluded_off_tree(&self, p: DVec3, x: DVec3) -> Option<bool> {
        if !(p.is_finite() && x.is_finite()) {
            return Some(true);
        }
        if self.outliers.iter().any(|t| segment_blocked(p, x, t)) {
            return Some(false);
        }
        if self.wide.is_empty() || !(in_f32_range(p) && in_f32_range(x)) {
            return Some(!self.triangles.iter().any(|t| segment_blocked(p, x, t)));
        }
        None
    }

    /// The any-hit walk of [`Bvh::segment_unoccluded`] over the occlusion
    /// tree, depth first.
    #[inline(always)]
    fn walk<S: WalkLanes, T: Tally, K: WalkStack>(
        &self,
        s: S,
        p: DVec3,
        x: DVec3,
        ray: &Ray32,
        tally: &mut T,
        stack: &mut K,
    ) -> bool {
        let (mut top, mut node) = (0usize, 0u32);
        // The leaves' constants, on the first leaf (most of Monte Carlo's
        // rays miss the root's boxes).
        let mut leaf_ray: Option<LeafRay<<S::Leaf as Lanes<PACK>>::F>> = None;
        let slab = WideSlab::new(s.node(), ray);
        let mut touched = 0u32;
        loop {
            let n = &self.wide[node as usize];
            tally.node();
            let hits = slab.hits(s.node(), n);
            // Inner children pushed and leaves noted first, a value read
            // from each (the crate forbids the `unsafe` prefetch
            // intrinsic): the loads of the hit packs and of the node
            // visited next start together, rather than each when its
            // test needs it.
            let mut inner = hits & !n.leaf_lanes;
            let mut leaves = hits & n.leaf_lanes;
            while inner != 0 {
                let child = n.child[inner.trailing_zeros() as usize];
                inner &= inner - 1;
                stack.set(top, child);
                top += 1;
                touched = touched.wrapping_add(self.wide[child as usize].child[0]);
            }
            let mut rest = leaves;
            while rest != 0 {
                let child = n.child[rest.trailing_zeros() as usize];
                rest &= rest - 1;
                touched = touched.wrapping_add(self.packs.get(child & !WIDE_LEAF).count());
            }
            while leaves != 0 {
                let lane = leaves.trailing_zeros() as usize;
                leaves &= leaves - 1;
                let at = n.child[lane] & !WIDE_LEAF;
                if leaf_ray.is_none() {
                    leaf_ray = Some(LeafRay::new(s.leaf(), p, x));
                }
                let Some(leaf_ray) = &leaf_ray else {
                    unreachable!()
                };
                if self.pack_blocks(s.leaf(), p, x, at, leaf_ray, tally) {
                    std::hint::black_box(touched);
                    return false;
                }
            }
            if top == 0 {
                std::hint::black_box(touched);
                return true;
            }
            top -= 1;
            node = stack.get(top);
        }
    }

    /// Whether a triangle of pack `at` blocks the segment: the `f32` test,
    /// then the exact one on the lanes it leaves uncertain.
    #[inline(always)]
    fn pack_blocks<L: Lanes<PACK>, T: Tally>(
        &self,
        s: L,
        p: DVec3,
        x: DVec3,
        at: u32,
        leaf_ray: &LeafRay<L::F>,
        tally: &mut T,
    ) -> bool {
        let pack = self.packs.get(at);
        let (hit, unsure) = leaf::test(s, pack, leaf_ray);
        tally.pack(pack.count(), unsure.count_ones());
        hit != 0 || (unsure != 0 && self.exact_lanes(p, x, pack, unsure))
    }

    /// Whether a triangle of the lanes `unsure` of `pack` blocks the
    /// segment, by [`segment_blocked`]: out of line (rare; inline, the
    /// compiler computed parts of the exact test ahead of every walk).
    #[cold]
    #[inline(never)]
    fn exact_lanes(&self, p: DVec3, x: DVec3, pack: leaf::Pack<'_>, mut unsure: u32) -> bool {
        while unsure != 0 {
            let lane = unsure.trailing_zeros() as usize;
            unsure &= unsure - 1;
            if segment_blocked(p, x, &self.occluders.triangles()[pack.id(lane) as usize]) {
                return true;
            }
        }
        false
    }
}

/// The lanes of the occlusion walk: [`WIDE`] for a node's boxes, [`PACK`]
/// for a leaf's triangles.
pub(super) trait WalkLanes: Copy {
    type Node: Lanes<WIDE>;
    type Leaf: Lanes<PACK>;
    fn node(self) -> Self::Node;
    fn leaf(self) -> Self::Leaf;
    /// [`Ray32::axes`] of four lanes (the same bits).
    fn axes(self, p: [f64; 4], d: [f64; 4]) -> Axes32<4>;
}

impl WalkLanes for Portable {
    type Node = Portable;
    type Leaf = Portable;
    #[inline(always)]
    fn axes(self, p: [f64; 4], d: [f64; 4]) -> Axes32<4> {
        Ray32::axes(p, d)
    }
    #[inline(always)]
    fn node(self) -> Portable {
        self
    }
    #[inline(always)]
    fn leaf(self) -> Portable {
        self
    }
}

#[cfg(all(feature = "simd", target_arch = "x86_64"))]
impl WalkLanes for pulp::x86::V3 {
    type Node = Avx8;
    type Leaf = Avx8;
    #[inline(always)]
    fn axes(self, p: [f64; 4], d: [f64; 4]) -> Axes32<4> {
        super::lanes::axes4(self, p, d)
    }
    #[inline(always)]
    fn node(self) -> Avx8 {
        Avx8(self)
    }
    #[inline(always)]
    fn leaf(self) -> Avx8 {
        Avx8(self)
    }
}

/// The slab test's per-ray vectors (see [`Ray32`]), `1/d` negated (see
/// [`WideSlab::hits`]).
pub(super) struct WideSlab<F> {
    near: [F; 3],
    far: [F; 3],
    neg_inv: [F; 3],
    entry: [usize; 3],
    one: F,
    slack: F,
}

impl<F: Copy> WideSlab<F> {
    #[inline(always)]
    pub(super) fn new<S: Lanes<WIDE, F = F>>(s: S, ray: &Ray32) -> WideSlab<F> {
        WideSlab {
            near: [
                s.splat(ray.near[0]),
                s.splat(ray.near[1]),
                s.splat(ray.near[2]),
            ],
            far: [
                s.splat(ray.far[0]),
                s.splat(ray.far[1]),
                s.splat(ray.far[2]),
            ],
            neg_inv: [
                s.splat(-ray.inv[0]),
                s.splat(-ray.inv[1]),
                s.splat(-ray.inv[2]),
            ],
            entry: ray.entry,
            one: s.splat(1.0),
            slack: s.splat(T_SLACK),
        }
    }

    /// The lanes of the occlusion tree's node `n` whose box the segment
    /// may meet, as a bit mask (the argument of
    /// [`Bvh::segment_unoccluded`]). Each parameter is computed as
    /// `(origin − plane) · (−1/d)`: the same bits as `(plane − origin) ·
    /// (1/d)` (negation is exact and rounding to nearest symmetric; only
    /// a zero's sign may differ, which no comparison sees), in the order
    /// that lets the plane be read straight from memory by the subtraction.
    #[inline(always)]
    pub(super) fn hits<S: Lanes<WIDE, F = F>>(&self, s: S, n: &WideNode) -> u32 {
        let (mut a, mut b) = ([s.splat(0.0); 3], [self.one; 3]);
        for axis in 0..3 {
            let side = self.entry[axis];
            let entry = s.load(&n.planes[side][axis]);
            let exit = s.load(&n.planes[1 - side][axis]);
            a[axis] = s.mul(s.sub(self.near[axis], entry), self.neg_inv[axis]);
            b[axis] = s.mul(s.sub(self.far[axis], exit), self.neg_inv[axis]);
        }
        // `max` and `min` are exact (no NaN arises): taken pairwise, the
        // same bits as one after another, in two steps rather than three.
        let t_near = s.max(s.max(a[0], a[1]), s.max(a[2], s.splat(0.0)));
        let t_far = s.min(s.min(b[0], b[1]), s.min(b[2], self.one));
        s.le(t_near, s.mul(t_far, self.slack))
    }
}

/// The occlusion walk's stack of node indices (its bound proven by
/// `Bvh::wide_stack_need`).
pub(super) trait WalkStack {
    fn set(&mut self, at: usize, node: u32);
    fn get(&self, at: usize) -> u32;
}

/// [`STACK`] entries on the machine stack, indexed modulo [`STACK`] (no
/// bounds test: a tree whose walk needs at most [`STACK`] entries never
/// indexes beyond them; the tests' builds check the proven bound).
pub(super) struct ArrayStack {
    entries: [u32; STACK],
    #[cfg(debug_assertions)]
    need: usize,
}

impl ArrayStack {
    #[inline(always)]
    pub(super) fn new(need: usize) -> ArrayStack {
        debug_assert!(need <= STACK);
        let _ = need;
        ArrayStack {
            entries: [0; STACK],
            #[cfg(debug_assertions)]
            need,
        }
    }
}

impl WalkStack for ArrayStack {
    #[inline(always)]
    fn set(&mut self, at: usize, node: u32) {
        #[cfg(debug_assertions)]
        assert!(at < self.need, "the walk outgrew its proven stack");
        self.entries[at % STACK] = node;
    }
    #[inline(always)]
    fn get(&self, at: usize) -> u32 {
        self.entries[at % STACK]
    }
}

/// Entries on the heap, exactly as many as the bound (a walk outgrowing
/// it panics).
pub(super) struct SliceStack<'a>(&'a mut [u32]);

impl WalkStack for SliceStack<'_> {
    #[inline(always)]
    fn set(&mut self, at: usize, node: u32) {
        self.0[at] = node;
    }
    #[inline(always)]
    fn get(&self, at: usize) -> u32 {
        self.0[at]
    }
}

/// What [`Bvh::segment_unoccluded_counting`] counts, summed over calls.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OcclusionCounts {
    /// Segments asked.
    pub segments: u64,
    /// Nodes whose child boxes were tested.
    pub nodes: u64,
    /// Leaves (packs of up to eight triangles) tested in `f32`.
    pub leaves: u64,
    /// Triangles tested in `f32`.
    pub triangles: u64,
    /// Triangles the `f32` test left uncertain, decided by the exact test.
    pub exact: u64,
}

/// What the walk counts (nothing, for `()`).
pub(super) trait Tally {
    /// A node's boxes tested.
    fn node(&mut self) {}
    /// A pack of `lanes` triangles tested, `unsure` of them left uncertain.
    fn pack(&mut self, lanes: u32, unsure: u32) {
        let _ = (lanes, unsure);
    }
}

impl Tally for () {}

impl Tally for OcclusionCounts {
    fn node(&mut self) {
        self.nodes += 1;
    }
    fn pack(&mut self, lanes: u32, unsure: u32) {
        self.leaves += 1;
        self.triangles += u64::from(lanes);
        self.exact += u64::from(unsure);
    }
}

/// The per-ray constants of the conservative `f32` slab test (see
/// [`Bvh::segment_unoccluded`] for the argument).
pub(super) struct Ray32 {
    /// The origin subtracted from the entry plane of each axis.
    pub(super) near: [f32; 3],
    /// The origin subtracted from the exit plane of each axis.
    pub(super) far: [f32; 3],
    /// `1/d` per axis.
    pub(super) inv: [f32; 3],
    /// The side (index of [`Node::q`]) of the entry plane of each axis: `1`
    /// (the maximum) where `dᵢ < 0`.
    pub(super) entry: [usize; 3],
}

/// `1 + 2⁻²⁰`: covers the `(1 + γ₃)/(1 − γ₃)` of three roundings on each side
/// of the comparison, and the rounding of the product itself.
pub(super) const T_SLACK: f32 = 1.0 + 1.0 / (1u32 << 20) as f32;

impl Ray32 {
    /// `None` when `p` or `x` leaves the `f32` range.
    #[inline(always)]
    pub(super) fn new(p: DVec3, x: DVec3) -> Option<Ray32> {
        (in_f32_range(p) && in_f32_range(x)).then(|| Ray32::in_range(p, x))
    }

    /// [`Ray32::new`] of endpoints within the `f32` range.
    #[inline(always)]
    pub(super) fn in_range(p: DVec3, x: DVec3) -> Ray32 {
        let d = x - p;
        let axes = Ray32::axes(p.to_array(), d.to_array());
        Ray32 {
            near: axes.near,
            far: axes.far,
            inv: axes.inv,
            entry: axes.backward.map(usize::from),
        }
    }

    /// The axes of [`Ray32::new`], `L` at a time (each lane the same
    /// operations, so the same bits, whatever `L`: the packets of closest
    /// hits take eight rays' axes at once, and their bits are each
    /// single ray's): from the coordinate `p` of a segment's start and `d`
    /// of its direction (both within the `f32` range), the origins
    /// subtracted from the entry and exit planes, the reciprocal of the
    /// direction, and whether the ray runs toward lower values (enters by
    /// the upper plane).
    #[inline(always)]
    pub(super) fn axes<const L: usize>(p: [f64; L], d: [f64; L]) -> Axes32<L> {
        const TINY: f32 = 1.0 / (1u128 << 100) as f32;
        let mut axes = Axes32 {
            near: [0.0; L],
            far: [0.0; L],
            inv: [0.0; L],
            backward: [false; L],
        };
        // Plain loops over the lanes (`array::from_fn`'s closures were
        // left out of line in the packets' set-up).
        for l in 0..L {
            let (p, d) = (p[l], d[l]);
            let o = f64::from(p as f32);
            let (di, tiny) = (d as f32, if d < 0.0 { -TINY } else { TINY });
            let di = if di.abs() < TINY { tiny } else { di };
            let delta = (p.abs() + d.abs()) * (1.0 / f64::from(1u32 << 21)) + 4.0 * f64::from(TINY);
            // `o ± wide` rounded to nearest lands on or beyond `o ± delta`
            // (see `Bvh::segment_unoccluded`): no branch per rounding.
            let wide =
                delta * (1.0 + 1.0 / f64::from(1u32 << 22)) + o.abs() / f64::from(1u32 << 23);
            let up = ((o + wide) as f32).clamp(-f32::MAX, f32::MAX);
            let down = ((o - wide) as f32).clamp(-f32::MAX, f32::MAX);
            let backward = di < 0.0;
            (axes.near[l], axes.far[l]) = if backward { (down, up) } else { (up, down) };
            axes.inv[l] = 1.0 / di;
            axes.backward[l] = backward;
        }
        axes
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
    pub(super) fn slab(&self, n: &Node, limit: f32) -> (u32, [f32; WIDTH]) {
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
