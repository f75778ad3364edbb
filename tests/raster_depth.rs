//! The light-view rasterizer (`softshadow::render::raster`): depth,
//! triangle and object against a Möller–Trumbore ray cast through every
//! pixel centre (relative depth error below `1e-12`) on random triangle
//! soups, and exact depth for a plane parallel to the image plane.
#![cfg(feature = "render")]

use glam::{DVec2, DVec3};
use softshadow::arbitrary::Rng;
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
