//! Tests of the samples decided on the light's plane against their rays.

use super::super::SplitMix64;
use super::*;
use crate::bvh::Occluders;
use crate::scene::Light;
use proptest::prelude::*;

/// Uniform in `[lo, hi)`.
fn uniform(rng: &mut SplitMix64, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * ((rng.next() >> 11) as f64 / (1u64 << 53) as f64)
}

fn vector(rng: &mut SplitMix64, size: f64) -> DVec3 {
    DVec3::new(
        uniform(rng, -size, size),
        uniform(rng, -size, size),
        uniform(rng, -size, size),
    )
}

/// A light of each kind but the point, a receiver `p` below it, and a soup of
/// triangles made to sit on the decisions' edges: corners exactly at
/// `p`, at sample points, on the segments to them, edges through those,
/// triangles in a plane through `p` (exactly: `p` and the corners share
/// `z`), crossing or beyond the light's plane, behind `p`, tiny and
/// huge ones, and quads split along a diagonal that sample rays graze.
fn scene(seed: u64) -> (Light, DVec3, Vec<[DVec3; 3]>, Vec<DVec2>) {
    scene_on(seed, None)
}

/// [`scene`], its triangles made to sit on the first 1024 points of
/// `replicate` where one is given (else on uniform samples).
fn scene_on(
    seed: u64,
    replicate: Option<&Replicate>,
) -> (Light, DVec3, Vec<[DVec3; 3]>, Vec<DVec2>) {
    let mut rng = SplitMix64(seed);
    let offset = if rng.next() % 2 == 0 {
        DVec3::ZERO
    } else {
        vector(&mut rng, 1e4)
    };
    let p = offset + vector(&mut rng, 0.5);
    let size = uniform(&mut rng, 0.05, 1.0);
    let lateral = DVec3::new(
        uniform(&mut rng, -1.0, 1.0),
        uniform(&mut rng, -1.0, 1.0),
        0.0,
    );
    let above = p + lateral + DVec3::new(0.0, 0.0, size + uniform(&mut rng, 0.3, 4.0));
    let light = match rng.next() % 4 {
        0 => Light::sphere(above, size),
        1 => Light::disk(
            above,
            DVec3::new(0.1, -0.2, 1.0) + vector(&mut rng, 0.5),
            size,
        ),
        2 => {
            let half = DVec3::new(size, 0.0, 0.0) + vector(&mut rng, 0.5 * size);
            Light::segment(above - half, above + half)
        }
        _ => Light::rect(
            above,
            DVec3::new(size, 0.0, 0.0) + vector(&mut rng, 0.2 * size),
            DVec3::new(0.0, size, 0.0) + vector(&mut rng, 0.2 * size),
        ),
    }
    .expect("a light");
    let emitter = light.emitter(p).expect("an emitter");
    let samples: Vec<DVec2> = (0..1024)
        .map(|i| match replicate {
            Some(replicate) => replicate.point(i),
            None => DVec2::new(uniform(&mut rng, 0.0, 1.0), uniform(&mut rng, 0.0, 1.0)),
        })
        .collect();
    let mut triangles = Vec::new();
    for _ in 0..(rng.next() % 60 + 1) {
        let x0 = emitter.point_at(samples[(rng.next() % 1024) as usize]);
        let scale = 10f64.powf(uniform(&mut rng, -4.0, 0.3));
        let on_ray = p.lerp(x0, uniform(&mut rng, 0.0, 1.2));
        // A triangle with a corner exactly at `a`.
        let cornered =
            |rng: &mut SplitMix64, a: DVec3| [a, a + vector(rng, scale), a + vector(rng, scale)];
        let t = match rng.next() % 8 {
            0 => cornered(&mut rng, p),
            1 => cornered(&mut rng, on_ray),
            2 => {
                let d = vector(&mut rng, scale);
                [on_ray - d, on_ray + d, on_ray + vector(&mut rng, scale)]
            }
            3 => {
                let mut t = [0; 3].map(|_| p + vector(&mut rng, scale * 4.0));
                for v in &mut t {
                    v.z = p.z;
                }
                t
            }
            4 => cornered(&mut rng, x0),
            5 => {
                let d = vector(&mut rng, scale);
                let (a, b) = (on_ray - d, on_ray + d);
                let e = vector(&mut rng, scale);
                triangles.push([a, b, on_ray + e]);
                [b, a, on_ray - e]
            }
            _ => {
                let c = p.lerp(above, uniform(&mut rng, -0.3, 1.3)) + vector(&mut rng, size * 2.0);
                [
                    c + vector(&mut rng, scale),
                    c + vector(&mut rng, scale),
                    c + vector(&mut rng, scale),
                ]
            }
        };
        triangles.push(t);
    }
    (light, p, triangles, samples)
}

/// `scene(seed)` set up: the receiver, its BVH, the emitter and its
/// kind (0 disk, 1 rect, 2 segment), the samples, and the plane
/// structure, `None` where the set-up declines (a grazing view of a
/// tilted disk: every ray is cast).
struct SetUp {
    p: DVec3,
    bvh: Bvh,
    emitter: Emitter,
    kind: usize,
    samples: Vec<DVec2>,
    binned: Option<Binned>,
}

fn set_up(seed: u64) -> SetUp {
    let (light, p, triangles, samples) = scene(seed);
    let bvh = Bvh::new(Occluders::from_triangles(triangles));
    let emitter = light.emitter(p).expect("an emitter");
    let kind = match emitter {
        Emitter::Disk(_) => 0,
        Emitter::Rect(_) => 1,
        _ => 2,
    };
    let mut binned = Binned::default();
    let binned = binned
        .build(&bvh, &emitter, p, 1 << 20, 16)
        .then_some(binned);
    SetUp {
        p,
        bvh,
        emitter,
        kind,
        samples,
        binned,
    }
}

/// The count of the samples of `scene(seed)` decided on the plane
/// (none where the set-up declines), each passed to `check` with the
/// ray's answer — all of them where the set-up found one answer for
/// all; and the emitter's kind.
fn decide_scene(seed: u64, mut check: impl FnMut(bool, bool, DVec2)) -> (usize, usize) {
    let SetUp {
        p,
        bvh,
        emitter,
        kind,
        samples,
        binned,
    } = set_up(seed);
    let Some(binned) = binned else {
        return (0, kind);
    };
    let map = binned.map.expect("a plane");
    let mut decided = 0;
    for &s in &samples {
        // The answer for every sample where one holds, else its own.
        let known = binned.all.or_else(|| binned.decide(map.approx(s)));
        if let Some(unoccluded) = known {
            decided += 1;
            check(
                unoccluded,
                bvh.segment_unoccluded(p, emitter.point_at(s)),
                s,
            );
        }
    }
    (decided, kind)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Every decision made on the light's plane is the exact ray's
    /// answer ([`Bvh::segment_unoccluded`]), on samples whose rays
    /// pass exactly through corners and along edges.
    #[test]
    fn decisions_are_the_rays_answers(seed in any::<u64>()) {
        let mut wrong = None;
        let _ = decide_scene(seed, |decided, ray, s| {
            if decided != ray && wrong.is_none() {
                wrong = Some(s);
            }
        });
        prop_assert_eq!(wrong, None);
    }
}

/// A replicate's count of unoccluded samples is the rays' count, on
/// scenes whose triangles sit on its own sample points (their corners,
/// edges and rays through them), for every kind of emitter and for
/// sample counts that end inside a run of the sequence's table; with
/// the run-time dispatch to AVX2 and without it.
#[test]
fn counts_are_the_rays_counts() {
    let (mut built, mut pending) = ([0; 3], 0);
    for seed in 0..400 {
        let replicate = Replicate::new(&mut SplitMix64(seed ^ 0x5EED));
        let (light, p, triangles, _) = scene_on(seed, Some(&replicate));
        let bvh = Bvh::new(Occluders::from_triangles(triangles));
        let emitter = light.emitter(p).expect("an emitter");
        let mut binned = Binned::default();
        // The same set-up compiled for the build's target, without the
        // run-time dispatch to AVX2: the same decisions.
        let mut plain = Binned::default();
        let ready = binned.build(&bvh, &emitter, p, 1 << 12, 16);
        let plain_ready = lanes::dispatch::without(|| plain.build(&bvh, &emitter, p, 1 << 12, 16));
        assert_eq!(plain_ready, ready);
        if !ready {
            continue;
        }
        assert_eq!(plain.all, binned.all, "seed {seed}");
        built[match emitter {
            Emitter::Disk(_) => 0,
            Emitter::Rect(_) => 1,
            _ => 2,
        }] += 1;
        for m in [1024, 300, 33] {
            let rays = (0..m)
                .filter(|&i| bvh.segment_unoccluded(p, emitter.point_at(replicate.point(i))))
                .count() as u32;
            let cast = std::cell::Cell::new(0);
            let counted = binned.count_unoccluded(&replicate, m, |s| {
                cast.set(cast.get() + 1);
                bvh.segment_unoccluded(p, emitter.point_at(s))
            });
            assert_eq!(counted, rays, "seed {seed}, {m} samples");
            pending += cast.get();
            if let (Some(map), None) = (plain.map, plain.all) {
                let ray = |s| bvh.segment_unoccluded(p, emitter.point_at(s));
                let plain_count = plain.count_here(&map, &replicate, m, &ray);
                assert_eq!(plain_count, rays, "seed {seed}, {m} samples");
            }
        }
    }
    // Every kind set up many times, and rays cast where the plane
    // left samples undecided.
    assert!(built.iter().all(|&n| n >= 40), "{built:?}");
    assert!(pending >= 1000, "{pending} rays");
}

/// Every sample point lies in the pyramid the candidates are culled to
/// (so every sample's segment from its apex does): on or inside each
/// of its faces, decided exactly, for every kind of emitter — a
/// segment's pyramid too, thin as it is across the segment's plane —
/// the light's own corners and ends included.
#[test]
fn sample_points_lie_in_the_pyramid() {
    let mut kinds = [0; 3];
    for seed in 0..300 {
        let set = set_up(seed);
        let Some(binned) = &set.binned else {
            continue;
        };
        let [apex, base @ ..] = binned.hull;
        let inner = (apex + base.iter().sum::<DVec3>() / 4.0) / 2.0;
        // The four sides, and the base (two triangles: its corners
        // need not be exactly coplanar), each facing `inner`.
        let faces = [
            [apex, base[0], base[1]],
            [apex, base[1], base[2]],
            [apex, base[2], base[3]],
            [apex, base[3], base[0]],
            [base[0], base[1], base[2]],
            [base[0], base[2], base[3]],
        ];
        // The samples, and the light's corners and ends exactly.
        let last = 1.0 - f64::EPSILON / 2.0;
        let corners = [0.0, last].map(|x| [0.0, last].map(|y| DVec2::new(x, y)));
        for [a, b, c] in faces {
            let side = orient3d(a, b, c, inner);
            assert_ne!(side, Sign::Zero, "seed {seed}: a flat face");
            for &s in set.samples.iter().chain(corners.as_flattened()) {
                let x = set.emitter.point_at(s);
                let at = orient3d(a, b, c, x);
                assert!(at == side || at == Sign::Zero, "seed {seed}: {s:?} outside");
            }
        }
        kinds[set.kind] += 1;
    }
    assert!(kinds.iter().all(|&n| n >= 50), "{kinds:?}");
}

/// Where the set-up finds one answer for every sample, that answer is
/// every ray's, and the count is that of the rays; and it finds one
/// where it should: with nothing in the way (a triangle off to the
/// side), and with one wide triangle just in front of the receiver.
#[test]
fn one_answer_for_all_is_every_rays() {
    let mut found = [0; 2];
    for seed in 0..300 {
        let (light, p, _, _) = scene(seed);
        let emitter = light.emitter(p).expect("an emitter");
        let map = emitter.plane_map().expect("a plane");
        let toward = map.center - p;
        let across = map.axes[0].length() + map.axes[1].length();
        let (u, v) = toward.normalize().any_orthonormal_pair();
        let side = p + u * 40.0 * (across + toward.length());
        // Every ray from `p` to the light crosses the plane normal to
        // `toward` at `near` within `2 t (across + |toward|)` of it.
        let t = 1e-4;
        let near = p + toward * t;
        let reach = 40.0 * t * (across + toward.length());
        let scenes = [
            vec![[side, side + v, side + toward]],
            vec![[
                near - (u + v) * reach,
                near + (u - v) * reach,
                near + v * reach,
            ]],
        ];
        for (answer, triangles) in [true, false].into_iter().zip(scenes) {
            let bvh = Bvh::new(Occluders::from_triangles(triangles));
            let replicate = Replicate::new(&mut SplitMix64(seed));
            let rays = (0..64)
                .filter(|&i| bvh.segment_unoccluded(p, emitter.point_at(replicate.point(i))))
                .count() as u32;
            assert_eq!(rays, if answer { 64 } else { 0 }, "seed {seed}");
            let mut binned = Binned::default();
            if !binned.build(&bvh, &emitter, p, 1 << 12, 16) {
                continue;
            }
            if let Some(all) = binned.all {
                assert_eq!(all, answer, "seed {seed}");
                found[usize::from(answer)] += 1;
            }
            let counted = binned.count_unoccluded(&replicate, 64, |s| {
                bvh.segment_unoccluded(p, emitter.point_at(s))
            });
            assert_eq!(counted, rays, "seed {seed}");
        }
    }
    assert!(found.iter().all(|&n| n >= 200), "{found:?}");
}

/// The test above is not vacuous: over a fixed set of its scenes, most
/// samples are decided on the plane (the rest cast their rays), on
/// each kind of emitter.
#[test]
fn most_samples_are_decided() {
    let (mut decided, mut total) = ([0; 3], [0; 3]);
    for seed in 0..300 {
        let (count, kind) = decide_scene(seed, |a, b, s| assert_eq!(a, b, "seed {seed} s {s:?}"));
        decided[kind] += count;
        total[kind] += 1024;
    }
    for (kind, (decided, total)) in ["disk", "rect", "segment"]
        .iter()
        .zip(decided.into_iter().zip(total))
    {
        assert!(total >= 50 * 1024, "{kind}: {total} samples");
        assert!(decided * 4 > total * 3, "{kind}: {decided} of {total}");
    }
}

/// The polynomial plane coordinates are within the stated error of
/// `point_at`'s, over every wedge of the concentric map, its diagonals
/// and its centre.
#[test]
fn approximate_coordinates_are_within_their_error() {
    let light =
        Light::disk(DVec3::new(1.0, 2.0, 3.0), DVec3::new(0.3, -0.1, 1.0), 0.7).expect("a light");
    let emitter = light.emitter(DVec3::ZERO).expect("an emitter");
    let map = emitter.plane_map().expect("a plane");
    let mut rng = SplitMix64(3);
    let mut worst: f64 = 0.0;
    let special = [0.0, 0.25, 0.5, 0.75, 1.0 - f64::EPSILON / 2.0];
    let mut grid = Vec::new();
    for a in special {
        for b in special {
            grid.push(DVec2::new(a, b));
        }
    }
    for s in grid.into_iter().chain(
        (0..100_000).map(|_| DVec2::new(uniform(&mut rng, 0.0, 1.0), uniform(&mut rng, 0.0, 1.0))),
    ) {
        let x = emitter.point_at(s) - map.center;
        let exact = DVec2::new(x.dot(map.axes[0]), x.dot(map.axes[1]));
        // At the sample and at the centre of its cell on the 2³² grid,
        // where `count_unoccluded` takes it.
        let cell = (s * 4_294_967_296.0).floor().as_uvec2();
        let mut at_centre = [0.0; 2];
        let (x, y) = at_centre.split_at_mut(1);
        map.approx_grid(&[cell.x], &[cell.y], x, y);
        for q in [map.approx(s), DVec2::from(at_centre)] {
            worst = worst.max((q - exact).abs().max_element());
            assert!(q.abs().max_element() <= map.half, "{s:?}");
        }
    }
    // The error is the polynomials' (4e-6 of the radius), far above
    // the rounding of the check itself.
    assert!(worst <= map.error, "worst {worst}, bound {}", map.error);
    assert!(
        worst > 0.1 * map.error,
        "worst {worst}: the bound is far from tight"
    );
}

/// The Lipschitz constant `PlaneMap::error` allows for moving `s` by
/// `2⁻³³`: the concentric map moves by at most `2.77` times as much
/// (in units of the radius), most near the wedges' diagonals.
#[test]
fn concentric_map_is_lipschitz_as_stated() {
    let light = Light::disk(DVec3::ZERO, DVec3::Z, 1.0).expect("a light");
    let emitter = light
        .emitter(DVec3::new(0.0, 0.0, -1.0))
        .expect("an emitter");
    let mut rng = SplitMix64(5);
    let mut worst: f64 = 0.0;
    for _ in 0..200_000 {
        let s = DVec2::new(uniform(&mut rng, 0.0, 1.0), uniform(&mut rng, 0.0, 1.0));
        let step = DVec2::new(uniform(&mut rng, -1.0, 1.0), uniform(&mut rng, -1.0, 1.0)) * 1e-5;
        let t = (s + step).clamp(DVec2::ZERO, DVec2::splat(0.999_999));
        let moved = (emitter.point_at(t) - emitter.point_at(s)).length();
        worst = worst.max(moved / (t - s).length());
    }
    // The bound derived at `PlaneMap`'s construction: `2 · 1.382351`.
    let bound = 2.0 * 1.382_351;
    assert!(worst <= bound, "worst {worst}");
    assert!(
        worst > bound * 0.999,
        "worst {worst}: the constant is far from tight"
    );
}
