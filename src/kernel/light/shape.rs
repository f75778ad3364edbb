//! The five shapes of light ([`Sphere`], [`Disk`], [`Rect`], [`Segment`],
//! [`Point`]), each validated by its constructor: its fields are private,
//! so no shape holds a NaN, a non-positive radius or a degenerate extent.

use super::error::LightError;
use crate::kernel::eft;
use glam::DVec3;

/// A uniform sphere of light, seen from a receiver as its facing disk.
/// Built only by [`Sphere::new`], so its centre is finite and its radius
/// finite and positive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    center: DVec3,
    radius: f64,
}

impl Sphere {
    /// A sphere light.
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::NonPositiveRadius`].
    pub fn new(center: DVec3, radius: f64) -> Result<Sphere, LightError> {
        let mut faults = Faults::default();
        faults.finite(center, "center");
        faults.positive(radius);
        faults.done()?;
        Ok(Sphere { center, radius })
    }

    /// The centre.
    #[must_use]
    pub fn center(&self) -> DVec3 {
        self.center
    }

    /// The radius, `> 0`.
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

/// A uniform disk of light (occlusion does not depend on the side it emits
/// from), also a sphere light's facing disk as a receiver sees it. Built
/// only by [`Disk::new`]: finite centre, unit normal, finite positive
/// radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disk {
    center: DVec3,
    normal: DVec3,
    radius: f64,
}

impl Disk {
    /// A disk light; `normal` need not be unit length: every finite
    /// non-zero normal is normalised, `1e-300` or `1e300` long alike
    /// (scaled by a power of two first, so its squared length cannot
    /// underflow or overflow; the same bits as `normal.normalize()`
    /// wherever that is finite).
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::NonPositiveRadius`],
    /// [`LightError::ZeroNormal`]; [`LightError::Several`] for more than
    /// one.
    pub fn new(center: DVec3, normal: DVec3, radius: f64) -> Result<Disk, LightError> {
        let mut faults = Faults::default();
        faults.finite(center, "center");
        let unit = faults.finite(normal, "normal").and_then(|n| {
            let unit = eft::unit(n);
            faults.check(unit.is_some(), LightError::ZeroNormal);
            unit
        });
        faults.positive(radius);
        faults.done()?;
        Ok(Disk {
            center,
            normal: unit.unwrap_or(DVec3::Z),
            radius,
        })
    }

    /// The disk of a sphere light facing a receiver: `normal` already of
    /// unit length, the sphere's finite centre and positive radius.
    pub(super) fn facing(center: DVec3, normal: DVec3, radius: f64) -> Disk {
        Disk {
            center,
            normal,
            radius,
        }
    }

    /// The centre.
    #[must_use]
    pub fn center(&self) -> DVec3 {
        self.center
    }

    /// The unit normal.
    #[must_use]
    pub fn normal(&self) -> DVec3 {
        self.normal
    }

    /// The radius, `> 0`.
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

/// A uniform parallelogram of light, `center + s u + t v` for
/// `s, t ∈ [−1, 1]`. Built only by [`Rect::new`]: finite centre and
/// half-axes spanning a finite, non-zero area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    center: DVec3,
    u: DVec3,
    v: DVec3,
}

impl Rect {
    /// A rect light with half-axes `u`, `v` (any non-parallel pair: the
    /// light is the parallelogram they span, whatever its area: `u × v` is
    /// decided on `u` and `v` scaled by powers of two, so an area beyond
    /// `f64`'s range, `1e400` or `1e-400`, is a rect like any other).
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::DegenerateRect`] when `u`
    /// or `v` is zero or they are parallel (`u × v` rounds to zero);
    /// [`LightError::Several`] for more than one.
    pub fn new(center: DVec3, u: DVec3, v: DVec3) -> Result<Rect, LightError> {
        let mut faults = Faults::default();
        faults.finite(center, "center");
        let axes = (faults.finite(u, "u"), faults.finite(v, "v"));
        if let (Some(u), Some(v)) = axes {
            faults.check(
                eft::scaled_cross(u, v).is_some(),
                LightError::DegenerateRect,
            );
        }
        faults.done()?;
        Ok(Rect { center, u, v })
    }

    /// The centre.
    #[must_use]
    pub fn center(&self) -> DVec3 {
        self.center
    }

    /// The first half-axis.
    #[must_use]
    pub fn u(&self) -> DVec3 {
        self.u
    }

    /// The second half-axis (not parallel to [`Rect::u`]).
    #[must_use]
    pub fn v(&self) -> DVec3 {
        self.v
    }

    /// The unit normal `u × v / ‖u × v‖`, for every rect whatever its
    /// area (computed on `u × v` scaled by a power of two).
    #[must_use]
    pub fn normal(&self) -> DVec3 {
        self.plane_direction().normalize()
    }

    /// `u × v` times the power of two that puts its largest component in
    /// `[1, 4)`: the plane's normal direction, never overflowing or
    /// underflowing (a power of two times `u × v` exactly wherever that is
    /// a normal vector).
    pub(crate) fn plane_direction(&self) -> DVec3 {
        // `Rect::new` refused the rects without one.
        eft::scaled_cross(self.u, self.v).map_or(DVec3::Z, |(n, _)| n)
    }

    /// The radius of the disk of equal area, `sqrt(4 ‖u × v‖ / π)`: the
    /// bits of that formula wherever `u × v` is a normal vector, and
    /// finite for every rect (`1e200` for half-axes of `1e200`, where
    /// `u × v` overflows).
    pub(crate) fn equivalent_radius(&self) -> f64 {
        let Some((n, mut k)) = eft::scaled_cross(self.u, self.v) else {
            return 0.0;
        };
        let mut length = n.length();
        // An even exponent comes out of the square root exactly.
        if k % 2 != 0 {
            length *= 2.0;
            k += 1;
        }
        eft::times_pow2((4.0 * length / std::f64::consts::PI).sqrt(), -k / 2)
    }
}

/// A uniform segment of light from `a` to `b`. Built only by
/// [`Segment::new`]: finite, distinct ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    a: DVec3,
    b: DVec3,
}

impl Segment {
    /// A segment light.
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::ZeroLengthSegment`].
    pub fn new(a: DVec3, b: DVec3) -> Result<Segment, LightError> {
        let mut faults = Faults::default();
        let ends = (faults.finite(a, "a"), faults.finite(b, "b"));
        if let (Some(a), Some(b)) = ends {
            faults.check(a != b, LightError::ZeroLengthSegment);
        }
        faults.done()?;
        Ok(Segment { a, b })
    }

    /// One end.
    #[must_use]
    pub fn a(&self) -> DVec3 {
        self.a
    }

    /// The other end.
    #[must_use]
    pub fn b(&self) -> DVec3 {
        self.b
    }
}

/// A point light. Built only by [`Point::new`]: a finite position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    position: DVec3,
}

impl Point {
    /// A point light.
    ///
    /// # Errors
    /// [`LightError::NonFinite`].
    pub fn new(position: DVec3) -> Result<Point, LightError> {
        let mut faults = Faults::default();
        faults.finite(position, "position");
        faults.done()?;
        Ok(Point { position })
    }

    /// The position.
    #[must_use]
    pub fn position(&self) -> DVec3 {
        self.position
    }
}

/// The faults a constructor finds, every argument checked.
#[derive(Default)]
struct Faults(Vec<LightError>);

impl Faults {
    /// Records `fault` unless `ok`.
    fn check(&mut self, ok: bool, fault: LightError) {
        if !ok {
            self.0.push(fault);
        }
    }

    /// `v` when finite, else a recorded [`LightError::NonFinite`].
    fn finite(&mut self, v: DVec3, field: &'static str) -> Option<DVec3> {
        self.check(v.is_finite(), LightError::NonFinite { field });
        v.is_finite().then_some(v)
    }

    /// Records why `radius` is not finite and positive, if it is not.
    fn positive(&mut self, radius: f64) {
        if !radius.is_finite() {
            self.0.push(LightError::NonFinite { field: "radius" });
        } else {
            self.check(radius > 0.0, LightError::NonPositiveRadius { radius });
        }
    }

    fn done(self) -> Result<(), LightError> {
        LightError::from_faults(self.0)
    }
}
