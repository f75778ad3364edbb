//! Lights: the five kinds of [visibility](crate::definitions#visibility), validated at construction, and
//! the emitting measure each presents to a receiver.
//!
//! `V(p)` is the fraction of a light's emitting measure visible from `p`:
//!
//! | light | measure |
//! |---|---|
//! | [`Light::Sphere`] | the area of the *facing disk*: centre `c`, radius `r`, normal `(c − p)/‖c − p‖` |
//! | [`Light::Disk`] | its area |
//! | [`Light::Rect`] | its area (centre and half-axes `u`, `v`) |
//! | [`Light::Segment`] | its length |
//! | [`Light::Point`] | a single point: `V ∈ {0, 1}` |
//!
//! Constructors return [`LightError`] for non-finite or degenerate input;
//! [`Light::emitter`] returns [`ReceiverError`] for a receiver inside a
//! sphere light or in the plane of a disk or rect light ([visibility](crate::definitions#visibility): an
//! error, not a NaN).

use crate::kernel::eft;
use crate::kernel::predicate::{orient2d, Sign};
use crate::kernel::receiver_view;
use glam::{DVec2, DVec3};
use std::fmt;

pub use super::emitter::Emitter;

/// Why a light could not be built. A constructor checks every argument
/// and reports each one that is invalid: one fault as its own variant,
/// several as [`LightError::Several`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum LightError {
    /// A coordinate or the radius is NaN or infinite; the field is named.
    NonFinite {
        /// The offending field (`"center"`, `"radius"`, `"normal"`, …).
        field: &'static str,
    },
    /// The radius is zero or negative.
    NonPositiveRadius {
        /// The radius given.
        radius: f64,
    },
    /// A disk's normal is zero (any other finite normal is accepted,
    /// however long or short).
    ZeroNormal,
    /// A rect's half-axes are zero or parallel (no area; an area beyond
    /// the range of `f64`, large or small, is accepted).
    DegenerateRect,
    /// A segment's endpoints coincide.
    ZeroLengthSegment,
    /// More than one of the above, in the order of the constructor's
    /// arguments (never nested, never fewer than two).
    Several(Vec<LightError>),
}

impl LightError {
    /// Each fault, in the order of the constructor's arguments: this one,
    /// or the list of [`LightError::Several`].
    #[must_use]
    pub fn faults(&self) -> &[LightError] {
        match self {
            LightError::Several(all) => all,
            one => std::slice::from_ref(one),
        }
    }

    /// The faults found, as one error: `Ok` for none.
    fn from_faults(mut faults: Vec<LightError>) -> Result<(), LightError> {
        match faults.len() {
            0 => Ok(()),
            1 => Err(faults.remove(0)),
            _ => Err(LightError::Several(faults)),
        }
    }
}

impl fmt::Display for LightError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LightError::NonFinite { field } => write!(f, "light field `{field}` is not finite"),
            LightError::NonPositiveRadius { radius } => {
                write!(f, "light radius must be positive, got {radius}")
            }
            LightError::ZeroNormal => write!(f, "disk light normal is zero"),
            LightError::DegenerateRect => write!(f, "rect light half-axes span no area"),
            LightError::ZeroLengthSegment => write!(f, "segment light endpoints coincide"),
            LightError::Several(all) => {
                for (k, e) in all.iter().enumerate() {
                    if k > 0 {
                        f.write_str("; ")?;
                    }
                    write!(f, "{e}")?;
                }
                Ok(())
            }
        }
    }
}

impl std::error::Error for LightError {}

/// Why a receiver cannot see a light's measure.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ReceiverError {
    /// The receiver has a NaN or infinite coordinate.
    NonFinite,
    /// The receiver is inside (or on) a sphere light.
    InsideSphere,
    /// The receiver lies in the plane of a disk or rect light (to rounding):
    /// the light is seen edge-on and its visible fraction is undefined.
    InLightPlane,
    /// The receiver is at the point light's position, or on a segment
    /// light.
    OnLight,
    /// The scene around the receiver is beyond a reference's range: the
    /// exact reference's determinants (products of three coordinate
    /// differences) would overflow, or, for Monte Carlo, a coordinate
    /// exceeds its segment test's domain (`10⁹⁰`). See
    /// [`reference::exact`](crate::reference)'s and Monte Carlo's domains.
    OutOfRange,
}

impl fmt::Display for ReceiverError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReceiverError::NonFinite => write!(f, "receiver position is not finite"),
            ReceiverError::InsideSphere => write!(f, "receiver is inside the sphere light"),
            ReceiverError::InLightPlane => write!(f, "receiver lies in the light's plane"),
            ReceiverError::OnLight => write!(f, "receiver lies on the light"),
            ReceiverError::OutOfRange => write!(
                f,
                "the scene's coordinates around the receiver are beyond the reference's range"
            ),
        }
    }
}

impl std::error::Error for ReceiverError {}

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
    fn equivalent_radius(&self) -> f64 {
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
            Light::Sphere(s) => s.center,
            Light::Disk(d) => d.center,
            Light::Rect(r) => r.center,
            Light::Segment(s) => s.a.midpoint(s.b),
            Light::Point(p) => p.position,
        }
    }

    /// The radius of the disk the light's measure is drawn as when a method
    /// projects it from its centre: a sphere's or disk's radius; for a rect
    /// the radius of the disk of equal area; for a segment half its length;
    /// `0` for a point.
    #[must_use]
    pub fn equivalent_radius(&self) -> f64 {
        match self {
            Light::Sphere(s) => s.radius,
            Light::Disk(d) => d.radius,
            Light::Rect(r) => r.equivalent_radius(),
            Light::Segment(s) => 0.5 * (s.b - s.a).length(),
            Light::Point(_) => 0.0,
        }
    }

    /// The radius of the smallest ball about [`center`](Light::center)
    /// that holds the whole light: a sphere's or disk's radius, a rect's
    /// longer half-diagonal, half a segment's length, `0` for a point.
    #[must_use]
    pub fn bounding_radius(&self) -> f64 {
        match self {
            Light::Rect(r) => eft::length(r.u + r.v).max(eft::length(r.u - r.v)),
            _ => self.equivalent_radius(),
        }
    }

    /// The unit normal of a disk or rect light's plane, `None` for the
    /// other kinds.
    #[must_use]
    pub fn plane_normal(&self) -> Option<DVec3> {
        match self {
            Light::Disk(d) => Some(d.normal),
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
        if !p.is_finite() {
            return Err(ReceiverError::NonFinite);
        }
        match *self {
            Light::Sphere(Sphere { center, radius }) => {
                // Halved, so that the difference cannot overflow; then
                // scaled to its largest component, so that its length
                // cannot either (a centre 3e300 away is not "inside").
                let half = center * 0.5 - p * 0.5;
                let scale = half.abs().max_element();
                if scale == 0.0 {
                    return Err(ReceiverError::InsideSphere);
                }
                let unit = half / scale;
                let normal = unit.try_normalize().ok_or(ReceiverError::InsideSphere)?;
                if unit.length() * scale * 2.0 <= radius {
                    return Err(ReceiverError::InsideSphere);
                }
                Ok(Emitter::Disk(Disk {
                    center,
                    normal,
                    radius,
                }))
            }
            Light::Disk(d) => {
                off_plane(p, d.center, d.normal)?;
                Ok(Emitter::Disk(d))
            }
            Light::Rect(r) => {
                off_plane(p, r.center, r.plane_direction())?;
                Ok(Emitter::Rect(r))
            }
            Light::Segment(s) => {
                let Segment { a, b } = s;
                // Collinear exactly: all three coordinate projections are.
                let on_line = [(0, 1), (1, 2), (2, 0)].iter().all(|&(i, j)| {
                    let q = |v: DVec3| DVec2::new(v[i], v[j]);
                    orient2d(q(a), q(b), q(p)) == Sign::Zero
                });
                let between = (p - a).dot(b - a) >= 0.0 && (p - b).dot(a - b) >= 0.0;
                if on_line && between {
                    return Err(ReceiverError::OnLight);
                }
                Ok(Emitter::Segment(s))
            }
            Light::Point(x) => {
                if p == x.position {
                    return Err(ReceiverError::OnLight);
                }
                Ok(Emitter::Point(x))
            }
        }
    }
}

/// `p` must be off the plane through `c` with normal `n`: the computed
/// `n · (p − c)` must exceed its own rounding bound, `γ(5) |n| · |p − c|`
/// (the rounded difference, three products and two sums; `γ(k) =
/// kε/(1 − kε)`, Higham).
fn off_plane(p: DVec3, c: DVec3, n: DVec3) -> Result<(), ReceiverError> {
    let d = p - c;
    let bound = crate::kernel::footprint::f64::gamma(5) * n.abs().dot(d.abs());
    if n.dot(d).abs() > bound {
        Ok(())
    } else {
        Err(ReceiverError::InLightPlane)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
