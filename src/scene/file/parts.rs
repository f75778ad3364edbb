//! The scene file's parts read whole: the camera, the light, a mesh from
//! its file or inline, a primitive and a transform.

use super::error::{short_path, FileError, Place};
use super::input::{read_input, MAX_OBJ_BYTES};
use super::json::{At, Cx, Json};
use super::obj::obj_mesh;
use super::points::DOMAIN;
use super::scene::{MeshParts, Triangles};
use super::{DEFAULT_SEGMENTS, MAX_IMAGE_SIDE};
use crate::scene::primitive::{self, axis_name, PrimitiveError, Transform};
use crate::scene::{Camera, CameraError, Light, LightError, Mesh};
use glam::DVec3;
use std::path::Path;

/// The scene file's parts, read with the generic accessors of `json`.
impl Cx<'_> {
    pub(super) fn camera(&self, v: &Json, at: &At) -> Result<Camera, FileError> {
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

    pub(super) fn light(&self, v: &Json, at: &At) -> Result<Light, FileError> {
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
    pub(super) fn mesh(
        &self,
        at: &At,
        parts: MeshParts,
        base_dir: &Path,
    ) -> Result<Mesh, FileError> {
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
                let segments = self.optional(&f, at, "segments", |v, s_at| {
                    let s = self.uint(v, s_at)?;
                    // Out-of-range counts are reported by `sphere`; beyond
                    // u32 they are reported here.
                    u32::try_from(s).map_err(|_| {
                        self.err(
                            s_at,
                            format!(
                                "must be in {}..={}, got {s}",
                                primitive::MIN_SEGMENTS,
                                primitive::MAX_SEGMENTS
                            ),
                        )
                    })
                })?;
                let segments = segments.unwrap_or(DEFAULT_SEGMENTS);
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
