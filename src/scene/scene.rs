//! A whole scene: occluder meshes (object id = mesh index), one light and an
//! optional pinhole camera.

use super::{Light, Mesh};
use glam::DVec3;

/// Why a camera could not be built.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum CameraError {
    /// A vector or the field of view is NaN or infinite; the field is named.
    NonFinite {
        /// The offending field.
        field: &'static str,
    },
    /// `eye` and `target` coincide, or `up` is parallel to the view
    /// direction (or zero).
    Degenerate,
    /// The vertical field of view is not in `(0°, 180°)`.
    FieldOfView {
        /// The value given, in degrees.
        degrees: f64,
    },
    /// Width or height is zero.
    EmptyImage,
}

impl_error!(CameraError, |error, f| match error {
    CameraError::NonFinite { field } => write!(f, "camera {field} is not finite"),
    CameraError::Degenerate => write!(
        f,
        "camera eye equals target, or up is parallel to the view direction"
    ),
    CameraError::FieldOfView { degrees } => {
        write!(f, "camera fov_y_deg {degrees} is not in (0, 180)")
    }
    CameraError::EmptyImage => write!(f, "camera width and height must be positive"),
});

/// A pinhole camera, validated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    eye: DVec3,
    target: DVec3,
    up: DVec3,
    fov_y_deg: f64,
    width: u32,
    height: u32,
    /// `forward`, `right`, `up′` of [`Camera::primary_ray`] and
    /// `tan(fov/2)`, derived from the fields above once.
    basis: [DVec3; 3],
    half: f64,
}

impl Camera {
    /// A camera at `eye` looking at `target`, `up` roughly up, with a
    /// vertical field of view in degrees and an image of `width × height`
    /// pixels.
    ///
    /// # Errors
    /// [`CameraError`] for non-finite input, a degenerate view, a field of
    /// view outside `(0°, 180°)` or an empty image.
    pub fn new(
        eye: DVec3,
        target: DVec3,
        up: DVec3,
        fov_y_deg: f64,
        width: u32,
        height: u32,
    ) -> Result<Camera, CameraError> {
        for (v, field) in [(eye, "eye"), (target, "target"), (up, "up")] {
            if !v.is_finite() {
                return Err(CameraError::NonFinite { field });
            }
        }
        if !fov_y_deg.is_finite() {
            return Err(CameraError::NonFinite { field: "fov_y_deg" });
        }
        if !(fov_y_deg > 0.0 && fov_y_deg < 180.0) {
            return Err(CameraError::FieldOfView { degrees: fov_y_deg });
        }
        if width == 0 || height == 0 {
            return Err(CameraError::EmptyImage);
        }
        let forward = (target - eye)
            .try_normalize()
            .ok_or(CameraError::Degenerate)?;
        if forward.cross(up).try_normalize().is_none() {
            return Err(CameraError::Degenerate);
        }
        let right = forward.cross(up).normalize();
        Ok(Camera {
            eye,
            target,
            up,
            fov_y_deg,
            width,
            height,
            basis: [forward, right, right.cross(forward)],
            half: (fov_y_deg.to_radians() * 0.5).tan(),
        })
    }

    /// The eye point.
    #[must_use]
    pub fn eye(&self) -> DVec3 {
        self.eye
    }

    /// The point looked at.
    #[must_use]
    pub fn target(&self) -> DVec3 {
        self.target
    }

    /// The up hint.
    #[must_use]
    pub fn up(&self) -> DVec3 {
        self.up
    }

    /// The vertical field of view, in degrees.
    #[must_use]
    pub fn fov_y_deg(&self) -> f64 {
        self.fov_y_deg
    }

    /// Image width and height in pixels.
    #[must_use]
    pub fn resolution(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The same camera with an image of `width × height` pixels (the field
    /// of view is kept: it is vertical).
    ///
    /// # Errors
    /// [`CameraError::EmptyImage`] when either is zero.
    pub fn with_resolution(&self, width: u32, height: u32) -> Result<Camera, CameraError> {
        if width == 0 || height == 0 {
            return Err(CameraError::EmptyImage);
        }
        Ok(Camera {
            width,
            height,
            ..*self
        })
    }

    /// [`Camera::primary_ray`] for every pixel, row by row from the
    /// top-left: `width · height` rays.
    pub fn primary_rays(&self) -> impl Iterator<Item = (DVec3, DVec3)> + '_ {
        (0..self.height)
            .flat_map(move |row| (0..self.width).map(move |col| self.primary_ray(col, row)))
    }

    /// The primary ray through the centre of pixel `(col, row)` (row 0 at
    /// the top, column 0 at the left): `(eye, direction)`, the direction not
    /// normalised. Pinhole model: `forward = target − eye` normalised,
    /// `right = forward × up` normalised, `up′ = right × forward`; pixel
    /// centres at `x = (2(col + ½)/width − 1) · tan(fov/2) · width/height`,
    /// `y = (1 − 2(row + ½)/height) · tan(fov/2)`, direction
    /// `forward + x · right + y · up′`. Pixels outside the image give rays
    /// outside the field of view (no error).
    #[must_use]
    pub fn primary_ray(&self, col: u32, row: u32) -> (DVec3, DVec3) {
        let [forward, right, up] = self.basis;
        let half = self.half;
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let x = (2.0 * (f64::from(col) + 0.5) / w - 1.0) * half * (w / h);
        let y = (1.0 - 2.0 * (f64::from(row) + 0.5) / h) * half;
        (self.eye, forward + right * x + up * y)
    }
}

/// A scene: named occluder meshes (object id = index in [`Scene::meshes`]),
/// one light, and an optional camera (the renderer needs one; visibility
/// queries do not).
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    meshes: Vec<Mesh>,
    names: Vec<String>,
    light: Light,
    camera: Option<Camera>,
}

impl Scene {
    /// A scene with the given light and no meshes and no camera.
    #[must_use]
    pub fn new(light: Light) -> Scene {
        Scene {
            meshes: Vec::new(),
            names: Vec::new(),
            light,
            camera: None,
        }
    }

    /// Adds a mesh under a name; its object id is the number of meshes
    /// before it.
    #[must_use]
    pub fn with_mesh(mut self, name: impl Into<String>, mesh: Mesh) -> Scene {
        self.names.push(name.into());
        self.meshes.push(mesh);
        self
    }

    /// Replaces the light.
    #[must_use]
    pub fn with_light(mut self, light: Light) -> Scene {
        self.light = light;
        self
    }

    /// Sets the camera.
    #[must_use]
    pub fn with_camera(mut self, camera: Camera) -> Scene {
        self.camera = Some(camera);
        self
    }

    /// The meshes, in object-id order.
    #[must_use]
    pub fn meshes(&self) -> &[Mesh] {
        &self.meshes
    }

    /// The meshes' names, in object-id order.
    #[must_use]
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The light.
    #[must_use]
    pub fn light(&self) -> &Light {
        &self.light
    }

    /// The camera, if the scene has one.
    #[must_use]
    pub fn camera(&self) -> Option<&Camera> {
        self.camera.as_ref()
    }

    /// The number of triangles over all meshes.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles().len()).sum()
    }

    /// The bounds of every mesh, `None` when no mesh has a triangle.
    #[must_use]
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        self.meshes
            .iter()
            .filter_map(Mesh::bounds)
            .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_cameras_are_typed_errors() {
        let c = |eye, up, fov, w| Camera::new(eye, DVec3::ZERO, up, fov, w, 4);
        assert_eq!(
            c(DVec3::ZERO, DVec3::Y, 45.0, 4),
            Err(CameraError::Degenerate)
        );
        assert_eq!(c(DVec3::Y, DVec3::Y, 45.0, 4), Err(CameraError::Degenerate));
        assert_eq!(
            c(DVec3::Z, DVec3::Y, 180.0, 4),
            Err(CameraError::FieldOfView { degrees: 180.0 })
        );
        assert_eq!(c(DVec3::Z, DVec3::Y, 45.0, 0), Err(CameraError::EmptyImage));
        assert_eq!(
            c(DVec3::Z, DVec3::NAN, 45.0, 4),
            Err(CameraError::NonFinite { field: "up" })
        );
        assert!(c(DVec3::Z, DVec3::Y, 45.0, 4).is_ok());
    }

    #[test]
    fn primary_rays_span_the_field_of_view() {
        // 90° vertical, 2:1 image: the top and bottom pixel edges are at
        // ±45°, the left and right ones at ±atan(2).
        let camera = Camera::new(DVec3::Z, DVec3::ZERO, DVec3::Y, 90.0, 200, 100).unwrap();
        let (eye, d) = camera.primary_ray(100, 50);
        assert_eq!(eye, DVec3::Z);
        // Just below and right of the centre by half a pixel.
        assert!((d - DVec3::new(0.01, -0.01, -1.0)).length() < 1e-12);
        let (_, top_left) = camera.primary_ray(0, 0);
        let expected = DVec3::new(-2.0 + 0.01, 1.0 - 0.01, -1.0);
        assert!((top_left - expected).length() < 1e-12, "{top_left}");
        let all: Vec<_> = camera.primary_rays().collect();
        assert_eq!(all.len(), 200 * 100);
        assert_eq!(all[100 * 200 - 1], camera.primary_ray(199, 99));
        assert_eq!(all[250], camera.primary_ray(50, 1));
    }
}
