//! `Bvh::closest_hit`: against brute force over every triangle (bit for
//! bit), watertightness on closed meshes, agreement with the occlusion
//! query, the returned normal, `t_max`, non-finite input, the paths without
//! a tree, determinism across thread counts, and the batch forms
//! (`closest_hits`, `closest_hit_many`) against one call per ray.

use softshadow::arbitrary::mesh::{closed_mesh, icosphere, Mesh as IndexedMesh};
use softshadow::arbitrary::scene::visibility_case;
use softshadow::arbitrary::Rng;
use softshadow::bvh::{Bvh, Hit, Occluders};
use softshadow::glam::DVec3;
use softshadow::kernel::segment::segment_crossing;
use softshadow::scene::primitive::{cuboid, sphere};
use softshadow::scene::Mesh;

/// The closest hit by testing every triangle in index order with the same
/// exact test on the same segment ([`Bvh::ray_segment`]): the least `u`,
/// the first index among equal ones.
fn brute_force(bvh: &Bvh, origin: DVec3, direction: DVec3, t_max: f64) -> Option<(f64, u32)> {
    if t_max.is_nan() || t_max <= 0.0 {
        return None;
    }
    let (x, t_x) = bvh.ray_segment(origin, direction)?;
    let mut best: Option<(f64, u32)> = None;
    for (i, t) in bvh.occluders().triangles().iter().enumerate() {
        if !t.iter().all(|v| v.is_finite()) {
            continue;
        }
        if let Some(u) = segment_crossing(origin, x, t) {
            if u * t_x <= t_max && best.is_none_or(|(b, _)| u < b) {
                best = Some((u, i as u32));
            }
        }
    }
    best.map(|(u, i)| ((u * t_x).clamp(f64::from_bits(1), t_max.min(f64::MAX)), i))
}

/// Asserts that the BVH's answer is brute force's, bit for bit, and that the
/// hit is well formed.
fn check(bvh: &Bvh, origin: DVec3, direction: DVec3, t_max: f64) -> Option<Hit> {
    let hit = bvh.closest_hit(origin, direction, t_max);
    // The batch, compiled apart (for AVX2 where present): the same bits.
    let mut batch = vec![None; 3];
    bvh.closest_hits(&[(origin, direction)], t_max, &mut batch);
    assert_eq!(batch, vec![hit]);
    let expected = brute_force(bvh, origin, direction, t_max);
    assert_eq!(
        hit.map(|h| (h.t, h.triangle)),
        expected,
        "origin {origin:?} direction {direction:?} t_max {t_max:?}"
    );
    if let Some(h) = hit {
        assert!(h.t > 0.0 && h.t <= t_max, "{h:?}");
        assert_eq!(
            h.object,
            bvh.occluders().objects()[h.triangle as usize],
            "{h:?}"
        );
        assert!((h.normal.length() - 1.0).abs() < 1e-12, "{h:?}");
        assert!(h.normal.dot(direction) <= 0.0, "{h:?} {direction:?}");
    }
    hit
}

fn bvh_of(triangles: Vec<[DVec3; 3]>) -> Bvh {
    Bvh::new(Occluders::from_triangles(triangles))
}

fn triangles_of(mesh: &IndexedMesh) -> Vec<[DVec3; 3]> {
    mesh.triangles
        .iter()
        .map(|t| t.map(|i| mesh.positions[i as usize]))
        .collect()
}

fn scene_triangles(mesh: &Mesh) -> Vec<[DVec3; 3]> {
    (0..mesh.triangles().len())
        .map(|t| mesh.corners(t).expect("index"))
        .collect()
}

fn unit(rng: &mut Rng) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        );
        if v.length_squared() <= 1.0 {
            if let Some(u) = v.try_normalize() {
                return u;
            }
        }
    }
}

/// A point of `t`: a corner, a point on an edge (one weight exactly zero),
/// or inside.
fn point_on(rng: &mut Rng, t: &[DVec3; 3]) -> DVec3 {
    let k = rng.below(3) as usize;
    let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
    match rng.below(4) {
        0 => a,
        1 => a + (b - a) * rng.unit(),
        2 => (a + b) * 0.5,
        _ => {
            let (mut s, mut r) = (rng.unit(), rng.unit());
            if s + r > 1.0 {
                (s, r) = (1.0 - s, 1.0 - r);
            }
            a + (b - a) * s + (c - a) * r
        }
    }
}

/// A direction for a ray from `origin` into `triangles`: at a corner, an
/// edge point or an inner point of one of them, or random.
fn direction(rng: &mut Rng, origin: DVec3, triangles: &[[DVec3; 3]]) -> DVec3 {
    if rng.chance(0.2) || triangles.is_empty() {
        return unit(rng) * rng.log_uniform(-3.0, 3.0);
    }
    let t = &triangles[rng.below(triangles.len() as u64) as usize];
    let d = point_on(rng, t) - origin;
    if d == DVec3::ZERO {
        unit(rng)
    } else {
        d * rng.log_uniform(-2.0, 2.0)
    }
}

fn t_max(rng: &mut Rng) -> f64 {
    if rng.chance(0.7) {
        f64::INFINITY
    } else {
        rng.log_uniform(-2.0, 1.0)
    }
}

#[test]
fn matches_brute_force_on_soups() {
    let mut rng = Rng::new(1);
    let mut hits = 0;
    for _ in 0..400 {
        let case = visibility_case(&mut rng, 60);
        let bvh = bvh_of(case.triangles.clone());
        for _ in 0..60 {
            let origin = if rng.chance(0.5) {
                case.receiver
            } else {
                case.receiver + unit(&mut rng) * rng.uniform(0.0, 3.0)
            };
            let d = direction(&mut rng, origin, &case.triangles);
            let tm = t_max(&mut rng);
            hits += usize::from(check(&bvh, origin, d, tm).is_some());
        }
    }
    // Most rays are aimed at a triangle.
    assert!(hits > 400 * 60 / 2, "{hits}");
}

#[test]
fn matches_brute_force_on_closed_meshes() {
    let mut rng = Rng::new(2);
    for _ in 0..300 {
        let mesh = closed_mesh(&mut rng);
        let triangles = triangles_of(&mesh);
        let bvh = bvh_of(triangles.clone());
        let (lo, hi) = mesh.positions.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let (centre, size) = ((lo + hi) * 0.5, (hi - lo).max_element());
        for _ in 0..60 {
            let origin = centre + unit(&mut rng) * size * rng.uniform(0.0, 2.0);
            let d = direction(&mut rng, origin, &triangles);
            let tm = if rng.chance(0.7) {
                f64::INFINITY
            } else {
                size * rng.uniform(0.0, 2.0) / d.length()
            };
            check(&bvh, origin, d, tm);
        }
    }
}

/// Rays from one origin within a narrow cone, as a camera's are: the batch
/// query traces eight such rays through one walk of the tree. Each ray's
/// answer is checked against brute force and one query per ray; the
/// directions are aimed at corners, edges and inner points of nearby
/// triangles (soups with coincident copies and shared edges, and closed
/// meshes), so ties and watertightness are exercised in packets too.
#[test]
fn coherent_batches_match_brute_force() {
    let mut rng = Rng::new(11);
    let (mut rays, mut coherent) = (0, 0);
    for case in 0..240 {
        let triangles = if case % 2 == 0 {
            visibility_case(&mut rng, 40).triangles
        } else {
            triangles_of(&closed_mesh(&mut rng))
        };
        let bvh = bvh_of(triangles.clone());
        let (lo, hi) = triangles.iter().flatten().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let (centre, size) = ((lo + hi) * 0.5, (hi - lo).max_element());
        for _ in 0..6 {
            let origin = centre + unit(&mut rng) * size * rng.uniform(2.0, 8.0);
            let n = 8 + rng.below(17) as usize;
            // Aimed at points of one triangle, or about its centre.
            let t = &triangles[rng.below(triangles.len() as u64) as usize];
            let about = ((t[0] + t[1] + t[2]) / 3.0 - origin).normalize();
            let spread = rng.log_uniform(-4.0, -1.0);
            let batch: Vec<(DVec3, DVec3)> = (0..n)
                .map(|_| {
                    let d = if rng.chance(0.8) {
                        point_on(&mut rng, t) - origin
                    } else {
                        about + unit(&mut rng) * spread
                    };
                    // Now and then a length outside `[1e-300, 1e300]`,
                    // where the set-up divides instead.
                    let length = match rng.below(20) {
                        0 => 1e-305,
                        1 => 1e303,
                        _ => rng.log_uniform(-1.0, 1.0),
                    };
                    (origin, d * length)
                })
                .collect();
            let tm = t_max(&mut rng) * size;
            let mut out = Vec::new();
            bvh.closest_hits(&batch, tm, &mut out);
            for (k, (&(o, d), hit)) in batch.iter().zip(&out).enumerate() {
                assert_eq!(*hit, check(&bvh, o, d, tm), "case {case}, ray {k}");
            }
            rays += n;
            // Packets the batch may trace together (directions within a
            // quarter of each other in max-norm units).
            for group in batch.chunks_exact(8) {
                let s = |d: DVec3| d / d.abs().max_element();
                let s0 = s(group[0].1);
                coherent += usize::from(
                    group
                        .iter()
                        .all(|&(_, d)| (s(d) - s0).abs().max_element() <= 0.25),
                );
            }
        }
    }
    assert!(
        coherent > 1500,
        "{coherent} coherent packets of {rays} rays"
    );
}

/// Convex closed meshes with shared, bit-identical corners: UV spheres,
/// boxes and icospheres at random scales and offsets.
fn convex_meshes(rng: &mut Rng) -> Vec<(Vec<[DVec3; 3]>, DVec3, f64)> {
    let mut out = Vec::new();
    for _ in 0..40 {
        let scale = rng.log_uniform(-3.0, 3.0);
        let centre = DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        ) * scale
            * rng.log_uniform(-2.0, 2.0);
        let triangles = match rng.below(3) {
            0 => scene_triangles(
                &sphere(centre, scale, 3 + rng.below(40) as u32).expect("sphere primitive"),
            ),
            1 => {
                let half = DVec3::new(
                    rng.uniform(0.2, 1.0),
                    rng.uniform(0.2, 1.0),
                    rng.uniform(0.2, 1.0),
                ) * scale;
                scene_triangles(&cuboid(centre - half, centre + half).expect("cuboid"))
            }
            _ => {
                triangles_of(&icosphere(rng.below(4) as u32).map_positions(|p| centre + p * scale))
            }
        };
        out.push((triangles, centre, scale));
    }
    out
}

#[test]
fn rays_through_vertices_and_edges_of_closed_meshes_hit() {
    let mut rng = Rng::new(3);
    for (triangles, centre, scale) in convex_meshes(&mut rng) {
        let bvh = bvh_of(triangles.clone());
        for _ in 0..400 {
            let t = &triangles[rng.below(triangles.len() as u64) as usize];
            let k = rng.below(3) as usize;
            let (a, b) = (t[k], t[(k + 1) % 3]);
            // A vertex, an edge midpoint, or a point along the edge.
            let q = match rng.below(3) {
                0 => a,
                1 => (a + b) * 0.5,
                _ => a + (b - a) * rng.unit(),
            };
            // From inside (near the centre): every ray leaves the solid.
            let inside = centre + unit(&mut rng) * scale * rng.uniform(0.0, 0.1);
            let hit = check(&bvh, inside, q - inside, f64::INFINITY);
            assert!(hit.is_some(), "slipped out through {q:?} from {inside:?}");
            // From outside, on a line through a point near the centre: the
            // ray enters the solid at `q`.
            let outside = centre + (q - centre) * 3.0 + unit(&mut rng) * scale * 0.05;
            let hit = check(&bvh, outside, q - outside, f64::INFINITY);
            let hit = hit.unwrap_or_else(|| panic!("slipped in at {q:?} from {outside:?}"));
            assert!(hit.t <= 1.0 + 1e-9, "{hit:?} beyond the aimed point {q:?}");
        }
    }
}

#[test]
fn hits_agree_with_segment_unoccluded() {
    let mut rng = Rng::new(4);
    let (mut before, mut past) = (0, 0);
    for round in 0..200 {
        let (triangles, origin) = if round % 2 == 0 {
            let case = visibility_case(&mut rng, 40);
            (case.triangles, case.receiver)
        } else {
            let mesh = closed_mesh(&mut rng);
            let p = mesh.positions[0] * 3.0;
            (triangles_of(&mesh), p)
        };
        let bvh = bvh_of(triangles);
        for _ in 0..50 {
            let d = unit(&mut rng);
            let hit = bvh.closest_hit(origin, d, f64::INFINITY);
            // No hit: the whole segment the query decided on is free.
            if let Some((x, _)) = bvh.ray_segment(origin, d) {
                assert_eq!(
                    hit.is_some(),
                    !bvh.segment_unoccluded(origin, x),
                    "{origin:?} {d:?}"
                );
            }
            let Some(hit) = hit else { continue };
            let near = origin + d * (hit.t * (1.0 - 1e-7));
            let far = origin + d * (hit.t * (1.0 + 1e-7));
            before += usize::from(bvh.segment_unoccluded(origin, near));
            past += usize::from(!bvh.segment_unoccluded(origin, far));
            assert!(
                bvh.segment_unoccluded(origin, near),
                "occluded before the hit {hit:?}: {origin:?} {d:?}"
            );
            assert!(
                !bvh.segment_unoccluded(origin, far),
                "unoccluded past the hit {hit:?}: {origin:?} {d:?}"
            );
        }
    }
    assert!(before > 1000 && before == past, "{before} {past}");
}

#[test]
fn normal_is_unit_and_faces_the_ray() {
    // Both windings, both sides.
    let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
    for tri in [t, [t[0], t[2], t[1]]] {
        let bvh = bvh_of(vec![tri]);
        for (o, d) in [
            (DVec3::new(0.2, 0.2, 1.0), -DVec3::Z * 3.0),
            (DVec3::new(0.2, 0.2, -1.0), DVec3::new(0.1, 0.0, 1.0)),
        ] {
            let hit = check(&bvh, o, d, f64::INFINITY).expect("hit");
            assert_eq!(hit.normal, DVec3::Z * -d.z.signum());
            let p = o + d * hit.t;
            assert!(p.z.abs() < 1e-15, "{p:?}");
        }
    }
    // A sliver in the plane `y = z`: the normal is still unit and facing.
    let sliver = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(1.0, 1e-13, 1e-13),
    ];
    let bvh = bvh_of(vec![sliver]);
    let centroid = (sliver[0] + sliver[1] + sliver[2]) / 3.0;
    let origin = DVec3::new(1.1, -1.0, 1.0);
    let d = centroid - origin;
    let hit = check(&bvh, origin, d, f64::INFINITY).expect("sliver hit");
    let expected = DVec3::new(0.0, -1.0, 1.0).normalize();
    assert!((hit.normal - expected).length() < 1e-12, "{hit:?}");
}

#[test]
fn ties_go_to_the_lower_index() {
    let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
    let (o, d) = (DVec3::new(0.2, 0.2, 1.0), -DVec3::Z);
    // Coincident copies, either winding, in either order, and behind a
    // neighbour sharing their edge `x + y = 1` (not on the ray).
    for triangles in [
        vec![t, [t[2], t[1], t[0]]],
        vec![[t[2], t[1], t[0]], t],
        vec![[DVec3::X, DVec3::ONE, DVec3::Y], t, t],
    ] {
        let bvh = bvh_of(triangles.clone());
        let hit = check(&bvh, o, d, f64::INFINITY).expect("hit");
        let first = triangles
            .iter()
            .position(|&u| u == t || u == [t[2], t[1], t[0]]);
        assert_eq!(Some(hit.triangle as usize), first);
    }
    // A ray through the shared edge of two triangles: the lower index.
    let quad = vec![
        [DVec3::ZERO, DVec3::X, DVec3::Y],
        [DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
    ];
    let hit = check(&bvh_of(quad), DVec3::new(0.5, 0.5, 1.0), -DVec3::Z, 9.0).expect("hit");
    assert_eq!(hit.triangle, 0);
    assert!((hit.t - 1.0).abs() < 1e-15, "{hit:?}");
}

#[test]
fn t_max_is_respected() {
    // Two parallel squares at z = 1 and z = 2, ray down the z axis.
    let square = |z: f64| {
        let c = [
            DVec3::new(-1.0, -1.0, z),
            DVec3::new(1.0, -1.0, z),
            DVec3::new(1.0, 1.0, z),
            DVec3::new(-1.0, 1.0, z),
        ];
        [[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
    };
    let mut triangles = square(2.0).to_vec();
    triangles.extend(square(1.0));
    let bvh = bvh_of(triangles);
    let (o, d) = (DVec3::new(0.3, 0.2, 0.0), DVec3::new(0.0, 0.0, 0.5));
    let first = check(&bvh, o, d, f64::INFINITY).expect("hit");
    assert_eq!(first.triangle / 2, 1);
    assert!((first.t - 2.0).abs() < 1e-14, "{first:?}");
    // t_max exactly at the hit: inclusive.
    assert_eq!(check(&bvh, o, d, first.t), Some(first));
    // Just short of it: nothing.
    assert_eq!(check(&bvh, o, d, first.t.next_down()), None);
    // Starting on the near square: it is not hit (t > 0), the far one is.
    let on = check(&bvh, DVec3::new(0.3, 0.2, 1.0), d, f64::INFINITY).expect("hit");
    assert_eq!(on.triangle / 2, 0);
    assert!((on.t - 2.0).abs() < 1e-14, "{on:?}");
    let mut rng = Rng::new(5);
    for _ in 0..2000 {
        let o = DVec3::new(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), -0.5);
        let d = DVec3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 1.0);
        check(&bvh, o, d, rng.uniform(0.0, 4.0));
    }
}

#[test]
fn invalid_input_gives_none() {
    let bvh = bvh_of(vec![[DVec3::ZERO, DVec3::X, DVec3::Y]]);
    let (o, d) = (DVec3::new(0.1, 0.1, 1.0), -DVec3::Z);
    assert!(bvh.closest_hit(o, d, f64::INFINITY).is_some());
    let nan = DVec3::new(f64::NAN, 0.0, 0.0);
    let inf = DVec3::new(0.0, f64::INFINITY, 0.0);
    for (o, d, t) in [
        (nan, d, f64::INFINITY),
        (inf, d, f64::INFINITY),
        (o, nan, f64::INFINITY),
        (o, inf, f64::INFINITY),
        (o, -inf, f64::INFINITY),
        (o, DVec3::ZERO, f64::INFINITY),
        (o, d, f64::NAN),
        (o, d, 0.0),
        (o, d, -1.0),
        (o, d, f64::NEG_INFINITY),
    ] {
        assert_eq!(bvh.closest_hit(o, d, t), None, "{o:?} {d:?} {t:?}");
        assert_eq!(bvh.closest_hit_many(&[(o, d)], t), vec![None]);
        // One such ray among seven good ones from one origin (a packet the
        // batch would otherwise trace together): every answer as one
        // query's.
        let good = (DVec3::new(0.1, 0.1, 1.0), -DVec3::Z);
        let mut batch = vec![good; 8];
        batch[5] = (o, d);
        let each: Vec<_> = batch
            .iter()
            .map(|&(o, d)| bvh.closest_hit(o, d, t))
            .collect();
        assert_eq!(bvh.closest_hit_many(&batch, t), each, "{o:?} {d:?} {t:?}");
        assert_eq!(each[5], None);
    }
    // No triangle, or only non-finite ones.
    assert_eq!(bvh_of(vec![]).closest_hit(o, d, f64::INFINITY), None);
    let broken = [DVec3::ZERO, DVec3::X, nan];
    assert_eq!(bvh_of(vec![broken]).closest_hit(o, d, f64::INFINITY), None);
    // Tiny and huge directions give the same hit point.
    for scale in [1e-300, 1e-200, 1e-30, 1e30, 1e200, 1e300] {
        let hit = check(&bvh, o, d * scale, f64::INFINITY).expect("hit");
        let p = o + d * scale * hit.t;
        assert!(p.z.abs() < 1e-14, "{scale}: {hit:?} {p:?}");
    }
    // A zero-area triangle is never hit.
    let flat = bvh_of(vec![[DVec3::ZERO, DVec3::X, DVec3::X * 2.0]]);
    assert_eq!(
        check(&flat, DVec3::new(0.5, 0.0, 1.0), -DVec3::Z, 9.0),
        None
    );
}

#[test]
fn far_triangles_and_the_untreed_path_match_brute_force() {
    let mut rng = Rng::new(6);
    for _ in 0..100 {
        let case = visibility_case(&mut rng, 40);
        let mut triangles = case.triangles.clone();
        // Triangles beyond the tree's range (2⁶⁰), one of them a huge
        // floor under everything.
        let big = 1e19;
        triangles.push([
            DVec3::new(-big, -big, -1.0),
            DVec3::new(big, -big, -1.0),
            DVec3::new(0.0, big, -1.0),
        ]);
        triangles.push([
            DVec3::new(big, 0.0, 0.0),
            DVec3::new(big, 1.0, 0.0),
            DVec3::new(big, 0.0, 1.0),
        ]);
        let bvh = bvh_of(triangles.clone());
        for _ in 0..40 {
            let origin = case.receiver + unit(&mut rng) * rng.uniform(0.0, 2.0);
            let d = direction(&mut rng, origin, &triangles);
            check(&bvh, origin, d, t_max(&mut rng));
        }
        // An origin beyond the f32 range: every triangle is tested.
        let bvh = bvh_of(case.triangles.clone());
        for _ in 0..10 {
            let origin = DVec3::new(1e39, rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
            let target = point_on(&mut rng, &case.triangles[0]);
            check(&bvh, origin, target - origin, f64::INFINITY);
        }
    }
}

/// Pinhole camera rays through pixel centres, row 0 at the top.
#[cfg(feature = "scene-file")]
fn camera_rays(camera: &softshadow::scene::Camera, step: u32) -> Vec<(DVec3, DVec3)> {
    let (w, h) = camera.resolution();
    let mut out = Vec::new();
    for row in (0..h).step_by(step as usize) {
        for col in (0..w).step_by(step as usize) {
            let (eye, d) = camera.primary_ray(col, row);
            out.push((eye, d.normalize()));
        }
    }
    out
}

#[cfg(feature = "scene-file")]
#[test]
fn primary_rays_of_the_default_scene_match_brute_force_on_any_thread_count() {
    let scene = softshadow::scene::builtin("default").expect("default scene");
    let camera = *scene.camera().expect("camera");
    let bvh = Bvh::new(Occluders::from_scene(&scene));
    let rays = camera_rays(&camera, 8);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .expect("pool");
    let a = one.install(|| bvh.closest_hit_many(&rays, f64::INFINITY));
    let b = two.install(|| bvh.closest_hit_many(&rays, f64::INFINITY));
    assert_eq!(a, b);
    let mut c = Vec::new();
    bvh.closest_hits(&rays, f64::INFINITY, &mut c);
    assert_eq!(a, c);
    let (mut floor, mut bunny, mut sky) = (0, 0, 0);
    for (&(o, d), hit) in rays.iter().zip(&a) {
        assert_eq!(*hit, check(&bvh, o, d, f64::INFINITY));
        match hit.map(|h| h.object) {
            Some(0) => floor += 1,
            Some(_) => bunny += 1,
            None => sky += 1,
        }
    }
    assert!(floor > 0 && bunny > 0, "{floor} {bunny} {sky}");
}
