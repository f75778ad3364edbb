//! The light-view rasterizer (`softshadow::render::raster`): depth,
//! triangle and object against a Möller–Trumbore ray cast through every
//! pixel centre (relative depth error below `1e-12`) on random triangle
//! soups, and exact depth for a plane parallel to the image plane.
#![cfg(feature = "render")]

use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3};
use softshadow::render::raster::{rasterize, LightView};

#[path = "support/raster.rs"]
mod raster_support;
use raster_support::{lattice_view, random_frame, ray_triangle};

// ---------------------------------------------------------------------------
// Depth, triangle and object against an independent ray cast.

#[test]
fn depth_triangle_and_object_match_a_ray_cast() {
    let mut rng = Rng::new(14);
    let margin = 1e-9;
    let mut checked = 0usize;
    let mut worst = 0.0f64;
    for case in 0..60 {
        let frame = random_frame(&mut rng);
        let near = 0.5;
        let [ax, ay, az] = frame.axes();
        // A soup of overlapping triangles at light depths 0.2..4 (some cut
        // by the near plane), not grazing.
        let count = 1 + rng.below(30) as usize;
        let tris: Vec<[DVec3; 3]> = (0..count)
            .map(|_| {
                let c = DVec3::new(
                    rng.uniform(-1.5, 1.5),
                    rng.uniform(-1.5, 1.5),
                    rng.uniform(0.6, 4.0),
                );
                let r = rng.uniform(0.3, 1.5);
                [0; 3].map(|_| {
                    let l = c + DVec3::new(
                        rng.uniform(-r, r),
                        rng.uniform(-r, r),
                        rng.uniform(-0.5, 0.5) * r,
                    );
                    frame.to_world(l)
                })
            })
            .collect();
        let objects: Vec<u32> = (0..count).map(|_| rng.below(5) as u32).collect();
        let view =
            LightView::new(frame, DVec2::splat(-0.9), DVec2::splat(0.9), 37, 29, near).unwrap();
        let maps = rasterize(&view, &tris, &objects).unwrap();
        for row in 0..view.height() {
            for col in 0..view.width() {
                let p = view.pixel_center(col, row);
                // The ray in the world; its light-frame z-component is 1, so
                // the hit's light depth is t (to rounding).
                let dir = ax * p.x + ay * p.y + az;
                let origin = frame.origin();
                let hits: Vec<(usize, f64, bool)> = tris
                    .iter()
                    .enumerate()
                    .filter_map(|(i, tri)| {
                        let (t, u, v) = ray_triangle(origin, dir, tri)?;
                        let z = frame.to_light(origin + dir * t).z;
                        let inside = u >= -margin && v >= -margin && u + v <= 1.0 + margin;
                        let robust = u > margin && v > margin && u + v < 1.0 - margin;
                        (inside && z >= near * (1.0 - margin)).then_some((
                            i,
                            z,
                            robust && z > near * (1.0 + margin),
                        ))
                    })
                    .collect();
                let nearest_robust = hits
                    .iter()
                    .filter(|h| h.2)
                    .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
                let tri = maps.triangle_at(col, row);
                if tri == u32::MAX {
                    assert_eq!(maps.depth_at(col, row), f64::INFINITY);
                    assert_eq!(maps.object_at(col, row), u32::MAX);
                    assert!(
                        nearest_robust.is_none(),
                        "case {case}: ({col}, {row}) missed {nearest_robust:?}"
                    );
                    continue;
                }
                checked += 1;
                let i = tri as usize;
                assert_eq!(maps.object_at(col, row), objects[i]);
                let depth = maps.depth_at(col, row);
                // The plane depth of the rasterised triangle on this ray.
                let (t, _, _) = ray_triangle(origin, dir, &tris[i]).unwrap();
                let z = frame.to_light(origin + dir * t).z;
                worst = worst.max(((depth - z) / z).abs());
                assert!(
                    ((depth - z) / z).abs() < 1e-12,
                    "case {case}: ({col}, {row}) depth {depth} against {z}"
                );
                // The rasterised triangle is a hit of the ray...
                assert!(
                    hits.iter().any(|h| h.0 == i),
                    "case {case}: ({col}, {row}) triangle {i} not hit"
                );
                // ...and the nearest robust hit, unless tied in depth.
                if let Some(&(j, zj, _)) = nearest_robust {
                    assert!(
                        depth <= zj * (1.0 + 1e-12),
                        "case {case}: ({col}, {row}) {depth} behind {zj}"
                    );
                    if j != i {
                        let tied = ((zj - depth) / depth).abs() < 1e-12;
                        let marginal = !hits.iter().any(|h| h.0 == i && h.2);
                        assert!(
                            tied || marginal,
                            "case {case}: ({col}, {row}) triangle {i}, ray says {j}"
                        );
                    }
                }
            }
        }
    }
    assert!(checked > 10_000, "checked {checked} pixels");
    eprintln!("worst relative depth error {worst:e} over {checked} pixels");
}

#[test]
fn depth_is_exact_for_a_plane_parallel_to_the_image_plane() {
    let view = lattice_view(0.5);
    let tri = [
        DVec3::new(-9.0, -9.0, 3.0),
        DVec3::new(9.0, -9.0, 3.0),
        DVec3::new(0.0, 9.0, 3.0),
    ];
    let maps = rasterize(&view, &[tri], &[0]).unwrap();
    assert!(maps.depth().iter().all(|&d| d == 3.0 || d == f64::INFINITY));
    assert!(maps.depth().iter().filter(|&&d| d == 3.0).count() > 500);
}

#[path = "support/dd.rs"]
#[allow(dead_code)]
mod dd;

/// The plane depth along `(u, v, 1)` of the triangle `q` (light frame), in
/// double-double: `z = n·p / n·(u, v, 1)` with `n = (b − a) × (c − a)` and
/// `p` the corner nearest the light, the differences and products carried
/// to about 106 bits.
fn depth_dd(q: [DVec3; 3], u: DVec2) -> f64 {
    use dd::{two_prod, Dd};
    let c = |x: f64| Dd { hi: x, lo: 0.0 };
    let sub = |p: DVec3, r: DVec3| [0, 1, 2].map(|k| c(p[k]).sub(c(r[k])));
    let (e1, e2) = (sub(q[1], q[0]), sub(q[2], q[0]));
    let n = [
        e1[1].mul(e2[2]).sub(e1[2].mul(e2[1])),
        e1[2].mul(e2[0]).sub(e1[0].mul(e2[2])),
        e1[0].mul(e2[1]).sub(e1[1].mul(e2[0])),
    ];
    let dot = |v: [f64; 3]| {
        n[0].mul(c(v[0]))
            .add(n[1].mul(c(v[1])))
            .add(n[2].mul(c(v[2])))
    };
    let _ = two_prod;
    // The plane's offset from the corner nearest the light: `n` carries an
    // absolute error (about 10⁻³² of its products), which a far corner
    // would multiply by its distance.
    let base = q
        .into_iter()
        .min_by(|x, y| x.length().total_cmp(&y.length()))
        .unwrap_or(q[0]);
    dot(base.to_array()).div(dot([u.x, u.y, 1.0])).to_f64()
}

#[test]
fn a_corner_far_behind_the_light_keeps_the_depth_of_the_sliver() {
    // Found by the `raster` fuzz target: a sliver whose third corner lies
    // 4·10¹³ away behind the light, clipped at the near depth. From that
    // corner both edges round to one direction, and the plane they gave
    // put a pixel at the sliver's far end (4.0739) where the plane is at
    // 4.0439; the plane is now taken from the corner opposite the longest
    // edge.
    let q = [
        DVec3::new(-41250006549658.49, 41192122540089.48, -2270596109324.049),
        DVec3::new(
            0.003796701237584077,
            -0.0006640484041836314,
            4.050879326622124,
        ),
        DVec3::new(
            0.017790165384235168,
            -0.018957469921259018,
            4.073942340988978,
        ),
    ];
    let frame = softshadow::scene::LightFrame::toward(DVec3::ZERO, DVec3::Z).unwrap();
    let world = q.map(|p| frame.to_world(p));
    let q = world.map(|p| frame.to_light(p));
    let view = LightView::new(frame, DVec2::splat(-0.5), DVec2::splat(0.5), 11, 11, 0.015).unwrap();
    let maps = rasterize(&view, &[world], &[0]).unwrap();
    let mut covered = 0;
    for row in 0..11 {
        for col in 0..11 {
            if !maps.is_covered(col, row) {
                continue;
            }
            covered += 1;
            let u = view.pixel_center(col, row);
            let want = depth_dd(q, u);
            let got = maps.depth_at(col, row);
            // The documented bound: a few ulps times the conditioning
            // |n|·|(u, v, 1)| / |n·(u, v, 1)| (the sliver is seen nearly
            // edge-on here).
            let n = (q[2] - q[1]).cross(q[0] - q[1]);
            let ray = DVec3::new(u.x, u.y, 1.0);
            let kappa = n.length() * ray.length() / n.dot(ray).abs();
            let bound = 8.0 * f64::EPSILON * kappa * want;
            assert!(
                (got - want).abs() <= bound,
                "pixel ({col}, {row}): {got} against {want} (κ = {kappa:.3e})"
            );
        }
    }
    assert!(covered > 0);
}

#[test]
fn a_corner_far_past_the_near_depth_keeps_the_clipped_outline() {
    // Found by the `raster` fuzz target: one corner behind the near depth,
    // one 10⁶⁶ beyond it. The crossing of their edge with the near plane
    // was interpolated from the far end, whose parameter rounds to 1, and
    // landed near the origin instead of at x ≈ −30; the clipped polygon
    // then covered the lower left of this window. Exactly (rational
    // arithmetic), the clipped polygon's corners project to
    // (−92.3, −169.7), (−0.645, −1.409), (−5.875, 0.055) and (−5025, −104):
    // all left of or below the window [−½, ½]², whose pixels it misses.
    let q = [
        DVec3::new(
            -1.0920388876787268,
            -0.8949689611650419,
            -4.9403953462796935,
        ),
        DVec3::new(-0.47437574118339815, -1.036587284102709, 0.7358299309484109),
        DVec3::new(
            -6.18817473522882e66,
            5.776022231042852e64,
            1.053276841691022e66,
        ),
    ];
    let frame = softshadow::scene::LightFrame::toward(DVec3::ZERO, DVec3::Z).unwrap();
    let world = q.map(|p| frame.to_world(p));
    assert_eq!(
        world.map(|p| frame.to_light(p)),
        q,
        "the frame is the identity"
    );
    let view = LightView::new(frame, DVec2::splat(-0.5), DVec2::splat(0.5), 13, 13, 0.006).unwrap();
    let maps = rasterize(&view, &[world], &[0]).unwrap();
    let covered = (0..13)
        .flat_map(|r| (0..13).map(move |c| (c, r)))
        .filter(|&(c, r)| maps.is_covered(c, r))
        .count();
    assert_eq!(covered, 0);
}

#[test]
fn two_far_corners_keep_the_depth_near_the_third() {
    // Found by the `raster` fuzz target: two corners 10³⁰ away, one near
    // the light. A plane anchored at a far corner places the near corner
    // only to 10¹⁴; anchored at the nearest corner, the depth of the
    // pixels near it is right. Checked against the double-double plane.
    let q = [
        DVec3::new(
            3.5294089286371225e30,
            2.46995630644165e26,
            3.006232127933387e28,
        ),
        DVec3::new(
            -0.06181157149560154,
            -0.05291364706523842,
            5.8231956460716745,
        ),
        DVec3::new(
            3.559224254285812e30,
            -3.5868067201318507e30,
            -3.4408768982998435e30,
        ),
    ];
    depths_match_the_double_double_plane(q, 9, 0.071);
}

#[test]
fn corners_far_apart_in_depth_keep_the_plane_near_the_light() {
    // Found by the `raster` fuzz target: corners 10⁷⁸ and 10²⁸ away, one
    // near the light. Both the near-plane cut of the far edge and the
    // normal's components are differences of terms that cancel by 16
    // digits or more; in double length (error-free products) the depths
    // near the light are right. Checked against the double-double plane.
    let q = [
        DVec3::new(
            0.004457689260174119,
            0.001213924242751352,
            3.1326282079377425,
        ),
        DVec3::new(
            -1.5508161707532255e78,
            3.793158882826991e75,
            7.266293279499008e76,
        ),
        DVec3::new(
            2.0793936589461615e28,
            -5.086012563626311e25,
            -9.742924051465575e26,
        ),
    ];
    depths_match_the_double_double_plane(q, 17, 0.013);
}

/// The triangle `q` (light-frame corners; the frame is the identity) in an
/// `n × n` view of the window `[−½, ½]²` with near depth `near`: every
/// covered pixel's depth within 1e-9 of the double-double plane's, and at
/// least one pixel covered.
fn depths_match_the_double_double_plane(q: [DVec3; 3], n: u32, near: f64) {
    let frame = softshadow::scene::LightFrame::toward(DVec3::ZERO, DVec3::Z).unwrap();
    let world = q.map(|p| frame.to_world(p));
    assert_eq!(
        world.map(|p| frame.to_light(p)),
        q,
        "the frame is the identity"
    );
    let view = LightView::new(frame, DVec2::splat(-0.5), DVec2::splat(0.5), n, n, near).unwrap();
    let maps = rasterize(&view, &[world], &[0]).unwrap();
    let mut covered = 0;
    for row in 0..n {
        for col in 0..n {
            if !maps.is_covered(col, row) {
                continue;
            }
            covered += 1;
            let want = depth_dd(q, view.pixel_center(col, row));
            let got = maps.depth_at(col, row);
            assert!(
                (got - want).abs() <= 1e-9 * want,
                "pixel ({col}, {row}): {got} against {want}"
            );
        }
    }
    assert!(covered > 0);
}
