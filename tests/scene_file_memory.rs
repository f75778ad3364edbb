//! The scene and points files are read as streams: the heap's peak while
//! loading is bounded by a small multiple of the file, whatever the file
//! holds and wherever its error is — where a tree of the whole file took
//! about 17 times its size before the first check (a 50 MB scene peaked at
//! 835 MB before "unknown key"). Counted with dhat's heap statistics (in
//! testing mode: bytes, not a noisy resident size), so the bounds are
//! exact properties of the reader, not timings.

#![cfg(feature = "scene-file")]

use softshadow::scene::file::{load_points, load_scene};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[global_allocator]
static ALLOC: dhat::Alloc = dhat::Alloc;

/// The heap statistics are global, so this file runs without the test
/// harness (`harness = false`), on one thread.
fn main() {
    a_scene_file_peaks_near_its_meshes();
    an_error_at_the_end_is_found_without_a_tree_of_the_file();
    a_points_file_peaks_near_its_receivers();
    a_huge_small_part_is_refused_without_building_it();
    println!("scene_file_memory: 4 passed, 0 failed");
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "softshadow-scene-file-memory-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// `load` of `text` written to the file `name`, with the heap's peak
/// while it runs (dhat) checked to be under `bound` × the file's size.
fn load_within<T>(name: &str, text: &str, bound: f64, load: impl FnOnce(&Path) -> T) -> T {
    let path = scratch(name);
    std::fs::write(&path, text).unwrap();
    let _profiler = dhat::Profiler::builder().testing().build();
    let base = dhat::HeapStats::get().curr_bytes as u64;
    let out = load(&path);
    let bytes = dhat::HeapStats::get().max_bytes as u64 - base;
    let ratio = bytes as f64 / text.len() as f64;
    println!(
        "  {name}: peak {bytes} bytes, {ratio:.2} × the file of {} bytes",
        text.len()
    );
    assert!(
        ratio < bound,
        "{name}: peak {bytes} bytes, {ratio:.2} × the file"
    );
    out
}

/// A scene of one inline mesh of `n` vertices with 7-decimal coordinates
/// (about 35 bytes a vertex and its triangle in the file) and `tail`
/// after the meshes.
fn scene_text(n: usize, tail: &str) -> String {
    let mut s = String::from(
        r#"{"light": {"type": "sphere", "center": [0, 5, 0], "radius": 0.5}, "meshes": [{"name": "soup", "positions": ["#,
    );
    // Deterministic, non-dyadic coordinates in (-1, 1); consecutive
    // triples never collinear (the third coordinate is a cubic in k).
    let c = |k: usize, a: usize| ((k * a + 17) % 1999) as f64 / 1000.0 - 0.9995;
    for k in 0..n {
        let sep = if k == 0 { "" } else { ", " };
        let (x, y, z) = (
            c(k, 7),
            c(k, 13),
            c(k * k % 1997, 3) + 1e-7 * (k % 7) as f64,
        );
        write!(s, "{sep}[{x:.7}, {y:.7}, {z:.7}]").unwrap();
    }
    s.push_str(r#"], "triangles": ["#);
    for k in 0..n / 3 {
        let sep = if k == 0 { "" } else { ", " };
        write!(s, "{sep}[{}, {}, {}]", 3 * k, 3 * k + 1, 3 * k + 2).unwrap();
    }
    s.push_str("]}]");
    s.push_str(tail);
    s.push('}');
    s
}

/// The bound of a scene of these vertices: the text, read whole into a
/// buffer of its size (1×), and the mesh — 24 bytes a vertex and 12 a
/// triangle (a third as many) for about 44.7 bytes of text — in vectors
/// at most twice their length while they grow: 1 + 2 × 28 / 44.7 = 2.25.
const SCENE_BOUND: f64 = 2.3;

/// A valid 10 MB scene peaks under [`SCENE_BOUND`] × the file; a tree of
/// the whole file was 7–17× (9.4× for these numbers by resident size,
/// `/usr/bin/time`).
fn a_scene_file_peaks_near_its_meshes() {
    let text = scene_text(240_000, "");
    let scene = load_within("ok.json", &text, SCENE_BOUND, load_scene).unwrap();
    assert_eq!(scene.meshes()[0].positions().len(), 240_000);
}

/// An unknown key after 10 MB of mesh: refused at that key, having held
/// no more than the mesh read so far and the text.
fn an_error_at_the_end_is_found_without_a_tree_of_the_file() {
    let text = scene_text(240_000, r#", "unknown": 1"#);
    let msg = load_within("unknown.json", &text, SCENE_BOUND, load_scene)
        .unwrap_err()
        .to_string();
    assert!(
        msg.ends_with("unknown: unknown key (expected one of: camera, light, meshes)"),
        "{msg}"
    );
}

/// 200,000 points (8.6 MB): the peak is the text (1×) and the receivers,
/// 64 bytes a point for 43 bytes of text in a vector at most twice its
/// length while it grows: 1 + 2 × 64 / 43 = 3.98.
fn a_points_file_peaks_near_its_receivers() {
    let mut text = String::from(r#"{"points": ["#);
    for k in 0..200_000usize {
        let sep = if k == 0 { "" } else { ", " };
        let x = (k % 1999) as f64 / 1000.0 - 0.9995;
        write!(text, r#"{sep}{{"p": [{x:.7}, 0.1234567, {:.7}]}}"#, -x).unwrap();
    }
    text.push_str("]}");
    let points = load_within("points.json", &text, 4.0, |p| load_points(p, 1)).unwrap();
    assert_eq!(points.len(), 200_000);
}

/// Where one small value goes (a light, one vertex, one point), a
/// 4 MB array is refused past `SMALL_VALUES` values, at its place, with a
/// peak of the text and at most 65,536 values of tree (3 MB), under 2×.
fn a_huge_small_part_is_refused_without_building_it() {
    let huge = format!("[{}]", vec!["0"; 2_000_000].join(","));
    let cases = [
        (
            format!(r#"{{"light": {huge}, "meshes": []}}"#),
            "huge-light.json: light: holds more than 65536 JSON values, far more than it can",
        ),
        (
            format!(
                r#"{{"light": {{"type": "point", "position": [0, 1, 0]}}, "meshes": [{{"positions": [[0, 0, 0], {huge}], "triangles": []}}]}}"#
            ),
            "huge-light.json: meshes[0].positions[1]: holds more than 65536 JSON values, far more than it can",
        ),
    ];
    for (text, want) in cases {
        let msg = load_within("huge-light.json", &text, 2.0, load_scene)
            .unwrap_err()
            .to_string();
        assert!(msg.ends_with(want), "{msg}");
    }
}
