//! The scene file, the points file, the primitive meshes and the built-in
//! scenes: one test per kind of bad input (exact one-line message naming
//! the file, the place and the field), round trips of DESIGN.md §8's
//! examples, and the geometric invariants of the generated meshes
//! (closedness, outward orientation, volume, transforms).

#![cfg(feature = "scene-file")]

use glam::{DMat3, DVec3};
use softshadow::scene::builtin::{builtin, BUILTIN_NAMES};
use softshadow::scene::file::{
    load_points, load_scene, mesh_from_obj, points_from_str, scene_from_str,
};
use softshadow::scene::primitive::{
    cuboid, merge, quad, sphere, sphere_bands, Transform, MAX_SEGMENTS, MIN_SEGMENTS,
};
use softshadow::scene::{Camera, FileError, Light, Mesh, Place, Receiver, Scene};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

fn manifest() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A scratch directory of this test binary, unique per test name.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "softshadow-scene-file-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The error message of loading `text` as `scene.json` (obj paths relative
/// to `base`), checked to be one line.
fn scene_err_in(text: &str, base: &Path) -> String {
    let e = scene_from_str("scene.json", text, base).expect_err(text);
    let msg = e.to_string();
    assert!(!msg.contains('\n') && !msg.contains('\r'), "{msg:?}");
    assert_eq!(e.file(), "scene.json");
    msg
}

fn scene_err(text: &str) -> String {
    scene_err_in(text, manifest())
}

const LIGHT: &str = r#""light": {"type": "point", "position": [0, 5, 0]}"#;

/// A scene with the point light and the given meshes.
fn with_meshes(meshes: &str) -> String {
    format!("{{{LIGHT}, \"meshes\": [{meshes}]}}")
}

/// A scene with the given light and one triangle.
fn with_light(light: &str) -> String {
    format!(
        r#"{{"light": {light}, "meshes": [{{"positions": [[0,0,0],[1,0,0],[0,0,1]], "triangles": [[0,1,2]]}}]}}"#
    )
}

fn points_err(text: &str, meshes: usize) -> String {
    let e = points_from_str("points.json", text, meshes).expect_err(text);
    let msg = e.to_string();
    assert!(!msg.contains('\n'), "{msg:?}");
    msg
}

// ---------------------------------------------------------------- bad input

#[test]
fn malformed_json_names_line_and_column() {
    let e = scene_from_str("scene.json", "{\n  \"light\": {,\n}", manifest()).unwrap_err();
    assert_eq!(
        e.place(),
        &Place::Position {
            line: 2,
            column: 13
        }
    );
    assert_eq!(e.to_string(), "scene.json:2:13: key must be a string");
    assert_eq!(
        scene_err("{\"light\": "),
        "scene.json:1:10: EOF while parsing a value"
    );
    assert_eq!(
        scene_err("{} trailing"),
        "scene.json:1:4: trailing characters"
    );
    assert_eq!(
        scene_err("[1, 2]"),
        "scene.json: expected an object, got an array of 2"
    );
}

#[test]
fn empty_file_is_an_error() {
    assert_eq!(scene_err(""), "scene.json: file is empty");
    assert_eq!(scene_err(" \n\t "), "scene.json: file is empty");
    assert_eq!(points_err("", 1), "points.json: file is empty");
}

#[test]
fn missing_file_is_an_error() {
    let path = scratch("missing").join("nope.json");
    let msg = load_scene(&path).unwrap_err().to_string();
    let expect = format!("{}: cannot read: ", path.display());
    assert!(msg.starts_with(&expect), "{msg}");
    assert!(!msg.contains('\n'));
    let msg = load_points(&path, 1).unwrap_err().to_string();
    assert!(msg.starts_with(&expect), "{msg}");
}

#[test]
fn non_utf8_file_is_an_error() {
    let path = scratch("utf8").join("bad.json");
    std::fs::write(&path, b"{\"light\": \xff}").unwrap();
    assert_eq!(
        load_scene(&path).unwrap_err().to_string(),
        format!("{}: not valid UTF-8 (byte 10)", path.display())
    );
}

#[test]
fn non_finite_numbers_are_rejected() {
    // JSON cannot spell NaN or infinity, and serde_json refuses literals
    // beyond f64: both are syntax errors at their position.
    assert_eq!(
        scene_err(&with_light(
            r#"{"type": "sphere", "center": [0, 1e999, 0], "radius": 1}"#
        )),
        "scene.json:1:48: number out of range (not a finite f64)"
    );
    assert_eq!(
        scene_err(&with_light(r#"{"type": "point", "position": [NaN, 0, 0]}"#)),
        "scene.json:1:42: expected value"
    );
    let huge_integer = "9".repeat(400);
    let msg = scene_err(&with_light(&format!(
        r#"{{"type": "sphere", "center": [0, {huge_integer}, 0], "radius": 1}}"#
    )));
    assert!(
        msg.ends_with(": number out of range (not a finite f64)"),
        "{msg}"
    );
    // Finite inputs that overflow when combined are reported where they
    // are combined.
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"positions": [[1e300,0,0],[0,0,0],[0,0,1]], "triangles": [[0,1,2]],
                "transform": {"scale": 1e10}}"#
        )),
        "scene.json: meshes[0].transform: moves a vertex out of range: \
         vertex 0 has a non-finite coordinate"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"primitive": {"type": "box", "min": [-1e308,0,0], "max": [1e308,1,1]},
                "transform": {"translate": [1e308, 0, 0]}}"#
        )),
        "scene.json: meshes[0].transform: moves a vertex out of range: \
         vertex 1 has a non-finite coordinate"
    );
}

#[test]
fn non_positive_radius_is_rejected() {
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"name": "a", "primitive": {"type": "box", "min": [0,0,0], "max": [1,1,1]}},
               {"primitive": {"type": "sphere", "center": [0,1,0], "radius": -1}}"#
        )),
        "scene.json: meshes[1].primitive.radius: must be positive, got -1"
    );
    assert_eq!(
        scene_err(&with_light(
            r#"{"type": "sphere", "center": [0, 5, 0], "radius": 0}"#
        )),
        "scene.json: light.radius: must be positive, got 0"
    );
    assert_eq!(
        scene_err(&with_light(
            r#"{"type": "disk", "center": [0, 5, 0], "normal": [0, -1, 0], "radius": -0.5}"#
        )),
        "scene.json: light.radius: must be positive, got -0.5"
    );
}

#[test]
fn triangle_index_out_of_range_is_rejected() {
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"positions": [[0,0,0],[1,0,0],[0,0,1]], "triangles": [[0,1,2],[0,1,3]]}"#
        )),
        "scene.json: meshes[0].triangles[1][2]: vertex index 3 is out of range \
         (the mesh has 3 positions)"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"positions": [[0,0,0]], "triangles": [[0,0,4294967296]]}"#
        )),
        "scene.json: meshes[0].triangles[0][2]: vertex index 4294967296 is out of range \
         (the mesh has 1 position)"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"positions": [[0,0,0]], "triangles": [[0,-1,0]]}"#
        )),
        "scene.json: meshes[0].triangles[0][1]: must be a non-negative integer, got -1"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"positions": [[0,0,0]], "triangles": [[0,1.0,0]]}"#
        )),
        "scene.json: meshes[0].triangles[0][1]: must be an integer, got 1.0"
    );
}

#[test]
fn wrong_arity_is_rejected() {
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"positions": [[0,0,0],[1,2],[0,0,1]], "triangles": [[0,1,2]]}"#
        )),
        "scene.json: meshes[0].positions[1]: expected [x, y, z], got an array of 2"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"positions": [[0,0,0],[1,0,0],[0,0,1]], "triangles": [[0,1]]}"#
        )),
        "scene.json: meshes[0].triangles[0]: expected [i, j, k] (3 vertex indices), \
         got an array of 2"
    );
    assert_eq!(
        scene_err(&with_light(
            r#"{"type": "point", "position": [0, 1, 2, 3]}"#
        )),
        "scene.json: light.position: expected [x, y, z], got an array of 4"
    );
    assert_eq!(
        scene_err(&with_light(r#"{"type": "point", "position": [0, "1", 2]}"#)),
        "scene.json: light.position[1]: expected a number, got the string \"1\""
    );
    assert_eq!(
        scene_err(&with_meshes(r#"{"positions": {}, "triangles": []}"#)),
        "scene.json: meshes[0].positions: expected an array, got an object"
    );
}

#[test]
fn unknown_light_type_is_rejected() {
    assert_eq!(
        scene_err(&with_light(r#"{"type": "spot", "position": [0, 5, 0]}"#)),
        "scene.json: light.type: unknown light type \"spot\" \
         (expected \"sphere\", \"disk\", \"rect\", \"segment\" or \"point\")"
    );
    assert_eq!(
        scene_err(&with_light(r#"{"position": [0, 5, 0]}"#)),
        "scene.json: light.type: required but missing \
         (one of \"sphere\", \"disk\", \"rect\", \"segment\" or \"point\")"
    );
    assert_eq!(
        scene_err(&with_meshes(r#"{"primitive": {"type": "cone"}}"#)),
        "scene.json: meshes[0].primitive.type: unknown primitive type \"cone\" \
         (expected \"sphere\", \"box\" or \"quad\")"
    );
}

#[test]
fn unknown_and_duplicate_keys_are_rejected() {
    assert_eq!(
        scene_err(&format!(r#"{{{LIGHT}, "meshes": [], "camra": {{}}}}"#)),
        "scene.json: camra: unknown key (expected one of: camera, light, meshes)"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"positions": [[0,0,0]], "triangels": [[0,0,0]]}"#
        )),
        "scene.json: meshes[0].triangels: unknown key \
         (expected one of: name, positions, triangles, obj, primitive, transform)"
    );
    assert_eq!(
        scene_err(&with_light(
            r#"{"type": "sphere", "center": [0, 5, 0], "radius": 1, "normal": [0,1,0]}"#
        )),
        "scene.json: light.normal: unknown key (expected one of: type, center, radius)"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"primitive": {"type": "box", "min": [0,0,0], "max": [1,1,1]},
                "transform": {"rotate_y": 90}}"#
        )),
        "scene.json: meshes[0].transform.rotate_y: unknown key \
         (expected one of: scale, rotate_y_deg, translate)"
    );
    assert_eq!(
        scene_err(&format!(r#"{{{LIGHT}, "meshes": [], "bad\nkey": 1}}"#)),
        "scene.json: [\"bad\\nkey\"]: unknown key (expected one of: camera, light, meshes)"
    );
    assert_eq!(
        scene_err(r#"{"meshes": [], "meshes": []}"#),
        "scene.json:1:23: duplicate key \"meshes\""
    );
}

#[test]
fn missing_required_fields_are_rejected() {
    assert_eq!(
        scene_err(r#"{"meshes": []}"#),
        "scene.json: light: required but missing"
    );
    assert_eq!(
        scene_err(&format!("{{{LIGHT}}}")),
        "scene.json: meshes: required but missing"
    );
    assert_eq!(
        scene_err(&with_light(r#"{"type": "sphere", "center": [0, 5, 0]}"#)),
        "scene.json: light.radius: required but missing"
    );
    assert_eq!(
        scene_err(&with_meshes(r#"{"name": "x"}"#)),
        "scene.json: meshes[0]: needs one of \"positions\" (with \"triangles\"), \
         \"obj\" or \"primitive\""
    );
    assert_eq!(
        scene_err(&with_meshes(r#"{"positions": [[0,0,0]]}"#)),
        "scene.json: meshes[0].triangles: required with \"positions\""
    );
    assert_eq!(
        scene_err(&with_meshes(r#"{"positions": [], "triangles": []}"#)),
        "scene.json: meshes[0].triangles: must hold at least one triangle"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"obj": "a.obj", "primitive": {"type": "box", "min": [0,0,0], "max": [1,1,1]}}"#
        )),
        "scene.json: meshes[0].primitive: conflicts with \"obj\" (a mesh has exactly one source)"
    );
}

#[test]
fn degenerate_lights_are_rejected() {
    assert_eq!(
        scene_err(&with_light(
            r#"{"type": "disk", "center": [0, 5, 0], "normal": [0, 0, 0], "radius": 1}"#
        )),
        "scene.json: light.normal: has zero length"
    );
    assert_eq!(
        scene_err(&with_light(
            r#"{"type": "rect", "center": [0, 5, 0], "u": [1, 0, 0], "v": [-2, 0, 0]}"#
        )),
        "scene.json: light.v: spans no area with u (u or v is zero, or they are parallel)"
    );
    assert_eq!(
        scene_err(&with_light(
            r#"{"type": "segment", "a": [0, 5, 0], "b": [0, 5, 0]}"#
        )),
        "scene.json: light.b: equals a (the segment has zero length)"
    );
}

#[test]
fn degenerate_primitives_transforms_and_cameras_are_rejected() {
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"primitive": {"type": "sphere", "center": [0,1,0], "radius": 1, "segments": 2}}"#
        )),
        "scene.json: meshes[0].primitive.segments: must be in 3..=1024, got 2"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"primitive": {"type": "sphere", "center": [0,1,0], "radius": 1,
                              "segments": 1000000000000}}"#
        )),
        "scene.json: meshes[0].primitive.segments: must be in 3..=1024, got 1000000000000"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"primitive": {"type": "box", "min": [0,0,0], "max": [1,0,1]}}"#
        )),
        "scene.json: meshes[0].primitive.max: must exceed min in every coordinate, got y 0 <= 0"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"primitive": {"type": "quad", "center": [0,0,0], "u": [1,0,0], "v": [0,0,0]}}"#
        )),
        "scene.json: meshes[0].primitive.v: spans no area with u \
         (u or v is zero, or they are parallel)"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"primitive": {"type": "box", "min": [0,0,0], "max": [1,1,1]},
                "transform": {"scale": -2}}"#
        )),
        "scene.json: meshes[0].transform.scale: must be positive, got -2"
    );
    let camera = |c: &str| format!(r#"{{{LIGHT}, "meshes": [], "camera": {c}}}"#);
    assert_eq!(
        scene_err(&camera(r#"{"eye": [0,1,0], "target": [0,1,0]}"#)),
        "scene.json: camera: eye equals target, or up is zero or parallel to the view direction"
    );
    assert_eq!(
        scene_err(&camera(
            r#"{"eye": [0,1,5], "target": [0,0,0], "fov_y_deg": 180}"#
        )),
        "scene.json: camera.fov_y_deg: must be in (0, 180) degrees, got 180"
    );
    assert_eq!(
        scene_err(&camera(
            r#"{"eye": [0,1,5], "target": [0,0,0], "width": 0}"#
        )),
        "scene.json: camera.width: must be in 1..=16384, got 0"
    );
    assert_eq!(
        scene_err(&camera(r#"{"target": [0,0,0]}"#)),
        "scene.json: camera.eye: required but missing"
    );
}

#[test]
fn obj_problems_are_reported_at_the_obj_field() {
    let dir = scratch("obj");
    let missing = dir.join("missing.obj");
    let msg = scene_err_in(&with_meshes(r#"{"obj": "missing.obj"}"#), &dir);
    assert!(
        msg.starts_with(&format!(
            "scene.json: meshes[0].obj: cannot read {missing:?}: "
        )),
        "{msg}"
    );
    let empty = dir.join("no_faces.obj");
    std::fs::write(&empty, "v 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
    assert_eq!(
        scene_err_in(&with_meshes(r#"{"obj": "no_faces.obj"}"#), &dir),
        format!("scene.json: meshes[0].obj: {empty:?}: has no faces")
    );
    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n").unwrap();
    assert_eq!(
        scene_err_in(&with_meshes(r#"{"obj": "bad.obj"}"#), &dir),
        format!("scene.json: meshes[0].obj: {bad:?}: OBJ: face vertex index out of bounds")
    );
    let inf = dir.join("inf.obj");
    std::fs::write(&inf, "v 0 0 0\nv 1e400 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    assert_eq!(
        scene_err_in(&with_meshes(r#"{"obj": "inf.obj"}"#), &dir),
        format!(
            "scene.json: meshes[0].obj: {inf:?}: vertex 1 (after merging objects) is not finite"
        )
    );
    assert_eq!(
        scene_err_in(&with_meshes(r#"{"obj": 3}"#), &dir),
        "scene.json: meshes[0].obj: expected a string, got a number"
    );
}

#[test]
fn obj_objects_are_merged_and_polygons_triangulated() {
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\no first\nf 1 2 3 4\n\
                o second\nv 0 0 1\nf 1 2 5\nl 1 2\n";
    let m = mesh_from_obj("two.obj", text.as_bytes()).unwrap();
    assert_eq!(m.triangles().len(), 3);
    let area: f64 = (0..3)
        .map(|t| {
            let [a, b, c] = m.corners(t).unwrap();
            (b - a).cross(c - a).length() / 2.0
        })
        .sum();
    assert_eq!(area, 1.0 + 0.5);
    assert_eq!(
        mesh_from_obj("x.obj", b"").unwrap_err().to_string(),
        "x.obj: has no faces"
    );
}

#[test]
fn points_file_is_checked() {
    let ok = points_from_str(
        "points.json",
        r#"{"points": [{"p": [0,1,2], "object": 1, "normal": [0,2,0]}, {"p": [3,4,5]}]}"#,
        2,
    )
    .unwrap();
    assert_eq!(
        ok,
        vec![
            Receiver {
                position: DVec3::new(0.0, 1.0, 2.0),
                object: Some(1),
                normal: Some(DVec3::Y)
            },
            Receiver {
                position: DVec3::new(3.0, 4.0, 5.0),
                object: None,
                normal: None
            }
        ]
    );
    // An empty list is allowed: no receivers.
    assert_eq!(
        points_from_str("points.json", r#"{"points": []}"#, 0),
        Ok(vec![])
    );
    assert_eq!(
        points_err(
            r#"{"points": [{"p": [0,0,0]}, {"p": [0,0,0], "object": 2}]}"#,
            2
        ),
        "points.json: points[1].object: 2 is out of range (the scene has 2 meshes)"
    );
    assert_eq!(
        points_err(r#"{"points": [{"p": [0,0,0], "object": 0}]}"#, 0),
        "points.json: points[0].object: 0 is out of range (the scene has 0 meshes)"
    );
    assert_eq!(
        points_err(r#"{"points": [{"p": [0,0,0], "normal": [0,0,0]}]}"#, 1),
        "points.json: points[0].normal: has zero length"
    );
    assert_eq!(
        points_err(r#"{"points": [{"q": [0,0,0]}]}"#, 1),
        "points.json: points[0].q: unknown key (expected one of: p, object, normal)"
    );
    assert_eq!(
        points_err(r#"{"points": [{"object": 0}]}"#, 1),
        "points.json: points[0].p: required but missing"
    );
    assert_eq!(
        points_err(r#"{"points": [{"p": [0,0]}]}"#, 1),
        "points.json: points[0].p: expected [x, y, z], got an array of 2"
    );
    assert_eq!(
        points_err("{}", 1),
        "points.json: points: required but missing"
    );
}

/// Mutations of a valid scene never panic, and every error is one line
/// naming the file.
#[test]
fn mutated_files_give_one_line_errors() {
    let base = std::fs::read_to_string(manifest().join("examples/scenes/primitives.json")).unwrap();
    let bytes = base.as_bytes();
    let alphabet = b"{}[],:\"-0123456789.eE xyztn\n";
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for _ in 0..3000 {
        let mut text = bytes.to_vec();
        for _ in 0..1 + next() % 3 {
            let at = (next() % text.len() as u64) as usize;
            let c = alphabet[(next() % alphabet.len() as u64) as usize];
            match next() % 3 {
                0 => text[at] = c,
                1 => text.insert(at, c),
                _ => {
                    text.remove(at);
                }
            }
        }
        let Ok(text) = String::from_utf8(text) else {
            continue;
        };
        if let Err(e) = scene_from_str("m.json", &text, manifest()) {
            let msg = e.to_string();
            assert!(msg.starts_with("m.json") && !msg.contains('\n'), "{msg}");
        }
    }
    // Likewise for OBJ text fed to tobj.
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2//1 3\nf -1 -2 -3\n";
    let alphabet = b"vfnt/ -0123456789.\n";
    for _ in 0..3000 {
        let mut text = obj.as_bytes().to_vec();
        for _ in 0..1 + next() % 3 {
            let at = (next() % text.len() as u64) as usize;
            text[at] = alphabet[(next() % alphabet.len() as u64) as usize];
        }
        if let Ok(m) = mesh_from_obj("m.obj", &text) {
            assert!(m.positions().iter().all(|p| p.is_finite()));
        }
    }
}

// -------------------------------------------------------------- round trips

/// DESIGN.md §8's example, with the floor spelled out and the bunny taken
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

/// Every light kind of DESIGN.md §8 and both optional parts (camera,
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
        matches!(builtin("large-light").unwrap().light(), Light::Sphere { radius, .. } if *radius == 2.0)
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

// -------------------------------------------------------------- primitives

/// Every undirected edge is used by exactly two triangles, once in each
/// direction (closed, consistently oriented, manifold at edges).
fn assert_closed(mesh: &Mesh) {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for t in mesh.triangles() {
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(n, 1, "edge {a}→{b} used {n} times in one direction");
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "edge {a}→{b} has no opposite"
        );
    }
}

/// The signed volume `Σ (a − o) · ((b − o) × (c − o)) / 6` about `o`.
fn signed_volume_about(mesh: &Mesh, o: DVec3) -> f64 {
    (0..mesh.triangles().len())
        .filter_map(|t| mesh.corners(t))
        .map(|[a, b, c]| (a - o).dot((b - o).cross(c - o)) / 6.0)
        .sum()
}

/// Higham's `γ(k) = kε/(1 − kε)`, `ε` the unit roundoff.
fn gamma(k: usize) -> f64 {
    let ku = k as f64 * f64::EPSILON / 2.0;
    ku / (1.0 - ku)
}

fn signed_volume(mesh: &Mesh) -> f64 {
    signed_volume_about(mesh, mesh.positions()[0])
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

#[test]
fn file_error_parts_are_accessible() {
    let e: FileError = scene_from_str("a.json", r#"{"meshes": []}"#, manifest()).unwrap_err();
    assert_eq!(e.file(), "a.json");
    assert_eq!(e.place(), &Place::Path("light".to_owned()));
    assert_eq!(e.message(), "required but missing");
    let _: Option<Scene> = None;
}
