//! The scene's light: one of the five shapes of
//! [visibility](crate::definitions#visibility) ([`Light`]), named by its
//! kind ([`LightKind`]).
//!
//! The shapes, their emitting measures ([`Emitter`]) and their errors are
//! the light's geometry, defined in [`kernel::light`](crate::kernel::light)
//! and named here too. Constructors return [`LightError`] for non-finite
//! or degenerate input; [`Light::emitter`] returns [`ReceiverError`] for a
//! receiver inside a sphere light or in the plane of a disk or rect light
//! ([visibility](crate::definitions#visibility): an error, not a NaN).

use crate::kernel::eft;
use crate::kernel::receiver_view;
use glam::DVec3;
use std::fmt;

pub use crate::kernel::light::{
    Disk, Emitter, LightError, Point, ReceiverError, Rect, Segment, Sphere,
};

/// The five kinds of light, for naming and for what a method handles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LightKind {
    /// [`Light::Sphere`].
    Sphere,
    /// [`Light::Disk`].
    Disk,
    /// [`Light::Rect`].
    Rect,
    /// [`Light::Segment`].
    Segment,
    /// [`Light::Point`].
    Point,
}

impl LightKind {
    /// Every kind, in the order of the scene file's documentation.
    pub const ALL: &'static [LightKind] = &[
        LightKind::Sphere,
        LightKind::Disk,
        LightKind::Rect,
        LightKind::Segment,
        LightKind::Point,
    ];

    /// The kind's name in the scene file (`"sphere"`, `"disk"`, …).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            LightKind::Sphere => "sphere",
            LightKind::Disk => "disk",
            LightKind::Rect => "rect",
            LightKind::Segment => "segment",
            LightKind::Point => "point",
        }
    }
}

impl fmt::Display for LightKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A light of one of the five kinds. Each variant holds a struct whose
/// fields are private, so every light was validated by its constructor:
/// no light can be built with a NaN, a non-positive radius or a
/// degenerate shape, and every part of the crate can rely on that.
///
/// ```compile_fail
/// use softshadow::scene::Light;
/// // The kinds' fields are private: a light cannot be written out unchecked.
/// let light = Light::Sphere(softshadow::scene::light::Sphere { center: softshadow::glam::DVec3::ZERO, radius: f64::NAN });
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// A uniform sphere, seen as its facing disk.
    Sphere(Sphere),
    /// A uniform disk.
    Disk(Disk),
    /// A uniform parallelogram.
    Rect(Rect),
    /// A uniform segment.
    Segment(Segment),
    /// A point light.
    Point(Point),
}

impl Light {
    /// A sphere light ([`Sphere::new`]).
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::NonPositiveRadius`].
    pub fn sphere(center: DVec3, radius: f64) -> Result<Light, LightError> {
        Sphere::new(center, radius).map(Light::Sphere)
    }

    /// A disk light ([`Disk::new`]); `normal` need not be unit length.
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::NonPositiveRadius`],
    /// [`LightError::ZeroNormal`].
    pub fn disk(center: DVec3, normal: DVec3, radius: f64) -> Result<Light, LightError> {
        Disk::new(center, normal, radius).map(Light::Disk)
    }

    /// A rect light ([`Rect::new`]).
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::DegenerateRect`].
    pub fn rect(center: DVec3, u: DVec3, v: DVec3) -> Result<Light, LightError> {
        Rect::new(center, u, v).map(Light::Rect)
    }

    /// A segment light ([`Segment::new`]).
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::ZeroLengthSegment`].
    pub fn segment(a: DVec3, b: DVec3) -> Result<Light, LightError> {
        Segment::new(a, b).map(Light::Segment)
    }

    /// A point light ([`Point::new`]).
    ///
    /// # Errors
    /// [`LightError::NonFinite`].
    pub fn point(position: DVec3) -> Result<Light, LightError> {
        Point::new(position).map(Light::Point)
    }

    /// The light's kind.
    #[must_use]
    pub fn kind(&self) -> LightKind {
        match self {
            Light::Sphere(_) => LightKind::Sphere,
            Light::Disk(_) => LightKind::Disk,
            Light::Rect(_) => LightKind::Rect,
            Light::Segment(_) => LightKind::Segment,
            Light::Point(_) => LightKind::Point,
        }
    }

    /// The light's centre (the segment's midpoint).
    #[must_use]
    pub fn center(&self) -> DVec3 {
        match self {
            Light::Sphere(s) => s.center(),
            Light::Disk(d) => d.center(),
            Light::Rect(r) => r.center(),
            Light::Segment(s) => s.a().midpoint(s.b()),
            Light::Point(p) => p.position(),
        }
    }

    /// The radius of the disk the light's measure is drawn as when a method
    /// projects it from its centre: a sphere's or disk's radius; for a rect
    /// the radius of the disk of equal area; for a segment half its length;
    /// `0` for a point.
    #[must_use]
    pub fn equivalent_radius(&self) -> f64 {
        match self {
            Light::Sphere(s) => s.radius(),
            Light::Disk(d) => d.radius(),
            Light::Rect(r) => r.equivalent_radius(),
            Light::Segment(s) => 0.5 * (s.b() - s.a()).length(),
            Light::Point(_) => 0.0,
        }
    }

    /// The radius of the smallest ball about [`center`](Light::center)
    /// that holds the whole light: a sphere's or disk's radius, a rect's
    /// longer half-diagonal, half a segment's length, `0` for a point.
    #[must_use]
    pub fn bounding_radius(&self) -> f64 {
        match self {
            Light::Rect(r) => eft::length(r.u() + r.v()).max(eft::length(r.u() - r.v())),
            _ => self.equivalent_radius(),
        }
    }

    /// The unit normal of a disk or rect light's plane, `None` for the
    /// other kinds.
    #[must_use]
    pub fn plane_normal(&self) -> Option<DVec3> {
        match self {
            Light::Disk(d) => Some(d.normal()),
            Light::Rect(r) => Some(r.normal()),
            _ => None,
        }
    }

    /// The exact `V(p)` of this light among `triangles` (two-sided
    /// occluders, no acceleration structure): the
    /// [receiver view](crate::kernel::receiver_view) of every triangle,
    /// `1 −` the fraction of the emitter they hide. For a few triangles and
    /// the kernels alone; over a whole scene, `reference::exact` culls with
    /// a BVH first and gives the same answer.
    ///
    /// # Errors
    /// As [`Light::emitter`].
    pub fn visibility_among(
        &self,
        p: DVec3,
        triangles: &[[DVec3; 3]],
    ) -> Result<f64, ReceiverError> {
        let emitter = self.emitter(p)?;
        let mut scratch = receiver_view::Scratch::default();
        let hidden = receiver_view::occluded_fraction(&emitter, p, triangles, &mut scratch);
        // `emitter` refused every receiver the views refuse.
        Ok(1.0 - hidden.unwrap_or(0.0))
    }

    /// The emitting measure as seen from the receiver `p` ([visibility](crate::definitions#visibility)).
    ///
    /// # Errors
    /// [`ReceiverError`] for a non-finite receiver, one inside a sphere
    /// light, in the plane of a disk or rect light (the signed distance
    /// within its own rounding bound of zero), on a segment light (exactly
    /// collinear, decided by the exact predicates, and between its ends) or
    /// at a point light.
    pub fn emitter(&self, p: DVec3) -> Result<Emitter, ReceiverError> {
        match self {
            Light::Sphere(s) => s.seen_from(p),
            Light::Disk(d) => d.seen_from(p),
            Light::Rect(r) => r.seen_from(p),
            Light::Segment(s) => s.seen_from(p),
            Light::Point(x) => x.seen_from(p),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn constructors_reject_bad_input() {
        assert_eq!(
            Light::sphere(DVec3::ZERO, 0.0),
            Err(LightError::NonPositiveRadius { radius: 0.0 })
        );
        assert_eq!(
            Light::sphere(DVec3::ZERO, f64::NAN),
            Err(LightError::NonFinite { field: "radius" })
        );
        assert_eq!(
            Light::sphere(DVec3::new(f64::INFINITY, 0.0, 0.0), 1.0),
            Err(LightError::NonFinite { field: "center" })
        );
        assert_eq!(
            Light::disk(DVec3::ZERO, DVec3::ZERO, 1.0),
            Err(LightError::ZeroNormal)
        );
        assert_eq!(
            Light::rect(DVec3::ZERO, DVec3::X, DVec3::X * 2.0),
            Err(LightError::DegenerateRect)
        );
        assert_eq!(
            Light::segment(DVec3::ONE, DVec3::ONE),
            Err(LightError::ZeroLengthSegment)
        );
        assert!(Light::point(DVec3::new(0.0, f64::NAN, 0.0)).is_err());
    }

    #[test]
    fn receivers_on_the_light_are_errors() {
        let sphere = Light::sphere(DVec3::ZERO, 1.0).unwrap();
        assert_eq!(
            sphere.emitter(DVec3::new(0.5, 0.0, 0.0)),
            Err(ReceiverError::InsideSphere)
        );
        assert_eq!(sphere.emitter(DVec3::X), Err(ReceiverError::InsideSphere));
        let disk = Light::disk(DVec3::ZERO, DVec3::Y, 1.0).unwrap();
        assert_eq!(
            disk.emitter(DVec3::new(5.0, 0.0, 3.0)),
            Err(ReceiverError::InLightPlane)
        );
        assert!(disk.emitter(DVec3::new(5.0, 1e-9, 3.0)).is_ok());
        let seg = Light::segment(DVec3::ZERO, DVec3::X * 4.0).unwrap();
        assert_eq!(seg.emitter(DVec3::X), Err(ReceiverError::OnLight));
        // Exactly on a slanted segment (a dyadic point): still on the light.
        let slanted = Light::segment(DVec3::ZERO, DVec3::new(1.0, 3.0, -2.0)).unwrap();
        assert_eq!(
            slanted.emitter(DVec3::new(0.25, 0.75, -0.5)),
            Err(ReceiverError::OnLight)
        );
        assert!(slanted
            .emitter(DVec3::new(0.25f64.next_up(), 0.75, -0.5))
            .is_ok());
        assert!(seg.emitter(DVec3::X * 5.0).is_ok());
        assert_eq!(
            Light::point(DVec3::ONE).unwrap().emitter(DVec3::ONE),
            Err(ReceiverError::OnLight)
        );
    }

    #[test]
    fn facing_disk_faces_the_receiver() {
        let sphere = Light::sphere(DVec3::new(1.0, 5.0, 0.0), 0.5).unwrap();
        let p = DVec3::new(1.0, 0.0, 0.0);
        let Ok(Emitter::Disk(disk)) = sphere.emitter(p) else {
            panic!("a disk");
        };
        let (normal, radius) = (disk.normal(), disk.radius());
        assert_eq!(normal, DVec3::Y);
        assert_eq!(radius, 0.5);
    }

    fn emitter_is_finite(e: &Emitter) -> bool {
        match *e {
            Emitter::Disk(d) => {
                d.center().is_finite() && d.normal().is_finite() && d.radius().is_finite()
            }
            Emitter::Rect(r) => r.center().is_finite() && r.u().is_finite() && r.v().is_finite(),
            Emitter::Segment(g) => g.a().is_finite() && g.b().is_finite(),
            Emitter::Point(p) => p.position().is_finite(),
        }
    }

    proptest::proptest! {
        /// Any bit patterns: constructors answer Ok or a typed error, and a
        /// valid light gives a receiver a finite emitter or a typed error.
        #[test]
        fn total_on_any_bits(bits in proptest::collection::vec(proptest::prelude::any::<u64>(), 13)) {
            let f = |i: usize| f64::from_bits(bits[i]);
            let v = |i: usize| DVec3::new(f(i), f(i + 1), f(i + 2));
            let p = v(10);
            for light in [
                Light::sphere(v(0), f(3)),
                Light::disk(v(0), v(3), f(6)),
                Light::rect(v(0), v(3), v(6)),
                Light::segment(v(0), v(3)),
                Light::point(v(0)),
            ]
            .into_iter()
            .flatten()
            {
                if let Ok(e) = light.emitter(p) {
                    proptest::prop_assert!(emitter_is_finite(&e), "{:?} from {:?}", e, p);
                    proptest::prop_assert!(e.point_at(DVec2::splat(0.3)).is_finite());
                }
            }
        }
    }
}
