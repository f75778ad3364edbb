//! The union's two searches (issue 46) give the same exact answers bit for
//! bit: the grid (`UnionSearch::Grid`) and the tree of bounding boxes
//! pruned by the edge's cover (`Tree`), and the default (`Auto`) the
//! same value with the bound of the one it chose, through the whole
//! exact reference — every
//! built-in scene's floor grid under its own light, a pile of random
//! occluders, layers stacked `10⁻⁴` apart, and convex polygons given as
//! fans of slivers; and under a pile deep enough for the union's raster,
//! the value without the bound (`visibility_with`, whose union leaves out
//! the images the raster shows inside others) is the bounded value, bit
//! for bit. Their certified bounds are each search's own: an
//! edge's band held deep inside another image is left out of the bound,
//! and which covering image a search meets first depends on its order, so
//! the bounds agree closely but not bit for bit.

use softshadow::arbitrary::Rng;
use softshadow::bvh::{Bvh, Occluders};
use softshadow::glam::DVec3;
use softshadow::kernel::receiver_view::UnionSearch;
use softshadow::reference::exact::{visibility_bounded_with, visibility_with, Scratch};
use softshadow::scene::builtin::{builtin, floor_receivers, BUILTIN_NAMES};
use softshadow::scene::Light;

#[path = "../benches/support/pile.rs"]
mod pile;

/// The largest certified bound either search may give here (the largest
/// on these cases is 1.4·10⁻¹², under the pile of 3000).
const TIGHT: f64 = 1e-11;

/// Every receiver's `V` bits under each search, compared with the grid's
/// and, under one search in turn, with the value asked for without a
/// bound (and every bound tight, at most [`TIGHT`]); the automatic choice's
/// bound is the grid's or the tree's bits, the tree's if `tree` (the
/// cases where it must choose the tree, else the grid's). How many answers
/// lie strictly between 0 and 1.
fn compare(what: &str, bvh: &Bvh, light: &Light, receivers: &[DVec3], tree: bool) -> usize {
    let searches = [UnionSearch::Grid, UnionSearch::Tree, UnionSearch::Auto];
    let mut scratch: Vec<Scratch> = searches
        .iter()
        .map(|&s| {
            let mut scratch = Scratch::default();
            scratch.set_union_search(s);
            scratch
        })
        .collect();
    let (mut partial, mut seen) = (0, 0);
    for &p in receivers {
        let answers: Vec<(u64, u64)> = scratch
            .iter_mut()
            .map(|s| match visibility_bounded_with(bvh, light, p, s) {
                Ok(b) => (b.visibility.to_bits(), b.bound.to_bits()),
                Err(_) => (u64::MAX, u64::MAX),
            })
            .collect();
        // The value without a bound, under each search in turn.
        let k = seen % searches.len();
        seen += 1;
        if let Ok(v) = visibility_with(bvh, light, p, &mut scratch[k]) {
            assert_eq!(
                v.to_bits(),
                answers[k].0,
                "{what}, receiver {p:?}, {:?}: {v:e} without a bound",
                searches[k]
            );
        }
        let shown = |search: &UnionSearch, answer: &(u64, u64)| {
            format!(
                "{what}, receiver {p:?}: grid {:?}, {search:?} {:?}",
                (f64::from_bits(answers[0].0), f64::from_bits(answers[0].1)),
                (f64::from_bits(answer.0), f64::from_bits(answer.1))
            )
        };
        for (search, answer) in searches.iter().zip(&answers).skip(1) {
            assert_eq!(answers[0].0, answer.0, "{}", shown(search, answer));
            let (a, b) = (f64::from_bits(answers[0].1), f64::from_bits(answer.1));
            assert!(
                a <= TIGHT && b <= TIGHT,
                "a bound above {TIGHT:e}: {}",
                shown(search, answer)
            );
        }
        let chosen = answers[usize::from(tree)].1;
        assert_eq!(answers[2].1, chosen, "{}", shown(&searches[2], &answers[2]));
        let v = f64::from_bits(answers[0].0);
        partial += usize::from(v > 0.0 && v < 1.0);
    }
    partial
}

#[test]
fn the_searches_agree_on_the_built_in_scenes() {
    for name in BUILTIN_NAMES {
        let scene = builtin(name).expect("a built-in scene");
        let bvh = Bvh::new(Occluders::from_scene(&scene));
        let receivers = floor_receivers(&scene, 20);
        let partial = compare(name, &bvh, scene.light(), &receivers, false);
        assert!(partial > 10, "{name}: {partial} receivers in a penumbra");
    }
}

/// The pile of `benches/references.rs`: random small triangles over one
/// receiver, every one projecting onto the light; receivers about it.
#[test]
fn the_searches_agree_under_a_pile() {
    let mut rng = Rng::new(7);
    let light = Light::sphere(DVec3::new(0.0, 0.0, 4.0), 0.5).expect("a light");
    for n in [300, 3000] {
        let tris: Vec<[DVec3; 3]> = (0..n)
            .map(|_| {
                let target = DVec3::new(0.0, 0.0, 4.0)
                    + DVec3::new(rng.uniform(-0.4, 0.4), rng.uniform(-0.4, 0.4), 0.0);
                let q = target * rng.uniform(0.2, 0.8);
                let s = 0.05 * q.z / 4.0;
                let mut corner =
                    || q + DVec3::new(rng.uniform(-s, s), rng.uniform(-s, s), rng.uniform(-s, s));
                [corner(), corner(), corner()]
            })
            .collect();
        let bvh = Bvh::new(Occluders::from_triangles(tris));
        let receivers: Vec<DVec3> = (0..6)
            .map(|_| DVec3::new(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), 0.0))
            .collect();
        assert!(compare("pile", &bvh, &light, &receivers, false) > 0);
    }
}

/// Layers stacked `10⁻⁴` apart (near-nested images), and one convex
/// polygon as a fan of slivers covering all or part of a disk light.
#[test]
fn the_searches_agree_on_stacked_layers_and_fans() {
    let t = [
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(1.0, 1.0, -1.0),
        DVec3::new(0.0, 1.0, 1.0),
    ];
    let stacked: Vec<[DVec3; 3]> = (0..2000)
        .map(|k| t.map(|v| v + DVec3::new(0.0, 1e-4 * k as f64, 0.0)))
        .collect();
    let light = Light::sphere(DVec3::new(0.0, 3.0, 0.0), 0.5).expect("a light");
    let receivers = [
        DVec3::new(0.9, 0.0, 0.0),
        DVec3::new(0.83, 0.0, 0.21),
        DVec3::new(-0.7, 0.0, 0.4),
    ];
    compare(
        "stacked",
        &Bvh::new(Occluders::from_triangles(stacked)),
        &light,
        &receivers,
        false,
    );
    let disk = Light::disk(
        DVec3::new(0.1031, 0.2017, 4.0),
        DVec3::new(0.03, 0.01, 1.0),
        0.5,
    )
    .expect("a light");
    let p = [DVec3::new(0.0137, 0.0213, 0.0), DVec3::new(0.2, -0.1, 0.0)];
    for (center, radius, apex) in [
        (
            DVec3::new(0.0, 0.0, 2.0),
            50.0,
            DVec3::new(0.0313, 0.0271, 2.0),
        ),
        (
            DVec3::new(0.35, 0.2, 2.0),
            0.23,
            DVec3::new(0.3513, 0.1871, 2.0),
        ),
    ] {
        let n = 3000;
        let ring: Vec<DVec3> = (0..n)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / n as f64;
                center + DVec3::new(a.cos(), a.sin(), 0.0) * radius
            })
            .collect();
        let tris: Vec<[DVec3; 3]> = (0..n).map(|k| [apex, ring[k], ring[(k + 1) % n]]).collect();
        compare(
            "fan",
            &Bvh::new(Occluders::from_triangles(tris)),
            &disk,
            &p,
            false,
        );
    }
}

/// Layers stacked many deep at ordinary (non-dyadic) heights and offsets,
/// enough for the automatic choice to take the tree: 4500 layers of one
/// triangle, each a random `0.5–1.5·10⁻⁴` above the last and shifted by
/// up to `10⁻⁶` sideways, and as many copies of one triangle stacked
/// `10⁻⁹` apart (near-coincident), seen from receivers whose answers lie
/// in the penumbra.
#[test]
fn the_automatic_search_takes_the_tree_under_deep_stacks() {
    let mut rng = Rng::new(11);
    let t = [
        DVec3::new(-1.0137, 1.0071, -0.9893),
        DVec3::new(1.0213, 0.9969, -1.0311),
        DVec3::new(0.0173, 1.0029, 1.0097),
    ];
    let light = Light::sphere(DVec3::new(0.0113, 3.0217, -0.0071), 0.5).expect("a light");
    let receivers = [
        DVec3::new(0.9013, 0.0, 0.0037),
        DVec3::new(0.8317, 0.0, 0.2113),
    ];
    for (what, step) in [("stacked", 1e-4), ("near-coincident", 1e-9)] {
        let mut y = 0.0;
        let layers: Vec<[DVec3; 3]> = (0..4500)
            .map(|_| {
                y += step * rng.uniform(0.5, 1.5);
                let d = DVec3::new(rng.uniform(-1e-6, 1e-6), y, rng.uniform(-1e-6, 1e-6));
                t.map(|v| v + d)
            })
            .collect();
        let bvh = Bvh::new(Occluders::from_triangles(layers));
        let partial = compare(what, &bvh, &light, &receivers, true);
        assert!(partial > 0, "{what}: no receiver in a penumbra");
    }
}

/// Under the benchmark's pile of 4096 occluders (`benches/support/pile.rs`:
/// ordinary coordinates, images deep enough for the union's raster, which
/// leaves about a quarter of them out of its marks and, where no bound is
/// asked for, out of the union), the value without the bound is the
/// bounded value bit for bit, under either search, for receivers about
/// the pile's axis.
#[test]
fn the_value_without_the_bound_is_the_bounded_one_under_a_deep_pile() {
    let light = Light::sphere(DVec3::new(0.0, 0.0, 4.0), 0.5).expect("a light");
    let bvh = Bvh::new(Occluders::from_triangles(pile::occluders(4096)));
    let receivers = [
        DVec3::new(0.0137, -0.0211, 0.0),
        DVec3::new(0.0419, 0.0073, 0.0),
        DVec3::new(-0.0291, 0.0347, 0.0),
    ];
    for search in [UnionSearch::Grid, UnionSearch::Tree] {
        let mut scratch = Scratch::default();
        scratch.set_union_search(search);
        for p in receivers {
            let bounded = visibility_bounded_with(&bvh, &light, p, &mut scratch)
                .expect("a receiver in range");
            let value =
                visibility_with(&bvh, &light, p, &mut scratch).expect("a receiver in range");
            assert!(
                bounded.visibility > 0.0 && bounded.visibility < 1.0,
                "{search:?}, {p:?}: {bounded:?}, not in a penumbra"
            );
            assert_eq!(
                value.to_bits(),
                bounded.visibility.to_bits(),
                "{search:?}, {p:?}: {value:e} without the bound, {bounded:?} with it"
            );
        }
    }
}

/// Faces seen edge-on and needles in a deep pile: `V` from
/// `visibility_with` (no bound asked for: the triangles the raster of a
/// deep pile leaves out take no part in the union's walk) and the value
/// of `visibility_bounded_with` (every triangle walked) are the same
/// bits, under each search. Over each receiver `p`, 5000 small
/// triangles over the middle of the light (deep enough for the raster,
/// which leaves about 1600 of them out), faces whose planes pass within
/// `10⁻¹⁵` to `10⁻⁸` (relatively) of `p` (their images slivers whose
/// lines nearly coincide, running on across the other images), and
/// needles (a corner's angle `10⁻¹²` to `10⁻⁷`), a few far longer,
/// reaching out of the pile: 2 piles, or `SOFTSHADOW_EDGE_ON_PILES`.
#[test]
fn edge_on_faces_and_needles_give_the_bounded_value() {
    let mut rng = Rng::new(4601);
    let light = Light::sphere(DVec3::new(0.0131, -0.0217, 4.0), 0.5).expect("a light");
    let (mut partial, mut cases) = (0, 0);
    let piles: usize = std::env::var("SOFTSHADOW_EDGE_ON_PILES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2);
    for _ in 0..piles {
        let p = DVec3::new(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), 0.0);
        let mut tris: Vec<[DVec3; 3]> = Vec::new();
        let in_pile = |rng: &mut Rng| {
            let target = DVec3::new(0.0131, -0.0217, 4.0)
                + DVec3::new(rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), 0.0);
            p + (target - p) * rng.uniform(0.2, 0.8)
        };
        for _ in 0..5000 {
            let q = in_pile(&mut rng);
            let s = 0.025 * q.z / 4.0;
            let mut corner =
                || q + DVec3::new(rng.uniform(-s, s), rng.uniform(-s, s), rng.uniform(-s, s));
            tris.push([corner(), corner(), corner()]);
        }
        for _ in 0..300 {
            let (a, b) = (in_pile(&mut rng), in_pile(&mut rng));
            let b = a + (b - a) * rng.uniform(0.02, 0.1);
            if rng.chance(0.5) {
                // In the plane through p, a and b, then moved off it.
                let c = a + (b - a) * rng.uniform(-0.5, 1.5) + (a - p) * rng.uniform(-0.1, 0.1);
                let n = (a - p).cross(b - p).normalize();
                let off = rng.sign() * 10f64.powf(rng.uniform(-15.0, -8.0)) * (a - p).length();
                tris.push([a, b, c + n * off]);
            } else {
                let alpha = 10f64.powf(rng.uniform(-12.0, -7.0));
                let d = b - a;
                let side = d
                    .cross(DVec3::new(rng.uniform(-1.0, 1.0), 1.0, 0.3))
                    .normalize();
                let reach = if rng.chance(0.03) { 6.0 } else { 1.0 };
                tris.push([
                    a,
                    a + d * reach,
                    a + (d + side * d.length() * alpha) * reach,
                ]);
            }
        }
        let bvh = Bvh::new(Occluders::from_triangles(tris));
        let receivers = [
            p,
            p + DVec3::new(rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3), 0.0),
        ];
        for search in [UnionSearch::Grid, UnionSearch::Tree, UnionSearch::Auto] {
            let mut scratch = Scratch::default();
            scratch.set_union_search(search);
            for &r in &receivers {
                let v = visibility_with(&bvh, &light, r, &mut scratch);
                let b = visibility_bounded_with(&bvh, &light, r, &mut scratch);
                match (v, b) {
                    (Ok(v), Ok(b)) => {
                        assert_eq!(
                            v.to_bits(),
                            b.visibility.to_bits(),
                            "{search:?}, receiver {r:?}: {v:e} against the bounded {:e}",
                            b.visibility
                        );
                        cases += 1;
                        partial += usize::from(v > 0.0 && v < 1.0);
                    }
                    (v, b) => panic!("{search:?}, receiver {r:?}: {v:?}, {b:?}"),
                }
            }
        }
    }
    assert!(partial * 2 > cases, "{partial} of {cases} in a penumbra");
}
