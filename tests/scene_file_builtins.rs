//! The built-in scenes: each loads with the meshes it claims, the bunny
//! rests on the floor and is closed, the contact scene touches the
//! floor.

#![cfg(feature = "scene-file")]

use softshadow::scene::builtin::{builtin, BUILTIN_NAMES};
use softshadow::scene::Light;

#[path = "support/scene_file.rs"]
mod scene_file_support;
use scene_file_support::{assert_closed, signed_volume};

// ------------------------------------------------------------------- builtins

#[test]
fn builtins_load_with_the_meshes_they_claim() {
    let claims: &[(&str, &[&str], usize)] = &[
        ("default", &["floor", "bunny"], 3676),
        (
            "overlapping-penumbrae",
            &["floor", "low plate", "high ball"],
            964,
        ),
        ("contact", &["floor", "box", "ball"], 974),
        ("comb", &["floor", "comb"], 170),
        ("large-light", &["floor", "ball", "box"], 974),
        ("depth-complexity", &[], 2050),
        (
            "linear-light",
            &["floor", "bar across", "bar along", "box", "ball"],
            998,
        ),
        (
            "several-objects",
            &["floor", "ball", "box", "block", "card", "small ball"],
            1948,
        ),
        ("rect-light", &["floor", "plate", "ball", "card"], 976),
    ];
    assert_eq!(
        claims.iter().map(|c| c.0).collect::<Vec<_>>(),
        BUILTIN_NAMES.to_vec()
    );
    for &(name, names, triangles) in claims {
        let scene = builtin(name).unwrap_or_else(|| panic!("{name}"));
        if name == "depth-complexity" {
            assert_eq!(scene.meshes().len(), 17);
            assert_eq!(scene.names()[16], "layer15");
        } else {
            assert_eq!(scene.names(), names, "{name}");
        }
        assert_eq!(scene.triangle_count(), triangles, "{name}");
        assert!(triangles < 50_000);
        assert_eq!(scene.names()[0], "floor");
        let (lo, hi) = scene.bounds().unwrap();
        assert!(lo.is_finite() && hi.is_finite(), "{name}");
        assert_eq!(lo.y, 0.0, "{name}: the floor is the lowest thing");
        let camera = scene.camera().unwrap();
        assert_eq!(camera.resolution(), (512, 512));
        // Every vertex is a valid receiver: outside a sphere light, off a
        // disk or rect light's plane.
        for mesh in scene.meshes() {
            for &p in mesh.positions() {
                assert!(scene.light().emitter(p).is_ok(), "{name}: {p}");
            }
            assert!(!mesh.triangles().is_empty());
        }
    }
    assert!(builtin("nope").is_none());
    assert!(
        matches!(builtin("large-light").unwrap().light(), Light::Sphere(s) if s.radius() == 2.0)
    );
    assert!(matches!(
        builtin("linear-light").unwrap().light(),
        Light::Segment { .. }
    ));
    assert!(matches!(
        builtin("rect-light").unwrap().light(),
        Light::Rect { .. }
    ));
}

#[test]
fn builtin_bunny_rests_on_the_floor_and_is_closed() {
    let scene = builtin("default").unwrap();
    let bunny = &scene.meshes()[1];
    let (lo, hi) = bunny.bounds().unwrap();
    assert!((hi.y - lo.y - 1.0).abs() < 1e-12);
    assert!(lo.y.abs() < 1e-12);
    assert!((lo.x + hi.x).abs() < 1e-12 && (lo.z + hi.z).abs() < 1e-12);
    assert_closed(bunny);
    assert!(signed_volume(bunny) > 0.0);
}

#[test]
fn contact_scene_touches_the_floor() {
    let scene = builtin("contact").unwrap();
    for mesh in &scene.meshes()[1..] {
        assert_eq!(mesh.bounds().unwrap().0.y, 0.0);
    }
}
