//! The light-view rasterizer (`softshadow::render::raster`) on the default
//! scene (feature `scene-file`): the closed bunny covers every pixel an
//! even number of times, also with pixel centres placed exactly on hundreds
//! of its vertices; depth, triangle and object match a Möller–Trumbore ray
//! cast through every pixel centre.
#![cfg(all(feature = "render", feature = "scene-file"))]

use softshadow::bvh::Occluders;
use softshadow::glam::{DVec2, DVec3};
use softshadow::render::raster::{rasterize_occluders, LightView};
use softshadow::scene::LightFrame;

#[path = "support/raster.rs"]
mod raster_support;
use raster_support::{coverage, ray_triangle};

// ---------------------------------------------------------------------------
// The default scene: a real closed mesh at arbitrary positions.

/// The default scene's occluders and its light view (the frame toward the
/// centre of the bounding box, fitted to every vertex).
fn default_scene_view(size: u32) -> (Occluders, LightView) {
    let scene = softshadow::scene::builtin("default").unwrap();
    let occ = Occluders::from_scene(&scene);
    let (lo, hi) = scene.bounds().unwrap();
    let frame = LightFrame::toward(scene.light().center(), 0.5 * (lo + hi)).unwrap();
    let view = LightView::fit(
        frame,
        occ.triangles().iter().flatten().copied(),
        size,
        size,
        1e-3,
    )
    .unwrap();
    (occ, view)
}

/// The top-left rule is the symbolic perturbation of every centre by
/// `(δ, δ²)`, `δ → 0⁺`, so over a closed mesh every pixel's coverage count
/// is even, edges and vertices through centres included: any inconsistency
/// between two triangles sharing an edge shows as an odd count.
#[test]
fn the_closed_bunny_covers_every_pixel_an_even_number_of_times() {
    let (occ, _) = default_scene_view(8);
    let bunny: Vec<[DVec3; 3]> = occ
        .triangles()
        .iter()
        .zip(occ.objects())
        .filter(|(_, &o)| o == 1)
        .map(|(t, _)| *t)
        .collect();
    assert_eq!(bunny.len(), 3674);
    let (_, view) = default_scene_view(8);
    let frame = *view.frame();
    // Fitted to the bunny alone, at several resolutions (so that many
    // pixel centres fall near vertices and edges).
    for size in [97, 256, 509] {
        let view =
            LightView::fit(frame, bunny.iter().flatten().copied(), size, size, 1e-3).unwrap();
        let counts = coverage(&view, &bunny);
        let odd = counts.iter().filter(|&&n| n % 2 == 1).count();
        assert_eq!(
            odd, 0,
            "{size}²: {odd} pixels covered an odd number of times"
        );
        let covered = counts.iter().filter(|&&n| n >= 2).count();
        assert!(
            covered > view.len() / 4,
            "{size}²: the bunny should fill its window"
        );
    }
    // Random positions rarely put a centre on an edge, so also centre a
    // small view's pixel exactly on the projection of each of many
    // vertices: the fans around them (front, back, silhouette).
    let mut exact = 0;
    let mut vertices: Vec<DVec3> = bunny.iter().flatten().copied().collect();
    vertices.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
    vertices.dedup();
    for &w in vertices.iter().step_by(4) {
        let u = frame.project(w).unwrap().point;
        let s = DVec2::splat(1e-3);
        let mut lo = u - s * 2.5;
        for _ in 0..8 {
            let view = LightView::new(frame, lo, lo + s * 5.0, 5, 5, 1e-3).unwrap();
            let c = view.pixel_center(2, 2);
            if c == u {
                let n = coverage(&view, &bunny)[view.index(2, 2).unwrap()];
                assert_eq!(n % 2, 0, "vertex {w}: covered {n} times");
                exact += 1;
                break;
            }
            lo += u - c;
        }
    }
    assert!(
        exact > 200,
        "only {exact} vertices landed on a pixel centre"
    );
}

#[test]
fn the_default_scene_matches_a_ray_cast() {
    let (occ, view) = default_scene_view(64);
    let maps = rasterize_occluders(&view, &occ);
    let frame = view.frame();
    let [ax, ay, az] = frame.axes();
    let mut seen = [0usize; 2];
    for row in 0..view.height() {
        for col in 0..view.width() {
            let p = view.pixel_center(col, row);
            let dir = ax * p.x + ay * p.y + az;
            let mut best: Option<(f64, usize)> = None;
            for (i, tri) in occ.triangles().iter().enumerate() {
                if let Some((t, u, v)) = ray_triangle(frame.origin(), dir, tri) {
                    if u >= 0.0
                        && v >= 0.0
                        && u + v <= 1.0
                        && t > 0.0
                        && best.is_none_or(|b| t < b.0)
                    {
                        best = Some((t, i));
                    }
                }
            }
            let tri = maps.triangle_at(col, row);
            match best {
                None => assert_eq!(tri, u32::MAX, "({col}, {row})"),
                Some((t, i)) => {
                    assert_ne!(tri, u32::MAX, "({col}, {row}) missed triangle {i}");
                    let z = frame.to_light(frame.origin() + dir * t).z;
                    let depth = maps.depth_at(col, row);
                    assert!(
                        ((depth - z) / z).abs() < 1e-12,
                        "({col}, {row}): {depth} against {z}"
                    );
                    // Different triangles only where they meet (same depth).
                    let object = maps.object_at(col, row);
                    assert_eq!(object, occ.objects()[tri as usize]);
                    if tri as usize != i {
                        assert_eq!(object, occ.objects()[i]);
                    }
                    seen[object as usize] += 1;
                }
            }
        }
    }
    // Floor and bunny both in view.
    assert!(seen[0] > 500 && seen[1] > 20, "{seen:?}");
}
