//! The occlusion tree: [`WIDE`] children a node, their boxes in
//! structure-of-arrays `f32` (one slab test over all eight at once), leaves
//! of up to [`PACK`] triangles (`leaf.rs`), and its build from the binary
//! tree.
//!
//! # Layout
//!
//! A [`WideNode`] is 256 bytes, four cache lines: the six planes of its
//! eight child boxes (`[side][axis][lane]`: the `f32` boxes of the build,
//! themselves rounded outward from the `f64` triangles, so each contains
//! every triangle below it exactly), eight child references — an inner
//! node's index, [`LEAF`] `|` a pack's index, or [`EMPTY`], whose box is
//! inverted (`lo = f32::MAX`, `hi = −f32::MAX`) so that no segment's slab
//! test keeps it — and the mask of the lanes holding packs. A pack of `n`
//! triangles takes `32 + 40 n` bytes, its indices included (`leaf.rs`). The child boxes are not
//! quantised as the 4-wide tree's are: the walk's time goes to its loads
//! and to the leaves, and decoding eight lanes' planes would add about a
//! third to a node visit's instructions.
//!
//! # Build
//!
//! Collapsed from the same binary tree as the 4-wide tree (PLOC and
//! reinsertion over the triangles' boxes, the runs of nested boxes split
//! in halves: `Source`), by the surface area heuristic: for every entry of
//! the binary tree, children before parents, the least expected cost of
//! representing it on `k = 1..=WIDE` lanes of its parent — as one lane (a
//! pack, if it holds at most [`PACK`] triangles, or a node over its
//! children's best sharing of `WIDE` lanes) or its children sharing the
//! `k` lanes — where a node costs [`NODE_COST`] and a pack [`PACK_COST`]
//! times its area (the chance a random ray meets its box). This is the
//! optimal collapse of Ylitie, Karras and Laine ("Efficient Incoherent Ray
//! Traversal on GPUs Through Compressed Wide BVHs", 2017, §4); the nodes
//! are then laid out from the root down as the choices say.

use super::leaf::PACK;
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
    /// The lanes holding a pack, as bits.
    pub(super) leaf_lanes: u32,
}

impl WideNode {
    /// No children: every box inverted.
    pub(super) const EMPTY_NODE: WideNode = WideNode {
        planes: [[[f32::MAX; WIDE]; 3], [[-f32::MAX; WIDE]; 3]],
        child: [EMPTY; WIDE],
        leaf_lanes: 0,
    };
}

/// The cost of visiting a node, in the surface area heuristic the collapse
/// minimises, per unit of its area.
const NODE_COST: f32 = 1.0;
/// The cost of testing a pack, per unit of its area: equal to a node
/// visit's, chosen by measurement (higher pack costs make smaller packs,
/// fewer instructions a ray but more nodes, memory and time; see
/// benches/README.md § Building the tree).
const PACK_COST: f32 = 1.0;

/// An entry of the binary tree, made explicit for the collapse.
struct Binary {
    aabb: Aabb,
    /// Children (entries after this one); `None` for one triangle.
    children: Option<[u32; 2]>,
    /// Triangles under it.
    count: u32,
    /// The item it stands for (its triangles are [`Source::members`]').
    item: Item,
}

/// The least cost of an entry given `k` lanes (index `k − 1`), and how
/// it is reached.
#[derive(Clone, Copy)]
struct Best {
    /// The least cost on at most `k` lanes.
    cost: [f32; WIDE],
    /// The least cost of its children shared out on at most `k ≥ 2` lanes.
    shared: [f32; WIDE],
    /// For `shared`: the lanes its left child takes (`0`: the sharing on
    /// `k − 1` lanes is as good).
    split: [u8; WIDE],
    /// For `cost` with `k ≥ 2`: whether the entry as one lane is best.
    whole: [bool; WIDE],
    /// As one lane: whether it is a pack (else a node).
    pack: bool,
}

impl Bvh {
    /// Builds the occlusion tree from `source` (see the module docs);
    /// `kept[i]` is the occluder index of the `i`-th box.
    pub(super) fn collapse_wide(&mut self, source: &Source<'_>, kept: &[u32]) {
        // The binary tree, parents before children.
        let mut binary: Vec<Binary> = Vec::new();
        let mut pending = vec![(source.root(), u32::MAX, 0usize)];
        while let Some((item, parent, side)) = pending.pop() {
            let at = binary.len() as u32;
            if parent != u32::MAX {
                if let Some(c) = &mut binary[parent as usize].children {
                    c[side] = at;
                }
            }
            let children = source.children(item);
            binary.push(Binary {
                aabb: source.aabb(item),
                children: children.map(|_| [0, 0]),
                count: 1,
                item,
            });
            if let Some([left, right]) = children {
                pending.push((right, at, 1));
                pending.push((left, at, 0));
            }
        }
        // Costs, children before parents (Ylitie, Karras and Laine 2017,
        // §4: the least cost of each entry on 1 to WIDE lanes).
        let mut best = vec![
            Best {
                cost: [f32::INFINITY; WIDE],
                shared: [f32::INFINITY; WIDE],
                split: [0; WIDE],
                whole: [true; WIDE],
                pack: false,
            };
            binary.len()
        ];
        for n in (0..binary.len()).rev() {
            let area = binary[n].aabb.half_area().max(0.0);
            let Some([l, r]) = binary[n].children else {
                best[n].cost = [area * PACK_COST; WIDE];
                best[n].pack = true;
                continue;
            };
            let (l, r) = (l as usize, r as usize);
            binary[n].count = binary[l].count + binary[r].count;
            let mut b = best[n];
            // The children shared out on 2 to WIDE lanes.
            for k in 2..=WIDE {
                let (mut cost, mut split) = (b.shared[k - 2], 0u8);
                for j in 1..k {
                    let c = best[l].cost[j - 1] + best[r].cost[k - j - 1];
                    if c < cost {
                        (cost, split) = (c, j as u8);
                    }
                }
                b.shared[k - 1] = cost;
                b.split[k - 1] = split;
            }
            // As one lane: a node over its children's lanes, or a pack.
            let node = area * NODE_COST + b.shared[WIDE - 1];
            let pack = area * PACK_COST;
            b.pack = binary[n].count as usize <= PACK && pack <= node;
            b.cost[0] = if b.pack { pack } else { node };
            for k in 2..=WIDE {
                b.whole[k - 1] = b.cost[0] <= b.shared[k - 1];
                b.cost[k - 1] = b.cost[0].min(b.shared[k - 1]);
            }
            best[n] = b;
        }
        // The nodes, from the root down.
        let mut members = Vec::new();
        let mut triangles = Vec::with_capacity(PACK);
        let mut lanes = Vec::with_capacity(WIDE);
        let mut work = vec![(0usize, 0usize, 1usize)];
        self.wide.push(WideNode::EMPTY_NODE);
        let mut depth = 1;
        while let Some((src, dst, level)) = work.pop() {
            depth = depth.max(level);
            lanes.clear();
            if best[src].pack {
                lanes.push(src);
            } else {
                spread(&binary, &best, src, WIDE, &mut lanes);
            }
            let mut node = WideNode::EMPTY_NODE;
            for (lane, &n) in lanes.iter().enumerate() {
                let b = &binary[n];
                for axis in 0..3 {
                    node.planes[0][axis][lane] = b.aabb.min[axis];
                    node.planes[1][axis][lane] = b.aabb.max[axis];
                }
                node.child[lane] = if best[n].pack {
                    members.clear();
                    source.members(b.item, &mut members);
                    triangles.clear();
                    triangles.extend(members.iter().map(|&m| {
                        let id = kept[m as usize];
                        (self.occluders.triangles()[id as usize], id)
                    }));
                    node.leaf_lanes |= 1 << lane;
                    LEAF | self.packs.push(&triangles)
                } else {
                    work.push((n, self.wide.len(), level + 1));
                    self.wide.push(WideNode::EMPTY_NODE);
                    (self.wide.len() - 1) as u32
                };
            }
            self.wide[dst] = node;
        }
        self.packs.finish();
        self.wide_depth = depth;
    }

    /// Stack entries the occlusion walk can need: at most `WIDE − 1`
    /// siblings waiting at each level, and the children of the node being
    /// visited.
    pub(super) fn wide_stack_need(&self) -> usize {
        self.wide_depth * (WIDE - 1) + 1
    }
}

/// The lanes of the node over binary entry `n`: its children shared out
/// on at most `k` lanes as `best` says.
fn spread(binary: &[Binary], best: &[Best], n: usize, k: usize, lanes: &mut Vec<usize>) {
    let [l, r] = binary[n].children.expect("a node has children");
    let mut k = k;
    while best[n].split[k - 1] == 0 {
        k -= 1;
    }
    let j = best[n].split[k - 1] as usize;
    place(binary, best, l as usize, j, lanes);
    place(binary, best, r as usize, k - j, lanes);
}

/// Binary entry `n` on at most `k` lanes, as `best` says.
fn place(binary: &[Binary], best: &[Best], n: usize, k: usize, lanes: &mut Vec<usize>) {
    if k == 1 || best[n].whole[k - 1] {
        lanes.push(n);
    } else {
        spread(binary, best, n, k, lanes);
    }
}
