//! The scene file, the points file and OBJ meshes: one test per kind of
//! bad input, each with the exact one-line message naming the file, the
//! place and the field; mutated files give one-line errors; a
//! [`FileError`]'s parts.

#![cfg(feature = "scene-file")]

use softshadow::glam::DVec3;
use softshadow::scene::file::{
    load_points, load_scene, mesh_from_obj, points_from_str, scene_from_str,
};
use softshadow::scene::{FileError, Place, Receiver, Scene};

#[path = "support/scene_file.rs"]
mod scene_file_support;
use scene_file_support::{
    manifest, points_err, scene_err, scene_err_in, scratch, with_light, with_meshes, LIGHT,
};

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

/// A byte that is not UTF-8 is reported at its line and column, with its
/// value, in a scene or a points file, large or small.
#[test]
fn non_utf8_file_is_an_error() {
    let path = scratch("utf8").join("bad.json");
    std::fs::write(&path, b"{\"light\": \xff}").unwrap();
    let latin1 = "(byte 0xFF; the file must be UTF-8, not Latin-1 or another encoding)";
    assert_eq!(
        load_scene(&path).unwrap_err().to_string(),
        format!("{}:1:11: not valid UTF-8 {latin1}", path.display())
    );
    // A Latin-1 "é" in a mesh name on line 3, past 100 kB of points.
    let many = vec!["[0, 0, 0]"; 12_000].join(", ");
    let text = format!(
        "{{{LIGHT},\n\"meshes\": [{{\"positions\": [{many}],\n  \"name\": \"caf\u{1}\"}}]}}"
    );
    let mut bytes = text.into_bytes();
    let at = bytes.iter().position(|&b| b == 1).unwrap();
    bytes[at] = 0xe9;
    std::fs::write(&path, &bytes).unwrap();
    let msg = load_scene(&path).unwrap_err().to_string();
    assert_eq!(
        msg,
        format!("{}:3:15: not valid UTF-8 (byte 0xE9; the file must be UTF-8, not Latin-1 or another encoding)", path.display())
    );
    std::fs::write(&path, b"{\"points\": [{\"p\": [0, 0, 0]}]}\n\x80").unwrap();
    assert_eq!(
        load_points(&path, 1).unwrap_err().to_string(),
        format!(
            "{}:2:1: not valid UTF-8 {}",
            path.display(),
            latin1.replace("0xFF", "0x80")
        )
    );
}

/// A UTF-8 byte-order mark (which some editors write) is skipped, in files
/// and in text; a UTF-16 one is refused by name, not as "expected value".
#[test]
fn a_byte_order_mark_is_skipped_and_utf16_named() {
    let dir = scratch("bom");
    let text = with_meshes("");
    let path = dir.join("bom.json");
    std::fs::write(&path, format!("\u{feff}{text}")).unwrap();
    assert!(load_scene(&path).is_ok());
    assert!(scene_from_str("s.json", &format!("\u{feff}{text}"), manifest()).is_ok());
    let points = dir.join("points.json");
    std::fs::write(&points, "\u{feff}{\"points\": [{\"p\": [0, 1, 0]}]}").unwrap();
    assert_eq!(load_points(&points, 0).unwrap().len(), 1);
    assert_eq!(
        points_from_str("p.json", "\u{feff}{\"points\": []}", 0).unwrap(),
        vec![]
    );
    // A mark then nothing is an empty file.
    std::fs::write(&path, "\u{feff}").unwrap();
    assert_eq!(
        load_scene(&path).unwrap_err().to_string(),
        format!("{}: file is empty", path.display())
    );
    let utf16: Vec<u8> = std::iter::once(0xfeff_u16)
        .chain(text.encode_utf16())
        .flat_map(u16::to_le_bytes)
        .collect();
    std::fs::write(&path, utf16).unwrap();
    assert_eq!(
        load_scene(&path).unwrap_err().to_string(),
        format!(
            "{}: is UTF-16 (it starts with a UTF-16 byte-order mark); save it as UTF-8",
            path.display()
        )
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
    // Numbers beyond the predicates' domain (|x| ≤ 1e30) are refused where
    // they are written, and vertices carried beyond it by a transform (or
    // made there by a primitive) at the mesh.
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"positions": [[1e300,0,0],[0,0,0],[0,0,1]], "triangles": [[0,1,2]],
                "transform": {"scale": 1e10}}"#
        )),
        "scene.json: meshes[0].positions[0][0]: 1e300 is outside the domain |x| ≤ 1e30 \
         (where the exact predicates are exact)"
    );
    assert_eq!(
        scene_err(&with_meshes(
            r#"{"primitive": {"type": "box", "min": [-1e20,0,0], "max": [1e20,1,1]},
                "transform": {"scale": 1e20}}"#
        )),
        "scene.json: meshes[0]: vertex 0 at [-1e40, 0e0, 0e0] \
         is outside the domain |x| ≤ 1e30 (where the exact predicates are exact)"
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
    // In a streamed mesh, a small part, the points file.
    let text = with_meshes(r#"{"name": "a", "name": "b"}"#);
    let column = text.find(r#""name": "b""#).unwrap() + 6; // after the key
    assert_eq!(
        scene_err(&text),
        format!("scene.json:1:{column}: duplicate key \"name\"")
    );
    assert!(scene_err(&with_light(
        r#"{"type": "point", "position": [0, 5, 0], "position": [0, 6, 0]}"#
    ))
    .ends_with(": duplicate key \"position\""));
    assert_eq!(
        points_err(r#"{"points": [], "points": []}"#, 1),
        "points.json:1:23: duplicate key \"points\""
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
            "scene.json: meshes[0].obj: {missing:?}: cannot read: "
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
        format!("scene.json: meshes[0].obj: {bad:?}: line 4: a face (f) names a vertex that does not exist")
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

/// OBJ errors name their line; bytes that are not UTF-8 (Latin-1 in a
/// comment, as old exporters write) are no error where they are harmless,
/// and one at its line where they are not.
#[test]
fn obj_errors_name_their_line() {
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let mut latin1 = b"# cr\xe9\xe9 par Blender\n".to_vec();
    latin1.extend_from_slice(tri.as_bytes());
    assert_eq!(
        mesh_from_obj("l.obj", &latin1).unwrap().triangles().len(),
        1
    );
    let mut bad_vertex = tri.as_bytes().to_vec();
    bad_vertex.extend_from_slice(b"v 1 \xe9 0\nf 1 2 4\n");
    assert_eq!(
        mesh_from_obj("b.obj", &bad_vertex).unwrap_err().to_string(),
        "b.obj: line 5: a vertex (v) that is not 3 or 4 numbers"
    );
    let cases = [
        ("v 0 0\n", "line 1: a vertex (v) that is not 3 or 4 numbers"),
        (
            "v 0 0 0\nvn 0 x 1\n",
            "line 2: a normal (vn) that is not 3 numbers",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 x\n",
            "line 5: a face (f) that cannot be read",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 -4 2\no next\nf 1 2 3",
            "line 5: a face (f) names a vertex that does not exist",
        ),
    ];
    for (text, want) in cases {
        assert_eq!(
            mesh_from_obj("c.obj", text.as_bytes())
                .unwrap_err()
                .to_string(),
            format!("c.obj: {want}"),
            "{text:?}"
        );
    }
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

#[test]
fn file_error_parts_are_accessible() {
    let e: FileError = scene_from_str("a.json", r#"{"meshes": []}"#, manifest()).unwrap_err();
    assert_eq!(e.file(), "a.json");
    assert_eq!(e.place(), &Place::Path("light".to_owned()));
    assert_eq!(e.message(), "required but missing");
    let _: Option<Scene> = None;
}

/// Points files of 64 KiB and more are read as a stream (never held whole,
/// nor as a tree): the same receivers and the same messages as from text.
#[test]
fn large_points_files_stream_with_the_same_answers_and_messages() {
    let dir = scratch("stream");
    let n = 5000;
    let file = |bad: usize| {
        let body: Vec<String> = (0..n)
            .map(|i| {
                let object = if i == bad { 7 } else { i % 2 };
                format!(r#"{{"p": [{i}.5, 0.25, -{i}], "object": {object}, "normal": [0, 2, 0]}}"#)
            })
            .collect();
        format!(r#"{{"points": [{}]}}"#, body.join(", "))
    };
    let text = file(n);
    assert!(text.len() >= 1 << 16);
    let path = dir.join("many.json");
    std::fs::write(&path, &text).unwrap();
    let streamed = load_points(&path, 2).unwrap();
    assert_eq!(streamed.len(), n);
    assert_eq!(
        Ok(streamed),
        points_from_str(&path.display().to_string(), &text, 2)
    );
    // A bad point deep in the file: named by its index.
    std::fs::write(&path, file(1999)).unwrap();
    let msg = load_points(&path, 2).unwrap_err().to_string();
    assert!(
        msg.ends_with("points[1999].object: 7 is out of range (the scene has 2 meshes)"),
        "{msg}"
    );
    // A syntax error: at its line and column.
    let broken = text.replacen("0.25", "0.2.5", 1);
    std::fs::write(&path, &broken).unwrap();
    let msg = load_points(&path, 2).unwrap_err().to_string();
    assert!(msg.contains("many.json:1:"), "{msg}");
    let unknown = format!(r#"{{"pointz": [], {}"#, &text[1..]);
    std::fs::write(&path, &unknown).unwrap();
    let msg = load_points(&path, 2).unwrap_err().to_string();
    assert!(
        msg.ends_with("pointz: unknown key (expected one of: points)"),
        "{msg}"
    );
}
