//! The light-view rasterizer (`softshadow::render::raster`): properties
//! over random frames and quads (no pixel covered twice, whichever diagonal
//! splits a quad; fragments finite and in range), a near-plane cut shared
//! bit for bit by the two triangles of an edge, and `rasterize_into`
//! matching `rasterize` while reusing its maps.
#![cfg(feature = "render")]

use proptest::prelude::*;
use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3};
use softshadow::render::raster::{
    rasterize, rasterize_into, rasterize_triangle, LightMaps, LightView, RasterError,
};
use softshadow::scene::LightFrame;

#[path = "support/raster.rs"]
mod raster_support;
use raster_support::{coverage, lattice_view, random_frame};

// ---------------------------------------------------------------------------
// Properties.

fn arb_frame() -> impl Strategy<Value = LightFrame> {
    (
        prop::array::uniform3(-3.0..3.0f64),
        prop::array::uniform3(-1.0..1.0f64),
    )
        .prop_filter_map("a direction", |(o, t)| {
            let (o, t) = (DVec3::from(o), DVec3::from(t));
            ((t - o).length() > 0.3).then(|| LightFrame::toward(o, t).unwrap())
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// A quad split along a diagonal, in any frame, any order of its four
    /// triangles' vertices, partly behind `near` or not: no pixel is
    /// covered twice, and the split does not change what the two halves
    /// cover, compared with the other diagonal.
    #[test]
    fn both_diagonals_of_a_quad_cover_the_same_pixels_once(
        frame in arb_frame(),
        corners in prop::array::uniform3(prop::array::uniform3(-1.0..1.0f64)),
        near in 0.05..2.0f64,
        rot in 0usize..3,
    ) {
        // A parallelogram a, b, c, d around light depth 2 (convex, so both
        // diagonals split it).
        let [a, b, c] = corners.map(DVec3::from);
        let (a, b, c) = (a + DVec3::Z * 2.0, b + DVec3::Z * 2.0, c + DVec3::Z * 2.0);
        let d = a + c - b; // parallelogram a, b, c, d
        let w = |p: DVec3| frame.to_world(p);
        let (a, b, c, d) = (w(a), w(b), w(c), w(d));
        let view = LightView::new(frame, DVec2::splat(-1.5), DVec2::splat(1.5), 24, 24, near).unwrap();
        let rotate = |t: [DVec3; 3]| [t[rot % 3], t[(rot + 1) % 3], t[(rot + 2) % 3]];
        let one = coverage(&view, &[rotate([a, b, c]), rotate([a, c, d])]);
        let other = coverage(&view, &[rotate([b, c, d]), rotate([d, a, b])]);
        prop_assert!(one.iter().all(|&n| n <= 1));
        prop_assert!(other.iter().all(|&n| n <= 1));
        // Same outline, so the same pixels (up to a centre within rounding
        // of a clipped outline, which random input does not hit).
        let diff = one.iter().zip(&other).filter(|(x, y)| x != y).count();
        prop_assert!(diff == 0, "{} pixels differ", diff);
    }

    /// Depth is never NaN, always within the near plane and the farthest
    /// vertex, for arbitrary triangles.
    #[test]
    fn fragments_are_finite_and_in_range(
        frame in arb_frame(),
        tri in prop::array::uniform3(prop::array::uniform3(-1e3..1e3f64)),
        near in 1e-6..10.0f64,
    ) {
        let tri = tri.map(DVec3::from);
        let view = LightView::new(frame, DVec2::splat(-3.0), DVec2::splat(3.0), 16, 16, near).unwrap();
        let zmax = tri.iter().map(|&p| frame.to_light(p).z).fold(f64::NEG_INFINITY, f64::max);
        rasterize_triangle(&view, &tri, |f| {
            assert!(f.depth >= near && f.depth <= zmax, "{} outside [{near}, {zmax}]", f.depth);
        });
    }
}

#[test]
fn an_edge_cut_by_the_near_plane_is_cut_at_the_same_point_from_both_sides() {
    // Two triangles sharing the edge P Q, P at depth 4 and Q at depth 1/4
    // (powers of two, so both project exactly onto the pixel-centre column
    // x = c), cut by a near plane in between. The clip point on P Q is
    // rounded; unless both triangles compute it from the same ordered
    // endpoints, their projected edges differ by an ulp and the centres on
    // the column x = c are covered twice or not at all.
    let mut rng = Rng::new(16);
    let mut checked = 0;
    for _ in 0..2000 {
        let near = rng.uniform(0.3, 3.5);
        let view = lattice_view(near);
        let col = 8 + rng.below(16) as u32;
        let c = view.pixel_center(col, 0).x;
        let (yp, yq) = (rng.uniform(-0.9, 0.9), rng.uniform(-0.9, 0.9));
        let p = DVec3::new(c * 4.0, yp * 4.0, 4.0);
        let q = DVec3::new(c * 0.25, yq * 0.25, 0.25);
        let left = DVec3::new((c - 0.5) * 4.0, rng.uniform(-0.9, 0.9) * 4.0, 4.0);
        let right = DVec3::new((c + 0.5) * 4.0, rng.uniform(-0.9, 0.9) * 4.0, 4.0);
        let tris = if rng.chance(0.5) {
            [[p, q, left], [q, p, right]]
        } else {
            [[q, left, p], [right, p, q]]
        };
        let counts = coverage(&view, &tris);
        // The clip point's projection, to rounding.
        let s = (near - 0.25) / (4.0 - 0.25);
        let clip_y = (q.y + s * (p.y - q.y)) / near;
        for row in 0..32 {
            let y = view.pixel_center(col, row).y;
            let (lo, hi) = (clip_y.min(yp), clip_y.max(yp));
            if y > lo + 1e-9 && y < hi - 1e-9 {
                checked += 1;
                // Strictly between the left and right triangles' far sides
                // as well: the union's interior (the sides are 0.5 away).
                assert_eq!(
                    counts[view.index(col, row).unwrap()],
                    1,
                    "near {near}, column {col}, row {row}"
                );
            }
        }
    }
    assert!(checked > 1000, "{checked}");
}

#[test]
fn rasterize_into_reuses_maps_and_matches_rasterize() {
    let mut rng = Rng::new(17);
    let frame = random_frame(&mut rng);
    let tris: Vec<[DVec3; 3]> = (0..40)
        .map(|_| {
            [0; 3].map(|_| {
                frame.to_world(DVec3::new(
                    rng.uniform(-2.0, 2.0),
                    rng.uniform(-2.0, 2.0),
                    rng.uniform(0.2, 3.0),
                ))
            })
        })
        .collect();
    let objects: Vec<u32> = (0..40).collect();
    let mut maps = LightMaps::empty(3, 5);
    for (w, h) in [(17, 9), (40, 33), (1, 1), (17, 9)] {
        let view = LightView::new(frame, DVec2::splat(-1.0), DVec2::splat(1.0), w, h, 0.5).unwrap();
        rasterize_into(&view, &tris, &objects, &mut maps).unwrap();
        assert_eq!(maps, rasterize(&view, &tris, &objects).unwrap());
        assert_eq!(
            rasterize_into(&view, &tris, &objects[1..], &mut maps),
            Err(RasterError::LengthMismatch {
                triangles: 40,
                objects: 39
            })
        );
        assert_eq!(maps, LightMaps::empty(w, h));
    }
}
