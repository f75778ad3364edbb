//! Lights: the five kinds of DESIGN.md §1, validated at construction, and
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
//! sphere light or in the plane of a disk or rect light (DESIGN §1: an
//! error, not a NaN).

use crate::kernel::predicate::{orient2d, Sign};
use glam::{DVec2, DVec3};
use std::fmt;

/// Why a light could not be built.
#[derive(Clone, Copy, Debug, PartialEq)]
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
    /// A disk's normal has zero length.
    ZeroNormal,
    /// A rect's half-axes are zero or parallel (no area).
    DegenerateRect,
    /// A segment's endpoints coincide.
    ZeroLengthSegment,
}

impl fmt::Display for LightError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LightError::NonFinite { field } => write!(f, "light field `{field}` is not finite"),
            LightError::NonPositiveRadius { radius } => {
                write!(f, "light radius must be positive, got {radius}")
            }
            LightError::ZeroNormal => write!(f, "disk light normal has zero length"),
            LightError::DegenerateRect => write!(f, "rect light half-axes span no area"),
            LightError::ZeroLengthSegment => write!(f, "segment light endpoints coincide"),
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
}

impl fmt::Display for ReceiverError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReceiverError::NonFinite => write!(f, "receiver position is not finite"),
            ReceiverError::InsideSphere => write!(f, "receiver is inside the sphere light"),
            ReceiverError::InLightPlane => write!(f, "receiver lies in the light's plane"),
            ReceiverError::OnLight => write!(f, "receiver lies on the light"),
        }
    }
}

impl std::error::Error for ReceiverError {}

/// A light of one of the five kinds. Fields are private: every value was
/// validated by its constructor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// A uniform sphere, seen as its facing disk.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius, `> 0`.
        radius: f64,
    },
    /// A uniform one-sided-or-two-sided disk (occlusion does not depend on
    /// the side).
    Disk {
        /// Centre.
        center: DVec3,
        /// Unit normal.
        normal: DVec3,
        /// Radius, `> 0`.
        radius: f64,
    },
    /// A uniform parallelogram `center + s u + t v`, `s, t ∈ [−1, 1]`.
    Rect {
        /// Centre.
        center: DVec3,
        /// First half-axis.
        u: DVec3,
        /// Second half-axis (not parallel to `u`).
        v: DVec3,
    },
    /// A uniform segment from `a` to `b`.
    Segment {
        /// One end.
        a: DVec3,
        /// The other end.
        b: DVec3,
    },
    /// A point light.
    Point {
        /// Position.
        position: DVec3,
    },
}

fn finite(v: DVec3, field: &'static str) -> Result<DVec3, LightError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(LightError::NonFinite { field })
    }
}

fn positive(radius: f64) -> Result<f64, LightError> {
    if !radius.is_finite() {
        Err(LightError::NonFinite { field: "radius" })
    } else if radius > 0.0 {
        Ok(radius)
    } else {
        Err(LightError::NonPositiveRadius { radius })
    }
}

impl Light {
    /// A sphere light.
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::NonPositiveRadius`].
    pub fn sphere(center: DVec3, radius: f64) -> Result<Light, LightError> {
        Ok(Light::Sphere {
            center: finite(center, "center")?,
            radius: positive(radius)?,
        })
    }

    /// A disk light; `normal` need not be unit length (it is normalised).
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::NonPositiveRadius`],
    /// [`LightError::ZeroNormal`].
    pub fn disk(center: DVec3, normal: DVec3, radius: f64) -> Result<Light, LightError> {
        let normal = finite(normal, "normal")?
            .try_normalize()
            .ok_or(LightError::ZeroNormal)?;
        Ok(Light::Disk {
            center: finite(center, "center")?,
            normal,
            radius: positive(radius)?,
        })
    }

    /// A rect light with half-axes `u`, `v` (any non-parallel pair: the
    /// light is the parallelogram they span).
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::DegenerateRect`] when
    /// `u × v` is zero or not finite.
    pub fn rect(center: DVec3, u: DVec3, v: DVec3) -> Result<Light, LightError> {
        let (u, v) = (finite(u, "u")?, finite(v, "v")?);
        let n = u.cross(v);
        if !(n.is_finite() && n.length_squared() > 0.0) {
            return Err(LightError::DegenerateRect);
        }
        Ok(Light::Rect {
            center: finite(center, "center")?,
            u,
            v,
        })
    }

    /// A segment light.
    ///
    /// # Errors
    /// [`LightError::NonFinite`], [`LightError::ZeroLengthSegment`].
    pub fn segment(a: DVec3, b: DVec3) -> Result<Light, LightError> {
        let (a, b) = (finite(a, "a")?, finite(b, "b")?);
        if a == b {
            return Err(LightError::ZeroLengthSegment);
        }
        Ok(Light::Segment { a, b })
    }

    /// A point light.
    ///
    /// # Errors
    /// [`LightError::NonFinite`].
    pub fn point(position: DVec3) -> Result<Light, LightError> {
        Ok(Light::Point {
            position: finite(position, "position")?,
        })
    }

    /// The light's centre (the segment's midpoint).
    #[must_use]
    pub fn center(&self) -> DVec3 {
        match *self {
            Light::Sphere { center, .. }
            | Light::Disk { center, .. }
            | Light::Rect { center, .. } => center,
            Light::Segment { a, b } => a.midpoint(b),
            Light::Point { position } => position,
        }
    }

    /// The emitting measure as seen from the receiver `p` (DESIGN §1).
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
            Light::Sphere { center, radius } => {
                // Halved, so that the difference cannot overflow.
                let half = center * 0.5 - p * 0.5;
                let normal = half.try_normalize().ok_or(ReceiverError::InsideSphere)?;
                if half.length() * 2.0 <= radius {
                    return Err(ReceiverError::InsideSphere);
                }
                Ok(Emitter::Disk {
                    center,
                    normal,
                    radius,
                })
            }
            Light::Disk {
                center,
                normal,
                radius,
            } => {
                off_plane(p, center, normal)?;
                Ok(Emitter::Disk {
                    center,
                    normal,
                    radius,
                })
            }
            Light::Rect { center, u, v } => {
                off_plane(p, center, u.cross(v))?;
                Ok(Emitter::Rect { center, u, v })
            }
            Light::Segment { a, b } => {
                // Collinear exactly: all three coordinate projections are.
                let on_line = [(0, 1), (1, 2), (2, 0)].iter().all(|&(i, j)| {
                    let q = |v: DVec3| DVec2::new(v[i], v[j]);
                    orient2d(q(a), q(b), q(p)) == Sign::Zero
                });
                let between = (p - a).dot(b - a) >= 0.0 && (p - b).dot(a - b) >= 0.0;
                if on_line && between {
                    return Err(ReceiverError::OnLight);
                }
                Ok(Emitter::Segment { a, b })
            }
            Light::Point { position } => {
                if p == position {
                    return Err(ReceiverError::OnLight);
                }
                Ok(Emitter::Point(position))
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
    let eps = f64::EPSILON / 2.0;
    let gamma5 = 5.0 * eps / (1.0 - 5.0 * eps);
    let bound = gamma5 * n.abs().dot(d.abs());
    if n.dot(d).abs() > bound {
        Ok(())
    } else {
        Err(ReceiverError::InLightPlane)
    }
}

/// A light's emitting measure as one receiver sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Emitter {
    /// A uniform disk (a disk light, or a sphere light's facing disk).
    Disk {
        /// Centre.
        center: DVec3,
        /// Unit normal.
        normal: DVec3,
        /// Radius.
        radius: f64,
    },
    /// A uniform parallelogram `center + s u + t v`, `s, t ∈ [−1, 1]`.
    Rect {
        /// Centre.
        center: DVec3,
        /// First half-axis.
        u: DVec3,
        /// Second half-axis.
        v: DVec3,
    },
    /// A uniform segment.
    Segment {
        /// One end.
        a: DVec3,
        /// The other end.
        b: DVec3,
    },
    /// A point.
    Point(DVec3),
}

impl Emitter {
    /// The point of the measure at the sample `s ∈ [0, 1)²`, uniform by
    /// area (length for a segment) when `s` is uniform: the disk by
    /// Shirley and Chiu's concentric map (low distortion, so stratified
    /// samples stay stratified), the rect and segment affinely. A point
    /// light ignores `s`.
    #[must_use]
    pub fn point_at(&self, s: DVec2) -> DVec3 {
        match *self {
            Emitter::Disk {
                center,
                normal,
                radius,
            } => {
                let (t, b) = normal.any_orthonormal_pair();
                let q = concentric_disk(s) * radius;
                center + t * q.x + b * q.y
            }
            Emitter::Rect { center, u, v } => {
                center + u * (2.0 * s.x - 1.0) + v * (2.0 * s.y - 1.0)
            }
            Emitter::Segment { a, b } => a.lerp(b, s.x),
            Emitter::Point(p) => p,
        }
    }
}

/// Shirley and Chiu's concentric map from `[0, 1)²` to the unit disk
/// ("A Low Distortion Map Between Disk and Square", 1997): area-preserving
/// up to the constant `π/4`.
fn concentric_disk(s: DVec2) -> DVec2 {
    let o = s * 2.0 - DVec2::ONE;
    if o == DVec2::ZERO {
        return DVec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, std::f64::consts::FRAC_PI_4 * (o.y / o.x))
    } else {
        (
            o.y,
            std::f64::consts::FRAC_PI_2 - std::f64::consts::FRAC_PI_4 * (o.x / o.y),
        )
    };
    DVec2::new(theta.cos(), theta.sin()) * r
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

    /// Uniform by area: with N uniform samples, the share landing inside
    /// half the radius is binomial with p = ¼; it must lie within 5σ,
    /// σ = √(p(1 − p)/N) (fixed seed). Every sample lies on the disk.
    #[test]
    fn disk_samples_are_uniform_by_area() {
        let emitter = Emitter::Disk {
            center: DVec3::new(1.0, 2.0, 3.0),
            normal: DVec3::new(1.0, 1.0, 0.0).normalize(),
            radius: 2.0,
        };
        let mut rng = crate::arbitrary::Rng::new(3);
        const N: usize = 200_000;
        let mut inner = 0;
        for _ in 0..N {
            let q =
                emitter.point_at(DVec2::new(rng.unit(), rng.unit())) - DVec3::new(1.0, 2.0, 3.0);
            assert!(q.length() <= 2.0 * (1.0 + 1e-15));
            assert!(q.dot(DVec3::new(1.0, 1.0, 0.0).normalize()).abs() < 1e-15);
            inner += (q.length() < 1.0) as usize;
        }
        let (p, n) = (0.25, N as f64);
        let sigma = (p * (1.0 - p) / n).sqrt();
        assert!((inner as f64 / n - p).abs() < 5.0 * sigma, "{inner}");
    }

    #[test]
    fn rect_and_segment_samples_cover_the_measure() {
        let rect = Emitter::Rect {
            center: DVec3::ZERO,
            u: DVec3::X,
            v: DVec3::new(0.5, 2.0, 0.0),
        };
        assert_eq!(
            rect.point_at(DVec2::ZERO),
            -DVec3::X - DVec3::new(0.5, 2.0, 0.0)
        );
        assert_eq!(rect.point_at(DVec2::splat(0.5)), DVec3::ZERO);
        let seg = Emitter::Segment {
            a: DVec3::ZERO,
            b: DVec3::new(4.0, 0.0, 0.0),
        };
        assert_eq!(seg.point_at(DVec2::new(0.25, 0.9)), DVec3::X);
    }

    #[test]
    fn facing_disk_faces_the_receiver() {
        let sphere = Light::sphere(DVec3::new(1.0, 5.0, 0.0), 0.5).unwrap();
        let p = DVec3::new(1.0, 0.0, 0.0);
        let Ok(Emitter::Disk { normal, radius, .. }) = sphere.emitter(p) else {
            panic!("a disk");
        };
        assert_eq!(normal, DVec3::Y);
        assert_eq!(radius, 0.5);
    }

    fn emitter_is_finite(e: &Emitter) -> bool {
        match *e {
            Emitter::Disk {
                center,
                normal,
                radius,
            } => center.is_finite() && normal.is_finite() && radius.is_finite(),
            Emitter::Rect { center, u, v } => center.is_finite() && u.is_finite() && v.is_finite(),
            Emitter::Segment { a, b } => a.is_finite() && b.is_finite(),
            Emitter::Point(p) => p.is_finite(),
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
                    proptest::prop_assert!(emitter_is_finite(&Emitter::Point(e.point_at(DVec2::splat(0.3)))));
                }
            }
        }
    }
}
