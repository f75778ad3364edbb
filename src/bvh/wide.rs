//! The occlusion tree: [`WIDE`] children a node, their boxes in
//! structure-of-arrays `f32` (one slab test over all of them at once),
//! leaves of up to [`PACK`] triangles (`leaf.rs`), and its build from the
//! binary tree.
//!
//! # Layout
//!
//! A [`WideNode`] is 256 bytes, four cache lines: the six planes of its
//! eight child boxes (`[side][axis][lane]`, the `f32` boxes of the build,
//! themselves rounded outward from the `f64` triangles, so each contains
//! every triangle below it exactly), and eight child references — an
//! inner node's index, [`LEAF`] `|` a pack's index, or [`EMPTY`], whose box
//! is inverted (`lo = f32::MAX`, `hi = −f32::MAX`) so that no segment's slab
//! test keeps it. A [`Pack`] is 192 bytes, three cache lines, for up to
//! four triangles.
//!
//! # Build
//!
//! Collapsed from the same binary tree as the 4-wide tree (PLOC and
//! reinsertion over the triangles' boxes, the runs of nested boxes split
//! in halves: `Source`): a node takes up to [`WIDE`] descendants,
//! repeatedly opening, among those holding more than [`PACK`] triangles,
//! the one of largest area; a descendant of at most [`PACK`] triangles
//! becomes a pack, a larger one a node.

use super::leaf::{Pack, PACK};
use super::{Bvh, Item, Source};
use obvhs::aabb::Aabb;

/// Children per node of the occlusion tree.
pub(super) const WIDE: usize = 8;
/// A reference to a pack in [`WideNode::child`].
pub(super) const LEAF: u32 = 1 << 31;
/// [`WideNode::child`] of an empty lane.
pub(super) const EMPTY: u32 = u32::MAX;

/// A node of the occlusion tree (see the module docs).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct WideNode {
    /// `planes[side][axis][lane]`: the child boxes' minima (side 0) and
    /// maxima (side 1).
    pub(super) planes: [[[f32; WIDE]; 3]; 2],
    /// Inner child: its node index; leaf: [`LEAF`] `|` its pack's index;
    /// empty lane: [`EMPTY`].
    pub(super) child: [u32; WIDE],
}

impl WideNode {
    /// No children: every box inverted.
    const EMPTY_NODE: WideNode = WideNode {
        planes: [[[f32::MAX; WIDE]; 3], [[-f32::MAX; WIDE]; 3]],
        child: [EMPTY; WIDE],
    };
}

impl Bvh {
    /// Builds the occlusion tree from `source` (see the module docs);
    /// `kept[i]` is the occluder index of the `i`-th box.
    pub(super) fn collapse_wide(&mut self, source: &Source<'_>, kept: &[u32]) {
        let counts = source.counts();
        let count = |item: Item| -> usize {
            match item {
                Item::Node(n) => counts[n] as usize,
                Item::Leaf(first, count) => source.tree.primitive_indices[first..first + count]
                    .iter()
                    .map(|&prim| source.groups.ranges[prim as usize].1 as usize)
                    .sum(),
                Item::Members(_, count) => count,
            }
        };
        let mut members = Vec::new();
        let mut triangles = Vec::with_capacity(PACK);
        let mut work = vec![(source.root(), 0usize, 1usize)];
        self.wide.push(WideNode::EMPTY_NODE);
        let mut depth = 1;
        while let Some((src, dst, level)) = work.pop() {
            depth = depth.max(level);
            let lanes = source.open(src, WIDE, |item| count(item) > PACK);
            let mut node = WideNode::EMPTY_NODE;
            for (lane, &item) in lanes.iter().enumerate() {
                let b: Aabb = source.aabb(item);
                for axis in 0..3 {
                    node.planes[0][axis][lane] = b.min[axis];
                    node.planes[1][axis][lane] = b.max[axis];
                }
                node.child[lane] = if count(item) <= PACK {
                    members.clear();
                    source.members(item, &mut members);
                    triangles.clear();
                    triangles.extend(members.iter().map(|&m| {
                        let id = kept[m as usize];
                        (self.occluders.triangles()[id as usize], id)
                    }));
                    let (pack, ids) = Pack::new(&triangles);
                    self.packs.push(pack);
                    self.pack_ids.push(ids);
                    LEAF | (self.packs.len() - 1) as u32
                } else {
                    work.push((item, self.wide.len(), level + 1));
                    self.wide.push(WideNode::EMPTY_NODE);
                    (self.wide.len() - 1) as u32
                };
            }
            self.wide[dst] = node;
        }
        self.wide_depth = depth;
    }

    /// Stack entries the occlusion walk can need: at most `WIDE − 1`
    /// siblings waiting at each level, and the children of the node being
    /// visited.
    pub(super) fn wide_stack_need(&self) -> usize {
        self.wide_depth * (WIDE - 1) + 1
    }
}
