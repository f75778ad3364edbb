//! The conservative `f32` slab test of a segment against a node's four
//! boxes, and the any-hit traversal ([`Bvh::segment_unoccluded`]).

use super::node::{decode, Node, EMPTY, LEAF, WIDTH};
use super::{in_f32_range, Bvh};
use crate::kernel::lanes;
use crate::kernel::segment::segment_blocked;
use glam::DVec3;

/// Stack entries kept on the machine stack by the depth-first traversals;
/// deeper trees use a heap stack.
pub(super) const STACK: usize = 64;

/// Nodes [`Bvh::segment_unoccluded`] takes from its stack at a time, on
/// a tree of [`GROUPED_FROM`] bytes or more, after
/// [`DEPTH_FIRST_STEPS`] steps one node at a time.
pub(super) const GROUP: usize = 3;

/// The size of a tree (nodes and triangles, in bytes) from which
/// [`Bvh::segment_unoccluded`] walks it [`GROUP`] nodes at a time: a
/// smaller one stays in the caches, and there the grouped walk only adds
/// work (on the default scene's 3,674 triangles, Monte Carlo's rays took
/// about 15 % more time).
pub(super) const GROUPED_FROM: usize = 1 << 20;

/// The steps a grouped walk first takes one node at a time: a segment
/// that meets a closed mesh finds its blocker within a few, where a
/// group's other members would be work wasted (measured: on a sphere of
/// 81,920 triangles, 0.89× the rays/s of a walk one node at a time
/// without these steps, 1.09× with eight).
const DEPTH_FIRST_STEPS: usize = 8;

/// Stack entries of [`Bvh::segment_unoccluded`]'s grouped walk: trees up
/// to depth 17 (its need is `GROUP · WIDTH · (depth − 1)`, see
/// `Bvh::grouped_stack_need`; a tree over 10⁵ triangles has depth about
/// 11); deeper ones are walked one node at a time.
pub(super) const GROUPED_STACK: usize = 192;

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
    /// The walk is depth-first, one node at a time; on a tree of a
    /// megabyte or more (one the caches do not hold), after eight such
    /// steps it takes the top three nodes of its stack at a time: their
    /// slab tests run together, so the loads of their lines overlap where
    /// a walk one node at a time waits on each in turn. The answer does
    /// not depend on the order in which nodes and triangles are visited:
    /// it is whether some triangle whose box the segment may meet blocks
    /// it, each decided exactly.
    ///
    /// Endpoints with a non-finite coordinate: `true` (no triangle meets
    /// them, by [`segment_blocked`]'s convention). Coordinates beyond
    /// `f32::MAX`: every triangle is tested.
    #[must_use]
    pub fn segment_unoccluded(&self, p: DVec3, x: DVec3) -> bool {
        // Compiled for AVX2 where present: the same answers, the slab
        // tests and exact predicates in wider, three-operand instructions.
        // Each walk in a function of its own: with both in one, the
        // depth-first walk took 3 % more instructions.
        if self.grouped {
            lanes::vectorized(
                #[inline(always)]
                |_| self.unoccluded_here::<true>(p, x),
            )
        } else {
            lanes::vectorized(
                #[inline(always)]
                |_| self.unoccluded_here::<false>(p, x),
            )
        }
    }

    /// [`Bvh::segment_unoccluded`], compiled where it is called; its walk
    /// grouped or not as `GROUPED` says (the same answer either way).
    #[inline(always)]
    pub(super) fn unoccluded_here<const GROUPED: bool>(&self, p: DVec3, x: DVec3) -> bool {
        // The common case in one test (a NaN or an infinity fails it too),
        // the others out of line: for a segment that misses the root's
        // boxes the set-up is most of the query.
        let common = in_f32_range(p)
            && in_f32_range(x)
            && self.outliers.is_empty()
            && !self.nodes.is_empty();
        if !common {
            if let Some(answer) = self.unoccluded_off_tree(p, x) {
                return answer;
            }
        }
        let ray = Ray32::in_range(p, x);
        if GROUPED {
            self.walk::<GROUP, GROUPED_STACK>(p, x, &ray)
        } else {
            self.walk::<1, STACK>(p, x, &ray)
        }
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
        if self.nodes.is_empty() || !(in_f32_range(p) && in_f32_range(x)) {
            return Some(!self.triangles.iter().any(|t| segment_blocked(p, x, t)));
        }
        None
    }

    /// The any-hit walk of [`Bvh::segment_unoccluded`] over the tree,
    /// taking the top `G` nodes of its stack at a time (`N` entries of it
    /// on the machine stack).
    #[inline(always)]
    fn walk<const G: usize, const N: usize>(&self, p: DVec3, x: DVec3, ray: &Ray32) -> bool {
        // The nodes still to visit: `node`, then the stack from the top
        // down, by nonincreasing depth (see `Bvh::grouped_stack_need`).
        let mut stack = NodeStack::<N>::new();
        let mut walk = Walk {
            stack: stack.entries(if G == 1 {
                self.stack_need()
            } else {
                self.grouped_stack_need(G)
            }),
            top: 0,
            node: 0,
            touched: 0,
        };
        for _ in 0..if G > 1 { DEPTH_FIRST_STEPS } else { 0 } {
            if let Some(answer) = self.step::<1>(p, x, ray, &mut walk) {
                return answer;
            }
        }
        loop {
            if let Some(answer) = self.step::<G>(p, x, ray, &mut walk) {
                return answer;
            }
        }
    }

    /// One step of [`Bvh::walk`]: `walk.node` and up to `G − 1` entries
    /// from the top of the stack taken, their hit inner children pushed,
    /// their hit leaves tested, the next node popped; `Some(answer)` when
    /// the walk ends.
    #[inline(always)]
    fn step<const G: usize>(
        &self,
        p: DVec3,
        x: DVec3,
        ray: &Ray32,
        walk: &mut Walk<'_>,
    ) -> Option<bool> {
        // The group, deepest first. Their loads and slab tests overlap,
        // where a walk one node at a time would wait on each node's load
        // in turn.
        let more = walk.top.min(G - 1);
        let mut group = [&self.nodes[walk.node as usize]; G];
        walk.top -= more;
        let taken = walk.stack[walk.top..walk.top + more].iter().rev();
        for (n, &i) in group[1..].iter_mut().zip(taken) {
            *n = &self.nodes[i as usize];
        }
        let g = 1 + more;
        // Member `k`'s hit lanes at bits `4 (G − 1 − k)` on: the deepest
        // member's highest.
        const { assert!(G * WIDTH <= 32) };
        let mut hits = 0u32;
        for (k, n) in group.iter().enumerate().take(g) {
            hits |= ray.hits(n) << (WIDTH * (G - 1 - k));
        }
        let child_at = |bit: usize| group[G - 1 - bit / WIDTH].child[bit % WIDTH];
        // Inner children pushed from the shallowest member (the lowest
        // bits) up, which keeps the stack sorted by depth. A value is
        // read from each child node and leaf triangle as soon as its box is
        // hit: the loads start while the group's other lanes and leaves are
        // handled (the crate forbids the `unsafe` prefetch intrinsic), and
        // `black_box` keeps them. Measured: soup rays/s 1.07× on
        // `examples/ray_corpus.rs`.
        let mut leaves = 0u32;
        let mut rest = hits;
        while rest != 0 {
            let bit = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            let child = child_at(bit);
            if child & LEAF == 0 {
                walk.stack[walk.top] = child;
                walk.top += 1;
                walk.touched = walk
                    .touched
                    .wrapping_add(self.nodes[child as usize].child[0]);
            } else {
                leaves |= 1 << bit;
                let t = &self.triangles[(child & !LEAF) as usize];
                walk.touched = walk.touched.wrapping_add(t[0].x.to_bits() as u32);
            }
        }
        while leaves != 0 {
            let bit = leaves.trailing_zeros() as usize;
            leaves &= leaves - 1;
            let t = &self.triangles[(child_at(bit) & !LEAF) as usize];
            if segment_blocked(p, x, t) {
                std::hint::black_box(walk.touched);
                return Some(false);
            }
        }
        if walk.top == 0 {
            std::hint::black_box(walk.touched);
            return Some(true);
        }
        walk.top -= 1;
        walk.node = walk.stack[walk.top];
        None
    }
}

/// The state of [`Bvh::walk`]: the node to visit next, the stack of those
/// after it, and the sum of the values read to start loads early.
struct Walk<'a> {
    stack: &'a mut [u32],
    top: usize,
    node: u32,
    touched: u32,
}

/// The per-ray constants of the conservative `f32` slab test (see
/// [`Bvh::segment_unoccluded`] for the argument).
pub(super) struct Ray32 {
    /// The origin subtracted from the entry plane of each axis.
    pub(super) near: [f32; 3],
    /// The origin subtracted from the exit plane of each axis.
    pub(super) far: [f32; 3],
    /// `1/d` per axis.
    inv: [f32; 3],
    /// The side (index of [`Node::q`]) of the entry plane of each axis: `1`
    /// (the maximum) where `dᵢ < 0`.
    pub(super) entry: [usize; 3],
}

/// Axes of [`Ray32`]s, lane by lane ([`Ray32::axes`]).
pub(super) struct Axes32<const L: usize> {
    pub(super) near: [f32; L],
    pub(super) far: [f32; L],
    pub(super) inv: [f32; L],
    pub(super) backward: [bool; L],
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
