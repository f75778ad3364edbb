//! The scene file's structure, streamed: its entries, its meshes' lists
//! of vertices and triangles.

use super::error::FileError;
use super::json::{Array, At, Cx, Entries, Items, Json, Object};
use crate::scene::{Camera, Light, Mesh, Scene};
use glam::DVec3;
use serde::de::{MapAccess, SeqAccess};
use std::path::Path;

/// The scene of a scene file, read as a stream: the top-level keys in
/// file order, each mesh as it comes, its vertex and triangle lists item
/// by item into the mesh (see [`load_scene`](super::load_scene)).
pub(super) fn scene_from<'de, R: serde_json::de::Read<'de>>(
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
pub(super) struct SceneParts {
    camera: Option<Camera>,
    light: Option<Light>,
    meshes: Option<Vec<(String, Mesh)>>,
}

/// The top level of a scene file.
pub(super) struct SceneEntries<'c, 'f> {
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
pub(super) struct MeshList<'c, 'f, 'a> {
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
pub(super) struct MeshEntries<'c, 'f, 'a> {
    cx: &'c Cx<'f>,
    at: &'a At<'a>,
    index: usize,
    base_dir: &'c Path,
}

/// A mesh's `triangles` as read: the indices (those beyond `u32` kept as
/// `u32::MAX`, the first of them with its value), checked against the
/// vertex count once the mesh is read.
pub(super) struct Triangles {
    pub(super) indices: Vec<[u32; 3]>,
    /// The first index beyond `u32`: triangle, corner, value.
    pub(super) wide: Option<(usize, usize, u64)>,
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
pub(super) struct MeshParts {
    pub(super) positions: Option<Vec<DVec3>>,
    pub(super) triangles: Option<Triangles>,
    pub(super) obj: Option<Json>,
    pub(super) primitive: Option<Json>,
    pub(super) transform: Option<Json>,
}

/// A list of small items (vertices, triangles, points), one at a time:
/// each read as a [`Json`] tree within its budget and made into a `T` by
/// `each` (given the item, its place and its index) before the next is
/// read.
pub(super) struct Each<'c, 'f, 'a, F> {
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
pub(super) fn list<'c, 'f, 'a, T, F>(
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
pub(super) fn triangle(
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
