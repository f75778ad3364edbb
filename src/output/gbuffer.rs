//! The G-buffer: the receivers a camera sees, as flat arrays another
//! renderer (a GPU program, numpy) reads directly — position, normal,
//! object id and the exact `V` per pixel — and the camera described with
//! the matrices and conventions needed to rasterise the same pixels
//! elsewhere ([`CameraModel`]).
//!
//! The arrays are row-major, row 0 the top of the image, `width · height`
//! pixels; a pixel that sees no surface has NaN position, normal and `V`
//! and object id `−1`. The positions are the renderer's receivers exactly
//! (each moved [`RECEIVER_OFFSET`](crate::render::RECEIVER_OFFSET) of the scene's
//! scale off its surface toward the camera), so `V` computed at them is the
//! exact answer `exact` holds, bit for bit.

use crate::method::{self, Exact, MethodError};
use crate::render::frame::{Frame, BACKGROUND};
use crate::render::stages::Stages;
use crate::scene::{Camera, Receiver, Scene};
use glam::{DMat4, DVec3, DVec4};

/// A pinhole camera as the matrices of a rasteriser, with the conventions
/// spelled out ([`CameraModel::CONVENTIONS`]).
///
/// - `view`: world to camera space, right-handed, the camera at the origin
///   looking down `−z`, `+y` up, `+x` right (`right = normalize(forward ×
///   up)`, `up′ = right × forward`, as [`Camera::primary_ray`]).
/// - `projection`: camera to clip space, right-handed perspective with
///   clip-space depth in `[0, 1]` (`0` at `near`, `1` at `far`; Direct3D,
///   Vulkan, Metal and WebGPU's range), `w_clip = −z_camera`, normalised
///   device `y` up.
/// - Pixels: pixel `(col, row)` (row 0 the top) has its centre at
///   `x_ndc = 2(col + ½)/width − 1`, `y_ndc = 1 − 2(row + ½)/height`.
///
/// Matrices are row-major (`m[i][j]`: row `i`, column `j`) and act on
/// column vectors: `clip = projection · view · [x, y, z, 1]ᵀ`. `near` and
/// `far` enclose the scene's bounds; `V` does not depend on them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraModel {
    /// The eye point.
    pub eye: [f64; 3],
    /// The point looked at.
    pub target: [f64; 3],
    /// The up hint.
    pub up: [f64; 3],
    /// The vertical field of view, degrees.
    pub fov_y_deg: f64,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// The near plane's distance along the view direction.
    pub near: f64,
    /// The far plane's distance.
    pub far: f64,
    /// World to camera space.
    pub view: [[f64; 4]; 4],
    /// Camera to clip space.
    pub projection: [[f64; 4]; 4],
}

impl CameraModel {
    /// The conventions of the matrices and pixels, as `(name, value)`
    /// pairs (also written into `camera.json`).
    pub const CONVENTIONS: [(&'static str, &'static str); 6] = [
        ("matrices", "row-major m[row][column], acting on column vectors: clip = projection · view · [x, y, z, 1]"),
        ("handedness", "right-handed; camera space looks down −z with +y up and +x right"),
        ("clip_depth", "[0, 1]: 0 at near, 1 at far (Direct3D/Vulkan/Metal/WebGPU); OpenGL's [−1, 1] needs z_gl = 2·z − w"),
        ("ndc_y", "up: row 0 (the top of the image) is y_ndc = +1 (a Vulkan viewport flips y: use a negative height)"),
        ("pixel_centre", "pixel (col, row), row 0 at the top: x_ndc = 2(col + 0.5)/width − 1, y_ndc = 1 − 2(row + 0.5)/height"),
        ("units", "the scene's own length units (those of its scene file); V is a fraction, 0 to 1"),
    ];

    /// The model of `camera` with near and far planes enclosing `bounds`
    /// (the scene's; `None`: `near = 10⁻³`, `far = 10³`).
    #[must_use]
    pub fn new(camera: &Camera, bounds: Option<(DVec3, DVec3)>) -> CameraModel {
        let (eye, target, up) = (camera.eye(), camera.target(), camera.up());
        let forward = (target - eye).normalize();
        let right = forward.cross(up).normalize();
        let up2 = right.cross(forward);
        let (width, height) = camera.resolution();
        // The farthest corner of the bounds along the view direction.
        let far = bounds
            .map(|(lo, hi)| {
                (0..8)
                    .map(|k| {
                        let c = DVec3::new(
                            if k & 1 == 0 { lo.x } else { hi.x },
                            if k & 2 == 0 { lo.y } else { hi.y },
                            if k & 4 == 0 { lo.z } else { hi.z },
                        );
                        (c - eye).length()
                    })
                    .fold(0.0, f64::max)
            })
            .filter(|f| f.is_finite() && *f > 0.0)
            .map_or(1e3, |f| f * 1.01);
        let near = far * 1e-4;
        let view = DMat4::from_rows(
            right.extend(-right.dot(eye)),
            up2.extend(-up2.dot(eye)),
            (-forward).extend(forward.dot(eye)),
            DVec4::W,
        );
        let aspect = f64::from(width) / f64::from(height);
        // Right-handed, clip depth in [0, 1]: z_clip = far/(near − far)·z +
        // near·far/(near − far), w_clip = −z.
        let f = 1.0 / (camera.fov_y_deg().to_radians() * 0.5).tan();
        let r = far / (near - far);
        let projection = DMat4::from_rows(
            DVec4::new(f / aspect, 0.0, 0.0, 0.0),
            DVec4::new(0.0, f, 0.0, 0.0),
            DVec4::new(0.0, 0.0, r, r * near),
            DVec4::new(0.0, 0.0, -1.0, 0.0),
        );
        let rows = |m: DMat4| [0, 1, 2, 3].map(|i| m.row(i).to_array());
        CameraModel {
            eye: eye.to_array(),
            target: target.to_array(),
            up: up.to_array(),
            fov_y_deg: camera.fov_y_deg(),
            width,
            height,
            near,
            far,
            view: rows(view),
            projection: rows(projection),
        }
    }

    /// Where `p` lands: `(col, row, depth)` in continuous pixel
    /// coordinates (pixel `(c, r)`'s centre at `(c + ½, r + ½)`) and
    /// clip-space depth in `[0, 1]`; `None` behind the camera.
    #[must_use]
    pub fn project(&self, p: DVec3) -> Option<(f64, f64, f64)> {
        let m = |rows: &[[f64; 4]; 4]| DMat4::from_cols_array_2d(rows).transpose();
        let clip = m(&self.projection) * m(&self.view) * p.extend(1.0);
        if clip.w <= 0.0 {
            return None;
        }
        let (x, y, z) = (clip.x / clip.w, clip.y / clip.w, clip.z / clip.w);
        Some((
            (x + 1.0) * 0.5 * f64::from(self.width),
            (1.0 - y) * 0.5 * f64::from(self.height),
            z,
        ))
    }

    /// `camera.json`: the camera, its matrices and conventions, the
    /// light's parameters (as in the scene file), and the scene's mesh
    /// names (object id = index), as pretty JSON.
    #[cfg(feature = "scene-file")]
    #[must_use]
    pub fn to_json(&self, scene: &Scene) -> String {
        use crate::scene::Light;
        let v = |d: DVec3| d.to_array();
        let light = match scene.light() {
            Light::Sphere(s) => {
                serde_json::json!({"type": "sphere", "center": v(s.center()), "radius": s.radius()})
            }
            Light::Disk(d) => serde_json::json!({"type": "disk", "center": v(d.center()),
                "normal": v(d.normal()), "radius": d.radius()}),
            Light::Rect(r) => serde_json::json!({"type": "rect", "center": v(r.center()),
                "u": v(r.u()), "v": v(r.v())}),
            Light::Segment(s) => {
                serde_json::json!({"type": "segment", "a": v(s.a()), "b": v(s.b())})
            }
            Light::Point(p) => serde_json::json!({"type": "point", "position": v(p.position())}),
        };
        let conventions: serde_json::Map<String, serde_json::Value> = Self::CONVENTIONS
            .iter()
            .map(|(k, s)| ((*k).to_owned(), serde_json::Value::from(*s)))
            .collect();
        let json = serde_json::json!({
            "format": "softshadow-camera/1",
            "eye": self.eye,
            "target": self.target,
            "up": self.up,
            "fov_y_deg": self.fov_y_deg,
            "width": self.width,
            "height": self.height,
            "aspect": f64::from(self.width) / f64::from(self.height),
            "near": self.near,
            "far": self.far,
            "view": self.view,
            "projection": self.projection,
            "conventions": conventions,
            "light": light,
            "objects": scene.names(),
            "receiver_offset": "each position is the surface point moved 2^-32 · (max |coordinate| + the scene's largest |coordinate|) along the normal, toward the camera",
        });
        serde_json::to_string_pretty(&json).unwrap_or_default()
    }
}

/// The receivers a camera sees as arrays, with the exact `V` at each.
#[derive(Clone, Debug, PartialEq)]
pub struct GBuffer {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// `3 · width · height` values: each pixel's receiver `x, y, z`; NaN
    /// where the pixel sees no surface.
    pub position: Vec<f64>,
    /// `3 · width · height` values: the unit geometric normal, facing the
    /// camera; NaN where no surface.
    pub normal: Vec<f64>,
    /// `width · height` object ids (mesh index); `−1` where no surface.
    pub object: Vec<i32>,
    /// `width · height` exact `V`; NaN where no surface.
    pub exact: Vec<f64>,
    /// The camera.
    pub camera: CameraModel,
}

impl GBuffer {
    /// The G-buffer of `scene` seen by `camera`: primary rays through the
    /// scene's BVH ([`Frame::from_camera`]) and the exact reference at
    /// every receiver.
    ///
    /// # Errors
    /// A receiver the light cannot be seen from (inside a sphere light, in
    /// the plane of a disk or rect light), as [`MethodError::Receiver`].
    pub fn compute(scene: &Scene, camera: &Camera) -> Result<GBuffer, MethodError> {
        let stages = Stages::new(scene);
        let frame = Frame::from_camera(camera, stages.bvh());
        let exact = method::run(&Exact, &stages, &frame)?.output.visibility;
        Ok(GBuffer::from_frame(
            &frame,
            &exact,
            CameraModel::new(camera, scene.bounds()),
        ))
    }

    /// The arrays of a camera `frame` whose exact values (one per receiver)
    /// are known.
    #[must_use]
    pub fn from_frame(frame: &Frame, exact: &[f64], camera: CameraModel) -> GBuffer {
        let (width, height) = frame.size();
        let n = frame.pixels().len();
        let mut g = GBuffer {
            width,
            height,
            position: vec![f64::NAN; 3 * n],
            normal: vec![f64::NAN; 3 * n],
            object: vec![-1; n],
            exact: vec![f64::NAN; n],
            camera,
        };
        for (k, &i) in frame.pixels().iter().enumerate() {
            if i == BACKGROUND {
                continue;
            }
            let r = &frame.receivers()[i as usize];
            g.position[3 * k..3 * k + 3].copy_from_slice(&r.position.to_array());
            if let Some(nrm) = r.normal {
                g.normal[3 * k..3 * k + 3].copy_from_slice(&nrm.to_array());
            }
            g.object[k] = r.object.map_or(-1, |o| i32::try_from(o).unwrap_or(-1));
            g.exact[k] = exact.get(i as usize).copied().unwrap_or(f64::NAN);
        }
        g
    }
}

/// Why arrays do not make a G-buffer: the array, the pixel (row, column)
/// where known, and the problem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GBufferError {
    /// `position`, `normal` or `object`.
    pub array: &'static str,
    /// The first offending pixel, `(row, col)`, when one pixel is at fault.
    pub pixel: Option<(usize, usize)>,
    /// What is wrong.
    pub message: String,
}

impl_error!(GBufferError, |error, f| match error.pixel {
    Some((r, c)) => write!(f, "pixel (row {r}, column {c}): {}", error.message),
    None => write!(f, "{}", error.message),
});

/// The camera frame of G-buffer arrays (the layout of [`GBuffer`]; one's
/// own rasteriser's, or ours read back): a pixel is a surface where its
/// object id is `≥ 0`, and its receiver is the position given, with the
/// normal given, exactly (no offset is applied: write positions on the
/// side of the surface the normal faces, as ours are).
///
/// # Errors
/// Arrays of the wrong length; at a surface pixel, a non-finite position,
/// a normal that is not finite and unit (within 10⁻³), an object id of no
/// mesh (`≥ mesh_count`) or below `−1`.
pub fn frame_from_arrays(
    width: usize,
    height: usize,
    position: &[f64],
    normal: &[f64],
    object: &[i64],
    mesh_count: usize,
) -> Result<Frame, GBufferError> {
    let n = width * height;
    let err = |array, pixel: Option<usize>, message: String| GBufferError {
        array,
        pixel: pixel.map(|k| (k / width.max(1), k % width.max(1))),
        message,
    };
    for (array, len, want) in [
        ("position", position.len(), 3 * n),
        ("normal", normal.len(), 3 * n),
        ("object", object.len(), n),
    ] {
        if len != want {
            return Err(err(
                array,
                None,
                format!("{len} values for {width}×{height} pixels (expected {want})"),
            ));
        }
    }
    let (Ok(w), Ok(h)) = (u32::try_from(width), u32::try_from(height)) else {
        return Err(err("position", None, "too many pixels".into()));
    };
    let mut pixels = Vec::with_capacity(n);
    for k in 0..n {
        let id = object[k];
        if id == -1 {
            pixels.push(None);
            continue;
        }
        if id < -1 || id >= mesh_count as i64 {
            return Err(err(
                "object",
                Some(k),
                format!(
                    "object id {id}: the scene has meshes 0 to {} (−1: no surface)",
                    mesh_count as i64 - 1
                ),
            ));
        }
        let p = DVec3::from_slice(&position[3 * k..3 * k + 3]);
        if !p.is_finite() {
            return Err(err(
                "position",
                Some(k),
                format!(
                    "position {p} is not finite where the object id ({id}) says there is a surface"
                ),
            ));
        }
        let nrm = DVec3::from_slice(&normal[3 * k..3 * k + 3]);
        if !nrm.is_finite() || (nrm.length() - 1.0).abs() > 1e-3 {
            return Err(err(
                "normal",
                Some(k),
                format!("normal {nrm} is not a finite unit vector"),
            ));
        }
        pixels.push(Some(Receiver {
            position: p,
            normal: Some(nrm),
            object: Some(id as u32),
        }));
    }
    Ok(Frame::from_pixels(w, h, pixels))
}
