//! The points file, and a receiver from its fields.

use super::error::FileError;
use super::json::{At, Cx, Entries, Json, Object};
use super::scene::list;
use crate::scene::Receiver;
use glam::DVec3;
use serde::de::MapAccess;

/// The points of a points file, read as a stream: one point's JSON at a
/// time becomes a [`Receiver`], so the peak is the receivers themselves
/// (about 64 bytes a point) and not a tree of the whole file (10⁷ points
/// took 5.25 GB for a 250 MB file). The messages are those of the rest of
/// the loader: a JSON error at its line and column, a bad point at its
/// path (`points[3].normal`).
pub(super) fn points_from<'de, R: serde_json::de::Read<'de>>(
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
pub(super) struct PointsEntries<'c, 'f> {
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
pub(super) fn point(
    cx: &Cx<'_>,
    v: &Json,
    at: &At<'_>,
    mesh_count: usize,
) -> Result<Receiver, FileError> {
    let f = cx.object(v, at, &["p", "object", "normal"])?;
    let p = cx.vec3(cx.required(&f, at, "p")?, &at.key("p"))?;
    let object = cx.optional(&f, at, "object", |v, at| {
        let id = cx.uint(v, at)?;
        match u32::try_from(id) {
            Ok(id) if (id as usize) < mesh_count => Ok(id),
            _ => Err(cx.err(
                at,
                format!(
                    "{id} is out of range (the scene has {mesh_count} mesh{})",
                    if mesh_count == 1 { "" } else { "es" }
                ),
            )),
        }
    })?;
    let normal = cx.optional(&f, at, "normal", |v, at| {
        let n = cx.vec3(v, at)?;
        crate::kernel::eft::unit(n).ok_or_else(|| cx.err(at, "has zero length"))
    })?;
    Ok(Receiver {
        position: p,
        normal,
        object,
    })
}

/// The largest magnitude of any number in a scene or points file, and of
/// any vertex a primitive, transform or OBJ file makes: `1e30`, the domain
/// in which the exact orientation predicates (products of three coordinate
/// differences) are exact, and so the exact reference and every method
/// right to their documented accuracy. A file beyond it is refused, naming
/// the field and the value, rather than answered wrongly.
pub const DOMAIN: f64 = 1e30;

/// The input of a receiver that [`receiver_from`] refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReceiverField {
    /// The position.
    Position,
    /// The normal.
    Normal,
    /// The object id.
    Object,
}

/// A receiver from numbers as an array row gives them (the command line's
/// `.npy` points, the Python package's arrays), under the points file's
/// rules: every coordinate finite and within [`DOMAIN`], a normal non-zero
/// (normalised, to the same bits as a points file's), an object id of one
/// of `mesh_count` meshes.
///
/// # Errors
/// The first input at fault, in the order position, normal, object, with
/// a message that names the value.
pub fn receiver_from(
    position: [f64; 3],
    normal: Option<[f64; 3]>,
    object: Option<i64>,
    mesh_count: usize,
) -> Result<Receiver, (ReceiverField, String)> {
    let check = |v: [f64; 3], field| match v.iter().find(|x| !x.is_finite() || x.abs() > DOMAIN) {
        Some(x) => Err((field, format!("{x} is not a finite number within ±1e30"))),
        None => Ok(DVec3::from_array(v)),
    };
    let position = check(position, ReceiverField::Position)?;
    let normal = match normal {
        Some(n) => Some(
            crate::kernel::eft::unit(check(n, ReceiverField::Normal)?).ok_or_else(|| {
                (
                    ReceiverField::Normal,
                    "the normal has zero length".to_owned(),
                )
            })?,
        ),
        None => None,
    };
    let object = match object {
        Some(id) => match u32::try_from(id) {
            Ok(o) if (o as usize) < mesh_count => Some(o),
            _ => {
                return Err((
                    ReceiverField::Object,
                    format!(
                        "object id {id}, the scene has meshes 0 to {}",
                        mesh_count as i64 - 1
                    ),
                ))
            }
        },
        None => None,
    };
    Ok(Receiver {
        position,
        normal,
        object,
    })
}
