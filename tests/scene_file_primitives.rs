//! The primitive meshes and transforms: the geometric invariants of the
//! generated meshes (closedness, outward orientation, volume), merging,
//! transforms, and a transform in a file matching the API.

#![cfg(feature = "scene-file")]

use softshadow::glam::{DMat3, DVec3};
use softshadow::scene::file::scene_from_str;
use softshadow::scene::primitive::{
    cuboid, merge, quad, sphere, sphere_bands, Transform, MAX_SEGMENTS, MIN_SEGMENTS,
};

#[path = "support/scene_file.rs"]
mod scene_file_support;
use scene_file_support::{
    assert_closed, manifest, signed_volume, signed_volume_about, with_meshes,
};

// -------------------------------------------------------------- primitives

/// Higham's `γ(k) = kε/(1 − kε)`, `ε` the unit roundoff.
fn gamma(k: usize) -> f64 {
    let ku = k as f64 * f64::EPSILON / 2.0;
    ku / (1.0 - ku)
}

#[test]
fn spheres_are_closed_outward_with_their_closed_form_volume() {
    let center = DVec3::new(0.25, -3.0, 7.5);
    let r = 1.5;
    for n in [MIN_SEGMENTS, 4, 5, 6, 7, 16, 32, 33, 200] {
        let m = sphere(center, r, n).unwrap();
        let bands = sphere_bands(n);
        assert_eq!(m.positions().len() as u32, n * (bands - 1) + 2);
        assert_eq!(m.triangles().len() as u32, 2 * n * (bands - 1));
        assert_closed(&m);
        // No duplicate vertices (no seam or pole copies).
        for (i, p) in m.positions().iter().enumerate() {
            for q in &m.positions()[i + 1..] {
                assert!(p.distance(*q) > 1e-9 * r, "{n}: duplicate {p}");
            }
            assert!(((p.distance(center) - r) / r).abs() < 1e-15);
        }
        // V(n, m) = (2n/3) r³ sin(2π/n) cos²(π/2m): exact for the
        // inscribed polyhedron. About the centre every tetrahedron is
        // positive, so the rounding of the naive sum of T terms is at most
        // γ(T − 1) V (Higham, §4.2), plus a few roundings per term, per
        // vertex and in the closed form: γ(T + 16) V bounds it all.
        let (nf, mf) = (f64::from(n), f64::from(bands));
        let closed = 2.0 * nf / 3.0
            * r.powi(3)
            * (std::f64::consts::TAU / nf).sin()
            * (std::f64::consts::PI / (2.0 * mf)).cos().powi(2);
        let v = signed_volume_about(&m, center);
        let bound = gamma(m.triangles().len() + 16) * closed;
        assert!((v - closed).abs() <= bound, "{n}: {v} vs {closed}");
        assert!(v > 0.0 && v < 4.0 / 3.0 * std::f64::consts::PI * r.powi(3));
        // Outward, triangle by triangle: the normal points away from the
        // centre.
        for t in 0..m.triangles().len() {
            let [a, b, c] = m.corners(t).unwrap();
            assert!(
                (b - a).cross(c - a).dot((a + b + c) / 3.0 - center) > 0.0,
                "{n}: {t}"
            );
        }
    }
    assert!(sphere(center, r, MAX_SEGMENTS).is_ok());
    assert!(sphere(center, r, MAX_SEGMENTS + 1).is_err());
    assert_eq!(
        sphere(center, r, 8).unwrap().bounds().unwrap().0.y,
        center.y - r
    );
}

#[test]
fn boxes_are_closed_outward_with_their_exact_volume() {
    let (min, max) = (DVec3::new(-1.0, 0.5, 2.0), DVec3::new(3.0, 1.25, 2.5));
    let m = cuboid(min, max).unwrap();
    assert_eq!((m.positions().len(), m.triangles().len()), (8, 12));
    assert_closed(&m);
    // Dyadic coordinates: every product and sum is exact.
    assert_eq!(signed_volume_about(&m, min), 4.0 * 0.75 * 0.5);
    assert_eq!(signed_volume_about(&m, DVec3::ZERO), 4.0 * 0.75 * 0.5);
    let mid = (min + max) / 2.0;
    for t in 0..12 {
        let [a, b, c] = m.corners(t).unwrap();
        let n = (b - a).cross(c - a);
        // Each normal is axis-aligned and points to the face's side.
        assert_eq!(n.abs().max_element(), n.abs().element_sum(), "{t}");
        assert!(n.dot((a + b + c) / 3.0 - mid) > 0.0, "{t}");
    }
    assert_eq!(m.bounds(), Some((min, max)));
}

#[test]
fn quads_face_along_u_cross_v() {
    let (c, u, v) = (
        DVec3::new(1.0, 2.0, 3.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -0.5),
    );
    let m = quad(c, u, v).unwrap();
    assert_eq!(m.triangles().len(), 2);
    let mut area = 0.0;
    for t in 0..2 {
        let [a, b, d] = m.corners(t).unwrap();
        let n = (b - a).cross(d - a);
        assert!(n.normalize().dot(u.cross(v).normalize()) == 1.0);
        area += n.length() / 2.0;
    }
    assert_eq!(area, 4.0 * u.cross(v).length());
    assert_eq!(m.bounds(), Some((c - u + v, c + u - v)));
}

#[test]
fn merge_reindexes_and_keeps_closedness() {
    let a = cuboid(DVec3::ZERO, DVec3::ONE).unwrap();
    let b = sphere(DVec3::splat(3.0), 0.5, 8).unwrap();
    let m = merge(&[a.clone(), b.clone()]).unwrap();
    assert_eq!(
        m.positions().len(),
        a.positions().len() + b.positions().len()
    );
    assert_eq!(m.triangles()[12], b.triangles()[0].map(|i| i + 8));
    assert_closed(&m);
    assert!((signed_volume(&m) - signed_volume(&a) - signed_volume(&b)).abs() < 1e-12);
    assert_eq!(merge(&[]).unwrap().triangles().len(), 0);
}

#[test]
fn transforms_scale_rotate_then_translate() {
    let s = 2.5;
    let t = DVec3::new(1.0, -2.0, 0.5);
    let m = cuboid(DVec3::new(-1.0, 0.0, -0.5), DVec3::new(1.0, 1.0, 0.5)).unwrap();
    for deg in [0.0, 30.0, 90.0, 180.0, -90.0, 270.0, 361.5, -1e-20] {
        let tr = Transform::new(s, deg, t).unwrap();
        let out = tr.apply(&m).unwrap();
        let rot = DMat3::from_rotation_y(f64::to_radians(deg));
        for (p, q) in m.positions().iter().zip(out.positions()) {
            let expect = rot * (*p * s) + t;
            // Rounding: a scale, a 2 × 2 rotation and a translation, each a
            // few ulps of the magnitude involved, and the angle's reduction.
            let bound = 8.0 * f64::EPSILON * (p.length() * s + t.length());
            assert!(q.distance(expect) <= bound, "{deg}: {q} vs {expect}");
        }
        assert_eq!(out.triangles(), m.triangles());
        assert_closed(&out);
        let v = signed_volume(&out);
        assert!((v - 2.0 * s.powi(3)).abs() < 1e-13, "{deg}: {v}");
    }
    // Right angles are exact: +x turns toward −z, as glam.
    let tr = Transform::new(1.0, 90.0, DVec3::ZERO).unwrap();
    assert_eq!(tr.apply_point(DVec3::X), -DVec3::Z);
    assert_eq!(tr.apply_point(DVec3::Z), DVec3::X);
    assert_eq!(Transform::default(), Transform::IDENTITY);
    assert_eq!(Transform::IDENTITY.apply(&m).unwrap(), m);
}

#[test]
fn transform_in_a_file_matches_the_api() {
    let scene = scene_from_str(
        "s.json",
        &with_meshes(
            r#"{"primitive": {"type": "box", "min": [0,0,0], "max": [1,2,3]},
                "transform": {"scale": 2, "rotate_y_deg": 90, "translate": [1,0,0]}}"#,
        ),
        manifest(),
    )
    .unwrap();
    let expect = Transform::new(2.0, 90.0, DVec3::X)
        .unwrap()
        .apply(&cuboid(DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0)).unwrap())
        .unwrap();
    assert_eq!(scene.meshes()[0], expect);
    assert_eq!(
        scene.meshes()[0].bounds(),
        Some((DVec3::new(1.0, 0.0, -2.0), DVec3::new(7.0, 4.0, 0.0)))
    );
}
