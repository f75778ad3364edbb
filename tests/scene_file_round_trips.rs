//! The scene file and the points file: round trips of the documented
//! examples, every light kind, and the example files in
//! `examples/scenes/`.

#![cfg(feature = "scene-file")]

use softshadow::glam::DVec3;
use softshadow::scene::file::{load_points, load_scene, scene_from_str};
use softshadow::scene::primitive::sphere;
use softshadow::scene::{Camera, Light, Mesh};

#[path = "support/scene_file.rs"]
mod scene_file_support;
use scene_file_support::{manifest, with_light, LIGHT};

// -------------------------------------------------------------- round trips

/// The scene file's documented example, with the floor spelled out and the bunny taken
/// from `src/scene/data`.
#[test]
fn design_example_round_trips() {
    let text = r#"{
      "camera": {"eye": [0,3,6], "target": [0,0,0], "up": [0,1,0],
                 "fov_y_deg": 45, "width": 512, "height": 512},
      "light":  {"type": "sphere", "center": [0,5,0], "radius": 0.5},
      "meshes": [
        {"name": "floor", "positions": [[-3,0,3],[3,0,3],[3,0,-3],[-3,0,-3]],
         "triangles": [[0,1,2],[0,2,3]]},
        {"name": "bunny", "obj": "bunny.obj",
         "transform": {"scale": 1.0, "rotate_y_deg": 0, "translate": [0,0,0]}},
        {"name": "ball",  "primitive": {"type": "sphere", "center": [0,1,0],
                                         "radius": 1, "segments": 32}}
      ]
    }"#;
    let scene = scene_from_str("scene.json", text, &manifest().join("src/scene/data")).unwrap();
    assert_eq!(
        scene.camera(),
        Some(
            &Camera::new(
                DVec3::new(0.0, 3.0, 6.0),
                DVec3::ZERO,
                DVec3::Y,
                45.0,
                512,
                512
            )
            .unwrap()
        )
    );
    assert_eq!(
        scene.light(),
        &Light::sphere(DVec3::new(0.0, 5.0, 0.0), 0.5).unwrap()
    );
    assert_eq!(scene.names(), ["floor", "bunny", "ball"]);
    assert_eq!(
        scene.meshes()[0],
        Mesh::new(
            vec![
                DVec3::new(-3.0, 0.0, 3.0),
                DVec3::new(3.0, 0.0, 3.0),
                DVec3::new(3.0, 0.0, -3.0),
                DVec3::new(-3.0, 0.0, -3.0)
            ],
            vec![[0, 1, 2], [0, 2, 3]]
        )
        .unwrap()
    );
    let bunny = &scene.meshes()[1];
    assert_eq!(
        (bunny.positions().len(), bunny.triangles().len()),
        (1839, 3674)
    );
    assert_eq!(scene.meshes()[2], sphere(DVec3::Y, 1.0, 32).unwrap());
}

/// Every light kind of the scene file and both optional parts (camera,
/// transform) load to the values the constructors give.
#[test]
fn every_light_kind_round_trips() {
    let v = DVec3::new;
    let cases = [
        (
            r#"{"type":"sphere","center":[0,5,0],"radius":0.5}"#,
            Light::sphere(v(0.0, 5.0, 0.0), 0.5),
        ),
        (
            r#"{"type":"disk","center":[0,5,0],"normal":[0,-2,0],"radius":0.5}"#,
            Light::disk(v(0.0, 5.0, 0.0), v(0.0, -1.0, 0.0), 0.5),
        ),
        (
            r#"{"type":"rect","center":[0,5,0],"u":[1,0,0],"v":[0,0,0.5]}"#,
            Light::rect(v(0.0, 5.0, 0.0), v(1.0, 0.0, 0.0), v(0.0, 0.0, 0.5)),
        ),
        (
            r#"{"type":"segment","a":[-1,5,0],"b":[1,5,0]}"#,
            Light::segment(v(-1.0, 5.0, 0.0), v(1.0, 5.0, 0.0)),
        ),
        (
            r#"{"type":"point","position":[0,5,0]}"#,
            Light::point(v(0.0, 5.0, 0.0)),
        ),
    ];
    for (json, light) in cases {
        let scene = scene_from_str("s.json", &with_light(json), manifest()).unwrap();
        assert_eq!(scene.light(), &light.unwrap());
        assert!(scene.camera().is_none());
        assert_eq!(scene.names(), ["mesh0"]);
    }
    // Camera defaults: up +y, 45°, 512 × 512.
    let scene = scene_from_str(
        "s.json",
        &format!(r#"{{{LIGHT}, "meshes": [], "camera": {{"eye": [0,1,5], "target": [0,0,0]}}}}"#),
        manifest(),
    )
    .unwrap();
    assert_eq!(
        scene.camera(),
        Some(&Camera::new(v(0.0, 1.0, 5.0), DVec3::ZERO, DVec3::Y, 45.0, 512, 512).unwrap())
    );
    assert!(scene.meshes().is_empty());
}

#[test]
fn example_files_load() {
    let dir = manifest().join("examples/scenes");
    let bunny = load_scene(&dir.join("bunny.json")).unwrap();
    assert_eq!(bunny.names(), ["floor", "bunny"]);
    let (lo, hi) = bunny.meshes()[1].bounds().unwrap();
    assert!((hi.y - lo.y - 1.0).abs() < 1e-4, "{lo} {hi}");
    assert!(lo.y.abs() < 1e-4);
    let quads = load_scene(&dir.join("two_quads.json")).unwrap();
    assert_eq!(quads.triangle_count(), 6);
    assert_eq!(quads.camera().unwrap().resolution(), (256, 256));
    let prims = load_scene(&dir.join("primitives.json")).unwrap();
    assert_eq!(prims.names(), ["floor", "ball", "box", "triangle"]);
    assert_eq!(prims.triangle_count(), 2 + 960 + 12 + 1);
    let points = load_points(&dir.join("points.json"), prims.meshes().len()).unwrap();
    assert_eq!(points.len(), 5);
    assert_eq!(points[0].object, Some(0));
    assert_eq!(points[2].normal, None);
}

// ------------------------------------------------- numbers, correctly rounded

/// A random decimal literal of 17 significant digits, `±d.dddddddddddddddde±x`
/// with the exponent in `-30..=29`: as a file holds it, not as Rust prints
/// a double (most are no double's shortest spelling).
fn literal17(rng: &mut softshadow::arbitrary::Rng) -> String {
    let sign = if rng.chance(0.5) { "-" } else { "" };
    let lead = 1 + rng.below(9);
    let rest: String = (0..16)
        .map(|_| char::from(b'0' + rng.below(10) as u8))
        .collect();
    let exp = rng.below(60) as i64 - 30;
    format!("{sign}{lead}.{rest}e{exp}")
}

/// Every number of a scene or points file is read correctly rounded: the
/// double nearest the literal, as Rust's `str::parse::<f64>` (correctly
/// rounded) gives it — not within an ulp of it. Random 17-digit literals
/// (about 9 % were read 1 ulp off before), in every place a number goes:
/// light, camera, inline positions, primitives and transforms, points.
#[test]
fn numbers_are_read_correctly_rounded() {
    use softshadow::scene::file::points_from_str;
    let mut rng = softshadow::arbitrary::Rng::new(0x5eed_0017);
    let mut off = 0;
    for _ in 0..400 {
        let lits: Vec<String> = (0..9).map(|_| literal17(&mut rng)).collect();
        let want: Vec<f64> = lits.iter().map(|s| s.parse().unwrap()).collect();
        let (x, y, z) = (&lits[0], &lits[1], &lits[2]);
        let w = |i: usize| DVec3::new(want[i], want[i + 1], want[i + 2]);
        // A radius is positive: the literal's magnitude.
        let radius = lits[3].trim_start_matches('-');
        let text = format!(
            r#"{{"light": {{"type": "sphere", "center": [{x}, {y}, {z}], "radius": {radius}}},
                "camera": {{"eye": [{}, {}, {}], "target": [0, 0, 0], "fov_y_deg": 45}},
                "meshes": [{{"positions": [[{x}, {y}, {z}], [{}, {}, {}], [{}, 0, 0]], "triangles": [[0, 1, 2]]}}]}}"#,
            lits[4], lits[5], lits[6], lits[4], lits[5], lits[6], lits[7]
        );
        let Ok(scene) = scene_from_str("s.json", &text, manifest()) else {
            // A degenerate draw (eye at the target, a flat triangle): rare.
            continue;
        };
        let Light::Sphere(s) = scene.light() else {
            unreachable!()
        };
        off += usize::from(s.center() != w(0));
        off += usize::from(s.radius() != want[3].abs());
        off += usize::from(scene.camera().unwrap().eye() != w(4));
        let p = scene.meshes()[0].positions();
        off += usize::from(p[0] != w(0) || p[1] != w(4) || p[2].x != want[7]);
        let points = points_from_str(
            "p.json",
            &format!(
                r#"{{"points": [{{"p": [{x}, {y}, {z}], "normal": [0, {}, 0]}}]}}"#,
                lits[8]
            ),
            1,
        )
        .unwrap();
        off += usize::from(points[0].position != w(0));
        assert_eq!(off, 0, "read off by an ulp: {lits:?}");
    }
    // Primitives and transforms, whose numbers go through the same reader.
    for _ in 0..200 {
        let lits: Vec<String> = (0..3).map(|_| literal17(&mut rng)).collect();
        let want: Vec<f64> = lits.iter().map(|s| s.parse().unwrap()).collect();
        let text = format!(
            r#"{{{LIGHT}, "meshes": [{{"primitive": {{"type": "quad", "center": [{}, {}, {}], "u": [1, 0, 0], "v": [0, 0, 1]}}}}]}}"#,
            lits[0], lits[1], lits[2]
        );
        let scene = scene_from_str("s.json", &text, manifest()).unwrap();
        let c = DVec3::new(want[0], want[1], want[2]);
        let want_quad = softshadow::scene::primitive::quad(c, DVec3::X, DVec3::Z).unwrap();
        assert_eq!(scene.meshes()[0], want_quad, "{lits:?}");
    }
}

/// The issue's case: `0.9999999999999999` is the double just below 1, not
/// 1, so a point read from it lies under a plate at `y = 1`.
#[test]
fn the_double_below_one_is_read_as_itself() {
    use softshadow::scene::file::points_from_str;
    let below = 1.0 - f64::EPSILON / 2.0;
    assert_eq!("0.9999999999999999".parse::<f64>().unwrap(), below);
    let points = points_from_str(
        "p.json",
        r#"{"points": [{"p": [0, 0.9999999999999999, 0]}]}"#,
        0,
    )
    .unwrap();
    assert_eq!(points[0].position.y, below);
}
