//! What the scene-file tests (`tests/scene_file_*.rs`) share, included
//! with `#[path]`: the manifest directory, scratch directories, the one-line
//! error messages of a scene or points text, small scene texts, and the
//! mesh checks (closed and consistently oriented; signed volume).
#![allow(dead_code)]

use softshadow::glam::DVec3;
use softshadow::scene::file::{points_from_str, scene_from_str};
use softshadow::scene::Mesh;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

pub fn manifest() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A scratch directory of this test binary, unique per test name.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "softshadow-scene-file-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The error message of loading `text` as `scene.json` (obj paths relative
/// to `base`), checked to be one line.
pub fn scene_err_in(text: &str, base: &Path) -> String {
    let e = scene_from_str("scene.json", text, base).expect_err(text);
    let msg = e.to_string();
    assert!(!msg.contains('\n') && !msg.contains('\r'), "{msg:?}");
    assert_eq!(e.file(), "scene.json");
    msg
}

pub fn scene_err(text: &str) -> String {
    scene_err_in(text, manifest())
}

pub const LIGHT: &str = r#""light": {"type": "point", "position": [0, 5, 0]}"#;

/// A scene with the point light and the given meshes.
pub fn with_meshes(meshes: &str) -> String {
    format!("{{{LIGHT}, \"meshes\": [{meshes}]}}")
}

/// A scene with the given light and one triangle.
pub fn with_light(light: &str) -> String {
    format!(
        r#"{{"light": {light}, "meshes": [{{"positions": [[0,0,0],[1,0,0],[0,0,1]], "triangles": [[0,1,2]]}}]}}"#
    )
}

pub fn points_err(text: &str, meshes: usize) -> String {
    let e = points_from_str("points.json", text, meshes).expect_err(text);
    let msg = e.to_string();
    assert!(!msg.contains('\n'), "{msg:?}");
    msg
}

/// Every undirected edge is used by exactly two triangles, once in each
/// direction (closed, consistently oriented, manifold at edges).
pub fn assert_closed(mesh: &Mesh) {
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
pub fn signed_volume_about(mesh: &Mesh, o: DVec3) -> f64 {
    (0..mesh.triangles().len())
        .filter_map(|t| mesh.corners(t))
        .map(|[a, b, c]| (a - o).dot((b - o).cross(c - o)) / 6.0)
        .sum()
}

pub fn signed_volume(mesh: &Mesh) -> f64 {
    signed_volume_about(mesh, mesh.positions()[0])
}
