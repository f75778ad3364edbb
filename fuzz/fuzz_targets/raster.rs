//! The light-view rasterizer on fuzzed triangles and views: no panic; a
//! covered texel holds a finite depth at or past `near`, a valid triangle
//! index, and, inside the documented depth domain (corners within a
//! factor `10¹⁵` of each other in distance) where the plane is well
//! conditioned (the documented conditioning below `10⁶`), that triangle's depth along the texel
//! centre's ray (its plane, to a relative `1e-9`) — the rasterizer reports
//! the surface it says it saw; an uncovered texel holds `+∞`.
//!
//! The first 8 bytes seed `arbitrary::scene::visibility_case` for the
//! triangles; the following words, read as raw `f64` bit patterns, replace
//! vertex coordinates (finite ones are kept) and then set the window; the
//! resolution is small (up to 24²) so that every texel is checked.
#![no_main]

use glam::{DVec2, DVec3};
use libfuzzer_sys::fuzz_target;
use softshadow::arbitrary::scene::visibility_case;
use softshadow::arbitrary::Rng;
use softshadow::bvh::Occluders;
use softshadow::render::raster::{rasterize_occluders, LightView};
use softshadow::scene::LightFrame;

fn word(data: &[u8], i: usize) -> Option<u64> {
    let bytes = data.get(8 * i..8 * i + 8)?;
    Some(u64::from_le_bytes(bytes.try_into().ok()?))
}

fuzz_target!(|data: &[u8]| {
    let seed = word(data, 0).unwrap_or(0);
    let mut rng = Rng::new(seed);
    let mut case = visibility_case(&mut rng, 6);
    let mut k = 1;
    for t in case.triangles.iter_mut() {
        for v in t.iter_mut() {
            for c in 0..3 {
                if let Some(w) = word(data, k) {
                    let x = f64::from_bits(w);
                    if x.is_finite() {
                        v[c] = x;
                    }
                }
                k += 1;
            }
        }
    }
    let centre = case.light.center();
    let Ok(frame) = LightFrame::toward(centre, case.receiver) else {
        return;
    };
    let side = 1 + (seed % 24) as u32;
    let span = 0.5 + (seed >> 8) as f64 % 4.0;
    let near = 1e-3 + ((seed >> 16) % 100) as f64 * 1e-3;
    let Ok(view) = LightView::new(
        frame,
        DVec2::splat(-span),
        DVec2::splat(span),
        side,
        side,
        near,
    ) else {
        return;
    };
    let occluders = Occluders::from_triangles(case.triangles.clone());
    let maps = rasterize_occluders(&view, &occluders);
    for row in 0..side {
        for col in 0..side {
            let depth = maps.depth_at(col, row);
            if !maps.is_covered(col, row) {
                assert_eq!(depth, f64::INFINITY);
                continue;
            }
            assert!(
                depth.is_finite() && depth >= near * (1.0 - 1e-12),
                "{depth} < {near}"
            );
            let t = occluders.triangles()[maps.triangle_at(col, row) as usize];
            let q = t.map(|p| frame.to_light(p));
            // The plane from the corner nearest the light (from a far
            // corner, the differences lose the near geometry), the normal's
            // components by another compensated algorithm than the
            // rasterizer's; the planes are also checked against
            // double-double ones in `tests/raster_depth.rs`.
            let i = if q[0].length() <= q[1].length() && q[0].length() <= q[2].length() {
                0
            } else if q[1].length() <= q[2].length() {
                1
            } else {
                2
            };
            let (a, b, c) = (q[i], q[(i + 1) % 3], q[(i + 2) % 3]);
            let (e1, e2) = (b - a, c - a);
            // Each component `x·y − z·w` by Kahan's fused algorithm (far
            // corners make the two products cancel).
            let det2 = |x: f64, y: f64, z: f64, w: f64| {
                let zw = z * w;
                let err = (-z).mul_add(w, zw);
                x.mul_add(y, -zw) + err
            };
            let n = DVec3::new(
                det2(e1.y, e2.z, e1.z, e2.y),
                det2(e1.z, e2.x, e1.x, e2.z),
                det2(e1.x, e2.y, e1.y, e2.x),
            );
            let u = view.pixel_center(col, row);
            let ray = DVec3::new(u.x, u.y, 1.0);
            let z = n.dot(a) / n.dot(ray);
            // The documented conditioning: the ray's (edge-on triangles
            // have no well-defined depth) times the offset's (every corner
            // far from the light compared with the plane's distance to it).
            let kappa = n.length() * ray.length() / n.dot(ray).abs()
                * (n.length() * a.length() / n.dot(a).abs()).max(1.0);
            // The documented depth domain: corners' distances from the
            // light within a factor 10¹⁵ of each other.
            let far = q.iter().map(|p| p.length()).fold(0.0, f64::max);
            let close = q.iter().map(|p| p.length()).fold(f64::INFINITY, f64::min);
            let in_domain = far <= 1e15 * close.max(near);
            if z.is_finite() && kappa < 1e6 && in_domain {
                assert!(
                    (z - depth).abs() <= 1e-9 * depth.abs().max(z.abs()).max(1.0),
                    "texel ({col}, {row}): depth {depth}, the triangle's plane {z}; light-frame corners {a} {b} {c}; centre ray {ray}; near {near}"
                );
            }
        }
    }
});
