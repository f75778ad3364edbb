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

mod json;

use super::primitive::{self, axis_name, PrimitiveError, Transform};
use super::{Camera, CameraError, Light, LightError, Mesh, MeshError, Receiver, Scene};
use glam::DVec3;
use json::{Array, At, Cx, Entries, Items, Json, Object};
use serde::de::{MapAccess, SeqAccess};
use std::borrow::Cow;
use std::fmt;
use std::path::Path;

/// The largest camera `width` or `height` a scene file may ask for.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// The number of longitudes of a sphere primitive without `segments`.
pub const DEFAULT_SEGMENTS: u32 = 32;

/// Where in a file a [`FileError`] is.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Place {
    /// The file as a whole (missing, empty, UTF-16, not an OBJ mesh).
    Whole,
    /// A syntax error at a 1-based line and column.
    Position {
        /// Line, from 1.
        line: usize,
        /// Column, from 1 (0 at the very start of an empty line).
        column: usize,
    },
    /// A JSON path to the offending field, such as
    /// `meshes[2].triangles[5][1]`.
    Path(String),
}

/// A scene, points or OBJ file that could not be loaded.
///
/// Displayed on one line (control characters escaped) as
/// `FILE: PATH: MESSAGE`, `FILE:LINE:COLUMN: MESSAGE` or `FILE: MESSAGE`,
/// following [`Place`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileError {
    file: String,
    place: Place,
    message: String,
}

impl FileError {
    /// The file's name as given.
    #[must_use]
    pub fn file(&self) -> &str {
        &self.file
    }

    /// Where in the file.
    #[must_use]
    pub fn place(&self) -> &Place {
        &self.place
    }

    /// What is wrong, without the file and the place.
    #[must_use]
    pub fn message(&self) -> &str {
        &self.message
    }
}

/// The longest prefix of `s` of at most `max` bytes that ends on a
/// character boundary.
fn prefix(s: &str, max: usize) -> &str {
    let end = (0..=max.min(s.len()))
        .rev()
        .find(|&i| s.is_char_boundary(i))
        .unwrap_or(0);
    &s[..end]
}

/// `s` cut to about `max` bytes at its end, with what was cut counted.
fn clip_end(s: &str, max: usize) -> Cow<'_, str> {
    if s.len() <= max {
        return Cow::Borrowed(s);
    }
    let kept = prefix(s, max);
    Cow::Owned(format!("{kept}… ({} more bytes)", s.len() - kept.len()))
}

/// `s` cut to about `max` bytes at its start (a path keeps its file name).
fn clip_start(s: &str, max: usize) -> Cow<'_, str> {
    if s.len() <= max {
        return Cow::Borrowed(s);
    }
    let from = (s.len() - max..s.len())
        .find(|&i| s.is_char_boundary(i))
        .unwrap_or(s.len());
    Cow::Owned(format!("…{}", &s[from..]))
}

/// A path for a message: its display, cut to its last 160 bytes.
fn short_path(path: &Path) -> String {
    clip_start(&path.display().to_string(), 160).into_owned()
}

/// `s` with control characters (newlines included) escaped, so that a
/// message stays on one line whatever a file name or key holds.
fn one_line(s: &str) -> Cow<'_, str> {
    if s.chars().any(char::is_control) {
        Cow::Owned(
            s.chars()
                .map(|c| {
                    if c.is_control() {
                        c.escape_default().to_string()
                    } else {
                        c.to_string()
                    }
                })
                .collect(),
        )
    } else {
        Cow::Borrowed(s)
    }
}

impl fmt::Display for FileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // One line of bounded length, whatever the input quoted.
        let file = one_line(&self.file);
        let file = clip_start(&file, 160);
        let message = one_line(&self.message);
        let message = clip_end(&message, 400);
        match &self.place {
            Place::Whole => write!(f, "{file}: {message}"),
            Place::Position { line, column } => write!(f, "{file}:{line}:{column}: {message}"),
            Place::Path(path) => write!(f, "{file}: {}: {message}", clip_end(&one_line(path), 200)),
        }
    }
}

impl std::error::Error for FileError {}

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

/// The scene of a scene file, read as a stream: the top-level keys in
/// file order, each mesh as it comes, its vertex and triangle lists item
/// by item into the mesh (see [`load_scene`]).
fn scene_from<'de, R: serde_json::de::Read<'de>>(
    cx: &Cx<'_>,
    de: &mut serde_json::Deserializer<R>,
    base_dir: &Path,
) -> Result<Scene, FileError> {
    use serde::de::DeserializeSeed as _;
    let top = At::ROOT;
    let seed = Object {
        cx,
        at: &top,
        entries: SceneEntries { cx, base_dir },
    };
    let parts = cx.finish(
        seed.deserialize(&mut *de)
            .and_then(|v| de.end().map(|()| v)),
    )?;
    let light = parts
        .light
        .ok_or_else(|| cx.err(&top.key("light"), "required but missing"))?;
    let Some(meshes) = parts.meshes else {
        return Err(cx.err(&top.key("meshes"), "required but missing"));
    };
    let mut scene = Scene::new(light);
    if let Some(camera) = parts.camera {
        scene = scene.with_camera(camera);
    }
    for (name, mesh) in meshes {
        scene = scene.with_mesh(name, mesh);
    }
    Ok(scene)
}

/// What the top level of a scene file gave.
#[derive(Default)]
struct SceneParts {
    camera: Option<Camera>,
    light: Option<Light>,
    meshes: Option<Vec<(String, Mesh)>>,
}

/// The top level of a scene file.
struct SceneEntries<'c, 'f> {
    cx: &'c Cx<'f>,
    base_dir: &'c Path,
}

impl<'de> Entries<'de> for SceneEntries<'_, '_> {
    type Out = SceneParts;

    fn entries<A: MapAccess<'de>>(self, mut map: A) -> Result<SceneParts, A::Error> {
        const KEYS: &[&str] = &["camera", "light", "meshes"];
        let (cx, top) = (self.cx, At::ROOT);
        let mut parts = SceneParts::default();
        let mut seen = [false; 3];
        while let Some(k) = cx.next_key(&mut map, &top, KEYS, &mut seen)? {
            let at = top.key(KEYS[k]);
            match k {
                0 => {
                    let v = cx.small_value(&mut map, &at)?;
                    parts.camera = Some(cx.camera(&v, &at).map_err(|e| cx.fail(e))?);
                }
                1 => {
                    let v = cx.small_value(&mut map, &at)?;
                    parts.light = Some(cx.light(&v, &at).map_err(|e| cx.fail(e))?);
                }
                _ => {
                    parts.meshes = Some(map.next_value_seed(Array {
                        cx,
                        at: &at,
                        items: MeshList {
                            cx,
                            at: &at,
                            base_dir: self.base_dir,
                        },
                    })?);
                }
            }
        }
        Ok(parts)
    }
}

/// The `meshes` list, one mesh at a time.
struct MeshList<'c, 'f, 'a> {
    cx: &'c Cx<'f>,
    at: &'a At<'a>,
    base_dir: &'c Path,
}

impl<'de> Items<'de> for MeshList<'_, '_, '_> {
    type Out = Vec<(String, Mesh)>;

    fn items<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Out, A::Error> {
        let mut meshes = Vec::new();
        loop {
            let at = self.at.index(meshes.len());
            let seed = Object {
                cx: self.cx,
                at: &at,
                entries: MeshEntries {
                    cx: self.cx,
                    at: &at,
                    index: meshes.len(),
                    base_dir: self.base_dir,
                },
            };
            match seq.next_element_seed(seed)? {
                Some(mesh) => meshes.push(mesh),
                None => return Ok(meshes),
            }
        }
    }
}

/// One mesh of the `meshes` list.
struct MeshEntries<'c, 'f, 'a> {
    cx: &'c Cx<'f>,
    at: &'a At<'a>,
    index: usize,
    base_dir: &'c Path,
}

/// A mesh's `triangles` as read: the indices (those beyond `u32` kept as
/// `u32::MAX`, the first of them with its value), checked against the
/// vertex count once the mesh is read.
struct Triangles {
    indices: Vec<[u32; 3]>,
    /// The first index beyond `u32`: triangle, corner, value.
    wide: Option<(usize, usize, u64)>,
}

impl<'de> Entries<'de> for MeshEntries<'_, '_, '_> {
    type Out = (String, Mesh);

    fn entries<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Out, A::Error> {
        const KEYS: &[&str] = &[
            "name",
            "positions",
            "triangles",
            "obj",
            "primitive",
            "transform",
        ];
        let (cx, at) = (self.cx, self.at);
        let mut seen = [false; 6];
        let mut name = None;
        let mut positions: Option<Vec<DVec3>> = None;
        let mut triangles: Option<Triangles> = None;
        let mut small: [Option<Json>; 3] = [None, None, None]; // obj, primitive, transform
        while let Some(k) = cx.next_key(&mut map, at, KEYS, &mut seen)? {
            let key_at = at.key(KEYS[k]);
            match k {
                0 => {
                    let v = cx.small_value(&mut map, &key_at)?;
                    name = Some(cx.string(&v, &key_at).map_err(|e| cx.fail(e))?.to_owned());
                }
                1 => {
                    let each = |v: &Json, at: &At, _| cx.vec3(v, at);
                    positions = Some(map.next_value_seed(list(cx, &key_at, each))?);
                }
                2 => {
                    let mut wide = None;
                    let each = |v: &Json, at: &At, t| triangle(cx, v, at, t, &mut wide);
                    let indices = map.next_value_seed(list(cx, &key_at, each))?;
                    triangles = Some(Triangles { indices, wide });
                }
                _ => small[k - 3] = Some(cx.small_value(&mut map, &key_at)?),
            }
        }
        let name = name.unwrap_or_else(|| format!("mesh{}", self.index));
        let [obj, primitive, transform] = small;
        cx.mesh(
            at,
            MeshParts {
                positions,
                triangles,
                obj,
                primitive,
                transform,
            },
            self.base_dir,
        )
        .map(|mesh| (name, mesh))
        .map_err(|e| cx.fail(e))
    }
}

/// A mesh's parts as read from the file, checked together once its
/// object is closed.
struct MeshParts {
    positions: Option<Vec<DVec3>>,
    triangles: Option<Triangles>,
    obj: Option<Json>,
    primitive: Option<Json>,
    transform: Option<Json>,
}

/// A list of small items (vertices, triangles, points), one at a time:
/// each read as a [`Json`] tree within its budget and made into a `T` by
/// `each` (given the item, its place and its index) before the next is
/// read.
struct Each<'c, 'f, 'a, F> {
    cx: &'c Cx<'f>,
    at: &'a At<'a>,
    each: F,
}

impl<'de, T, F: FnMut(&Json, &At, usize) -> Result<T, FileError>> Items<'de>
    for Each<'_, '_, '_, F>
{
    type Out = Vec<T>;

    fn items<A: SeqAccess<'de>>(mut self, mut seq: A) -> Result<Vec<T>, A::Error> {
        let cx = self.cx;
        let mut out = Vec::new();
        loop {
            let at = self.at.index(out.len());
            let Some(v) = cx.small_item(&mut seq, &at)? else {
                out.shrink_to_fit();
                return Ok(out);
            };
            out.push((self.each)(&v, &at, out.len()).map_err(|e| cx.fail(e))?);
        }
    }
}

/// The streamed list at `at` whose items `each` makes into `T`s.
fn list<'c, 'f, 'a, T, F>(
    cx: &'c Cx<'f>,
    at: &'a At<'a>,
    each: F,
) -> Array<'c, 'f, 'a, Each<'c, 'f, 'a, F>>
where
    F: FnMut(&Json, &At, usize) -> Result<T, FileError>,
{
    Array {
        cx,
        at,
        items: Each { cx, at, each },
    }
}

/// One triangle of a mesh's `triangles`: `[i, j, k]` of non-negative
/// integers, an index beyond `u32` kept as `u32::MAX` and the first of
/// them recorded in `wide` (triangle, corner, value).
fn triangle(
    cx: &Cx<'_>,
    v: &Json,
    at: &At,
    t: usize,
    wide: &mut Option<(usize, usize, u64)>,
) -> Result<[u32; 3], FileError> {
    let items = match v {
        Json::Array(items) if items.len() == 3 => items,
        _ => {
            return Err(cx.err(
                at,
                format!(
                    "expected [i, j, k] (3 vertex indices), got {}",
                    v.describe()
                ),
            ))
        }
    };
    let mut tri = [0u32; 3];
    for (c, slot) in tri.iter_mut().enumerate() {
        let i = cx.uint(&items[c], &at.index(c))?;
        *slot = u32::try_from(i).unwrap_or_else(|_| {
            wide.get_or_insert((t, c, i));
            u32::MAX
        });
    }
    Ok(tri)
}

/// The points of a points file, read as a stream: one point's JSON at a
/// time becomes a [`Receiver`], so the peak is the receivers themselves
/// (about 64 bytes a point) and not a tree of the whole file (10⁷ points
/// took 5.25 GB for a 250 MB file). The messages are those of the rest of
/// the loader: a JSON error at its line and column, a bad point at its
/// path (`points[3].normal`).
fn points_from<'de, R: serde_json::de::Read<'de>>(
    cx: &Cx<'_>,
    de: &mut serde_json::Deserializer<R>,
    mesh_count: usize,
) -> Result<Vec<Receiver>, FileError> {
    use serde::de::DeserializeSeed as _;
    let top = At::ROOT;
    let seed = Object {
        cx,
        at: &top,
        entries: PointsEntries { cx, mesh_count },
    };
    cx.finish(
        seed.deserialize(&mut *de)
            .and_then(|v| de.end().map(|()| v)),
    )?
    .ok_or_else(|| cx.err(&top.key("points"), "required but missing"))
}

/// The top level of a points file.
struct PointsEntries<'c, 'f> {
    cx: &'c Cx<'f>,
    mesh_count: usize,
}

impl<'de> Entries<'de> for PointsEntries<'_, '_> {
    type Out = Option<Vec<Receiver>>;

    fn entries<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Out, A::Error> {
        let (cx, top) = (self.cx, At::ROOT);
        let (mut points, mut seen) = (None, [false]);
        while cx
            .next_key(&mut map, &top, &["points"], &mut seen)?
            .is_some()
        {
            let at = top.key("points");
            let each = |v: &Json, at: &At, _| point(cx, v, at, self.mesh_count);
            points = Some(map.next_value_seed(list(cx, &at, each))?);
        }
        Ok(points)
    }
}

/// One point of a points file.
fn point(cx: &Cx<'_>, v: &Json, at: &At<'_>, mesh_count: usize) -> Result<Receiver, FileError> {
    let f = cx.object(v, at, &["p", "object", "normal"])?;
    let p = cx.vec3(cx.required(&f, at, "p")?, &at.key("p"))?;
    let object = match f.get("object") {
        None => None,
        Some(v) => {
            let at = at.key("object");
            let id = cx.uint(v, &at)?;
            match u32::try_from(id) {
                Ok(id) if (id as usize) < mesh_count => Some(id),
                _ => {
                    return Err(cx.err(
                        &at,
                        format!(
                            "{id} is out of range (the scene has {mesh_count} mesh{})",
                            if mesh_count == 1 { "" } else { "es" }
                        ),
                    ))
                }
            }
        }
    };
    let normal = match f.get("normal") {
        None => None,
        Some(v) => {
            let at = at.key("normal");
            let n = cx.vec3(v, &at)?;
            Some(crate::kernel::eft::unit(n).ok_or_else(|| cx.err(&at, "has zero length"))?)
        }
    };
    Ok(Receiver {
        position: p,
        normal,
        object,
    })
}

/// Parses an OBJ file's bytes into one mesh: every object and group merged,
/// polygons fan-triangulated, points and lines ignored, materials ignored.
/// `name` is used in error messages only.
///
/// # Errors
/// [`FileError`] (place [`Place::Whole`]) for an OBJ syntax error (tobj's
/// message: it gives no line), a vertex that is not finite, and a
/// file without faces.
pub fn mesh_from_obj(name: &str, bytes: &[u8]) -> Result<Mesh, FileError> {
    obj_mesh(bytes).map_err(|message| whole(name, message))
}

/// The largest magnitude of any number in a scene or points file, and of
/// any vertex a primitive, transform or OBJ file makes: `1e30`, the domain
/// in which the exact orientation predicates (products of three coordinate
/// differences) are exact, and so the exact reference and every method
/// right to their documented accuracy. A file beyond it is refused, naming
/// the field and the value, rather than answered wrongly.
pub const DOMAIN: f64 = 1e30;

/// The largest scene, points or report JSON file read (256 MiB).
pub const MAX_TEXT_BYTES: u64 = 256 << 20;

/// The largest OBJ file read (1 GiB).
pub const MAX_OBJ_BYTES: u64 = 1 << 30;

/// Why an input file could not be read ([`read_input`]); displayed as
/// one line.
#[derive(Debug)]
#[non_exhaustive]
pub enum InputError {
    /// The path is a directory.
    Directory,
    /// The path is a device, FIFO or socket, not a regular file.
    NotRegular,
    /// The file is longer than the limit, or grew past it while being read.
    TooLarge {
        /// Its length (at least; `limit + 1` when it grew while read).
        bytes: u64,
        /// The limit.
        limit: u64,
    },
    /// The system could not open or read it.
    Io(std::io::Error),
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InputError::Directory => write!(f, "not a regular file (a directory)"),
            InputError::NotRegular => {
                write!(f, "not a regular file (a device, FIFO or socket)")
            }
            InputError::TooLarge { bytes, limit } => {
                write!(f, "{bytes} bytes or more, over the limit of {limit} bytes")
            }
            InputError::Io(e) => write!(f, "cannot read: {e}"),
        }
    }
}

impl std::error::Error for InputError {}

/// The bytes of the regular file at `path`, at most `limit` of them.
///
/// Devices (`/dev/zero`), FIFOs, sockets and directories are refused before
/// they are opened (opening a FIFO would block until a writer comes), and
/// a file longer than `limit` — or one that grows past it while being read
/// — is refused rather than read whole.
///
/// # Errors
/// [`InputError`]: what the path is instead of a regular file, its size
/// against the limit, or the I/O error.
pub fn read_input(path: &Path, limit: u64) -> Result<Vec<u8>, InputError> {
    let (file, len) = open_input(path, limit)?;
    read_all(file, limit, len)
}

/// The bytes of an opened input of `len` bytes (as its metadata says), at
/// most `limit` of them, in a buffer of that size (not one doubled as it
/// grows).
fn read_all(file: std::fs::File, limit: u64, len: u64) -> Result<Vec<u8>, InputError> {
    use std::io::Read as _;
    let mut bytes = Vec::with_capacity(usize::try_from(len.min(limit) + 1).unwrap_or(0));
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(InputError::Io)?;
    if bytes.len() as u64 > limit {
        return Err(InputError::TooLarge {
            bytes: limit + 1,
            limit,
        });
    }
    Ok(bytes)
}

/// The regular file at `path`, opened, and its length (see [`read_input`]).
fn open_input(path: &Path, limit: u64) -> Result<(std::fs::File, u64), InputError> {
    let meta = std::fs::metadata(path).map_err(InputError::Io)?;
    let kind = meta.file_type();
    if kind.is_dir() {
        return Err(InputError::Directory);
    }
    if !kind.is_file() {
        return Err(InputError::NotRegular);
    }
    if meta.len() > limit {
        return Err(InputError::TooLarge {
            bytes: meta.len(),
            limit,
        });
    }
    let file = std::fs::File::open(path).map_err(InputError::Io)?;
    Ok((file, meta.len()))
}

/// An error about the whole file `name`.
pub(super) fn whole(name: &str, message: String) -> FileError {
    FileError {
        file: name.to_owned(),
        place: Place::Whole,
        message,
    }
}

fn obj_mesh(bytes: &[u8]) -> Result<Mesh, String> {
    // The struct update keeps this compiling when another crate enables
    // tobj's `merging` or `reordering` features (more fields, all false).
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    // tobj reads lines as UTF-8 and fails on any other byte, even in a
    // comment, with "read error": bytes that are not UTF-8 become U+FFFD
    // here, harmless in a comment or a name, an error at their line
    // elsewhere.
    let text = String::from_utf8_lossy(bytes);
    let mut reader = std::io::Cursor::new(text.as_bytes());
    let (models, _) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| {
        // tobj stops at the line it could not read: the last one taken.
        let taken = &text.as_bytes()[..reader.position() as usize];
        let line =
            taken.iter().filter(|&&b| b == b'\n').count() + usize::from(!taken.ends_with(b"\n"));
        obj_error(&text, line, &e)
    })?;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for model in &models {
        let base = u32::try_from(positions.len()).map_err(|_| "too many vertices".to_owned())?;
        positions.extend(
            model
                .mesh
                .positions
                .chunks_exact(3)
                .map(|c| DVec3::new(c[0], c[1], c[2])),
        );
        for t in model.mesh.indices.chunks_exact(3) {
            let shifted = [t[0], t[1], t[2]].map(|i| i.checked_add(base));
            match shifted {
                [Some(a), Some(b), Some(c)] => triangles.push([a, b, c]),
                _ => return Err("too many vertices".to_owned()),
            }
        }
    }
    if triangles.is_empty() {
        return Err("has no faces".to_owned());
    }
    Mesh::new(positions, triangles).map_err(|e| match e {
        MeshError::NonFinitePosition { vertex } => {
            format!("vertex {vertex} (after merging objects) is not finite")
        }
        e => e.to_string(),
    })
}

/// A one-line message for tobj's error `e`, at `line` (where tobj
/// stopped) or, for a face index out of range — which tobj finds only
/// when it closes an object — at the first face line that has one.
fn obj_error(text: &str, line: usize, e: &tobj::LoadError) -> String {
    use tobj::LoadError as E;
    let what = match e {
        E::PositionParseError => "a vertex (v) that is not 3 or 4 numbers",
        E::NormalParseError => "a normal (vn) that is not 3 numbers",
        E::TexcoordParseError => "a texture coordinate (vt) that cannot be read",
        E::FaceParseError => "a face (f) that cannot be read",
        E::FaceVertexOutOfBounds => {
            let line = bad_face_line(text).unwrap_or(line);
            return format!("line {line}: a face (f) names a vertex that does not exist");
        }
        E::FaceTexCoordOutOfBounds | E::FaceNormalOutOfBounds | E::FaceColorOutOfBounds => {
            return format!("OBJ: {e}");
        }
        _ => return format!("line {line}: {e} (OBJ)"),
    };
    format!("line {line}: {what}")
}

/// The 1-based line of the first face whose vertex index is 0, beyond
/// the vertices of the file (positive) or before its first vertex
/// (negative, counted back from the vertices so far).
fn bad_face_line(text: &str) -> Option<usize> {
    let total = text
        .lines()
        .filter(|l| l.split_whitespace().next() == Some("v"))
        .count() as i64;
    let mut vertices = 0i64;
    for (k, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => vertices += 1,
            Some("f") => {
                let bad = words.any(|w| {
                    let i: i64 = w
                        .split('/')
                        .next()
                        .and_then(|i| i.parse().ok())
                        .unwrap_or(0);
                    i == 0 || i > total || -i > vertices
                });
                if bad {
                    return Some(k + 1);
                }
            }
            _ => {}
        }
    }
    None
}

/// The scene file's parts, read with the generic accessors of `json`.
impl Cx<'_> {
    fn camera(&self, v: &Json, at: &At) -> Result<Camera, FileError> {
        let f = self.object(
            v,
            at,
            &["eye", "target", "up", "fov_y_deg", "width", "height"],
        )?;
        let eye = self.vec3(self.required(&f, at, "eye")?, &at.key("eye"))?;
        let target = self.vec3(self.required(&f, at, "target")?, &at.key("target"))?;
        let up = self.optional_vec3(&f, at, "up", DVec3::Y)?;
        let fov = match f.get("fov_y_deg") {
            Some(v) => self.number(v, &at.key("fov_y_deg"))?,
            None => 45.0,
        };
        let side = |key: &'static str| -> Result<u32, FileError> {
            let Some(v) = f.get(key) else { return Ok(512) };
            let at = at.key(key);
            let n = self.uint(v, &at)?;
            match u32::try_from(n) {
                Ok(n) if (1..=MAX_IMAGE_SIDE).contains(&n) => Ok(n),
                _ => Err(self.err(&at, format!("must be in 1..={MAX_IMAGE_SIDE}, got {n}"))),
            }
        };
        let (width, height) = (side("width")?, side("height")?);
        Camera::new(eye, target, up, fov, width, height).map_err(|e| match e {
            CameraError::NonFinite { field } => self.err(&at.key(field), "not finite"),
            CameraError::FieldOfView { degrees } => self.err(
                &at.key("fov_y_deg"),
                format!("must be in (0, 180) degrees, got {degrees}"),
            ),
            CameraError::Degenerate => self.err(
                at,
                "eye equals target, or up is zero or parallel to the view direction",
            ),
            e => self.err(at, e.to_string()),
        })
    }

    fn light(&self, v: &Json, at: &At) -> Result<Light, FileError> {
        let (ty, f) = self.tagged(
            v,
            at,
            "light",
            &[
                ("sphere", &["type", "center", "radius"]),
                ("disk", &["type", "center", "normal", "radius"]),
                ("rect", &["type", "center", "u", "v"]),
                ("segment", &["type", "a", "b"]),
                ("point", &["type", "position"]),
            ],
        )?;
        let vec = |key: &str| self.vec3(self.required(&f, at, key)?, &at.key(key));
        let num = |key: &str| self.number(self.required(&f, at, key)?, &at.key(key));
        let light = match ty {
            "sphere" => Light::sphere(vec("center")?, num("radius")?),
            "disk" => Light::disk(vec("center")?, vec("normal")?, num("radius")?),
            "rect" => Light::rect(vec("center")?, vec("u")?, vec("v")?),
            "segment" => Light::segment(vec("a")?, vec("b")?),
            _ => Light::point(vec("position")?),
        };
        light.map_err(|e| {
            // Every fault on the one line, located at the first.
            let mut faults = e.faults().iter().map(|fault| self.light_fault(fault, at));
            let mut first = faults.next().unwrap_or_else(|| self.err(at, e.to_string()));
            for other in faults {
                let place = match &other.place {
                    Place::Path(path) => format!("{path}: "),
                    _ => String::new(),
                };
                first.message = format!("{}; {place}{}", first.message, other.message);
            }
            first
        })
    }

    /// One fault of a light, located at its field.
    fn light_fault(&self, e: &LightError, at: &At) -> FileError {
        match e {
            LightError::NonFinite { field } => self.err(&at.key(field), "not finite"),
            LightError::NonPositiveRadius { radius } => {
                self.err(&at.key("radius"), format!("must be positive, got {radius}"))
            }
            LightError::ZeroNormal => self.err(&at.key("normal"), "has zero length"),
            LightError::DegenerateRect => self.err(
                &at.key("v"),
                "spans no area with u (u or v is zero, or they are parallel)",
            ),
            LightError::ZeroLengthSegment => {
                self.err(&at.key("b"), "equals a (the segment has zero length)")
            }
            e => self.err(at, e.to_string()),
        }
    }

    /// A mesh from its parts, once its object is read: exactly one source,
    /// `triangles` only with `positions`, the transform applied, every
    /// vertex within the domain.
    fn mesh(&self, at: &At, parts: MeshParts, base_dir: &Path) -> Result<Mesh, FileError> {
        let MeshParts {
            positions,
            triangles,
            obj,
            primitive,
            transform,
        } = parts;
        let sources: Vec<&str> = [
            ("positions", positions.is_some()),
            ("obj", obj.is_some()),
            ("primitive", primitive.is_some()),
        ]
        .into_iter()
        .filter_map(|(k, given)| given.then_some(k))
        .collect();
        let only_with_positions = |triangles: &Option<Triangles>| match triangles {
            Some(_) => Err(self.err(&at.key("triangles"), "only goes with \"positions\"")),
            None => Ok(()),
        };
        let mesh = match (&sources[..], positions, obj, primitive) {
            (["positions"], Some(positions), _, _) => self.inline_mesh(at, positions, triangles)?,
            (["obj"], _, Some(obj), _) => {
                only_with_positions(&triangles)?;
                let at = at.key("obj");
                let rel = self.string(&obj, &at)?;
                let path = base_dir.join(rel);
                let shown = short_path(&path);
                let bytes = read_input(&path, MAX_OBJ_BYTES)
                    .map_err(|e| self.err(&at, format!("{shown:?}: {e}")))?;
                obj_mesh(&bytes).map_err(|m| self.err(&at, format!("{shown:?}: {m}")))?
            }
            (["primitive"], _, _, Some(primitive)) => {
                only_with_positions(&triangles)?;
                self.primitive(&primitive, &at.key("primitive"))?
            }
            ([first, second, ..], ..) => {
                return Err(self.err(
                    &at.key(second),
                    format!("conflicts with {first:?} (a mesh has exactly one source)"),
                ))
            }
            _ => {
                return Err(self.err(
                    at,
                    "needs one of \"positions\" (with \"triangles\"), \"obj\" or \"primitive\"",
                ))
            }
        };
        let mesh = match transform {
            None => mesh,
            Some(v) => {
                let at = at.key("transform");
                self.transform(&v, &at)?
                    .apply(&mesh)
                    .map_err(|e| self.err(&at, format!("moves a vertex out of range: {e}")))?
            }
        };
        // What a primitive, a transform or an OBJ file made must lie in the
        // domain too.
        if let Some((k, q)) = mesh
            .positions()
            .iter()
            .enumerate()
            .find(|(_, q)| q.abs().max_element() > DOMAIN)
        {
            return Err(self.err(
                at,
                format!(
                    "vertex {k} at [{:e}, {:e}, {:e}] is outside the domain |x| ≤ 1e30 \
                     (where the exact predicates are exact)",
                    q.x, q.y, q.z
                ),
            ));
        }
        Ok(mesh)
    }

    /// A mesh of `positions` and the `triangles` read with them, every
    /// index checked against the vertex count (the first out of range, in
    /// file order, reported).
    fn inline_mesh(
        &self,
        at: &At,
        positions: Vec<DVec3>,
        triangles: Option<Triangles>,
    ) -> Result<Mesh, FileError> {
        let t_at = at.key("triangles");
        let Some(Triangles { indices, wide }) = triangles else {
            return Err(self.err(&t_at, "required with \"positions\""));
        };
        if indices.is_empty() {
            return Err(self.err(&t_at, "must hold at least one triangle"));
        }
        let n = positions.len();
        let beyond = indices.iter().enumerate().find_map(|(t, tri)| {
            let c = tri.iter().position(|&i| i as usize >= n)?;
            Some((t, c, u64::from(tri[c])))
        });
        if let Some((t, c, i)) = beyond {
            // An index beyond u32 was kept as u32::MAX: its own value.
            let i = match wide {
                Some((wt, wc, value)) if (wt, wc) == (t, c) => value,
                _ => i,
            };
            return Err(self.err(
                &t_at.index(t).index(c),
                format!(
                    "vertex index {i} is out of range (the mesh has {n} position{})",
                    if n == 1 { "" } else { "s" }
                ),
            ));
        }
        Mesh::new(positions, indices).map_err(|e| self.err(at, e.to_string()))
    }

    fn primitive(&self, v: &Json, at: &At) -> Result<Mesh, FileError> {
        let (ty, f) = self.tagged(
            v,
            at,
            "primitive",
            &[
                ("sphere", &["type", "center", "radius", "segments"]),
                ("box", &["type", "min", "max"]),
                ("quad", &["type", "center", "u", "v"]),
            ],
        )?;
        let vec = |key: &str| self.vec3(self.required(&f, at, key)?, &at.key(key));
        let mesh = match ty {
            "sphere" => {
                let center = vec("center")?;
                let radius = self.number(self.required(&f, at, "radius")?, &at.key("radius"))?;
                let segments = match f.get("segments") {
                    None => DEFAULT_SEGMENTS,
                    Some(v) => {
                        let s_at = at.key("segments");
                        let s = self.uint(v, &s_at)?;
                        // Out-of-range counts are reported by `sphere`;
                        // beyond u32 they are reported here.
                        u32::try_from(s).map_err(|_| {
                            self.err(
                                &s_at,
                                format!(
                                    "must be in {}..={}, got {s}",
                                    primitive::MIN_SEGMENTS,
                                    primitive::MAX_SEGMENTS
                                ),
                            )
                        })?
                    }
                };
                primitive::sphere(center, radius, segments)
            }
            "box" => primitive::cuboid(vec("min")?, vec("max")?),
            _ => primitive::quad(vec("center")?, vec("u")?, vec("v")?),
        };
        mesh.map_err(|e| self.primitive_error(e, at))
    }

    fn primitive_error(&self, e: PrimitiveError, at: &At) -> FileError {
        match e {
            PrimitiveError::NonFinite { field } => self.err(&at.key(field), "not finite"),
            PrimitiveError::NonPositiveRadius { radius } => {
                self.err(&at.key("radius"), format!("must be positive, got {radius}"))
            }
            PrimitiveError::Segments { segments } => self.err(
                &at.key("segments"),
                format!(
                    "must be in {}..={}, got {segments}",
                    primitive::MIN_SEGMENTS,
                    primitive::MAX_SEGMENTS
                ),
            ),
            PrimitiveError::EmptyBox { axis, min, max } => self.err(
                &at.key("max"),
                format!(
                    "must exceed min in every coordinate, got {} {max} <= {min}",
                    axis_name(axis)
                ),
            ),
            PrimitiveError::DegenerateQuad => self.err(
                &at.key("v"),
                "spans no area with u (u or v is zero, or they are parallel)",
            ),
            PrimitiveError::NonPositiveScale { scale } => {
                self.err(&at.key("scale"), format!("must be positive, got {scale}"))
            }
            e => self.err(at, e.to_string()),
        }
    }

    fn transform(&self, v: &Json, at: &At) -> Result<Transform, FileError> {
        let f = self.object(v, at, &["scale", "rotate_y_deg", "translate"])?;
        let num = |key: &str, default: f64| {
            f.get(key)
                .map_or(Ok(default), |v| self.number(v, &at.key(key)))
        };
        let scale = num("scale", 1.0)?;
        let rotate = num("rotate_y_deg", 0.0)?;
        let translate = self.optional_vec3(&f, at, "translate", DVec3::ZERO)?;
        Transform::new(scale, rotate, translate).map_err(|e| self.primitive_error(e, at))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_stay_on_one_line() {
        let e = FileError {
            file: "a\nb.json".to_owned(),
            place: Place::Path("x".to_owned()),
            message: "bad\r\nthing".to_owned(),
        };
        assert_eq!(e.to_string(), "a\\nb.json: x: bad\\r\\nthing");
    }

    #[test]
    fn inputs_that_cannot_be_read_are_typed_errors() {
        let dir = std::env::temp_dir().join(format!("softshadow-input-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("ten.txt");
        std::fs::write(&file, b"0123456789").unwrap();
        assert_eq!(read_input(&file, 10).unwrap(), b"0123456789");
        let e = read_input(&file, 9).unwrap_err();
        assert!(
            matches!(
                e,
                InputError::TooLarge {
                    bytes: 10,
                    limit: 9
                }
            ),
            "{e:?}"
        );
        assert_eq!(e.to_string(), "10 bytes or more, over the limit of 9 bytes");
        assert!(matches!(
            read_input(&dir, 1 << 20),
            Err(InputError::Directory)
        ));
        let missing = read_input(&dir.join("missing"), 1 << 20).unwrap_err();
        assert!(
            matches!(&missing, InputError::Io(io) if io.kind() == std::io::ErrorKind::NotFound),
            "{missing:?}"
        );
        #[cfg(unix)]
        assert!(matches!(
            read_input(Path::new("/dev/null"), 1 << 20),
            Err(InputError::NotRegular)
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
