//! The light-view rasterizer (`softshadow::render::raster`): ids, ties and
//! the corner cases — empty scenes, 1 × 1 views, windows off the geometry,
//! ties, both orientations, non-finite and huge input, the validation of
//! `LightView::new` and `LightView::fit`.
#![cfg(feature = "render")]

use softshadow::arbitrary::Rng;
use softshadow::bvh::Occluders;
use softshadow::glam::{DVec2, DVec3};
use softshadow::render::raster::{
    rasterize, rasterize_occluders, LightMaps, LightView, RasterError,
};

#[path = "support/raster.rs"]
mod raster_support;
use raster_support::{axis_frame, lattice_view, random_frame};

// ---------------------------------------------------------------------------
// Ids, ties, corner cases.

#[test]
fn ties_go_to_the_lower_index_and_both_orientations_render() {
    let view = lattice_view(0.5);
    let t = [
        DVec3::new(-4.0, -4.0, 4.0),
        DVec3::new(4.0, -4.0, 4.0),
        DVec3::new(0.0, 4.0, 4.0),
    ];
    let r = [t[0], t[2], t[1]];
    let a = rasterize(&view, &[t, r], &[5, 6]).unwrap();
    let b = rasterize(&view, &[r, t], &[6, 5]).unwrap();
    assert_eq!(a.depth(), b.depth());
    let covered: Vec<usize> = (0..view.len())
        .filter(|&k| a.triangles()[k] != u32::MAX)
        .collect();
    assert!(covered.len() > 100);
    for &k in &covered {
        assert_eq!((a.triangles()[k], a.objects()[k]), (0, 5));
        assert_eq!((b.triangles()[k], b.objects()[k]), (0, 6));
    }
    // A nearer triangle later in the list wins.
    let nearer = t.map(|p| p * 0.5);
    let c = rasterize(&view, &[t, nearer], &[1, 2]).unwrap();
    for &k in &covered {
        assert_eq!(c.triangles()[k], 1);
        assert_eq!(c.depth()[k], 2.0);
    }
}

#[test]
fn several_objects_keep_their_ids() {
    let view = lattice_view(0.5);
    // Three stacked squares (two triangles each) of decreasing size, the
    // smallest nearest; occluders in mesh order.
    let square = |h: f64, z: f64| {
        let c = [(-h, -h), (h, -h), (h, h), (-h, h)].map(|(x, y)| DVec3::new(x * z, y * z, z));
        vec![[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
    };
    let mut tris = Vec::new();
    let mut objects = Vec::new();
    for (o, (h, z)) in [(0.9, 8.0), (0.5, 4.0), (0.25, 2.0)]
        .into_iter()
        .enumerate()
    {
        for t in square(h, z) {
            tris.push(t);
            objects.push(o as u32 * 10);
        }
    }
    let maps = rasterize(&view, &tris, &objects).unwrap();
    for row in 0..32 {
        for col in 0..32 {
            let p = view.pixel_center(col, row).abs().max_element();
            let want = if p < 0.25 {
                (20, 2.0)
            } else if p < 0.5 {
                (10, 4.0)
            } else if p < 0.9 {
                (0, 8.0)
            } else {
                (u32::MAX, f64::INFINITY)
            };
            assert_eq!(
                (maps.object_at(col, row), maps.depth_at(col, row)),
                want,
                "({col}, {row})"
            );
            let t = maps.triangle_at(col, row);
            if t != u32::MAX {
                assert_eq!(objects[t as usize], want.0);
            }
        }
    }
    // The same through `Occluders`.
    let occ = Occluders::from_triangles(tris.clone());
    let m2 = rasterize_occluders(&view, &occ);
    assert_eq!(m2.depth(), maps.depth());
    assert!(m2.objects().iter().all(|&o| o == 0 || o == u32::MAX));
}

#[test]
fn empty_scenes_tiny_views_and_windows_off_the_geometry() {
    let frame = axis_frame();
    let view = lattice_view(0.5);
    let empty = rasterize(&view, &[], &[]).unwrap();
    assert_eq!(empty, LightMaps::empty(32, 32));
    assert!(empty.depth().iter().all(|&d| d == f64::INFINITY));
    assert_eq!(empty.depth_at(99, 0), f64::INFINITY);

    let big = [
        DVec3::new(-9.0, -9.0, 2.0),
        DVec3::new(9.0, -9.0, 2.0),
        DVec3::new(0.0, 9.0, 2.0),
    ];
    let one = LightView::new(frame, DVec2::splat(-0.1), DVec2::splat(0.1), 1, 1, 0.5).unwrap();
    assert_eq!(one.pixel_center(0, 0), DVec2::ZERO);
    let m = rasterize(&one, &[big], &[3]).unwrap();
    assert_eq!(
        (m.depth_at(0, 0), m.object_at(0, 0), m.triangle_at(0, 0)),
        (2.0, 3, 0)
    );

    let off = LightView::new(
        frame,
        DVec2::new(40.0, 40.0),
        DVec2::new(41.0, 42.0),
        16,
        16,
        0.5,
    )
    .unwrap();
    let m = rasterize(&off, &[big], &[3]).unwrap();
    assert!(m.triangles().iter().all(|&t| t == u32::MAX));
    // Entirely nearer than `near`: dropped.
    let close = big.map(|p| p * 0.1);
    assert!(rasterize(&view, &[close], &[0])
        .unwrap()
        .depth()
        .iter()
        .all(|d| d.is_infinite()));
}

#[test]
fn non_finite_and_huge_input_neither_panics_nor_lies() {
    let view = lattice_view(0.5);
    let good = [
        DVec3::new(-9.0, -9.0, 2.0),
        DVec3::new(9.0, -9.0, 2.0),
        DVec3::new(0.0, 9.0, 2.0),
    ];
    let bad = [
        [
            DVec3::new(f64::NAN, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ],
        [
            DVec3::new(f64::INFINITY, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ],
        [
            DVec3::new(1e300, -1e300, 1.0),
            DVec3::new(1.0, 0.0, 1e300),
            DVec3::new(-1e300, 1.0, 1.0),
        ],
        [
            DVec3::new(-1e200, -1e200, 1.0),
            DVec3::new(1e200, -1e200, 1.0),
            DVec3::new(0.0, 1e200, 1.0),
        ],
        [
            DVec3::new(0.0, 0.0, 1e-300),
            DVec3::new(1e-300, 0.0, 1.0),
            DVec3::new(0.0, 1e-300, 1.0),
        ],
        [DVec3::splat(1.0); 3],
    ];
    let mut tris = bad.to_vec();
    tris.push(good);
    let objects: Vec<u32> = (0..tris.len() as u32).collect();
    let maps = rasterize(&view, &tris, &objects).unwrap();
    let alone = rasterize(&view, &[good], &[6]).unwrap();
    // The out-of-domain triangles are skipped; the good one is unaffected.
    assert_eq!(maps.depth(), alone.depth());
    assert!(maps.depth().iter().all(|d| !d.is_nan()));
    // Large but in the domain: a triangle 1e40 across, seen at depth 1e30,
    // covers the whole view at that depth.
    let far = [
        DVec3::new(-1e40, -1e40, 1e30),
        DVec3::new(1e40, -1e40, 1e30),
        DVec3::new(0.0, 1e40, 1e30),
    ];
    let m = rasterize(&view, &[far], &[0]).unwrap();
    assert!(m.depth().iter().all(|&d| (d / 1e30 - 1.0).abs() < 1e-12));
}

#[test]
fn light_views_validate_their_input() {
    let f = axis_frame();
    let (lo, hi) = (DVec2::splat(-1.0), DVec2::splat(1.0));
    assert!(LightView::new(f, lo, hi, 1, 1, 1e-9).is_ok());
    assert!(LightView::new(f, lo, hi, 16384, 1, 1.0).is_ok());
    let e = |r: Result<LightView, RasterError>| r.unwrap_err();
    assert_eq!(
        e(LightView::new(f, hi, lo, 4, 4, 1.0)),
        RasterError::EmptyWindow
    );
    assert_eq!(
        e(LightView::new(f, lo, DVec2::new(1.0, -1.0), 4, 4, 1.0)),
        RasterError::EmptyWindow
    );
    assert_eq!(
        e(LightView::new(f, lo, DVec2::new(f64::NAN, 1.0), 4, 4, 1.0)),
        RasterError::NonFiniteWindow
    );
    assert_eq!(
        e(LightView::new(f, lo, DVec2::new(1e200, 1.0), 4, 4, 1.0)),
        RasterError::NonFiniteWindow
    );
    assert_eq!(
        e(LightView::new(f, lo, hi, 0, 4, 1.0)),
        RasterError::Resolution {
            width: 0,
            height: 4
        }
    );
    assert_eq!(
        e(LightView::new(f, lo, hi, 4, 16385, 1.0)),
        RasterError::Resolution {
            width: 4,
            height: 16385
        }
    );
    assert_eq!(
        e(LightView::new(
            f,
            DVec2::ZERO,
            DVec2::splat(2e-140),
            4,
            4,
            1.0
        )),
        RasterError::EmptyWindow
    );
    for near in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(e(LightView::new(f, lo, hi, 4, 4, near)), RasterError::Near);
    }
    let t = [DVec3::Z; 3];
    assert_eq!(
        rasterize(
            &LightView::new(f, lo, hi, 4, 4, 1.0).unwrap(),
            &[t, t],
            &[0]
        )
        .unwrap_err(),
        RasterError::LengthMismatch {
            triangles: 2,
            objects: 1
        }
    );
    // Pixel geometry.
    let v = LightView::new(f, DVec2::new(-1.0, 0.0), DVec2::new(1.0, 3.0), 4, 6, 0.1).unwrap();
    assert_eq!(v.texel_size(), DVec2::new(0.5, 0.5));
    assert_eq!(v.pixel_center(0, 0), DVec2::new(-0.75, 0.25));
    assert_eq!(v.pixel_center(3, 5), DVec2::new(0.75, 2.75));
    assert_eq!(v.to_pixel(v.pixel_center(2, 1)), DVec2::new(2.5, 1.5));
    assert_eq!(v.pixel_of(DVec2::new(0.0, 0.0)), Some((2, 0)));
    assert_eq!(v.pixel_of(DVec2::new(1.0, 0.0)), None);
    assert_eq!(v.index(3, 5), Some(23));
    assert_eq!(v.index(4, 0), None);
}

#[test]
fn fit_contains_the_points_with_a_pixel_to_spare() {
    let mut rng = Rng::new(15);
    for _ in 0..200 {
        let frame = random_frame(&mut rng);
        let near = 0.3;
        let points: Vec<DVec3> = (0..1 + rng.below(50))
            .map(|_| {
                DVec3::new(
                    rng.uniform(-2.0, 2.0),
                    rng.uniform(-2.0, 2.0),
                    rng.uniform(-2.0, 2.0),
                )
            })
            .collect();
        let (w, h) = (1 + rng.below(300) as u32, 1 + rng.below(300) as u32);
        let in_front: Vec<DVec2> = points
            .iter()
            .filter_map(|&p| {
                let q = frame.to_light(p);
                (q.z >= near).then(|| DVec2::new(q.x / q.z, q.y / q.z))
            })
            .collect();
        match LightView::fit(frame, points.iter().copied(), w, h, near) {
            Err(err) => {
                assert!(in_front.is_empty());
                assert_eq!(err, RasterError::NothingInFront);
            }
            Ok(view) => {
                assert!(!in_front.is_empty());
                let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
                for &u in &in_front {
                    let q = view.to_pixel(u);
                    lo = lo.min(q);
                    hi = hi.max(q);
                }
                // One pixel of margin each side for sizes ≥ 3, n/(n + 2) of
                // one below (the extent floor only widens).
                let size = DVec2::new(w as f64, h as f64);
                let margin = size.map(|n| if n >= 3.0 { 1.0 } else { n / (n + 2.0) });
                assert!(lo.cmpge(margin - 1e-9).all(), "{lo} {size}");
                assert!(hi.cmple(size - margin + 1e-9).all(), "{hi} {size}");
                if w >= 3 && in_front.len() > 1 && (hi.x - lo.x) > 1.0 {
                    assert!((lo.x - 1.0).abs() < 1e-9 && (hi.x - (size.x - 1.0)).abs() < 1e-9);
                }
            }
        }
    }
    let f = axis_frame();
    assert_eq!(
        LightView::fit(f, [DVec3::new(0.0, 0.0, -1.0)], 8, 8, 0.5).unwrap_err(),
        RasterError::NothingInFront
    );
    // One point: a tiny window around it.
    let v = LightView::fit(f, [DVec3::new(1.0, 2.0, 4.0)], 8, 8, 0.5).unwrap();
    let c = (v.lo() + v.hi()) * 0.5;
    assert!((c - DVec2::new(0.25, 0.5)).length() < 1e-15 && v.hi().x > v.lo().x);
}
