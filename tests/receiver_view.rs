//! The public receiver-view kernel (`kernel::receiver_view`) and
//! `Light::visibility_among`: closed forms at contact (a corner `10⁻¹²`
//! above the receiver), behind the receiver and beyond the light; a single
//! triangle's image against the independent `polygon_disk_area`; the
//! kernel without a BVH against `reference::exact` on the generators'
//! stiff scenes (every light kind); and the refusals.
#![cfg(all(feature = "reference", feature = "arbitrary"))]

mod support;

use proptest::prelude::*;
use softshadow::arbitrary::scene::visibility_case;
use softshadow::arbitrary::Rng;
use softshadow::glam::{DVec2, DVec3};
use softshadow::kernel::disk::f64::polygon_disk_area;
use softshadow::kernel::receiver_view::{AreaView, Scratch, SegmentView};
use softshadow::reference::exact;
use softshadow::{Bvh, Light, Occluders};
use std::f64::consts::PI;

/// A triangle with its corner `(0, 0, eps)` right above the receiver at the
/// origin and its other corners 10 away at azimuths `alpha` and `beta`, in
/// the plane `z = eps`.
fn sector(eps: f64, alpha: f64, beta: f64) -> [DVec3; 3] {
    let c = DVec3::new(0.0, 0.0, eps);
    let at = |a: f64| c + 10.0 * DVec3::new(a.cos(), a.sin(), 0.0);
    [c, at(alpha), at(beta)]
}

/// Seen from the origin, the triangle `sector(eps, α, β)` with `eps > 0`
/// covers every direction whose azimuth lies between α and β and whose
/// elevation exceeds `atan(eps / 10 cos((β−α)/2))`: on a light plane at
/// height 4 its image is the sector of angle `β − α` about the point above
/// the receiver, reaching `4 · 10 cos(…) / eps` far.
/// So a disk (or sphere) light centred above the receiver loses exactly
/// `(β − α) / 2π` of its area, whatever `eps`, as long as that reach
/// exceeds the light's radius (for a sector angle near π and a corner high
/// enough, `cos(…)` is small and the image is a thin triangle across the
/// light instead: no longer the sector). With `eps < 0` the triangle lies
/// below the receiver and hides nothing.
#[test]
fn contact_closed_form_at_a_corner_1e_12_above_the_receiver() {
    let theta = 0.115 * 2.0 * PI;
    let tri = [sector(1e-12, 0.3, 0.3 + theta)];
    let light = Light::disk(DVec3::new(0.0, 0.0, 4.0), DVec3::Z, 1.0).unwrap();
    let v = light.visibility_among(DVec3::ZERO, &tri).unwrap();
    assert!((v - 0.885).abs() < 1e-12, "V = {v}, closed form 0.885");
    // The exact reference over a BVH agrees.
    let bvh = Bvh::new(Occluders::from_triangles(tri.to_vec()));
    let e = exact::visibility(&bvh, &light, DVec3::ZERO).unwrap();
    assert!((e - 0.885).abs() < 1e-12, "exact {e}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(support::samples(256) as u32))]

    /// The sector closed form for every light that is a disk centred above
    /// the receiver (a disk light, a sphere's facing disk), corners from
    /// `10⁻¹⁵` to `10⁻²` above the receiver, any sector angle up to π; and
    /// `V = 1` for the same triangle below the receiver.
    #[test]
    fn contact_sector_closed_form(
        exponent in -15.0f64..-2.0,
        alpha in 0.0f64..(2.0 * PI),
        theta in 0.01f64..PI,
        radius in 0.05f64..3.0,
    ) {
        let eps = 10f64.powf(exponent);
        // The closed form's premise: the image reaches past the light (by
        // a factor of 2; a sphere's facing disk is no wider than its
        // radius). Fails only for θ within about 10⁻³ of π at the highest
        // corners.
        prop_assume!(40.0 * (theta / 2.0).cos() / eps > 2.0 * radius);
        let above = [sector(eps, alpha, alpha + theta)];
        let below = [sector(-eps, alpha, alpha + theta)];
        let center = DVec3::new(0.0, 0.0, 4.0);
        for light in [
            Light::disk(center, DVec3::Z, radius).unwrap(),
            Light::sphere(center, radius).unwrap(),
        ] {
            let v = light.visibility_among(DVec3::ZERO, &above).unwrap();
            let expected = 1.0 - theta / (2.0 * PI);
            prop_assert!((v - expected).abs() < 1e-12, "{light:?} eps {eps}: {v} vs {expected}");
            prop_assert_eq!(light.visibility_among(DVec3::ZERO, &below).unwrap(), 1.0);
        }
    }

    /// A square rect light centred above the receiver loses a quarter to a
    /// right-angled sector along its axes (the sector of the plane
    /// `x, y ≥ 0` covers one quadrant of the square).
    #[test]
    fn contact_quadrant_of_a_rect(exponent in -15.0f64..-2.0, half in 0.05f64..3.0) {
        let eps = 10f64.powf(exponent);
        let light = Light::rect(DVec3::new(0.0, 0.0, 4.0), DVec3::X * half, DVec3::Y * half).unwrap();
        let v = light.visibility_among(DVec3::ZERO, &[sector(eps, 0.0, 0.5 * PI)]).unwrap();
        prop_assert!((v - 0.75).abs() < 1e-12, "{v}");
    }

    /// One triangle wholly between the receiver and a disk light: its image
    /// is the central projection of its corners onto the light's plane, and
    /// the hidden fraction is that polygon's overlap with the disk — by
    /// `polygon_disk_area`, a kernel the receiver view does not use for a
    /// single triangle's clipping.
    #[test]
    fn one_triangle_is_its_projected_corners(
        seed in any::<u64>(),
        radius in 0.1f64..2.0,
    ) {
        let mut rng = Rng::new(seed);
        let h = 4.0;
        let view = AreaView::disk(DVec3::ZERO, DVec3::new(0.0, 0.0, h), DVec3::Z, radius).unwrap();
        let tri: [DVec3; 3] = std::array::from_fn(|_| {
            let z = rng.uniform(0.5, 3.5);
            // Projecting within the disk's bounding square.
            let s = radius * z / h;
            DVec3::new(rng.uniform(-s, s), rng.uniform(-s, s), z)
        });
        let (center, [e0, e1]) = view.axes();
        let projected: Vec<DVec2> = tri
            .iter()
            .map(|&q| {
                // (X, Y) with x = center + X e₀ + Y e₁, the axes orthogonal.
                let x = q * (h / q.z) - center;
                DVec2::new(x.dot(e0) / e0.length_squared(), x.dot(e1) / e1.length_squared())
            })
            .collect();
        let image = view.image(&tri);
        prop_assert_eq!(image.vertices().len(), 3);
        let area = |v: &[DVec2]| 0.5 * (0..3).map(|k| v[k].perp_dot(v[(k + 1) % 3])).sum::<f64>();
        prop_assert!(image.area() > 0.0, "counter-clockwise");
        prop_assert!((image.area() - area(&projected).abs()).abs() < 1e-12);
        let mut ccw = projected.clone();
        if area(&ccw) < 0.0 {
            ccw.swap(1, 2);
        }
        // In radii: the light is the unit disk.
        let expected = polygon_disk_area(1.0, &ccw) / PI;
        let hidden = view.occluded_fraction(&[tri], &mut Scratch::default());
        prop_assert!((hidden - expected).abs() < 1e-12, "{hidden} vs {expected}");
    }
}

/// A triangle beyond the light, one behind the receiver, and one crossing
/// the light's plane: only the part between the receiver and the light
/// hides anything.
#[test]
fn only_the_slab_between_receiver_and_light_occludes() {
    let light = Light::disk(DVec3::new(0.0, 0.0, 4.0), DVec3::Z, 1.0).unwrap();
    let plate = |z: f64| {
        [
            DVec3::new(-50.0, -50.0, z),
            DVec3::new(50.0, -50.0, z),
            DVec3::new(0.0, 80.0, z),
        ]
    };
    for (z, v) in [(5.0, 1.0), (-1.0, 1.0), (2.0, 0.0), (4.0, 1.0)] {
        assert_eq!(
            light.visibility_among(DVec3::ZERO, &[plate(z)]).unwrap(),
            v,
            "z = {z}"
        );
    }
    // A wall in the plane x = 0.5 from below the receiver to far above the
    // light: the part of it between receiver and light hides the disk's
    // points with x > 0.5 · (4 / z) for z up to 4, i.e. x > 0.5 — the
    // segment of the unit disk beyond x = 0.5: (π/3 − √3/4)/π.
    let wall = [
        DVec3::new(0.5, -100.0, -10.0),
        DVec3::new(0.5, 100.0, -10.0),
        DVec3::new(0.5, 0.0, 100.0),
    ];
    let v = light.visibility_among(DVec3::ZERO, &[wall]).unwrap();
    let segment = (PI / 3.0 - 3f64.sqrt() / 4.0) / PI;
    assert!((v - (1.0 - segment)).abs() < 1e-12, "{v}");
}

/// On the generators' stiff scenes (every light kind; occluders straddling
/// the receiver's side and the light's plane, corners at the receiver,
/// edge-on triangles, coincident copies), the kernel over all the
/// triangles and no BVH gives the exact reference's answer (the BVH only
/// culls), and refuses exactly the receivers it refuses.
#[test]
fn the_kernel_alone_agrees_with_the_exact_reference() {
    let mut rng = Rng::new(0x0bad_5eed);
    let cases = support::samples(400);
    let mut worst = 0.0_f64;
    for case_index in 0..cases {
        let case = visibility_case(&mut rng, 12);
        let bvh = Bvh::new(Occluders::from_triangles(case.triangles.clone()));
        let reference = exact::visibility(&bvh, &case.light, case.receiver);
        let kernel = case.light.visibility_among(case.receiver, &case.triangles);
        match (reference, kernel) {
            (Ok(e), Ok(k)) => {
                assert!((0.0..=1.0).contains(&k), "case {case_index}: {k}");
                worst = worst.max((e - k).abs());
                assert!(
                    (e - k).abs() <= 1e-12,
                    "case {case_index}: exact {e}, kernel {k}\n{case:?}"
                );
            }
            (Err(a), Err(b)) => assert_eq!(a, b),
            (a, b) => panic!("case {case_index}: exact {a:?}, kernel {b:?}"),
        }
    }
    eprintln!("{cases} cases, worst |exact − kernel| = {worst:.2e}");
}

#[test]
fn views_refuse_what_has_no_view() {
    let c = DVec3::new(0.0, 0.0, 4.0);
    assert!(AreaView::disk(DVec3::ZERO, c, DVec3::Z, 1.0).is_some());
    assert!(AreaView::disk(DVec3::NAN, c, DVec3::Z, 1.0).is_none());
    assert!(AreaView::disk(DVec3::ZERO, c, DVec3::ZERO, 1.0).is_none());
    assert!(AreaView::disk(DVec3::ZERO, c, DVec3::Z, 0.0).is_none());
    assert!(AreaView::disk(DVec3::ZERO, c, DVec3::Z, f64::INFINITY).is_none());
    assert!(AreaView::disk(DVec3::new(3.0, 0.0, 4.0), c, DVec3::Z, 1.0).is_none());
    assert!(AreaView::rect(DVec3::ZERO, c, DVec3::X, DVec3::X).is_none());
    assert!(AreaView::rect(DVec3::new(1.0, 1.0, 4.0), c, DVec3::X, DVec3::Y).is_none());
    let (a, b) = (DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0));
    assert!(SegmentView::new(DVec3::new(2.0, 0.0, 0.0), a, b).is_none());
    assert!(SegmentView::new(DVec3::new(4.0, 0.0, 0.0), a, b).is_none());
    assert!(SegmentView::new(DVec3::new(5.0, 0.0, 0.0), a, b).is_some());
    assert!(SegmentView::new(DVec3::new(2.0, 1.0, 0.0), a, a).is_none());
    // Non-finite triangles hide nothing.
    let view = AreaView::disk(DVec3::ZERO, c, DVec3::Z, 1.0).unwrap();
    let bad = [DVec3::new(f64::NAN, 0.0, 2.0), DVec3::X, DVec3::Y];
    assert!(view.image(&bad).is_empty());
    assert_eq!(view.occluded_fraction(&[bad], &mut Scratch::default()), 0.0);
}

/// A receiver on the segment light's line beyond an end: a triangle
/// crossing the line between the ends hides what lies beyond the crossing.
#[test]
fn segment_receiver_on_the_lights_line() {
    let light = Light::segment(DVec3::new(1.0, 0.0, 0.0), DVec3::new(5.0, 0.0, 0.0)).unwrap();
    // A wall through x = 2 crossing the line: the light from x = 2 to 5
    // is hidden from the origin, 3/4 of it.
    let wall = [
        DVec3::new(2.0, -1.0, -1.0),
        DVec3::new(2.0, 1.0, -1.0),
        DVec3::new(2.0, 0.0, 1.0),
    ];
    let v = light.visibility_among(DVec3::ZERO, &[wall]).unwrap();
    assert!((v - 0.25).abs() < 1e-15, "{v}");
    // Seen from the other end: the light from 1 to 2 is hidden from x = 6.
    let v = light
        .visibility_among(DVec3::new(6.0, 0.0, 0.0), &[wall])
        .unwrap();
    assert!((v - 0.75).abs() < 1e-15, "{v}");
}
