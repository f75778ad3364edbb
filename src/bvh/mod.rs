//! The scene's triangles ([`Occluders`]: one flat list over all meshes,
//! each triangle tagged with its object id) and a bounding volume hierarchy
//! over them ([`Bvh`]), for the occlusion rays of the Monte Carlo reference
//! and of the hard shadow, for culling the triangles a receiver's view of
//! the light can meet (the exact reference), and for the renderer's primary
//! rays ([`Bvh::closest_hit`]: the nearest triangle on a ray, decided with
//! the same exact test).
//!
//! # How it decides
//!
//! A binary tree is built by `obvhs` (PLOC, `Bvh2`; then our reinsertion,
//! `reinsert.rs`) over boxes computed in `f64` and rounded *outward* to
//! `f32` (a run of nested boxes, on which PLOC is quadratic, given to it as
//! one box and split in halves by us: `nested.rs`), then collapsed into
//! two trees of our own:
//!
//! - the *occlusion tree* (`wide.rs`), for [`Bvh::segment_unoccluded`]:
//!   eight child boxes a node in structure-of-arrays `f32`, tested in one
//!   pass, and leaves of up to eight triangles in `f32` (`leaf.rs`),
//!   tested together with a proven error bound, each triangle whose signs
//!   the bound leaves uncertain going to the exact test;
//! - the *4-wide tree* (`node.rs`), for closest hits and culling: one
//!   64-byte node per four children, boxes quantised outward to 8 bits per
//!   plane, one triangle a leaf.
//!
//! Both traversals are conservative (see [`Bvh::segment_unoccluded`]): the
//! `f32` trees only ever prune boxes the true `f64` segment cannot meet.
//! Every triangle a traversal reaches is decided exactly as
//! [`segment_blocked`] decides it, in `f64` with the exact [`orient3d`]
//! wherever an `f32` or `f64` evaluation cannot be certain. The answer is
//! therefore exactly [visibility](crate::definitions#visibility)'s: the
//! light point `x` is visible from `p` iff the open segment `(p, x)` meets
//! no triangle, with an edge shared by two triangles never leaking light.
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
//!
//! # Layout
//!
//! This file holds the trees' build; `nested.rs` the runs of nested boxes
//! the build groups; `reinsert.rs` the improvement of the binary tree by
//! moving subtrees, its work bounded; `wide.rs` the occlusion tree's node
//! and its collapse; `leaf.rs` its leaves' packs and their `f32` test;
//! `lanes.rs` the eight `f32` lanes both run on (AVX2 through `pulp`, or
//! portable); `ray.rs` the conservative `f32` slab tests and the any-hit
//! walk ([`Bvh::segment_unoccluded`]); `node.rs` the quantised 4-wide
//! node; `closest.rs` the closest hit ([`Bvh::closest_hit`]); `hit.rs`
//! what it returns ([`Hit`]) and the triangles' unit normals it reads;
//! `packet.rs` the closest hits of eight coherent rays through one walk
//! (for [`Bvh::closest_hits`]); `hull.rs` the culling query of the exact
//! reference ([`Bvh::triangles_meeting_hull`]); `occluders.rs` the
//! triangle list. The exact segment–triangle test itself is a kernel,
//! [`crate::kernel::segment`].
//!
//! # Memory
//!
//! Per triangle: the occluders (76 bytes: three `f64` corners and the
//! object id), the 4-wide tree's copy of each triangle and its index (76)
//! and nodes (about 21), and the occlusion tree's packs (`32 + 40 n` bytes
//! for `n` triangles, with each triangle's index: about 40–60 a triangle)
//! and nodes (about 10–50): about 250 bytes a triangle in all (the
//! 100,000-triangle soup of `examples/ray_corpus.rs`: 6.9 MB for the
//! occlusion tree, the sphere 5.8 MB; see [`Bvh::memory`]).
//!
//! [`segment_blocked`]: crate::kernel::segment::segment_blocked
//! [`orient3d`]: crate::kernel::predicate::orient3d

mod closest;
mod hit;
mod hull;
mod lanes;
mod leaf;
mod nested;
mod node;
mod occluders;
mod packet;
mod ray;
mod reinsert;
#[cfg(test)]
mod tests;
mod wide;

pub use hit::Hit;
pub use occluders::Occluders;
pub use ray::OcclusionCounts;

use glam::{DVec3, Vec3A};
use node::{Node, LEAF, WIDTH};
use obvhs::aabb::Aabb;
use obvhs::bvh2::builder::build_bvh2;
use obvhs::bvh2::Bvh2;
use obvhs::BvhBuildParams;
use std::fmt;
use std::time::Duration;

/// An entry of a node under construction: an obvhs node; a run of its
/// `primitive_indices` (a leaf of more than one box, split in halves); or
/// a run of [`nested::Groups::order`] (one box's members, split in halves).
#[derive(Clone, Copy)]
enum Item {
    Node(usize),
    Leaf(usize, usize),
    Members(usize, usize),
}

/// obvhs's binary tree and the groups it was built over, read as a tree
/// of [`Item`]s: what both of our trees are collapsed from.
pub(super) struct Source<'a> {
    tree: &'a Bvh2,
    /// The boxes of the kept triangles.
    boxes: &'a [Aabb],
    groups: &'a nested::Groups,
}

impl Source<'_> {
    /// The root, as an item.
    fn root(&self) -> Item {
        self.normal(Item::Node(0))
    }

    /// The box of an item.
    fn aabb(&self, item: Item) -> Aabb {
        let (prims, order) = (&self.tree.primitive_indices, &self.groups.order);
        match item {
            Item::Node(n) => *self.tree.nodes[n].aabb(),
            Item::Leaf(first, count) => prims[first..first + count]
                .iter()
                .fold(Aabb::empty(), |b, &i| {
                    b.union(&self.groups.boxes[i as usize])
                }),
            Item::Members(first, count) => order[first..first + count]
                .iter()
                .fold(Aabb::empty(), |b, &i| b.union(&self.boxes[i as usize])),
        }
    }

    /// An obvhs leaf as the run of its primitives; one primitive as the run
    /// of its members.
    fn normal(&self, item: Item) -> Item {
        let item = match item {
            Item::Node(n) if self.tree.nodes[n].is_leaf() => {
                let node = &self.tree.nodes[n];
                Item::Leaf(node.first_index as usize, node.prim_count as usize)
            }
            other => other,
        };
        match item {
            Item::Leaf(first, 1) => {
                let (at, count) = self.groups.ranges[self.tree.primitive_indices[first] as usize];
                Item::Members(at as usize, count as usize)
            }
            other => other,
        }
    }

    /// The two children of an item (runs split in halves); `None` for one
    /// triangle.
    fn children(&self, item: Item) -> Option<[Item; 2]> {
        let halves =
            |first: usize, count: usize| (first, count / 2, first + count / 2, count - count / 2);
        match item {
            Item::Node(n) => {
                let first = self.tree.nodes[n].first_index as usize;
                Some([
                    self.normal(Item::Node(first)),
                    self.normal(Item::Node(first + 1)),
                ])
            }
            Item::Leaf(first, count) if count > 1 => {
                let (a, na, b, nb) = halves(first, count);
                Some([
                    self.normal(Item::Leaf(a, na)),
                    self.normal(Item::Leaf(b, nb)),
                ])
            }
            Item::Members(first, count) if count > 1 => {
                let (a, na, b, nb) = halves(first, count);
                Some([Item::Members(a, na), Item::Members(b, nb)])
            }
            Item::Leaf(..) | Item::Members(..) => None,
        }
    }

    /// The lanes of a node made from `item`: up to `width` descendants,
    /// found by repeatedly opening, of the entries `openable` accepts, the
    /// one of largest area.
    fn open(&self, item: Item, width: usize, openable: impl Fn(Item) -> bool) -> Vec<Item> {
        let mut lanes = vec![item];
        while lanes.len() < width {
            let widest = lanes
                .iter()
                .enumerate()
                .filter(|(_, &item)| openable(item) && self.children(item).is_some())
                .max_by(|(_, &a), (_, &b)| {
                    self.aabb(a)
                        .half_area()
                        .total_cmp(&self.aabb(b).half_area())
                })
                .map(|(k, _)| k);
            let Some(k) = widest else { break };
            let [left, right] = self.children(lanes[k]).expect("filtered");
            lanes[k] = left;
            lanes.push(right);
        }
        // (obvhs leaves and groups are never empty; an empty run would not
        // end.)
        lanes.retain(|item| !matches!(item, Item::Leaf(_, 0) | Item::Members(_, 0)));
        lanes
    }

    /// The indices (in the kept boxes) of the triangles under `item`, in
    /// order.
    fn members(&self, item: Item, out: &mut Vec<u32>) {
        match item {
            Item::Node(n) => {
                let first = self.tree.nodes[n].first_index as usize;
                if self.tree.nodes[n].is_leaf() {
                    self.members(
                        Item::Leaf(first, self.tree.nodes[n].prim_count as usize),
                        out,
                    );
                } else {
                    self.members(Item::Node(first), out);
                    self.members(Item::Node(first + 1), out);
                }
            }
            Item::Leaf(first, count) => {
                for &prim in &self.tree.primitive_indices[first..first + count] {
                    let (at, count) = self.groups.ranges[prim as usize];
                    out.extend_from_slice(&self.groups.order[at as usize..(at + count) as usize]);
                }
            }
            Item::Members(first, count) => {
                out.extend_from_slice(&self.groups.order[first..first + count]);
            }
        }
    }
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
    /// The depth of the tree (the root alone, or no tree: 1).
    depth: usize,
    /// The occlusion tree (`wide.rs`): its nodes, the root first (none
    /// when there is no tree), its leaf packs and its depth.
    wide: Vec<wide::WideNode>,
    packs: leaf::Packs,
    wide_depth: usize,
    /// Triangles with a coordinate beyond [`TREE_RANGE`], kept out of the
    /// tree and tested by every query, and their indices in `occluders`.
    outliers: Vec<[DVec3; 3]>,
    outlier_ids: Vec<u32>,
    /// The exact bounding box `(lo, hi)` of every finite triangle (in the
    /// tree or not); `None` when there is none.
    bounds: Option<(DVec3, DVec3)>,
    /// Each occluder's unit geometric normal, computed on the first
    /// closest-hit query (see [`Bvh::closest_hit`]'s `Hit::normal`).
    normals: std::sync::OnceLock<Vec<DVec3>>,
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
            .field("occlusion_nodes", &self.wide.len())
            .field(
                "occlusion_bytes",
                &(self.wide.len() * 256 + self.packs.bytes()),
            )
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

/// The binary tree over `boxes` our tree is collapsed from, one box a
/// leaf (the 4-wide node test then culls single triangles, cheaper than
/// their exact test: chosen by measurement, see benches/README.md §
/// Building the tree): [`ploc_tree`], then our reinsertion (`reinsert.rs`:
/// the improvement of obvhs's reinsertion passes, whose searches are
/// quadratic on heavily overlapping boxes, within a budget of order
/// `n log n`). Also returns the reinsertion's work.
fn binary_tree(boxes: &[Aabb]) -> (Bvh2, reinsert::Work) {
    let mut tree = ploc_tree(boxes);
    let work = reinsert::optimise(&mut tree);
    (tree, work)
}

/// obvhs's PLOC over `boxes`, one a leaf, with its slowest preset's search
/// and no reinsertion.
fn ploc_tree(boxes: &[Aabb]) -> Bvh2 {
    let params = BvhBuildParams {
        max_prims_per_leaf: 1,
        reinsertion_batch_ratio: 0.0,
        ..BvhBuildParams::very_slow_build()
    };
    build_bvh2(boxes, params, &mut Duration::default())
}

/// Whether every coordinate is finite and at most `f32::MAX` in magnitude:
/// the region the `f32` boxes are valid in (see [`Bvh::new`]).
fn in_f32_range(v: DVec3) -> bool {
    v.abs().max_element() <= f64::from(f32::MAX)
}

impl Bvh {
    /// The BVH over every triangle of the scene's meshes: what the
    /// references, the renderer and the methods need, in one call
    /// (`Bvh::new(Occluders::from_scene(scene))`).
    #[must_use]
    pub fn from_scene(scene: &crate::scene::Scene) -> Bvh {
        Bvh::new(Occluders::from_scene(scene))
    }

    /// Builds the hierarchy (single-threaded; about 0.3 s per 100k
    /// triangles).
    ///
    /// Each triangle's box is computed in `f64` and rounded outward to `f32`,
    /// so it contains the triangle exactly; coordinates beyond `f32::MAX`
    /// clamp to it, which keeps the box valid inside `[−f32::MAX,
    /// f32::MAX]³`, the only region queries use the tree in. Triangles with
    /// a non-finite corner are left out, and so are exact copies of an
    /// earlier triangle (the same corners, bit for bit, in the same
    /// order): every query answers as if they were there — a copy hides
    /// nothing its first does not, closest hits tie to the lower index —
    /// except that the culling query reports the first copy's index only.
    #[must_use]
    pub fn new(occluders: Occluders) -> Bvh {
        let mut boxes = Vec::with_capacity(occluders.len());
        let mut kept = Vec::with_capacity(occluders.len());
        let (mut outliers, mut outlier_ids) = (Vec::new(), Vec::new());
        let mut bounds: Option<(DVec3, DVec3)> = None;
        // Exact copies (the same three corners in the same order, so that
        // every rounded answer is the same bits) are indexed once, as their
        // first: a copy blocks nothing its first does not, and ties go to
        // the lower index anyway. Without this, identical boxes, which
        // cannot be split, slow the build, and every ray through them tests
        // each copy (measured in benches/README.md § Building the tree).
        let mut seen = std::collections::HashSet::with_capacity(occluders.len());
        for (i, t) in occluders.triangles().iter().enumerate() {
            if !t.iter().all(|v| v.is_finite()) {
                continue;
            }
            let key = t.map(|v| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]);
            if !seen.insert(key) {
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
            depth: 1,
            wide: Vec::new(),
            packs: leaf::Packs::default(),
            wide_depth: 1,
            outliers,
            outlier_ids,
            bounds,
            normals: std::sync::OnceLock::new(),
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
        let groups = nested::Groups::find(&boxes);
        let (tree, _) = binary_tree(groups.as_ref().map_or(&boxes[..], |g| &g.boxes[..]));
        let groups = groups.unwrap_or_else(|| nested::Groups::identity(&boxes));
        let source = Source {
            tree: &tree,
            boxes: &boxes,
            groups: &groups,
        };
        bvh.collapse(&source, &kept);
        bvh.collapse_wide(&source, &kept);
        bvh
    }

    /// Turns obvhs's binary tree into ours: each node takes up to [`WIDTH`]
    /// descendants (repeatedly opening the entry of largest area), every
    /// leaf lane holds one triangle, and the triangles are copied in leaf
    /// order.
    fn collapse(&mut self, source: &Source<'_>, kept: &[u32]) {
        // (entry, our node, depth of our node)
        let mut work = vec![(source.root(), 0usize, 1usize)];
        self.nodes.push(Node::EMPTY_NODE);
        let mut depth = 1;
        while let Some((src, dst, level)) = work.pop() {
            depth = depth.max(level);
            let lanes = source.open(src, WIDTH, |_| true);
            let lane_boxes: Vec<([f32; 3], [f32; 3])> = lanes
                .iter()
                .map(|&item| {
                    let b = source.aabb(item);
                    (b.min.to_array(), b.max.to_array())
                })
                .collect();
            let mut node = Node::quantised(&lane_boxes);
            for (lane, &item) in lanes.iter().enumerate() {
                node.child[lane] = match item {
                    Item::Members(first, 1) => {
                        let id = kept[source.groups.order[first] as usize];
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
        self.depth = depth;
    }

    /// Stack entries a depth-first traversal can need: at most `WIDTH − 1`
    /// siblings waiting at each level, and the children of the node being
    /// visited.
    pub(super) fn stack_need(&self) -> usize {
        self.depth * (WIDTH - 1) + 1
    }

    /// The largest coordinate magnitude of the finite triangles (from the
    /// exact bounding box; 0 when there are none).
    pub(crate) fn max_coordinate(&self) -> f64 {
        self.bounds
            .map_or(0.0, |(lo, hi)| lo.abs().max(hi.abs()).max_element())
    }

    /// The triangles it was built over.
    #[must_use]
    pub fn occluders(&self) -> &Occluders {
        &self.occluders
    }

    /// The bytes it holds, part by part (the lengths of its arrays; the
    /// normals only once a closest-hit query has computed them).
    #[must_use]
    pub fn memory(&self) -> Memory {
        use std::mem::size_of;
        let corners = size_of::<[DVec3; 3]>();
        Memory {
            occluders: self.occluders.len() * (corners + size_of::<u32>()),
            tree: self.nodes.len() * size_of::<Node>()
                + (self.triangles.len() + self.outliers.len()) * (corners + size_of::<u32>()),
            occlusion_tree: self.wide.len() * size_of::<wide::WideNode>() + self.packs.bytes(),
            normals: self
                .normals
                .get()
                .map_or(0, |n| n.len() * size_of::<DVec3>()),
        }
    }
}

/// The bytes a [`Bvh`] holds ([`Bvh::memory`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Memory {
    /// The triangles it owns and their object ids.
    pub occluders: usize,
    /// The 4-wide tree of closest hits and culling: its nodes, and its
    /// copy of the triangles in leaf order with their indices.
    pub tree: usize,
    /// The occlusion tree: its nodes and its leaves' packs.
    pub occlusion_tree: usize,
    /// Each triangle's unit normal, once computed.
    pub normals: usize,
}

impl Memory {
    /// All of it.
    #[must_use]
    pub fn total(&self) -> usize {
        self.occluders + self.tree + self.occlusion_tree + self.normals
    }
}
