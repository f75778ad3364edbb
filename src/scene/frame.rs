//! The [light frame](crate::definitions#light-frame) and the [light image plane](crate::definitions#light-image-plane).
//!
//! Origin at the light's centre, `+z` toward the scene (the centre of the
//! scene's bounding box unless the scene says otherwise), `x` and `y`
//! completing a right-handed orthonormal frame. The light image plane is
//! `z = 1`: a point at light-frame `(x, y, z)`, `z > 0`, projects to
//! `(x/z, y/z)`.

use glam::{DVec2, DVec3};

/// Why a light frame could not be built.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum FrameError {
    /// The origin or the target is not finite.
    NonFinite,
    /// The target coincides with the origin: no direction toward the scene.
    NoDirection,
}

impl_error!(FrameError, |error, f| match error {
    FrameError::NonFinite => write!(f, "light frame origin or target is not finite"),
    FrameError::NoDirection => write!(f, "light frame target coincides with its origin"),
});

/// A right-handed orthonormal frame at the light's centre, `+z` toward the
/// scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightFrame {
    origin: DVec3,
    x: DVec3,
    y: DVec3,
    z: DVec3,
}

impl LightFrame {
    /// The frame at `origin` whose `+z` points at `target`. `x` and `y` are
    /// glam's `any_orthonormal_pair` of `z` (Duff et al. 2017), so the frame
    /// is a deterministic function of the direction.
    ///
    /// # Errors
    /// [`FrameError::NonFinite`], [`FrameError::NoDirection`].
    pub fn toward(origin: DVec3, target: DVec3) -> Result<LightFrame, FrameError> {
        if !(origin.is_finite() && target.is_finite()) {
            return Err(FrameError::NonFinite);
        }
        // Halved so that the difference cannot overflow.
        LightFrame::along(origin, target * 0.5 - origin * 0.5)
    }

    /// The frame at `origin` whose `+z` is the direction `direction` (any
    /// length), `x` and `y` as in [`LightFrame::toward`].
    ///
    /// # Errors
    /// [`FrameError::NonFinite`], [`FrameError::NoDirection`] (a zero
    /// direction).
    pub fn along(origin: DVec3, direction: DVec3) -> Result<LightFrame, FrameError> {
        if !(origin.is_finite() && direction.is_finite()) {
            return Err(FrameError::NonFinite);
        }
        let z = direction.try_normalize().ok_or(FrameError::NoDirection)?;
        let (x, y) = z.any_orthonormal_pair();
        Ok(LightFrame { origin, x, y, z })
    }

    /// The frame at `origin` whose `+z` is `direction` (any length) and
    /// whose `+x` is the part of `x_hint` orthogonal to it, normalised; `y =
    /// z × x`. For views that must share an axis: OESS's two endpoint maps
    /// put `x` along the segment light.
    ///
    /// # Errors
    /// [`FrameError::NonFinite`]; [`FrameError::NoDirection`] when
    /// `direction` is zero or `x_hint` is parallel to it (no `x` is
    /// defined).
    pub fn with_x_axis(
        origin: DVec3,
        direction: DVec3,
        x_hint: DVec3,
    ) -> Result<LightFrame, FrameError> {
        if !(origin.is_finite() && direction.is_finite() && x_hint.is_finite()) {
            return Err(FrameError::NonFinite);
        }
        let z = direction.try_normalize().ok_or(FrameError::NoDirection)?;
        // Gram–Schmidt twice: once is not orthogonal to rounding when the
        // hint is nearly parallel to `z` (the difference cancels).
        let orthogonal = |h: DVec3| (h - z * h.dot(z)).try_normalize();
        let x = x_hint
            .try_normalize()
            .and_then(orthogonal)
            .and_then(orthogonal)
            .ok_or(FrameError::NoDirection)?;
        Ok(LightFrame {
            origin,
            x,
            y: z.cross(x),
            z,
        })
    }

    /// The frame at the world origin with `+z` world `−y`, `x` world `+x`,
    /// `y` world `+z`: a total fallback where no other frame is defined.
    #[must_use]
    pub fn down_at_origin() -> LightFrame {
        LightFrame {
            origin: DVec3::ZERO,
            x: DVec3::X,
            y: DVec3::Z,
            z: -DVec3::Y,
        }
    }

    /// The frame's origin (the light's centre).
    #[must_use]
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The axes `x`, `y`, `z` in world coordinates.
    #[must_use]
    pub fn axes(&self) -> [DVec3; 3] {
        [self.x, self.y, self.z]
    }

    /// World point to light-frame coordinates.
    #[must_use]
    pub fn to_light(&self, p: DVec3) -> DVec3 {
        let d = p - self.origin;
        DVec3::new(d.dot(self.x), d.dot(self.y), d.dot(self.z))
    }

    /// Light-frame coordinates to a world point.
    #[must_use]
    pub fn to_world(&self, q: DVec3) -> DVec3 {
        self.origin + self.x * q.x + self.y * q.y + self.z * q.z
    }

    /// The light-image-plane projection `(x/z, y/z)` of a world point, with
    /// its light-frame depth `z`; `None` when `z ≤ 0` (at or behind the
    /// light's centre plane) or the point is not finite.
    #[must_use]
    pub fn project(&self, p: DVec3) -> Option<Projected> {
        let q = self.to_light(p);
        (q.z > 0.0 && q.is_finite()).then(|| Projected {
            point: crate::kernel::footprint::f64::project(q),
            depth: q.z,
        })
    }
}

/// A point on the light image plane and the depth it came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projected {
    /// `(x/z, y/z)`.
    pub point: DVec2,
    /// The light-frame depth `z > 0`.
    pub depth: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arbitrary::Rng;

    #[test]
    fn the_fallback_frame_is_right_handed_and_along_agrees_with_toward() {
        let [x, y, z] = LightFrame::down_at_origin().axes();
        assert_eq!(x.cross(y), z);
        assert_eq!(z, -DVec3::Y);
        let o = DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(
            LightFrame::along(o, DVec3::new(0.0, -4.0, 0.0)),
            LightFrame::toward(o, o - DVec3::Y)
        );
        assert_eq!(
            LightFrame::along(o, DVec3::ZERO),
            Err(FrameError::NoDirection)
        );
        assert_eq!(LightFrame::along(o, DVec3::NAN), Err(FrameError::NonFinite));
    }

    /// A point of the cube `[−1, 1)³`.
    fn in_cube(rng: &mut Rng) -> DVec3 {
        DVec3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        )
    }

    #[test]
    fn frames_are_right_handed_and_orthonormal() {
        let mut rng = Rng::new(5);
        for _ in 0..10_000 {
            let mut v = || in_cube(&mut rng);
            let (o, t) = (v() * 10.0, v() * 10.0);
            let Ok(f) = LightFrame::toward(o, t) else {
                continue;
            };
            let [x, y, z] = f.axes();
            for (a, b) in [(x, y), (y, z), (z, x)] {
                assert!(a.dot(b).abs() < 4.0 * f64::EPSILON);
            }
            for a in [x, y, z] {
                assert!((a.length() - 1.0).abs() < 4.0 * f64::EPSILON);
            }
            assert!((x.cross(y) - z).length() < 8.0 * f64::EPSILON);
            // +z toward the target: the target projects to the image centre.
            let p = f.project(t).expect("the target is in front");
            assert!(p.point.length() < 1e-12 && (p.depth - (t - o).length()).abs() < 1e-12);
            // Round trip.
            let w = v();
            assert!((f.to_world(f.to_light(w)) - w).length() < 1e-13);
        }
    }

    #[test]
    fn behind_the_light_does_not_project() {
        let f = LightFrame::toward(DVec3::new(0.0, 5.0, 0.0), DVec3::ZERO).unwrap();
        assert!(f.project(DVec3::new(0.0, 6.0, 0.0)).is_none());
        assert!(f.project(DVec3::new(3.0, 5.0, 0.0)).is_none());
        let below = f.project(DVec3::new(1.0, 3.0, 0.0)).unwrap();
        assert_eq!(below.depth, 2.0);
        assert!((below.point.length() - 0.5).abs() < 1e-15);
        assert_eq!(
            LightFrame::toward(DVec3::ONE, DVec3::ONE),
            Err(FrameError::NoDirection)
        );
        assert_eq!(
            LightFrame::toward(DVec3::ONE, DVec3::new(f64::NAN, 0.0, 0.0)),
            Err(FrameError::NonFinite)
        );
    }

    #[test]
    fn a_chosen_x_axis_gives_a_right_handed_orthonormal_frame_with_that_x() {
        let mut rng = Rng::new(17);
        let mut v = || in_cube(&mut rng);
        for _ in 0..10_000 {
            let (o, d, h) = (v(), v(), v());
            let Ok(f) = LightFrame::with_x_axis(o, d, h) else {
                continue;
            };
            let [x, y, z] = f.axes();
            for (a, b) in [(x, y), (y, z), (z, x)] {
                assert!(a.dot(b).abs() < 8.0 * f64::EPSILON, "{a} {b}");
            }
            assert!((x.cross(y) - z).length() < 8.0 * f64::EPSILON);
            // x lies in the plane of z and the hint, on the hint's side.
            assert!(z.cross(h).normalize().dot(x).abs() < 1e-12);
            assert!(x.dot(h) > 0.0);
            assert!((z - d.normalize()).length() < 4.0 * f64::EPSILON);
        }
        let o = DVec3::ZERO;
        assert_eq!(
            LightFrame::with_x_axis(o, DVec3::Y, DVec3::Y * 3.0),
            Err(FrameError::NoDirection)
        );
        assert_eq!(
            LightFrame::with_x_axis(o, DVec3::Y, DVec3::NAN),
            Err(FrameError::NonFinite)
        );
        let f = LightFrame::with_x_axis(o, -DVec3::Y, DVec3::X).unwrap();
        assert_eq!(f.axes(), [DVec3::X, DVec3::Z, -DVec3::Y]);
    }
}
