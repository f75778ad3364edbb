//! Reinsertion: the binary tree PLOC built, improved by moving subtrees to
//! where they cost less, with the search's work bounded.
//!
//! The cost of a binary tree is the sum of its inner nodes' surface areas
//! (the surface area heuristic: a random ray visits a node in proportion to
//! its area). Moving a subtree `A` from beside its sibling `S` to beside a
//! target `T` removes `A`'s parent `P` and shrinks each ancestor of `P` to
//! what it holds without `A`, then adds a node `A ∪ T` in `T`'s place and
//! grows each ancestor of `T` to hold `A`. Meister and Bittner ("Parallel
//! Reinsertion for Bounding Volume Hierarchy Optimization", 2018) find the
//! best target by a branch-and-bound search: walking up from `P`, the
//! removal's credit so far (`area(P)` plus each ancestor's shrinkage below
//! the level where the target's subtree hangs) is carried down into the
//! subtree of the path's sibling at each level; at a node `R` reached with
//! credit `c`, inserting there gains `c − area(R ∪ A)`, and descending
//! below `R` leaves `c − (area(R ∪ A) − area(R))`. No target below `R` can
//! gain more than `c − area(A)` (the new node holds `A`), which prunes the
//! search.
//!
//! Here the nodes are taken largest area first, in passes over a shrinking
//! share of them (all, a third, a fifth, … a thirty-first), and each
//! move is made as soon as it is found (one thread: no conflicts between
//! moves to resolve).
//!
//! # The bound on the work
//!
//! The pruning needs areas that differ: where boxes overlap heavily — a
//! soup of large triangles crossing one another — every subtree's area is
//! close to its parent's, the credit hardly falls on the way down, and a
//! search visits most of the tree. With every node a candidate (obvhs's
//! optimiser) the build is quadratic there (measured in benches/README.md
//! § Building the tree). So the searches share a
//! budget of [`VISITS_PER_NODE_LOG`]` · n · (⌊log₂ n⌋ + 1)` node visits (`n` the
//! node count): a search that exhausts it keeps the best target found so
//! far, and no search follows. Ordinary scenes need under a third of it
//! (about `3 n log₂ n`: 47 visits a node on the 100,000-triangle soup of
//! `examples/ray_corpus.rs`, 43 on an 81,920-triangle sphere, where the
//! budget allows 144 and 144), so their trees are those of the unbounded
//! search.

use obvhs::bvh2::reinsertion::reinsert_node;
use obvhs::bvh2::Bvh2;

/// The budget's factor: node visits per node and per level of a balanced
/// tree (ours; ordinary scenes use about 3).
pub(super) const VISITS_PER_NODE_LOG: u64 = 8;

/// The passes: pass `k` searches the `n / (2k + 1)` largest nodes (one pass
/// of obvhs's schedule; on the corpora's trees the moves stop within
/// eight).
const PASSES: usize = 16;

/// What an optimisation did.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Work {
    /// Nodes visited by the searches.
    pub visits: u64,
    /// The budget it had.
    pub budget: u64,
    /// Subtrees moved.
    pub moves: u64,
}

impl Work {
    /// Whether the budget ran out (the later searches were skipped).
    pub(super) fn exhausted(&self) -> bool {
        self.visits >= self.budget
    }
}

/// The other child of `node`'s parent (obvhs keeps siblings in pairs at
/// `(2k + 1, 2k + 2)`).
fn sibling(node: usize) -> usize {
    if node % 2 == 1 {
        node + 1
    } else {
        node - 1
    }
}

/// Improves `tree` by reinsertion within the work budget (see the module
/// docs).
pub(super) fn optimise(tree: &mut Bvh2) -> Work {
    let n = tree.nodes.len();
    let levels = u64::from(usize::BITS - n.leading_zeros());
    let mut work = Work {
        budget: VISITS_PER_NODE_LOG * n as u64 * levels,
        ..Work::default()
    };
    if n < 3 {
        return work;
    }
    tree.init_parents_if_uninit();
    tree.children_are_ordered_after_parents = false;
    let mut stack = Vec::new();
    for pass in 0..PASSES {
        // The largest nodes first (ties by slot, so that the build is
        // deterministic); a move changes the nodes in three slots, so a
        // later candidate may stand for another node than when chosen,
        // which only changes which nodes are tried.
        let by_area = |a: &(f32, u32), b: &(f32, u32)| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1));
        let mut candidates: Vec<(f32, u32)> = (1..n)
            .map(|i| (tree.nodes[i].aabb().half_area(), i as u32))
            .collect();
        let count = (n / (2 * pass + 1)).clamp(1, n - 1);
        if count < candidates.len() {
            candidates.select_nth_unstable_by(count, by_area);
            candidates.truncate(count);
        }
        candidates.sort_unstable_by(by_area);
        for &(_, node) in &candidates {
            if work.exhausted() {
                return work;
            }
            if let Some(target) = best_target(tree, node as usize, &mut work, &mut stack) {
                reinsert_node(tree, node as usize, target);
                work.moves += 1;
            }
        }
    }
    work
}

/// The target whose reinsertion of `node` beside it lowers the tree's cost
/// most, if any does, within what is left of `work`'s budget.
fn best_target(
    tree: &Bvh2,
    node: usize,
    work: &mut Work,
    stack: &mut Vec<(usize, f32)>,
) -> Option<usize> {
    let own = *tree.nodes[node].aabb();
    let own_area = own.half_area();
    let parent = tree.parents[node] as usize;
    let (mut best, mut best_gain) = (None, 0.0f32);
    // The path's sibling at this level, the ancestor it hangs from, the
    // removal's credit for targets below it, and the ancestor's box
    // without `node`.
    let (mut hanging, mut above) = (sibling(node), parent);
    let mut credit = tree.nodes[parent].aabb().half_area();
    let mut without = *tree.nodes[hanging].aabb();
    loop {
        stack.push((hanging, credit));
        while let Some((at, credit_here)) = stack.pop() {
            if credit_here - own_area <= best_gain {
                continue;
            }
            if work.exhausted() {
                stack.clear();
                break;
            }
            work.visits += 1;
            let target = &tree.nodes[at];
            let gain = credit_here - target.aabb().union(&own).half_area();
            if gain > best_gain {
                (best, best_gain) = (Some(at), gain);
            }
            if !target.is_leaf() {
                let below = gain + target.aabb().half_area();
                let first = target.first_index as usize;
                stack.push((first, below));
                stack.push((first + 1, below));
            }
        }
        if above == 0 || work.exhausted() {
            break;
        }
        // One level up: `above` shrinks for the targets beyond it.
        if above != parent {
            without = without.union(tree.nodes[hanging].aabb());
            credit += tree.nodes[above].aabb().half_area() - without.half_area();
        }
        hanging = sibling(above);
        above = tree.parents[above] as usize;
    }
    best.filter(|&t| t != sibling(node) && t != parent)
}

#[cfg(test)]
mod tests {
    use super::super::tests::scattered_triangle;
    use super::super::{binary_tree, ploc_tree};
    use super::*;
    use crate::arbitrary::mesh::icosphere;
    use crate::arbitrary::Rng;
    use glam::DVec3;
    use obvhs::aabb::Aabb;

    /// The boxes of `triangles` (rounded to nearest `f32`: the work does
    /// not depend on the outward rounding).
    fn boxes(triangles: &[[DVec3; 3]]) -> Vec<Aabb> {
        triangles
            .iter()
            .map(|t| {
                let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
                Aabb::new(lo.as_vec3().into(), hi.as_vec3().into())
            })
            .collect()
    }

    /// `n` triangles whose corners are uniform in a cube: their boxes
    /// overlap one another heavily (the case that made the build
    /// quadratic).
    fn overlapping_soup(n: usize, seed: u64) -> Vec<[DVec3; 3]> {
        let mut rng = Rng::new(seed);
        (0..n)
            .map(|_| {
                [0, 1, 2].map(|_| {
                    DVec3::new(
                        rng.uniform(-3.7, 1.3),
                        rng.uniform(-2.1, 2.9),
                        rng.uniform(10.6, 15.6),
                    )
                })
            })
            .collect()
    }

    /// The sum of the inner nodes' areas (what reinsertion lowers), and a
    /// check of the tree's structure: each leaf's primitive listed once,
    /// each node's parent recorded, each inner box the union of its
    /// children's.
    fn cost_and_check(tree: &Bvh2, primitives: usize) -> f64 {
        let mut seen = vec![false; primitives];
        let mut cost = 0.0;
        let mut stack = vec![0usize];
        while let Some(at) = stack.pop() {
            let node = &tree.nodes[at];
            if node.is_leaf() {
                let first = node.first_index as usize;
                for &p in &tree.primitive_indices[first..first + node.prim_count as usize] {
                    assert!(!std::mem::replace(&mut seen[p as usize], true), "{p} twice");
                }
                continue;
            }
            cost += f64::from(node.aabb().half_area());
            let first = node.first_index as usize;
            let union = tree.nodes[first].aabb().union(tree.nodes[first + 1].aabb());
            assert_eq!(*node.aabb(), union, "node {at}");
            for child in [first, first + 1] {
                if !tree.parents.is_empty() {
                    assert_eq!(tree.parents[child] as usize, at);
                }
                stack.push(child);
            }
        }
        assert!(seen.iter().all(|&s| s), "a primitive is missing");
        cost
    }

    /// On heavily overlapping boxes the searches hit the budget, so the
    /// work grows as `n log n`: four times the triangles, at most about
    /// 4.7 times the visits (the budget's `n (⌊log₂ n⌋ + 1)`; without the
    /// budget the visits grow quadratically, benches/README.md § Building
    /// the tree). The tree stays a tree over every triangle, cheaper than
    /// PLOC's.
    #[test]
    fn work_on_overlapping_boxes_grows_as_n_log_n() {
        let mut visits = Vec::new();
        for (n, seed) in [(1_000, 3), (4_000, 5)] {
            let boxes = boxes(&overlapping_soup(n, seed));
            let ploc = ploc_tree(&boxes);
            let (tree, work) = binary_tree(&boxes);
            assert!(work.exhausted(), "{n}: {work:?}");
            assert!(work.visits <= work.budget);
            let (before, after) = (cost_and_check(&ploc, n), cost_and_check(&tree, n));
            assert!(after < before * 0.99, "{n}: cost {before} → {after}");
            visits.push(work.visits as f64);
        }
        let ratio = visits[1] / visits[0];
        assert!(ratio < 4.0 * 13.0 / 11.0 * 1.05, "{visits:?}");
    }

    /// Ordinary scenes — a soup of small triangles as in
    /// `examples/ray_corpus.rs`, a sphere, every built-in scene's
    /// occluders — need at most half the budget: the budget never changes
    /// their trees.
    #[test]
    fn ordinary_scenes_need_at_most_half_the_budget() {
        let mut rng = Rng::new(29);
        let (lo, hi) = (DVec3::new(-1.0, -1.0, 0.1), DVec3::new(1.0, 1.0, 0.9));
        let soup: Vec<[DVec3; 3]> = (0..20_000)
            .map(|_| scattered_triangle(&mut rng, lo, hi, 0.01))
            .collect();
        let sphere = icosphere(5);
        let sphere: Vec<[DVec3; 3]> = sphere
            .triangles
            .iter()
            .map(|t| t.map(|i| sphere.positions[i as usize]))
            .collect();
        let mut scenes = vec![("soup", soup), ("sphere", sphere)];
        #[cfg(feature = "scene-file")]
        for &name in crate::scene::builtin::BUILTIN_NAMES {
            let scene = crate::scene::builtin::builtin(name).expect("built in");
            let occluders = super::super::Occluders::from_scene(&scene);
            scenes.push((name, occluders.triangles().to_vec()));
        }
        for (name, triangles) in scenes {
            let boxes = boxes(&triangles);
            let (tree, work) = binary_tree(&boxes);
            assert!(2 * work.visits <= work.budget, "{name}: {work:?}");
            assert!(work.moves > 0 || triangles.len() < 100, "{name}: {work:?}");
            cost_and_check(&tree, triangles.len());
        }
    }

    /// Moving subtrees never makes the tree more costly, and keeps it a
    /// tree over every box, on soups of every density.
    #[test]
    fn reinsertion_keeps_a_cheaper_tree_over_every_box() {
        let mut rng = Rng::new(31);
        for case in 0..40 {
            let n = 2 + rng.below(600) as usize;
            let size = rng.log_uniform(-4.0, 1.0);
            let triangles: Vec<[DVec3; 3]> = (0..n)
                .map(|_| scattered_triangle(&mut rng, -DVec3::ONE, DVec3::ONE, size))
                .collect();
            let boxes = boxes(&triangles);
            let ploc = ploc_tree(&boxes);
            let (tree, _) = binary_tree(&boxes);
            let (before, after) = (cost_and_check(&ploc, n), cost_and_check(&tree, n));
            assert!(
                after <= before * (1.0 + 1e-5),
                "case {case}: {before} → {after}"
            );
        }
    }
}
