//! The scene and points file parsers on fuzzed text: no panic; an error
//! is one line naming the file; a scene that parses is finite and
//! consistent (every mesh finite with indices in range, a valid light, a
//! camera that can cast its rays), and points that parse are finite, with
//! unit normals and object ids below the mesh count.
//!
//! The input is read as UTF-8 (lossily); the first byte picks the parser
//! (even: scene; odd: points, for `pick / 2 % 8` meshes). A
//! seed corpus of valid files is worth giving (`examples/scenes/*.json`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use softshadow::scene::file::{points_from_str, scene_from_str};
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let text = String::from_utf8_lossy(rest);
    if pick % 2 == 0 {
        match scene_from_str("fuzz.json", &text, Path::new("/nonexistent")) {
            Ok(scene) => {
                for mesh in scene.meshes() {
                    let n = mesh.positions().len();
                    assert!(mesh.positions().iter().all(|p| p.is_finite()));
                    assert!(mesh.triangles().iter().flatten().all(|&i| (i as usize) < n));
                }
                assert!(scene.light().center().is_finite());
                if let Some((lo, hi)) = scene.bounds() {
                    assert!(lo.is_finite() && hi.is_finite() && lo.cmple(hi).all());
                }
                if let Some(camera) = scene.camera() {
                    let (w, h) = camera.resolution();
                    let (o, d) = camera.primary_ray(w - 1, h - 1);
                    assert!(o.is_finite() && d.is_finite());
                }
            }
            Err(e) => {
                let line = e.to_string();
                assert!(!line.contains('\n'), "{line:?}");
                assert!(line.starts_with("fuzz.json"), "{line:?}");
            }
        }
    } else {
        let meshes = usize::from(pick / 2 % 8);
        match points_from_str("points.json", &text, meshes) {
            Ok(points) => {
                for r in points {
                    assert!(r.position.is_finite());
                    if let Some(n) = r.normal {
                        assert!((n.length() - 1.0).abs() < 1e-9, "{n}");
                    }
                    if let Some(o) = r.object {
                        assert!((o as usize) < meshes);
                    }
                }
            }
            Err(e) => {
                let line = e.to_string();
                assert!(!line.contains('\n'), "{line:?}");
                assert!(line.starts_with("points.json"), "{line:?}");
            }
        }
    }
});
