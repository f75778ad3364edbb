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
    // Every kind has lights at both ends of the range (rects whose area
    // overflows or underflows among them).
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
        for entry in REGISTRY {
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

/// `2^k`, exactly.
fn pow2(k: i32) -> f64 {
    2f64.powi(k)
}

#[test]
fn every_finite_non_zero_normal_is_accepted_and_normalised_alike() {
    let c = DVec3::new(0.3, 4.0, -0.2);
    for n in [
        DVec3::new(0.3, -1.0, 0.1),
        DVec3::new(1e-3, 1.0, 0.0),
        DVec3::new(-0.7, -0.2, 0.6),
    ] {
        let unit = Light::disk(c, n, 0.5).unwrap();
        // A power of two changes only exponents: the very same light.
        for k in [-1000, -600, -300, 300, 600, 1000] {
            assert_eq!(Light::disk(c, n * pow2(k), 0.5), Ok(unit), "{n} · 2^{k}");
        }
        // Lengths 1e-200 and 1e200 (squared, they underflow and overflow):
        // the direction to rounding.
        for scale in [1e-200, 1e200, 1e-300, 1e300] {
            let light = Light::disk(c, n * scale, 0.5).unwrap();
            let got = light.plane_normal().unwrap();
            let want = unit.plane_normal().unwrap();
            assert!(
                (got - want).length() <= 4.0 * f64::EPSILON,
                "{scale}: {got} {want}"
            );
        }
    }
    // The receiver view of a disk and a points file's receiver normals
    // take them too.
    let p = DVec3::new(0.1, 0.0, 0.2);
    let plate = [[
        DVec3::new(-1.0, 2.0, -1.0),
        DVec3::new(1.0, 2.0, -0.5),
        DVec3::new(0.2, 2.0, 0.1),
    ]];
    let n = DVec3::new(0.3, -1.0, 0.1);
    let hidden = |normal: DVec3| {
        softshadow::kernel::receiver_view::AreaView::disk(p, c, normal, 0.5)
            .map(|v| v.occluded_fraction(&plate, &mut Default::default()))
    };
    assert!(hidden(n).is_some_and(|f| f > 0.0 && f < 1.0));
    for k in [-900, 900] {
        assert_eq!(hidden(n * pow2(k)), hidden(n), "2^{k}");
    }
    #[cfg(feature = "scene-file")]
    {
        let text = r#"{"points": [{"p": [0, 0, 0], "normal": [0, 1e-200, 0]}, {"p": [1, 0, 0], "normal": [0, 0, -1e-320]}]}"#;
        let points = softshadow::scene::file::points_from_str("p.json", text, 1).unwrap();
        assert_eq!(points[0].normal, Some(DVec3::Y));
        // (A subnormal's few bits, normalised: within an ulp.)
        let n1 = points[1].normal.unwrap();
        assert!((n1 + DVec3::Z).length() <= f64::EPSILON, "{n1}");
    }
    // The extremes of f64.
    for tiny_or_huge in [f64::from_bits(1), f64::MIN_POSITIVE, f64::MAX] {
        let light = Light::disk(c, DVec3::new(0.0, -tiny_or_huge, 0.0), 0.5).unwrap();
        assert_eq!(light.plane_normal(), Some(-DVec3::Y), "{tiny_or_huge}");
    }
}

#[test]
fn rects_whose_area_overflows_or_underflows_are_rects() {
    let c = DVec3::new(0.0, 1.0, 0.0);
    let (u, v) = (DVec3::new(0.9, 0.0, 0.1), DVec3::new(-0.2, 0.0, 1.1));
    let base = Light::rect(c, u, v).unwrap();
    // Half-axes 2^±600 times these: areas 2^±1200 times, beyond f64.
    for k in [-600, 600] {
        let light = Light::rect(c, u * pow2(k), v * pow2(k)).unwrap();
        assert_eq!(light.plane_normal(), base.plane_normal());
        assert_eq!(
            light.equivalent_radius(),
            base.equivalent_radius() * pow2(k)
        );
        assert_eq!(
            light.bounding_radius(),
            base.bounding_radius() * pow2(k),
            "{k}"
        );
    }
    // Parallel or zero half-axes are still refused, however long.
    assert_eq!(
        Light::rect(c, u * 1e200, u * -3e200),
        Err(LightError::DegenerateRect)
    );
    assert_eq!(
        Light::rect(c, DVec3::ZERO, v * 1e-200),
        Err(LightError::DegenerateRect)
    );
    // A half-plane hides half the light from a receiver under its edge,
    // whether the light's half-axes are 1e200 (area 4e400; the light as far
    // away, so that an occluder of ordinary size hides half of it) or
    // 1e-200 (area 4e-400): V = 1/2, from the exact reference and the
    // receiver view alike. (Monte Carlo's rays to points 1e200 away, or
    // 1e-200 apart, are outside the domain of its segment test,
    // `kernel::segment`, magnitudes in [1e-90, 1e90].)
    let p = DVec3::ZERO;
    for (axis, height, edge) in [(1e200, 1e200, 2.0), (1e300, 1e300, 2.0), (1e-200, 1.0, 1.0)] {
        let light = Light::rect(DVec3::Y * height, DVec3::X * axis, DVec3::Z * axis).unwrap();
        // Its image from p on the light's plane (y = height) is the
        // triangle 2·height times as large: it covers the whole half x < 0
        // of the light.
        let half_plane = [
            DVec3::new(0.0, 0.5, -edge),
            DVec3::new(0.0, 0.5, edge),
            DVec3::new(-edge, 0.5, 0.0),
        ];
        let mesh = softshadow::Mesh::new(half_plane.to_vec(), vec![[0, 1, 2]]).unwrap();
        let scene = Scene::new(light).with_mesh("half plane", mesh);
        let bvh = Bvh::from_scene(&scene);
        let v = exact::visibility(&bvh, &light, p).unwrap();
        assert!((v - 0.5).abs() < 1e-12, "{axis}: exact {v}");
        assert_eq!(light.visibility_among(p, &[half_plane]), Ok(v));
    }
}

#[test]
fn every_invalid_field_is_reported() {
    let nan = DVec3::new(f64::NAN, 0.0, 0.0);
    let inf = DVec3::new(0.0, f64::INFINITY, 0.0);
    let e = Light::disk(nan, DVec3::ZERO, -1.0).unwrap_err();
    assert_eq!(
        e.faults(),
        [
            LightError::NonFinite { field: "center" },
            LightError::ZeroNormal,
            LightError::NonPositiveRadius { radius: -1.0 }
        ]
    );
    let message = e.to_string();
    for part in ["`center`", "normal", "got -1"] {
        assert!(
            message.contains(part) && !message.contains('\n'),
            "{message}"
        );
    }
    assert_eq!(
        Light::disk(DVec3::ZERO, inf, f64::NAN)
            .unwrap_err()
            .faults(),
        [
            LightError::NonFinite { field: "normal" },
            LightError::NonFinite { field: "radius" }
        ]
    );
    assert_eq!(
        Light::sphere(inf, 0.0).unwrap_err().faults(),
        [
            LightError::NonFinite { field: "center" },
            LightError::NonPositiveRadius { radius: 0.0 }
        ]
    );
    assert_eq!(
        Light::rect(nan, DVec3::X, DVec3::X).unwrap_err().faults(),
        [
            LightError::NonFinite { field: "center" },
            LightError::DegenerateRect
        ]
    );
    assert_eq!(
        Light::rect(DVec3::ZERO, nan, inf).unwrap_err().faults(),
        [
            LightError::NonFinite { field: "u" },
            LightError::NonFinite { field: "v" }
        ]
    );
    assert_eq!(
        Light::segment(nan, inf).unwrap_err().faults(),
        [
            LightError::NonFinite { field: "a" },
            LightError::NonFinite { field: "b" }
        ]
    );
    // One fault is itself, not a list of one.
    assert_eq!(
        Light::disk(DVec3::ZERO, DVec3::ZERO, 1.0),
        Err(LightError::ZeroNormal)
    );
    #[cfg(feature = "scene-file")]
    {
        let text = r#"{"light": {"type": "disk", "center": [0, 4, 0], "normal": [0, 0, 0], "radius": -1}, "meshes": []}"#;
        let e = softshadow::scene::file::scene_from_str("s.json", text, std::path::Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("s.json: light.normal: ") && e.contains("light.radius: must be positive"),
            "{e}"
        );
    }
}
