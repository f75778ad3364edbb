//! No public path yields a light that makes a reference or a method return
//! NaN or a silent wrong answer: every light kind refuses non-finite and
//! non-positive fields with a typed error (the kinds' fields are private,
//! see the `compile_fail` example on `Light`), and the valid lights nearest
//! those edges — tiny and huge radii, far centres, thin rects, short
//! segments — give every reference and every method of the registry a
//! value in `[0, 1]` or an error, never NaN.
#![cfg(feature = "render")]

use softshadow::glam::DVec3;
use softshadow::method::{self, registry::REGISTRY};
use softshadow::reference::{exact, monte_carlo};
use softshadow::scene::{primitive, LightError};
use softshadow::{Bvh, Frame, Light, Receiver, Scene, Stages};

const BAD: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

#[test]
fn every_kind_refuses_non_finite_and_non_positive_fields() {
    let c = DVec3::new(0.0, 4.0, 0.0);
    for bad in BAD {
        let b3 = [
            DVec3::new(bad, 0.0, 0.0),
            DVec3::new(0.0, bad, 1.0),
            DVec3::splat(bad),
        ];
        assert!(matches!(
            Light::sphere(c, bad),
            Err(LightError::NonFinite { .. })
        ));
        assert!(matches!(
            Light::disk(c, DVec3::Y, bad),
            Err(LightError::NonFinite { .. })
        ));
        for v in b3 {
            assert!(matches!(
                Light::sphere(v, 1.0),
                Err(LightError::NonFinite { .. })
            ));
            assert!(matches!(
                Light::disk(v, DVec3::Y, 1.0),
                Err(LightError::NonFinite { .. })
            ));
            assert!(matches!(
                Light::disk(c, v, 1.0),
                Err(LightError::NonFinite { .. })
            ));
            assert!(matches!(
                Light::rect(v, DVec3::X, DVec3::Z),
                Err(LightError::NonFinite { .. })
            ));
            assert!(matches!(
                Light::rect(c, v, DVec3::Z),
                Err(LightError::NonFinite { .. })
            ));
            assert!(matches!(
                Light::rect(c, DVec3::X, v),
                Err(LightError::NonFinite { .. })
            ));
            assert!(matches!(
                Light::segment(v, c),
                Err(LightError::NonFinite { .. })
            ));
            assert!(matches!(
                Light::segment(c, v),
                Err(LightError::NonFinite { .. })
            ));
            assert!(matches!(Light::point(v), Err(LightError::NonFinite { .. })));
        }
    }
    for r in [0.0, -0.0, -0.5, -f64::MIN_POSITIVE] {
        assert!(
            matches!(
                Light::sphere(c, r),
                Err(LightError::NonPositiveRadius { .. })
            ),
            "{r}"
        );
        assert!(
            matches!(
                Light::disk(c, DVec3::Y, r),
                Err(LightError::NonPositiveRadius { .. })
            ),
            "{r}"
        );
    }
    assert_eq!(
        Light::disk(c, DVec3::ZERO, 1.0),
        Err(LightError::ZeroNormal)
    );
    assert_eq!(
        Light::rect(c, DVec3::ZERO, DVec3::Z),
        Err(LightError::DegenerateRect)
    );
    assert_eq!(
        Light::rect(c, DVec3::X, DVec3::X * -3.0),
        Err(LightError::DegenerateRect)
    );
    assert_eq!(Light::segment(c, c), Err(LightError::ZeroLengthSegment));
}

/// The valid lights nearest the refused ones.
fn edge_lights() -> Vec<Light> {
    let c = DVec3::new(0.0, 4.0, 0.0);
    let far = DVec3::new(0.0, 1e150, 0.0);
    let mut out = Vec::new();
    for r in [1e-300, 1e-12, 1e12, 1e200] {
        out.extend(Light::sphere(c, r));
        out.extend(Light::disk(c, DVec3::new(0.3, -1.0, 0.1), r));
        out.extend(Light::rect(c, DVec3::X * r, DVec3::Z * r));
        out.extend(Light::segment(c - DVec3::X * r, c + DVec3::X * r));
    }
    out.extend(Light::sphere(far, 1.0));
    out.extend(Light::disk(far, -DVec3::Y, 1e140));
    out.extend(Light::rect(c, DVec3::X, DVec3::Z * 1e-200));
    out.extend(Light::rect(c, DVec3::X, DVec3::new(1.0, 0.0, 1e-15)));
    out.extend(Light::segment(far, far + DVec3::X));
    out.extend(Light::point(far));
    out.extend(Light::point(c));
    out
}

/// The radius of a sphere or disk light centred at `(0, 4, 0)` with radius
/// at most `1e-12`.
fn tiny_radius(light: &Light) -> Option<f64> {
    let (center, radius) = match light {
        Light::Sphere(s) => (s.center(), s.radius()),
        Light::Disk(d) => (d.center(), d.radius()),
        _ => return None,
    };
    (center == DVec3::new(0.0, 4.0, 0.0) && radius <= 1e-12).then_some(radius)
}

#[test]
fn lights_at_the_edge_give_every_reference_and_method_a_value_or_an_error() {
    let plate = primitive::quad(DVec3::new(0.3, 2.0, 0.1), DVec3::X, DVec3::Z).unwrap();
    let floor = primitive::quad(DVec3::ZERO, DVec3::X * 5.0, DVec3::Z * 5.0).unwrap();
    let receivers: Vec<Receiver> = [(0.0, 0.0), (0.9, 0.4), (1.3, -0.2), (3.0, 3.0)]
        .iter()
        .map(|&(x, z)| Receiver {
            position: DVec3::new(x, 1e-9, z),
            normal: Some(DVec3::Y),
            object: Some(0),
        })
        .collect();
    let lights = edge_lights();
    // A rect whose area underflows is refused (`DegenerateRect`); every
    // kind still has lights at both ends of the range.
    for kind in softshadow::scene::LightKind::ALL {
        assert!(
            lights.iter().filter(|l| l.kind() == *kind).count() >= 2,
            "{kind}"
        );
    }
    for light in lights {
        let scene = Scene::new(light)
            .with_mesh("floor", floor.clone())
            .with_mesh("plate", plate.clone());
        let bvh = Bvh::from_scene(&scene);
        let triangles = bvh.occluders().triangles().to_vec();
        for r in &receivers {
            let p = r.position;
            let in_range = |v: f64| (0.0..=1.0).contains(&v);
            if let Ok(v) = exact::visibility(&bvh, &light, p) {
                assert!(in_range(v), "exact {v} for {light:?} at {p}");
                assert_eq!(light.visibility_among(p, &triangles), Ok(v));
                // A light of radius 1e-12 or less at distance 4 is a point
                // light for these receivers (none within 1e-9 of the hard
                // shadow's edge): V is 0 or 1 as the ray to the centre says.
                if let Some(r) = tiny_radius(&light) {
                    assert!(r <= 1e-12);
                    let lit = bvh.segment_unoccluded(p, DVec3::new(0.0, 4.0, 0.0));
                    assert_eq!(v, if lit { 1.0 } else { 0.0 }, "{light:?} at {p}");
                }
            }
            let options = monte_carlo::Options::new(64);
            if let Ok(m) = monte_carlo::visibility(&bvh, &light, p, &options) {
                assert!(
                    in_range(m.visibility) && m.stderr.is_finite(),
                    "{m:?} for {light:?}"
                );
            }
        }
        let frame = Frame::from_receivers(receivers.clone());
        let stages = Stages::new(&scene);
        for entry in REGISTRY.iter().filter(|e| e.is_built()) {
            if !entry.handles(light.kind()) {
                continue;
            }
            let setting = entry.compare.first().copied().unwrap_or(entry.name);
            let setting = if setting == "mc" { "mc:16" } else { setting };
            let m = method::parse(setting).unwrap();
            if let Ok(run) = method::run(m.as_ref(), &stages, &frame) {
                for &v in &run.output.visibility {
                    assert!((0.0..=1.0).contains(&v), "{setting}: {v} for {light:?}");
                }
            }
        }
    }
}
