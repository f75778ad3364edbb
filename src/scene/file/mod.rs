//! The scene file and the points file (JSON), with OBJ
//! meshes.
//!
//! # Scene file
//!
//! ```json
//! {
//!   "camera": {"eye": [0,3,6], "target": [0,0,0], "up": [0,1,0],
//!              "fov_y_deg": 45, "width": 512, "height": 512},
//!   "light":  {"type": "sphere", "center": [0,5,0], "radius": 0.5},
//!   "meshes": [
//!     {"name": "floor", "positions": [[-3,0,3],[3,0,3],[3,0,-3]], "triangles": [[0,1,2]]},
//!     {"name": "bunny", "obj": "bunny.obj",
//!      "transform": {"scale": 1.0, "rotate_y_deg": 0, "translate": [0,0,0]}},
//!     {"name": "ball",  "primitive": {"type": "sphere", "center": [0,1,0],
//!                                      "radius": 1, "segments": 32}}
//!   ]
//! }
//! ```
//!
//! - `light` (required): `{"type": "sphere", "center", "radius"}`,
//!   `{"type": "disk", "center", "normal", "radius"}`,
//!   `{"type": "rect", "center", "u", "v"}` (half-axes),
//!   `{"type": "segment", "a", "b"}` or `{"type": "point", "position"}`,
//!   validated by the [`Light`] constructors.
//! - `meshes` (required, may be empty): object id = index in the list. Each
//!   has an optional `name` (default `mesh<i>`), exactly one source —
//!   `positions` with `triangles` (0-based indices), `obj` (a path relative
//!   to the scene file's directory; every object and group of the file
//!   merged into one mesh, polygons fan-triangulated), or `primitive`
//!   (`{"type": "sphere", "center", "radius", "segments"}` with `segments`
//!   defaulting to 32, `{"type": "box", "min", "max"}`,
//!   `{"type": "quad", "center", "u", "v"}`; see [`primitive`])
//!   — and an optional `transform` `{"scale", "rotate_y_deg", "translate"}`
//!   (defaults 1, 0, `[0,0,0]`; see [`Transform`]). A mesh must have at
//!   least one triangle.
//! - `camera` (optional): `eye` and `target` required; `up` defaults to
//!   `[0,1,0]`, `fov_y_deg` to 45, `width` and `height` to 512 (at most
//!   [`MAX_IMAGE_SIDE`]).
//!
//! # Points file
//!
//! `{"points": [{"p": [x,y,z], "object": 0, "normal": [0,1,0]}, …]}` →
//! [`Receiver`]s. `object` and `normal` are optional; `object` must be the
//! index of one of the scene's meshes, `normal` non-zero (it is
//! normalised). An empty list is allowed and gives no receivers. Whether a
//! receiver lies inside the light is the query's business
//! ([`Light::emitter`](super::Light::emitter)), not the file's.
//!
//! # Numbers
//!
//! Every number is read correctly rounded: the double nearest the literal
//! (ties to even), whatever its number of digits, so that a file written
//! with 17 significant digits, or by any shortest-round-trip printer,
//! reads back as the doubles it was written from.
//!
//! # Errors
//!
//! Every problem is a [`FileError`], displayed on one line as
//! `FILE: PLACE: MESSAGE`, where PLACE is the JSON path of the offending
//! field (`meshes[2].triangles[5][1]`), or `FILE:LINE:COLUMN: MESSAGE` for
//! a syntax error or a byte that is not UTF-8, or `FILE: MESSAGE` for the
//! file as a whole (missing, empty, UTF-16). For example
//! `scene.json: meshes[1].primitive.radius: must be positive, got -1`.
//! Unknown keys and duplicate keys are errors (a misspelt optional key
//! would otherwise be silently ignored). JSON cannot hold NaN or infinity,
//! and a literal too large for an `f64` (`1e999`) is a syntax error, so
//! every number read is finite; values that overflow later (a transform
//! moving a vertex past `f64::MAX`) are reported at the field that did it.
//! A UTF-8 byte-order mark at the start is skipped.
//!
//! # Reading
//!
//! Both files are read as streams over their text: the top-level keys in
//! file order, each mesh as it comes, the vertex, triangle and point lists
//! one item at a time straight into the meshes and receivers. The peak is
//! the text and what it makes (a scene of inline meshes about 1.7× its
//! size, a points file about 3×), never a tree of the whole file, and an
//! error is found where it is — after whatever came before it in the
//! file, in file order. One small part (a light, a camera, a primitive, a
//! transform, one vertex, triangle or point) is read whole, and holds at
//! most 65,536 JSON values.
//!
//! [`Light`]: crate::scene::Light
//! [`primitive`]: crate::scene::primitive
//! [`Transform`]: crate::scene::primitive::Transform

mod error;
mod input;
mod json;
mod obj;
mod parts;
mod points;
mod scene;

pub use error::{FileError, Place};
pub use input::{read_input, InputError, MAX_OBJ_BYTES, MAX_TEXT_BYTES};
pub use obj::mesh_from_obj;
pub use points::{receiver_from, ReceiverField, DOMAIN};

use crate::scene::{Receiver, Scene};
use error::*;
use json::Cx;
use points::*;
use scene::*;
use std::path::Path;

/// The largest camera `width` or `height` a scene file may ask for.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// The number of longitudes of a sphere primitive without `segments`.
pub const DEFAULT_SEGMENTS: u32 = 32;

/// Loads a scene file; `obj` paths are relative to its directory.
///
/// The file is read as a stream: its meshes' vertex and triangle lists go
/// straight into the meshes, never into a tree of the whole file, so the
/// peak is about the meshes themselves (a 50 MB file of inline meshes
/// peaked at 835 MB before anything was checked; see the README).
///
/// # Errors
/// [`FileError`] for a missing or unreadable file and for every problem of
/// [`scene_from_str`].
pub fn load_scene(path: &Path) -> Result<Scene, FileError> {
    let name = path.display().to_string();
    let base = path.parent().unwrap_or(Path::new(""));
    let cx = Cx::new(&name);
    read_json(&cx, path, |de| scene_from(&cx, de, base))
}

/// Parses a scene file's text; `name` is used in error messages only, and
/// `obj` paths are relative to `base_dir`.
///
/// # Errors
/// [`FileError`] (see the module documentation) for malformed JSON, an
/// empty text, unknown or duplicate keys, a missing required field, a
/// value of the wrong kind or arity, an index out of range, a degenerate
/// light, primitive, transform or camera, a missing or malformed OBJ file,
/// and a mesh without triangles.
pub fn scene_from_str(name: &str, text: &str, base_dir: &Path) -> Result<Scene, FileError> {
    let cx = Cx::new(name);
    let text = text.strip_prefix(BOM).unwrap_or(text);
    scene_from(&cx, &mut serde_json::Deserializer::from_str(text), base_dir)
}

/// Loads a points file for a scene of `mesh_count` meshes (the bound on
/// each receiver's `object`).
///
/// # Errors
/// [`FileError`] for a missing or unreadable file and for every problem of
/// [`points_from_str`].
pub fn load_points(path: &Path, mesh_count: usize) -> Result<Vec<Receiver>, FileError> {
    let name = path.display().to_string();
    let cx = Cx::new(&name);
    read_json(&cx, path, |de| points_from(&cx, de, mesh_count))
}

/// Parses a points file's text for a scene of `mesh_count` meshes; `name`
/// is used in error messages only. An empty `points` list gives an empty
/// vector. Each receiver's `object`, when given, is less than
/// `mesh_count`; its `normal`, when given, is a unit vector.
///
/// # Errors
/// [`FileError`] for malformed JSON, an empty text, unknown or duplicate
/// keys, a missing `points` or `p`, a value of the wrong kind or arity, an
/// `object` not below `mesh_count`, a zero `normal`.
pub fn points_from_str(
    name: &str,
    text: &str,
    mesh_count: usize,
) -> Result<Vec<Receiver>, FileError> {
    let cx = Cx::new(name);
    let text = text.strip_prefix(BOM).unwrap_or(text);
    points_from(
        &cx,
        &mut serde_json::Deserializer::from_str(text),
        mesh_count,
    )
}

/// The UTF-8 byte-order mark, which a JSON reader may skip (RFC 8259 §8.1)
/// and some editors write.
const BOM: &str = "\u{feff}";

/// A scene or points file at `path` (a regular file within
/// [`MAX_TEXT_BYTES`]) walked by `walk`: its text checked as UTF-8 (the
/// first byte that is not is reported at its line and column), a UTF-8
/// byte-order mark skipped, a UTF-16 one refused by name.
fn read_json<T>(
    cx: &Cx<'_>,
    path: &Path,
    walk: impl FnOnce(
        &mut serde_json::Deserializer<serde_json::de::StrRead<'_>>,
    ) -> Result<T, FileError>,
) -> Result<T, FileError> {
    let bytes = read_input(path, MAX_TEXT_BYTES).map_err(|e| whole(cx.file, e.to_string()))?;
    let text = text_of(cx, &bytes)?;
    walk(&mut serde_json::Deserializer::from_str(text))
}

/// An input's bytes as text: UTF-8, a byte-order mark skipped.
fn text_of<'b>(cx: &Cx<'_>, bytes: &'b [u8]) -> Result<&'b str, FileError> {
    if bytes.starts_with(&[0xff, 0xfe]) || bytes.starts_with(&[0xfe, 0xff]) {
        return Err(whole(
            cx.file,
            "is UTF-16 (it starts with a UTF-16 byte-order mark); save it as UTF-8".to_owned(),
        ));
    }
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let at = e.valid_up_to();
        let (line, column) = line_column(&bytes[..at]);
        FileError {
            file: cx.file.to_owned(),
            place: Place::Position { line, column },
            message: format!(
                "not valid UTF-8 (byte 0x{:02X}; the file must be UTF-8, not Latin-1 or another encoding)",
                bytes[at]
            ),
        }
    })?;
    Ok(text.strip_prefix(BOM).unwrap_or(text))
}

/// The 1-based line and column (in bytes, as serde_json counts them) of
/// the byte just after `before`.
fn line_column(before: &[u8]) -> (usize, usize) {
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let line = 1 + before.iter().filter(|&&b| b == b'\n').count();
    (line, before.len() - line_start + 1)
}
