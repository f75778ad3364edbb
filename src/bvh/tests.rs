//! The invariants the conservative traversal rests on: decoded boxes contain
//! their triangles, ray origins are padded outward, quantisation is tight.

use super::lanes::Portable;
use super::leaf::PACK;
use super::node::{decode, Node, EMPTY, LEAF, WIDTH};
use super::ray::{Ray32, WideSlab, T_SLACK};
use super::wide::{WideNode, EMPTY as WIDE_EMPTY, LEAF as WIDE_LEAF, WIDE};
use super::{Bvh, Occluders, OcclusionCounts};
use crate::arbitrary::Rng;
use crate::kernel::segment::segment_blocked;
use glam::DVec3;

/// A coordinate near `centre`, `scale` across, with now and then a value
/// clamped by the `f32` range or a repeated one.
fn coordinate(rng: &mut Rng, centre: f64, scale: f64) -> f64 {
    match rng.below(8) {
        0 => f64::from(f32::MAX) * rng.sign(),
        1 => centre,
        _ => centre + rng.uniform(-1.0, 1.0) * scale,
    }
}

/// A triangle whose corners lie within `r` on each axis of a centre drawn
/// uniformly from the box `lo..hi` (the soups of the tests below and of
/// `reinsert.rs`'s).
pub(super) fn scattered_triangle(rng: &mut Rng, lo: DVec3, hi: DVec3, r: f64) -> [DVec3; 3] {
    let c = DVec3::new(
        rng.uniform(lo.x, hi.x),
        rng.uniform(lo.y, hi.y),
        rng.uniform(lo.z, hi.z),
    );
    [0, 1, 2].map(|_| c + DVec3::new(rng.uniform(-r, r), rng.uniform(-r, r), rng.uniform(-r, r)))
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

/// The invariants of the occlusion tree: every lane's box contains,
/// exactly, every triangle below it (clamped to the `f32` range); every
/// pack holds its triangles' corner `A` and edges `B − A`, `A − C`
/// rounded to nearest `f32`, lane by lane, and its bounds' terms bound
/// them; every triangle in the tree is in one pack lane; empty lanes'
/// boxes are inverted.
fn check_wide(bvh: &Bvh) {
    let clamp = |v: DVec3| {
        v.clamp(
            DVec3::splat(-f64::from(f32::MAX)),
            DVec3::splat(f64::from(f32::MAX)),
        )
    };
    let mut seen = Vec::new();
    let mut stack = vec![0u32];
    while let Some(node) = stack.pop() {
        let n = &bvh.wide[node as usize];
        for lane in 0..WIDE {
            let (lo, hi) = (
                DVec3::from_array([0, 1, 2].map(|a| f64::from(n.planes[0][a][lane]))),
                DVec3::from_array([0, 1, 2].map(|a| f64::from(n.planes[1][a][lane]))),
            );
            let child = n.child[lane];
            if child == WIDE_EMPTY {
                assert!(lo.cmpgt(hi).all(), "an empty lane's box is inverted");
                continue;
            }
            let mut below = Vec::new();
            let mut todo = vec![child];
            while let Some(c) = todo.pop() {
                if c & WIDE_LEAF == 0 {
                    let m = &bvh.wide[c as usize];
                    todo.extend(m.child.iter().filter(|&&k| k != WIDE_EMPTY));
                } else {
                    below.extend(bvh.packs.get(c & !WIDE_LEAF).ids());
                }
            }
            for &id in &below {
                let t = bvh.occluders.triangles()[id as usize].map(clamp);
                let (t_lo, t_hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
                assert!(
                    lo.cmple(t_lo).all() && hi.cmpge(t_hi).all(),
                    "lane {lane} of node {node}"
                );
            }
            if child & WIDE_LEAF == 0 {
                stack.push(child);
                continue;
            }
            let pack = bvh.packs.get(child & !WIDE_LEAF);
            assert!((1..=PACK as u32).contains(&pack.count()));
            let ids = pack.ids();
            assert_eq!(ids.len(), pack.count() as usize);
            seen.extend(ids);
            pack.check_terms(bvh.occluders.triangles());
        }
    }
    seen.sort_unstable();
    let mut ids = bvh.ids.clone();
    ids.sort_unstable();
    assert_eq!(seen, ids, "each triangle of the tree in one pack lane");
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
            check_wide(&bvh);
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
                    decode(o, ql, s) <= lo[axis] && (ql == 255 || decode(o, ql + 1, s) > lo[axis])
                );
                assert!(
                    decode(o, qh, s) >= hi[axis] && (qh == 0 || decode(o, qh - 1, s) < hi[axis])
                );
            }
        }
    }
}

/// A flat triangle at height 1 (the degenerate tests' shape).
const FLAT: [DVec3; 3] = [
    DVec3::new(-1.0, 1.0, -1.0),
    DVec3::new(1.0, 1.0, -1.0),
    DVec3::new(0.0, 1.0, 1.0),
];

/// Nested triangles about one centre (the case PLOC chains, one pair per
/// pass): the tree holds each triangle once, its boxes contain their
/// triangles, it is balanced (`nested.rs` gives the run to PLOC as one box
/// and splits it in halves by area), and rays through it answer as the
/// triangles themselves do.
#[test]
fn nested_triangles_make_a_balanced_tree() {
    let centre = (FLAT[0] + FLAT[1] + FLAT[2]) / 3.0;
    // Shuffled sizes, so that the input order is not the nesting order.
    shallow_and_agrees(5, |s| FLAT.map(|v| centre + (v - centre) * (1.0 + s)));
}

/// 4096 copies of [`FLAT`] changed by `change(s)`, `s` the copy's place
/// in `[0, 1)`, shuffled: the tree is shallow — a chain would need a stack
/// of about n·3/4 entries; halving 4096 boxes needs 6 levels of 4-wide
/// nodes under PLOC's root — and holds each triangle once and agrees.
fn shallow_and_agrees(seed: u64, change: impl Fn(f64) -> [DVec3; 3]) {
    let n = 4096;
    let tris: Vec<[DVec3; 3]> = (0..n)
        .map(|k| change(((k * 1237) % n) as f64 / n as f64))
        .collect();
    let bvh = Bvh::new(Occluders::from_triangles(tris.clone()));
    assert!(bvh.stack_need() < 64, "stack {}", bvh.stack_need());
    holds_each_once_and_agrees(&bvh, &tris, &mut Rng::new(seed), 2.5, 0.5);
}

/// Parallel layers stacked closely (one triangle lifted by 10⁻⁴ a layer,
/// shuffled), which `nested.rs` takes as one run (PLOC chains on them as
/// on nested ones: benches/README.md § Building the tree): the tree holds each once, its
/// boxes contain their triangles, it is shallow, and rays answer as the
/// triangles do.
#[test]
fn stacked_layers_make_a_balanced_tree() {
    // 1e-4 apart: 4096 layers over 0.4096.
    shallow_and_agrees(9, |s| FLAT.map(|v| v + DVec3::new(0.0, 0.4096 * s, 0.0)));
}

/// A segment that meets the box of every node and no triangle: 4096
/// triangles across the `z` axis, each missing it by 0.1 on the far side
/// of its hypotenuse, turned about the axis by a random multiple of a
/// right angle (so that its box still holds the axis). The occlusion walk
/// visits every node, which is where its stack grows most: it stays
/// within `wide_stack_need` (the stack has exactly that many entries, so
/// one more would panic), and the segment is unoccluded, on every lane
/// form.
#[test]
fn a_walk_over_every_node_stays_within_its_stack() {
    let mut rng = Rng::new(31);
    let tris: Vec<[DVec3; 3]> = (0..4096)
        .map(|_| {
            let (z, turn) = (
                rng.uniform(-1.0, 1.0),
                std::f64::consts::FRAC_PI_2 * rng.below(4) as f64,
            );
            let (s, c) = turn.sin_cos();
            [(-1.0, 1.1), (1.0, 1.1), (1.0, -0.9)]
                .map(|(x, y)| DVec3::new(c * x - s * y, s * x + c * y, z))
        })
        .collect();
    let bvh = Bvh::new(Occluders::from_triangles(tris.clone()));
    let (p, x) = (DVec3::new(0.0, 0.0, -2.0), DVec3::new(0.0, 0.0, 2.0));
    assert!(tris.iter().all(|t| !segment_blocked(p, x, t)));
    assert!(bvh.wide_depth >= 3, "a deep tree: depth {}", bvh.wide_depth);
    let mut counts = OcclusionCounts::default();
    assert!(bvh.segment_unoccluded_counting(p, x, &mut counts));
    assert_eq!(counts.nodes, bvh.wide.len() as u64, "every node visited");
    assert!(bvh.unoccluded_here(Portable, p, x, &mut ()));
}

/// Random soups mixing runs of nested triangles (about shared centres, in
/// shuffled order) with scattered ones: every triangle is in the tree
/// once, every box contains its triangles, and rays answer as brute force
/// does — whichever runs the build groups.
#[test]
fn soups_with_nested_runs_answer_as_brute_force() {
    let mut rng = Rng::new(23);
    for _ in 0..20 {
        let mut tris: Vec<[DVec3; 3]> = Vec::new();
        for _ in 0..(1 + rng.below(4)) {
            let c = DVec3::new(
                rng.uniform(-2.0, 2.0),
                rng.uniform(0.5, 1.5),
                rng.uniform(-2.0, 2.0),
            );
            let shape = [0, 1, 2].map(|_| {
                DVec3::new(
                    rng.uniform(-1.0, 1.0),
                    rng.uniform(-0.2, 0.2),
                    rng.uniform(-1.0, 1.0),
                )
            });
            let mean = (shape[0] + shape[1] + shape[2]) / 3.0;
            let count = 10 + rng.below(60) as usize;
            for _ in 0..count {
                let s = rng.uniform(0.05, 1.0);
                tris.push(shape.map(|v| c + (v - mean) * s));
            }
        }
        let (lo, hi) = (DVec3::new(-3.0, 0.2, -3.0), DVec3::new(3.0, 2.0, 3.0));
        for _ in 0..rng.below(200) {
            tris.push(scattered_triangle(&mut rng, lo, hi, 0.2));
        }
        // Shuffle, so that runs are not contiguous in the input.
        for i in (1..tris.len()).rev() {
            tris.swap(i, rng.below(i as u64 + 1) as usize);
        }
        let bvh = Bvh::new(Occluders::from_triangles(tris.clone()));
        holds_each_once_and_agrees(&bvh, &tris, &mut rng, 4.0, 1.0);
    }
}

/// `bvh` holds every triangle of `tris` once, its boxes contain their
/// triangles, and 100 rays from the floor (`|x|, |z| ≤ floor`) to a light
/// square (`≤ light`) at height 3 answer as the triangles themselves do.
fn holds_each_once_and_agrees(
    bvh: &Bvh,
    tris: &[[DVec3; 3]],
    rng: &mut Rng,
    floor: f64,
    light: f64,
) {
    let mut ids = bvh.ids.clone();
    ids.sort_unstable();
    assert_eq!(ids, (0..tris.len() as u32).collect::<Vec<_>>());
    check_subtree(bvh, 0, 0);
    check_wide(bvh);
    for _ in 0..100 {
        let p = DVec3::new(rng.uniform(-floor, floor), 0.0, rng.uniform(-floor, floor));
        let x = DVec3::new(rng.uniform(-light, light), 3.0, rng.uniform(-light, light));
        let brute = tris
            .iter()
            .any(|t| crate::kernel::segment::segment_blocked(p, x, t));
        assert_eq!(bvh.segment_unoccluded(p, x), !brute, "{p:?} → {x:?}");
        // The portable lanes, the same answer.
        let portable = bvh.unoccluded_here(Portable, p, x, &mut ());
        assert_eq!(portable, !brute, "{p:?} → {x:?}");
    }
}

/// The cases `Bvh::segment_unoccluded` decides off the tree answer as the
/// triangles themselves do: triangles beyond the tree's range (`2⁶⁰`,
/// tested by every query) beside a tree, an endpoint beyond the `f32`
/// range (every triangle tested), outliers and no tree; and an endpoint
/// with a non-finite coordinate meets nothing.
#[test]
fn segments_off_the_tree_answer_as_brute_force() {
    let mut rng = Rng::new(31);
    let brute =
        |tris: &[[DVec3; 3]], p: DVec3, x: DVec3| !tris.iter().any(|t| segment_blocked(p, x, t));
    for _ in 0..20 {
        let (lo, hi) = (DVec3::new(-2.0, 0.2, -2.0), DVec3::new(2.0, 2.0, 2.0));
        let mut tris: Vec<[DVec3; 3]> = (0..rng.below(300))
            .map(|_| scattered_triangle(&mut rng, lo, hi, 0.5))
            .collect();
        let tree = Bvh::new(Occluders::from_triangles(tris.clone()));
        // A huge sheet at height 1 over part of the floor, its far corners
        // beyond the tree's range: an outlier every query tests.
        let big = 1e19;
        tris.push([
            DVec3::new(-big, 1.0, -big),
            DVec3::new(rng.uniform(-1.0, 1.0), 1.0, big),
            DVec3::new(big, 1.0, -big),
        ]);
        let with_outlier = Bvh::new(Occluders::from_triangles(tris.clone()));
        assert_eq!(with_outlier.outliers.len(), 1);
        let sheet = Bvh::new(Occluders::from_triangles(tris[tris.len() - 1..].to_vec()));
        assert!(sheet.nodes.is_empty());
        for _ in 0..50 {
            let p = DVec3::new(rng.uniform(-4.0, 4.0), 0.0, rng.uniform(-4.0, 4.0));
            let x = DVec3::new(rng.uniform(-1.0, 1.0), 3.0, rng.uniform(-1.0, 1.0));
            let n = tris.len();
            assert_eq!(with_outlier.segment_unoccluded(p, x), brute(&tris, p, x));
            // An end beyond the `f32` range, far up the same line.
            let far = p + (x - p) * 1e39;
            assert_eq!(
                tree.segment_unoccluded(p, far),
                brute(&tris[..n - 1], p, far)
            );
            assert_eq!(
                with_outlier.segment_unoccluded(p, far),
                brute(&tris, p, far)
            );
            assert_eq!(sheet.segment_unoccluded(p, x), brute(&tris[n - 1..], p, x));
            for bad in [f64::NAN, f64::INFINITY] {
                let q = DVec3::new(x.x, bad, x.z);
                assert!(with_outlier.segment_unoccluded(p, q));
                assert!(with_outlier.segment_unoccluded(q, p));
            }
        }
    }
}

/// The capped hull query gives the whole query's answer when it finds no
/// more than the cap, and says so when it finds more.
#[test]
fn capped_hull_query_is_the_query_or_refuses() {
    let mut rng = Rng::new(11);
    let triangles: Vec<[DVec3; 3]> = (0..2000)
        .map(|_| {
            let c = DVec3::new(
                coordinate(&mut rng, 0.0, 3.0),
                coordinate(&mut rng, 0.0, 3.0),
                coordinate(&mut rng, 0.0, 3.0),
            );
            [
                c,
                c + DVec3::new(0.1, 0.0, 0.02),
                c + DVec3::new(0.0, 0.1, -0.03),
            ]
        })
        .collect();
    let bvh = Bvh::new(Occluders::from_triangles(triangles));
    let hull = [
        DVec3::new(0.0, 0.0, -3.0),
        DVec3::new(1.0, 1.0, 3.0),
        DVec3::new(-1.0, 1.0, 3.0),
        DVec3::new(-1.0, -1.0, 3.0),
        DVec3::new(1.0, -1.0, 3.0),
    ];
    let mut all = Vec::new();
    bvh.triangles_meeting_hull(&hull, &mut all);
    assert!(all.len() > 20 && all.len() < 2000, "{} found", all.len());
    let mut capped = Vec::new();
    for cap in [0, 1, all.len() / 2, all.len() - 1] {
        assert!(
            !bvh.triangles_meeting_hull_at_most(&hull, &mut capped, cap),
            "cap {cap}"
        );
    }
    for cap in [all.len(), all.len() + 1, usize::MAX] {
        assert!(bvh.triangles_meeting_hull_at_most(&hull, &mut capped, cap));
        assert_eq!(capped, all);
    }
}

/// The lanes of `node` whose box the segment `(p, x)` may meet, on the
/// portable lanes and, where the processor has them, AVX2's (the two
/// agree bit for bit).
fn wide_hits(node: &WideNode, p: DVec3, x: DVec3) -> u32 {
    let ray = Ray32::new(p, x).expect("within the f32 range");
    let portable = WideSlab::new(Portable, &ray).hits(Portable, node);
    #[cfg(all(feature = "simd", target_arch = "x86_64"))]
    if let Some(v3) = pulp::x86::V3::try_new() {
        let s = super::lanes::Avx8(v3);
        let wide = v3.vectorize(
            #[inline(always)]
            || WideSlab::new(s, &ray).hits(s, node),
        );
        assert_eq!(wide, portable, "AVX2 and portable lanes differ");
    }
    portable
}

/// A size (`10⁻⁶` to `10⁶`) and a centre (the origin, or up to `10⁹` off
/// on every axis) for the slab tests' boxes and segments.
fn size_and_centre(rng: &mut Rng) -> (f64, f64) {
    let scale = rng.log_uniform(-6.0, 6.0);
    let centre = if rng.chance(0.5) {
        0.0
    } else {
        rng.log_uniform(0.0, 9.0) * rng.sign()
    };
    (scale, centre)
}

/// The slab test never drops a box the segment meets, at the edges:
/// segments ending or starting exactly on a face, at a corner, lying in a
/// face's plane across it, running along an edge; boxes of every size at
/// offsets up to `10⁹` (the tree's boxes lie within `±2⁶⁰`), endpoints
/// `f32` values or not; the box in any lane among others and empty lanes.
#[test]
fn slab_test_keeps_boxes_the_segment_touches() {
    let mut rng = Rng::new(61);
    let coordinate = |rng: &mut Rng, centre: f64, scale: f64| {
        if rng.chance(0.1) {
            centre
        } else {
            centre + rng.uniform(-1.0, 1.0) * scale
        }
    };
    for case in 0..50_000 {
        let (scale, centre) = size_and_centre(&mut rng);
        let mut node = WideNode::EMPTY_NODE;
        let lanes = 1 + rng.below(WIDE as u64) as usize;
        let mut boxes = Vec::new();
        for lane in 0..lanes {
            let (a, b) = (
                DVec3::new(
                    coordinate(&mut rng, centre, scale),
                    coordinate(&mut rng, centre, scale),
                    coordinate(&mut rng, centre, scale),
                ),
                DVec3::new(
                    coordinate(&mut rng, centre, scale),
                    coordinate(&mut rng, centre, scale),
                    coordinate(&mut rng, centre, scale),
                ),
            );
            let (lo, hi) = (a.min(b).as_vec3(), a.max(b).as_vec3());
            for axis in 0..3 {
                node.planes[0][axis][lane] = lo[axis];
                node.planes[1][axis][lane] = hi[axis];
            }
            node.child[lane] = lane as u32;
            boxes.push((lo.as_dvec3(), hi.as_dvec3()));
        }
        let lane = rng.below(lanes as u64) as usize;
        let (lo, hi) = boxes[lane];
        // A point of the box's surface: on one face (or an edge, or a
        // corner), inside it on the other axes.
        let mut on = DVec3::new(
            rng.uniform(lo.x, hi.x),
            rng.uniform(lo.y, hi.y),
            rng.uniform(lo.z, hi.z),
        );
        let face = rng.below(3) as usize;
        let pick = |rng: &mut Rng, k: usize| if rng.chance(0.5) { lo[k] } else { hi[k] };
        on[face] = pick(&mut rng, face);
        if rng.chance(0.3) {
            let other = (face + 1 + rng.below(2) as usize) % 3;
            on[other] = pick(&mut rng, other);
            if rng.chance(0.3) {
                let third = 3 - face - other;
                on[third] = pick(&mut rng, third);
            }
        }
        let away = DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        ) * scale
            * 4.0;
        let (p, x) = match rng.below(4) {
            0 => (on + away, on),
            1 => (on, on + away),
            // In the face's plane, across the face through `on`.
            2 => {
                let mut along = away;
                along[face] = 0.0;
                let (mut p, mut x) = (on - along, on + along);
                p[face] = on[face];
                x[face] = on[face];
                // Clamped ends may leave the line through `on`: end at it.
                if rng.chance(0.5) {
                    (p, on)
                } else {
                    (on, x)
                }
            }
            // Along an edge or a face, ending inside it.
            _ => {
                let mut q = on;
                let free = (face + 1) % 3;
                q[free] = rng.uniform(lo[free], hi[free]);
                (q, on)
            }
        };
        assert!(
            wide_hits(&node, p, x) >> lane & 1 == 1,
            "case {case}: lane {lane} {lo:?}..{hi:?} dropped for {p:?} → {x:?}"
        );
        assert_eq!(wide_hits(&node, p, x) >> lanes, 0, "empty lanes kept");
    }
}

/// The node test's lanes are those of the slab test written one lane and
/// one axis at a time — `t_near = max(0, a₀, a₁, a₂)` and `t_far = min(1,
/// b₀, b₁, b₂)` taken in sequence, `t_near ≤ t_far (1 + 2⁻²⁰)` — whatever
/// order `WideSlab::hits` takes them in: on boxes and segments of every
/// size at offsets up to `10⁹`, with empty lanes, where the parameters of
/// several axes tie now and then (a box's planes on the segment's ends).
#[test]
fn node_test_is_the_sequential_slab_test() {
    let mut rng = Rng::new(71);
    for _ in 0..20_000 {
        let (scale, centre) = size_and_centre(&mut rng);
        let point = |rng: &mut Rng| {
            DVec3::new(
                centre + rng.uniform(-1.0, 1.0) * scale,
                centre + rng.uniform(-1.0, 1.0) * scale,
                centre + rng.uniform(-1.0, 1.0) * scale,
            )
        };
        let (p, x) = (point(&mut rng), point(&mut rng));
        let mut node = WideNode::EMPTY_NODE;
        for lane in 0..rng.below(WIDE as u64 + 1) as usize {
            let (mut a, mut b) = (point(&mut rng), point(&mut rng));
            if rng.chance(0.2) {
                (a, b) = (p.min(x), p.max(x));
            }
            let (lo, hi) = (a.min(b).as_vec3(), a.max(b).as_vec3());
            for axis in 0..3 {
                node.planes[0][axis][lane] = lo[axis];
                node.planes[1][axis][lane] = hi[axis];
            }
        }
        let ray = Ray32::new(p, x).expect("within the f32 range");
        let mut expected = 0;
        for lane in 0..WIDE {
            let (mut t_near, mut t_far) = (0.0f32, 1.0f32);
            for axis in 0..3 {
                let side = ray.entry[axis];
                let entry = node.planes[side][axis][lane];
                let exit = node.planes[1 - side][axis][lane];
                let a = (entry - ray.near[axis]) * ray.inv[axis];
                let b = (exit - ray.far[axis]) * ray.inv[axis];
                t_near = if a > t_near { a } else { t_near };
                t_far = if b < t_far { b } else { t_far };
            }
            expected |= u32::from(t_near <= t_far * T_SLACK) << lane;
        }
        assert_eq!(wide_hits(&node, p, x), expected, "{p:?} → {x:?}");
    }
}

/// The occlusion walk's per-segment slab constants in AVX `f64` lanes are
/// `Ray32::axes`' bit for bit: over many decades, signs, zero and tiny
/// directions, and the edge of the `f32` range.
#[test]
fn slab_constants_agree_on_every_lane_form() {
    #[cfg(all(feature = "simd", target_arch = "x86_64"))]
    if let Some(v3) = pulp::x86::V3::try_new() {
        let mut rng = Rng::new(67);
        let value = |rng: &mut Rng| match rng.below(6) {
            0 => 0.0,
            1 => -0.0,
            2 => rng.log_uniform(-45.0, -25.0) * rng.sign(),
            3 => f64::from(f32::MAX) * rng.sign(),
            _ => rng.log_uniform(-40.0, 38.0) * rng.sign(),
        };
        for _ in 0..100_000 {
            let p: [f64; 4] = core::array::from_fn(|_| value(&mut rng));
            let d: [f64; 4] = core::array::from_fn(|_| value(&mut rng));
            let wide = v3.vectorize(
                #[inline(always)]
                || super::lanes::axes4(v3, p, d),
            );
            let portable = Ray32::axes(p, d);
            let bits = |v: [f32; 4]| v.map(f32::to_bits);
            assert_eq!(bits(wide.near), bits(portable.near), "{p:?} {d:?}");
            assert_eq!(bits(wide.far), bits(portable.far), "{p:?} {d:?}");
            assert_eq!(bits(wide.inv), bits(portable.inv), "{p:?} {d:?}");
            assert_eq!(wide.backward, portable.backward, "{p:?} {d:?}");
        }
    }
}

/// A tree deeper than the machine-stack walk takes (triangles spaced ever
/// farther apart along a line: PLOC chains them): the walk on the heap
/// answers as brute force does.
#[test]
fn a_deep_tree_is_walked_on_the_heap() {
    let tris: Vec<[DVec3; 3]> = (0..400)
        .map(|k| {
            let x = 1.07f64.powi(k) - 1.0;
            [
                DVec3::new(x, -1.0, -1.0),
                DVec3::new(x, 1.0, -1.0),
                DVec3::new(x, 0.0, 1.0),
            ]
        })
        .collect();
    let bvh = Bvh::new(Occluders::from_triangles(tris.clone()));
    assert!(
        bvh.wide_stack_need() > super::ray::STACK,
        "depth {}",
        bvh.wide_depth
    );
    check_wide(&bvh);
    let mut rng = Rng::new(71);
    for _ in 0..200 {
        let p = DVec3::new(
            rng.uniform(-1.0, 1e12),
            rng.uniform(-2.0, 2.0),
            rng.uniform(-2.0, 2.0),
        );
        let x = DVec3::new(
            rng.uniform(-1.0, 1e12),
            rng.uniform(-2.0, 2.0),
            rng.uniform(-2.0, 2.0),
        );
        let brute = !tris.iter().any(|t| segment_blocked(p, x, t));
        assert_eq!(bvh.segment_unoccluded(p, x), brute, "{p:?} → {x:?}");
        assert_eq!(bvh.unoccluded_here(Portable, p, x, &mut ()), brute);
    }
}

/// A closed convex mesh (an icosphere of 1,280 triangles, scaled and moved
/// by non-dyadic amounts, up to `10⁶` from the origin) leaks no light and
/// shadows nothing outside it: segments from inside it to points beyond
/// each vertex and each edge's midpoint (through shared edges and
/// vertices, where the `f32` test cannot be certain) are blocked; from a
/// vertex (on its triangles' planes) outward they are not, from a vertex
/// across the mesh they are — every answer also brute force's, and the
/// exact test reached.
#[test]
fn a_closed_mesh_is_watertight_at_its_edges_and_vertices() {
    let mesh = crate::arbitrary::mesh::icosphere(3);
    let mut rng = Rng::new(71);
    let mut counts = OcclusionCounts::default();
    for (offset, radius) in [(0.0, 1.0), (1e3, 0.37), (1e6, 3.1), (-2e4, 1e-3)] {
        let centre = DVec3::new(
            offset * rng.uniform(0.5, 1.0),
            offset * rng.uniform(-1.0, 1.0),
            offset * rng.uniform(-1.0, 1.0),
        );
        let positions: Vec<DVec3> = mesh
            .positions
            .iter()
            .map(|&v| centre + v * radius)
            .collect();
        let triangles: Vec<[DVec3; 3]> = mesh
            .triangles
            .iter()
            .map(|t| t.map(|i| positions[i as usize]))
            .collect();
        let bvh = Bvh::new(Occluders::from_triangles(triangles.clone()));
        let brute = |p: DVec3, x: DVec3| !triangles.iter().any(|t| segment_blocked(p, x, t));
        let mut check = |p: DVec3, x: DVec3, unoccluded: bool| {
            let got = bvh.segment_unoccluded_counting(p, x, &mut counts);
            assert_eq!(got, unoccluded, "{p} {x}");
            assert_eq!(got, brute(p, x), "{p} {x}");
        };
        let inside = |rng: &mut Rng| {
            centre
                + DVec3::new(
                    rng.uniform(-0.4, 0.4),
                    rng.uniform(-0.4, 0.4),
                    rng.uniform(-0.4, 0.4),
                ) * radius
        };
        let mut through = positions.clone();
        for t in &mesh.triangles {
            through.push((positions[t[0] as usize] + positions[t[1] as usize]) * 0.5);
        }
        for &v in &through {
            let p = inside(&mut rng);
            check(p, p + (v - p) * rng.uniform(1.2, 3.0), false);
        }
        for &v in &positions {
            let k = rng.uniform(0.1, 2.0);
            check(v, v + (v - centre) * k, true);
            check(v, centre - (v - centre) * (1.0 + k), false);
        }
    }
    assert!(counts.exact > 1000, "{counts:?}");
}
